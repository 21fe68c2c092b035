"""Accuracy against cost, static half of study 6: a work-precision diagram.

Error: |u - u_ref| / |u_ref| over (ux, uy), u_ref the converged continuum value of the
matching model (ANCF plane-stress against continuum plane stress, plane-strain against
continuum plane strain with the same penalty). Cost: the median wall time of serial warm
runs of the whole solver call (build + solve + tip), one process, after a warm-up
(the cases' ``timing`` option; never timed inside a pool). Every element, formulation,
quadrature and mesh, and the continuum model's own curve: its levels timed the same
way, their error against the continuum's own Richardson value.

The hyperelastic cable HC2n-8 runs beside the other elements where it can: its plane-stress
cells, and the pendulum on Table 4's step ladder (this study's own pendulum cases, the
``pendulum`` grid: Table 4 runs the paper's elements); it refuses plane strain (its section is
uniaxial with free faces), and the tables say so (:func:`absent`). The choose-an-element
table adds, from the cable's card records (its slenderness sweep), the L / h below which the
cable stops being within each accuracy of the continuum: below it a shear-deformable section
is needed (:func:`cable_slenderness`).
"""
from __future__ import annotations

from ..engine.case import make_case
from ..verification.continuum import scene as continuum_scene
from ..common.pendulum_cases import LENGTH
from ..common.grid import DEFAULT, cantilever_case, counts_of, qlabel, takes
from ..common.gold import short, MATCHING, continuum_references, describe, variant_of
from ..engine.report import (GOOD, MAX_SERIES, Section, Table, draw, draw_front, draw_grey, draw_targets, element_color,
                             figure, front, hollow_legend, legend_outside, marker, pct, target_handle, vec_error,
                             verdict)


STUDY = {
    "name": "accuracy-cost",
    "title": "Accuracy against cost (static cantilever and pendulum)",
    # the pendulum half reads Table 4's timed step ladder (no cases of its own)
    "needs": ["continuum", "table4"],
    "grid": {
        "laws": ["neo-hookean", "mooney-rivlin", "yeoh"],
        # HC2n-8, the hyperelastic cable, runs plane stress alone (its plane-strain cells are absent, :func:`absent`)
        "elements": ["HB2n-12", "HB3n-12", "HB2n-16", "LB2n-12", "HB2n-20xyp", "HB2n-20xypm", "HB2n-40p", "HB2n-60p",
                     "HC2n-8"],
        "formulations": ["plane-strain", "plane-stress"],
        # "default": each element's own rule at each mesh's l_e / h; the fixed rules of the paper's
        # elements are the study accuracy-cost-rules (make study-full), drawn here when recorded
        "quadratures": ["default"],
        "counts": [4, 8, 16, 32, 64, 160, 320, 640],
        "clamp": "face",
        # serial warm timings: the compiled code loaded, then up to `repeats` runs within `budget_s`
        "timing": {"repeats": 3, "budget_s": 2.0},
        # the continuum curve: these levels of the continuum study's variants, timed the same way
        "continuum_levels": [[16, 1], [32, 2], [64, 4], [128, 8]],
        # the targets of the tables and the figures' dotted lines (the peer report's three)
        "accuracies": [0.01, 0.003, 0.001],
        # the pendulum beside Table 4's rungs (the paper's elements): the elements of this grid that
        # Table 4 does not run (:func:`pendulum_elements`: the lock-free pressure elements and the
        # cable), in Table 4's formulations where they run them, on Table 4's grid (its step ladder,
        # 8 ms halving to dt_last, its counts and timing)
        "pendulum": {"counts": [4, 8, 16, 32], "rho_inf": 0.5, "t_end": 0.5, "dt_last": 0.00025,
                     "timing": {"repeats": 3, "budget_s": 1.5}},
    },
    "tiny": {
        "laws": ["yeoh"],
        "elements": ["HB2n-12", "HB3n-12", "HC2n-8"],
        "counts": [4, 8],
        "timing": {"repeats": 2, "budget_s": 0.5},
        "continuum_levels": [[8, 1]],
        "pendulum": {"elements": ["HC2n-8"], "counts": [8], "formulations": ["plane-stress"], "rho_inf": 0.5,
                     "t_end": 0.5, "dt_last": 0.0005, "timing": {"repeats": 1, "budget_s": 0.0}},
    },
}

STYLE = {(2, 2): ":", (3, 2): "-", (5, 3): "--", (3, 3): "-.", DEFAULT: "-"}
# the fixed rules of the paper's elements (make study-full), drawn here when recorded
RULES = "accuracy-cost-rules"


