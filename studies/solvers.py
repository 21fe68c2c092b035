"""The solvers every study uses, registered with the engine (:mod:`studies.engine.solvers`):

- ``ancf``: the ANCF solver (``ancf/``, and what it imports of ``mechanics/`` and
  ``contract/``);
- ``ancf-effects``: the ANCF solver, then the cost of each effect's assembly (the study
  ``effects``);
- ``ancf-cold``: the ANCF solver in a fresh process with an empty numba cache (Table 4's
  first-run cost, compiling included);
- ``continuum``: the continuum reference, with the backend its scene names
  (``fem.backend``, :data:`reference_fem.backends.BACKENDS`; not the other ones); its
  records are labelled with that backend's name.

A study's own solver is registered by the study (``mms`` by :mod:`studies.verification.manufactured`,
``ancf-material`` by :mod:`studies.verification.benchmarks`).
"""
from __future__ import annotations

from pathlib import Path

from reference_fem.backends import DEFAULT

from .engine.solvers import Solver, register_solver

ROOT = Path(__file__).resolve().parents[1]


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

    from ancf.build import build_model, plan
    from ancf.simulation import run_scene
    from contract.scene import scene_from_dict

    sc = scene_from_dict(scene)
    rec, (model, res) = run_scene(sc)
    if rec.get("status") != "converged":
        return rec
    u = res.u if res.u is not None else np.zeros(model.mesh.n_dof)
    costs = _paired(lambda: run_scene(sc), lambda: run_scene(sc)[1][0].mass_matrix())
    costs["build_model"] = _median_spread(lambda: build_model(plan(sc)))
    costs["tangent"] = _median_spread(lambda: model.internal_force_and_tangent(u))
    costs["mass_matrix"] = _median_spread(model.mass_matrix)
    if sc.loads.gravity is not None:
        costs["gravity"] = _median_spread(lambda: model.gravity_force(sc.loads.gravity))
    if sc.loads.tip_force is not None:
        costs["tip_force"] = _median_spread(lambda: model.tip_force(sc.loads.tip_force))
    rec["effect_costs"] = costs
    return rec


def _run_continuum(scene: dict) -> dict:
    from contract.scene import scene_from_dict
    from reference_fem.simulation import run_scene

    return run_scene(scene_from_dict(scene))


def _warm_ancf(scene: dict) -> None:
    from ancf.build import plan
    from ancf.warm import load
    from contract.scene import scene_from_dict

    load(plan(scene_from_dict(scene)))


def _check_ancf(scene: dict) -> None:
    from ancf.build import capacity
    from contract.scene import scene_from_dict

    capacity(scene_from_dict(scene))


def _check_continuum(scene: dict) -> None:
    from contract.scene import scene_from_dict
    from reference_fem.simulation import check

    check(scene_from_dict(scene))


def _fem_backend(scene: dict) -> str:
    return (scene.get("fem") or {}).get("backend", DEFAULT)


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


for _solver in (Solver("ancf", _run_ancf, _check_ancf, warm=_warm_ancf),
                Solver("ancf-effects", _run_ancf_effects, _check_ancf),
                Solver("continuum", _run_continuum, _check_continuum, backend=_fem_backend),
                Solver("ancf-cold", _run_ancf_cold, _check_ancf, also=("ancf.simulation", "contract.scene"))):
    register_solver(_solver)
