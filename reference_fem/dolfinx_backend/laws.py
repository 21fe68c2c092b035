"""The laws of :mod:`mechanics.laws` in UFL, and the invariants they see (no dolfinx).

The laws themselves are the shared table (one energy per law, the same code ANCF runs);
this module gives them UFL's ``ln`` (:data:`UFL_MATH`) and builds the invariants from
the 3D right Cauchy-Green tensor, independently of the 2D shortcuts in
:mod:`ancf.core.formulations`, so that the pointwise test compares two derivations:

- plane strain: F3 = diag(F, 1); I1 = tr C3, I2 = (I1^2 - tr C3^2) / 2, made
  isochoric with J = det F: I1bar = J^(-2/3) I1, I2bar = J^(-4/3) I2;
- plane stress (incompressible): F3 = diag(F, 1/J), so I1 = tr C + J^-2,
  I2 = tr C J^-2 + J^2; no volumetric term;
- 3D: the full C = F^T F, isochoric as in plane strain (no planar reduction).

How a continuum model uses them (and enforces incompressibility) is
:mod:`reference_fem.dolfinx_backend.models`.
"""
from __future__ import annotations

from types import SimpleNamespace

import ufl

from mechanics.laws import Law

def _log(x):
    """ln x where x > 0; not a number (value and derivatives) elsewhere, as on ANCF's
    jets, so that a state outside a law's domain (Gent: I1 - 3 >= Jm) makes the residual
    NaN and the step is rejected, instead of a finite stress of the wrong sign (ln's
    derivative 1/x is finite for x < 0). UFL has no NaN literal that the generated C
    accepts: sqrt(-1 - x^2) is NaN for every x, and so is its derivative."""
    return ufl.conditional(ufl.gt(x, 0.0), ufl.ln(x), ufl.sqrt(-1.0 - x * x))


# the math namespace a law's energy is handed in UFL
UFL_MATH = SimpleNamespace(log=_log)


def energy(law: Law, I1, I2, c):
    """The law's energy psi(I1, I2) as a UFL expression."""
    return law.psi(I1, I2, c, UFL_MATH)


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