def cases(grid: dict, tiny: bool, study: str = "accuracy-cost") -> list:
    """The static cantilever of every law, formulation, element (where it runs the
    formulation: :func:`absent`), rule and mesh; the continuum's levels; the ``pendulum``
    grid's runs on Table 4's step ladder (where the grid has one)."""
    from ancf.checks import runs
    from ..common.pendulum_cases import ladder, pendulum_case

    opts = {"timing": dict(grid["timing"])}
    out = [cantilever_case(study, law, f, el, n, q, grid["clamp"], opts)
           for law in grid["laws"] for f in grid["formulations"] for el in grid["elements"] if runs(el, f)
           for q in grid["quadratures"] if takes(grid, el, q) for n in counts_of(grid, el)]
    out += [make_case(study, "continuum", continuum_scene(law, MATCHING[f], tuple(lv)), opts)
            for law in grid["laws"] for f in grid["formulations"] for lv in grid["continuum_levels"]]
    pd = grid.get("pendulum")
    if pd:
        popts = {"timing": dict(pd["timing"])}
        out += [pendulum_case(study, el, n, f, dt, rho_inf=pd["rho_inf"], t_end=pd["t_end"], options=popts)
                for f in pendulum_formulations(grid) for el in pendulum_elements(grid) if runs(el, f)
                for n in pd["counts"] for dt in ladder(last=pd.get("dt_last"))]
    return out


def pendulum_elements(grid: dict) -> list[str]:
    """The elements of the ``pendulum`` grid: its own list where it names one (the CI grid),
    else every element of the static grid that Table 4 does not run (Table 4's rungs are read,
    not rerun), so that the pendulum rows of the tables search the elements the static rows do."""
    from ..paper.table4 import STUDY as TABLE4

    pd = grid.get("pendulum") or {}
    if "elements" in pd:
        return list(pd["elements"])
    return [el for el in grid["elements"] if el not in TABLE4["grid"]["elements"]]


def pendulum_formulations(grid: dict) -> list[str]:
    """The ``pendulum`` grid's formulations: its own where it names them, else Table 4's."""
    from ..paper.table4 import STUDY as TABLE4

    return list((grid.get("pendulum") or {}).get("formulations") or TABLE4["grid"]["formulations"])


def absent(grid: dict) -> list[str]:
    """Why the grid's elements that refuse one of its formulations have no cells there
    (a cable: plane stress alone), one sentence each."""
    from ancf.checks import runs
    from ancf.elements import get_element
    from .card_cable import CABLE_NOT_RUN

    out = []
    for el in grid["elements"]:
        miss = [f for f in grid["formulations"] if not runs(el, f)]
        if miss:
            why = CABLE_NOT_RUN if get_element(el).cable else f"it runs {', '.join(get_element(el).formulations)} only"
            out.append(f"{el} has no {' or '.join(f'`{f}`' for f in miss)} cells: {why}.")
    return out


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


def draw_fronts(ax, fr: dict[str, list[dict]], colored: list[str], markers: list[str]) -> None:
    """The coloured elements' fronts, one series each, and the others' in one grey series."""
    draw_grey(ax, [([p["time"] for p in f], [p["settled"] for p in f]) for el, f in fr.items() if el not in colored])
    for el in colored:
        draw_front(ax, fr[el], el, error="settled", color=element_color(el), marker=marker(el, markers), zorder=3)


def _log_axes(ax) -> None:
    """Log scales, decades gridded, no minor ticks (several panels of minor log ticks cost
    a constrained layout most of its drawing time, and say little on these ranges)."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.grid(True, which="major", alpha=0.3)
    ax.minorticks_off()


def _panel(ax, g: dict, sel: list[dict]) -> None:
    """One law and model of the full cloud: a curve per configuration (ANCF element and
    rule) over its meshes, and the continuum's own levels in black."""
    for cfg in dict.fromkeys(p["config"] for p in sel):
        ser = [p for p in sel if p["config"] == cfg and p["error"] is not None and p["time"]]
        ser.sort(key=lambda p: p["ndof"] or 0)  # along the refinement
        if not ser:
            continue
        xs, ys, vs = [p["time"] for p in ser], [max(p["error"], 1e-7) for p in ser], [p["verdict"] for p in ser]
        if cfg.startswith("continuum"):
            draw(ax, xs, ys, vs, "continuum Q2 (levels)", color="k", marker="D", lw=2, ms=5)
            continue
        el, q = ser[0]["element"], ser[0]["quadrature"]
        draw(ax, xs, ys, vs, cfg, marker=marker(el, g["elements"]), ls=STYLE.get(q, "-"), lw=1, ms=3.5)
    draw_targets(ax, g["accuracies"])
    _log_axes(ax)


def _grid_of_panels(g: dict, models: list[str]):
    fig, axes = figure(len(models), len(g["laws"]), figsize=(3.9 * len(g["laws"]), 3.3 * len(models)),
                       squeeze=False, sharex=True, sharey=True, layout="constrained")
    for i, (f, m) in enumerate(zip(g["formulations"], models)):
        for j, law in enumerate(g["laws"]):
            ax = axes[i][j]
            ax.set_title(f"{law}: `{f}` vs continuum {m}", fontsize=8)
            if i == len(models) - 1:
                ax.set_xlabel("wall time, serial warm (s)")
    return fig, axes


def static_fronts(g: dict, pts: list[dict], law: str, model: str) -> tuple[dict, dict | None]:
    """({element: front}, the continuum's front) of one law and model (:func:`fronts`)."""
    sel = [p for p in pts if p["law"] == law and p["model"] == model]
    fr = fronts(with_settled(sel, static_finer(sel)))
    return {el: f for el, f in fr.items() if el != "continuum"}, fr.get("continuum")


