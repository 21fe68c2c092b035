"""``python -m reference_fem``: the continuum reference's command line.

- ``run SCENE.toml [--json OUT.json] [--vtk DIR | --xdmf DIR]``: solve one scene,
  write its record (and the deformed mesh for ParaView);
- ``converge SCENE.toml [--levels N] [--json OUT.json]``: refinement study, table of
  tip values per level, observed order, Richardson value and error estimate.

The continuum's gold files, their tables and the pendulum's convergence check are study
code: ``python -m studies continuum gold | pendulum | report``
(:mod:`studies.verification.continuum_gold`).
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

T_IMPORT = time.perf_counter()


def _s(v, fmt: str = ".3f") -> str:
    return "-" if v is None else format(v, fmt)


def _run(args) -> int:
    from contract.console import Progress, check_output_dir, check_output_file, import_modules
    from contract.record import sanitize, write_record
    from contract.scene import load_scene

    from .simulation import capacity, check, run_scene

    import_modules(args.imports)
    scene = load_scene(args.scene)
    settings = check(scene)
    json_out = check_output_file(args.json, "--json")
    out, fmt = (args.vtk, "vtk") if args.vtk else (args.xdmf, "xdmf") if args.xdmf else (None, None)
    out = check_output_dir(out, f"--{fmt}")
    for w in capacity(scene, settings):
        print(f"reference_fem: warning: {w}", file=sys.stderr)
    progress = Progress(scene.analysis.t_end, enabled=not args.quiet) if scene.analysis.kind == "dynamic" else None
    try:
        rec = sanitize(run_scene(scene, output=out, output_format=fmt or "vtk", progress=progress))
    finally:
        if progress:
            progress.close()
    if not _root():
        return 0 if rec["status"] == "converged" else 1
    if json_out:
        write_record(rec, json_out)
    f = rec["fem"]
    cells = f"{f['cells_length']} x {f['cells_height']}" + (f" x {f['cells_width']}" if f.get("cells_width") else "")
    ranks = f", {rec['mpi_ranks']} MPI ranks" if rec.get("mpi_ranks", 1) > 1 else ""
    print(f"scene       {scene.name}  ({rec['continuum_model']}, {rec['incompressibility']}, "
          f"{cells} {f['cell']}, degree {f['degree']}, ndof {rec['ndof']}{ranks})")
    print(f"status      {rec['status']}" + (f"  ({rec['reason']})" if rec["reason"] else ""))
    if rec["tip"]:
        print(f"tip         ux = {rec['tip']['ux'] * 1e3:.4f} mm   uy = {rec['tip']['uy'] * 1e3:.4f} mm")
    if rec.get("tip_history") is not None:
        for h, e in zip(rec["tip_history"], rec["energy"]):
            print(f"t = {h['t']:.4f} s  x = {h['x'] * 1e3:10.4f} mm  y = {h['y'] * 1e3:10.4f} mm  "
                  f"E = {_s(e['total'], '.4e')} J")
        print(f"newton      {rec['newton_iterations']} iterations, {rec['steps']} steps, "
              f"{rec['rejected_steps']} rejected")
    else:
        print(f"newton      {rec['newton_iterations']} iterations, {rec['load_steps']} load steps, "
              f"{rec['rejected_steps']} rejected")
    if rec.get("note"):
        print(f"note        {rec['note']}")
    print(f"time        solve {_s(rec['wall_s'])} s wall, {_s(rec['cpu_s'])} s cpu; "
          f"set-up {_s(rec['setup_s'])} s (meshing + JIT)")
    print(f"effects     {', '.join(rec['effects'] or [])}")
    if rec.get("output"):
        print(f"output      {rec['output']}")
    return 0 if rec["status"] == "converged" else 1


def _root() -> bool:
    """True unless this process is a rank > 0 of an MPI launch (which writes nothing)."""
    import sys as _sys

    if "mpi4py.MPI" not in _sys.modules:
        return True
    from mpi4py import MPI

    return MPI.COMM_WORLD.rank == 0


def _root_after_import() -> bool:
    """:func:`_root` for a command that will start dolfinx (and MPI) anyway."""
    from mpi4py import MPI

    return MPI.COMM_WORLD.rank == 0


def _level_line(level: dict) -> str:
    tip = level["tip"]
    vals = f"{tip['ux'] * 1e3:12.5f} {tip['uy'] * 1e3:12.5f}" if tip else f"{'-':>12s} {'-':>12s}"
    cells = f"{level['cells_length']:6d} x {level['cells_height']:<4d}"
    if level.get("cells_width"):
        cells = f"{level['cells_length']:4d} x {level['cells_height']} x {level['cells_width']:<3d}"
    return (f"{cells} {level['ndof']:8d} {vals} "
            f"{level['wall_s']:8.2f} {level['status']}")


def _converge(args) -> int:
    from contract.record import sanitize
    from contract.scene import load_scene

    from .convergence import refinement_study
    from .simulation import check_static

    scene = load_scene(args.scene)
    check_static(scene)
    root = _root_after_import()
    if root:
        print(f"{'cells':>13s} {'ndof':>8s} {'ux (mm)':>12s} {'uy (mm)':>12s} {'solve s':>8s}")
    study = refinement_study(scene, args.levels,
                             progress=lambda lv: root and print(_level_line(lv), flush=True))
    d = study.to_dict()
    if not root:
        return 0 if d["extrapolated"] else 1
    print("observed order (per triple of levels): "
          + ", ".join("-" if p is None else f"{p:.2f}" for p in d["orders"]))
    if d["extrapolated"]:
        e = d["extrapolated"]
        print(f"Richardson   ux = {e['ux'] * 1e3:.5f} mm   uy = {e['uy'] * 1e3:.5f} mm   "
              f"error estimate {d['error_estimate'] * 1e3:.2e} mm")
    else:
        print("Richardson   not available (fewer than 3 converged levels or no monotone convergence)")
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(sanitize(d), indent=2) + "\n")
    return 0 if d["extrapolated"] else 1


def parser() -> argparse.ArgumentParser:
    """The command line's parser (importable: the documentation renders it)."""
    p = argparse.ArgumentParser(prog="python -m reference_fem",
                                description="2D and 3D continuum reference (DOLFINx) for the ANCF scenes "
                                            "(its gold files: python -m studies continuum)")
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run", help="solve one scene file")
    r.add_argument("scene")
    r.add_argument("--json", metavar="OUT", help="write the result record here")
    g = r.add_mutually_exclusive_group()
    g.add_argument("--vtk", metavar="DIR", help="write the mesh (reference geometry) with the displacement and "
                                                "pressure as point data (VTK .pvd) here: ParaView's Warp By Vector "
                                                "shows the deformed beam")
    g.add_argument("--xdmf", metavar="DIR", help="the same as XDMF")
    r.add_argument("--quiet", action="store_true", help="no progress bar")
    r.add_argument("--import", dest="imports", action="append", default=[], metavar="MODULE",
                   help="import a module first (one that registers a law in mechanics.laws)")
    c = sub.add_parser("converge", help="mesh refinement study of one scene")
    c.add_argument("scene")
    c.add_argument("--levels", type=int, default=4, help="number of meshes (>= 3, default 4)")
    c.add_argument("--json", metavar="OUT", help="write the study here")
    return p


