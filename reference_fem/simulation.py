"""Run one scene with the continuum reference and produce its record.

Two backends (``[fem] backend``): DOLFINx (default, :mod:`reference_fem.dolfinx_backend`)
and FElupe (:mod:`reference_fem.felupe_backend`); each offers a static model of the scene
(:func:`backend`: its Newton system, load parameter, unknowns, effects, point
displacement, output) that one driver runs with the shared load stepping
(:func:`reference_fem.statics.solve_static`), and a dynamic problem (one time step's
equations, the start, energies, point positions, output) that one stepper
(:class:`reference_fem.stepper.ContinuumStepper`) drives through the one time loop; the
record is the same but for the version key (``dolfinx`` or ``felupe``) and ``fem.backend``
(given for "felupe" only).

The record is :func:`contract.record.new_record` (labelled with the backend that ran: "dolfinx", "felupe") with the same keys as an
ANCF run, plus ``continuum_model`` ("plane-strain" | "plane-stress" | "3d"),
``incompressibility`` ("mixed" | "penalty" | "exact") and ``fem`` (the resolved
discretisation: cells, cell type, degree, quadrature degree) and ``dolfinx``
(version). ``ndof`` counts the unknowns of the solve (displacement and pressure
degrees of freedom minus those the supports fix or, for the hinge, eliminate), like
ancf's free dofs. A scene with an end moment adds ``tip.rotation`` (rad, the end face's
theta continued along the load path) and ``end_moment`` (how the couple is applied); a
hinged one ``pin`` (how the hinge is modelled, as in dynamic records). ``setup_s``
is meshing and JIT compilation, apart from the solve. The 3D model adds ``tip_uz`` (m,
the lateral displacement of the free-end face centre: zero by symmetry on hexahedra)
and ``mpi_ranks``; under ``mpiexec`` every rank computes the same record and the
command line writes it from rank 0.

Dynamic scenes (``analysis.kind = "dynamic"``) add the dynamic keys of the one time
loop (:func:`mechanics.time_loop.record_keys`, the same as ``ancf run``'s): ``tip_history``
[{t, x, y}] (position of the free-end centre point at the output times),
``configurations``, ``energy`` [{t, kinetic, strain, gravity, total}] (J, full beam),
``steps``, ``rejected_steps``, ``newton_iterations``, ``integrator`` (name, rho_inf,
coefficients) and ``energy_limit``; ``pin`` says how the support is modelled
(:func:`reference_fem.geometry.support_note`). The
continuum models are stress-free at the reference: the motion starts from the
undeformed beam at rest.
"""
from __future__ import annotations

import time
from pathlib import Path

from contract.console import safe_name
from contract.errors import SceneError
from contract.record import new_record
from contract.scene import FORMULATIONS, Scene, check_names

from .settings import FemSettings, fem_settings


def check(scene: Scene) -> FemSettings:
    """The scene's names against reference_fem's vocabulary, and its [fem] table
    resolved (one message naming the field and the allowed values)."""
    from .stepper import alpha_family
    from mechanics.laws import LAWS

    check_names(scene, laws=LAWS,
                formulations=FORMULATIONS, integrators=alpha_family())
    return fem_settings(scene)


# Peak memory of a run: the interpreter with dolfinx (~170 MB), plus MUMPS's LU of the
# N unknowns: ~2.6 kB per unknown measured in 2D (256 x 16 Q2/Q1: 38161 unknowns,
# 259 MB peak; 64 x 4: 168 MB); the model takes 4 kB x N x max(1, log2(N / 1e4)) in 2D
# (nested dissection fill ~ N log N) and BYTES_3D x N^(4/3) in 3D.
BASE_BYTES = 170e6
BYTES_2D = 4e3
BYTES_3D = 400.0


