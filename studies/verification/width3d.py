"""The 2D-assumption map: the static tip of the real 3D beam against plane stress and
plane strain as the width grows.

The paper's cantilever (L = 160 mm, h = 5 mm, own weight) as a 3D solid
(reference_fem ``model = "3d"``, Q2/Q1 hexahedra, exactly incompressible, clamped face)
at widths w = 0.2 h ... 20 h, on one coarse mesh (``xy``: cells along x, across h;
``cell_width``: the widest cell across the width, m), against the converged 2D
continuum (the Richardson values of the ``continuum`` study: plane stress, plane strain
mixed). Per unit width the gravity load is the same at every width, so a 2D model's tip
does not depend on w. The 3D mesh error is measured at the paper's width against the
converged 3D gold (tests/gold/fem_cantilever_3d.json), which is quoted beside it.

- ``(3D - plane stress) / |plane stress|`` and ``(3D - plane strain) / |plane strain|``
  of uy and of ux;
- the fraction ``(u_3D - u_stress) / (u_strain - u_stress)`` of uy: 0 is plane stress, 1
  plane strain.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

from contract import paper

from ..engine.case import make_case
from ..common.gold import GOLD_3D, continuum_references, short
from ..engine.report import Section, Table, figure, legend_outside, mm, pct, verdict


STUDY = {
    "name": "width-3d",
    "title": "The 2D-assumption map: the 3D beam against plane stress and plane strain by width",
    "needs": ["continuum"],
    "full": True,
    "grid": {
        "laws": ["neo-hookean", "mooney-rivlin", "yeoh"],
        # widths in units of h = 5 mm (1.4 h = 7 mm: the paper's beam); the real beam in 3D
        "widths_h": [0.2, 0.5, 1.0, 1.4, 2.0, 5.0, 10.0, 20.0],
        # the 3D mesh: Q2/Q1 cells 10 x 5 mm in x-y (0.05 % of the tip at w = 7 mm), across the
        # width at most `cell_width` (m) wide; against the continuum study's converged 2D tips.
        # `mpi_ranks = N` would launch each case by mpiexec on N ranks instead of the pool
        "xy": [16, 1],
        "cell_width": 0.01,
    },
    "tiny": {
        "laws": ["yeoh"],
        "widths_h": [1.4, 5.0],
        "xy": [8, 1],
        "cell_width": 0.02,
    },
}

ROOT = Path(__file__).resolve().parents[2]
GOLD_2D = ROOT / "tests" / "gold" / "fem_cantilever.json"


def _width(h: float, k: float) -> float:
    return round(h * k, 12)


def scene(law: str, xy, width: float, cell_width: float) -> dict:
    """The paper's cantilever as the 3D beam of ``width`` (m)."""
    nx, ny = int(xy[0]), int(xy[1])
    fem = {"model": "3d", "cells_length": nx, "cells_height": ny, "degree": 2, "quadrature_degree": 4,
           "cells_width": max(1, math.ceil(width / cell_width - 1e-9))}
    d = paper.cantilever_scene(law, "paper", fem=fem, load_steps=10,
                               name=f"width-{law}-3d-w{width * 1e3:g}mm-{nx}x{ny}x{fem['cells_width']}")
    d["beam"]["width"] = width
    return d


def cases(grid: dict, tiny: bool) -> list:
    """The 3D beam at every width; with the grid key ``mpi_ranks`` the cases are
    launched by mpiexec on that many ranks."""
    h = paper.CANTILEVER["height"]
    options = {"mpi_ranks": int(grid["mpi_ranks"])} if grid.get("mpi_ranks") else None
    out = []
    for law in grid["laws"]:
        for k in grid["widths_h"]:
            out.append(make_case("width-3d", "continuum", scene(law, grid["xy"], _width(h, k), grid["cell_width"]),
                                 options))
    return out


def _table(records: list[dict], continuum: list[dict]):
    """{law: {"plane-stress": tip, "plane-strain": tip, "3d": [(w, rec), ...]}}; the 2D
    tips are the continuum study's Richardson values, as {"status", "tip"} records."""
    refs = continuum_references(continuum)
    out: dict[str, dict] = {}
    for r in records:
        s = r["scene"]
        out.setdefault(s["material"]["law"], {"3d": []})["3d"].append((s["beam"]["width"], r))
    for law, d in out.items():
        d["3d"].sort(key=lambda t: t[0])
        for v in ("plane-stress", "plane-strain"):
            ref = refs.get((law, v))
            if ref and ref.tip:
                d[v] = {"status": "converged", "tip": {"ux": ref.tip[0], "uy": ref.tip[1]}}
    return out


def _ok(r) -> bool:
    return bool(r) and r.get("status") == "converged" and bool(r.get("tip"))


