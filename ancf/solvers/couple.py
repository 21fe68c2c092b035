"""The end moment of a static scene (:mod:`contract.loads`), and what a static solve balances.

The end moment is a conservative couple M on the rotation theta of the free end face:
potential -M theta, theta = atan2(-d_x, d_y) of the face's first moment

    d = int r(L, y) y dy / int y^2 dy = (12 / h^3) int r(L, y) y dy,

which is linear in the nodal coordinates of the last element: d = d0 + A u[rows]
(:class:`ancf.kinematics.face.EndFace`, made by the element's kinematics: for the
continuum-based section its polynomial times y integrated exactly across the thickness, so
for an element linear in y, d = r_y(L)). With g and H the gradient and
Hessian of theta in d (:func:`mechanics.end_rotation.rotation_derivatives`), the couple's
generalised force is M A^T g(d) and its load stiffness M A^T H(d) A: a dense block on the
face's unknowns, all inside the last element, so inside the band. The compiled static
Newton adds both by :func:`add_couple` (the same arrays); :class:`Loading` is the numpy
side, which the Python solvers and the stability check use.

:class:`Loading` is what a static solve balances at one point of its load path: the dead
load vector Q (N) and the couple M (N m) on the end face; at load parameter t the
scene's loads are ``loading.scaled(t)``.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from numba import njit

from mechanics.end_rotation import rotation_derivatives

from ..core.banded import Banded
from ..kinematics.face import EndFace


@dataclass(frozen=True)
class Loading:
    """The external loads at one point of a static load path: the dead vector ``Q`` (N)
    and the end couple ``M`` (N m) on ``face`` (None: no couple)."""
    Q: np.ndarray
    M: float = 0.0
    face: EndFace | None = None

    def scaled(self, t: float) -> "Loading":
        return replace(self, Q=self.Q * t, M=self.M * t)

    @property
    def has_couple(self) -> bool:
        return self.face is not None and self.M != 0.0

    def force(self, u: np.ndarray) -> np.ndarray:
        """Q + M dtheta/du (N): the external force at u."""
        if not self.has_couple:
            return self.Q
        g, _ = rotation_derivatives(self.face.first_moment(u))
        f = self.Q.copy()
        np.add.at(f, self.face.rows, self.M * (g @ self.face.A))
        return f

    def stiffness(self, u: np.ndarray) -> np.ndarray:
        """M A^T H A (m, m) on ``face.rows``: the external force's derivative in u."""
        _, H = rotation_derivatives(self.face.first_moment(u))
        return self.M * self.face.A.T @ H @ self.face.A

    def out_of_balance(self, model, u: np.ndarray) -> np.ndarray:
        """f_int(u) - the external force (N), every dof."""
        return model.internal_force(u) - self.force(u)

    def out_of_balance_and_tangent(self, model, u: np.ndarray) -> tuple[np.ndarray, Banded]:
        """(f_int(u) - f_ext(u), K_int - d f_ext / du): the residual and the tangent of the
        total potential."""
        f, K = model.internal_force_and_tangent(u)
        if self.has_couple:
            rows = self.face.rows
            K.ab[K.b + rows[:, None] - rows[None, :], rows[None, :]] -= self.stiffness(u)
        return f - self.force(u), K

    def potential(self, u: np.ndarray, theta: float | None = None) -> float:
        """-Q . u - M theta (J): the loads' potential; theta continued along the path where
        the caller has it (else its principal value)."""
        out = -float(self.Q @ u)
        if self.has_couple:
            out -= self.M * (self.face.rotation(u) if theta is None else theta)
        return out

    def compiled(self) -> tuple:
        """(rows, A, d0, M): the couple's arrays for :func:`add_couple` (empty without one)."""
        if not self.has_couple:
            return np.zeros(0, np.int64), np.zeros((2, 0)), np.zeros(2), 0.0
        f = self.face
        return (np.ascontiguousarray(f.rows), np.ascontiguousarray(f.A), np.ascontiguousarray(f.d0),
                float(self.M))


def as_loading(loads) -> Loading:
    """A :class:`Loading` as it is, or a dead load vector Q (N) made one."""
    return loads if isinstance(loads, Loading) else Loading(np.asarray(loads, dtype=float))


@njit(cache=True)
def add_couple(u, rows, A, d0, M, f, S, b, with_tangent):
    """f -= M A^T g(d) and, with the tangent, its upper column band S (K[r, c] =
    S[c, b - (c - r)], r <= c) -= M A^T H(d) A: the couple moved to the left-hand side of
    f_int(u) - f_ext(u) = 0 (:class:`Loading`, the same terms)."""
    m = rows.shape[0]
    if m == 0 or M == 0.0:
        return
    dx, dy = d0[0], d0[1]
    for k in range(m):
        dx += A[0, k] * u[rows[k]]
        dy += A[1, k] * u[rows[k]]
    r2 = dx * dx + dy * dy
    gx, gy = -dy / r2, dx / r2
    hxx = 2.0 * dx * dy / (r2 * r2)
    hxy = (dy * dy - dx * dx) / (r2 * r2)
    for k in range(m):
        f[rows[k]] -= M * (gx * A[0, k] + gy * A[1, k])
    if not with_tangent:
        return
    for k in range(m):
        hk0 = hxx * A[0, k] + hxy * A[1, k]
        hk1 = hxy * A[0, k] - hxx * A[1, k]
        for l in range(m):
            r, c = rows[k], rows[l]
            if r <= c:
                S[c, b - (c - r)] -= M * (hk0 * A[0, l] + hk1 * A[1, l])
