"""A case: one solver run of one scene, as pure data with an identity.

A :class:`Case` is frozen and hashable: (study, solver, scene, options), the scene and
the options held as canonical JSON. Its :attr:`Case.id` is a hash of

- the canonical scene JSON and the options (a ``timing`` option changes what is measured),
- the solver's source hash (:func:`studies.engine.solvers.source_hash`: the .py files of the
  package that solves it),
- the numpy / numba / dolfinx versions (:func:`versions`),
- with an ``imports`` option (a user's element or law), those modules' source files,

so that a record can be reused exactly while none of these changed. The study name is
not part of the id: the records of each study live in their own file.
"""
from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass, field
from functools import lru_cache
from importlib import metadata
from pathlib import Path
from typing import Any, Mapping

from .solvers import SOLVERS, get_solver, source_hash

# Distribution names whose versions enter every case id (dolfinx is "fenics-dolfinx").
VERSIONED = {"numpy": "numpy", "numba": "numba", "dolfinx": "fenics-dolfinx"}


@lru_cache(maxsize=None)
def _versions() -> tuple[tuple[str, str | None], ...]:
    out = []
    for name, dist in VERSIONED.items():
        try:
            out.append((name, metadata.version(dist)))
        except metadata.PackageNotFoundError:
            out.append((name, None))
    return tuple(out)


def versions() -> dict[str, str | None]:
    """{numpy, numba, dolfinx: version or None}, read from package metadata (no import)."""
    return dict(_versions())


def canonical(obj: Any) -> str:
    """The canonical JSON of ``obj``: sorted keys, no spaces, tuples as lists."""
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), allow_nan=False)


@dataclass(frozen=True)
class Case:
    study: str
    solver: str         # a key of studies.engine.solvers.SOLVERS
    scene_json: str     # canonical JSON of the scene dict (contract.scene format, SI)
    options_json: str   # canonical JSON of the options dict (e.g. {"timing": {...}})
    # the id, fixed where the case is made and carried to any worker with the case: a
    # worker never re-derives it from sources that may have changed since (see
    # :meth:`Case.sources_changed`)
    id: str = field(default="", compare=False)

    def __post_init__(self):
        if not self.id:
            object.__setattr__(self, "id", case_id(self.solver, self.scene_json, self.options_json))

    def sources_changed(self) -> bool:
        """Whether the solver's sources (or versions) differ from those the id was made
        with: a record computed now would not be what the id names."""
        return _fresh_id(self.solver, self.scene_json, self.options_json) != self.id

    @property
    def scene(self) -> dict:
        return json.loads(self.scene_json)

    @property
    def options(self) -> dict:
        return json.loads(self.options_json)

    @property
    def timing(self) -> dict | None:
        """The ``timing`` option ({"repeats": N, "budget_s": s}) or None."""
        return self.options.get("timing")

    @property
    def name(self) -> str:
        return self.scene["name"]

    def to_dict(self) -> dict:
        return {"id": self.id, "study": self.study, "solver": self.solver,
                "name": self.name, "options": self.options}


def _imports_hash(modules) -> str | None:
    """sha256 over the source files of the modules a case imports (a user's element or
    law): a record depends on them as on the solver's own sources. None without any."""
    if not modules:
        return None
    import importlib.util

    h = hashlib.sha256()
    for m in sorted(modules):
        spec = importlib.util.find_spec(m)
        origin = Path(spec.origin) if spec and spec.origin else None
        h.update(m.encode() + b"\0" + (origin.read_bytes() if origin and origin.exists() else b"?") + b"\0")
    return h.hexdigest()


def _fresh_id(solver: str, scene_json: str, options_json: str) -> str:
    options = json.loads(options_json)
    ident = {"solver": solver, "scene": json.loads(scene_json), "options": options,
             "source": source_hash(solver), "versions": versions()}
    if options.get("imports"):
        ident["imports_source"] = _imports_hash(options["imports"])
    return hashlib.sha256(canonical(ident).encode()).hexdigest()[:20]


case_id = lru_cache(maxsize=None)(_fresh_id)   # sources are read once per process


def make_case(study: str, solver: str, scene: Mapping, options: Mapping | None = None) -> Case:
    """A case from plain data; the solver name and the scene are checked here (an
    unknown solver fails with the list of valid ones; a bad scene with a SceneError)."""
    get_solver(solver).check(dict(scene))
    return Case(study, solver, canonical(scene), canonical(dict(options or {})))


__all__ = ["Case", "make_case", "case_id", "versions", "canonical", "SOLVERS"]
