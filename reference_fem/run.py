"""Run one scene with the continuum reference and produce its record.

The record is :func:`ancf.record.new_record` ("fenicsx") with the same keys as an
ANCF run, plus ``continuum_model`` ("plane-strain" | "plane-stress"),
``incompressibility`` ("mixed" | "penalty" | "exact") and ``fem`` (the resolved
discretisation: cells, cell type, degree, quadrature degree) and ``dolfinx``
(version). ``ndof`` counts the unknowns of the solve (displacement and pressure
degrees of freedom minus those the supports fix), like ancf's free dofs. ``setup_s``
is meshing and JIT compilation, apart from the solve.
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
        raise SceneError(f"analysis.kind: {scene.analysis.kind!r} is not available yet in "
                         "reference_fem; allowed: 'static'")


def run_scene(scene: Scene, settings: FemSettings | None = None, output: Path | None = None,
              output_format: str = "vtk") -> dict:
    """Solve ``scene`` (with ``settings`` overriding its [fem] table, e.g. in a
    refinement study); return the record. ``output``: write the deformed mesh there."""
    check_static(scene)
    settings = settings or fem_settings(scene)
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

