"""``python -m studies continuum``: the continuum's gold files, their tables and the
pendulum's convergence check (until the move of this code out of reference_fem, the
commands ``python -m reference_fem gold | pendulum | report``).

- ``gold [--out DIR] [--levels N]``: regenerate tests/gold/fem_cantilever.json;
  ``gold --3d [--laws L ...]``: tests/gold/fem_cantilever_3d.json (the 3D beam; runs on
  the ranks of an ``mpiexec`` launch); ``gold --pendulum [--models M ...]``: regenerate
  tests/gold/fem_pendulum.json (three laws x models, each with its dt / 2 and
  refined-mesh runs);
- ``pendulum [--law L] [--model M] [--dt DT] [--cells-height N] [--aspect A]
  [--rho-inf R] [--integrator I] [--json OUT]``: step and mesh convergence check of
  the paper's pendulum at one (mesh, dt): tip positions and changes per output time;
- ``report [GOLD.json] [--pendulum]``: markdown tables for reports/reference_fem.md from
  the gold file (of the cantilever, or of the pendulum).
"""
from __future__ import annotations

import json
from pathlib import Path

LAW_NAMES = ["neo-hookean", "mooney-rivlin", "yeoh"]
MODELS = ["plane-stress", "plane-strain"]


def _root_after_import() -> bool:
    """True on rank 0 of an MPI launch (or without one), for a command that starts
    dolfinx (and MPI) anyway."""
    from mpi4py import MPI

    return MPI.COMM_WORLD.rank == 0


def _gold(args) -> int:
    if args.pendulum:
        from studies.verification.continuum_gold.pendulum import write_pendulum_gold

        path = write_pendulum_gold(Path(args.out), tuple(args.models), workers=args.workers,
                                   progress=lambda m: print(m, flush=True))
        print(f"wrote {path}")
        return 0
    if args.solid:
        from .cantilever import LAWS, write_gold_3d

        path = write_gold_3d(Path(args.out), args.levels or 3, laws=args.laws or LAWS,
                             progress=print if _root_after_import() else None)
        print(f"wrote {path}") if _root_after_import() else None
        return 0
    from .cantilever import write_gold

    path = write_gold(Path(args.out), args.levels or 5, progress=print)
    print(f"wrote {path}")
    return 0


def _pendulum(args) -> int:
    from contract.record import sanitize
    from studies.verification.continuum_gold.pendulum import convergence_case

    case = convergence_case(args.law, args.model, args.dt, args.cells_height, args.aspect,
                            workers=args.workers, rho_inf=args.rho_inf, integrator=args.integrator)
    for name, run in case["runs"].items():
        f = run["fem"] or {}
        print(f"{name:13s} {f.get('cells_length')} x {f.get('cells_height')}  ndof {run['ndof']}  "
              f"steps {run['steps']}  newton {run['newton_iterations']}  rejected {run['rejected_steps']}  "
              f"{run['wall_s'] or 0:.1f} s  energy drift {run['energy_drift_J'] or float('nan'):.2e} J  "
              f"{run['status']}" + (f" ({run['reason']})" if run["reason"] else ""))
    if case["tip_history"]:
        print(f"{'t (s)':>6s} {'x (mm)':>10s} {'y (mm)':>10s} {'d dt/2 (mm)':>12s} {'d mesh (mm)':>12s}")
        for h, a, b in zip(case["tip_history"], case["change_half_dt_m"], case["change_refined_mesh_m"]):
            print(f"{h['t']:6.3f} {h['x'] * 1e3:10.4f} {h['y'] * 1e3:10.4f} {a * 1e3:12.5f} {b * 1e3:12.5f}")
        print(f"converged (< {0.1:g} mm at t > 0): {case['converged']}")
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(sanitize(case), indent=1) + "\n")
    return 0 if case.get("converged") else 1


def _report(args) -> int:
    if args.pendulum:
        from studies.verification.continuum_gold.pendulum import render as render_pendulum

        print(render_pendulum(Path(args.gold or "tests/gold/fem_pendulum.json")), end="")
        return 0
    from .cantilever_tables import render

    print(render(Path(args.gold or "tests/gold/fem_cantilever.json")), end="")
    return 0


def add_commands(sub) -> None:
    """``continuum`` and its three sub-commands, on the sub-parsers ``sub`` of
    ``python -m studies``."""
    p = sub.add_parser("continuum", help="the continuum's gold files, their tables, the pendulum's convergence check")
    cs = p.add_subparsers(dest="continuum_command", required=True)
    gd = cs.add_parser("gold", help="regenerate the gold file of the paper's cantilever")
    gd.add_argument("--out", default="tests/gold", help="directory (default tests/gold)")
    gd.add_argument("--levels", type=int, default=None, help="meshes per case (default 5; --3d: 3)")
    gd.add_argument("--3d", dest="solid", action="store_true",
                    help="the 3D beam's gold file (tests/gold/fem_cantilever_3d.json) instead; "
                         "runs on the ranks of an mpiexec launch")
    gd.add_argument("--laws", nargs="+", choices=LAW_NAMES,
                    help="with --3d: only these laws (the file's other cases are kept)")
    gd.add_argument("--pendulum", action="store_true",
                    help="the pendulum's gold file (tests/gold/fem_pendulum.json) instead")
    gd.add_argument("--models", nargs="+", default=MODELS, choices=MODELS, help="with --pendulum")
    gd.add_argument("--workers", type=int, default=2, help="processes (with --pendulum)")
    pd = cs.add_parser("pendulum", help="step and mesh convergence of the paper's pendulum")
    pd.add_argument("--law", default="yeoh", choices=LAW_NAMES)
    pd.add_argument("--model", default="plane-stress", choices=MODELS)
    pd.add_argument("--dt", type=float, default=1e-3)
    pd.add_argument("--cells-height", type=int, default=4)
    pd.add_argument("--aspect", type=float, default=2.0)
    pd.add_argument("--rho-inf", type=float, default=0.8)
    pd.add_argument("--integrator", default="generalized-alpha", choices=["generalized-alpha", "newmark"])
    pd.add_argument("--workers", type=int, default=2)
    pd.add_argument("--json", metavar="OUT")
    rp = cs.add_parser("report", help="markdown tables from the gold file")
    rp.add_argument("gold", nargs="?", default=None,
                    help="default tests/gold/fem_cantilever.json (fem_pendulum.json with --pendulum)")
    rp.add_argument("--pendulum", action="store_true", help="tables of the pendulum gold file")


def run(args) -> int:
    """The sub-command ``args`` names."""
    return {"gold": _gold, "pendulum": _pendulum, "report": _report}[args.continuum_command](args)
