"""Run one scene with the ANCF solver and produce its record."""
from __future__ import annotations

import os
import time

import numpy as np

from contract.record import new_record
from contract.scene import Scene
from mechanics.time_loop import energy_limit, integrate, record_keys

from .build import Plan, Run, build, plan
from .solvers.statics import relax, solve_static


# Below this many unknowns a run uses one BLAS thread: the band (b <= 15) leaves a thread
# pool nothing to share out, only its start-up and hand-over costs.
ONE_THREAD_BELOW = 20000
THREAD_VARS = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")


def run_scene(scene: Scene | Plan, progress=None) -> tuple[dict, object]:
    """Solve ``scene`` (or a :class:`ancf.build.Plan` of it: a scene is planned here, once);
    return (record, (model, solver result)). The record follows :mod:`contract.record`: SI
    units, nulls (never NaN) where a run failed. ``progress(t, result)``: called after every
    accepted time step (dynamics). A small scene runs with one BLAS thread unless the caller
    set a thread count (the ``ancf`` command and the study runner set one before numpy loads)."""
    p = scene if isinstance(scene, Plan) else plan(scene)
    if any(v in os.environ for v in THREAD_VARS) or p.estimate.unknowns >= ONE_THREAD_BELOW:
        return _run_scene(p, progress)
    from threadpoolctl import threadpool_limits
    with threadpool_limits(1):
        return _run_scene(p, progress)


def _run_scene(p: Plan, progress=None) -> tuple[dict, object]:
    scene = p.scene
    rec = new_record("ancf", scene.to_dict())
    rec["quadrature"] = list(p.rule)
    if p.warnings:
        rec["warnings"] = p.warnings
    t0 = time.perf_counter()
    run = build(p)
    if scene.analysis.kind == "dynamic":
        return _run_dynamic(run, rec, t0, progress)
    model, loading, effects = run.model, run.loading, run.effects
    model.internal_force_and_tangent(np.zeros(model.mesh.n_dof))  # tabulate, warm caches
    rec["setup_s"] = time.perf_counter() - t0
    a = scene.analysis
    res = solve_static(model, loading, a.load_steps, a.newton_rtol, a.max_iterations, a.wall_time)
    rec.update(
        status=res.status, reason=res.reason, ndof=model.n_free,
        newton_iterations=res.newton_iterations, load_steps=res.load_steps,
        relax_steps=res.relax_steps, rejected_steps=res.rejected_steps,
        stable=res.stable, stability=res.stability, negative_eigenvalues=res.negative_eigenvalues,
        lowest_eigenvalue=res.lowest_eigenvalue,
        cpu_s=res.cpu_s, wall_s=res.wall_s,
        effects=sorted(effects),
    )
    if res.u is not None:
        ux, uy = model.tip_displacement(res.u)
        rec["tip"] = {"ux": float(ux), "uy": float(uy)}
        if res.rotation is not None:
            rec["tip"]["rotation"] = float(res.rotation)       # of the end face, rad (contract.loads)
        # two stable equilibria of one scene (a load path may reach either) are told apart
        # by this: the lower total potential is the better answer
        rec["potential_energy"] = float(model.strain_energy(res.u) + loading.potential(res.u, res.rotation))
    if not np.any(loading.Q[np.setdiff1d(np.arange(model.mesh.n_dof), model.fixed)]) and not loading.has_couple:
        rec["note"] = ("no load: an unloaded static scene is valid, its answer is the "
                       + ("reference state" if model.material.formulation.stress_free else "relaxed state"))
    return rec, (model, res)


def _run_dynamic(run: Run, rec: dict, t0: float, progress=None):
    scene, model, integrator = run.plan.scene, run.model, run.integrator
    a = scene.analysis
    u0 = np.zeros(model.mesh.n_dof)
    rec.update(effects=sorted(run.effects), ndof=model.n_free)
    if not model.material.formulation.stress_free:
        relaxed = relax(model, a.newton_rtol, a.max_iterations, a.wall_time)
        if relaxed.u is None or relaxed.status != "converged":
            rec.update(status="failed", reason=f"relaxation: {relaxed.reason}")
            return rec, (model, None)
        u0 = relaxed.u
    integrator.warm(u0)  # load compiled code before the solve timer
    rec["setup_s"] = time.perf_counter() - t0
    limit = energy_limit(scene)
    res = integrate(integrator, u0, a.t_end, a.dt, a.output_times, a.dt_min, a.tolerance,
                    energy_limit=None if limit == float("inf") else limit, energy_check_every=1,
                    max_steps=a.max_steps,
                    wall_time=a.wall_time, progress=progress)
    rec.update(record_keys(res, integrator.describe(), limit, scene.beam.length))
    return rec, (model, res)