def lead_figure(g: dict, pts: list[dict], models: list[str]):
    """The lead work-precision figure of the static cantilever (a matplotlib Figure): per law
    and model, each element's front of settled errors (:func:`fronts`), the leaders coloured
    (:func:`leaders`), the others grey, the continuum's own front in black, the targets dotted."""
    fig, axes = _grid_of_panels(g, models)
    for i, m in enumerate(models):
        for j, law in enumerate(g["laws"]):
            ax = axes[i][j]
            fr, cont = static_fronts(g, pts, law, m)
            draw_fronts(ax, fr, [el for el in g["elements"] if el in leaders(fr, g["accuracies"])], g["elements"])
            if cont:
                draw_front(ax, cont, "continuum Q2 (levels)", error="settled", color="k", marker="D", ms=4, lw=1.8)
            draw_targets(ax, g["accuracies"])
            _log_axes(ax)
            if j == 0:
                ax.set_ylabel("settled |u - u_ref| / |u_ref|")
    legend_outside(fig, *_with_targets(fig, g["accuracies"], g["elements"]))
    return fig


def _with_targets(fig, targets, order=()) -> tuple[list, list]:
    """Every axes' labelled artists once (those named in ``order`` first, in its order) and
    the targets' entry."""
    hs, ls = [], []
    for ax in fig.axes:
        for h, l in zip(*ax.get_legend_handles_labels()):
            if l not in ls:
                hs.append(h)
                ls.append(l)
    rank = {l: i for i, l in enumerate(order)}
    pairs = sorted(zip(hs, ls), key=lambda hl: rank.get(hl[1], len(rank)))
    h, l = target_handle(targets)
    return [p[0] for p in pairs] + [h], [p[1] for p in pairs] + [l]


def all_figure(g: dict, pts: list[dict], models: list[str]):
    """The full cloud of the static cantilever: every configuration's curve over its meshes."""
    fig, axes = _grid_of_panels(g, models)
    for i, m in enumerate(models):
        for j, law in enumerate(g["laws"]):
            ax = axes[i][j]
            _panel(ax, g, [p for p in pts if p["law"] == law and p["model"] == m])
            if j == 0:
                ax.set_ylabel("|u - u_ref| / |u_ref|")
    h, l = _with_targets(fig, g["accuracies"])
    hh, ll = hollow_legend(axes[0][0])
    legend_outside(fig, h + hh[-1:], l + ll[-1:], ncol=2, fontsize=6)
    return fig


def _figure(ctx, sec: Section, g: dict, pts: list[dict], models: list[str]) -> None:
    targets = ", ".join(f"{100 * a:g}" for a in g["accuracies"])
    sec.figure(ctx, lead_figure(g, pts, models), "accuracy_cost",
               "Work-precision of the static cantilever, each element's cheapest front: for each run (an element, "
               "rule and mesh) its settled error, the largest over it and every finer mesh of its configuration, "
               "against its median serial warm wall time, and of an element's runs those that no cheaper run of "
               "the element beats, as the staircase of the smallest error each time buys. Where the staircase "
               "first drops below a target (dotted: " + targets + " %) is the table's cheapest run. Coloured: the "
               "elements cheapest at a target (or within " + f"{TIE:g}" + " times its time) and the most accurate one; "
               "grey: the others; black: the continuum's own levels. Only stable, unwarned runs count. Every run "
               "and configuration: accuracy_cost_all.png and accuracy_cost_points.md.")
    sec.figure(ctx, all_figure(g, pts, models), "accuracy_cost_all",
               "Every run of the static cantilever: each line one ANCF element and quadrature over its meshes (4 to "
               "640 elements), black the continuum model's own refinement; lower left is better. Hollow markers: runs "
               "that converged to a singular or indefinite state, or carry a warning (verdict column of the points "
               "table). The ANCF curves level off at the beam model's distance from the continuum.")


def _cheapest_rows(g: dict, pts: list[dict], models: list[str]) -> list[list]:
    """Per law, formulation and accuracy: the cheapest settled ANCF run and continuum level."""
    rows = []
    for f, m in zip(g["formulations"], models):
        for law in g["laws"]:
            sel = [p for p in pts if p["law"] == law and p["model"] == m]
            for a in g["accuracies"]:
                best_a = cheapest(settled([p for p in sel if p["solver"] == "ancf"], a), a)
                best_c = cheapest(settled([p for p in sel if p["solver"] == "continuum"], a), a)
                rows.append([short(law), f, f"{100 * a:g} %",
                             f"{best_a['config']} x {best_a['mesh']}" if best_a else "none",
                             best_a["verdict"] if best_a else None,
                             best_a["time"] if best_a else None, pct(best_a["error"]) if best_a else None,
                             f"{best_c['mesh']} Q2" if best_c else "none",
                             best_c["time"] if best_c else None, pct(best_c["error"]) if best_c else None])
    return rows


