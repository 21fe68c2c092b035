"""The static hard-load sweep: the cantilever under a tip force up to 200 N and gravity up
to 1000 g, every law and element, ANCF and the continuum side by side.

What it shows: every run ends, converged or failed with a reason (each run carries a
``wall_time`` bound, so a run that would hang fails with "wall time" instead), and where
both models converge, how far apart they are; the 1 g row of each element is the
distance the formulation table reports at the paper's load, the baseline the hard loads
are read against. Both models use the same 2D assumption (``formulation``: ANCF's
consistent one against the continuum's).
"""
from __future__ import annotations

from contract import paper

from .engine.case import make_case
from .reference import short
from .engine.report import verdict
from .engine.report import Section, Table, mm, pct, vec_error

G = paper.GRAVITY


def loads(grid: dict) -> list[tuple[str, float, dict]]:
    """[(label, magnitude, the scene's [loads] table)]: gravity factors, then tip forces."""
    out = [(f"{k:g} g", k, {"gravity": [0.0, -G * k]}) for k in grid["gravity_factors"]]
    out += [(f"{f:g} N tip", f, {"tip_force": [0.0, -f]}) for f in grid["tip_forces"]]
    return out


def _scene(grid: dict, law: str, label: str, load: dict, element: str | None) -> dict:
    f = grid["formulation"]
    tag = label.replace(" ", "")
    if element is None:
        c = grid["continuum_cells"]
        fem = {"cells_length": int(c[0]), "cells_height": int(c[1]), "cell": "quadrilateral", "degree": 2,
               "quadrature_degree": 4}
        s = paper.cantilever_scene(law, f, fem=fem, name=f"hard-{law}-{f}-{tag}-fem{c[0]}x{c[1]}",
                                   wall_time=float(grid["wall_time"]))
    else:
        n = int(grid["count"])
        s = paper.cantilever_scene(law, f, element, n, name=f"hard-{law}-{f}-{tag}-{element}-{n}",
                                   wall_time=float(grid["wall_time"]))
    s["loads"] = load
    return s


def cases(grid: dict, tiny: bool) -> list:
    out = []
    for law in grid["laws"]:
        for label, _, load in loads(grid):
            out.append(make_case("hard-loads", "fenicsx", _scene(grid, law, label, load, None)))
            out += [make_case("hard-loads", "ancf", _scene(grid, law, label, load, el)) for el in grid["elements"]]
    return out


def _by_name(ctx) -> dict:
    return {r["scene"]["name"]: r for r in ctx.records()}


def rows_of(ctx) -> list[dict]:
    g = ctx.study.grid
    recs = _by_name(ctx)
    out = []
    for law in g["laws"]:
        for label, size, load in loads(g):
            cont = recs.get(_scene(g, law, label, load, None)["name"])
            ctip = (cont or {}).get("tip")
            ref = (ctip["ux"], ctip["uy"]) if ctip and cont["status"] == "converged" else None
            for el in g["elements"]:
                r = recs.get(_scene(g, law, label, load, el)["name"])
                if r is None:
                    continue
                ok = r["status"] == "converged"
                out.append({"law": law, "load": label, "size": size, "kind": next(iter(load)), "element": el,
                            "ancf": r, "continuum": cont,
                            "distance": vec_error(r.get("tip"), ref) if ok else None})
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
                  f"The cantilever, `{g['formulation']}` in both models, under gravity x {g['gravity_factors']} and a "
                  f"downward tip force of {g['tip_forces']} N; ANCF {g['count']} elements of each kind (default "
                  f"quadrature), the continuum {c[0]} x {c[1]} Q2 cells. Every run is bounded by wall_time = "
                  f"{g['wall_time']:g} s. Distance: |u_ANCF - u_continuum| / |u_continuum| over (ux, uy); the 1 g row "
                  "is the paper's load.")
    table = []
    for x in rows:
        a, cont = x["ancf"], x["continuum"]
        tip = a.get("tip") or {}
        ctip = (cont or {}).get("tip") or {}
        table.append([short(x["law"]), x["load"], x["element"], _status(a), verdict(a) if a.get("status") else None,
                      mm(tip.get("ux")), mm(tip.get("uy")), _status(cont), mm(ctip.get("ux")), mm(ctip.get("uy")),
                      pct(x["distance"]), a.get("load_steps"), a.get("rejected_steps"), a.get("wall_s")])
    sec.table(ctx, Table("hard_loads", ["law", "load", "element", "ANCF status", "verdict", "ANCF ux (mm)",
                                        "ANCF uy (mm)", "continuum status", "continuum ux (mm)", "continuum uy (mm)",
                                        "distance (%)", "increments", "cut", "ANCF wall s"], table,
                         {5: ".2f", 6: ".2f", 8: ".2f", 9: ".2f", 10: ".2f", 13: ".3f"}),
              "Every law x load x element: the status of both models (a failure with its reason), the tips, and "
              "their distance.")
    lines = []
    done = [x for x in rows if x["ancf"]["status"] in ("converged", "failed")]
    failed = [x for x in rows if x["ancf"]["status"] != "converged"]
    cfail = {(x["law"], x["load"]): x["continuum"] for x in rows
             if x["continuum"] is not None and x["continuum"]["status"] != "converged"}
    lines.append(f"- {len(done)} of {len(rows)} ANCF runs ended with a status ({len(rows) - len(failed)} converged, "
                 f"{len(failed)} failed with a reason); {len(cfail)} continuum run(s) failed.")
    lines += [f"- ANCF {x['law']} {x['element']} at {x['load']}: {_status(x['ancf'])}" for x in failed]
    lines += [f"- continuum {law} at {load}: {_status(r)}" for (law, load), r in sorted(cfail.items())]
    high = [x for x in rows if x["distance"] is not None and x["element"] not in g.get("low_order", [])]
    paper_load = [x for x in high if x["kind"] == "gravity" and x["size"] == 1.0]
    hard = [x for x in high if x not in paper_load]
    for label, group in (("at the paper's load (1 g)", paper_load), ("under the hard loads", hard)):
        if group:
            worst = max(group, key=lambda x: x["distance"])
            lines.append(f"- higher-order elements {label}, both models converged: largest distance "
                         f"{pct(worst['distance']):.2f} % ({worst['law']}, {worst['element']}, {worst['load']}).")
    sec.text = "\n".join(lines)
    return sec


def gold_values(ctx) -> dict:
    out = {}
    for x in rows_of(ctx):
        tip = x["ancf"].get("tip")
        if tip and x["ancf"]["status"] == "converged":
            key = f"hard-loads/{x['law']}/{x['element']}/{x['load'].replace(' ', '')}"
            for comp in ("ux", "uy"):
                out[f"{key}/{comp}"] = (tip[comp], 1e-6 * abs(tip[comp]) + 1e-9)
    return out
