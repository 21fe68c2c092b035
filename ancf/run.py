"""Run one scene with the ANCF solver and produce its record."""
from __future__ import annotations

import time

from .build import build_model, external_force
from .errors import SceneError
from .record import new_record
from .scene import Scene
from .static import solve_static


def run_scene(scene: Scene, keep_state: bool = False) -> tuple[dict, object]:
    """Solve ``scene``; return (record, solver result). The record follows
    :mod:`ancf.record`: SI units, nulls (never NaN) where a run failed."""
    rec = new_record("ancf", scene.to_dict())
    t0 = time.perf_counter()
    model = build_model(scene)
    if scene.analysis.kind != "static":
        raise SceneError("analysis.kind: \"dynamic\" is not available in this version of ancf; "
                         "allowed: \"static\"")
    f_ext = external_force(model, scene)
    model.internal_force_and_tangent(model.mesh.reference * 0.0)  # tabulate, warm caches
    rec["setup_s"] = time.perf_counter() - t0
    a = scene.analysis
    res = solve_static(model, f_ext, a.load_steps, a.newton_rtol, a.max_iterations)
    rec.update(
        status=res.status, reason=res.reason, ndof=model.n_free,
        newton_iterations=res.newton_iterations, load_steps=res.load_steps,
        relax_steps=res.relax_steps, rejected_steps=res.rejected_steps,
        stable=res.stable, stability=res.stability, cpu_s=res.cpu_s, wall_s=res.wall_s,
        effects=sorted(model.effects),
    )
    if res.u is not None:
        ux, uy = model.tip_displacement(res.u)
        rec["tip"] = {"ux": float(ux), "uy": float(uy)}
    return rec, (model, res)
