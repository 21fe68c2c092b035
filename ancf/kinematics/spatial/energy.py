"""A registered law on the full 3D deformation gradient: energy, first Piola stress and its
tangent, at many points at once.

The energy density is

    W(F) = psi(I1bar, I2bar; c) + alpha / 2 (J - 1)^2,
    I1bar = J^(-2/3) tr C,  I2bar = J^(-4/3) (tr(C)^2 - tr(C^2)) / 2,  J = det F,  C = F^T F,

psi the law's own function (:mod:`mechanics.laws`, the same one the planar solver and the
continuum codes evaluate; nothing here knows which law it is) and alpha the penalty (the
planar plane-strain formulation's, ABAQUS's D1 = 2 / alpha; stress free at F = I). Its
derivatives come in two exact steps: W as a function of (I1, I2, J) on a second-order
forward jet in those three variables (:class:`Jet3`), then the invariants' own first and
second derivatives in F (closed forms, :func:`invariant_derivatives`). No finite differences.
"""
from __future__ import annotations

from typing import Mapping

import numpy as np

from mechanics.laws import get_law

_PAIRS = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)]


class Jet3:
    """A value with its first (3) and second (6: 00, 01, 02, 11, 12, 22) derivatives in
    three variables, elementwise over arrays: D (10, ...)."""

    __slots__ = ("D",)

    def __init__(self, D: np.ndarray):
        self.D = D

    @staticmethod
    def variables(*xs) -> tuple["Jet3", ...]:
        xs = np.broadcast_arrays(*(np.asarray(x, float) for x in xs))
        out = []
        for i, x in enumerate(xs):
            D = np.zeros((10,) + x.shape)
            D[0], D[1 + i] = x, 1.0
            out.append(Jet3(D))
        return tuple(out)

    def gradient(self) -> np.ndarray:
        return self.D[1:4]

    def hessian(self) -> np.ndarray:
        """(3, 3, ...)."""
        H = np.empty((3, 3) + self.D.shape[1:])
        for n, (i, j) in enumerate(_PAIRS):
            H[i, j] = H[j, i] = self.D[4 + n]
        return H

    def __add__(self, o):
        if isinstance(o, Jet3):
            return Jet3(self.D + o.D)
        D = self.D.copy()
        D[0] = D[0] + o
        return Jet3(D)

    __radd__ = __add__

    def __neg__(self):
        return Jet3(-self.D)

    def __sub__(self, o):
        return self + (-o)

    def __rsub__(self, o):
        return (-self) + o

    def __mul__(self, o):
        if not isinstance(o, Jet3):
            return Jet3(self.D * o)
        x, y = self.D, o.D
        D = np.empty(np.broadcast_shapes(x.shape, y.shape))
        D[0] = x[0] * y[0]
        D[1:4] = x[1:4] * y[0] + x[0] * y[1:4]
        for n, (i, j) in enumerate(_PAIRS):
            D[4 + n] = x[4 + n] * y[0] + x[0] * y[4 + n] + x[1 + i] * y[1 + j] + x[1 + j] * y[1 + i]
        return Jet3(D)

    __rmul__ = __mul__

    def __truediv__(self, o):
        if not isinstance(o, Jet3):
            return Jet3(self.D / o)
        return self * o ** -1

    def __rtruediv__(self, o):
        return self ** -1 * o

    def __pow__(self, p: float):
        if p == 1:
            return self
        x = self.D[0]
        with np.errstate(invalid="ignore", divide="ignore"):   # x <= 0 outside a law's domain: not a number
            return self.compose(x ** p, p * x ** (p - 1), p * (p - 1) * x ** (p - 2))

    def log(self) -> "Jet3":
        """log and its derivatives; not a number where x <= 0 (outside a law's domain)."""
        x = np.where(self.D[0] > 0.0, self.D[0], np.nan)
        with np.errstate(invalid="ignore"):
            return self.compose(np.log(x), 1.0 / x, -1.0 / (x * x))

    def compose(self, f, df, d2f) -> "Jet3":
        """phi(self), given phi, phi' and phi'' at self's value."""
        x = self.D
        D = np.empty_like(x)
        D[0] = f
        D[1:4] = df * x[1:4]
        for n, (i, j) in enumerate(_PAIRS):
            D[4 + n] = df * x[4 + n] + d2f * x[1 + i] * x[1 + j]
        return Jet3(D)


def density_jet(law: str, constants: Mapping[str, float], alpha: float, I1, I2, J) -> Jet3:
    """W and its derivatives in (I1, I2, J) at the given invariants (see the module doc)."""
    l = get_law(law)
    a, b, j = Jet3.variables(I1, I2, J)
    return l.psi(j ** (-2.0 / 3.0) * a, j ** (-4.0 / 3.0) * b, constants) + 0.5 * alpha * (j - 1.0) ** 2


