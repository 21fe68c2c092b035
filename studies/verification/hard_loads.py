"""The static hard-load sweep: the cantilever under a tip force up to 200 N, gravity up to
1000 g and an end moment up to a full turn, every law, every built-in element, in plane
stress and in (penalised) plane strain, ANCF and the continuum side by side.

What it shows: every run ends, converged or failed with a reason (each run carries a
``wall_time`` bound, so a run that would hang fails with "wall time" instead), and where
both models converge, how far apart they are; the 1 g row of each element is the
distance the formulation table reports at the paper's load, the baseline the hard loads
are read against. Both models use the same 2D assumption (ANCF's plane stress against the
continuum's; ANCF's penalised plane strain against the continuum with the same penalty).
The end load is a uniform traction on the end face in both (:mod:`contract.loads`).

The continuum: one mesh here (``continuum_cells``); the study hard-loads-reference
(``make study-full``) adds the meshes a refinement needs (``reference_levels``, each
halving the cells), and where all its levels converged the reference is their Richardson
value (:func:`reference_fem.convergence.richardson`) with its error estimate, else this
study's own mesh, said so in the table.
"""
from __future__ import annotations

import math

from contract import paper

from ..engine.case import make_case
from ..common.gold import short
from ..engine.report import verdict
from ..engine.report import Section, Table, mm, pct, vec_error


STUDY = {
    "name": "hard-loads",
    "title": "Hard cases: static loads far beyond the paper's (tip force, gravity)",
    "grid": {
        # elements that lock (tagged so: the paper's LB2n-12): kept out of the findings about
        # the higher-order elements and out of the golden values, drawn dashed
        "low_order": {"registered": {"tagged": "locking"}},
        "laws": ["neo-hookean", "mooney-rivlin", "yeoh"],
        # every element that runs both formulations; a costly one (HB2n-60p: half of this
        # sweep's time, in plane strain) runs in hard-loads-reference
        "elements": {"registered": {"without": ["costly"], "running": ["plane-stress", "plane-strain"]}},
        "count": 32,
        "formulations": ["plane-stress", "plane-strain"],
        "gravity_factors": [1.0, 10.0, 100.0, 1000.0],  # x 9.81 m/s^2; 1 g is the paper's load
        "tip_forces": [1.0, 20.0, 200.0],  # N, downward at the free end
        "end_moment_turns": [0.25, 0.5, 1.0],  # x 2 pi E I / L, counter-clockwise (contract.loads)
        "continuum_cells": [64, 4],
        # the continuum's refinement (hard-loads-reference, make study-full): cells halving
        "reference_levels": [[32, 2], [64, 4], [128, 8]],
        "wall_time": 300.0,  # s per run: a run that would hang fails instead
    },
    "tiny": {
        "laws": ["yeoh"],
        "elements": ["HB2n-12"],
        "formulations": ["plane-stress"],
        "count": 8,
        "gravity_factors": [100.0],
        "tip_forces": [20.0],
        "continuum_cells": [16, 1],
        "reference_levels": [[16, 1]],
    },
}

G = paper.GRAVITY
REFERENCE = "hard-loads-reference"


def loads(grid: dict, law: str) -> list[tuple[str, float, dict]]:
    """[(label, magnitude, the scene's [loads] table)]: gravity factors, tip forces, then end
    moments given in turns: M = turns 2 pi E I / L (E = 3 mu, the law's small-strain
    modulus in plane stress), the couple that rolls the inextensible elastica up by that
    many turns (:mod:`contract.loads`: it stays a couple at any rotation)."""
    out = [(f"{k:g} g", k, {"gravity": [0.0, -G * k]}) for k in grid["gravity_factors"]]
    out += [(f"{f:g} N tip", f, {"tip_force": [0.0, -f]}) for f in grid["tip_forces"]]
    out += [(f"{n:g} turn", n, {"end_moment": moment(law, n)}) for n in grid.get("end_moment_turns", [])]
    return out


def moment(law: str, turns: float) -> float:
    """turns 2 pi E I / L (N m) on the paper's strip, E = 3 mu of the law's paper constants."""
    from mechanics.laws import get_law

    c = dict(paper.materials()[law])
    c.pop("density")
    b = paper.cantilever_scene(law, "plane-stress")["beam"]
    EI = 3.0 * get_law(law).shear_modulus(c) * b["width"] * b["height"] ** 3 / 12.0
    return turns * 2.0 * math.pi * EI / b["length"]


