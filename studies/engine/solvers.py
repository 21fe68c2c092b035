"""The solvers a case can name: how to check a scene, run it, and hash the source.

Each solver is one entry of :data:`SOLVERS`; ``run(scene_dict) -> record`` returns the
solver's record (``contract.record`` schema, SI units) and ``check(scene_dict)`` raises a
SceneError for a scene it cannot run. The source hash covers the .py files the solver
runs, so a change there invalidates its cases:

- ``ancf``: every module of ``ancf/``, ``mechanics/`` and ``contract/`` (scenes, records);
- ``fenicsx``: every module of ``reference_fem/`` (its backends included), ``mechanics/``
  and ``contract/``, and ``ancf/integrators.py`` (the integrators' coefficients, until
  they move to ``mechanics``).

Adding a solver (e.g. a dynamic integrator living in another package) is one entry here.
"""
from __future__ import annotations

import hashlib
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Callable

ROOT = Path(__file__).resolve().parents[2]


def _run_ancf(scene: dict) -> dict:
    from ancf.simulation import run_scene
    from contract.scene import scene_from_dict

    rec, _ = run_scene(scene_from_dict(scene))
    return rec


def _run_fenicsx(scene: dict) -> dict:
    from contract.scene import scene_from_dict
    from reference_fem.simulation import run_scene

    return run_scene(scene_from_dict(scene))


def _check_ancf(scene: dict) -> None:
    from ancf.build import capacity
    from contract.scene import scene_from_dict

    capacity(scene_from_dict(scene))


def _check_fenicsx(scene: dict) -> None:
    from contract.scene import scene_from_dict
    from reference_fem.simulation import check

    check(scene_from_dict(scene))


@dataclass(frozen=True)
class Solver:
    name: str
    sources: tuple[str, ...]     # globs relative to the repository root
    run: Callable[[dict], dict]  # scene dict -> record
    check: Callable[[dict], None]


SOLVERS: dict[str, Solver] = {
    s.name: s for s in (
        Solver("ancf", ("ancf/*.py", "mechanics/**/*.py", "contract/*.py"), _run_ancf, _check_ancf),
        Solver("fenicsx", ("reference_fem/**/*.py", "mechanics/**/*.py", "contract/*.py"),
               _run_fenicsx, _check_fenicsx),
    )
}


def get_solver(name: str) -> Solver:
    try:
        return SOLVERS[name]
    except KeyError:
        raise ValueError(f"solver: unknown {name!r}; allowed: {', '.join(sorted(SOLVERS))}") from None


@lru_cache(maxsize=None)
def source_hash(name: str) -> str:
    """sha256 over the solver's source files (relative path and content, sorted)."""
    h = hashlib.sha256()
    files = sorted({p for g in get_solver(name).sources for p in ROOT.glob(g)})
    for p in files:
        h.update(str(p.relative_to(ROOT)).encode() + b"\0" + p.read_bytes() + b"\0")
    return h.hexdigest()
