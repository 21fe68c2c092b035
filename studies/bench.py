"""Benchmarks: tables of measured times (medians of warm runs in one process).

    python -m studies.bench table3    # the twelve ANCF cells of the paper's Table 3
    python -m studies.bench penalty   # static convergence over alpha = 10..1e5 C10

Speed is measured here, never asserted in tests.
"""
from __future__ import annotations

import argparse
import itertools
import statistics
import sys
import time

from ancf.run import run_scene
from ancf.scene import scene_from_dict

from . import paper

# The setting that reproduces the paper's Table 3 (README, "Reproducing Table 3").
PAPER_SETTING = {"quadrature": (2, 2), "clamp": "all"}
LAWS = ("neo-hookean", "mooney-rivlin", "yeoh")


def _timed(scene, repeats: int):
    run_scene(scene)                                   # warm-up: caches, imports
    recs = [run_scene(scene)[0] for _ in range(repeats)]
    return recs[-1], statistics.median(r["wall_s"] for r in recs)


def table3(repeats: int = 5) -> float:
    print(f"Table 3 cells, `paper` formulation, quadrature {PAPER_SETTING['quadrature']}, "
          f"clamp '{PAPER_SETTING['clamp']}'; wall time = median of {repeats} warm runs, one process")
    print(f"{'element':8s} {'n':>4s} {'law':14s} {'ndof':>5s} {'steps':>5s} {'newton':>6s} "
          f"{'ux mm':>8s} {'paper':>8s} {'uy mm':>8s} {'paper':>8s} {'wall s':>7s}")
    total = 0.0
    for element, law in itertools.product(("HB2n-12", "HB3n-12", "HB2n-16", "LB2n-12"), LAWS):
        ref = paper.table3()[(element, law)]
        s = scene_from_dict(paper.cantilever_scene(law, "paper", element, ref["elements"], **PAPER_SETTING))
        rec, wall = _timed(s, repeats)
        total += wall
        tip = rec["tip"] or {"ux": float("nan"), "uy": float("nan")}
        print(f"{element:8s} {ref['elements']:4d} {law:14s} {rec['ndof']:5d} {rec['load_steps']:5d} "
              f"{rec['newton_iterations']:6d} {tip['ux'] * 1e3:8.2f} {ref['ux'] * 1e3:8.2f} "
              f"{tip['uy'] * 1e3:8.2f} {ref['uy'] * 1e3:8.2f} {wall:7.3f}")
    print(f"total wall time of the twelve cells: {total:.2f} s (target < 10 s)")
    return total


def penalty(elements=(16, 160, 640), factors=(1e1, 1e2, 1e3, 1e4, 1e5)) -> bool:
    """Does every static solve converge for alpha = factor * C10, and how many load
    steps does it need? (default quadrature (3, 2), face clamp)"""
    print("Static cantilever under gravity over the penalty range; "
          "cells: accepted load steps (+rejected) / stable, or FAILED")
    ok = True
    for form, n in itertools.product(("paper", "plane-strain"), elements):
        print(f"\n{form}, {n} elements")
        print(f"{'element':8s} {'law':14s} " + " ".join(f"{f'a={f:.0e}C10':>16s}" for f in factors))
        for element, law in itertools.product(("HB2n-12", "HB3n-12", "HB2n-16", "LB2n-12"), LAWS):
            cells = []
            for f in factors:
                alpha = f * paper.materials()[law]["C10"]
                t0 = time.perf_counter()
                rec, _ = run_scene(scene_from_dict(paper.cantilever_scene(law, form, element, n, penalty=alpha)))
                dt = time.perf_counter() - t0
                if rec["status"] != "converged":
                    ok = False
                    cells.append("FAILED")
                else:
                    mark = {True: "", False: "!", None: "?"}[rec["stable"]]
                    cells.append(f"{rec['load_steps']}(+{rec['rejected_steps']}){mark} {dt:5.1f}s")
            print(f"{element:8s} {law:14s} " + " ".join(f"{c:>16s}" for c in cells))
            sys.stdout.flush()
    print("\n'!': converged to a state whose tangent is not positive definite (unstable or a "
          "zero-energy mode); '?': stability undetermined (lowest eigenvalue within round-off); "
          "see README.")
    return ok


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m studies.bench")
    p.add_argument("which", choices=("table3", "penalty", "all"), nargs="?", default="table3")
    p.add_argument("--repeats", type=int, default=5)
    a = p.parse_args(argv)
    if a.which in ("table3", "all"):
        table3(a.repeats)
    if a.which in ("penalty", "all"):
        return 0 if penalty() else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