def _points_table(ctx, sec: Section, pts: list[dict]) -> None:
    long = [[p["law"], p["model"], p["solver"], p["config"], p["mesh"], p["ndof"], p["status"], p["verdict"],
             p["time"], pct(p["error"])] for p in pts]
    t = Table("accuracy_cost_points", ["law", "model", "solver", "configuration", "mesh", "ndof", "status",
                                       "verdict", "time (s)", "error (%)"], long, {8: ".4f", 9: ".4f"})
    t.write(ctx.out)
    sec.items.append(("link", t.name + ".md", "Every point of the diagram."))


def _verdicts_prose(pts: list[dict]) -> str:
    ancf = [p for p in pts if p["solver"] == "ancf"]
    counts = {v: sum(1 for p in ancf if p["verdict"] == v) for v in dict.fromkeys(p["verdict"] for p in ancf)}
    text = (f"\nVerdicts of the {len(ancf)} static ANCF runs: "
            + ", ".join(f"{n} {v}" for v, n in sorted(counts.items(), key=lambda kv: -kv[1]))
            + "; only stable, unwarned runs count for the cheapest cells.")
    failed = [p for p in pts if p["status"] != "converged"]
    if failed:
        text += f"\n{len(failed)} of {len(pts)} static runs failed: " + "; ".join(
            f"{short(p['law'])} {p['model']} {p['config']} x {p['mesh']}" for p in failed)
    return text


def report(ctx) -> Section:
    g = ctx.study.grid
    pts = points(ctx)
    sec = Section(ctx.study.title,
                  "Error |u - u_ref| / |u_ref| of the static tip against the median wall time of serial warm runs "
                  "(build + solve), for every element, formulation, quadrature and mesh, and for the continuum "
                  "model's own refinement levels; u_ref is the converged continuum value of the matching model.")
    models = [MATCHING[f] for f in g["formulations"]]
    _figure(ctx, sec, g, pts, models)
    sec.table(ctx, Table("accuracy_cost", ["law", "formulation", "accuracy", "cheapest ANCF", "verdict", "time (s)",
                                           "error (%)", "cheapest continuum", "time (s)", "error (%)"],
                         _cheapest_rows(g, pts, models), {5: ".3f", 6: ".3f", 8: ".3f", 9: ".3f"}),
              f"For {_targets_text(g)} accuracy, the cheapest configuration (median serial warm wall time) of ANCF and of "
              "the continuum model that reaches it and stays within it on every finer mesh of the same configuration "
              "(a curve that crosses the target on its way to a plateau above it, or through zero error, does not "
              "count), counting only stable, unwarned runs whose finer meshes are stable and unwarned too; 'none' "
              "where no configuration of the grid does." + "".join(" " + t for t in absent(g)))
    _points_table(ctx, sec, pts)
    pendulum_part(ctx, sec)
    choose_element(ctx, sec, pts)
    sec.text += _verdicts_prose(pts)
    return sec


# runs within this factor of the cheapest one's time are named beside it: timings drift by
# 10 to 30 % between runs of one machine (the peers' rounds), so a closer order is not a ranking
TIE = 1.3


def choose_element(ctx, sec: Section, pts: list[dict]) -> None:
    """For each scene (the static cantilever per law and 2D assumption, the pendulum per
    formulation) and accuracy: the cheapest element and mesh (its settled run: it and every
    finer one within the accuracy), the other elements within :data:`TIE` of its time, the
    scene's L / h, and, from the grid's cables' card records (:func:`cable_slenderness`),
    the L / h down to which a cable stays within the accuracy (below it a shear-deformable
    section is needed; a cable refuses the formulations other than plane stress)."""
    g = ctx.study.grid
    rows = choose_rows(g, pts, all_pendulum_points(ctx), cable_slenderness(ctx))
    absent_text = "".join(" " + t for t in absent(g))
    sec.table(ctx, Table("choose_element", ["scene", "accuracy", "cheapest ANCF run", "time (s)", "error (%)",
                                            f"within {TIE:g} x its time", "scene L / h",
                                            "shear-deformable section needed below L / h (cable's card)"],
                         rows, {3: ".3g", 4: ".3f"}),
              "Which element to choose: for each scene and accuracy the cheapest ANCF run that reaches the accuracy "
              "and stays within it on every finer mesh (and, for the pendulum, every smaller step), with the other "
              f"elements whose cheapest such run is within {TIE:g} times its time (median serial warm wall time; "
              "timings drift by tens of percent between runs, so these are ties, not a ranking). Last column: the "
              "slenderness L / h below which a shear-deformable section is needed, the L / h down to which the cable "
              "(a centre line without shear or thickness change) stays within the accuracy of the converged continuum, "
              "from its card's slenderness sweep (the paper's "
              "cantilever under the paper's load parameter, the row's law; the card's interpolation between the "
              "two ratios around the crossing, '> x': within it down to the stoutest beam run, '< x': beyond it "
              "already at the most slender)." + absent_text
              + " The pendulum rows take Table 4's rungs and this study's own runs of the elements Table 4 does "
              "not run, on its ladder.")


