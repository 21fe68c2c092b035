"""The laws of :mod:`mechanics.laws` on tensortrax tensors: each continuum model's energy,
written once for any law (the law's energy psi(I1, I2; c) is the shared table's; this
module only builds the invariants it sees, with tensortrax's math handed to it as ``m``).

- plane strain: F is FElupe's plane-strain 3 x 3 gradient (F33 = 1); isochoric
  I1bar = J^(-2/3) tr C, I2bar = J^(-4/3) (tr C^2 - tr(C C)) / 2; J = det F;
- plane stress (incompressible): F is 2 x 2, F33 = 1/J: I1 = tr C + J^-2, I2 = J^2 + tr C J^-2;
- 3D: F 3 x 3, isochoric as in plane strain.

The pressure terms (mixed: mu phat (J - 1); penalty: also - (mu phat)^2 / (2 alpha)) are in
:class:`reference_fem.felupe_backend.problem.MixedMaterial`, with their derivatives in
closed form.
"""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import tensortrax.math as tm

from mechanics.laws import Law


def _log(x):
    """ln x; NaN beyond x > 0 (value and derivatives), as on ANCF's jets and in UFL, so a
    state beyond a law's domain gives a non-finite residual and the step is rejected."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return tm.log(x)


TENSORTRAX_MATH = SimpleNamespace(log=_log)


def _isochoric(F):
    J = tm.linalg.det(F)
    C = tm.transpose(F) @ F
    I1 = tm.trace(C)
    I2 = (I1 ** 2 - tm.trace(C @ C)) / 2
    return J ** (-2 / 3) * I1, J ** (-4 / 3) * I2


def _plane_stress(F):
    J = tm.linalg.det(F)
    trC = tm.trace(tm.transpose(F) @ F)
    return trC + J ** -2, J ** 2 + trC * J ** -2


INVARIANTS = {"plane-strain": _isochoric, "3d": _isochoric, "plane-stress": _plane_stress}


def strain_energy(law: Law, model: str, constants: dict):
    """W(F): the law's energy at the invariants ``model`` gives (a function of a tensortrax
    tensor, for :func:`tensortrax.hessian`)."""
    invariants = INVARIANTS[model]

    def W(F):
        I1, I2 = invariants(F)
        return law.psi(I1, I2, constants, TENSORTRAX_MATH)
    return W
