"""The accuracy-cost study's points, from its records and Table 4's (:mod:`studies.design.accuracy_cost`):
one point per run (its configuration, time and error), and the rules that say which points
reach an accuracy without resting on a cancellation of errors: the static cantilever's
:func:`settled` (every finer mesh of the configuration within it too), the pendulum's
:func:`settled_steps` (every run with as many elements or more and the step or less), and
each element's front of settled errors against time (:func:`fronts`, :func:`leaders`)."""
from __future__ import annotations

from ..common.gold import MATCHING, continuum_references, describe, variant_of
from ..common.grid import qlabel
from ..common.pendulum_cases import continuum_pendulum, describe_dynamic, tip_errors
from ..engine.report import GOOD, MAX_SERIES, front, vec_error, verdict


# the fixed rules of the paper's elements (make study-full), drawn here when recorded
RULES = "accuracy-cost-rules"


def _static(r: dict) -> bool:
    return (r.get("scene") or {}).get("analysis", {}).get("kind", "static") == "static"


def _slenderness(scene: dict) -> float:
    b = scene["beam"]
    return b["length"] / b["height"]


def points(ctx) -> list[dict]:
    """One point per record: configuration, time (s), error (fraction) or None."""
    refs = continuum_references(ctx.records("continuum"))
    out = []
    for r in [r for r in ctx.records() if _static(r)] + ctx.records(RULES):
        d = describe(r)
        t = (r.get("timing") or {}).get("median_s")
        if r["solver"] == "ancf":
            ref = refs.get((d["law"], MATCHING[d["formulation"]]))
            p = {"law": d["law"], "model": MATCHING[d["formulation"]], "solver": "ancf",
                 "config": f"{d['element']} {qlabel(d['quadrature'])}", "element": d["element"],
                 "quadrature": d["quadrature"], "mesh": d["elements"], "ndof": r.get("ndof"),
                 "slenderness": _slenderness(r["scene"])}
        else:
            ref = refs.get((d["law"], variant_of(r["scene"])))
            p = {"law": d["law"], "model": variant_of(r["scene"]), "solver": "continuum", "config": "continuum Q2",
                 "element": "continuum", "quadrature": None, "mesh": f"{d['cells'][0]}x{d['cells'][1]}",
                 "ndof": r.get("ndof")}
        ok = d["status"] == "converged"
        p.update(status=d["status"], verdict=verdict(r), time=t if ok else None,
                 error=vec_error(d["tip"], ref.tip if ref else None) if ok else None)
        out.append(p)
    return out


def settled(pts: list[dict], target: float) -> list[dict]:
    """The points that reach ``target`` without resting on cancellation: the point and
    every finer mesh (at least as many unknowns) of the same solver and configuration
    are good (stable, unwarned: :data:`GOOD`) and within ``target``; a failed, singular,
    indefinite or warned finer run disqualifies."""
    def ok(q):
        return q["verdict"] in GOOD and q["error"] is not None and q["error"] <= target
    return [p for p in pts
            if all(ok(q) for q in pts
                   if q["solver"] == p["solver"] and q["config"] == p["config"] and (q["ndof"] or 0) >= (p["ndof"] or 0))]


def cheapest(pts: list[dict], target: float) -> dict | None:
    ok = [p for p in pts if p["error"] is not None and p["time"] is not None and p["error"] <= target]
    return min(ok, key=lambda p: p["time"]) if ok else None


def with_settled(pts: list[dict], finer) -> list[dict]:
    """Each point that has a time, with ``settled``: the largest error over it and the runs
    ``finer(p)`` refining it (its own among them), None where one of those is not good
    (:data:`GOOD`) or has no error. A point reaches an accuracy by :func:`settled` (or
    :func:`settled_steps`) exactly when its settled error is within it, so the fronts of these
    errors (:func:`fronts`) name the tables' cheapest runs."""
    out = []
    for p in pts:
        if not p.get("time"):
            continue
        qs = finer(p)
        ok = all(q["verdict"] in GOOD and q["error"] is not None for q in qs)
        out.append(dict(p, settled=max(q["error"] for q in qs) if ok and qs else None))
    return out