def _dev(a, b, k):
    return (a["tip"][k] - b["tip"][k]) / abs(b["tip"][k])


def _fraction(u, ps, pe, k="uy"):
    return (u["tip"][k] - ps["tip"][k]) / (pe["tip"][k] - ps["tip"][k])


def converged_paper_beam() -> list[list]:
    """Rows: law, 3D gold (ux, uy, error), plane stress and plane strain gold, deviations (%)."""
    if not (GOLD_2D.exists() and GOLD_3D.exists()):
        return []
    g2 = json.loads(GOLD_2D.read_text())["cases"]
    g3 = json.loads(GOLD_3D.read_text())["cases"]
    rows = []
    for law in ("neo-hookean", "mooney-rivlin", "yeoh"):
        c3, ps, pe = g3.get(f"{law}/3d"), g2.get(f"{law}/plane-stress"), g2.get(f"{law}/plane-strain")
        if not (c3 and c3.get("tip") and ps and pe):
            continue
        t3, tps, tpe = c3["tip"], ps["tip"], pe["tip"]
        rows.append([law, mm(t3["ux"]), mm(t3["uy"]), mm(c3["error_estimate_m"]), mm(tps["uy"]), mm(tpe["uy"]),
                     pct((t3["ux"] - tps["ux"]) / abs(tps["ux"])), pct((t3["uy"] - tps["uy"]) / abs(tps["uy"])),
                     pct((t3["ux"] - tpe["ux"]) / abs(tpe["ux"])), pct((t3["uy"] - tpe["uy"]) / abs(tpe["uy"]))])
    return rows


def report(ctx) -> Section:
    g = ctx.study.grid
    h = paper.CANTILEVER["height"]
    data = _table(ctx.records(), ctx.records("continuum"))
    sec = Section(ctx.study.title,
                  "The paper's cantilever (160 x 5 mm, own weight, clamped face) as the real 3D beam "
                  "(reference_fem `model = \"3d\"`: Q2/Q1 hexahedra, exactly incompressible) at widths "
                  f"0.2 h to 20 h ({g['xy'][0]} x {g['xy'][1]} cells along x and across h, across the width "
                  f"cells of at most {g['cell_width'] * 1e3:g} mm), against the converged 2D continuum in "
                  "plane stress and plane strain (the Richardson values of the continuum study). Gravity "
                  "per unit width is the same at every width, so the 2D tips do not depend on w." + _mesh_error(data))
    rows = []
    for law, d in data.items():
        ps, pe = d.get("plane-stress"), d.get("plane-strain")
        for w, r in d["3d"]:
            both = _ok(r) and _ok(ps) and _ok(pe)
            f = r["scene"]["fem"]
            rows.append([law, w * 1e3, w / h, f"{f['cells_length']} x {f['cells_height']} x {f['cells_width']}",
                         r.get("ndof"), mm(r["tip"]["ux"]) if _ok(r) else None, mm(r["tip"]["uy"]) if _ok(r) else None,
                         pct(_dev(r, ps, "uy")) if both else None, pct(_dev(r, pe, "uy")) if both else None,
                         _fraction(r, ps, pe) if both else None, _fraction(r, ps, pe, "ux") if both else None,
                         r.get("status") if not _ok(r) else "converged", verdict(r)])
    sec.table(ctx, Table("width_3d",
                         ["law", "w (mm)", "w/h", "cells", "unknowns", "3D ux (mm)", "3D uy (mm)",
                          "uy vs plane stress (%)", "uy vs plane strain (%)", "fraction uy", "fraction ux",
                          "status", "verdict"], rows,
                         {1: "g", 2: "g", 5: ".3f", 6: ".3f", 7: "+.2f", 8: "+.2f", 9: ".3f", 10: ".3f"}),
              "Tip of the 3D beam (centre of the free end face) per width, against the converged 2D "
              "continuum: (3D - 2D) / |2D|. 'fraction' = (u_3D - u_stress) / (u_strain - u_stress): 0 is "
              "plane stress, 1 plane strain.")
    conv = converged_paper_beam()
    if conv:
        sec.table(ctx, Table("width_3d_paper_beam",
                             ["law", "3D ux (mm)", "3D uy (mm)", "3D est. error (mm)", "plane stress uy (mm)",
                              "plane strain uy (mm)", "ux vs plane stress (%)", "uy vs plane stress (%)",
                              "ux vs plane strain (%)", "uy vs plane strain (%)"], conv,
                             {1: ".3f", 2: ".3f", 3: ".3f", 4: ".3f", 5: ".3f", 6: "+.2f", 7: "+.2f", 8: "+.2f",
                              9: "+.2f"}),
                  "The paper's beam (w = 7 mm), converged: the Richardson values of tests/gold/"
                  "fem_cantilever_3d.json (3D, graded hexahedra 16 x 1 x 1 ... 64 x 4 x 4, error estimate "
                  "with the order capped at 1) and tests/gold/fem_cantilever.json (2D).")
    if rows and not ctx.tiny:
        fig, ax = figure(figsize=(6.4, 4.2))
        for law, d in data.items():
            ps, pe = d.get("plane-stress"), d.get("plane-strain")
            pts = [(w / h, _fraction(r, ps, pe)) for w, r in d["3d"] if _ok(r) and _ok(ps) and _ok(pe)]
            if pts:
                ax.plot(*zip(*pts), "o-", label=short(law))
        ax.axvline(paper.CANTILEVER["width"] / h, color="0.6", ls=":", label="paper beam (7 mm)")
        ax.axhline(0.0, color="0.3", lw=0.8)
        ax.axhline(1.0, color="0.3", lw=0.8)
        ax.set_xscale("log")
        ax.set_xlabel("width / height")
        ax.set_ylabel("(uy_3D - uy_stress) / (uy_strain - uy_stress)")
        ax.set_title("3D beam between plane stress (0) and plane strain (1)")
        legend_outside(fig, fontsize=9)
        sec.figure(ctx, fig, "width_3d", "The 2D-assumption map: where the 3D beam's tip deflection lies between "
                   "plane stress (0) and plane strain (1), per width, for the three laws.")
    sec.text = _findings(data, conv, h)
    return sec


