"""Run one scene with the ANCF solver and produce its record."""
from __future__ import annotations

import time

import numpy as np

from .build import build_model, external_force
from .dynamics import INTEGRATORS
from .record import new_record
from .scene import Scene
from .static import relax, solve_static


def run_scene(scene: Scene, keep_state: bool = False) -> tuple[dict, object]:
    """Solve ``scene``; return (record, solver result). The record follows
    :mod:`ancf.record`: SI units, nulls (never NaN) where a run failed."""
    rec = new_record("ancf", scene.to_dict())
    t0 = time.perf_counter()
    model = build_model(scene)
    if scene.analysis.kind == "dynamic":
        return _run_dynamic(scene, model, rec, t0)
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


def tip_position(model, u) -> np.ndarray:
    """r(L, 0) in m."""
    return np.array([model.mesh.length, 0.0]) + model.tip_displacement(u)


def default_energy_limit(scene: Scene) -> float:
    """1e-3 m |g| L / 2 (J): a thousandth of the pendulum's potential-energy scale; inf
    without gravity."""
    if scene.loads.gravity is None:
        return float("inf")
    b = scene.beam
    m = scene.material.density * b.length * b.height * b.width
    return 1e-3 * m * float(np.hypot(*scene.loads.gravity)) * b.length / 2


def _run_dynamic(scene: Scene, model, rec: dict, t0: float):
    a = scene.analysis
    M = model.mass_matrix()
    f_ext = external_force(model, scene)
    u0 = np.zeros(model.mesh.n_dof)
    if not model.material.formulation.stress_free:
        relaxed = relax(model, a.newton_rtol, a.max_iterations)
        if relaxed.u is None or relaxed.status != "converged":
            rec.update(status="failed", reason=f"relaxation: {relaxed.reason}", effects=sorted(model.effects))
            return rec, (model, None)
        u0 = relaxed.u
    integrator = INTEGRATORS[a.integrator](model, M, f_ext, a.rho_inf, a.newton_rtol, a.max_iterations)
    integrator.initial_state(u0)  # warm caches
    rec["setup_s"] = time.perf_counter() - t0
    limit = a.energy_limit if a.energy_limit is not None else default_energy_limit(scene)
    res = integrator.run(u0, a.t_end, a.dt, a.output_times, a.dt_min, a.tolerance,
                         energy_limit=None if limit == float("inf") else limit)
    rec.update(
        status=res.status, reason=res.reason, ndof=model.n_free,
        newton_iterations=res.newton_iterations, steps=res.steps, rejected_steps=res.rejected_steps,
        cpu_s=res.cpu_s, wall_s=res.wall_s, effects=sorted(model.effects),
        energy_limit=limit,
        integrator={"name": a.integrator, "rho_inf": a.rho_inf,
                    **{k: getattr(integrator, k) for k in ("alpha_m", "alpha_f", "gamma", "beta")}},
    )
    rec["tip_history"] = [dict(zip(("t", "x", "y"), (s.t, *tip_position(model, s.u)))) for s in res.states]
    rec["configurations"] = []
    for s in res.states:
        line = model.centre_line(s.u, per_element=4)
        rec["configurations"].append({"t": s.t, "x": line[:, 0].tolist(), "y": line[:, 1].tolist()})
    rec["energy"] = []
    for s in res.states:
        k, e, g = integrator.energies(s)
        rec["energy"].append({"t": s.t, "kinetic": k, "strain": e, "gravity": g, "total": k + e + g})
    if res.states:
        ux, uy = model.tip_displacement(res.states[-1].u)
        rec["tip"] = {"ux": float(ux), "uy": float(uy)}
    return rec, (model, res)
