"""A material: one law seen through one formulation, with its constants.

:meth:`Material.evaluate` turns deformation gradients F (..., 2, 2) into the energy
density W (Pa), the first Piola-Kirchhoff stress P = dW/dF (Pa) and the tangent
A = d2W/dF2 (Pa), flattened so that F_ij is entry 2 i + j of a 4-vector. The chain
rule from (a, J) to F is written here once for every law and formulation:

    P = 2 W_a F + W_J cof F
    A = 4 W_aa f f^T + 2 W_aJ (f c^T + c f^T) + W_JJ c c^T + 2 W_a I + W_J E

with f = vec F, c = vec cof F and E = d2J/dF2 (constant).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from .formulations import Formulation
from .jet import Jet
from mechanics.laws import Law

# d2(det F)/dF2 in the flattened index 2 i + j
_E = np.array([[0, 0, 0, 1], [0, 0, -1, 0], [0, -1, 0, 0], [1, 0, 0, 0]], dtype=float)


@dataclass(frozen=True)
class Material:
    law: Law
    formulation: Formulation
    constants: Mapping[str, float] = field(hash=False)
    penalty: float | None = None  # Pa; alpha in alpha/2 (J - 1)^2
    density: float = 0.0          # kg/m^3

    def energy_jet(self, a, J) -> Jet:
        """W and its (a, J) partials, elementwise over arrays a and J."""
        ja, jJ = Jet.variables(np.asarray(a, float), np.asarray(J, float))
        I1, I2 = self.formulation.invariants(ja, jJ)
        W = self.law.psi(I1, I2, self.constants)
        if self.formulation.penalised:
            W = W + 0.5 * self.penalty * (jJ - 1.0) ** 2
        return W

    def evaluate(self, F: np.ndarray, tangent: bool = True):
        """W (...), P (..., 2, 2) and, if asked, A (..., 4, 4) at gradients F (..., 2, 2)."""
        f = F.reshape(F.shape[:-2] + (4,))
        a = np.einsum("...i,...i->...", f, f)
        J = f[..., 0] * f[..., 3] - f[..., 1] * f[..., 2]
        c = np.stack([f[..., 3], -f[..., 2], -f[..., 1], f[..., 0]], axis=-1)
        W = self.energy_jet(a, J)
        P = 2.0 * W.a[..., None] * f + W.J[..., None] * c
        if not tangent:
            return W.v, P.reshape(F.shape), None
        ff = f[..., :, None] * f[..., None, :]
        fc = f[..., :, None] * c[..., None, :]
        cc = c[..., :, None] * c[..., None, :]
        A = (4.0 * W.aa[..., None, None] * ff
             + 2.0 * W.aJ[..., None, None] * (fc + np.swapaxes(fc, -1, -2))
             + W.JJ[..., None, None] * cc
             + 2.0 * W.a[..., None, None] * np.eye(4)
             + W.J[..., None, None] * _E)
        return W.v, P.reshape(F.shape), A

    def reference_stress_derivative(self) -> float:
        """W_a = dW/d(tr C) at F = I (for the paper's effective modulus 8 W_a)."""
        return float(self.energy_jet(2.0, 1.0).a)