def _scene(grid: dict, law: str, form: str, label: str, load: dict, element: str | None,
           cells: list | None = None) -> dict:
    tag = label.replace(" ", "")
    if element is None:
        c = cells or grid["continuum_cells"]
        fem = {"cells_length": int(c[0]), "cells_height": int(c[1]), "cell": "quadrilateral", "degree": 2,
               "quadrature_degree": 4}
        if form == "plane-strain":
            fem["incompressibility"] = "penalty"      # the ANCF penalty (MATCHING: plane-strain-penalty)
        s = paper.cantilever_scene(law, form, fem=fem, name=f"hard-{law}-{form}-{tag}-fem{c[0]}x{c[1]}",
                                   wall_time=float(grid["wall_time"]))
    else:
        n = int(grid["count"])
        s = paper.cantilever_scene(law, form, element, n, quadrature=None,
                                   name=f"hard-{law}-{form}-{tag}-{element}-{n}", wall_time=float(grid["wall_time"]))
    s["loads"] = load
    return s


def _forms(grid: dict) -> list[str]:
    return list(grid["formulations"])


def cases(grid: dict, tiny: bool) -> list:
    out = []
    for form in _forms(grid):
        for law in grid["laws"]:
            for label, _, load in loads(grid, law):
                out.append(make_case("hard-loads", "continuum", _scene(grid, law, form, label, load, None)))
                out += [make_case("hard-loads", "ancf", _scene(grid, law, form, label, load, el))
                        for el in grid["elements"]]
    return out


def reference_cases(grid: dict, tiny: bool) -> list:
    """The continuum refinement of every (formulation, law, load): the meshes of
    ``reference_levels`` that hard-loads does not run itself; and the hard loads of the
    heavy elements (``elements``), run as hard-loads runs its own."""
    from ..engine.catalog import load_catalog

    out = [make_case(REFERENCE, "continuum", _scene(grid, law, form, label, load, None, cells))
           for form in _forms(grid) for law in grid["laws"] for label, _, load in loads(grid, law)
           for cells in grid["reference_levels"] if list(cells) != list(grid["continuum_cells"])]
    own = load_catalog(tiny=tiny)["hard-loads"].grid
    return out + [make_case(REFERENCE, "ancf", _scene(own, law, form, label, load, el))
                  for form in _forms(grid) for law in grid["laws"] for label, _, load in loads(grid, law)
                  for el in grid.get("elements", [])]


def _elements(ctx) -> list[str]:
    """hard-loads' elements, then the heavy ones hard-loads-reference runs."""
    heavy = ctx.catalog[REFERENCE].grid.get("elements", []) if REFERENCE in ctx.catalog else []
    return list(ctx.study.grid["elements"]) + [e for e in heavy if e not in ctx.study.grid["elements"]]


def _by_name(ctx) -> dict:
    return {r["scene"]["name"]: r for r in ctx.records() + ctx.records(REFERENCE)}


def inverted(rec: dict | None) -> bool:
    """Does the record's state hold an inverted cell (det F <= 0 between the quadrature points,
    :func:`reference_fem.simulation.run_scene`'s admissibility)?"""
    return bool(rec) and (rec.get("admissibility") or {}).get("det_F", 1.0) <= 0.0


def unstable(rec: dict | None) -> bool:
    return bool(rec) and (rec.get("unstable_directions") or 0) > 0


def continuum_reference(grid: dict, recs: dict, law: str, form: str, label: str, load: dict) -> dict:
    """{"tip": (ux, uy) or None, "error": its estimate (m) or None, "how": text, "record",
    "compare": "both" | "uy"}: the Richardson value of the refinement levels where all
    converged to a stable state and the order is trusted, else the study's own mesh.

    The levels stop short of resolving the clamp's compressed corner: under the large end
    loads its face wrinkles once the cells there resolve the mode (a surface instability of
    the law past its Biot stretch: an indefinite tangent, then only tangled or unstable
    states), so the refinement stops at ``reference_levels`` and follows the unbuckled branch
    a beam model is compared with. Where a level's corner cell is inverted between the
    quadrature points (the hanging strip's face behind the clamp plane: 200 N, 1000 g), ux
    is a clamp-corner quantity: the reference is said to hold for uy only (``compare``)."""
    from reference_fem.convergence import richardson

    own = recs.get(_scene(grid, law, form, label, load, None)["name"])
    levels = [recs.get(_scene(grid, law, form, label, load, None, c)["name"]) for c in grid["reference_levels"]]
    used = levels[-3:] if len(levels) >= 3 else [own]
    compare = "uy" if any(inverted(r) for r in used) else "both"
    note = "; a corner cell inverted: uy compared" if compare == "uy" else ""
    if len(levels) >= 3 and all(r and r["status"] == "converged" and not unstable(r) for r in levels):
        tips = [(r["tip"]["ux"], r["tip"]["uy"]) for r in levels[-3:]]
        rich = richardson(*tips)
        if rich.value is not None:
            c = grid["reference_levels"][-1]
            return {"tip": rich.value, "error": rich.error_estimate, "record": own, "compare": compare,
                    "how": f"Richardson of {' / '.join(f'{a}x{b}' for a, b in grid['reference_levels'][-3:])} "
                           f"(order {rich.order:.2f}), finest {c[0]}x{c[1]}{note}"}
    ok = own is not None and own["status"] == "converged" and not unstable(own)
    c = grid["continuum_cells"]
    return {"tip": (own["tip"]["ux"], own["tip"]["uy"]) if ok else None, "error": None, "record": own,
            "compare": compare, "how": f"{c[0]}x{c[1]} cells (no refinement recorded){note}"}


