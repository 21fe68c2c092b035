"""The work-precision bench's rules, the same for both sides: which runs count for an
accuracy (:func:`holds`, the two-way fairness rule over the runs that refine a run,
:func:`finer`), the cheapest that do (:func:`cheapest`), and the ratio that decides a row
(:func:`deciding_ratio`: the median of the rounds, :func:`rounds_of`, where the row's two
points were re-timed, else the grid's). The grid's runner (:mod:`studies.peers.work_precision`),
the step-cost measurement (:mod:`studies.peers.step_cost`) and the report
(:mod:`studies.peers.precision_report`) apply them."""
from __future__ import annotations

import statistics


def round_pair(o: dict, p: dict) -> dict:
    """The (ours, cable's) points a rounds record re-times, as it stores them."""
    return {k: {"element": r["element"], "elements": r["elements"], "dt": r["dt"]} for k, r in (("ours", o), ("exudyn", p))}


def rounds_of(rounds: list[dict], scene: str, accuracy: float, o: dict, p: dict) -> dict | None:
    """The rounds record of ``scene`` and ``accuracy`` that re-timed exactly these two points."""
    pts = round_pair(o, p)
    return next((r for r in rounds if r["scene"] == scene and r["accuracy"] == accuracy
                 and {k: r[k] for k in pts} == pts), None)


def round_ratios(r: dict | None) -> list[float | None]:
    """Each round's ours / cable's (None where a side has no time)."""
    return [x["ours_s"] / x["exudyn_s"] if x["ours_s"] and x["exudyn_s"] else None for x in (r or {}).get("rounds", [])]


def deciding_ratio(o: dict | None, p: dict | None, rr: dict | None) -> tuple:
    """(ratio, source) of a row with our and the cable's cheapest runs o, p and their rounds
    record rr: ours / cable's by the median of the rounds ('rounds') where they were
    re-timed, else by the grid's medians ('grid'); (None, None) without both runs."""
    if not (o and p):
        return None, None
    x = [r for r in round_ratios(rr) if r is not None]
    return (statistics.median(x), "rounds") if x else (o["time_s"] / p["time_s"], "grid")


def finer(r: dict, recs: list[dict]) -> list[dict]:
    """The grid's runs that refine run ``r`` one way at a time (its own record among them):
    the same solver and element, and either its mesh at every step no larger than its step,
    or its step on every mesh at least as fine as its mesh."""
    return [q for q in recs if (q["solver"], q["element"]) == (r["solver"], r["element"])
            and ((q["elements"] == r["elements"] and q["dt"] <= r["dt"])
                 or (q["dt"] == r["dt"] and q["elements"] >= r["elements"]))]


def holds(r: dict, recs: list[dict], accuracy: float) -> bool:
    """The two-way fairness rule: does run ``r`` reach ``accuracy``, and does every run of
    the grid that refines it one way (:func:`finer`: every finer step of its mesh, every
    finer mesh at its step) reach it too? A coarse step's error can cancel the mesh's
    (numerical dissipation against stiffness), and a coarse mesh's the step's: such a run is
    accurate by luck, and a finer step or a finer mesh would lose it. A finer run that
    failed or diverged reaches nothing, so it refuses ``r`` too. The same rule for both
    sides."""
    return all(q["error"] is not None and q["error"] <= accuracy for q in finer(r, recs))


def cheapest(recs: list[dict], solver: str, element: str | None, accuracy: float) -> dict | None:
    """The fastest run of ``solver`` (and ``element``) that :func:`holds` ``accuracy``."""
    ok = [r for r in recs if r["solver"] == solver and (element is None or r["element"] == element)
          and r["time_s"] and holds(r, recs, accuracy)]
    return min(ok, key=lambda r: r["time_s"]) if ok else None