def choose_rows(g: dict, pts: list[dict], pend: list[dict], sweeps: dict) -> list[list]:
    """The rows of :func:`choose_element` from the static points (:func:`points`), the
    pendulum points (:func:`all_pendulum_points`) and the cables' slenderness sweeps
    (:func:`cable_slenderness`): scene, accuracy, the cheapest settled run's name, time and
    error, the ties, the scene's L / h and the cables' L / h limits at that accuracy."""
    from ancf.checks import runs

    rows = []
    cables = sorted({el for el, _ in sweeps} | set(cable_elements(g["elements"])))

    def limit(law, formulation, acc) -> str:
        """The cables' cells: 'HC2n-8: 23.4' (the card's crossing), or why there is none."""
        from .card_cable import _crossing
        cells = []
        for el in cables:
            if not runs(el, formulation):
                cells.append(f"{el}: - (plane stress only)")
            elif (el, law) not in sweeps:
                cells.append(f"{el}: no card records")
            else:
                cells.append(f"{el}: {_crossing(sweeps[(el, law)], acc)}")
        return "; ".join(cells)

    def pick(label, acc, cands, lh, cable):
        best = {}
        for p in cands:            # each element's cheapest settled run
            el = p["element"]
            if el not in best or p["time"] < best[el]["time"]:
                best[el] = p
        order = sorted(best.values(), key=lambda p: p["time"])
        if not order:
            rows.append([label, f"{100 * acc:g} %", "none", None, None, "", lh, cable])
            return
        top = order[0]
        ties = [p for p in order[1:] if p["time"] <= TIE * top["time"]]
        rows.append([label, f"{100 * acc:g} %", top["name"], top["time"], pct(top["error"]),
                     ", ".join(f"{p['name']} ({p['time']:.3g} s)" for p in ties), lh, cable])

    def lh_of(sel) -> str:
        v = sorted({round(p["slenderness"], 6) for p in sel if p.get("slenderness")})
        return ", ".join(f"{x:g}" for x in v)

    for f in g["formulations"]:
        m = MATCHING[f]
        for law in g["laws"]:
            sel = [p for p in pts if p["solver"] == "ancf" and p["law"] == law and p["model"] == m]
            for a in g["accuracies"]:
                ok = [dict(p, name=f"{p['config']} x {p['mesh']}") for p in settled(sel, a) if p["time"]]
                pick(f"cantilever, {short(law)}, `{f}`", a, ok, lh_of(sel), limit(law, f, a))
    for f in dict.fromkeys(p["formulation"] for p in pend):
        sel = [p for p in pend if p["formulation"] == f]
        laws = sorted({p["law"] for p in sel})
        for a in g["accuracies"]:
            ok = [dict(p, name=f"{p['element']} x {p['n']}, dt {1e3 * p['dt']:g} ms")
                  for p in settled_steps(sel, a) if p["time"]]
            pick(f"pendulum, `{f}`", a, ok, lh_of(sel),
                 limit(laws[0], f, a) if len(laws) == 1 else "-")
    return rows


def cable_elements(elements) -> list[str]:
    """The centre-line cables among ``elements``."""
    from ancf.elements import get_element

    return [el for el in elements if get_element(el).cable]


def cable_slenderness(ctx) -> dict[tuple[str, str], list[tuple[float, float]]]:
    """{(cable, law): [(L / h, error)]} from the card records of the grid's cables
    (``<out>/data/card-<element>.jsonl``, their slenderness sweep, part 9 of the card, of its
    full grid or its CI grid, whichever has records): at
    each L / h the tip of the finest mesh against the converged continuum
    (tests/gold/fem_slenderness.json), as the card reads it. Empty where a cable has no
    card records (``python -m studies card <element>`` makes them)."""
    from .card_cases import cases as card_cases, slug
    from ..verification.slenderness_gold import GOLD, references

    refs = references(GOLD)
    out: dict = {}
    for el in cable_elements(ctx.study.grid["elements"]):
        tips: dict = {}
        # the card's full grid and its CI grid (a case of both is read once)
        sweep = {c.id: c for tiny in (False, True) for c in card_cases(el, tiny) if c.name.startswith("slenderness-")}
        for c in sweep.values():
            r = ctx.record_for(c, f"card-{slug(el)}")
            if r is None or r.get("status") != "converged" or not r.get("tip"):
                continue
            s = r["scene"]
            tips.setdefault((s["material"]["law"], round(_slenderness(s), 6)), {})[s["ancf"]["elements"]] = r["tip"]
        for (law, ratio), by_n in sorted(tips.items()):
            ref = refs.get((law, float(ratio)))
            if ref:
                out.setdefault((el, law), []).append((ratio, vec_error(by_n[max(by_n)], ref["tip"])))
    return out


def _pendulum_point(r: dict, cont: dict) -> dict:
    """A pendulum record as a point: its median serial warm wall time and its error max over
    t of |r - r_ref| / L against the converged continuum plane-stress pendulum."""
    from ..common.pendulum_cases import describe_dynamic, tip_errors

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
    from ..common.pendulum_cases import continuum_pendulum

    cont = continuum_pendulum()
    return [_pendulum_point(r, cont) for r in ctx.records("table4")]


def own_pendulum_points(ctx) -> list[dict]:
    """This study's own pendulum runs (the ``pendulum`` grid: the elements Table 4 does not
    run, on its ladder) as points, as :func:`pendulum_points`."""
    from ..common.pendulum_cases import continuum_pendulum

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


