"""The solvers a case can name: how to check a scene, run it, and hash the source.

Each solver is one entry of :data:`SOLVERS`; ``run(scene_dict) -> record`` returns the
solver's record (``ancf.record`` schema, SI units). The source hash covers the .py files
of the package that solves the scene, so a change there invalidates its cases:

- ``ancf``: every module of ``ancf/``;
- ``fenicsx``: every module of ``reference_fem/``, plus the three ``ancf`` modules it
  imports (scene loading, records, errors).

Adding a solver (e.g. a dynamic integrator living in another package) is one entry here.
"""
from __future__ import annotations

import hashlib
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Callable

ROOT = Path(__file__).resolve().parent.parent


def _run_ancf(scene: dict) -> dict:
    from ancf.run import run_scene
    from ancf.scene import scene_from_dict

    rec, _ = run_scene(scene_from_dict(scene))
    return rec


def _run_fenicsx(scene: dict) -> dict:
    from ancf.scene import scene_from_dict
    from reference_fem.run import run_scene

    return run_scene(scene_from_dict(scene))


def _check_ancf(scene: dict) -> None:
    from ancf.scene import scene_from_dict

    if scene_from_dict(scene).ancf is None:
        from ancf.errors import SceneError
        raise SceneError("ancf: an ancf case needs the scene's [ancf] table")


def _check_fenicsx(scene: dict) -> None:
    from ancf.scene import scene_from_dict
    from reference_fem.settings import fem_settings

    fem_settings(scene_from_dict(scene))


@dataclass(frozen=True)
class Solver:
    name: str
    sources: tuple[str, ...]     # globs relative to the repository root
    run: Callable[[dict], dict]  # scene dict -> record
    check: Callable[[dict], None]


SOLVERS: dict[str, Solver] = {
    s.name: s for s in (
        Solver("ancf", ("ancf/*.py",), _run_ancf, _check_ancf),
        Solver("fenicsx", ("reference_fem/*.py", "ancf/scene.py", "ancf/record.py", "ancf/errors.py"),
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
