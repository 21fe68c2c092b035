"""``ancf`` command line: ``ancf run SCENE.toml [--json OUT.json] [--vtk DIR] [--quiet]``,
``ancf elements``, ``ancf laws``, ``ancf formulations``, ``ancf warm``.

``ancf run`` first loads the compiled code the scene runs (:func:`ancf.warm.load`: from
numba's cache, or compiled when the cache is empty) and reports that time as ``load``,
apart from the solve; ``ancf warm`` fills the cache for every shipped scene and the
variants the studies run (the set-up calls it once per clone).

Exit status: 0 converged, 1 the run failed (the record says why), 2 a bad scene or
option (one line naming the field), 130 interrupted."""
from __future__ import annotations

import argparse
import os
import sys
import time

T_IMPORT = time.perf_counter()

# One BLAS / OpenMP thread, set before numpy loads (free here; ancf.simulation limits an already
# loaded BLAS with threadpoolctl): a banded system of a few hundred unknowns only pays
# for a thread pool (measured: 0.61 s of solve against 0.33 s with one thread).
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


def _s(v, fmt: str = ".3f") -> str:
    return "-" if v is None else format(v, fmt)


def _run(args) -> int:
    from contract.console import Progress, check_output_dir, check_output_file, safe_name
    from contract.record import sanitize, write_record
    from contract.scene import load_scene

    from .build import plan
    from .simulation import run_scene
    from .warm import load

    scene = load_scene(args.scene)
    json_out = check_output_file(args.json, "--json")
    vtk_dir = check_output_dir(args.vtk, "--vtk")
    name = safe_name(scene.name)            # the output files' stem
    resolved = plan(scene)                  # the scene checked and resolved once, for the whole run
    for w in resolved.capacity_warnings:
        print(f"ancf: warning: {w}", file=sys.stderr)
    load_s = load(resolved)
    progress = Progress(scene.analysis.t_end, enabled=not args.quiet) if scene.analysis.kind == "dynamic" else None
    try:
        rec, (model, res) = run_scene(resolved, progress=progress)
    finally:
        if progress:
            progress.close()
    rec = sanitize(rec)
    rec["load_s"] = load_s
    if json_out:
        write_record(rec, json_out)
    if vtk_dir and res is not None and getattr(res, "u", True) is not None:
        from .output import frame_strip, write_vtk
        states = ([(o.t, o.state.u) for o in res.outputs] if scene.analysis.kind == "dynamic"
                  else [(0.0, res.u)])
        pvd = write_vtk(model, states, vtk_dir, name)
        extra = ""
        if rec.get("configurations"):
            extra = f" and {frame_strip(rec['configurations'], vtk_dir / f'{name}-frames.png', scene.name)}"
        print(f"vtk         {pvd}{extra} (reference geometry with the displacement: Warp By Vector)")
    print(f"scene       {scene.name}  ({scene.ancf.element} x {scene.ancf.elements}, "
          f"{scene.material.law}, {scene.material.formulation}, ndof {rec['ndof']})")
    print(f"status      {rec['status']}" + (f"  ({rec['reason']})" if rec["reason"] else ""))
    if rec["tip"]:
        turn = f"   end face turned {rec['tip']['rotation']:.6f} rad" if "rotation" in rec["tip"] else ""
        print(f"tip         ux = {rec['tip']['ux'] * 1e3:.4f} mm   uy = {rec['tip']['uy'] * 1e3:.4f} mm{turn}")
    if rec.get("note"):
        print(f"note        {rec['note']}")
    if scene.analysis.kind == "static":
        print(f"newton      {rec['newton_iterations']} iterations, {rec['load_steps']} load steps "
              f"({rec.get('relax_steps')} relaxation), {rec['rejected_steps']} rejected")
        print(f"stable      {rec['stable']}" + (f"  ({rec['stability']})" if rec.get("stability") else ""))
    else:
        print(f"steps       {rec.get('steps')} accepted, {rec['rejected_steps']} rejected, "
              f"{rec['newton_iterations']} Newton iterations ({scene.analysis.integrator}, "
              f"rho_inf {scene.analysis.rho_inf})")
        for h, e in zip(rec.get("tip_history") or [], rec.get("energy") or []):
            print(f"  t = {h['t']:.4f} s   tip ({h['x'] * 1e3:9.3f}, {h['y'] * 1e3:9.3f}) mm   "
                  f"E = {_s(e['total'], '+.3e')} J (kinetic {_s(e['kinetic'], '.3e')}, strain {_s(e['strain'], '.3e')})")
    rest = time.perf_counter() - T_IMPORT - (rec["wall_s"] or 0.0) - (rec["setup_s"] or 0.0) - load_s
    print(f"time        solve {_s(rec['wall_s'])} s wall, {_s(rec['cpu_s'])} s cpu; set-up {_s(rec['setup_s'])} s; "
          f"compiled code {load_s:.3f} s ({'loaded from the cache' if load_s < COMPILED else 'compiled: `ancf warm` fills the cache'}); "
          f"plus {rest:.2f} s imports and output")
    print(f"effects     {', '.join(rec['effects'] or [])}")
    if json_out:
        print(f"record      {json_out}")
    return 0 if rec["status"] == "converged" else 1


