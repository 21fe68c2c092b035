"""The continuum reference as a study: each law x 2D variant on a refinement sequence
of Q2 quadrilateral meshes (reference_fem), and its Richardson value.

Its records are what the ANCF studies are judged by (:mod:`studies.common.gold`); the
report cross-checks the Richardson values against reference_fem's gold file.
"""
from __future__ import annotations

import math
from pathlib import Path

from contract import paper

from ..engine.case import make_case
from ..common.gold import short, VARIANT_LABEL, abaqus, continuum_references, gold_references
from ..engine.report import Section, Table, mm, pct


STUDY = {
    "name": "continuum",
    "title": "Continuum reference: refinement and Richardson values",
    "grid": {
        "laws": ["neo-hookean", "mooney-rivlin", "yeoh"],
        # gold-file names: plane strain exact (mixed), plane strain with the ANCF penalty, plane stress
        "variants": ["plane-strain", "plane-strain-penalty", "plane-stress"],
        # Q2 quadrilaterals, cells along x cells across; each level halves the cell size
        "levels": [[16, 1], [32, 2], [64, 4], [128, 8], [256, 16]],
    },
    "tiny": {
        "laws": ["neo-hookean", "yeoh"],
        "levels": [[8, 1], [16, 2], [32, 4]],
    },
}

GOLD = Path(__file__).resolve().parents[2] / "tests" / "gold" / "fem_cantilever.json"
MODELS = {"plane-strain": ("plane-strain", "mixed"), "plane-strain-penalty": ("plane-strain", "penalty"),
          "plane-stress": ("plane-stress", None)}


def scene(law: str, variant: str, cells: tuple[int, int]) -> dict:
    model, inc = MODELS[variant]
    fem = {"cells_length": int(cells[0]), "cells_height": int(cells[1]), "cell": "quadrilateral",
           "degree": 2, "quadrature_degree": 4}
    if inc:
        fem["incompressibility"] = inc
    return paper.cantilever_scene(law, model, fem=fem, load_steps=10,
                                  name=f"fem-cantilever-{law}-{variant}-{cells[0]}x{cells[1]}")


def cases(grid: dict, tiny: bool) -> list:
    return [make_case("continuum", "continuum", scene(law, v, tuple(lv)))
            for law in grid["laws"] for v in grid["variants"] for lv in grid["levels"]]


def report(ctx) -> Section:
    refs = continuum_references(ctx.records())
    gold = gold_references(GOLD) if GOLD.exists() else {}
    sec = Section(ctx.study.title,
                  "The paper's cantilever as a 2D continuum (reference_fem, DOLFINx, Q2 quadrilaterals), "
                  "refined uniformly; the reference value of each law and 2D model is the Richardson "
                  "extrapolation of the last three levels.")
    rows = []
    for (law, v), r in refs.items():
        g = gold.get((law, v))
        diff = math.hypot(r.tip[0] - g[0], r.tip[1] - g[1]) if r.tip and g else None
        ab = abaqus(law)
        rows.append([law, VARIANT_LABEL[v], f"{r.levels[-1]['cells'][0]} x {r.levels[-1]['cells'][1]}",
                     mm(r.tip[0]) if r.tip else None, mm(r.tip[1]) if r.tip else None,
                     mm(r.error_estimate), r.order, mm(diff),
                     pct(_dev(r.tip, ab, 0)), pct(_dev(r.tip, ab, 1))])
    sec.table(ctx, Table("continuum_reference",
                         ["law", "model", "finest mesh", "ux (mm)", "uy (mm)", "est. error (mm)", "order",
                          "vs gold file (mm)", "ux vs ABAQUS (%)", "uy vs ABAQUS (%)"], rows,
                         {3: ".3f", 4: ".3f", 5: ".1e", 6: ".2f", 7: ".1e", 8: "+.2f", 9: "+.2f"}),
              "Converged continuum tip per law and 2D model: the reference u_ref of every ANCF comparison. "
              "'vs gold file' is the distance to tests/gold/fem_cantilever.json (same solver, computed apart).")
    # error of each level against its Richardson value
    hdr = ["law", "model"] + [f"{c[0]} x {c[1]}" for c in (lv["cells"] for lv in next(iter(refs.values())).levels)] if refs else []
    rows = []
    for (law, v), r in refs.items():
        errs = []
        for lv in r.levels:
            e = None
            if r.tip and lv["tip"]:
                e = math.hypot(lv["tip"]["ux"] - r.tip[0], lv["tip"]["uy"] - r.tip[1]) / math.hypot(*r.tip)
            errs.append(pct(e))
        rows.append([law, VARIANT_LABEL[v], *errs])
    if rows:
        sec.table(ctx, Table("continuum_levels", hdr, rows, {j: ".4f" for j in range(2, len(hdr))}),
                  "Error (%) of each continuum level against its own Richardson value: how fast the "
                  "reference converges (not independent errors: the extrapolation uses the finest levels).")
    return sec


def _dev(tip, ref, i):
    if not tip or ref is None:
        return None
    return (tip[i] - ref[i]) / abs(ref[i])


def gold_values(ctx) -> dict:
    """Richardson tips (m); tolerance: Newton stops at 1e-8 of the load residual, so the
    tips reproduce to ~1e-7 relative; extrapolation amplifies level differences by
    1/(2^p - 1) < 1.5: 1e-6 relative + 1 nm."""
    out = {}
    for (law, v), r in continuum_references(ctx.records()).items():
        if r.tip:
            for i, comp in enumerate(("ux", "uy")):
                out[f"continuum/{short(law)}/{v}/{comp}"] = (r.tip[i], 1e-6 * abs(r.tip[i]) + 1e-9)
    return out
