"""The solvers a case can name: how to check a scene, run it, and what a record of it
depends on. The engine knows none of them: each is registered by the module that defines
it (:func:`register_solver`), the ones every study uses by :mod:`studies.solvers`, a
study's own by the study (the manufactured solutions, the material point).

A :class:`Solver` has ``run(scene_dict) -> record`` (the solver's record,
``contract.record`` schema, SI units) and ``check(scene_dict)``, which raises a SceneError
for a scene it cannot run. What a record depends on is the solver's fingerprint
(:meth:`Solver.fingerprint`, :mod:`studies.engine.fingerprint`): the code its run function
reaches, normalised, and the packages that code imports. A case carries the module that
registered its solver (:attr:`studies.engine.case.Case.solver_module`), so that a worker
process imports it before it runs the case (:func:`get_solver`).
"""
from __future__ import annotations

import importlib
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from contract.registry import Registry

from . import fingerprint as fp

ROOT = Path(__file__).resolve().parents[2]


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
        if backend in fp.backends():
            entries.append(fp.backends()[backend])
        if (options or {}).get("mpi_ranks"):
            entries += ["studies.engine.worker:_run_launched", "reference_fem.__main__"]
        return entries, backend

    def fingerprint(self, scene: dict, options: dict | None = None) -> dict:
        """{"code": hash, "packages": {name: version}} of what a run of ``scene`` executes
        (:meth:`entries`, :func:`studies.engine.fingerprint.fingerprint`)."""
        return fp.fingerprint(*self.entries(scene, options))


SOLVERS: Registry[Solver] = Registry("solver", "solver")


def register_solver(solver: Solver) -> Solver:
    """Add a solver (a ValueError if its name is taken); its module is recorded as its origin."""
    return SOLVERS.register(solver.name, solver, sys._getframe(1).f_globals.get("__name__", "__main__"))


def get_solver(name: str, module: str | None = None) -> Solver:
    """The solver ``name``; ``module``: the module that registers it, imported first if the
    name is not known yet in this process (a worker). A ValueError names the known ones."""
    if name not in SOLVERS and module:
        importlib.import_module(module)
    return SOLVERS.lookup(name)