def _mesh_error(data) -> str:
    """The 3D mesh error at the paper's width: the study's level against the 3D gold."""
    if not GOLD_3D.exists():
        return ""
    gold = json.loads(GOLD_3D.read_text())["cases"]
    errs = []
    for law, d in data.items():
        g = gold.get(f"{law}/3d")
        for w, r in d["3d"]:
            if g and g.get("tip") and _ok(r) and abs(w - paper.CANTILEVER["width"]) < 1e-9:
                t = g["tip"]
                errs.append(math.hypot(r["tip"]["ux"] - t["ux"], r["tip"]["uy"] - t["uy"]) / math.hypot(t["ux"], t["uy"]))
    if not errs:
        return ""
    return (f" The 3D mesh error, measured at w = 7 mm against the converged 3D gold, is {min(errs) * 100:.2f} to "
            f"{max(errs) * 100:.2f} % of the tip: differences smaller than that are not resolved.")


def _findings(data, conv, h) -> str:
    lines = []
    for law, d in data.items():
        ps, pe = d.get("plane-stress"), d.get("plane-strain")
        pts = [(w, r) for w, r in d["3d"] if _ok(r) and _ok(ps) and _ok(pe)]
        if not pts:
            continue
        within = []   # the widths, from the narrowest, while uy stays within 1 % of plane stress
        for w, r in pts:
            if abs(_dev(r, ps, "uy")) > 0.01:
                break
            within.append(w)
        half = [w for w, r in pts if _fraction(r, ps, pe) >= 0.5]
        widest = pts[-1]
        lines.append(f"- {short(law)}: uy within 1 % of plane stress for w <= {max(within) * 1e3:g} mm "
                     f"({max(within) / h:g} h)" if within else
                     f"- {short(law)}: uy more than 1 % from plane stress already at the narrowest width")
        lines[-1] += (f"; nearer plane strain than plane stress from w = {min(half) * 1e3:g} mm ({min(half) / h:g} h)"
                      if half else "; nearer plane stress at every width shown")
        lines[-1] += (f"; at w = {widest[0] * 1e3:g} mm the fraction is {_fraction(widest[1], ps, pe):.2f} "
                      "(a wide plate reaches plane strain only slowly: near its free edges a beam-like "
                      "boundary layer remains).")
    for row in conv:
        lines.append(f"- Paper beam (7 mm), converged, {short(row[0])}: uy {row[7]:+.2f} % from plane stress, "
                     f"{row[9]:+.2f} % from plane strain (ux {row[6]:+.2f} % / {row[8]:+.2f} %).")
    if lines:
        lines.append("- Caveat for the narrow beams: at full gravity the symmetric equilibrium of a beam "
                     "narrower than about 4 mm is unstable (lateral-torsional buckling under its own weight; "
                     "MUMPS LDL^T inertia of the 32 x 2 x nz prototype runs: 7 negative directions at w = 1 mm, "
                     "1 at 2.5 mm, 0 at 4 and 7 mm). Newton finds the symmetric branch on a symmetric mesh; its "
                     "tip is shown, but such a beam would not be loaded this way in an experiment.")
    return "\n".join(lines)
