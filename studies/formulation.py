"""The formulation question, static half of study 7: for each law, the `paper`,
`plane-strain` and `plane-stress` ANCF formulations against each continuum model, and
which 2D assumption the paper's ABAQUS column matches, stated from the numbers.

ANCF values are the finest mesh of each element and setting (the change from the
previous mesh is reported, to show they are converged); distances are
|u_a - u_b| / |u_b| over (ux, uy).
"""
from __future__ import annotations

import math

from .grid import cantilever_case
from .reference import LAW_SHORT, MATCHING, VARIANT_LABEL, abaqus, continuum_references, describe
from .report import Section, Table, mm, pct, vec_error

VARIANTS = ("plane-strain", "plane-strain-penalty", "plane-stress")


def configurations(grid: dict) -> list[tuple[str, tuple[int, int], str]]:
    return [(f, tuple(q), c) for f, q, c in grid["configurations"]]


def cases(grid: dict, tiny: bool) -> list:
    return [cantilever_case("formulation", law, f, el, n, q, c)
            for law in grid["laws"] for f, q, c in configurations(grid)
            for el in grid["elements"] for n in grid["counts"]]


def candidates(ctx) -> dict[str, list[tuple[str, tuple[float, float], float | None]]]:
    """{law: [(label, tip (m), change from the previous mesh (fraction) or None)]}:
    the continuum models, then every ANCF element x configuration at its finest mesh."""
    g = ctx.study.grid
    refs = continuum_references(ctx.records("continuum"))
    recs = [describe(r) for r in ctx.records()]
    out = {}
    for law in g["laws"]:
        lst = [(f"continuum {VARIANT_LABEL[v]}", refs[(law, v)].tip, None)
               for v in VARIANTS if (law, v) in refs and refs[(law, v)].tip]
        for f, q, c in configurations(g):
            for el in g["elements"]:
                ser = sorted([d for d in recs if (d["law"], d["formulation"], d["quadrature"], d["clamp"],
                                                  d["element"]) == (law, f, q, c, el)
                              and d["status"] == "converged"], key=lambda d: d["elements"])
                if not ser:
                    continue
                tip = (ser[-1]["tip"]["ux"], ser[-1]["tip"]["uy"])
                change = vec_error(ser[-2]["tip"], tip) if len(ser) > 1 else None
                lst.append((f"ANCF `{f}` q{q[0]}{q[1]} {c}, {el} x {ser[-1]['elements']}", tip, change))
        out[law] = lst
    return out


def report(ctx) -> Section:
    g = ctx.study.grid
    refs = continuum_references(ctx.records("continuum"))
    cands = candidates(ctx)
    sec = Section(ctx.study.title,
                  "Each ANCF formulation (finest mesh) and each continuum model against the others and against the "
                  "paper's ABAQUS column: distances |u_a - u_b| / |u_b| over (ux, uy).")
    hdr = ["law", "model", "ux (mm)", "uy (mm)", "mesh change (%)"] + \
          [f"vs continuum {v} (%)" for v in VARIANTS] + ["vs ABAQUS (%)"]
    rows = []
    for law in g["laws"]:
        ab = abaqus(law)
        for label, tip, change in cands[law]:
            t = {"ux": tip[0], "uy": tip[1]}
            rows.append([LAW_SHORT[law], label, mm(tip[0]), mm(tip[1]), pct(change)]
                        + [pct(vec_error(t, refs[(law, v)].tip)) if (law, v) in refs and refs[(law, v)].tip else None
                           for v in VARIANTS] + [pct(vec_error(t, ab))])
    sec.table(ctx, Table("formulation", hdr, rows, {2: ".2f", 3: ".2f", 4: ".3f", 5: ".2f", 6: ".2f", 7: ".2f", 8: ".2f"}),
              "Every model of the static cantilever against the three continuum models and ABAQUS; 'mesh change' is the "
              "ANCF tip's change from the previous mesh (how converged the ANCF value is).")
    rows, lines = [], []
    for law in g["laws"]:
        ab = abaqus(law)
        if not ab or not cands[law]:
            continue
        ranked = sorted(((vec_error({"ux": tip[0], "uy": tip[1]}, ab), label) for label, tip, _ in cands[law]),
                        key=lambda p: p[0])
        comp = {lbl: tip for lbl, tip, _ in cands[law]}
        best_d, best = ranked[0]
        rows.append([LAW_SHORT[law], best, pct(best_d), ranked[1][1] if len(ranked) > 1 else None,
                     pct(ranked[1][0]) if len(ranked) > 1 else None,
                     pct((comp[best][0] - ab[0]) / abs(ab[0])), pct((comp[best][1] - ab[1]) / abs(ab[1]))])
        lines.append(f"- {law}: ABAQUS ({mm(ab[0]):.2f}, {mm(ab[1]):.2f}) mm is closest to {best} "
                     f"({100 * best_d:.2f} %); next {ranked[1][1]} ({100 * ranked[1][0]:.2f} %)." if len(ranked) > 1
                     else f"- {law}: closest to {best} ({100 * best_d:.2f} %).")
    sec.table(ctx, Table("formulation_abaqus", ["law", "closest to ABAQUS", "distance (%)", "next closest",
                                                "distance (%)", "ux dev. (%)", "uy dev. (%)"], rows,
                         {2: ".2f", 4: ".2f", 5: "+.2f", 6: "+.2f"}),
              "Which model the paper's ABAQUS column matches: the closest and the next closest of all models above, "
              "with the componentwise deviation (closest - ABAQUS) / |ABAQUS|.")
    sec.text = "\n".join(lines + _verdict(cands, g["laws"]))
    return sec


def _verdict(cands, laws) -> list[str]:
    """Plane strain or plane stress, per law, from which family is closer to ABAQUS."""
    out = []
    votes = {}
    for law in laws:
        ab = abaqus(law)
        if not ab:
            continue
        fam = {}
        for label, tip, _ in cands[law]:
            if not label.startswith("continuum"):
                continue
            key = "plane stress" if "plane stress" in label else "plane strain"
            d = vec_error({"ux": tip[0], "uy": tip[1]}, ab)
            fam[key] = min(fam.get(key, math.inf), d)
        if len(fam) == 2:
            w = min(fam, key=fam.get)
            votes[law] = (w, fam)
    if votes:
        winners = {w for w, _ in votes.values()}
        detail = "; ".join(f"{LAW_SHORT[l]}: plane stress {100 * f['plane stress']:.2f} % vs plane strain "
                           f"{100 * f['plane strain']:.2f} %" for l, (w, f) in votes.items())
        if len(winners) == 1:
            out.append(f"- Verdict: the ABAQUS column matches the continuum **{winners.pop()}** model for every "
                       f"law ({detail}).")
        else:
            out.append(f"- Verdict: mixed ({detail}).")
    return out


def gold_values(ctx) -> dict:
    out = {}
    for r in ctx.records():
        d = describe(r)
        if d["status"] == "converged" and d["stable"] is not False:
            q = d["quadrature"]
            for comp in ("ux", "uy"):
                v = d["tip"][comp]
                out[f"formulation/{d['formulation']}/q{q[0]}{q[1]}/{d['clamp']}/{d['element']}/{d['elements']}/"
                    f"{LAW_SHORT[d['law']]}/{comp}"] = (v, 1e-6 * abs(v) + 1e-9)
    return out
