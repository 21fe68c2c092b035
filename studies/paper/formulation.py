"""The formulation question, static half of study 7: for each law, the `paper`,
`plane-strain` and `plane-stress` ANCF formulations against each continuum model, and
which 2D assumption the paper's ABAQUS column matches, stated from the numbers.

ANCF values are the finest mesh of each element and setting (the change from the
previous mesh is reported, to show they are converged); distances are
|u_a - u_b| / |u_b| over (ux, uy).
"""
from __future__ import annotations

import math

from ..common.grid import cantilever_case, counts_of, qlabel, rule, takes
from ..common.pendulum_cases import LENGTH, continuum_pendulum, describe_dynamic, gold_tips, pendulum_case, tip_errors
from ..common.gold import short, SOLID_LABEL, VARIANT_LABEL, abaqus, continuum_references, describe, solid_references
from ..engine.report import Section, Table, mm, pct, vec_error


STUDY = {
    "name": "formulation",
    "title": "Which 2D assumption? ANCF formulations against the continuum and ABAQUS",
    "needs": ["continuum"],
    "full": True,
    "grid": {
        "laws": ["neo-hookean", "mooney-rivlin", "yeoh"],
        # every element that runs the three formulations, but one that locks, and one not
        # converged on these meshes (a formulation's answer is compared here, not a mesh's)
        "elements": {"registered": {"without": ["locking"], "running": ["paper", "plane-strain", "plane-stress"],
                                    "except": {"HB2n-16": "its tip still moves 1.2 to 3.2 % from 160 to 320 "
                                                          "elements in the penalised formulations (volumetric "
                                                          "locking: its card; the paper runs it on 640)"}}},
        "counts": [160, 320],
        # [formulation, quadrature, clamp]
        "configurations": [["paper", [2, 2], "all"], ["paper", [3, 2], "face"], ["plane-strain", "default", "face"],
                           ["plane-stress", "default", "face"]],
        # (an element with a pressure field takes its own rule only: studies.common.grid.takes)
        # the pendulum half: each formulation's ANCF pendulum against the continuum pendulums
        # (tests/gold/fem_pendulum.json: plane stress, and plane strain exactly incompressible)
        "pendulum": {"elements": {"registered": {"without": ["locking"],
                                                 "running": ["paper", "plane-strain", "plane-stress"],
                                                 "except": {"HB3n-12": "on 32 elements its plane-stress pendulum "
                                                                       "is 8 to 9 mm off its own continuum model "
                                                                       "(NH, Yeoh; shear locking: its card)"}}},
                     "count": 32,
                     "dt": 0.0005,
                     "rho_inf": 0.5,
                     "t_end": 0.5,
                     "formulations": ["paper", "plane-strain", "plane-stress"]},
    },
    "tiny": {
        "laws": ["neo-hookean", "yeoh"],
        "elements": ["HB3n-12"],
        "counts": [8, 16],
        "pendulum": {"elements": ["HB2n-12"],
                     "count": 4,
                     "dt": 0.001,
                     "rho_inf": 0.5,
                     "t_end": 0.2,
                     "formulations": ["paper", "plane-strain", "plane-stress"]},
    },
}

VARIANTS = ("plane-strain", "plane-strain-penalty", "plane-stress")


def configurations(grid: dict) -> list[tuple[str, tuple[int, int], str]]:
    return [(f, rule(q), c) for f, q, c in grid["configurations"]]


def cases(grid: dict, tiny: bool) -> list:
    out = [cantilever_case("formulation", law, f, el, n, q, c)
           for law in grid["laws"] for f, q, c in configurations(grid)
           for el in grid["elements"] if takes(grid, el, q) for n in counts_of(grid, el)]
    p = grid.get("pendulum")
    if p:
        out += [pendulum_case("formulation", el, p["count"], f, p["dt"], rho_inf=p["rho_inf"], t_end=p["t_end"],
                              law=law)
                for law in grid["laws"] for f in p["formulations"] for el in p["elements"]]
    return out


def static_records(ctx) -> list[dict]:
    return [r for r in ctx.records() if r["scene"]["analysis"]["kind"] == "static"]


