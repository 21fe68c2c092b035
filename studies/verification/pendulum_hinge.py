"""The pendulum on a hinge: a continuum reference with a mesh limit and an error bar.

The paper's pendulum hangs on a point pin, which is singular in a 2D continuum: each halving
of the cells moves the tip by the same vector, so the continuum pendulum has no mesh limit,
only error bars (:mod:`contract.loads`). The ``hinge`` holds the face x = 0 straight through
its fixed centre, free to turn and to stretch, r(0, y) = y a, in both solvers (ANCF: r and the
y-kinds of order two or more fixed; the continuum: the face's displacements eliminated for
the two components of a). Here the continuum pendulum (DOLFINx, plane stress, the paper's
Yeoh law, the continuum gold's step and rho_inf) runs on both supports with the cells across
the height halving (``levels``), and:

- the hinge's tip histories converge: at each output time the last three levels give the
  observed order and the Richardson value (:func:`reference_fem.convergence.richardson`),
  whose error estimate is the spatial half of the reference's error bar; the temporal half
  is 4/3 |r(dt) - r(dt/2)| at one level (second order in time, as the continuum gold's);
- the pin's do not (the differences of successive levels, shown beside);
- the ANCF elements on the same hinge (their converged step, rho_inf 0.5) against that
  reference, with its error bar.
"""
from __future__ import annotations

import math

from contract import paper

from ..engine.case import make_case
from ..engine.report import Section, Table

STUDY = {
    "name": "pendulum-hinge",
    "title": "The pendulum on a hinge: a continuum reference that converges",
    "full": True,
    "grid": {"law": "yeoh", "formulation": "plane-stress", "levels": [2, 4, 8], "aspect": 2.0, "dt": 1e-3,
             "rho_inf": 0.8, "time_level": 4,
             "elements": {"registered": {"without": ["locking"], "running": ["plane-stress"]}}, "count": 32,
             "ancf_dt": 5e-4, "ancf_rho_inf": 0.5},
    "tiny": {"aspect": 4.0, "dt": 2e-3, "time_level": 2, "elements": ["HB2n-40p"], "count": 4, "ancf_dt": 2e-3,
             "t_end": 0.1},
}
SUPPORTS = ("hinge", "pin")


def _t_end(g: dict) -> float:
    return float(g.get("t_end", paper.PENDULUM_T_END))


def continuum_scene(g: dict, support: str, cells: int, dt: float | None = None) -> dict:
    dt = g["dt"] if dt is None else dt
    d = paper.pendulum_scene(g["law"], g["formulation"], dt, rho_inf=g["rho_inf"], t_end=_t_end(g),
                             fem={"cells_height": cells, "aspect": g["aspect"]},
                             name=f"pendulum-{support}-{g['law']}-{g['formulation']}-fem-h{cells}-dt{dt:g}")
    d["supports"] = {"left": support}
    return d


def ancf_scene(g: dict, element: str) -> dict:
    d = paper.pendulum_scene(g["law"], g["formulation"], g["ancf_dt"], element, g["count"], rho_inf=g["ancf_rho_inf"],
                             t_end=_t_end(g), name=f"pendulum-hinge-{g['law']}-{g['formulation']}-{element}-"
                                                   f"{g['count']}-dt{g['ancf_dt']:g}")
    d["supports"] = {"left": "hinge"}
    return d


def cases(grid: dict, tiny: bool) -> list:
    out = [make_case("pendulum-hinge", "continuum", continuum_scene(grid, s, c)) for s in SUPPORTS for c in grid["levels"]]
    out.append(make_case("pendulum-hinge", "continuum", continuum_scene(grid, "hinge", grid["time_level"], grid["dt"] / 2)))
    return out + [make_case("pendulum-hinge", "ancf", ancf_scene(grid, el)) for el in grid["elements"]]


def _tips(rec: dict | None) -> dict | None:
    """{t: (x, y)} of a converged record's tip history."""
    if rec is None or rec.get("status") != "converged":
        return None
    return {round(h["t"], 9): (h["x"], h["y"]) for h in rec.get("tip_history") or []}


