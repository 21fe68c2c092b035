"""Benchmarks: tables of measured times (medians of warm runs in one process).

    python -m studies.bench table3    # the twelve ANCF cells of the paper's Table 3
    python -m studies.bench penalty   # static convergence over alpha = 10..1e5 C10
    python -m studies.bench pendulum  # the paper's Table 4 grid, each case at its converged step

Speed is measured here, never asserted in tests.
"""
from __future__ import annotations

import argparse
import itertools
import statistics
import sys
import time

from ancf.simulation import run_scene
from contract import paper
from contract.scene import scene_from_dict

from .pendulum_cases import LADDER, converged_rung, describe_dynamic, ladder, pendulum_dict

# The setting that reproduces the paper's Table 3 (README, "Reproducing Table 3").
PAPER_SETTING = {"quadrature": (2, 2), "clamp": "all"}


def paper_cells() -> list[tuple[str, str]]:
    """(element, law) of the paper's Table 3 ANCF cells, in its order."""
    return [k for k in paper.table3() if k[0] != "ABAQUS"]


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
    for element, law in paper_cells():
        ref = paper.table3()[(element, law)]
        s = scene_from_dict(paper.cantilever_scene(law, "paper", element, ref["elements"], **PAPER_SETTING))
        rec, wall = _timed(s, repeats)
        total += wall
        tip = rec["tip"] or {"ux": float("nan"), "uy": float("nan")}
        print(f"{element:8s} {ref['elements']:4d} {law:14s} {rec['ndof']:5d} {rec['load_steps']:5d} "
              f"{rec['newton_iterations']:6d} {tip['ux'] * 1e3:8.2f} {ref['ux'] * 1e3:8.2f} "
              f"{tip['uy'] * 1e3:8.2f} {ref['uy'] * 1e3:8.2f} {wall:7.3f}")
    print(f"total wall time of the twelve cells: {total:.2f} s (target < 1 s)")
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
        for element, law in paper_cells():
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


def converged_step(element, n, formulation, rho_inf=0.5, dt0=LADDER["dt0"], tol=LADDER["tol"],
                   dt_floor=LADDER["dt_floor"]):
    """The converged step of Table 4's rule (:func:`studies.pendulum_cases.converged_rung`),
    running the ladder only as far as needed; returns (dt, difference in m)."""
    rungs = []
    for dt in ladder(dt0, dt_floor):
        rec = run_scene(scene_from_dict(pendulum_dict(element, n, formulation, dt, rho_inf)))[0]
        rungs.append(describe_dynamic(rec))
        rung, diff = converged_rung(rungs[-2:], tol)
        if rung is not None:
            return rung["dt"], diff
    return None, None


def pendulum(repeats: int = 5, rho_inf: float = 0.5, formulations=("plane-stress", "paper")) -> None:
    print(f"Table 4 grid: pendulum (Yeoh, 0.5 s), generalized-alpha rho_inf = {rho_inf}; each case "
          f"at its converged step (largest dt whose tip positions are within 0.1 mm of the dt/2 "
          f"run); wall time = median of {repeats} warm runs, one process, one thread; the "
          f"paper's CPU time on an i5-5200U for comparison")
    for form in formulations:
        print(f"\n{form}")
        print(f"{'element':8s} {'n':>3s} {'ndof':>5s} {'dt ms':>6s} {'steps':>6s} {'newton':>6s} "
              f"{'wall s':>7s} {'paper s':>8s} {'paper/ours':>10s}")
        cells = paper.table4()
        order = list(dict.fromkeys(el for el, _ in cells))
        for element, n in sorted(cells, key=lambda k: (order.index(k[0]), k[1])):
            dt, _ = converged_step(element, n, form, rho_inf)
            paper_s = paper.table4()[(element, n)]
            if dt is None:
                print(f"{element:8s} {n:3d}  no converged step above 0.1 ms")
                continue
            rec, wall = _timed(scene_from_dict(pendulum_dict(element, n, form, dt, rho_inf)), repeats)
            print(f"{element:8s} {n:3d} {rec['ndof']:5d} {dt * 1e3:6.3f} {rec['steps']:6d} "
                  f"{rec['newton_iterations']:6d} {wall:7.3f} {paper_s:8.1f} {paper_s / wall:10.0f}")
            sys.stdout.flush()


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m studies.bench")
    p.add_argument("which", choices=("table3", "penalty", "pendulum", "all"), nargs="?", default="table3")
    p.add_argument("--repeats", type=int, default=5)
    a = p.parse_args(argv)
    if a.which in ("table3", "all"):
        table3(a.repeats)
    if a.which in ("pendulum", "all"):
        pendulum(a.repeats)
    if a.which in ("penalty", "all"):
        return 0 if penalty() else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