def distance(tip: dict | None, ref: dict) -> float | None:
    """|u - u_ref| / |u_ref| over (ux, uy), or |uy - uy_ref| / |uy_ref| where the reference
    holds for uy only."""
    if tip is None or ref["tip"] is None:
        return None
    if ref["compare"] == "uy":
        return abs(tip["uy"] - ref["tip"][1]) / abs(ref["tip"][1])
    return vec_error(tip, ref["tip"])


def error_bar(ref: dict) -> float | None:
    """The reference's own error estimate on the scale of :func:`distance` (over |u_ref|, or over
    |uy_ref| where the reference holds for uy only), None where it has none (one mesh)."""
    if ref["tip"] is None or ref["error"] is None:
        return None
    scale = abs(ref["tip"][1]) if ref["compare"] == "uy" else math.hypot(*ref["tip"])
    return ref["error"] / scale


UNRESOLVED = "below the reference's error bar: not resolved"


def resolution(d: float | None, bar: float | None) -> str:
    """How a distance stands against the reference's error bar: unresolved where the bar
    reaches it (the reference cannot tell it from 0), else how many bars it spans."""
    if d is None:
        return ""
    if bar is None:
        return "no error bar (one mesh)"
    return UNRESOLVED if d <= bar else f"{d / bar:.3g} x the bar"


def rows_of(ctx) -> list[dict]:
    g = ctx.study.grid
    recs = _by_name(ctx)
    out = []
    for form in _forms(g):
        for law in g["laws"]:
            for label, size, load in loads(g, law):
                ref = continuum_reference(g, recs, law, form, label, load)
                for el in _elements(ctx):
                    r = recs.get(_scene(g, law, form, label, load, el)["name"])
                    if r is None:
                        continue
                    ok = r["status"] == "converged"
                    out.append({"law": law, "formulation": form, "load": label, "size": size,
                                "kind": next(iter(load)), "element": el, "ancf": r, "continuum": ref["record"],
                                "reference": ref, "error_bar": error_bar(ref),
                                "distance": distance(r.get("tip"), ref) if ok else None})
    return out


def _status(r: dict | None) -> str:
    if r is None:
        return "no record"
    if r["status"] == "converged":
        return "converged"
    return "failed: " + str(r.get("reason") or "?").split(":")[0][:60]