# the FEniCSx stack's modules: a run that needs one this Python cannot import is a choice of
# backend, said in one line (exit 2), not a traceback
FENICSX = ("dolfinx", "ufl", "basix", "ffcx", "petsc4py", "mpi4py", "gmsh")


def _stack_named(run):
    """``run``, with an ImportError of the FEniCSx stack turned into one line naming
    ``fem.backend`` and what to do."""
    def guarded():
        try:
            return run()
        except ModuleNotFoundError as e:
            if (e.name or "").split(".")[0] not in FENICSX:
                raise
            from reference_fem.backends import BACKENDS

            others = ", ".join(repr(b) for b in BACKENDS if b != "dolfinx")
            raise ValueError(f"fem.backend: 'dolfinx' needs the FEniCSx stack, which this Python cannot import "
                               f"(no module {e.name!r}): install it (Debian: python3-dolfinx; conda-forge: "
                               f"fenics-dolfinx) or choose fem.backend from {others}") from None
    return guarded


def main(argv: list[str] | None = None) -> int:
    from contract.console import command

    args = parser().parse_args(argv)
    run = {"run": _run, "converge": _converge}[args.command]
    return command("reference_fem", _stack_named(lambda: run(args)), errors=(ValueError,))


if __name__ == "__main__":
    sys.exit(main())
