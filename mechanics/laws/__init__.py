"""Hyperelastic laws as energies psi(I1, I2) of two invariant jets.

A law is data: its name, the constants it needs (Pa), and its energy written once.
Which invariants it sees (the paper's 2D ones, plane strain isochoric ones, or the
incompressible plane-stress ones) is the formulation's business
(:mod:`ancf.formulations`); the law never knows.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Mapping

from contract.errors import UnknownName


@dataclass(frozen=True)
class Law:
    name: str
    constants: tuple[str, ...]
    energy: Callable  # (I1, I2, constants: Mapping[str, float]) -> Jet
    doc: str = ""

    def shear_modulus(self, c: Mapping[str, float]) -> float:
        """Small-strain shear modulus mu = 2 (dpsi/dI1 + dpsi/dI2) at I1 = I2 = 3."""
        return 2.0 * (c.get("C10", 0.0) + c.get("C01", 0.0))


def _neo_hookean(I1, I2, c):
    return c["C10"] * (I1 - 3.0)


def _mooney_rivlin(I1, I2, c):
    return c["C10"] * (I1 - 3.0) + c["C01"] * (I2 - 3.0)


def _yeoh(I1, I2, c):
    d = I1 - 3.0
    return c["C10"] * d + c["C20"] * d ** 2 + c["C30"] * d ** 3


LAWS: dict[str, Law] = {}


def register_law(law: Law) -> Law:
    if law.name in LAWS:
        raise ValueError(f"law {law.name!r} is registered already")
    LAWS[law.name] = law
    return law


register_law(Law("neo-hookean", ("C10",), _neo_hookean, "C10 (I1 - 3)"))
register_law(Law("mooney-rivlin", ("C10", "C01"), _mooney_rivlin, "C10 (I1 - 3) + C01 (I2 - 3)"))
register_law(Law("yeoh", ("C10", "C20", "C30"), _yeoh, "sum_i Ci0 (I1 - 3)^i, i = 1..3"))


def get_law(name: str) -> Law:
    try:
        return LAWS[name]
    except KeyError:
        raise UnknownName("material.law", name, LAWS) from None
