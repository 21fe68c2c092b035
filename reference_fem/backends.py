"""The continuum backends behind one interface, and their registry.

A backend is one folder, ``reference_fem/<name>_backend/``, whose package offers the
:class:`Backend` interface: ``version()``, ``static_model(scene, settings)`` (the static
system the shared :mod:`reference_fem.statics` drives), ``dynamic_model(scene, settings)``
(one time step's equations for :class:`reference_fem.stepper.ContinuumStepper`) and
``manufactured(solution, cells)`` (one level of a manufactured solution,
:mod:`reference_fem.manufactured`). Adding one is that folder and one line here
(:func:`register_backend`); a scene names it in ``[fem] backend``, and everything else
(the settings' check, the record's label, the study engine's fingerprint of the code a
run reaches, the studies) asks :data:`BACKENDS`. A backend package is imported only when
it is used, so that DOLFINx is loaded only by a run that names it.
"""
from __future__ import annotations

import importlib
from dataclasses import dataclass
from types import ModuleType
from typing import Protocol

from contract.registry import Registry

DEFAULT = "dolfinx"


class Backend(Protocol):
    name: str
    package: str     # the module path of its folder (what the study engine fingerprints)

    def version(self) -> str: ...

    def static_model(self, scene, settings): ...

    def dynamic_model(self, scene, settings): ...

    def manufactured(self, solution, cells: int) -> dict: ...


@dataclass(frozen=True)
class PackageBackend:
    """A backend whose folder is a package offering the interface's functions."""
    name: str
    package: str
    label: str      # how reports print it

    @property
    def module(self) -> ModuleType:
        return importlib.import_module(self.package)

    def version(self) -> str:
        return self.module.version()

    def static_model(self, scene, settings):
        return self.module.static_model(scene, settings)

    def dynamic_model(self, scene, settings):
        return self.module.dynamic_model(scene, settings)

    def manufactured(self, solution, cells: int) -> dict:
        return self.module.manufactured(solution, cells)


BACKENDS: Registry[Backend] = Registry("fem.backend", "continuum backend")


def register_backend(backend: Backend) -> Backend:
    return BACKENDS.register(backend.name, backend)


def get_backend(name: str) -> Backend:
    return BACKENDS.lookup(name)


register_backend(PackageBackend("dolfinx", "reference_fem.dolfinx_backend", "DOLFINx"))
register_backend(PackageBackend("felupe", "reference_fem.felupe_backend", "FElupe"))
BACKENDS.freeze_builtin()