def _continuum_point(ax, cont) -> None:
    """The continuum gold's base run: its wall time and its own error estimate over L."""
    from ..common.pendulum_cases import LENGTH

    if cont and cont.wall_s and cont.error_estimate:
        ax.plot([cont.wall_s], [cont.error_estimate / LENGTH], "kD", ms=6,
                label="continuum (gold base run, own error estimate)")


def _pendulum_panels(pts: list[dict], laws: list[str]):
    forms = list(dict.fromkeys(p["formulation"] for p in pts))
    fig, axes = figure(1, len(forms), figsize=(4.6 * len(forms), 3.8), squeeze=False, sharex=True, sharey=True,
                       layout="constrained")
    for j, f in enumerate(forms):
        ax = axes[0][j]
        ax.set_xlabel("wall time, serial warm (s)")
        ax.set_title(f"pendulum ({', '.join(laws)}): ANCF `{f}` vs continuum plane stress", fontsize=8)
    return fig, axes[0], forms


def pendulum_lead_figure(g: dict, pts: list[dict], cont=None):
    """The lead work-precision figure of the pendulum (a matplotlib Figure): per formulation,
    each element's front of settled errors over its meshes and steps (:func:`fronts`,
    :func:`settled_steps`' rule), the leaders coloured (:func:`leaders`), the others grey, the
    continuum's own run, the targets dotted."""
    laws = sorted({p["law"] for p in pts})
    els = list(dict.fromkeys(p["element"] for p in pts))
    fig, axes, forms = _pendulum_panels(pts, laws)
    for ax, f in zip(axes, forms):
        sel = [p for p in pts if p["formulation"] == f]
        fr = fronts(with_settled(sel, pendulum_finer(sel)))
        draw_fronts(ax, fr, [el for el in els if el in leaders(fr, g["accuracies"], MAX_SERIES - 2)], els)
        _continuum_point(ax, cont)
        draw_targets(ax, g["accuracies"])
        _log_axes(ax)
    axes[0].set_ylabel("settled max over t of |r - r_ref| / L")
    legend_outside(fig, *_with_targets(fig, g["accuracies"], els))
    return fig


def pendulum_all_figure(g: dict, pts: list[dict], cont=None):
    """Every pendulum run: per formulation, a curve per element and count along the step
    ladder (the element's colour, a line style per count)."""
    laws = sorted({p["law"] for p in pts})
    els = list(dict.fromkeys(p["element"] for p in pts))
    counts = sorted({p["n"] for p in pts})
    fig, axes, forms = _pendulum_panels(pts, laws)
    for ax, f in zip(axes, forms):
        for el in els:
            for n in counts:
                ser = sorted([p for p in pts if (p["formulation"], p["element"], p["n"]) == (f, el, n)
                              and p["error"] is not None and p["time"]], key=lambda p: -p["dt"])
                if ser:
                    draw(ax, [p["time"] for p in ser], [max(p["error"], 1e-7) for p in ser],
                         [p["verdict"] for p in ser], f"{el} x {n}", marker=marker(el, els), lw=0.8, ms=3,
                         color=element_color(el), ls=("-", "--", ":", "-.")[counts.index(n) % 4])
        _continuum_point(ax, cont)
        draw_targets(ax, g["accuracies"])
        _log_axes(ax)
    axes[0].set_ylabel("max over t of |r - r_ref| / L")
    h, l = _with_targets(fig, g["accuracies"])
    hh, ll = hollow_legend(axes[0])
    legend_outside(fig, h + hh[-1:], l + ll[-1:], ncol=3, fontsize=6)
    return fig


