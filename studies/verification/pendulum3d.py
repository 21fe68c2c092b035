"""The paper's pendulum as the real 3D beam (``make study-full``).

The flexible pendulum (350 x 5 x 7 mm, pinned, released horizontal under gravity) as a
3D solid (reference_fem ``model = "3d"``: Q2/Q1 hexahedra, exactly incompressible, the
pin a line across the width at the left face's mid-height), generalized-alpha at the
continuum gold's step, on a sequence of meshes. Its tip (centre of the free end face) at
the output times against:

- the converged 2D continuum pendulums of tests/gold/fem_pendulum.json (plane stress,
  plane strain exactly incompressible);
- the ANCF elements in plane stress at their finest mesh of the ``figure4`` study.

Distances are |r_a(t) - r_b(t)| in mm; "max over t" is over the output times after 0.
Not part of ``make study`` (a 3D pendulum level takes minutes): its cases run only when
named (``python -m studies run pendulum-3d``).
"""
from __future__ import annotations

import math

from contract import paper

from ..engine.case import make_case
from ..common.pendulum_cases import LENGTH, continuum_pendulum, describe_dynamic, tip_errors
from ..engine.report import Section, Table


STUDY = {
    "name": "pendulum-3d",
    "title": "The pendulum as the real 3D beam",
    "needs": ["figure4"],
    # heavy (minutes per level): not in `make study`; `make study-full` runs it by name
    "full": True,
    "grid": {
        "laws": ["yeoh"],
        # Q2/Q1 hexahedra along x, across h (even: the pin is at mid-height), across the width;
        # the step and rho_inf of the continuum pendulum gold (tests/gold/fem_pendulum.json)
        "meshes": [[35, 2, 1], [70, 2, 1], [70, 4, 2]],
        # a case may run this long (s) before the runner stops it (the default is 300 s)
        "timeout_s": 7200,
        "dt": 0.001,
        "rho_inf": 0.8,
        "t_end": 0.5,
    },
    "tiny": {
        "meshes": [[8, 2, 1]],
        "dt": 0.005,
        "t_end": 0.1,
    },
}

MODELS = ("plane-stress", "plane-strain")


def scene(law: str, mesh, dt: float, rho_inf: float, t_end: float) -> dict:
    nx, ny, nz = (int(v) for v in mesh)
    fem = {"model": "3d", "cells_length": nx, "cells_height": ny, "cells_width": nz,
           "degree": 2, "quadrature_degree": 4}
    return paper.pendulum_scene(law, "paper", dt, rho_inf=rho_inf, t_end=t_end, fem=fem,
                                name=f"pendulum-{law}-3d-{nx}x{ny}x{nz}-dt{dt:g}-rho{rho_inf:g}-t{t_end:g}")


def cases(grid: dict, tiny: bool) -> list:
    return [make_case("pendulum-3d", "continuum", scene(law, mesh, grid["dt"], grid["rho_inf"], grid["t_end"]))
            for law in grid["laws"] for mesh in grid["meshes"]]


def _tips(rec: dict) -> dict[float, tuple[float, float]]:
    return {round(h["t"], 9): (h["x"], h["y"]) for h in rec.get("tip_history") or []}


def _ok(rec: dict) -> bool:
    return rec.get("status") == "converged" and bool(rec.get("tip_history"))


def _mesh(rec: dict) -> tuple[int, int, int]:
    f = rec["scene"]["fem"]
    return f["cells_length"], f["cells_height"], f["cells_width"]


def _dist_mm(tips, ref) -> tuple[float | None, float | None]:
    """(at the last common output time, max over the common output times after 0), mm."""
    e = tip_errors(tips, ref)
    if not e:
        return None, None
    return 1e3 * LENGTH * e[max(e)], 1e3 * LENGTH * max(e.values())


def ancf_finest(records: list[dict], law: str) -> dict[str, dict]:
    """{element: description} of the finest plane-stress ANCF pendulum of each element
    (at its smallest step) among ``records`` (the figure4 study's)."""
    best: dict[str, dict] = {}
    for d in map(describe_dynamic, records):
        if d["law"] != law or d["formulation"] != "plane-stress" or not d["ok"]:
            continue
        b = best.get(d["element"])
        if b is None or (d["elements"], -d["dt"]) > (b["elements"], -b["dt"]):
            best[d["element"]] = d
    return best


