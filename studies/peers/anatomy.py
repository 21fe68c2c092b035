"""Where the time of a work-precision row goes, from its two runs' records (ours and the
cable's): time = steps x Newton iterations per step x time per iteration.

An element that reaches the accuracy on fewer or cheaper elements changes only the last
factor; the step the accuracy allows sets the first, the Newton scheme the second. The
table says which factor separates the two codes, and judges the target (ours at most
:data:`TARGET` of the cable's time, at each of :data:`TARGET_ACCURACIES`) by the row's
ratio: the rounds' median where the row was re-timed in rounds, else the grid's.

The coarsest step's error on the finest meshes (:func:`step_error_lines`) is the step's
own error, the same for every element: no element reaches an accuracy below it at that
step, except where a coarse mesh's error happens to cancel it.

Where a target is not met, :func:`reach_lines` asks whether any element could meet it:
our cheapest run at each step, at any error (the fewest elements of the cheapest
element), against the target's time. A step with no run under it is out of reach for
every element at least that cheap per step; a step whose own error is above the accuracy
admits it only by cancellation. What is left is an element's question, and the sentence
says how far any run is from it: the smallest error, at any cost, of ours and of the
cable's on as few elements as fit the time.
"""
from __future__ import annotations

from contract import paper

from .precision_grid import cable_mode

TARGET = 0.5                    # our cheapest run at most half of Exudyn's time ...
# ... at 1 %, 0.3 % and 0.1 % (1 % and 0.1 %, the accuracies the studies judge; 0.3 % added with the cable)
TARGET_ACCURACIES = (0.01, 0.003, 0.001)


def factors(r: dict) -> dict:
    """steps (t_end / dt, the fixed step), Newton iterations (as the run's code counts them),
    their ratio, and the time per iteration and per step (s)."""
    steps = round(paper.PENDULUM_T_END / r["dt"])
    its = r.get("newton_iterations")
    return {"steps": steps, "iterations": its, "per_step": its / steps if its else None,
            "per_iteration_s": r["time_s"] / its if its else None, "per_step_s": r["time_s"] / steps}


def verdict(accuracy: float, ratio: float | None, ours: dict | None, cable: dict | None) -> str:
    """The target at this accuracy ('-' where it sets none)."""
    if accuracy not in TARGET_ACCURACIES:
        return "-"
    if ours is None:
        return "not met: no run of ours reaches it" + ("" if cable else ", nor of the cable")
    if cable is None:
        return "no run of the cable reaches it"
    ok = ratio <= TARGET
    return f"{'met' if ok else 'not met'} ({ratio:.3f} {'<=' if ok else '>'} {TARGET:g})"    # 3 decimals: 0.498 is not 0.50


def _run(r: dict | None) -> list[str]:
    if r is None:
        return ["none"] + ["-"] * 5
    f = factors(r)
    name = (f"{r['element']} x {r['elements']}" if r["solver"] == "ancf"
            else f"cable x {r['elements']}{cable_mode(r['element'])}")
    it = f["iterations"]
    return [f"{name}, dt {r['dt'] * 1e3:g} ms", str(f["steps"]), str(it) if it else "-",
            f"{f['per_step']:.2f}" if it else "-", f"{1e6 * f['per_iteration_s']:.1f}" if it else "-",
            f"{1e6 * f['per_step_s']:.0f}"]


def anatomy_lines(rows: list[tuple]) -> list[str]:
    """The table of ``rows`` = [(accuracy, ours, cable, ratio, source)]: the cheapest runs
    (records or None), the row's ratio (None without both) and where it comes from
    ('rounds' or 'grid')."""
    out = ["Where the time goes (time = steps x iterations per step x time per iteration; iterations as each "
           f"code counts them) and the target, ours at most {TARGET:g} of the cable's time:", "",
           "| accuracy | run | steps | Newton iterations | per step | time / iteration (us) | time / step (us) | "
           "target |", "|---|---|---|---|---|---|---|---|"]
    for acc, o, p, ratio, source in rows:
        how = {"rounds": ", by the rounds' median", "grid": ", by the grid's medians"}.get(source, "")
        v = verdict(acc, ratio, o, p) + (how if acc in TARGET_ACCURACIES else "")
        out.append(f"| {100 * acc:g} % | ours: " + " | ".join(_run(o)) + f" | {v} |")
        out.append("| | cable: " + " | ".join(_run(p)) + " | |")
    return out


def step_error_lines(recs: list[dict]) -> list[str]:
    """One sentence: the errors at the coarsest step on each side's finest mesh that has
    a result there."""
    if not recs:
        return []
    dt = max(r["dt"] for r in recs)
    parts = []
    for solver, name in (("ancf", "ours"), ("exudyn", "the cable's")):
        finest = _finest_errors(recs, solver, dt)
        if finest is None:
            continue
        n, e = finest
        lo, hi = f"{100 * min(e):.2f}", f"{100 * max(e):.2f}"
        parts.append(f"{name} {lo}{'' if lo == hi else ' to ' + hi} % ({n} elements)")
    return [f"At the coarsest step, {dt * 1e3:g} ms, the runs on the finest mesh with a result there (the "
            "step's error plus the model's floor, tabled below) are off by: " + "; ".join(parts) + "."] if parts else []


