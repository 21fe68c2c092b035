"""The hyperelastic laws in UFL and the invariants they see (written once, no dolfinx).

Laws carry the names and constants of :mod:`ancf.laws` (checked by a test) and are
energies psi(I1, I2) of the 3D invariants. The invariants are built here from the 3D
right Cauchy-Green tensor, independently of the 2D shortcuts in
:mod:`ancf.formulations`, so that the pointwise test compares two derivations:

- plane strain: F3 = diag(F, 1); I1 = tr C3, I2 = (I1^2 - tr C3^2) / 2, made
  isochoric with J = det F: I1bar = J^(-2/3) I1, I2bar = J^(-4/3) I2;
- plane stress (incompressible): F3 = diag(F, 1/J), so I1 = tr C + J^-2,
  I2 = tr C J^-2 + J^2; no volumetric term;
- 3D: the full C = F^T F, isochoric as in plane strain (no planar reduction).

How a continuum model uses them (and enforces incompressibility) is
:mod:`reference_fem.dolfinx_backend.models`.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Mapping

import ufl

from contract.errors import UnknownName


@dataclass(frozen=True)
class LawUFL:
    name: str
    constants: tuple[str, ...]
    energy: Callable  # (I1, I2, c: Mapping[str, UFL scalar]) -> UFL scalar

    def shear_modulus(self, c: Mapping[str, float]) -> float:
        """Small-strain shear modulus mu = 2 (dpsi/dI1 + dpsi/dI2) at I1 = I2 = 3 (Pa)."""
        return 2.0 * (c.get("C10", 0.0) + c.get("C01", 0.0))


def _neo_hookean(I1, I2, c):
    return c["C10"] * (I1 - 3)


def _mooney_rivlin(I1, I2, c):
    return c["C10"] * (I1 - 3) + c["C01"] * (I2 - 3)


def _yeoh(I1, I2, c):
    d = I1 - 3
    return c["C10"] * d + c["C20"] * d ** 2 + c["C30"] * d ** 3


LAWS_UFL: dict[str, LawUFL] = {
    law.name: law for law in (
        LawUFL("neo-hookean", ("C10",), _neo_hookean),
        LawUFL("mooney-rivlin", ("C10", "C01"), _mooney_rivlin),
        LawUFL("yeoh", ("C10", "C20", "C30"), _yeoh),
    )
}


def get_law_ufl(name: str) -> LawUFL:
    try:
        return LAWS_UFL[name]
    except KeyError:
        raise UnknownName("material.law", name, LAWS_UFL) from None


def _invariants_3d(C3):
    I1 = ufl.tr(C3)
    return I1, 0.5 * (I1 ** 2 - ufl.tr(C3 * C3))


def plane_strain_invariants(F):
    """Isochoric (I1bar, I2bar) of F3 = diag(F, 1), and J = det F."""
    J = ufl.det(F)
    F3 = ufl.as_matrix([[F[0, 0], F[0, 1], 0], [F[1, 0], F[1, 1], 0], [0, 0, 1]])
    I1, I2 = _invariants_3d(F3.T * F3)
    return J ** (-2.0 / 3.0) * I1, J ** (-4.0 / 3.0) * I2, J


def plane_stress_invariants(F):
    """(I1, I2) of F3 = diag(F, 1/J), J = det F."""
    J = ufl.det(F)
    F3 = ufl.as_matrix([[F[0, 0], F[0, 1], 0], [F[1, 0], F[1, 1], 0], [0, 0, 1 / J]])
    I1, I2 = _invariants_3d(F3.T * F3)
    return I1, I2, J


def solid_invariants(F):
    """Isochoric (I1bar, I2bar) of a 3 x 3 gradient F, and J = det F."""
    J = ufl.det(F)
    I1, I2 = _invariants_3d(F.T * F)
    return J ** (-2.0 / 3.0) * I1, J ** (-4.0 / 3.0) * I2, J