def static_finer(sel: list[dict]):
    """:func:`settled`'s refinement: the same solver and configuration on as many unknowns or more."""
    return lambda p: [q for q in sel if q["solver"] == p["solver"] and q["config"] == p["config"]
                      and (q["ndof"] or 0) >= (p["ndof"] or 0)]


def pendulum_finer(sel: list[dict]):
    """:func:`settled_steps`' refinement: the same formulation and element, at least as many
    elements and at most the step."""
    return lambda p: [q for q in sel if (q["formulation"], q["element"]) == (p["formulation"], p["element"])
                      and q["n"] >= p["n"] and q["dt"] <= p["dt"]]


def fronts(pts: list[dict]) -> dict[str, list[dict]]:
    """{element: the front of its settled errors against time} (:func:`with_settled` points;
    an element's configurations, rules and meshes, or its meshes and steps, together)."""
    out = {}
    for el in dict.fromkeys(p["element"] for p in pts):
        f = front([p for p in pts if p["element"] == el], error="settled")
        if f:
            out[el] = f
    return out


def leaders(fr: dict[str, list[dict]], targets, most: int = MAX_SERIES - 2) -> list[str]:
    """The elements a lead figure colours, at most ``most`` of them: at each target the one
    whose front reaches it cheapest and those within :data:`TIE` of its time (the choose
    table's ties), then the one with the smallest settled error of all."""
    out = []
    for a in targets:
        first = {el: next((p for p in f if p["settled"] <= a), None) for el, f in fr.items()}
        first = {el: p for el, p in first.items() if p}
        if first:
            t = min(p["time"] for p in first.values())
            out += sorted((el for el, p in first.items() if p["time"] <= TIE * t), key=lambda el: first[el]["time"])
    if fr:
        out.append(min(fr, key=lambda el: fr[el][-1]["settled"]))
    return list(dict.fromkeys(out))[:most]


# runs within this factor of the cheapest one's time are named beside it: timings drift by
# 10 to 30 % between runs of one machine (the peers' rounds), so a closer order is not a ranking
TIE = 1.3


def _pendulum_point(r: dict, cont: dict) -> dict:
    """A pendulum record as a point: its median serial warm wall time and its error max over
    t of |r - r_ref| / L against the converged continuum plane-stress pendulum."""
    d = describe_dynamic(r)
    ref = cont.get((d["law"], "plane-stress"))
    e = tip_errors(d["tips"], ref.tips) if (ref and d["ok"]) else {}
    t = (d["timing"] or {}).get("median_s")
    return {"formulation": d["formulation"], "element": d["element"], "n": d["elements"], "dt": d["dt"],
            "law": d["law"], "rho_inf": d["rho_inf"], "slenderness": _slenderness(r["scene"]), "status": d["status"], "verdict": verdict(r),
            "time": t if d["ok"] else None, "error": max(e.values()) if e else None}


def pendulum_points(ctx) -> list[dict]:
    """The dynamic half: every timed rung of Table 4 (element, count, step) as a point:
    its median serial warm wall time and its pendulum error max over t of |r - r_ref| / L
    against the converged continuum plane-stress pendulum (`paper` against it too)."""
    cont = continuum_pendulum()
    return [_pendulum_point(r, cont) for r in ctx.records("table4")]


def own_pendulum_points(ctx) -> list[dict]:
    """This study's own pendulum runs (the ``pendulum`` grid: the elements Table 4 does not
    run, on its ladder) as points, as :func:`pendulum_points`."""
    cont = continuum_pendulum()
    return [_pendulum_point(r, cont) for r in ctx.records() if not _static(r)]


def all_pendulum_points(ctx) -> list[dict]:
    """Table 4's rungs and this study's own pendulum runs."""
    return pendulum_points(ctx) + own_pendulum_points(ctx)


def settled_steps(pts: list[dict], target: float) -> list[dict]:
    """The pendulum points within ``target`` whose every finer run (same formulation and
    element, at least as many elements and at most the step) is good and within it too."""
    def ok(q):
        return q["verdict"] in GOOD and q["error"] is not None and q["error"] <= target
    return [p for p in pts
            if all(ok(q) for q in pts if (q["formulation"], q["element"]) == (p["formulation"], p["element"])
                   and q["n"] >= p["n"] and q["dt"] <= p["dt"])]