def _finest_errors(recs: list[dict], solver: str, dt: float) -> tuple[int, list[float]] | None:
    """(n, errors) of ``solver``'s runs at step dt on the finest mesh with a result there;
    None: no result at dt."""
    mine = [r for r in recs if r["solver"] == solver and r["dt"] == dt and r.get("error") is not None]
    if not mine:
        return None
    n = max(r["elements"] for r in mine)
    return n, [r["error"] for r in mine if r["elements"] == n]


def _cheapest_per_step(recs: list[dict]) -> dict[float, dict]:
    """dt -> our fastest run at that step, whatever its element, mesh and error."""
    out = {}
    for r in recs:
        if r["solver"] == "ancf" and r.get("time_s") and (r["dt"] not in out or r["time_s"] < out[r["dt"]]["time_s"]):
            out[r["dt"]] = r
    return out


def step_floor(recs: list[dict], dt: float) -> float | None:
    """Our smallest error at step dt on the finest mesh with a result there: the step's own
    error plus the best model's floor (None: no result at dt)."""
    finest = _finest_errors(recs, "ancf", dt)
    return None if finest is None else min(finest[1])


def _step_run(dt: float, r: dict) -> str:
    """'10 ms HB2n-12 x 2 1.9 ms (20.6 %)': a run of :func:`reach_lines`' list."""
    err = f" ({100 * r['error']:.1f} %)" if r.get("error") is not None else ""
    return f"{dt * 1e3:g} ms {r['element']} x {r['elements']} {r['time_s'] * 1e3:.1f} ms{err}"


def reach_lines(recs: list[dict], rows: list[tuple]) -> list[str]:
    """For each row of ``rows`` (as :func:`anatomy_lines`) whose target is not met and the
    cable reaches: can an element meet it? Half the cable's time (grid medians) against our
    cheapest run at each step at any error, and the step's own error where one fits."""
    out = []
    per_step = _cheapest_per_step(recs)
    steps = sorted(per_step, reverse=True)
    listed = ", ".join(_step_run(dt, per_step[dt]) for dt in steps)
    for acc, o, p, ratio, _ in rows:
        if acc not in TARGET_ACCURACIES or p is None or (o is not None and ratio <= TARGET) or not per_step:
            continue
        budget = TARGET * p["time_s"]
        text = (f"Can an element meet the {100 * acc:g} % target? {TARGET:g} of the cable's time is "
                f"{budget * 1e3:.2f} ms (its grid median {p['time_s'] * 1e3:.2f} ms). Our cheapest run at each step, "
                f"at any error: {listed}. ")
        fit = [dt for dt in steps if per_step[dt]["time_s"] <= budget]
        if not fit:
            lo = min(per_step.values(), key=lambda r: r["time_s"])
            text += (f"None is within it (the cheapest, {lo['time_s'] / p['time_s']:.2f} of the cable's time): no "
                     "element at least as cheap per step as these meets the target on this step loop; it takes a "
                     "cheaper step, not a better element.")
        else:
            floor = {dt: step_floor(recs, dt) for dt in fit}
            if all(e is not None and e > acc for e in floor.values()):
                text += (f"Only the runs at {_ms(fit)} ms are within it, and there our "
                         "finest meshes are off by " + ", ".join(f"{100 * floor[dt]:.2f} %" for dt in fit)
                         + f" (the step's own error): an element would reach {100 * acc:g} % there only through a "
                         "mesh error that cancels the step's.")
            else:
                allows = [dt for dt in fit if floor[dt] is None or floor[dt] <= acc]     # as the test above
                n = max(r["elements"] for r in recs if r["solver"] == "ancf" and r["dt"] in allows
                        and r.get("time_s") and r["time_s"] <= budget)
                text += (f"Runs at {_ms(fit)} ms are within it, and at {_ms(allows)} ms the step allows "
                         f"{100 * acc:g} %: an element that reaches it there on {n} elements or fewer (the most within the time) would "
                         "meet the target. " + _fewest_elements(recs, n, allows))
                if o is not None and o["time_s"] <= budget:
                    text += (f" Our cheapest {100 * acc:g} % run is within it by the grid's medians "
                             f"({o['time_s'] * 1e3:.1f} ms); the verdict above is the rounds'.")
        out.append(text)
    return out


def _ms(steps: list[float]) -> str:
    """'10, 5, 2.5': steps in ms, as the reach sentences list them."""
    return ", ".join(f"{dt * 1e3:g}" for dt in steps)


def _fewest_elements(recs: list[dict], n: int, steps: list[float]) -> str:
    """How close any run comes on n elements or fewer at these steps, at any cost: the
    smallest error of ours and of the cable's."""
    parts = []
    for solver, name in (("ancf", "ours"), ("exudyn", "the cable's")):
        mine = [r for r in recs if r["solver"] == solver and r["elements"] <= n and r["dt"] in steps
                and r.get("error") is not None and r.get("time_s")]
        if mine:
            b = min(mine, key=lambda r: r["error"])
            what = (f"{b['element']} x {b['elements']}" if solver == "ancf"
                    else f"{b['elements']} elements{cable_mode(b['element'])}")
            parts.append(f"{name} {100 * b['error']:.2f} % ({what}, {b['dt'] * 1e3:g} ms, {b['time_s'] * 1e3:.1f} ms)")
    return (f"On {n} elements or fewer at {'these steps' if len(steps) > 1 else 'that step'}, the smallest error of "
            "any run, at any cost: " + "; ".join(parts) + ".") if parts else ""
