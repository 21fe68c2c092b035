"""``ancf`` command line: ``ancf run SCENE.toml [--json OUT.json]``, ``ancf elements``,
``ancf laws``."""
from __future__ import annotations

import argparse
import sys
import time

T_IMPORT = time.perf_counter()


def _run(args) -> int:
    from contract.record import sanitize, write_record
    from contract.scene import load_scene

    from .run import run_scene

    scene = load_scene(args.scene)
    rec, (model, res) = run_scene(scene)
    rec = sanitize(rec)
    if args.json:
        write_record(rec, args.json)
    if args.vtk and res is not None and getattr(res, "u", True) is not None:
        from .output import frame_strip, write_vtk
        states = ([(o.t, o.state.u) for o in res.outputs] if scene.analysis.kind == "dynamic"
                  else [(0.0, res.u)])
        pvd = write_vtk(model, states, args.vtk, scene.name)
        extra = ""
        if rec.get("configurations"):
            extra = f" and {frame_strip(rec['configurations'], pvd.with_name(scene.name + '-frames.png'), scene.name)}"
        print(f"vtk         {pvd}{extra}")
    print(f"scene       {scene.name}  ({scene.ancf.element} x {scene.ancf.elements}, "
          f"{scene.material.law}, {scene.material.formulation}, ndof {rec['ndof']})")
    print(f"status      {rec['status']}" + (f"  ({rec['reason']})" if rec["reason"] else ""))
    if rec["tip"]:
        print(f"tip         ux = {rec['tip']['ux'] * 1e3:.4f} mm   uy = {rec['tip']['uy'] * 1e3:.4f} mm")
    if scene.analysis.kind == "static":
        print(f"newton      {rec['newton_iterations']} iterations, {rec['load_steps']} load steps "
              f"({rec['relax_steps']} relaxation), {rec['rejected_steps']} rejected")
        print(f"stable      {rec['stable']}" + (f"  ({rec['stability']})" if rec.get("stability") else ""))
    else:
        print(f"steps       {rec['steps']} accepted, {rec['rejected_steps']} rejected, "
              f"{rec['newton_iterations']} Newton iterations ({scene.analysis.integrator}, "
              f"rho_inf {scene.analysis.rho_inf})")
        for h, e in zip(rec.get("tip_history") or [], rec.get("energy") or []):
            print(f"  t = {h['t']:.4f} s   tip ({h['x'] * 1e3:9.3f}, {h['y'] * 1e3:9.3f}) mm   "
                  f"E = {e['total']:+.3e} J (kinetic {e['kinetic']:.3e}, strain {e['strain']:.3e})")
    print(f"time        solve {rec['wall_s']:.3f} s wall, {rec['cpu_s']:.3f} s cpu; set-up {rec['setup_s']:.3f} s "
          f"(plus {time.perf_counter() - T_IMPORT - rec['wall_s'] - rec['setup_s']:.2f} s imports and output)")
    print(f"effects     {', '.join(rec['effects'])}")
    return 0 if rec["status"] == "converged" else 1


def _list(registry: dict) -> int:
    for name, item in registry.items():
        print(f"{name:16s} {getattr(item, 'reference', '') or getattr(item, 'doc', '')}")
    return 0


def main(argv: list[str] | None = None) -> int:
    from contract.errors import SceneError

    p = argparse.ArgumentParser(prog="ancf", description="2D ANCF beams with hyperelastic laws")
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run", help="solve one scene file")
    r.add_argument("scene", help="scene file (TOML)")
    r.add_argument("--json", metavar="OUT", help="write the result record here")
    r.add_argument("--vtk", metavar="DIR", help="write the deformed beam (.vtu per output time, .pvd) "
                                                  "and, for dynamics, a frame strip PNG here")
    sub.add_parser("elements", help="list the registered elements")
    sub.add_parser("laws", help="list the registered laws")
    sub.add_parser("formulations", help="list the 2D formulations")
    args = p.parse_args(argv)
    try:
        if args.command == "run":
            return _run(args)
        from .elements import ELEMENTS
        from .formulations import FORMULATIONS
        from .laws import LAWS
        return _list({"elements": ELEMENTS, "laws": LAWS, "formulations": FORMULATIONS}[args.command])
    except SceneError as e:
        print(f"ancf: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
