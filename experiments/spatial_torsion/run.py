"""Small-twist torsion of the paper's bar in 3D (160 x 5 x 7 mm, clamped, a torque at the free
end) on the spatial ANCF elements, against Saint-Venant (studies.verification.torsion).

The torque is the dead traction (T / I_p) (0, -z, y) on the end face
(ancf.kinematics.spatial.statics.end_torque_load), about 1e-3 rad over the length; the twist
rate is read between the nodes at L / 4 and 3 L / 4, far from the clamp's and the loaded
face's end zones, and gives the bar's torsion constant J = T / (mu rate) (mu = 2 C10, neo-
Hookean, the paper's C10; the paper's penalty). Each element's J is set beside the bound of
its section (the Saint-Venant energy minimised over the warping its section holds: the
span of its section's monomials) and the exact J. Appends a JSON line per run
to res.jsonl here and skips the runs it holds.

    .venv/bin/python experiments/spatial_torsion/run.py ELEMENT COUNTS [--penalty PA] [--support clamp|free-warping]

ELEMENT a registered spatial element or a trial of the Hermite-section family
(``H<degree>p<pressure degree>[w]``, as experiments/spatial_cantilever/run.py reads it), COUNTS
comma-separated element counts, multiples of 4; the support the clamp unless given
(``free-warping``: the face's r, r_y, r_z held, its warping and distortion free,
ancf.kinematics.spatial.statics.free_warping_rows).
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from ancf.kinematics.spatial import SPATIAL_ELEMENTS
from ancf.kinematics.spatial.beam import SpatialBeam
from ancf.kinematics.spatial.statics import clamp_rows, end_torque_load, free_warping_rows, section_rotation, solve_static
from contract import paper
from studies.verification import torsion

HERE = Path(__file__).resolve().parent
SUPPORTS = {"clamp": clamp_rows, "free-warping": free_warping_rows}
sys.path.insert(0, str(HERE.parent / "spatial_cantilever"))
from run import element  # noqa: E402


def section_degree(spec) -> int:
    """The degree to which the element's section is complete."""
    have = set(spec.section_monomials)
    d = 0
    while all((d + 1 - b, b) in have for b in range(d + 2)):
        d += 1
    return d


def main() -> None:
    a = argparse.ArgumentParser()
    a.add_argument("element", help=f"one of {list(SPATIAL_ELEMENTS)} or H<degree>[p<degree>][w]")
    a.add_argument("counts")
    a.add_argument("--penalty", type=float, default=paper.PENALTY)
    a.add_argument("--support", choices=SUPPORTS, default="clamp")
    a = a.parse_args()
    spec = element(a.element)
    L, h, w = paper.CANTILEVER["length"], paper.CANTILEVER["height"], paper.CANTILEVER["width"]
    c10 = paper.materials()["neo-hookean"]["C10"]
    mu = 2.0 * c10
    d = section_degree(spec)
    bound, exact = torsion.warping_bound(h, w, spec.section_monomials), torsion.saint_venant_rectangle(h, w)
    out = HERE / "res.jsonl"
    have = {(r["element"], r["elements"], r["penalty"], r.get("support", "clamp"))
            for r in map(json.loads, out.read_text().splitlines())} if out.exists() else set()
    for n in (int(x) for x in a.counts.split(",")):
        if n % 4:
            raise SystemExit(f"counts: multiples of 4 (nodes at L / 4 and 3 L / 4), got {n}")
        if (a.element, n, a.penalty, a.support) in have:
            continue
        b = SpatialBeam(spec, L, h, w, n, "neo-hookean", {"C10": c10}, a.penalty)
        T = 1e-3 * mu * bound / L
        t0 = time.perf_counter()
        res = solve_static(b, end_torque_load(b, T), SUPPORTS[a.support](b), load_steps=1)
        seconds = time.perf_counter() - t0
        k = len(spec.nodes) - 1
        i, j = n // 4 * k, 3 * n // 4 * k
        xs = b.node_positions()
        J = None
        if res.status == "converged":
            rate = (section_rotation(b, res.q, j) - section_rotation(b, res.q, i)) / (xs[j] - xs[i])
            J = T / (mu * rate)
        rec = {"element": a.element, "elements": n, "section_degree": d, "points": list(b.points), "dof": b.dof,
               "penalty": a.penalty, "support": a.support, "mu": mu, "torque": T, "status": res.status, "reason": res.reason,
               "J": J, "J_section_bound": bound, "J_saint_venant": exact, "newton_iterations": res.newton_iterations,
               "seconds": seconds}
        with out.open("a") as f:
            f.write(json.dumps(rec) + "\n")
        print(json.dumps(rec), flush=True)


if __name__ == "__main__":
    main()
