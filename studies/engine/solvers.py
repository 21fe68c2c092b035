"""The solvers a case can name: how to check a scene, run it, and what a record of it
depends on.

Each solver is one entry of :data:`SOLVERS`; ``run(scene_dict) -> record`` returns the
solver's record (``contract.record`` schema, SI units) and ``check(scene_dict)`` raises a
SceneError for a scene it cannot run. What a record depends on is the solver's
fingerprint (:meth:`Solver.fingerprint`, :mod:`studies.engine.fingerprint`): the code
its run function reaches, normalised, and the packages that code imports:

- ``ancf``: the ANCF solver (``ancf/``, and what it imports of ``mechanics/`` and
  ``contract/``);
- ``ancf-effects``: the ANCF solver, then the cost of each effect's assembly (the study
  ``effects``);
- ``ancf-cold``: the ANCF solver in a fresh process with an empty numba cache (Table 4's
  first-run cost, compiling included);
- ``fenicsx``: the continuum reference, with the backend its scene names (DOLFINx or
  FElupe; not the other one);
- ``mms``: the manufactured solutions of one continuum code;
- ``ancf-material``: the ANCF material at one deformation gradient (the benchmarks'
  material-point cases).

Adding a solver (e.g. a dynamic integrator living in another package) is one entry here.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from . import fingerprint as fp

ROOT = Path(__file__).resolve().parents[2]


def _run_ancf(scene: dict) -> dict:
    from ancf.simulation import run_scene
    from contract.scene import scene_from_dict

    rec, _ = run_scene(scene_from_dict(scene))
    return rec


EFFECT_REPEATS = 7   # timed repeats of each assembly (median and spread), after one warm-up


def _median_spread(f, repeats: int = EFFECT_REPEATS) -> dict:
    import statistics
    import time

    f()
    ts = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        f()
        ts.append(time.perf_counter() - t0)
    return {"median_s": statistics.median(ts), "min_s": min(ts), "max_s": max(ts), "repeats": repeats}


def _paired(as_is, with_extra, repeats: int = 2 * EFFECT_REPEATS + 1) -> dict:
    """The two variants run alternately (a warm-up each, then A B A B ...) so that a
    busy machine slows both alike: each one's median and spread, and the median of the
    paired differences B - A."""
    import statistics
    import time

    as_is(), with_extra()
    a, b = [], []
    for _ in range(repeats):
        for f, ts in ((as_is, a), (with_extra, b)):
            t0 = time.perf_counter()
            f()
            ts.append(time.perf_counter() - t0)
    summary = lambda ts: {"median_s": statistics.median(ts), "min_s": min(ts), "max_s": max(ts), "repeats": repeats}
    return {"static_solve": summary(a), "static_solve_with_mass_matrix": summary(b),
            "mass_matrix_paired_difference": summary([y - x for x, y in zip(a, b)])}


def _run_ancf_effects(scene: dict) -> dict:
    """A static ANCF scene solved as it is, then what each effect costs when it is
    assembled, measured in the same process (median of EFFECT_REPEATS after a warm-up):
    the whole static solve as is; the same followed by the mass matrix (inertia assembled
    but unused by a static scene); one internal force + tangent at the converged state
    (elastic law, and the penalty term where the formulation has one); the mass matrix;
    each load vector the scene names (gravity, tip force). The record is the solver's own,
    with ``effect_costs``."""
    import numpy as np

    from ancf.build import build_model
    from ancf.simulation import run_scene
    from contract.scene import scene_from_dict

    sc = scene_from_dict(scene)
    rec, (model, res) = run_scene(sc)
    if rec.get("status") != "converged":
        return rec
    u = res.u if res.u is not None else np.zeros(model.mesh.n_dof)
    costs = _paired(lambda: run_scene(sc), lambda: run_scene(sc)[1][0].mass_matrix())
    costs["build_model"] = _median_spread(lambda: build_model(sc))
    costs["tangent"] = _median_spread(lambda: model.internal_force_and_tangent(u))
    costs["mass_matrix"] = _median_spread(model.mass_matrix)
    if sc.loads.gravity is not None:
        costs["gravity"] = _median_spread(lambda: model.gravity_force(sc.loads.gravity))
    if sc.loads.tip_force is not None:
        costs["tip_force"] = _median_spread(lambda: model.tip_force(sc.loads.tip_force))
    rec["effect_costs"] = costs
    return rec


def _run_fenicsx(scene: dict) -> dict:
    from contract.scene import scene_from_dict
    from reference_fem.simulation import run_scene

    return run_scene(scene_from_dict(scene))


def _warm_ancf(scene: dict) -> None:
    from ancf.warm import load
    from contract.scene import scene_from_dict

    load(scene_from_dict(scene))


def _check_ancf(scene: dict) -> None:
    from ancf.build import capacity
    from contract.scene import scene_from_dict

    capacity(scene_from_dict(scene))


def _check_fenicsx(scene: dict) -> None:
    from contract.scene import scene_from_dict
    from reference_fem.simulation import check

    check(scene_from_dict(scene))


def _fem_backend(scene: dict) -> str:
    return (scene.get("fem") or {}).get("backend", "dolfinx")


def _mms_code(scene: dict) -> str:
    return (scene.get("mms") or {}).get("code", "dolfinx")


@dataclass(frozen=True)
class Solver:
    name: str
    run: Callable[[dict], dict]  # scene dict -> record
    check: Callable[[dict], None]
    # modules the run reaches without importing them (code run in a fresh process)
    also: tuple[str, ...] = ()
    # the continuum backend a scene names, for a solver that has several
    backend: Callable[[dict], str] | None = None
    # the warm-up of a timed case (scene dict -> None): load what its runs need without a
    # full run (None: a full run warms)
    warm: Callable[[dict], None] | None = None

    def entries(self, scene: dict, options: dict | None = None) -> tuple[list[str], str | None]:
        """(where a run of ``scene`` starts, the continuum backend it uses): the run
        function, the backend's package for a continuum scene, and for a case launched on
        MPI ranks the launcher and the command line it runs."""
        backend = self.backend(scene) if self.backend else None
        entries = [fp.entry(self.run), *self.also]
        if backend in fp.BACKENDS:
            entries.append(fp.BACKENDS[backend])
        if (options or {}).get("mpi_ranks"):
            entries += ["studies.engine.worker:_run_launched", "reference_fem.__main__"]
        return entries, backend

    def fingerprint(self, scene: dict, options: dict | None = None) -> dict:
        """{"code": hash, "packages": {name: version}} of what a run of ``scene`` executes
        (:meth:`entries`, :func:`studies.engine.fingerprint.fingerprint`)."""
        return fp.fingerprint(*self.entries(scene, options))


_COLD_RUN = ("import json, sys, time; t0 = time.perf_counter(); "
             "from ancf.simulation import run_scene; from contract.scene import scene_from_dict; "
             "rec, _ = run_scene(scene_from_dict(json.load(sys.stdin))); "
             "rec['process_s'] = time.perf_counter() - t0; print(json.dumps(rec))")


def _run_ancf_cold(scene: dict) -> dict:
    """The ANCF solver in a fresh Python process with an empty numba cache (a new
    NUMBA_CACHE_DIR): what a user's first run after installing pays, compiling included.
    The record is the solver's own, with ``cold`` = {"process_s": wall time of the whole
    process (interpreter start, imports, compile, build, solve), "import_build_solve_s":
    the same from the first import on}."""
    import json
    import os
    import subprocess
    import sys
    import tempfile
    import time

    with tempfile.TemporaryDirectory(prefix="numba-cold-") as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        t0 = time.perf_counter()
        out = subprocess.run([sys.executable, "-c", _COLD_RUN], input=json.dumps(scene), env=env, cwd=ROOT,
                             capture_output=True, text=True, check=True)
        process_s = time.perf_counter() - t0
    rec = json.loads(out.stdout.strip().splitlines()[-1])
    rec["cold"] = {"process_s": process_s, "import_build_solve_s": rec.pop("process_s")}
    return rec


def _run_material_point(scene: dict) -> dict:
    from studies.benchmarks import run_material_point

    return run_material_point(scene)


def _check_material_point(scene: dict) -> None:
    from studies.benchmarks import check_material_point

    check_material_point(scene)


def _run_mms(scene: dict) -> dict:
    from studies.mms import run

    return run(scene)


def _check_mms(scene: dict) -> None:
    from studies.mms import check

    check(scene)


SOLVERS: dict[str, Solver] = {
    s.name: s for s in (
        Solver("ancf", _run_ancf, _check_ancf, warm=_warm_ancf),
        Solver("ancf-effects", _run_ancf_effects, _check_ancf),
        Solver("fenicsx", _run_fenicsx, _check_fenicsx, backend=_fem_backend),
        Solver("ancf-cold", _run_ancf_cold, _check_ancf, also=("ancf.simulation", "contract.scene")),
        Solver("mms", _run_mms, _check_mms, backend=_mms_code),
        Solver("ancf-material", _run_material_point, _check_material_point),
    )
}


def get_solver(name: str) -> Solver:
    try:
        return SOLVERS[name]
    except KeyError:
        raise ValueError(f"solver: unknown {name!r}; allowed: {', '.join(sorted(SOLVERS))}") from None