def report(ctx) -> Section:
    g = ctx.study.grid
    rows = rows_of(ctx)
    c = g["continuum_cells"]
    sec = Section(ctx.study.title,
                  f"The cantilever in {' and '.join(f'`{f}`' for f in _forms(g))} (both models the same 2D "
                  f"assumption; plane strain with the paper's penalty in both), under gravity x {g['gravity_factors']} "
                  f"a downward end load of {g['tip_forces']} N (a uniform traction on the end face) and an end "
                  f"moment of {g.get('end_moment_turns', [])} turns (x 2 pi E I / L, E = 3 mu: a couple on the end "
                  "face's rotation, the same in both models); ANCF "
                  f"{g['count']} elements of each kind (default quadrature), the continuum {c[0]} x {c[1]} Q2 cells, and "
                  "its Richardson value where the refinement of hard-loads-reference is recorded. Every run is bounded "
                  f"by wall_time = {g['wall_time']:g} s. Distance: |u_ANCF - u_ref| / |u_ref| over (ux, uy), or over "
                  "uy alone where a level of the reference has its clamp corner cell inverted between the quadrature "
                  "points (ux is then a property of that corner, not of the beam); a level whose tangent has an "
                  "unstable direction is no reference. The refinement stops before the cells at the clamp resolve the "
                  "compressed face's wrinkling (a surface instability past the law's Biot stretch, which the large "
                  "end loads reach: finer meshes fail there), so the references follow the unbuckled branch a beam "
                  "model is compared with. The 1 g row is the paper's load.")
    table = []
    for x in rows:
        a, cont, ref = x["ancf"], x["continuum"], x["reference"]
        tip = a.get("tip") or {}
        rtip = ref["tip"] or (None, None)
        table.append([short(x["law"]), x["formulation"], x["load"], x["element"], _status(a),
                      verdict(a) if a.get("status") else None, mm(tip.get("ux")), mm(tip.get("uy")), _status(cont),
                      mm(rtip[0]), mm(rtip[1]), mm(ref["error"]), ref["how"], pct(x["distance"]),
                      pct(x["error_bar"]), resolution(x["distance"], x["error_bar"]), a.get("load_steps"),
                      a.get("rejected_steps"), a.get("wall_s")])
    sec.table(ctx, Table("hard_loads", ["law", "formulation", "load", "element", "ANCF status", "verdict",
                                        "ANCF ux (mm)", "ANCF uy (mm)", "continuum status", "reference ux (mm)",
                                        "reference uy (mm)", "reference error (mm)", "reference", "distance (%)",
                                        "reference error bar (%)", "distance against the bar", "increments", "cut",
                                        "ANCF wall s"], table,
                         {6: ".3f", 7: ".3f", 9: ".3f", 10: ".3f", 11: ".3f", 13: ".3f", 14: ".3f", 18: ".3f"}),
              "Every formulation x law x load x element: the status of both models (a failure with its reason), the "
              "tips, the continuum reference and its error estimate, and the distance, against the reference's "
              "error bar (its error estimate on the distance's scale): a distance within the bar is not resolved "
              "by the reference.")
    lines = []
    done = [x for x in rows if x["ancf"]["status"] in ("converged", "failed")]
    failed = [x for x in rows if x["ancf"]["status"] != "converged"]
    cfail = {(x["law"], x["formulation"], x["load"]): x["continuum"] for x in rows
             if x["continuum"] is not None and x["continuum"]["status"] != "converged"}
    lines.append(f"- {len(done)} of {len(rows)} ANCF runs ended with a status ({len(rows) - len(failed)} converged, "
                 f"{len(failed)} failed with a reason); {len(cfail)} continuum run(s) failed.")
    lines += [f"- ANCF {x['law']} {x['formulation']} {x['element']} at {x['load']}: {_status(x['ancf'])}"
              for x in failed]
    lines += [f"- continuum {law} {form} at {load}: {_status(r)}" for (law, form, load), r in sorted(cfail.items())]
    measured = [x for x in rows if x["distance"] is not None]
    unresolved = [x for x in measured if resolution(x["distance"], x["error_bar"]) == UNRESOLVED]
    if unresolved:
        where: dict = {}
        for x in unresolved:
            where.setdefault((x["law"], x["formulation"], x["load"]), []).append(x["element"])
        lines.append(f"- {len(unresolved)} of {len(measured)} distances are below the continuum reference's own error "
                     "bar, so the reference does not resolve them (they say only that ANCF is within that bar): "
                     + "; ".join(f"{law} {form} {load}: {', '.join(els)}" for (law, form, load), els in where.items())
                     + ".")
    high = [x for x in measured if x["element"] not in g.get("low_order", [])]
    for form in _forms(g):
        paper_load = [x for x in high if x["formulation"] == form and x["kind"] == "gravity" and x["size"] == 1.0]
        hard = [x for x in high if x["formulation"] == form and x not in paper_load]
        for label, group in (("at the paper's load (1 g)", paper_load), ("under the hard loads", hard)):
            if group:
                worst = max(group, key=lambda x: x["distance"])
                largest = {el: max((x for x in group if x["element"] == el), key=lambda x: x["distance"])
                           for el in dict.fromkeys(x["element"] for x in group)}
                lines.append(f"- {form}, higher-order elements {label}, both models converged: largest distance "
                             f"{_flagged(worst)} ({worst['law']}, {worst['element']}, {worst['load']}); "
                             "each element's largest: " + ", ".join(f"{el} {_flagged(x)}" for el, x in largest.items())
                             + ".")
    sec.text = "\n".join(lines)
    return sec


def _flagged(x: dict) -> str:
    """A row's distance in %, said to be unresolved where the reference's error bar reaches it."""
    unresolved = resolution(x["distance"], x["error_bar"]) == UNRESOLVED
    return f"{pct(x['distance']):.2f} %" + (" (below the reference's error bar)" if unresolved else "")


def gold_values(ctx) -> dict:
    out = {}
    for x in rows_of(ctx):
        tip = x["ancf"].get("tip")
        if tip and x["ancf"]["status"] == "converged":
            key = f"hard-loads/{x['law']}/{x['formulation']}/{x['element']}/{x['load'].replace(' ', '')}"
            for comp in ("ux", "uy"):
                out[f"{key}/{comp}"] = (tip[comp], 1e-6 * abs(tip[comp]) + 1e-9)
    return out