def report(ctx) -> Section:
    g = ctx.study.grid
    recs = sorted(ctx.records(), key=lambda r: (r["scene"]["material"]["law"], math.prod(_mesh(r))))
    cont = continuum_pendulum()
    sec = Section(ctx.study.title,
                  f"The paper's pendulum ({g['t_end']:g} s) as the real 3D beam (Q2/Q1 hexahedra, exactly "
                  "incompressible, generalized-alpha rho_inf "
                  f"{g['rho_inf']:g} at dt {1e3 * g['dt']:g} ms; the pin is the line (0, 0, z) across the width at "
                  "the left face's mid-height, every displacement component zero there) against the converged 2D "
                  "continuum pendulums (tests/gold/fem_pendulum.json) and the ANCF elements in plane stress at their "
                  "finest mesh of Figure 4. Distances |r_a(t) - r_b(t)| of the tip in mm.")
    rows, lines = [], []
    ancf = {law: ancf_finest(ctx.records("figure4"), law) for law in g["laws"]}
    els = sorted({el for law in g["laws"] for el in ancf[law]})
    prev: dict[str, dict] = {}
    for r in recs:
        law = r["scene"]["material"]["law"]
        nx, ny, nz = _mesh(r)
        row = [law, f"{nx} x {ny} x {nz}", r.get("ndof"), r.get("status"), r.get("wall_s")]
        tips = _tips(r) if _ok(r) else {}
        change = _dist_mm(tips, _tips(prev[law]))[1] if tips and law in prev else None
        row.append(change)
        for m in MODELS:
            c = cont.get((law, m))
            row += list(_dist_mm(tips, c.tips)) if tips and c else [None, None]
        for el in els:
            d = ancf.get(law, {}).get(el)
            row.append(_dist_mm(tips, d["tips"])[1] if tips and d else None)
        rows.append(row)
        if tips:
            prev[law] = r
    hdr = ["law", "3D mesh", "ndof", "status", "wall (s)", "change from previous mesh: max over t (mm)"]
    for m in MODELS:
        hdr += [f"vs continuum {m}: at t_end (mm)", f"vs continuum {m}: max over t (mm)"]
    hdr += [f"vs ANCF {el} plane stress: max over t (mm)" for el in els]
    sec.table(ctx, Table("pendulum_3d", hdr, rows, {4: ".1f", **{j: ".3f" for j in range(5, len(hdr))}}),
              "The 3D pendulum's tip against the 2D continuum pendulums and the ANCF elements (plane stress, finest "
              "mesh of Figure 4, at its smallest step), per 3D mesh.")
    hist = []
    for r in recs:
        if _ok(r):
            for t, (x, y) in sorted(_tips(r).items()):
                hist.append([r["scene"]["material"]["law"], "x".join(map(str, _mesh(r))), t, 1e3 * x, 1e3 * y])
    sec.table(ctx, Table("pendulum_3d_tips", ["law", "3D mesh", "t (s)", "tip x (mm)", "tip y (mm)"], hist,
                         {2: ".1f", 3: ".3f", 4: ".3f"}),
              "The 3D pendulum's tip (centre of the free end face) at the output times.")
    for law in g["laws"]:
        fin = prev.get(law)
        if not fin:
            continue
        tips = _tips(fin)
        d = {m: _dist_mm(tips, cont[(law, m)].tips)[1] for m in MODELS if (law, m) in cont}
        nx, ny, nz = _mesh(fin)
        txt = ", ".join(f"{d[m]:.3f} mm from the continuum {m} pendulum" for m in d)
        lines.append(f"- {law}, finest 3D mesh {nx} x {ny} x {nz}: the tip is at most {txt} "
                     f"(max over t = 0.1 ... {g['t_end']:g} s; the pendulum is {1e3 * LENGTH:.0f} mm long).")
    sec.text = "\n".join(lines)
    return sec


def gold_values(ctx) -> dict:
    """Tip x, y (m) at every output time after 0; tolerance: Newton stops at 1e-8 of the
    residual, so the tips reproduce to ~1e-7 relative: 1e-6 relative + 10 nm."""
    out = {}
    for r in ctx.records():
        if _ok(r):
            law, mesh = r["scene"]["material"]["law"], "x".join(map(str, _mesh(r)))
            for t, (x, y) in _tips(r).items():
                if t > 0:
                    for comp, v in (("x", x), ("y", y)):
                        out[f"pendulum-3d/{law}/{mesh}/t{t:g}/{comp}"] = (v, 1e-6 * abs(v) + 1e-8)
    return out
