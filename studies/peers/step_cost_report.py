"""The report's section on a missed target, from the step-cost records alone
(:mod:`studies.peers.step_cost` measures them; ``data/peers/peers-step-cost.json``): our
deciding run's time under each Newton a scene offers beside the cable's (:func:`mode_ratios`),
its step split into its parts, the estimate of a step with one linear solve and no
convergence test (:func:`linear_estimate`), and whether the linear mode's own runs count
(:func:`linear_refused`); :func:`lines` draws them for
:func:`studies.peers.precision_report.scene_markdown`."""
from __future__ import annotations

import statistics

from .anatomy import TARGET
from .precision_grid import MODES, our_element
from .precision_rules import finer, holds
from .records import COSTS


def mode_ratios(rec: dict) -> dict[str, float | None]:
    """{mode: the rounds' median of ours in that mode / the cable's}."""
    out = {}
    for k in MODES:
        x = [r["modes"][k]["time_s"] / r["exudyn_s"] for r in rec["rounds"]
             if r["exudyn_s"] and (r["modes"].get(k) or {}).get("time_s")]
        out[k] = statistics.median(x) if x else None
    return out


def linear_estimate(rec: dict) -> float | None:
    """The rounds' median of (ours - steps x the verifying residual) / the cable's, with
    ours in the deciding run's own mode; None unless the run takes one iteration per step."""
    sp = rec["split"]
    run = sp["run"]
    if not run["steps"] or run["newton_iterations"] != run["steps"]:
        return None
    mode = next((k for k, st in MODES.items() if st == {"newton": "chord", **rec["ours"]["settings"]}), None)
    if mode is None:
        return None
    saved = run["steps"] * sp["seconds_per_call"]["verifying_residual"]
    x = [(r["modes"][mode]["time_s"] - saved) / r["exudyn_s"] for r in rec["rounds"]
         if r["exudyn_s"] and r["modes"][mode].get("time_s")]
    return statistics.median(x) if x else None


def linear_refused(rec: dict, grid: list[dict]) -> list[dict] | None:
    """Where the linear mode's run of the deciding point is within the target but the grid's
    own run of it in that mode (``<element> (linear)``) does not count at the row's accuracy:
    the runs refining it (:func:`studies.peers.precision_rules.finer`) that fail or miss
    it; None where it counts, or the grid has no such run."""
    o = rec["ours"]
    base, _ = our_element(o["element"])
    run = next((r for r in grid if r["solver"] == "ancf" and r["element"] == f"{base} (linear)"
                and r["elements"] == o["elements"] and r["dt"] == o["dt"]), None)
    if run is None or holds(run, grid, rec["accuracy"]):
        return None
    return [q for q in finer(run, grid) if q["error"] is None or q["error"] > rec["accuracy"]]


def lines(recs: list[dict], grid: list[dict] | None = None) -> list[str]:
    """The report's sentences and table of a scene's step-cost records (:func:`studies.peers.records.costs_path`);
    ``grid``: the scene's work-precision records (to say whether the linear mode's run counts)."""
    out = []
    for rec in recs:
        o, p = rec["ours"], rec["exudyn"]
        ratios = mode_ratios(rec)
        sp = rec["split"]
        t = {k: 1e6 * v for k, v in sp["seconds_per_call"].items()}
        run = sp["run"]
        est = linear_estimate(rec)
        acc = f"{100 * rec['accuracy']:g} %"
        out += [f"Why the {acc} target is missed, measured (data/peers/{COSTS}, `python -m studies peers step-cost`): "
                f"our deciding run ({o['element']} x {o['elements']}, dt {o['dt'] * 1e3:g} ms) under each Newton the "
                f"compiled loop offers, timed in {len(rec['rounds'])} rounds of {rec['repeats']} runs beside the "
                f"cable's ({p['elements']} elements{', linear' if p['element'].endswith('-linear') else ''}, dt "
                f"{p['dt'] * 1e3:g} ms), the rounds' median of ours / the cable's:", "",
                "| `[analysis]` setting | ours / cable (rounds' median) | Newton iterations | steps |",
                "|---|---|---|---|"]
        for k in MODES:
            m = rec["rounds"][-1]["modes"].get(k) or {}
            out.append(f"| {k} | " + (f"{ratios[k]:.3f}" if ratios[k] is not None else "-")
                       + f" | {m.get('newton_iterations') or '-'} | {m.get('steps') or '-'} |")
        text = (f"One of its steps ({sp['ndof']} coordinates, at the run's final state; compiled loops of {sp['calls']} calls, "
                f"the best of {sp['repeats']}): the whole step {t['step']:.2f} us, of which the force and tangent at the "
                f"predictor {t['force_and_tangent']:.2f} us, the factorisation and solve {t['factorise_and_solve']:.2f} "
                f"us, and the force and residual that verify the corrected state {t['verifying_residual']:.2f} us "
                f"(the run: {run['wall_s'] * 1e6 / run['steps']:.2f} us per step over {run['steps']} steps).")
        if est is not None:
            text += (f" The run takes {run['newton_iterations']} Newton iterations in {run['steps']} steps: its "
                     "states are those of one linear solve per step already, and a step with one linear solve and no "
                     "convergence test (the cable's linear mode; ours, `newton = \"linear\"`, is the table's last row, "
                     f"run) leaves out only the verifying residual: with it taken off our time, the rounds' "
                     f"median would be {est:.3f} ({'<=' if est <= TARGET else '>'} {TARGET:g}; an estimate from the "
                     "timed parts, not a run).")
        lin = ratios.get("linear")
        refused = linear_refused(rec, grid or []) if lin is not None and lin <= TARGET else None
        if refused:
            worst = ", ".join(f"{q['elements']} elements at {q['dt'] * 1e3:g} ms "
                              + (f"{100 * q['error']:.2f} % off" if q["error"] is not None else
                                 f"{q['status']} ({q.get('reason') or 'no reason recorded'})")
                              for q in sorted(refused, key=lambda q: (q["elements"], -q["dt"])))
            text += (f" The linear mode's run meets the target in time ({lin:.3f}) but does not count at {acc}: the "
                     f"two-way rule asks the runs that refine it in the same setting to reach it too: {worst}. "
                     "What misses the target is the linear step's robustness on the finer meshes, not its cost.")
        out += ["", text, ""]
    return out