def estimate(scene: Scene, settings: FemSettings | None = None):
    """Unknowns, peak memory and time steps of the scene's continuum run, without
    building it (see the constants above)."""
    import math

    from contract.capacity import Estimate

    s = settings or check(scene)
    gdim = s.geometry.gdim
    cells = s.cells(gdim)
    n = gdim * math.prod(s.degree * c + 1 for c in cells)
    if s.has_pressure:
        n += math.prod((s.degree - 1) * c + 1 for c in cells)
    if gdim == 2:
        mem = BASE_BYTES + BYTES_2D * n * max(1.0, math.log2(n / 1e4))
    else:
        mem = BASE_BYTES + BYTES_3D * n ** (4 / 3)
    a = scene.analysis
    steps = math.ceil(a.t_end / a.dt) if a.kind == "dynamic" else None
    return Estimate(n, mem, steps, "fem.cells_length / cells_height / degree")


def capacity(scene: Scene, settings: FemSettings | None = None) -> list[str]:
    """Refuse a scene that cannot fit in this machine's memory (SceneError); warnings."""
    from contract.capacity import check_capacity

    return check_capacity(estimate(scene, settings), "reference_fem")


def check_static(scene: Scene) -> None:
    if scene.analysis.kind != "static":
        raise SceneError(f"analysis.kind: {scene.analysis.kind!r}: refinement studies are "
                         "static only (dynamic scenes: `run`, `pendulum`); allowed: 'static'")


def backend(name: str):
    """The backend of ``[fem] backend`` (:data:`reference_fem.backends.BACKENDS`):
    ``version()``, ``static_model(scene, settings)``, an object with the Newton system
    (``system``, driven by :func:`reference_fem.statics.solve_static`), ``set_load(t)``,
    ``n_free``, ``effects``, ``ranks``, ``displacement(point)`` and ``write(path, fmt)``,
    and ``dynamic_model(scene, settings)``, an object with what
    :class:`reference_fem.stepper.ContinuumStepper` steps (see there) and ``n_dof``,
    ``n_free``, ``effects``, ``geometry`` and ``write(path, fmt, w, t)``."""
    from .backends import get_backend

    return get_backend(name)


def _record(scene: Scene, settings: FemSettings) -> dict:
    rec = new_record(settings.backend, scene.to_dict())      # labelled with what ran
    rec.update(continuum_model=settings.model, incompressibility=settings.incompressibility,
               fem=settings.to_dict())
    rec[settings.backend] = backend(settings.backend).version()
    warnings = capacity(scene, settings)
    if warnings:
        rec["warnings"] = warnings
    return rec


def run_scene(scene: Scene, settings: FemSettings | None = None, output: Path | None = None,
              output_format: str = "vtk", progress=None) -> dict:
    """Solve ``scene`` (with ``settings`` overriding its [fem] table, e.g. in a
    refinement study); return the record. ``output``: write the mesh and its
    displacement there; ``progress(t, result)``: after every accepted time step."""
    checked = check(scene)
    settings = settings or checked
    if scene.analysis.kind == "dynamic":
        return run_dynamic(scene, settings, output=output, output_format=output_format, progress=progress)
    from .statics import solve_static

    rec = _record(scene, settings)
    t0 = time.perf_counter()
    model = backend(settings.backend).static_model(scene, settings)
    rec["setup_s"] = time.perf_counter() - t0
    a = scene.analysis
    res = solve_static(model.system, model.set_load, a.load_steps, a.newton_rtol,
                       a.max_iterations, a.wall_time)
    if settings.geometry.gdim == 3:
        rec["mpi_ranks"] = model.ranks
    rec.update(status=res.status, reason=res.reason, ndof=model.n_free,
               newton_iterations=res.newton_iterations, load_steps=res.load_steps,
               rejected_steps=res.rejected_steps, cpu_s=res.cpu_s, wall_s=res.wall_s,
               effects=sorted(model.effects), load_reached=res.t_reached)
    if res.unloaded:
        rec["note"] = "no load: an unloaded static scene is valid, its answer is the reference state"
    _notes(rec, scene, settings.geometry, model)
    if hasattr(model, "admissibility"):
        # det F over the cells of the final (or last accepted) state: an inverted cell hides
        # between the quadrature points (the clamp's compressed corner under the hard loads)
        rec["admissibility"] = model.admissibility()
        if rec["admissibility"]["det_F"] <= 0:
            rec.setdefault("warnings", []).append(
                f"inverted cell: det F = {rec['admissibility']['det_F']:.3g} at "
                f"({', '.join(f'{1e3 * c:.3g}' for c in rec['admissibility']['at'])}) mm (between the quadrature points)")
    if res.status == "converged" and not res.unloaded and hasattr(model.system, "unstable_directions"):
        # Newton does not see stability: past a bifurcation it converges as readily to the
        # unstable branch (512 x 16 cells at 20 N: one unstable direction, the compressed face
        # at the clamp); one LDL^T factorization tells
        rec["unstable_directions"] = model.system.unstable_directions()
        if rec["unstable_directions"] is not None and rec["unstable_directions"] > 0:
            rec.setdefault("warnings", []).append(
                f"unstable equilibrium: the tangent has {rec['unstable_directions']} unstable direction(s)")
    if res.status != "converged" and res.last_failure is not None and hasattr(model, "diagnose"):
        # the path failed: from the last accepted state toward the failed increment's load
        t1 = res.last_failure[0]
        rec["failure"] = {"t": t1, **model.diagnose(t1)}
        f = rec["failure"]
        if (f["unstable_directions"] or 0) > 0:
            rec["reason"] += (f"; the tangent turns indefinite on the way ({f['unstable_directions']} unstable "
                              f"direction(s): a critical point of the load path), Newton's corrections peak at "
                              f"({', '.join(f'{1e3 * c:.3g}' for c in f['correction_peak'])}) mm")
    if res.status == "converged":
        u = model.displacement(settings.geometry.tip_point(scene.beam))
        rec["tip"] = {"ux": float(u[0]), "uy": float(u[1])}
        if scene.loads.end_moment is not None:
            rec["tip"]["rotation"] = float(model.rotation())
        if len(u) == 3:
            rec["tip_uz"] = float(u[2])
        if output is not None:
            rec["output"] = str(model.write(Path(output) / safe_name(scene.name), output_format))
    return rec