def pendulum_part(ctx, sec: Section) -> None:
    from ..common.pendulum_cases import continuum_pendulum

    pts = all_pendulum_points(ctx)
    if not pts:
        return
    g = ctx.study.grid
    laws = sorted({p["law"] for p in pts})
    law = laws[0] if len(laws) == 1 else None
    cont = continuum_pendulum().get((law, "plane-stress"))
    forms = list(dict.fromkeys(p["formulation"] for p in pts))
    targets = ", ".join(f"{100 * a:g}" for a in g["accuracies"])
    sec.figure(ctx, pendulum_lead_figure(g, pts, cont), "accuracy_cost_pendulum",
               "Work-precision of the pendulum, each element's cheapest front: for each run (an element, count and "
               "step of Table 4's ladder) its settled error, the largest over it and every run with at least as "
               "many elements and at most its step, against its median serial warm wall time, and of an element's "
               "runs those that no cheaper run of the element beats, as a staircase. Where it first drops below a "
               "target (dotted: " + targets + " %) is the table's cheapest run. Coloured: the elements cheapest at "
               f"a target (or within {TIE:g} times its time) and the most accurate one; grey: the others; the black "
               "diamond is the continuum's own run (one run's wall time, its error estimate). Every run: "
               "accuracy_cost_pendulum_all.png.")
    sec.figure(ctx, pendulum_all_figure(g, pts, cont), "accuracy_cost_pendulum_all",
               "Every pendulum run: each line one element and count along the step ladder of Table 4 (8 ms "
               "halving; larger dt to the left; Table 4's elements and this study's own runs of the others), error "
               "against the converged continuum plane-stress pendulum; the black diamond is the continuum's own "
               "run (one run's wall time, its error estimate).")
    rows = []
    for f in forms:
        for a in g["accuracies"]:
            ok = [p for p in settled_steps([p for p in pts if p["formulation"] == f], a) if p["time"]]
            best = min(ok, key=lambda p: p["time"]) if ok else None
            rows.append([f, f"{100 * a:g} %", f"{best['element']} x {best['n']}, dt {1e3 * best['dt']:g} ms"
                         if best else "none", best["time"] if best else None, pct(best["error"]) if best else None,
                         cont.wall_s if cont else None, pct(cont.error_estimate / LENGTH) if cont and cont.error_estimate
                         else None])
    searched = "; ".join(f"`{f}`: " + ", ".join(dict.fromkeys(p["element"] for p in pts if p["formulation"] == f))
                         for f in forms)
    sec.table(ctx, Table("accuracy_cost_pendulum", ["ANCF formulation", "accuracy", "cheapest ANCF", "time (s)",
                                                    "error (%)", "continuum run (s)", "continuum error estimate (%)"],
                         rows, {3: ".3f", 4: ".3f", 5: ".1f", 6: ".4f"}),
              f"For {_targets_text(g)} pendulum accuracy (max over t of |r - r_ref| / L), the cheapest ANCF run of the "
              "Table 4 ladder (median serial warm wall time of a whole run) whose every finer run (more elements, "
              "smaller step, same element) converged and stays within the accuracy, beside the wall time of the "
              "continuum gold's base run (DOLFINx, one run inside the generator's 2-process pool, not warm, timed when "
              "the gold was generated, on that day's machine: a scale, not a ratio to this run's times) and its own "
              f"error estimate. The elements searched (Table 4's rungs and this study's own runs): {searched}.")
    peer_comparison(ctx, sec, pts)


# the peer report's records (studies.peers.work_precision), read where they are beside this study's
PEER_RECORDS = ("peers", "peers-work-precision.jsonl")


def two_way_finer(sel: list[dict]):
    """The peer report's refinement (:func:`studies.peers.precision_rules.finer`): the same
    element, its mesh at every step no larger, or its step on every mesh at least as fine."""
    return lambda p: [q for q in sel if q["element"] == p["element"]
                      and ((q["n"] == p["n"] and q["dt"] <= p["dt"]) or (q["dt"] == p["dt"] and q["n"] >= p["n"]))]


def quadrant_finer(sel: list[dict]):
    """This study's refinement (:func:`settled_steps`): the same element, at least as many
    elements and at most the step."""
    return lambda p: [q for q in sel if q["element"] == p["element"] and q["n"] >= p["n"] and q["dt"] <= p["dt"]]


def cheapest_under(sel: list[dict], finer, a: float) -> dict | None:
    """The fastest point of ``sel`` whose every refinement (``finer``, its own among them) is
    good and within ``a``."""
    ok = [p for p in with_settled(sel, finer) if p["settled"] is not None and p["settled"] <= a]
    return min(ok, key=lambda p: p["time"]) if ok else None


def peer_points(ctx) -> list[dict]:
    """The peer report's runs of ours on its `pendulum` scene (the paper's pendulum) as
    points (element label with its setting, n, dt, solve time, error); [] without its records."""
    from ..peers.precision_grid import SCENE
    from ..peers.records import read

    recs = read(ctx.out / "data" / PEER_RECORDS[0] / PEER_RECORDS[1])
    return [{"element": r["element"], "n": r["elements"], "dt": r["dt"], "time": r["time_s"], "error": r["error"],
             "verdict": "converged" if r["error"] is not None else "failed", "law": r.get("law"),
             "rho_inf": r.get("rho_inf"), "height": r.get("height"), "guard": r.get("energy_guard")}
            for r in recs if r["solver"] == "ancf" and r.get("scene", SCENE) == SCENE]