# above this, the compiled-code step compiled rather than loaded (a load takes 0.1-0.7 s)
COMPILED = 5.0


def _warm(args) -> int:
    from .warm import warm

    warm()
    return 0


def _list(registry: dict) -> int:
    """One line per entry: its name and reference; an element's also what it refuses
    (:func:`ancf.admission.refused_integrators`, its kinematics' formulations)."""
    from .admission import refused_integrators
    from .core.spec import ElementSpec

    for name, item in registry.items():
        line = f"{name:16s} {getattr(item, 'reference', '') or getattr(item, 'doc', '')}"
        if isinstance(item, ElementSpec):
            if refused := sorted(refused_integrators(item)):
                line += f"  [refuses integrator {', '.join(refused)}]"
            if item.family.formulations is not None:
                line += f"  [formulation {', '.join(item.family.formulations)} only]"
        print(line)
    return 0


def parser() -> argparse.ArgumentParser:
    """The command line's parser (importable: the documentation renders it)."""
    p = argparse.ArgumentParser(prog="ancf", description="2D ANCF beams with hyperelastic laws")
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run", help="solve one scene file")
    r.add_argument("scene", help="scene file (TOML)")
    r.add_argument("--json", metavar="OUT", help="write the result record here")
    r.add_argument("--vtk", metavar="DIR", help="write the beam (reference geometry with the displacement as point "
                                                  "data: ParaView's Warp By Vector shows the deformed beam; .vtu per "
                                                  "output time, .pvd) and, for dynamics, a frame strip PNG here")
    r.add_argument("--quiet", action="store_true", help="no progress bar")
    for q in (r, sub.add_parser("elements", help="list the registered elements"),
              sub.add_parser("laws", help="list the registered laws")):
        q.add_argument("--import", dest="imports", action="append", default=[], metavar="MODULE",
                       help="import a module first (one that registers a law or an element)")
    sub.add_parser("formulations", help="list the 2D formulations")
    sub.add_parser("warm", help="compile (or load) the solver's code for every shipped scene and study variant "
                                "into numba's cache (the set-up runs it once per clone)")
    return p


def main(argv: list[str] | None = None) -> int:
    from contract.console import command, import_modules

    args = parser().parse_args(argv)

    def body() -> int:
        import_modules(getattr(args, "imports", ()))
        if args.command == "run":
            return _run(args)
        if args.command == "warm":
            return _warm(args)
        from .elements import ELEMENTS
        from .core.formulations import FORMULATIONS
        from mechanics.laws import LAWS
        return _list({"elements": ELEMENTS, "laws": LAWS, "formulations": FORMULATIONS}[args.command])
    return command("ancf", body)


if __name__ == "__main__":
    sys.exit(main())
