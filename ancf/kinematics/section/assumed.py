"""Assumed strains along the beam: components of C taken from fewer points along x.

An element may name components of C = F^T F (``ElementSpec.assumed``: "xx" the membrane
stretch, "yy" the thickness stretch, "xy" the shear) that the elastic rule does not take
at its own points. They are sampled at ``ElementSpec.assumed_points`` Gauss points along
the beam, at each of the rule's rows across the thickness, and carried to the rule's
points along by Lagrange interpolation: C_bar_c(x_r) = sum_p T_c[r, p] C_c(x_p). The energy
is the law's at the assumed C,

    U = sum_e sum_r w_r W(a_bar, J_bar),   a_bar = tr C_bar,   J_bar = sqrt(det C_bar),

and the force and tangent are its exact derivatives. With the element's pressure field
the penalty acts on the projection of J_bar - 1.

Why (tests/oracles/assumed_membrane.py, README "Which strain carries it"): a cubic
centre line in large rotation cannot keep its membrane stretch at 1 at four points along
an element; it bends too stiffly (membrane locking). In small strain eps_xx is quadratic
along x (u_x is cubic), so three points see it exactly and an assumed C_xx leaves the
stiffness at u = 0, and with it the rank tests, as they are.

This module tabulates the sampling (:func:`sampling`: the rule's points followed by the
sample points, weights zero there, and T) and holds the numpy reference
(:class:`AssumedStrain`) that the compiled kernel (:func:`ancf.kinematics.section.assumed_kernels.assumed_terms`) is
tested against. The force is f = sum_p sum_c S_pc dC_c(p)/du with the point stresses
S_pc = sum_r w_r dW/dC_bar_c(r) T_c[r, p]; the tangent adds to the geometric part
sum_p sum_c S_pc d2C_c(p)/du2 the material part sum_r w_r g_r^T D_r g_r,
g_rc = dC_bar_c(r)/du, D_r = d2W/dC_bar2.
"""
from __future__ import annotations

import numpy as np

from ...core.quadrature import Rule, gauss

COMPONENTS = ("xx", "yy", "xy")     # C_bar's order: c = 0, 1, 2


def sampling(components: tuple[str, ...], points: int, rule: Rule) -> tuple[Rule, np.ndarray]:
    """The points the assumed strain reads (the rule's, then ``points`` x n_y sample
    points, with weight zero) and T (3, nq, nq + ns): C_bar_c at the rule's points from
    C_c at all of them (the identity on the rule's own for a component not assumed).

    The rule must be a tensor rule, x-major (:func:`ancf.core.quadrature.gauss`)."""
    xs, ys = np.unique(rule.xi.round(14)), np.unique(rule.eta.round(14))
    nx, ny = len(xs), len(ys)
    if nx * ny != len(rule.xi) or not np.allclose(rule.xi.reshape(nx, ny), xs[:, None]):
        raise ValueError("ancf.kinematics.section.assumed: an assumed strain needs a tensor rule (points along x times "
                         "points across)")
    sample = gauss(points, ny)
    xp = np.unique(sample.xi.round(14))
    # Lagrange from the sample points along to the rule's points along: L (nx, points)
    L = np.array([[np.prod([(x - xp[j]) / (xp[i] - xp[j]) for j in range(points) if j != i])
                   for i in range(points)] for x in xs])
    nq, ns = nx * ny, points * ny
    T = np.zeros((3, nq, nq + ns))
    for c, name in enumerate(COMPONENTS):
        if name in components:
            # rule point (i, j) <- sample points (k, j): index i ny + j <- nq + k ny + j
            for j in range(ny):
                T[c, j::ny, nq + j::ny] = L
        else:
            T[c, :, :nq] = np.eye(nq)
    points_all = Rule(np.concatenate([rule.xi, sample.xi]), np.concatenate([rule.eta, sample.eta]),
                      np.concatenate([rule.weight, np.zeros(ns)]))
    return points_all, T


def _C(f: np.ndarray) -> np.ndarray:
    """(C_xx, C_yy, C_xy) (..., 3) of gradients f (..., 4) = (F00, F01, F10, F11)."""
    return np.stack([f[..., 0] ** 2 + f[..., 2] ** 2, f[..., 1] ** 2 + f[..., 3] ** 2,
                     f[..., 0] * f[..., 1] + f[..., 2] * f[..., 3]], axis=-1)


