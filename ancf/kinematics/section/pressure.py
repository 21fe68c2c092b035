"""The volumetric penalty on an element-wise pressure field: the u-p mixed form, condensed.

With an element pressure p (in the span of the element's ``pressure`` basis q_k) the
perturbed-Lagrangian energy is

    int [ psi + p (J - 1) - p^2 / (2 alpha) ] dV,

and p is eliminated element by element: with g_k = int q_k (J - 1) dV and the pressure
mass M_kl = int q_k q_l dV, the stationary p has coefficients p = alpha M^-1 g, and the
energy is

    U_vol = alpha/2 g^T M^-1 g = alpha/2 int (Pi (J - 1))^2 dV,

Pi the L2 projection onto the pressure basis. With a pressure value at every quadrature
point it is the pointwise penalty alpha/2 int (J - 1)^2 dV again (a test holds this); with
fewer pressure unknowns than points the constraint J = 1 is imposed weakly, and a
displacement field rich enough to meet it no longer locks (the beam analogue of the Q2/P1
or F-bar continuum elements; Malkus and Hughes 1978 for the equivalence with reduced
integration of the penalty).

Derivatives, with G_kj = dg_k/du_j = int q_k cof F : dF/du_j dV:

    f = G^T p,    K = alpha G^T M^-1 G + int (q . p) B^T E B dV,

E = d2(det F)/dF2 (constant in 2D), B the strain-displacement operator.
"""
from __future__ import annotations

import numpy as np

# d2(det F)/dF2 in the flattened index 2 i + j (as in ancf.core.material)
_E = np.array([[0, 0, 0, 1], [0, 0, -1, 0], [0, -1, 0, 0], [1, 0, 0, 0]], dtype=float)


class ProjectedPenalty:
    """alpha/2 int (Pi (J - 1))^2 dV per element, at the quadrature points of a beam model.

    q (nq, nk): the pressure basis at the points; w (nq,): weights times element volume;
    B (nq, 4, nd): vec(grad u) = B u_e at each point; alpha (Pa)."""

    def __init__(self, q: np.ndarray, w: np.ndarray, B: np.ndarray, alpha: float):
        mass = q.T @ (w[:, None] * q)
        if np.linalg.matrix_rank(mass) < q.shape[1]:
            raise ValueError(f"ancf.quadrature: the rule's {q.shape[0]} points do not resolve the "
                             f"element's pressure basis ({q.shape[1]} functions, rank "
                             f"{np.linalg.matrix_rank(mass)} at the points); use a rule with more "
                             "points across the thickness, or the element's default")
        self.alpha = float(alpha)
        self.wq = w[:, None] * q                               # (nq, nk)
        self.q = q
        self.minv = np.linalg.inv(mass)
        self.B = B
        self.w = w
        self.BEB = np.einsum("qai,ab,qbj->qij", B, _E, B)      # (nq, nd, nd)

    def _projected(self, F: np.ndarray):
        f = F.reshape(F.shape[0], F.shape[1], 4)
        J = f[..., 0] * f[..., 3] - f[..., 1] * f[..., 2]
        g = (J - 1.0) @ self.wq                                # (ne, nk)
        return f, g, self.alpha * g @ self.minv                # p (ne, nk)

    def energy(self, F: np.ndarray) -> float:
        """U_vol (J) of gradients F (ne, nq, 2, 2)."""
        _, g, p = self._projected(F)
        return 0.5 * float(np.sum(g * p))

    def _G(self, f: np.ndarray) -> np.ndarray:
        """dg/du_e (ne, nk, nd) at gradients f (ne, nq, 4)."""
        cof = np.stack([f[..., 3], -f[..., 2], -f[..., 1], f[..., 0]], axis=-1)
        dJ = (cof[:, :, None, :] @ self.B[None])[:, :, 0]     # (ne, nq, nd)
        return self.wq.T @ dJ

    def element_terms(self, F: np.ndarray, tangent: bool = True):
        """Element forces (ne, nd) and, if asked, stiffness blocks (ne, nd, nd)."""
        f, g, p = self._projected(F)
        G = self._G(f)
        fe = np.einsum("ek,ekj->ej", p, G)
        if not tangent:
            return fe, None
        pw = (p @ self.q.T) * self.w                           # pressure at the points times weight
        nd = G.shape[-1]
        Ke = self.alpha * np.swapaxes(G, 1, 2) @ (self.minv @ G) \
            + (pw @ self.BEB.reshape(len(self.w), -1)).reshape(-1, nd, nd)
        return fe, Ke

    def discrete_gradient_terms(self, F0: np.ndarray, F1: np.ndarray):
        """Element forces f_dg (ne, nd) with (u1 - u0) . f_dg = U_vol(u1) - U_vol(u0)
        exactly, and the midpoint stiffness / 2. In 2D g is quadratic in u, so
        g1 - g0 = G(u_mid) (u1 - u0), and U_vol(u1) - U_vol(u0) =
        (g1 - g0)^T alpha M^-1 (g1 + g0) / 2: f_dg = G(u_mid)^T p_bar with p_bar the
        pressure of (g0 + g1) / 2."""
        _, g0, p0 = self._projected(F0)
        _, g1, p1 = self._projected(F1)
        Fm = 0.5 * (F0 + F1)
        fm = Fm.reshape(Fm.shape[0], Fm.shape[1], 4)
        fe = np.einsum("ek,ekj->ej", 0.5 * (p0 + p1), self._G(fm))
        return fe, 0.5 * self.element_terms(Fm)[1]

    def magnitudes(self, F: np.ndarray) -> np.ndarray:
        """|terms| of the element forces (ne, nd): the sizes round-off acts on."""
        f, g, p = self._projected(F)
        cof = np.stack([f[..., 3], -f[..., 2], -f[..., 1], f[..., 0]], axis=-1)
        pw = np.abs(p @ self.q.T) * self.w                     # (ne, nq)
        return np.einsum("eq,eqa,qaj->ej", pw, np.abs(cof), np.abs(self.B))
