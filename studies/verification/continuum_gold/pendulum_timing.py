"""The continuum pendulum the reports use on both backends: wall time and tips.

    python -m studies.verification.continuum_gold.pendulum_timing [--laws L ...] [--models M ...] [--t-end T]

Each gold base scene (:mod:`studies.verification.continuum_gold.pendulum`: 140 x 4 Q2 or Q2/Q1 cells,
dt = 1 ms, generalized-alpha rho_inf = 0.8, 0.5 s) is run once by DOLFINx and once by
FElupe on the same mesh with the same integrator; printed: the runs' wall times with the
median and quartiles of the time per accepted step (the spread within a run), the Newton
iterations, and the tips at the output times with their distance (the discrete problems
are the same: expect the Newton tolerance). One run per backend: the per-step quartiles
are the spread; the machine's load moves the medians between runs.
"""
from __future__ import annotations

import argparse
import dataclasses
import math
import time

import numpy as np

from reference_fem.backends import BACKENDS
from studies.verification.continuum_gold.pendulum import LAWS, pendulum_dict


def run(law: str, model: str, backend: str, t_end: float | None = None) -> dict:
    """The gold base scene of (law, model) on ``backend``: its record and per-step times."""
    from contract.scene import scene_from_dict

    from reference_fem.settings import fem_settings
    from reference_fem.simulation import run_scene

    kw = {} if t_end is None else {"t_end": t_end}
    scene = scene_from_dict(pendulum_dict(law, model, **kw))
    stamps: list[float] = []
    t0 = time.perf_counter()
    rec = run_scene(scene, dataclasses.replace(fem_settings(scene), backend=backend),
                    progress=lambda t, r: stamps.append(time.perf_counter()))
    rec["total_s"] = time.perf_counter() - t0
    steps = np.diff(stamps)           # the first step's time (with the set-up) left out
    rec["step_ms"] = [float(x) for x in np.percentile(steps, [25, 50, 75]) * 1e3] if len(steps) else None
    return rec


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m studies.verification.continuum_gold.pendulum_timing", description=__doc__.split("\n\n")[0])
    ap.add_argument("--laws", nargs="+", default=list(LAWS), choices=LAWS)
    ap.add_argument("--models", nargs="+", default=["plane-stress", "plane-strain"],
                    choices=["plane-stress", "plane-strain"])
    ap.add_argument("--t-end", type=float, default=None, help="s (default: the gold's 0.5)")
    args = ap.parse_args(argv)
    times, tips = [], []
    for law in args.laws:
        for model in args.models:
            recs = {b: run(law, model, b, args.t_end) for b in BACKENDS}
            d, f = recs["dolfinx"], recs["felupe"]
            for b, r in recs.items():
                q = r["step_ms"] or [math.nan] * 3
                times.append(f"| {law}/{model} | {b} | {r['status']} | {r['ndof']} | {r['steps']} | "
                             f"{r['newton_iterations']} | {r['wall_s']:.1f} | {q[1]:.1f} ({q[0]:.1f}-{q[2]:.1f}) |")
            if d["status"] == f["status"] == "converged":
                for p, o in zip(d["tip_history"], f["tip_history"]):
                    if p["t"] > 0:
                        tips.append(f"| {law}/{model} | {p['t']:g} | {p['x'] * 1e3:.4f}, {p['y'] * 1e3:.4f} | "
                                    f"{o['x'] * 1e3:.4f}, {o['y'] * 1e3:.4f} | "
                                    f"{math.hypot(p['x'] - o['x'], p['y'] - o['y']):.1e} |")
            times.append(f"| {law}/{model} | FElupe / DOLFINx | | | | | {f['wall_s'] / d['wall_s']:.2f} | |")
    print("| case | backend | status | ndof | steps | Newton its | wall (s) | per step (ms): median (quartiles) |")
    print("|---|---|---|---|---|---|---|---|")
    print("\n".join(times))
    print()
    print("| case | t (s) | DOLFINx tip x, y (mm) | FElupe tip x, y (mm) | distance (m) |")
    print("|---|---|---|---|---|")
    print("\n".join(tips))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