class AssumedStrain:
    """The numpy reference of an element with assumed strains (module docstring).

    material: the law the points see (its penalty included unless ``penalty`` carries it);
    dN (np, ns, 2): shape gradients at :func:`sampling`'s points; w (np,): their weights
    times the element volume (zero at the sample points); T: :func:`sampling`'s; penalty:
    an :class:`ancf.kinematics.section.pressure.ProjectedPenalty` at the rule's points, or None."""

    def __init__(self, material, dN: np.ndarray, w: np.ndarray, T: np.ndarray, penalty=None):
        self.material, self.dN, self.T, self.penalty = material, dN, T, penalty
        self.nq = T.shape[1]
        self.w = w[:self.nq]

    def _kinematics(self, ue: np.ndarray):
        """F (ne, np, 4), C_bar (ne, nq, 3), g = dC_bar/du_e (ne, nq, 3, nd) and dC/du_e
        (ne, np, 3, nd) at element displacements ue (ne, nd); InadmissibleState if det F <= 0
        at a point (as the compiled kernels' point_gradients)."""
        ne, ns = len(ue), self.dN.shape[1]
        gu = np.einsum("eki,qkj->eqij", ue.reshape(ne, ns, 2), self.dN)
        f = (gu + np.eye(2)).reshape(ne, -1, 4)
        J = f[..., 0] * f[..., 3] - f[..., 1] * f[..., 2]
        if not np.all(np.isfinite(f)) or J.min() <= 0.0:              # an inverted point: C cannot tell
            from ...core.errors import InadmissibleState
            raise InadmissibleState(f"det F = {J.min():.3g} <= 0 at a point")
        # dC_c(p)/du_(s, i): xx 2 F_i0 dN_s,x, yy 2 F_i1 dN_s,y, xy F_i0 dN_s,y + F_i1 dN_s,x
        Fi0, Fi1 = f[..., [0, 2]], f[..., [1, 3]]                      # (ne, np, 2): i
        dx, dy = self.dN[..., 0], self.dN[..., 1]                      # (np, ns)
        dC = np.stack([2 * np.einsum("epi,ps->epsi", Fi0, dx), 2 * np.einsum("epi,ps->epsi", Fi1, dy),
                       np.einsum("epi,ps->epsi", Fi0, dy) + np.einsum("epi,ps->epsi", Fi1, dx)],
                      axis=2).reshape(ne, f.shape[1], 3, -1)
        Cbar = np.einsum("crp,epc->erc", self.T, _C(f))
        g = np.einsum("crp,epcd->ercd", self.T, dC)
        return f, Cbar, g, dC

    def _law(self, Cbar: np.ndarray):
        det = Cbar[..., 0] * Cbar[..., 1] - Cbar[..., 2] ** 2
        if not np.all(np.isfinite(Cbar)) or det.min() <= 0.0:
            from ...core.errors import InadmissibleState
            raise InadmissibleState(f"det C_bar = {det.min():.3g} <= 0 at a quadrature point")
        J = np.sqrt(det)
        W = self.material.energy_jet(Cbar[..., 0] + Cbar[..., 1], J)
        WJ, U_vol, pk = W.J, 0.0, None
        if self.penalty is not None:
            pen = self.penalty
            gk = (J - 1.0) @ pen.wq                                    # (ne, nk)
            pk = pen.alpha * gk @ pen.minv
            U_vol = 0.5 * float(np.sum(gk * pk))
            WJ = WJ + pk @ pen.q.T
        return J, W, WJ, U_vol, pk

    def energy(self, ue: np.ndarray) -> float:
        _, Cbar, _, _ = self._kinematics(ue)
        _, W, _, U_vol, _ = self._law(Cbar)
        return float(np.sum(W.v * self.w)) + U_vol

    def element_terms(self, ue: np.ndarray, tangent: bool = True):
        """Element forces (ne, nd) and, if asked, stiffness blocks (ne, nd, nd)."""
        f, Cbar, g, dC = self._kinematics(ue)
        J, W, WJ, _, _ = self._law(Cbar)
        c0, c1, c2 = Cbar[..., 0], Cbar[..., 1], Cbar[..., 2]
        da = np.array([1.0, 1.0, 0.0])
        dJ = np.stack([c1 / (2 * J), c0 / (2 * J), -c2 / J], axis=-1)    # (ne, nq, 3)
        S = W.a[..., None] * da + WJ[..., None] * dJ                    # dW/dC_bar
        Sp = np.einsum("r,erc,crp->epc", self.w, S, self.T)            # point stresses
        fe = np.einsum("epc,epcd->ed", Sp, dC)
        if not tangent:
            return fe, None
        gp = np.stack([c1, c0, -2 * c2], axis=-1)                       # d det / dC_bar
        hess = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -2.0]])
        d2J = hess / (2 * J[..., None, None]) - gp[..., :, None] * gp[..., None, :] / (4 * J[..., None, None] ** 3)
        D = (W.aa[..., None, None] * np.outer(da, da)
             + W.aJ[..., None, None] * (da[:, None] * dJ[..., None, :] + dJ[..., :, None] * da[None, :])
             + W.JJ[..., None, None] * dJ[..., :, None] * dJ[..., None, :] + WJ[..., None, None] * d2J)
        Ke = np.einsum("r,ercd,erci,erdj->eij", self.w, D, g, g)
        dx, dy = self.dN[..., 0], self.dN[..., 1]
        geo = (2 * np.einsum("ep,ps,pt->est", Sp[..., 0], dx, dx) + 2 * np.einsum("ep,ps,pt->est", Sp[..., 1], dy, dy)
               + np.einsum("ep,ps,pt->est", Sp[..., 2], dx, dy) + np.einsum("ep,ps,pt->est", Sp[..., 2], dy, dx))
        Ke = Ke + np.einsum("est,ik->esitk", geo, np.eye(2)).reshape(Ke.shape)
        if self.penalty is not None:
            pen = self.penalty
            G = np.einsum("rk,erc,ercd->ekd", pen.wq, dJ, g)           # d g_k / du_e
            Ke = Ke + pen.alpha * np.swapaxes(G, 1, 2) @ (pen.minv @ G)
        return fe, Ke
