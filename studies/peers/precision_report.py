"""The work-precision report: ``reports/peers_work_precision.md`` and one figure per scene,
drawn from the bench's records alone (``data/peers/peers-work-precision.jsonl`` and the
deciding points' re-timings beside it; :mod:`studies.peers.work_precision` writes them, the
audit redraws from them; :mod:`studies.peers.records` reads them). Each row names the
cheapest runs that count for its accuracy, by the rules of :mod:`studies.peers.precision_rules`,
and its deciding ratio; beside the rows, the models' floors (:func:`floors`) and, where a
target is missed, its measurements (:mod:`studies.peers.step_cost_report`)."""
from __future__ import annotations

import csv
import io
import itertools
import statistics
from pathlib import Path

from ancf.elements import ELEMENTS

from ..engine.report import (draw_front, draw_targets, element_color, figure_data, front, legend_outside,
                             target_handle)
from .anatomy import anatomy_lines, reach_lines, step_error_lines
from .precision_grid import ACCURACIES, MIN_REPEATS, NAME, SCENE, SCENES, cable_mode, our_element
from .precision_rules import cheapest, deciding_ratio, finer, round_pair, round_ratios, rounds_of
from .step_cost_report import lines as cost_lines


def rounds_text(r: dict | None) -> str:
    """'median (each round's ratio)' of a rounds record, or '-'."""
    rr = [x for x in round_ratios(r) if x is not None]
    return f"{statistics.median(rr):.2f} ({', '.join(f'{x:.2f}' for x in rr)})" if rr else "-"


def floors(recs: list[dict]) -> dict[tuple, dict]:
    """(solver, element) -> the run at the finest step of its finest mesh: its error is
    the model's accuracy floor read where step and mesh errors are smallest (not the
    smallest error over the grid, which a cancellation of the two can reach)."""
    out = {}
    for r in recs:
        if r["error"] is None:
            continue
        k = (r["solver"], r["element"])
        q = out.get(k)
        if q is None or (r["elements"], -r["dt"]) > (q["elements"], -q["dt"]):
            out[k] = r
    return out


def is_cable(element: str) -> bool | None:
    """Is our run's element (a label, :func:`our_element`) a centre-line cable (no section
    field: no shear, no thickness change)? None: not a registered element here."""
    name = our_element(element)[0]
    return (not ELEMENTS[name].family.section_field) if name in ELEMENTS else None


def floors_by_section(fl: dict[tuple, dict]) -> str:
    """One sentence: our cables' floors (each at our default settings) beside the range of
    our shear-deformable elements' (a section field: shear and thickness change) and the
    peer cable's, from :func:`floors`; '' without a cable of ours or a section element."""
    ours = {e: r for (s, e), r in fl.items() if s == "ancf" and our_element(e)[0] == e}
    cables = {e: r for e, r in ours.items() if is_cable(e)}
    sections = {e: r for e, r in ours.items() if is_cable(e) is False}
    if not (cables and sections):
        return ""
    lo = min(sections, key=lambda e: sections[e]["error"])
    hi = max(sections, key=lambda e: sections[e]["error"])
    peer = sorted({f"{100 * r['error']:.3f} %" for (s, _), r in fl.items() if s == "exudyn"})
    return ("The floors by section model: our cable" + ("s " if len(cables) > 1 else " ")
            + ", ".join(f"{e} {100 * r['error']:.3f} %" for e, r in sorted(cables.items()))
            + f" (a centre line, Euler-Bernoulli, the law's exact uniaxial energy), against {100 * sections[lo]['error']:.3f} "
            f"% ({lo}) to {100 * sections[hi]['error']:.3f} % ({hi}) for our shear-deformable elements (a section field: "
            "shear and the section's thickness change)"
            + (f", and {' and '.join(peer)} for Exudyn's linear elastic cable" if peer else "") + ".")


def spread(r: dict) -> str:
    """'min-max' of the record's timed runs, or '-' (older records kept the median only)."""
    runs = r.get("time_runs_s")
    return f"{min(runs):.4f}-{max(runs):.4f}" if runs else "-"


def scenes_of(recs: list[dict]) -> list[str]:
    """The records' scenes, in :data:`SCENES` order (older records: the pendulum)."""
    have = {r.get("scene", SCENE) for r in recs}
    return [s for s in SCENES if s in have] + sorted(have - set(SCENES))