def peer_comparison(ctx, sec: Section, pts: list[dict]) -> None:
    """The pendulum's cheapest runs beside the peer report's on the same scene, each grid under
    each rule, and why they differ, from the two sets of records."""
    from ..peers.precision_grid import our_element

    peer = peer_points(ctx)
    ours = [p for p in pts if p["formulation"] == "plane-stress"]
    if not (peer and ours):
        return
    g = ctx.study.grid
    defaults = [p for p in peer if our_element(p["element"])[0] == p["element"]]

    def cell(p):
        return f"{p['element']} x {p['n']}, dt {1e3 * p['dt']:g} ms ({p['time']:.3g} s, {100 * p['error']:.3f} %)" \
            if p else "none"

    picks = {a: [cheapest_under(ours, quadrant_finer(ours), a), cheapest_under(ours, two_way_finer(ours), a),
                 cheapest_under(defaults, quadrant_finer(defaults), a), cheapest_under(defaults, two_way_finer(defaults), a),
                 cheapest_under(peer, two_way_finer(peer), a)] for a in g["accuracies"]}
    rows = [[f"{100 * a:g} %", *map(cell, ps)] for a, ps in picks.items()]
    # element (without its setting) and mesh of each cell: where the five agree on them
    agree = [a for a, ps in picks.items()
             if all(ps) and len({(our_element(p["element"])[0], p["n"]) for p in ps}) == 1]
    verdict = ("At every accuracy the five cells name the same element and mesh"
               if len(agree) == len(picks) else
               "The five cells name the same element and mesh at " + (", ".join(f"{100 * a:g} %" for a in agree)
                                                                       or "no accuracy"))

    def ladder(sel):
        return ", ".join(f"{1e3 * d:g}" for d in sorted({p["dt"] for p in sel}, reverse=True)) + " ms"

    def counts(sel):
        ns = sorted({p["n"] for p in sel})
        return f"{ns[0]} to {ns[-1]}"

    shared = sorted({p["dt"] for p in ours} & {p["dt"] for p in peer}, reverse=True)
    same = ({(p["law"], p["rho_inf"]) for p in peer} == {(p["law"], p["rho_inf"]) for p in ours}
            and {p["height"] for p in peer} == {round(LENGTH / p["slenderness"], 9) for p in ours})
    settings = sorted({p["element"][len(our_element(p["element"])[0]):].strip() for p in peer} - {""})
    sec.table(ctx, Table("accuracy_cost_pendulum_peers",
                         ["accuracy", "this study: its grid, its rule", "its grid, the peer report's rule",
                          "peer report's grid at our defaults, this study's rule", "the same, the peer report's rule",
                          "peer report: every setting, its rule (its table)"], rows, {}),
              "The plane-stress pendulum's cheapest run here beside the peer report's (peers_work_precision.md, scene "
              "`pendulum`), each grid under each refinement rule (time in parentheses: each grid's own measure, "
              "error: the run's own). " + verdict + ". The scenes are " + ("the same (the paper's pendulum, Yeoh, plane stress, "
              "rho_inf 0.5, h = 5 mm, against the same continuum gold)" if same else "NOT the same in these records")
              + "; what differs, from the two sets of records: the step ladder (this study's, Table 4's: "
              + ladder(ours) + "; the peer report's: " + ladder(peer) + "; "
              + ("no step in common" if not shared else "in common: " + ", ".join(f"{1e3 * d:g}" for d in shared) + " ms")
              + ") and the meshes (" + counts(ours) + " against " + counts(peer) + " elements), so that where the two "
              "agree on element and mesh they can still name different steps; the time (here the median serial warm wall "
              "time of a whole run, build and solve; there the solve's, the median of its timed runs); the Newton "
              "settings (here each element's defaults; the peer report also takes " + ", ".join(settings)
              + ", last column against the one before); the refinement rule (here every run with at least as many "
              "elements and at most the step must stay within the accuracy; there every finer step of the same mesh "
              "and every finer mesh at the same step: second column against the first, fourth against the third); "
              "and the energy guard (here each scene's; there none on either side, "
              + ", ".join(sorted({str(p["guard"]) for p in peer})) + " in its records).")


def _targets_text(g: dict) -> str:
    """'1 %, 0.3 % and 0.1 %': the grid's accuracies."""
    t = [f"{100 * a:g} %" for a in g["accuracies"]]
    return t[0] if len(t) == 1 else ", ".join(t[:-1]) + " and " + t[-1]


def audit(ctx) -> list[str]:
    """A referee's recheck from the written CSVs alone: every 'cheapest ANCF' cell of
    accuracy_cost.csv is a stable point of accuracy_cost_points.csv within the accuracy,
    and so is every finer mesh of its configuration (no cell rests on cancellation)."""
    import csv

    out = []
    cells, pts = ctx.out / "accuracy_cost.csv", ctx.out / "accuracy_cost_points.csv"
    if not (cells.exists() and pts.exists()):
        return out
    points = list(csv.DictReader(open(pts)))
    for i, row in enumerate(csv.DictReader(open(cells)), start=2):
        if row["cheapest ANCF"] == "none":
            continue
        config, mesh = row["cheapest ANCF"].rsplit(" x ", 1)
        a = float(row["accuracy"].rstrip(" %"))
        model = MATCHING[row["formulation"]]
        law = next((p["law"] for p in points if short(p["law"]) == row["law"]), row["law"])
        same = [p for p in points if p["solver"] == "ancf" and p["law"] == law and p["model"] == model
                and p["configuration"] == config]
        me = [p for p in same if p["mesh"] == mesh]
        if not me:
            out.append(f"accuracy_cost.csv:{i}: {row['cheapest ANCF']} is not a point of accuracy_cost_points.csv")
            continue
        finer = [p for p in same if int(p["ndof"] or 0) >= int(me[0]["ndof"] or 0)]
        bad = [p for p in finer if p["verdict"] not in GOOD or not p["error (%)"] or float(p["error (%)"]) > a]
        if bad:
            out.append(f"accuracy_cost.csv:{i}: cheapest at {row['accuracy']} {row['cheapest ANCF']} rests on "
                       f"{', '.join(p['mesh'] + ' (' + p['verdict'] + ', ' + (p['error (%)'] or '-') + ' %)' for p in bad)}")
    return out