def pendulum_part(ctx, sec: Section) -> list[str]:
    """The dynamic half: each formulation's ANCF pendulum against both continuum pendulums."""
    p = ctx.study.grid.get("pendulum")
    if not p:
        return []
    cont = continuum_pendulum()
    models = ("plane-stress", "plane-strain")
    rows, lines = [], []
    descs = [describe_dynamic(r) for r in ctx.records() if r["scene"]["analysis"]["kind"] == "dynamic"]
    for law in ctx.study.grid["laws"]:
        for f in p["formulations"]:
            dists = {m: [] for m in models}
            for d in descs:
                if (d["law"], d["formulation"]) != (law, f):
                    continue
                errs = {m: tip_errors(d["tips"], cont[(law, m)].tips) if (d["ok"] and (law, m) in cont) else {}
                        for m in models}
                row = [short(law), f, d["element"], d["elements"], d["status"]]
                for m in models:
                    e = errs[m]
                    row += [1e3 * LENGTH * e[max(e)] if e else None, 1e3 * LENGTH * max(e.values()) if e else None]
                    if e:
                        dists[m].append(1e3 * LENGTH * max(e.values()))
                rows.append(row + [d["verdict"]])
            if all(dists[m] for m in models):
                near = min(models, key=lambda m: min(dists[m]))
                lines.append(f"- pendulum, {law}, ANCF `{f}`: closest to the continuum **{near}** pendulum (max tip "
                             f"distance of its best element {min(dists['plane-stress']):.2f} mm to plane stress, "
                             f"{min(dists['plane-strain']):.2f} mm to plane strain).")
    missing = sorted({f"{law}/{m}" for law in ctx.study.grid["laws"] for m in models if (law, m) not in cont})
    hdr = ["law", "ANCF formulation", "element", "n", "status"]
    for m in models:
        hdr += [f"vs continuum {m}: at t_end (mm)", f"vs continuum {m}: max over t (mm)"]
    hdr += ["verdict"]
    sec.table(ctx, Table("formulation_pendulum", hdr, rows, {i: ".2f" for i in range(5, 9)}),
              f"The pendulum ({p['t_end']:g} s, {p['count']} elements, dt {1e3 * p['dt']:g} ms, generalized-alpha "
              f"rho_inf {p['rho_inf']}): each ANCF formulation's tip against the converged continuum plane-stress and "
              "plane-strain (exactly incompressible) pendulums of tests/gold/fem_pendulum.json, at t_end and the "
              "maximum over t = 0.1 ... t_end." + (f" No converged continuum case for: {', '.join(missing)}." if missing
                                                   else ""))
    return lines


def candidates(ctx) -> dict[str, list[tuple[str, tuple[float, float], float | None]]]:
    """{law: [(label, tip (m), change from the previous mesh (fraction) or None)]}:
    the continuum models, then every ANCF element x configuration at its finest mesh."""
    g = ctx.study.grid
    refs = continuum_references(ctx.records("continuum"))
    recs = [describe(r) for r in static_records(ctx)]
    out = {}
    for law in g["laws"]:
        lst = [(f"continuum {VARIANT_LABEL[v]}", refs[(law, v)].tip, None)
               for v in VARIANTS if (law, v) in refs and refs[(law, v)].tip]
        solid = solid_references().get(law)
        if solid:
            lst.append((f"continuum {SOLID_LABEL}", solid, None))
        for f, q, c in configurations(g):
            for el in g["elements"]:
                ser = sorted([d for d in recs if (d["law"], d["formulation"], d["quadrature"], d["clamp"],
                                                  d["element"]) == (law, f, q, c, el)
                              and d["status"] == "converged"], key=lambda d: d["elements"])
                if not ser:
                    continue
                tip = (ser[-1]["tip"]["ux"], ser[-1]["tip"]["uy"])
                change = vec_error(ser[-2]["tip"], tip) if len(ser) > 1 else None
                lst.append((f"ANCF `{f}` {qlabel(q)} {c}, {el} x {ser[-1]['elements']}", tip, change))
        out[law] = lst
    return out


