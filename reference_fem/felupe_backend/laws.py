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

Derivatives (:class:`InvariantEnergy`): every model's invariants are functions of
x = (I1, I2, J) of F itself (I1 = F : F, I2 = (I1^2 - C : C) / 2, J = det F), so

    dW/dF     = sum_a W_a dx_a/dF
    d2W/dF2   = sum_ab W_ab dx_a/dF (x) dx_b/dF + sum_a W_a d2x_a/dF2

with W_a, W_ab tensortrax's derivatives of the law at the model's invariants (three
scalars per quadrature point) and the kinematic derivatives in closed form:
dI1 = 2 F, dI2 = 2 I1 F - 2 F C, dJ = J F^-T; d2I1 = 2 d_ik d_JL,
d2I2 = 4 F_iJ F_kL + 2 I1 d_ik d_JL - 2 d_ik C_LJ - 2 F_iL F_kJ - 2 (F F^T)_ik d_JL,
d2J = (dJ_iJ dJ_kL - dJ_iL dJ_kJ) / J. The same numbers as tensortrax's hessian of W(F)
(tests/test_felupe_dynamics.py, 1e-12 relative), five to ten times faster: tensortrax
carries 81 second derivatives through every operation on a 3 x 3 F.
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


def _isochoric_x(I1, I2, J):
    return J ** (-2 / 3) * I1, J ** (-4 / 3) * I2


def _plane_stress_x(I1, I2, J):
    return I1 + J ** -2, J ** 2 + I1 * J ** -2


INVARIANTS_X = {"plane-strain": _isochoric_x, "3d": _isochoric_x, "plane-stress": _plane_stress_x}


class InvariantEnergy:
    """W(F): the law's energy at the invariants ``model`` gives. Called on a tensortrax
    tensor it is W (for :func:`tensortrax.hessian`: the reference derivatives);
    :meth:`gradient` and :meth:`hessian` give dW/dF and d2W/dF2 (FElupe's (i, J, [k, L,]
    q, c) layout) by the chain rule through (I1, I2, J), plus ``w_J`` dJ/dF and its
    derivative (the pressure term mu phat (J - 1) of the mixed forms)."""

    def __init__(self, law: Law, model: str, constants: dict):
        self.law, self.model, self.constants = law, model, constants
        self._invariants, self._of_x = INVARIANTS[model], INVARIANTS_X[model]

    def __call__(self, F):
        I1, I2 = self._invariants(F)
        return self.law.psi(I1, I2, self.constants, TENSORTRAX_MATH)

    def _psi_x(self, x):
        I1, I2 = self._of_x(x[0], x[1], x[2])
        return self.law.psi(I1, I2, self.constants, TENSORTRAX_MATH)

    @staticmethod
    def _kinematics(F):
        """x = (I1, I2, J) (3, q, c), their first derivatives (3, i, J, q, c), C, F F^T."""
        I1 = np.einsum("iJ...,iJ...->...", F, F)
        C = np.einsum("kI...,kJ...->IJ...", F, F)
        I2 = (I1 ** 2 - np.einsum("IJ...,IJ...->...", C, C)) / 2
        Fm = np.moveaxis(F, (0, 1), (-2, -1))
        J = np.linalg.det(Fm)
        dJ = np.moveaxis(J[..., None, None] * np.swapaxes(np.linalg.inv(Fm), -1, -2), (-2, -1), (0, 1))
        dI2 = 2 * I1 * F - 2 * np.einsum("iK...,KJ...->iJ...", F, C)
        return np.stack([I1, I2, J]), np.stack([2 * F, dI2, dJ]), C

    def gradient(self, F, w_J=0.0):
        import tensortrax as tr

        x, dx, _ = self._kinematics(F)
        g = np.array(tr.gradient(self._psi_x, ntrax=2)(np.ascontiguousarray(x)))
        g[2] = g[2] + w_J
        return np.einsum("a...,aiJ...->iJ...", g, dx)

    def hessian(self, F, w_J=0.0):
        import tensortrax as tr

        x, dx, C = self._kinematics(F)
        H, g, _ = tr.hessian(self._psi_x, ntrax=2, full_output=True)(np.ascontiguousarray(x))
        g = np.array(g)
        g[2] = g[2] + w_J
        n = F.shape[0]
        eye = np.eye(n)
        d = eye[:, None, :, None] * eye[None, :, None, :]                 # d_ik d_JL
        d = d.reshape(d.shape + (1,) * (F.ndim - 2))
        I1, J, dJ = x[0], x[2], dx[2]
        b = np.einsum("iK...,jK...->ij...", F, F)
        FF = np.einsum("iJ...,kL...->iJkL...", F, F)
        d2I2 = (4 * FF + 2 * I1 * d - 2 * np.einsum("ik,LJ...->iJkL...", eye, C)
                - 2 * np.swapaxes(FF, 1, 3) - 2 * np.einsum("ik...,JL->iJkL...", b, eye))
        dJdJ = np.einsum("iJ...,kL...->iJkL...", dJ, dJ)
        d2J = (dJdJ - np.swapaxes(dJdJ, 1, 3)) / J
        A = np.einsum("ab...,aiJ...,bkL...->iJkL...", H, dx, dx)
        return A + 2 * g[0] * d + g[1] * d2I2 + g[2] * d2J


def strain_energy(law: Law, model: str, constants: dict) -> InvariantEnergy:
    """W(F): the law's energy at the invariants ``model`` gives (:class:`InvariantEnergy`)."""
    return InvariantEnergy(law, model, constants)