def _notes(rec: dict, scene: Scene, geometry, model) -> None:
    """How a static record's hinge (``pin``) and end moment (``end_moment``: the shared
    definition and the backend's method) are modelled; records of other scenes keep their
    keys."""
    from .geometry import END_MOMENT_NOTE, support_note

    if scene.supports.left == "hinge":
        rec["pin"] = support_note("hinge", geometry)
    if scene.loads.end_moment is not None:
        rec["end_moment"] = f"{END_MOMENT_NOTE}; {model.end_moment_method}"


def run_dynamic(scene: Scene, settings: FemSettings, output: Path | None = None,
                output_format: str = "vtk", energy_every_step: bool = False,
                energy_limit: float | None = None, progress=None) -> dict:
    """Integrate a dynamic scene; the record has the keys of ``ancf run``'s dynamic records.
    ``energy_limit``: overrides the scene's (or the default) limit."""
    import numpy as np

    from mechanics.time_loop import energy_limit as scene_energy_limit
    from mechanics.time_loop import integrate, record_keys

    from .geometry import support_note
    from .stepper import ContinuumStepper

    a = scene.analysis
    rec = _record(scene, settings)
    t0 = time.perf_counter()
    problem = backend(settings.backend).dynamic_model(scene, settings)
    rec["pin"] = support_note(scene.supports.left, problem.geometry)
    stepper = ContinuumStepper(problem, a.integrator, a.rho_inf, a.newton_rtol, a.max_iterations, scene.beam)
    rec["setup_s"] = time.perf_counter() - t0
    limit = energy_limit if energy_limit is not None else scene_energy_limit(scene)
    res = integrate(stepper, np.zeros(problem.n_dof), a.t_end, a.dt, a.output_times, a.dt_min,
                    a.tolerance, energy_limit=None if limit == float("inf") else limit,
                    energy_every_step=energy_every_step, max_steps=a.max_steps, wall_time=a.wall_time,
                    progress=progress)
    rec.update(ndof=problem.n_free, effects=sorted(problem.effects + ["inertia"]),
               **record_keys(res, stepper.describe(), limit, scene.beam.length))
    if energy_every_step:
        rec["energy_steps"] = [e.to_dict(t) for t, e in res.energy_steps]
    if output is not None and res.final is not None:
        rec["output"] = str(problem.write(Path(output) / safe_name(scene.name), output_format,
                                          res.final.u, res.final.t))
    return rec
