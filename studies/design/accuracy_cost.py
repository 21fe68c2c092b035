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
uniaxial with free faces), and the tables say so (:func:`studies.design.choose_element.absent`). The choose-an-element
table adds, from the cable's card records (its slenderness sweep), the L / h below which the
cable stops being within each accuracy of the continuum: below it a shear-deformable section
is needed (:func:`studies.design.choose_element.cable_slenderness`).

This module declares the study, its cases, its report and its audit; the points and the
rules that say which of them count are :mod:`studies.design.accuracy_cost_points`', the
figures :mod:`studies.design.accuracy_cost_figures`', the choose-an-element table
:mod:`studies.design.choose_element`'s and the comparison with the peer report's pendulum
:mod:`studies.design.accuracy_cost_peers`'.
"""
from __future__ import annotations

from ancf.checks.element import runs

from .accuracy_cost_figures import all_figure, lead_figure, pendulum_all_figure, pendulum_lead_figure
from .accuracy_cost_peers import peer_comparison
from .accuracy_cost_points import TIE, all_pendulum_points, cheapest, points, settled, settled_steps
from .choose_element import absent, choose_element
from ..common.gold import MATCHING, short
from ..common.grid import cantilever_case, counts_of, takes
from ..common.pendulum_cases import LENGTH, continuum_pendulum, ladder, pendulum_case
from ..engine.case import make_case
from ..engine.catalog import registered
from ..engine.report import GOOD, Section, Table, pct
from ..paper.table4 import STUDY as TABLE4
from ..verification.continuum import scene as continuum_scene


STUDY = {
    "name": "accuracy-cost",
    "title": "Accuracy against cost (static cantilever and pendulum)",
    # the pendulum half reads Table 4's timed step ladder (no cases of its own)
    "needs": ["continuum", "table4"],
    "grid": {
        "laws": ["neo-hookean", "mooney-rivlin", "yeoh"],
        # HC2n-8, the hyperelastic cable, runs plane stress alone (its plane-strain cells are absent, studies.design.choose_element.absent)
        "elements": {"registered": {}},
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


def cases(grid: dict, tiny: bool, study: str = "accuracy-cost") -> list:
    """The static cantilever of every law, formulation, element (where it runs the
    formulation: :func:`studies.design.choose_element.absent`), rule and mesh; the continuum's levels; the ``pendulum``
    grid's runs on Table 4's step ladder (where the grid has one)."""
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
    pd = grid.get("pendulum") or {}
    if "elements" in pd:
        return list(pd["elements"])
    table4 = registered(TABLE4["grid"]["elements"], "table4.elements")
    return [el for el in grid["elements"] if el not in table4]


def pendulum_formulations(grid: dict) -> list[str]:
    """The ``pendulum`` grid's formulations: its own where it names them, else Table 4's."""
    return list((grid.get("pendulum") or {}).get("formulations") or TABLE4["grid"]["formulations"])


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


def pendulum_part(ctx, sec: Section) -> None:
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
