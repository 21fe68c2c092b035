"""Hyperelastic laws: one table of energies psi(I1, I2; c), each written once.

A law is data: its name, the constants it needs (Pa, or as the law says), and its
energy as arithmetic (+, -, *, /, ** with constant exponents) plus the functions of a
math namespace ``m`` it is handed (``m.log``). The same function then runs on ANCF's
jets and on its tape (:class:`ancf.core.jet.Jet`, :class:`ancf.core.tape.Node`: the default
namespace :data:`MATH` dispatches to their ``.log()``), in UFL (the DOLFINx backend
passes ``ufl.ln``) and on any other algebra that brings its own ``log`` (FElupe's
tensortrax). Which invariants a law sees (the paper's 2D ones, plane strain isochoric
ones, the incompressible plane-stress ones, 3D) is the solver's business; the law never
knows.

Each law's own small-strain shear modulus mu = 2 (psi_1 + psi_2) at I1 = I2 = 3 is
derived from its energy (a dual number, :func:`Law.shear_modulus`), not written per law;
the continuum uses it as its pressure scale and the beam theory as its modulus.

Adding a law is one module in this package defining ``LAW = Law(...)`` (found by
:func:`_discover`); a law of a user's own is registered with :func:`register_law` from a
module given to the CLIs with ``--import``.
"""
from __future__ import annotations

import importlib
import math
import pkgutil
from dataclasses import dataclass, field
from typing import Callable, Mapping

import numpy as np

from contract.errors import SceneError
from contract.registry import Registry


class _Dispatch:
    """The default math namespace: ``log`` of a float or array is numpy's; of anything
    else (a jet, a tape node, a dual number) its own ``.log()``."""

    @staticmethod
    def log(x):
        if isinstance(x, (int, float, np.ndarray, np.floating)):
            with np.errstate(invalid="ignore", divide="ignore"):   # NaN beyond the domain
                return np.log(x)
        return x.log()


MATH = _Dispatch()


class _Dual:
    """A value with its gradient in (I1, I2): enough forward-mode arithmetic to take
    first derivatives of a law's energy (shear modulus, checks)."""

    __slots__ = ("v", "g")

    def __init__(self, v, g):
        self.v, self.g = float(v), np.asarray(g, float)

    def _lift(self, o):
        return o if isinstance(o, _Dual) else _Dual(o, (0.0, 0.0))

    def __add__(self, o):
        o = self._lift(o)
        return _Dual(self.v + o.v, self.g + o.g)

    __radd__ = __add__

    def __neg__(self):
        return _Dual(-self.v, -self.g)

    def __sub__(self, o):
        return self + (-self._lift(o))

    def __rsub__(self, o):
        return self._lift(o) - self

    def __mul__(self, o):
        o = self._lift(o)
        return _Dual(self.v * o.v, self.g * o.v + self.v * o.g)

    __rmul__ = __mul__

    def __truediv__(self, o):
        return self * self._lift(o) ** -1

    def __rtruediv__(self, o):
        return self._lift(o) * self ** -1

    def __pow__(self, p):
        if p == 0:
            return _Dual(1.0, (0.0, 0.0))
        return _Dual(self.v ** p, p * self.v ** (p - 1) * self.g)

    def log(self):
        return _Dual(math.log(self.v), self.g / self.v)


@dataclass(frozen=True)
class Law:
    name: str
    constants: tuple[str, ...]
    energy: Callable          # (I1, I2, c: Mapping[str, float], m=MATH) -> same algebra as I1
    doc: str = ""
    # a check of the constants beyond "finite": returns a message naming the constant, or None
    admissible: Callable[[Mapping[str, float]], str | None] | None = field(default=None, compare=False)
    # constants to show the law with (cards, examples) when no scene gives them
    example: Mapping[str, float] = field(default_factory=dict, compare=False)

    def psi(self, I1, I2, c: Mapping[str, float], m=MATH):
        return self.energy(I1, I2, c, m)

    def first_derivatives(self, c: Mapping[str, float], I1: float = 3.0, I2: float = 3.0) -> tuple[float, float]:
        """(dpsi/dI1, dpsi/dI2) at (I1, I2)."""
        W = self.energy(_Dual(I1, (1.0, 0.0)), _Dual(I2, (0.0, 1.0)), c, MATH)
        W = W if isinstance(W, _Dual) else _Dual(W, (0.0, 0.0))
        return float(W.g[0]), float(W.g[1])

    def shear_modulus(self, c: Mapping[str, float]) -> float:
        """Small-strain shear modulus mu = 2 (dpsi/dI1 + dpsi/dI2) at I1 = I2 = 3."""
        return 2.0 * sum(self.first_derivatives(c))

    def check(self, c: Mapping[str, float]) -> None:
        """Raise a :class:`SceneError` naming the constant if ``c`` is not admissible:
        a positive small-strain shear modulus, and the law's own rule."""
        msg = self.admissible(c) if self.admissible else None
        if msg is None:
            mu = self.shear_modulus(c)
            if not mu > 0:
                names = ", ".join(f"material.{k}" for k in self.constants)
                msg = (f"{names}: the {self.name} law's small-strain shear modulus "
                       f"2 (dpsi/dI1 + dpsi/dI2) must be positive, got {mu!r} Pa")
        if msg:
            raise SceneError(msg)


LAWS: Registry[Law] = Registry("material.law", "law")


def register_law(law: Law) -> Law:
    import sys

    return LAWS.register(law.name, law, sys._getframe(1).f_globals.get("__name__", "__main__"))


def get_law(name: str) -> Law:
    return LAWS.lookup(name)


def _discover() -> None:
    """Register the ``LAW`` (or ``LAWS``) of every module of this package, in name order."""
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda i: i.name):
        mod = importlib.import_module(f"{__name__}.{info.name}")
        for law in getattr(mod, "LAWS", ()) or (getattr(mod, "LAW", None),):
            if law is not None:
                register_law(law)


_discover()
# the laws of this package; any other was registered by a user's module
BUILTIN = LAWS.freeze_builtin()