_EPS = np.zeros((3, 3, 3))
for _i, _j, _k in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
    _EPS[_i, _j, _k], _EPS[_i, _k, _j] = 1.0, -1.0


def invariant_derivatives(F: np.ndarray, order: int = 2) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
    """The invariants (3, npts), their derivatives in F (3, npts, 3, 3) and second
    derivatives (3, npts, 3, 3, 3, 3) (index order i J k L of F_iJ, F_kL), up to ``order``
    (the ones above it None: an energy needs no derivative, a force no second one):

    dI1 = 2 F,  dI2 = 2 (I1 F - F C),  dJ = cof F = (1/2) eps_ikm eps_JLM F_kL F_mM,
    d2I1 = 2 delta_ik delta_JL,
    d2I2 = 4 F_iJ F_kL + 2 I1 delta_ik delta_JL - 2 (delta_ik C_JL + F_iL F_kJ + B_ik delta_JL),
    d2J = eps_ikm eps_JLM F_mM   (B = F F^T)."""
    n = F.shape[0]
    C = np.einsum("pki,pkj->pij", F, F)
    I1 = np.einsum("pij,pij->p", F, F)
    I2 = 0.5 * (I1 ** 2 - np.einsum("pij,pij->p", C, C))
    J = np.linalg.det(F)
    if order == 0:
        return np.stack([I1, I2, J]), None, None
    d = np.empty((3, n, 3, 3))
    d[0] = 2.0 * F
    d[1] = 2.0 * (I1[:, None, None] * F - F @ C)
    # cof F column by column: the cross products of F's other two columns
    a, b, c = F[:, :, 0], F[:, :, 1], F[:, :, 2]
    d[2] = np.stack([np.cross(b, c), np.cross(c, a), np.cross(a, b)], axis=-1)
    if order == 1:
        return np.stack([I1, I2, J]), d, None
    B = np.einsum("pik,pjk->pij", F, F)
    eye = np.eye(3)
    dd = np.empty((3, n, 3, 3, 3, 3))
    dd[0] = 2.0 * np.einsum("ik,JL->iJkL", eye, eye)[None]
    dd[1] = (4.0 * F[:, :, :, None, None] * F[:, None, None, :, :] + I1[:, None, None, None, None] * dd[0]
             - 2.0 * (eye[None, :, None, :, None] * C[:, None, :, None, :]
                      + F[:, :, None, None, :] * np.swapaxes(F, 1, 2)[:, None, :, :, None]
                      + B[:, :, None, :, None] * eye[None, None, :, None, :]))
    # eps_ikm eps_JLM F_mM in two contractions, (p, M, i, k) then (p, i, k, J, L)
    X = np.tensordot(F, _EPS, axes=([1], [2]))
    dd[2] = np.tensordot(X, _EPS, axes=([1], [2])).transpose(0, 1, 3, 2, 4)
    return np.stack([I1, I2, J]), d, dd


def density(law: str, constants: Mapping[str, float], alpha: float, F: np.ndarray) -> np.ndarray:
    """W (npts) alone at deformation gradients F (npts, 3, 3)."""
    inv, _, _ = invariant_derivatives(np.asarray(F, float), 0)
    return density_jet(law, constants, alpha, *inv).D[0]


def stress(law: str, constants: Mapping[str, float], alpha: float, F: np.ndarray, tangent: bool = True):
    """W (npts), the first Piola stress P = dW/dF (npts, 3, 3) and, with ``tangent``, its
    derivative A = d2W/dF2 (npts, 3, 3, 3, 3) at deformation gradients F (npts, 3, 3)."""
    F = np.asarray(F, float)
    return stress_of(law, constants, alpha, *invariant_derivatives(F, 2 if tangent else 1))


def stress_of(law: str, constants: Mapping[str, float], alpha: float, inv, d, dd):
    """:func:`stress` from the invariants and their derivatives (:func:`invariant_derivatives`;
    ``dd`` None: no tangent)."""
    tangent = dd is not None
    W = density_jet(law, constants, alpha, *inv)
    g, H = W.gradient(), W.hessian()
    P = np.einsum("ap,apiJ->piJ", g, d)
    if not tangent:
        return W.D[0], P, None
    # sum_a g_a dd_a + sum_ab H_ab d_a (x) d_b, as broadcast products (a three-operand einsum
    # loops over every index at once)
    Hd = np.einsum("abp,bpkL->apkL", H, d)
    A = np.einsum("ap,apiJkL->piJkL", g, dd)
    for k in range(3):
        A += d[k][:, :, :, None, None] * Hd[k][:, None, None, :, :]
    return W.D[0], P, A