def figure_name(scene: str, every: bool = False) -> str:
    """The lead figure of a scene, or (``every``) its full cloud of every run."""
    stem = "peers_work_precision" if scene == SCENE else f"peers_work_precision_{scene}"
    return f"{stem}_all.png" if every else f"{stem}.png"


def report(recs: list[dict], out: Path, rounds: list[dict] = (), costs: list[dict] = ()) -> str:
    """The tables (markdown, :func:`report_markdown`) and two figures per scene from the
    records: the lead one (each element's front) and every run."""
    text = report_markdown(recs, rounds, costs)
    for scene in scenes_of(recs):
        for every in (False, True):
            figure([r for r in recs if r.get("scene", SCENE) == scene], out / figure_name(scene, every), scene, every)
    (out / "peers_work_precision.md").write_text(text)
    return text


def ratio_range(o: dict, p: dict) -> str:
    """'lo-hi' of ours / Exudyn's over their timed runs (slowest against fastest and back)."""
    a, b = o.get("time_runs_s"), p.get("time_runs_s")
    return f"{min(a) / max(b):.2f}-{max(a) / min(b):.2f}" if a and b else "-"


def load_text(recs: list[dict]) -> str:
    loads = [x for r in recs for x in (r["host_load"] if isinstance(r.get("host_load"), list)
                                        else [r["host_load"]] if r.get("host_load") is not None else [])]
    return (f"{min(loads):.2f} to {max(loads):.2f} (median {statistics.median(loads):.2f}; before and after each point)"
            if loads else "not recorded")


def ref_text(recs: list[dict]) -> str:
    e = {r.get("reference_error") for r in recs} - {None}
    return (f", its error estimate at most {100 * max(e):.3f} % of L" if e else ", its error estimate not recorded")


