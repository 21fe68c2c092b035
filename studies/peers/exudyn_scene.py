"""Exudyn as an external solver of the harness (:mod:`studies.external`): a harness scene in,
a record out, with Exudyn's ObjectANCFCable2D or ObjectBeamGeometricallyExact2D, the one the
scene's ``ancf.element`` names (runs in `.venv-peers`).

    .venv-peers/bin/python studies/peers/exudyn_scene.py SCENE.toml OUT.json

Declared by ``studies/peers/exudyn.toml`` (the cable) and ``exudyn-beam2d.toml`` (the
geometrically exact beam). The model is :func:`exudyn_model.build`'s (beside this file: the
one place where a scene becomes an Exudyn system, its section law and supports described
there; the peer benchmark's timed runs build theirs the same way); this file solves it and
writes the record. Imports exudyn, numpy, the standard library and :mod:`exudyn_model`, never
``ancf``. Anything outside the model (another support, an end moment on the cable, the
discrete gradient) is left out by the declaration, so the harness skips it with the reason
before calling this.
"""
from __future__ import annotations

import json
import sys
import time
import tomllib
from pathlib import Path

HERE = Path(__file__).resolve().parent


def run(scene: dict) -> dict:
    sys.path.insert(0, str(HERE))
    sys.exudynFast = True
    import exudyn as exu
    import numpy as np
    from exudyn_model import BEAM, build, tip_history

    a, loads = scene["analysis"], scene.get("loads", {})
    L = scene["beam"]["length"]
    gravity, force, moment = loads.get("gravity"), loads.get("tip_force"), loads.get("end_moment")
    model = build(exu, scene)
    mbs, nodes, s, sec, element = model.mbs, model.nodes, model.settings, model.section, model.element
    rec = {"schema": "ancf-harness/record/1", "solver": "exudyn", "status": "failed", "reason": None,
           "tip": None, "ndof": int(mbs.systemData.ODE2Size()), "newton_iterations": None, "load_steps": None,
           "rejected_steps": None, "stable": None, "cpu_s": None, "wall_s": None, "setup_s": None,
           "effects": ["elastic", *(["gravity"] if gravity else []), *(["tip_force"] if force else []),
                       *(["end_moment"] if moment is not None else [])],
           "scene": scene, "exudyn": {"version": exu.__version__, "element": element, **sec}}
    what = "SolveStatic" if a["kind"] == "static" else "SolveDynamic"
    t0, c0 = time.perf_counter(), time.process_time()
    ok = _solve(getattr(mbs, what), s, rec, what)
    rec["wall_s"], rec["cpu_s"] = time.perf_counter() - t0, time.process_time() - c0
    if not ok:
        rec["reason"] = rec["reason"] or f"Exudyn's {what} returned False"
        return rec
    x, y = (float(v) for v in mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Position)[:2])
    q = mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Coordinates)     # displacements from the reference
    # the end face's rotation: the beam's node angle (not wrapped), the cable's slope angle
    rotation = float(q[2]) if element == BEAM else float(np.arctan2(q[3], 1.0 + q[2]))
    rec.update(status="converged", reason=None, tip={"ux": x - L, "uy": y, "rotation": rotation})
    if a["kind"] == "dynamic":
        rec["tip_history"] = tip_history(exu, model, a.get("output_times") or [a["t_end"]])
        rec["steps"] = int(s.timeIntegration.numberOfSteps)
    return rec


def _solve(solve, settings, rec: dict, what: str) -> bool:
    """Exudyn's solver run; its own error (it raises SolverError when Newton gives up) is
    the record's reason, not a traceback."""
    try:
        return bool(solve(settings))
    except Exception as e:                    # exudyn.SolverError is built in its C++ module
        rec["reason"] = f"Exudyn's {what}: {type(e).__name__}: {e}"
        return False


def main(argv: list[str]) -> int:
    scene_path, out = argv
    scene = tomllib.loads(Path(scene_path).read_text())
    Path(out).write_text(json.dumps(run(scene)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