def report(ctx) -> Section:
    g = ctx.study.grid
    refs = continuum_references(ctx.records("continuum"))
    cands = candidates(ctx)
    sec = Section(ctx.study.title,
                  "Each ANCF formulation (finest mesh) and each continuum model against the others and against the "
                  "paper's ABAQUS column: distances |u_a - u_b| / |u_b| over (ux, uy).")
    solid = solid_references()
    hdr = ["law", "model", "ux (mm)", "uy (mm)", "mesh change (%)"] + \
          [f"vs continuum {v} (%)" for v in VARIANTS] + ["vs 3D beam (%)", "vs ABAQUS (%)"]
    rows = []
    for law in g["laws"]:
        ab = abaqus(law)
        for label, tip, change in cands[law]:
            t = {"ux": tip[0], "uy": tip[1]}
            rows.append([short(law), label, mm(tip[0]), mm(tip[1]), pct(change)]
                        + [pct(vec_error(t, refs[(law, v)].tip)) if (law, v) in refs and refs[(law, v)].tip else None
                           for v in VARIANTS]
                        + [pct(vec_error(t, solid[law])) if law in solid else None, pct(vec_error(t, ab))])
    sec.table(ctx, Table("formulation", hdr, rows, {2: ".2f", 3: ".2f", 4: ".3f", **{j: ".2f" for j in range(5, 10)}}),
              "Every model of the static cantilever against the three continuum models, the converged "
              f"{SOLID_LABEL} (exactly incompressible; tests/gold/fem_cantilever_3d.json) and ABAQUS; 'mesh change' "
              "is the ANCF tip's change from the previous mesh (how converged the ANCF value is).")
    rows, lines = [], []
    for law in g["laws"]:
        ab = abaqus(law)
        if not ab or not cands[law]:
            continue
        ranked = sorted(((vec_error({"ux": tip[0], "uy": tip[1]}, ab), label) for label, tip, _ in cands[law]),
                        key=lambda p: p[0])
        comp = {lbl: tip for lbl, tip, _ in cands[law]}
        best_d, best = ranked[0]
        rows.append([short(law), best, pct(best_d), ranked[1][1] if len(ranked) > 1 else None,
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
    sec.text = "\n".join(lines + _verdict(cands, g["laws"]) + pendulum_part(ctx, sec))
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
            if not label.startswith("continuum") or "plane" not in label:
                continue        # the vote is between the two 2D assumptions, not the 3D beam
            key = "plane stress" if "plane stress" in label else "plane strain"
            d = vec_error({"ux": tip[0], "uy": tip[1]}, ab)
            fam[key] = min(fam.get(key, math.inf), d)
        if len(fam) == 2:
            w = min(fam, key=fam.get)
            votes[law] = (w, fam)
    if votes:
        winners = {w for w, _ in votes.values()}
        detail = "; ".join(f"{short(l)}: plane stress {100 * f['plane stress']:.2f} % vs plane strain "
                           f"{100 * f['plane strain']:.2f} %" for l, (w, f) in votes.items())
        if len(winners) == 1:
            out.append(f"- Verdict: the ABAQUS column matches the continuum **{winners.pop()}** model for every "
                       f"law ({detail}).")
        else:
            out.append(f"- Verdict: mixed ({detail}).")
    return out


def gold_values(ctx) -> dict:
    out = {}
    for r in static_records(ctx):
        d = describe(r)
        if d["status"] == "converged" and d["stable"] is not False:
            q = d["quadrature"]
            for comp in ("ux", "uy"):
                v = d["tip"][comp]
                out[f"formulation/{d['formulation']}/{qlabel(q)}/{d['clamp']}/{d['element']}/{d['elements']}/"
                    f"{short(d['law'])}/{comp}"] = (v, 1e-6 * abs(v) + 1e-9)
    for r in ctx.records():
        if r["scene"]["analysis"]["kind"] == "dynamic":
            d = describe_dynamic(r)
            out.update(gold_tips(f"formulation/pendulum/{d['formulation']}/{d['element']}/{d['elements']}/"
                                 f"{short(d['law'])}", d))
    return out
