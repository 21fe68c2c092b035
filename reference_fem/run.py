"""Run one scene with the continuum reference and produce its record.

The record is :func:`ancf.record.new_record` ("fenicsx") with the same keys as an
ANCF run, plus ``continuum_model`` ("plane-strain" | "plane-stress"),
``incompressibility`` ("mixed" | "penalty" | "exact") and ``fem`` (the resolved
discretisation: cells, cell type, degree, quadrature degree) and ``dolfinx``
(version). ``ndof`` counts the unknowns of the solve (displacement and pressure
degrees of freedom minus those the supports fix), like ancf's free dofs. ``setup_s``
is meshing and JIT compilation, apart from the solve.

Dynamic scenes (``analysis.kind = "dynamic"``) add the keys of ``ancf run``'s dynamic
records: ``tip_history`` [{t, x, y}] (position of the free-end centre point (L, 0) at
the output times; pin at the origin, beam along +x at t = 0), ``energy`` [{t,
kinetic, strain, gravity, total}] (J, full width, gravity potential -int rho g . r dV),
``steps``, ``rejected_steps``, ``newton_iterations`` and ``integrator`` (name, rho_inf,
coefficients); ``pin`` says how the support is modelled (see
:mod:`reference_fem.dynamic_problem`). The continuum models are stress-free at the
reference: the motion starts from the undeformed beam at rest.
"""
from __future__ import annotations

import time
from pathlib import Path

from ancf.errors import SceneError
from ancf.record import new_record
from ancf.scene import Scene

from .settings import FemSettings, fem_settings


def check_static(scene: Scene) -> None:
    if scene.analysis.kind != "static":
        raise SceneError(f"analysis.kind: {scene.analysis.kind!r}: refinement studies are "
                         "static only (dynamic scenes: `run`, `pendulum`); allowed: 'static'")


def run_scene(scene: Scene, settings: FemSettings | None = None, output: Path | None = None,
              output_format: str = "vtk") -> dict:
    """Solve ``scene`` (with ``settings`` overriding its [fem] table, e.g. in a
    refinement study); return the record. ``output``: write the deformed mesh there."""
    settings = settings or fem_settings(scene)
    if scene.analysis.kind == "dynamic":
        return run_dynamic(scene, settings, output=output, output_format=output_format)
    check_static(scene)
    from . import dolfinx_backend as backend
    from .newton import solve_static
    from .problem import build_beam_problem

    rec = new_record("fenicsx", scene.to_dict())
    rec.update(continuum_model=settings.model, incompressibility=settings.incompressibility,
               fem=settings.to_dict(), dolfinx=backend.VERSION)
    t0 = time.perf_counter()
    problem = build_beam_problem(scene, settings)
    rec["setup_s"] = time.perf_counter() - t0
    a = scene.analysis
    res = solve_static(problem.system, problem.set_load, a.load_steps, a.newton_rtol,
                       a.max_iterations)
    rec.update(status=res.status, reason=res.reason, ndof=problem.n_free,
               newton_iterations=res.newton_iterations, load_steps=res.load_steps,
               rejected_steps=res.rejected_steps, cpu_s=res.cpu_s, wall_s=res.wall_s,
               effects=sorted(problem.effects), load_reached=res.t_reached)
    if res.status == "converged":
        ux, uy = problem.disc.point_displacement([[scene.beam.length, 0.0]])[0]
        rec["tip"] = {"ux": float(ux), "uy": float(uy)}
        if output is not None:
            rec["output"] = str(problem.disc.write(Path(output) / scene.name, output_format,
                                                   scale=problem.pressure_scale))
    return rec



PIN = ("the node at the centre (0, 0) of the left face: both displacement components "
       "zero there; the face is otherwise free to rotate and deform")


def run_dynamic(scene: Scene, settings: FemSettings, output: Path | None = None,
                output_format: str = "vtk", energy_every_step: bool = False,
                energy_limit: float | None = None, progress=None) -> dict:
    """Integrate a dynamic scene; the record has the keys of ``ancf run``'s dynamic records."""
    import numpy as np

    from . import dolfinx_backend as backend
    from .dynamic_problem import build_dynamic_problem
    from .dynamics import Integrator, coefficients

    a = scene.analysis
    coef = coefficients(a.integrator, a.rho_inf)   # refuses unknown methods before meshing
    rec = new_record("fenicsx", scene.to_dict())
    rec.update(continuum_model=settings.model, incompressibility=settings.incompressibility,
               fem=settings.to_dict(), dolfinx=backend.VERSION,
               pin=PIN if scene.supports.left == "pin" else "clamp: the whole face x = 0 fixed")
    t0 = time.perf_counter()
    problem = build_dynamic_problem(scene, settings)
    integrator = Integrator(problem, a.integrator, a.rho_inf, a.newton_rtol, a.max_iterations)
    rec["setup_s"] = time.perf_counter() - t0
    res = integrator.run(np.zeros(problem.n_dof), a.t_end, a.dt, a.output_times, a.dt_min,
                         a.tolerance, energy_limit=energy_limit,
                         energy_every_step=energy_every_step, progress=progress)
    rec.update(status=res.status, reason=res.reason, ndof=problem.n_free,
               newton_iterations=res.newton_iterations, steps=res.steps,
               rejected_steps=res.rejected_steps, cpu_s=res.cpu_s, wall_s=res.wall_s,
               effects=sorted(problem.effects),
               integrator={"name": a.integrator, "rho_inf": a.rho_inf, **coef})
    rec["tip_history"] = [{"t": o.t, "x": o.tip[0], "y": o.tip[1]} for o in res.outputs]
    rec["configurations"] = [{"t": o.t, "x": o.line[:, 0].tolist(), "y": o.line[:, 1].tolist()}
                             for o in res.outputs if o.line is not None]
    rec["energy"] = [{"t": o.t, "kinetic": o.energy[0], "strain": o.energy[1],
                      "gravity": o.energy[2], "total": sum(o.energy)} for o in res.outputs]
    if energy_every_step:
        rec["energy_steps"] = [{"t": e[0], "kinetic": e[1], "strain": e[2], "gravity": e[3],
                                "total": sum(e[1:])} for e in res.energy_steps]
    if res.outputs and res.status == "converged":
        x, y = res.outputs[-1].tip
        rec["tip"] = {"ux": x - scene.beam.length, "uy": y}
    if output is not None and res.final is not None:
        problem.disc.w.x.array[:] = res.final.u
        rec["output"] = str(problem.disc.write(Path(output) / scene.name, output_format,
                                               scale=problem.pressure_scale, t=res.final.t))
    return rec
