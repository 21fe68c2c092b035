"""Static solve time of a pressure element (HB2n-40p) on the compiled static Newton against
the Python Newton loop it replaced (issue 20's compiled pressure term), in one process.

The paper's cantilever, Yeoh, penalised plane strain (the paper's penalty), default rule;
n elements. Each repeat runs the scene once on each path, interleaved (the machine's load
hits both alike); printed: the median wall time of the solve (the record's wall_s, the model
build included) and its spread (max - min) / median, and the two tips' difference. The
Python path is the same code with BeamModel.compiled patched to False (statics.newton then
runs newton_reference, whose force and tangent are the numpy band kernel plus
ancf.kinematics.section.pressure.ProjectedPenalty). Times are printed, never asserted.

    nice -n 10 .venv/bin/python -m experiments.bench_pressure [n ...] [--repeats 3] [--element HB2n-40p]
"""
from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from ancf.kinematics.section.model import BeamModel
from ancf.simulation import run_scene
from contract import paper
from contract.scene import scene_from_dict


def solve(element: str, n: int, law: str, compiled: bool) -> tuple[float, np.ndarray, dict]:
    scene = scene_from_dict(paper.cantilever_scene(law, "plane-strain", element, n, quadrature=None))
    saved = BeamModel.compiled
    if not compiled:
        BeamModel.compiled = property(lambda self: False)
    try:
        t0 = time.perf_counter()
        rec, _ = run_scene(scene)
        wall = time.perf_counter() - t0
    finally:
        BeamModel.compiled = saved
    assert rec["status"] == "converged", rec.get("reason")
    return wall, np.array([rec["tip"]["ux"], rec["tip"]["uy"]]), rec


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("n", nargs="*", type=int, default=[64, 640])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--element", default="HB2n-40p")
    ap.add_argument("--law", default="yeoh")
    ap.add_argument("--import", dest="module", help="a module that registers the element (e.g. examples.transversely_cubic)")
    a = ap.parse_args(argv)
    if a.module:
        __import__(a.module)
    solve(a.element, 4, a.law, True)                          # compile or load the kernels once
    print(f"{a.element}, {a.law}, plane-strain (penalised), paper cantilever; wall s, median of {a.repeats}")
    print("| elements | Python Newton s | spread | compiled s | spread | speed-up | |tip diff| m | load steps |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for n in a.n:
        t = {True: [], False: []}
        tips = {}
        for _ in range(a.repeats):
            for compiled in (False, True):
                wall, tip, rec = solve(a.element, n, a.law, compiled)
                t[compiled].append(wall)
                tips[compiled] = tip
                steps = rec.get("load_steps")
        med = {k: statistics.median(v) for k, v in t.items()}
        spread = {k: (max(v) - min(v)) / med[k] for k, v in t.items()}
        print(f"| {n} | {med[False]:.3f} | {spread[False]:.2f} | {med[True]:.3f} | {spread[True]:.2f} | "
              f"{med[False] / med[True]:.1f} | {np.hypot(*(tips[True] - tips[False])):.2e} | {steps} |", flush=True)


if __name__ == "__main__":
    main()
