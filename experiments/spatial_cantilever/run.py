"""The paper's cantilever in 3D (160 x 5 x 7 mm, the clamped face, gravity) on the spatial
ANCF elements (ancf.kinematics.spatial), against the 3D continuum's gold
(reports/data/solid3d/fem_cantilever_3d.json: DOLFINx Q2/Q1 hexahedra, exactly
incompressible, Richardson-extrapolated). Appends one JSON line per run to res.jsonl here
and skips the runs it holds.

    .venv/bin/python experiments/spatial_cantilever/run.py LAW ELEMENT COUNTS [--penalty PA] [--iterations N] [--points P,P,P] [--grading G]

ELEMENT a registered spatial element or a trial of the Hermite-section family,
``H<degree>p<pressure degree>[w]`` (ancf.kinematics.spatial.elements.hermite_section: cubic
Hermite along, the complete section of that degree, the pressure {1, x} x the complete
section of its degree; ``H2`` without a pressure; a ``w`` adds the section modes
y^3 z and y z^3, the next torsion warping; ``+y3+yz2`` adds these modes, ``/y2+z2`` these
modes to the pressure's section), COUNTS comma-separated element counts. The law's
constants and density are the paper's (contract.paper), the penalty the paper's 1000 MPa
unless given; the element's default rule (its points along, across the height, across the width) unless given;
equal elements, or with ``--grading G`` each G times as long as the one before it from the clamp;
10 load steps, Newton to 1e-8 of the load or to a correction of 1e-12 L, 100 iterations
per increment unless given.
"""
from __future__ import annotations

import argparse
import json
import re
import time
from pathlib import Path

import numpy as np

from ancf.kinematics.spatial import SPATIAL_ELEMENTS
from ancf.kinematics.spatial.elements import TORSION_MODES, hermite_section
from ancf.kinematics.spatial.beam import SpatialBeam
from ancf.kinematics.spatial.statics import clamp_rows, gravity_load, solve_static
from contract import paper

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
GOLD = ROOT / "reports" / "data" / "solid3d" / "fem_cantilever_3d.json"
# the static loop a record comes from: the first, damped Newton, and the full steps with the
# force's round-off floor on the residual (ancf.kinematics.spatial.statics); a run is
# repeated under a new loop, the old record kept
LOOP = "full-newton"


def _modes(text: str) -> tuple[tuple[int, int], ...]:
    """Section modes from monomials joined by '+': 'y3+yz2' -> ((3, 0), (1, 2))."""
    out = []
    for m in text.split("+"):
        powers = dict(re.findall(r"([yz])(\d*)", m))
        if not m or "".join(f"{v}{powers[v]}" for v in "yz" if v in powers) != m:
            raise SystemExit(f"section mode {m!r}: a monomial in y and z, y's first (y3, yz2, z4)")
        out.append(tuple(int(powers[v] or 1) if v in powers else 0 for v in "yz"))
    return tuple(out)


def element(name: str):
    """A registered spatial element, or H<degree>[p<degree>][w][+<modes>][/<modes>] of the
    Hermite-section family (``w``: with the torsion warping modes y^3 z and y z^3 added to the
    section; ``+y3+yz2``: these section modes added too; ``/y2+z2``: these section modes added
    to the pressure's)."""
    if name in SPATIAL_ELEMENTS:
        return SPATIAL_ELEMENTS[name]
    name_, _, pmore = name.partition("/")
    base, _, more = name_.partition("+")
    base, extra = (base[:-1], TORSION_MODES) if base.endswith("w") else (base, ())
    head, _, p = base[1:].partition("p")
    if not base.startswith("H") or not head.isdigit() or (p and not p.isdigit()):
        raise SystemExit(f"element {name!r}: one of {list(SPATIAL_ELEMENTS)} or H<degree>[p<degree>][w][+<modes>][/<modes>]")
    if pmore and not p:
        raise SystemExit(f"element {name!r}: pressure modes '/{pmore}' need a pressure degree p<degree>")
    return hermite_section(name, int(head), int(p) if p else None, "trial", extra + (_modes(more) if more else ()),
                           _modes(pmore) if pmore else ())


def main() -> None:
    a = argparse.ArgumentParser()
    a.add_argument("law")
    a.add_argument("element", help=f"one of {list(SPATIAL_ELEMENTS)} or H<degree>[p<degree>][w]")
    a.add_argument("counts")
    a.add_argument("--penalty", type=float, default=paper.PENALTY)
    a.add_argument("--iterations", type=int, default=100, help="Newton iterations per increment")
    a.add_argument("--points", help="Gauss points along, across h, across w (default: the element's default rule)")
    a.add_argument("--grading", type=float, default=1.0, help="each element this times as long as the one before it")
    a = a.parse_args()
    spec = element(a.element)
    points = tuple(int(v) for v in a.points.split(",")) if a.points else spec.default_rule()
    gold = json.loads(GOLD.read_text())["cases"][f"{a.law}/3d"]
    m = paper.materials()[a.law]
    c = {k: v for k, v in m.items() if k != "density"}
    L, h, w = paper.CANTILEVER["length"], paper.CANTILEVER["height"], paper.CANTILEVER["width"]
    out = HERE / "res.jsonl"
    have = {(r["law"], r["element"], r["elements"], r["penalty"], r.get("iterations", 100), tuple(r["points"]),
             r.get("loop", "damped"), r.get("grading", 1.0))
            for r in map(json.loads, out.read_text().splitlines())} if out.exists() else set()
    for n in (int(x) for x in a.counts.split(",")):
        if (a.law, a.element, n, a.penalty, a.iterations, points, LOOP, a.grading) in have:
            continue
        b = SpatialBeam(spec, L, h, w, n, a.law, c, a.penalty, points, a.grading)
        t0 = time.perf_counter()
        res = solve_static(b, gravity_load(b, m["density"], (0.0, -paper.GRAVITY, 0.0)), clamp_rows(b),
                           load_steps=10, max_iterations=a.iterations)
        tip = res.tip(b)
        g = gold["tip"]
        err = None if tip is None else float(np.hypot(tip["ux"] - g["ux"], tip["uy"] - g["uy"]) / L)
        rec = {"law": a.law, "element": a.element, "elements": n, "penalty": a.penalty, "iterations": a.iterations, "loop": LOOP,
               "points": points, "grading": a.grading, "first_element_m": float(b.lengths[0]),
               "rejected_steps": res.rejected_steps,
               "dof": b.dof, "status": res.status, "reason": res.reason, "tip": tip, "gold": g,
               "gold_error_estimate_m": gold["error_estimate_m"], "error_over_L": err,
               "newton_iterations": res.newton_iterations, "seconds": time.perf_counter() - t0}
        with out.open("a") as f:
            f.write(json.dumps(rec) + "\n")
        print(json.dumps(rec), flush=True)


if __name__ == "__main__":
    main()