def reference(ctx) -> dict:
    """{t: {"value": (x, y), "order": p, "space": e_h, "time": e_dt, "bar": e_h + e_dt}} of the
    hinge's continuum, and the pin's successive differences {t: [d_1, d_2, ...]}."""
    from reference_fem.convergence import richardson

    g = ctx.study.grid
    recs = {r["scene"]["name"]: r for r in ctx.records()}
    hinge = [_tips(recs.get(continuum_scene(g, "hinge", c)["name"])) for c in g["levels"]]
    pin = [_tips(recs.get(continuum_scene(g, "pin", c)["name"])) for c in g["levels"]]
    half = _tips(recs.get(continuum_scene(g, "hinge", g["time_level"], g["dt"] / 2)["name"]))
    base = hinge[g["levels"].index(g["time_level"])] if g["time_level"] in g["levels"] else None
    out = {"hinge": {}, "pin": {}}
    if all(h is not None for h in hinge[-3:]):
        for t in sorted(hinge[-1]):
            if t == 0.0:
                continue
            r = richardson(*(h[t] for h in hinge[-3:]))
            e_dt = 4.0 / 3.0 * math.dist(base[t], half[t]) if base and half else None
            out["hinge"][t] = {"value": r.value, "order": r.order, "space": r.error_estimate, "time": e_dt,
                               "bar": None if r.error_estimate is None or e_dt is None else r.error_estimate + e_dt,
                               "steps": [math.dist(a[t], b[t]) for a, b in zip(hinge, hinge[1:])]}
    if all(p is not None for p in pin):
        for t in sorted(pin[-1]):
            if t != 0.0:
                out["pin"][t] = [math.dist(a[t], b[t]) for a, b in zip(pin, pin[1:])]
    return out


def report(ctx) -> Section:
    g = ctx.study.grid
    ref = reference(ctx)
    levels = " / ".join(f"{int(round(paper.PENDULUM['length'] / paper.PENDULUM['height'] * c / g['aspect']))}x{c}"
                        for c in g["levels"])
    sec = Section(ctx.study.title,
                  f"The paper's pendulum ({g['law']}, `{g['formulation']}`), DOLFINx Q2 on {levels} cells, dt = "
                  f"{g['dt'] * 1e3:g} ms, rho_inf = {g['rho_inf']:g}, on the hinge (the face straight through its fixed "
                  "centre) and on the paper's point pin. The hinge's reference at each output time: the Richardson value "
                  "of the three levels; its bar: the spatial estimate plus the temporal one, 4/3 |r(dt) - r(dt/2)| "
                  f"on {g['time_level']} cells across.")
    rows = []
    for t, r in ref["hinge"].items():
        x, y = r["value"] if r["value"] else (None, None)
        rows.append([t, "hinge", *(s * 1e3 for s in r["steps"]), r["order"], None if x is None else x * 1e3,
                     None if y is None else y * 1e3, None if r["space"] is None else r["space"] * 1e3,
                     None if r["time"] is None else r["time"] * 1e3])
    for t, steps in ref["pin"].items():
        rows.append([t, "pin", *(s * 1e3 for s in steps), None, None, None, None, None])
    n = len(g["levels"]) - 1
    head = ["t (s)", "support", *(f"|r_{k + 1} - r_{k}| (mm)" for k in range(n)), "order", "reference x (mm)",
            "reference y (mm)", "space bar (mm)", "time bar (mm)"]
    fmt = {k: ".2e" for k in range(2, 2 + n)} | {2 + n: ".2f", 3 + n: ".4f", 4 + n: ".4f", 5 + n: ".1e", 6 + n: ".1e"}
    sec.table(ctx, Table("pendulum_hinge_levels", head, rows, fmt),
              "The tip's move at each halving of the cells: the hinge's falls at the element's order, the pin's does "
              "not (its point support is singular); the hinge's reference and its error bar.")
    recs = {r["scene"]["name"]: r for r in ctx.records()}
    arows = []
    for el in g["elements"]:
        tips = _tips(recs.get(ancf_scene(g, el)["name"]))
        if tips is None or not ref["hinge"]:
            arows.append([el, "failed" if tips is None else "no reference", None, None, None, None])
            continue
        dist = {t: math.dist(tips[t], r["value"]) for t, r in ref["hinge"].items() if r["value"] and t in tips}
        worst = max(dist, key=dist.get)
        bar = ref["hinge"][worst]["bar"]
        arows.append([el, "converged", worst, dist[worst] * 1e3, None if bar is None else bar * 1e3,
                      None if bar is None else ("yes" if dist[worst] <= bar else "no")])
    sec.table(ctx, Table("pendulum_hinge_ancf", ["element", "ANCF status", "worst t (s)", "distance (mm)",
                                                 "reference bar (mm)", "within the bar"], arows,
                         {3: ".4f", 4: ".1e"}),
              f"ANCF on the same hinge ({g['count']} elements, dt = {g['ancf_dt'] * 1e3:g} ms, rho_inf = "
              f"{g['ancf_rho_inf']:g}): the largest distance from the hinge's reference over the output times.")
    lines = []
    for t, r in ref["hinge"].items():
        if r["order"] is not None:
            lines.append(f"{t:g} s: order {r['order']:.2f}, bar {r['bar'] * 1e3:.2g} mm" if r["bar"] is not None
                         else f"{t:g} s: order {r['order']:.2f}")
    if lines:
        sec.text = "- the hinge's reference converges: " + "; ".join(lines) + "."
    if ref["pin"]:
        worst = max(ref["pin"], key=lambda t: ref["pin"][t][-1])
        sec.text += (f"\n- the pin's tip moves by {ref['pin'][worst][-1] * 1e3:.3g} mm at the last halving "
                     f"(t = {worst:g} s): no mesh limit.")
    return sec