def scene_markdown(recs: list[dict], scene: str, rounds: list[dict] = (), costs: list[dict] = ()) -> list[str]:
    """The section of one scene's records (``rounds``: its deciding points' re-timings,
    :func:`studies.peers.work_precision.retime`; ``costs``: its missed targets' measurements,
    :mod:`studies.peers.step_cost`, drawn while their two points are still the row's)."""
    guards = {r.get("energy_guard", "the scene's energy limit") for r in recs if r["solver"] == "ancf"}
    runs = [len(r["time_runs_s"]) for r in recs if r.get("time_runs_s")]
    els = sorted({r["element"] for r in recs if r["solver"] == "ancf"})
    info = SCENES.get(scene, {"title": scene, "reference": "?"})
    lines = [f"## Scene `{scene}`: {info['title']}", "",
             f"Reference: {info['reference']}" + ref_text(recs) + f". Our elements: {', '.join(els)}"
             + " (all on the compiled step loop: the scenes are plane stress, where an element's pressure "
             "field carries no penalty).", "",
             "Energy guard: "
             + ("none on either side (Exudyn's run has none; ours runs with energy_limit = inf)"
                if guards == {"none"} else "NOT the same on both sides in these records (ours: "
                + ", ".join(sorted(guards)) + "; Exudyn: none): rerun with --force")
             + ". Timed runs per point: " + ((f"{min(runs)}" if min(runs) == max(runs) else f"{min(runs)} to {max(runs)}") if runs else "not recorded (older records)")
             + (f" (fewer than {MIN_REPEATS}: rerun with --repeats {MIN_REPEATS})" if not runs or min(runs) < MIN_REPEATS
                else "") + "; time = their median, spread = min-max. Load average (1 min) during the runs: "
             + load_text(recs) + ".",
             "",
             "| accuracy | cheapest ours | time (s) | error (%) | cheapest Exudyn cable | time (s) | error (%) | "
             "ours / Exudyn (medians) | range over runs | by rounds: median (each round) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    rows = []                          # (accuracy, ours, cable, ratio, source): the anatomy's rows
    for a in ACCURACIES:
        o, p = cheapest(recs, "ancf", None, a), cheapest(recs, "exudyn", None, a)
        fo = (f"{o['element']} x {o['elements']}, dt {o['dt'] * 1e3:g} ms | {o['time_s']:.4f} | "
              f"{100 * o['error']:.3f}") if o else "none | - | -"
        fp = (f"{p['elements']} elements{cable_mode(p['element'])}, dt {p['dt'] * 1e3:g} ms | {p['time_s']:.4f} | "
              f"{100 * p['error']:.3f}") if p else "none | - | -"
        ratio = (f"{o['time_s'] / p['time_s']:.2f} | {ratio_range(o, p)}" if o and p
                 else "- (ours reaches it, the cable does not) | -" if o else "- | -")
        rr = rounds_of(rounds, scene, a, o, p) if o and p else None
        lines.append(f"| {100 * a:g} % | {fo} | {fp} | {ratio} | {rounds_text(rr)} |")
        rows.append((a, o, p, *deciding_ratio(o, p, rr)))
    if any(r.get("rounds") for r in rounds):
        n = sorted({len(r["rounds"]) for r in rounds})
        lines += ["", f"By rounds: the two points of a row timed again alternately after the grid ({'/'.join(map(str, n))} "
                  f"rounds of {'/'.join(map(str, sorted({r['repeats'] for r in rounds})))} runs, the cable's first), "
                  "each round's ratio of its two medians; the machine's speed drifts within a run, and a round's "
                  "two medians share its phase (data/peers/" + f"{NAME}-rounds.jsonl)."]
    lines += [""] + anatomy_lines(rows)
    lines += [""] + step_error_lines(recs)
    for text in reach_lines(recs, rows):
        lines += ["", text]
    def pair(c):
        return {k: {x: c[k][x] for x in ("element", "elements", "dt")} for k in ("ours", "exudyn")}
    current = [c for c in costs if any(a == c["accuracy"] and o and p and round_pair(o, p) == pair(c)
                                       for a, o, p, _, _ in rows)]
    if current:
        lines += [""] + cost_lines(current, recs)[:-1]
    fl = floors(recs)
    if fl:
        lines += ["", "Accuracy floors, read at the finest step of the finest mesh (the cable's: its physics, "
                  "linear elastic E = 6 C10, Euler-Bernoulli, no thickness deformation):", "",
                  "| solver | element | n | dt (ms) | error (%) |", "|---|---|---|---|---|"]
        for (solver, element), r in sorted(fl.items()):
            lines.append(f"| {solver} | {element} | {r['elements']} | {r['dt'] * 1e3:g} | {100 * r['error']:.4f} |")
        by_section = floors_by_section(fl)
        lines += ["", by_section] if by_section else []
    pins = sorted({k for r in fl.values() for k in (r.get("error_by_pin_mm") or {})}, key=float, reverse=True)
    if pins:
        lines += ["", "The floors against the same continuum with other pin sizes (the point pin is as large as its "
                  "cell, so the larger pins come from coarser meshes, 2 cells across at 10 mm; the reference's pin is 1.25 mm): the error of a beam pinned at its centreline depends on the "
                  "continuum pin it is held against, the gap between the codes much less:", "",
                  "| solver | element | " + " | ".join(f"pin {p} mm (%)" for p in pins) + " |",
                  "|---|---|" + "---|" * len(pins)]
        for (solver, element), r in sorted(fl.items()):
            e = r.get("error_by_pin_mm") or {}
            lines.append(f"| {solver} | {element} | "
                         + " | ".join(f"{100 * e[p]:.3f}" if p in e else "-" for p in pins) + " |")
    lines += ["", "| solver | element | n | dt (ms) | status | time (s) | spread (s) | error (%) |",
              "|---|---|---|---|---|---|---|---|"]
    for r in sorted(recs, key=lambda r: (r["solver"], r["element"], r["elements"], -r["dt"])):
        lines.append(f"| {r['solver']} | {r['element']} | {r['elements']} | {r['dt'] * 1e3:g} | {r['status']} | "
                     + (f"{r['time_s']:.4f}" if r["time_s"] else "-") + f" | {spread(r)} | "
                     + (f"{100 * r['error']:.4f}" if r["error"] is not None else "-") + " |")
    lines += ["", f"![work-precision, {scene}]({figure_name(scene)})", "",
              f"![work-precision, {scene}, every run]({figure_name(scene, True)})", ""]
    return lines


def report_markdown(recs: list[dict], rounds: list[dict] = (), costs: list[dict] = ()) -> str:
    """reports/peers_work_precision.md from the records alone (a plain function): one
    section per scene (``rounds``: the deciding points' re-timings, :func:`studies.peers.work_precision.retime`;
    ``costs``: the missed targets' measurements, :mod:`studies.peers.step_cost`)."""
    lines = ["# Work-precision: our pendulum against Exudyn's ANCF cable",
             "",
             "Generated by `python -m studies peers work-precision` (`make bench-peers`) from "
             f"`data/peers/{NAME}.jsonl`; do not edit; see the docstring of `studies/peers/work_precision.py` for the "
             "method. Error: max over t = 0.1 ... 0.5 s of |r - r_ref| / L against the scene's converged continuum plane-stress Yeoh pendulum; "
             "time: median warm solve wall time, both solvers in one run (each point: Exudyn's runs, then ours), "
             "one thread. A run counts for an accuracy only if every finer step of its mesh and every finer mesh at its "
             "step reach it too, failed or diverged runs reaching nothing (the two-way fairness rule, the same for both "
             "sides: no accuracy by cancellation of step and mesh errors). Ratios below 1: ours is cheaper. The cable runs "
             "with modified Newton (ANCFCable2D) and with one linear solve per step (ANCFCable2D-linear: Exudyn's "
             "newton.active = False, no convergence test); its cheapest run at an accuracy is taken over "
             "both (marked 'linear' where it is the latter); ours runs at its defaults, marked '(rtol 1e-3)' at the "
             "loosest Newton tolerance a scene accepts, and marked '(linear)' with one solve per step and no "
             "convergence test, as the cable's linear mode (its state's det F still checked), its cheapest run taken "
             "over the three.",
             ""]
    for scene in scenes_of(recs):
        lines += scene_markdown([r for r in recs if r.get("scene", SCENE) == scene], scene,
                                [r for r in rounds if r["scene"] == scene], [c for c in costs if c["scene"] == scene])
    return "\n".join(lines)


def figure(recs: list[dict], path: Path, scene: str = SCENE, every: bool = False) -> None:
    """The work-precision figure of one scene's records (``path``, a .png; ``every``: the full
    cloud, else the lead figure) and the data it draws beside it (``<name>.figure.csv``,
    :func:`figure_csv`, which the audit compares)."""
    import matplotlib.pyplot as plt

    fig = (make_all_figure if every else make_figure)(recs, scene)
    fig.savefig(path, dpi=150, bbox_inches="tight")
    path.with_name(path.stem + ".figure.csv").write_text(_csv(fig))
    plt.close(fig)


def _csv(fig) -> str:
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(["panel", "title", "x label", "y label", "label", "marker", "filled", "x", "y"])
    w.writerows(figure_data(fig))
    return buf.getvalue()


def figure_csv(recs: list[dict], scene: str = SCENE, every: bool = False) -> str:
    """Every point the scene's figure draws (``every``: its full cloud's), as the audit's
    figure data (CSV text)."""
    import matplotlib.pyplot as plt

    fig = (make_all_figure if every else make_figure)([r for r in recs if r.get("scene", SCENE) == scene], scene)
    try:
        return _csv(fig)
    finally:
        plt.close(fig)


def _title(recs: list[dict], scene: str) -> str:
    h = SCENES.get(scene, {}).get("height")
    return (f"{scene}" + (f" (h = {h * 1e3:g} mm)" if h else "") + ", Yeoh, plane stress; "
            f"step {1e3 * max(r['dt'] for r in recs):g} ms halving")


def settled_fronts(recs: list[dict]) -> dict[tuple[str, str], list[dict]]:
    """{(solver, element): its front}: each run's settled error (the largest over it and the
    runs that refine it one way, :func:`finer`; None where one of them failed), and of a
    registered element's runs (every Newton setting of ours, both modes of the cable) those no
    cheaper one beats (:func:`studies.engine.report.front`): the first point of a front within
    an accuracy is the element's cheapest run that :func:`holds` it."""
    pts, runs = [], {}
    for r in recs:                  # finer(r, ...) looks among r's own solver and element only
        runs.setdefault((r["solver"], r["element"]), []).append(r)
    for r in recs:
        if r["error"] is None or not r["time_s"]:
            continue
        qs = finer(r, runs[(r["solver"], r["element"])])
        if all(q["error"] is not None for q in qs):
            key = (r["solver"], our_element(r["element"])[0] if r["solver"] == "ancf" else "cable")
            pts.append({"key": key, "time": r["time_s"], "settled": max(q["error"] for q in qs), "run": r})
    out = {}
    for key in dict.fromkeys(p["key"] for p in pts):
        out[key] = front([p for p in pts if p["key"] == key], error="settled")
    return out


def make_figure(recs: list[dict], scene: str = SCENE):
    """The lead work-precision figure of one scene's records (a matplotlib Figure): each of our
    elements' front (:func:`settled_fronts`, over its Newton settings) in its colour, the
    Exudyn cable's front (over its two modes) in black beside them, the accuracies dotted."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fr = settled_fronts(recs)
    fig, ax = plt.subplots(figsize=(5.6, 4.2), layout="constrained")
    markers = dict(zip([k for k in fr if k[0] == "ancf"], itertools.cycle("o^vDpXh*P<>")))
    for key, f in fr.items():
        if key[0] == "ancf":
            draw_front(ax, f, f"ours {key[1]}", error="settled", color=element_color(key[1]), marker=markers[key],
                       zorder=3)
    for key, f in fr.items():
        if key[0] == "exudyn":
            draw_front(ax, f, "Exudyn ANCFCable2D (either mode)", error="settled", color="k", marker="s", ls="--",
                       lw=1.8, zorder=4)
    draw_targets(ax, ACCURACIES)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.grid(True, alpha=0.3)
    ax.minorticks_off()
    ax.set_xlabel("solve wall time, median warm (s)")
    ax.set_ylabel("settled max over t of |r - r_ref| / L")
    ax.set_title(_title(recs, scene), fontsize=9)
    h, l = ax.get_legend_handles_labels()
    th, tl = target_handle(ACCURACIES)
    legend_outside(fig, h + [th], l + [tl], title="fronts", title_fontsize=7)
    return fig


def make_all_figure(recs: list[dict], scene: str = SCENE):
    """Every run of one scene's records (a matplotlib Figure): a curve per code, element (and
    setting) and mesh along the step ladder."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.lines
    import matplotlib.pyplot as plt

    els = list(dict.fromkeys(r["element"] for r in recs if r["solver"] == "ancf"))
    cables = list(dict.fromkeys(r["element"] for r in recs if r["solver"] == "exudyn"))
    fig, ax = plt.subplots(figsize=(6.4, 4.6), layout="constrained")
    markers = {**{e: m for e, m in zip(cables, itertools.cycle("sx+"))},
               **{e: m for e, m in zip(els, itertools.cycle("o^vDpXh*P<>"))}}
    colors = dict(zip([("exudyn", e) for e in cables] + [("ancf", e) for e in els],
                      itertools.cycle(plt.rcParams["axes.prop_cycle"].by_key()["color"])))
    handles = []
    for solver, element in [("exudyn", e) for e in cables] + [("ancf", e) for e in els]:
        style = dict(marker=markers[element], color=colors[(solver, element)],
                     ls="--" if solver == "exudyn" else ":" if element != our_element(element)[0] else "-")
        for n in sorted({r["elements"] for r in recs if (r["solver"], r["element"]) == (solver, element)}):
            ser = sorted([r for r in recs if (r["solver"], r["element"], r["elements"]) == (solver, element, n)
                          and r["error"] is not None and r["time_s"]], key=lambda r: -r["dt"])
            if ser:
                ax.plot([r["time_s"] for r in ser], [r["error"] for r in ser], ms=3, lw=0.8, **style,
                        label=f"{'Exudyn ' + element if solver == 'exudyn' else 'ours ' + element} x {n}")
        handles.append(matplotlib.lines.Line2D([], [], ms=3, lw=0.8, **style,
                                               label=f"{'Exudyn ' if solver == 'exudyn' else 'ours '}{element}"))
    draw_targets(ax, ACCURACIES)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.grid(True, alpha=0.3)
    ax.set_xlabel("solve wall time, median warm (s)")
    ax.set_ylabel("max over t of |r - r_ref| / L")
    ax.set_title(_title(recs, scene), fontsize=9)
    # one entry per element and solver (its meshes share its colour; every curve runs over the
    # steps, halving; which mesh a curve is: its label in the figure's data, and the run table)
    th, tl = target_handle(ACCURACIES)
    legend_outside(fig, handles + [th], [h.get_label() for h in handles] + [tl], fontsize=6,
                   title="curve = one mesh over the steps;\ndashed: Exudyn, dotted: ours at cheap settings",
                   title_fontsize=6)
    return fig
