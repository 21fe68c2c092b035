"""The planar ANCF cable with an incompressible hyperelastic section (``kinematics = "cable"``).

The centre line r(x) is interpolated from position and slope at the nodes (HC2n-8: cubic
Hermite, r and r_x at two nodes, 8 dof); the section is not interpolated but integrated.
Euler-Bernoulli kinematics with eta = Y: the fibre at height Y stays at r + Y n, n the
unit left normal of r_x, so its stretch is

    lambda(X, Y) = |r_x| - Y theta_X,     theta_X = (r_x x r_xx) / |r_x|^2

(theta the angle of r_x, theta_X its rotation per reference length), and the strain
energy is

    U = w int_0^L int_(-h/2)^(h/2) W_u(lambda(X, Y)) dY dX,    W_u(lambda) = W(lambda, lambda^-1/2, lambda^-1/2),

W_u the law's exact incompressible uniaxial energy (free lateral faces: the lateral
stretches lambda^-1/2 follow from incompressibility), every law through its plane-stress
formulation (:func:`ancf.core.tape.trace_uniaxial`). The rule is Gauss along (the element's
points along) times Gauss across the section (its points across). The numpy reference
(``*_numpy``) sees at each fibre e = r_x and g = Y r_xx as the two columns of a "gradient"
(:attr:`CableModel._dN`: dN[p, s] = (N_s'(X), Y N_s''(X))); the compiled kernels
(:mod:`ancf.kinematics.cable.kernels`, through the same element interface as the continuum-based
elements, :mod:`ancf.kinematics.kernels`) take G = [r_x | r_xx] once per point along and the
section's resultants of W_u' and W_u'' over its fibres (:attr:`CableModel.fused`: N', N''
at the points along, the section rule as the element's fields), the same B for both.

What the model leaves out, by construction: shear (Euler-Bernoulli), the section's change
of thickness (eta = Y; with the thickness change d eta / dY = lambda^-1/2 the fibres move,
:func:`section_moment` measures both), the radial stress of a curved strip (each fibre is
in uniaxial stress; the exact plane-stress bending, :func:`studies.verification.closed_forms.plane_stress_bending`,
is not: the card and tests/test_cable.py state the model error of order (kappa h)^2 this
makes), and rotary inertia (the mass is rho h w int N^T N dx). Plane stress only: a scene in
``plane-strain`` or ``paper`` is refused (:func:`ancf.build.check`).

Supports (:meth:`ancf.kinematics.cable.Cable.fixed_dofs`): a clamp fixes r and the direction of r_x (its
y-component); ``pin`` and ``hinge`` fix r; ``slide`` is the clamp (the section, always
normal to r_x, held on the plane x = 0 fixes r_x's direction; the centre held fixes r).
The end face of the end moment is d = R90 r_x(L) (:meth:`ancf.kinematics.cable.Cable.end_face`).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ...core.banded import Banded
from ..model import ElementModel, refuse_discrete_gradient
from ...core.errors import InadmissibleState
from ...core.jet import Jet


@dataclass
class CableModel(ElementModel):
    """The cable's model (see the module doc): points (X_q, Y_j) of the rule, p = q n_y + j."""

    INADMISSIBLE = "a fibre's stretch <= 0 (or not finite) at a quadrature point"
    pressure = None            # no element pressure field, no assumed strain
    assumed = None
    sampled = None

    # -- the element's data ------------------------------------------------------------
    @cached_property
    def _dN(self) -> np.ndarray:
        """(nq, ns, 2): N_s'(X_p) and Y_p N_s''(X_p) at the rule's points (1/m, -)."""
        m = self.mesh
        return m.element.family.point_data(m.element, self.rule.xi, self.rule.eta, m.element_length, m.height)

    @cached_property
    def _tape(self):
        """The law's uniaxial energy W_u(lambda), traced once (:func:`ancf.core.tape.trace_uniaxial`)."""
        from ...core.tape import trace_uniaxial
        return trace_uniaxial(self.material)

    @cached_property
    def tensor(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The rule as points along times points across: (xi (nx,), weights along (nx,),
        eta (ny,), weights across (ny,)), the weights summing to 1 each; ValueError for a
        rule that is not a tensor product (gauss makes them, point along outer)."""
        r = self.rule
        nx = len(np.unique(r.xi))
        ny = len(r.xi) // nx
        xi, eta, W = r.xi.reshape(nx, ny), r.eta.reshape(nx, ny), r.weight.reshape(nx, ny)
        wx, wy = W.sum(axis=1), W[0] / W[0].sum()
        if nx * ny != len(r.xi) or np.ptp(xi, axis=1).max() > 0 or np.ptp(eta, axis=0).max() > 0 \
                or not np.allclose(W, np.outer(wx, wy), rtol=1e-14, atol=0):
            raise ValueError(f"element {self.mesh.element.name}: a cable's rule is points along times points across")
        return xi[:, 0], wx, eta[0], wy

    @cached_property
    def fused(self) -> tuple:
        """What the compiled loops read (:mod:`ancf.kinematics.cable.kernels`): N' and N'' at the points
        along (nx, ns, 2), their weights times l_e, element dofs, the uniaxial tape, the
        section rule as the element's fields (pr[0] = (Y_j, w_j h w_b), :func:`section_fields`),
        the band envelope."""
        from ...core.bandsolve import envelope
        from .kernels import section_fields
        m = self.mesh
        xi, wx, eta, wy = self.tensor
        z = np.zeros_like(xi)
        _, d1 = m.element.tabulate(xi, z, m.element_length, m.height)
        d2 = m.element.tabulate_derivative(xi, z, m.element_length, m.height, 2)
        ops, consts = self._tape
        return (np.ascontiguousarray(np.stack([d1[..., 0], d2], axis=-1)),
                np.ascontiguousarray(wx * m.element_length, dtype=float),
                np.ascontiguousarray(self._dofs, dtype=np.int64), np.ascontiguousarray(ops),
                np.ascontiguousarray(consts, dtype=float),
                section_fields(eta * m.height, wy * m.height * m.width, len(xi)),
                envelope(self._dofs, self.mesh.n_dof))

    @property
    def full_rule(self):
        """Exact along for the squared cubic, two points across (a strain linear in Y)."""
        from ...core.quadrature import gauss
        dx = self.mesh.element.degree()[0]
        return gauss(dx + 1, 2)

    def roundoff_floor(self, u: np.ndarray) -> float:
        return self.static_kernel.roundoff_floor(u)

    def discrete_gradient_force_and_tangent(self, u0, u1):
        refuse_discrete_gradient(self)

    # -- kinematics, numpy (the reference of the compiled kernels) -------------------
    def slopes(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """e = r_x and g = Y r_xx at every element and point, (ne, nq, 2) each."""
        G = (u[self._dofs] @ self._B_flat.T).reshape(self.mesh.n_elements, -1, 2, 2)
        e = G[..., :, 0] + np.array([1.0, 0.0])
        return e, G[..., :, 1]

    def stretches(self, u: np.ndarray) -> np.ndarray:
        """The fibre stretch lambda = |r_x| - Y theta_X at every element and point (ne, nq)."""
        e, g = self.slopes(u)
        s2 = np.einsum("...i,...i->...", e, e)
        return np.sqrt(s2) - (e[..., 0] * g[..., 1] - e[..., 1] * g[..., 0]) / s2

    def _admissible(self, u: np.ndarray) -> None:
        lam = self.stretches(u)
        if not np.all(np.isfinite(lam)) or lam.min() <= 0.0:
            raise InadmissibleState(f"a fibre's stretch {lam.min():.3g} <= 0 at a quadrature point")

    def uniaxial_energy(self, lam: np.ndarray) -> Jet:
        """W_u and its first two derivatives at stretches lam (the Jet's v, a, aa): the
        material's plane-stress energy at F = diag(lam, lam^-1/2) by numpy's jets (the tape's
        reference)."""
        return _uniaxial(self.material, lam)

    def _stress(self, u: np.ndarray, tangent: bool):
        """P (ne, nq, 4) = W_u' dlambda and A (ne, nq, 4, 4) = W_u'' dl dl^T + W_u' d2lambda in
        vec(e, g) = (e_x, g_x, e_y, g_y), and W_u (ne, nq)."""
        self._admissible(u)
        e, g = self.slopes(u)
        ex, ey, gx, gy = e[..., 0], e[..., 1], g[..., 0], g[..., 1]
        s2 = ex * ex + ey * ey
        s, p = np.sqrt(s2), 1.0 / s2
        c = ex * gy - ey * gx
        lam = s - c * p
        W = self.uniaxial_energy(lam)
        z = np.zeros_like(ex)
        ds = np.stack([ex / s, z, ey / s, z], axis=-1)
        dc = np.stack([gy, -ey, -gx, ex], axis=-1)
        dp = np.stack([-2 * ex * p * p, z, -2 * ey * p * p, z], axis=-1)
        dl = ds - p[..., None] * dc - c[..., None] * dp
        P = W.a[..., None] * dl
        if not tangent:
            return W.v, P, None
        s3, p3 = s * s2, p * p * p
        d2s = np.zeros(ex.shape + (4, 4))
        d2s[..., 0, 0], d2s[..., 2, 2] = ey * ey / s3, ex * ex / s3
        d2s[..., 0, 2] = d2s[..., 2, 0] = -ex * ey / s3
        d2c = np.zeros((4, 4))
        d2c[0, 3] = d2c[3, 0] = 1.0
        d2c[1, 2] = d2c[2, 1] = -1.0
        d2p = np.zeros(ex.shape + (4, 4))
        d2p[..., 0, 0] = -2 * p * p + 8 * ex * ex * p3
        d2p[..., 2, 2] = -2 * p * p + 8 * ey * ey * p3
        d2p[..., 0, 2] = d2p[..., 2, 0] = 8 * ex * ey * p3
        outer = dc[..., :, None] * dp[..., None, :]
        H = d2s - p[..., None, None] * d2c - outer - np.swapaxes(outer, -1, -2) - c[..., None, None] * d2p
        A = W.aa[..., None, None] * dl[..., :, None] * dl[..., None, :] + W.a[..., None, None] * H
        return W.v, P, A

    def strain_energy_numpy(self, u: np.ndarray) -> float:
        W, _, _ = self._stress(u, tangent=False)
        return float(np.sum(W * self._w))

    def internal_force_numpy(self, u: np.ndarray) -> np.ndarray:
        _, P, _ = self._stress(u, tangent=False)
        fe = P.reshape(P.shape[0], -1) @ self._Bw_flat
        return np.bincount(self._dofs.ravel(), fe.ravel(), minlength=self.mesh.n_dof)

    def internal_force_and_tangent_numpy(self, u: np.ndarray) -> tuple[np.ndarray, Banded]:
        _, P, A = self._stress(u, tangent=True)
        ne, nq = P.shape[:2]
        fe = P.reshape(ne, -1) @ self._Bw_flat
        AB = A @ self._B[None]                              # (ne, nq, 4, nd)
        Ke = self._Bw_flat.T @ AB.reshape(ne, nq * 4, -1)
        f = np.bincount(self._dofs.ravel(), fe.ravel(), minlength=self.mesh.n_dof)
        return f, self.pattern.assemble(Ke)

    # -- outputs ------------------------------------------------------------------------
    def section_points(self, u: np.ndarray, xi: np.ndarray, eta: np.ndarray) -> np.ndarray:
        """Deformed positions r(x) + Y n(x) (ne, len(xi), 2) of the points (xi, eta) of every
        element (Y = eta h; the drawn section, eta = Y)."""
        m = self.mesh
        N, dN = m.element.tabulate(xi, np.zeros_like(xi), m.element_length, m.height)
        q = (m.reference + u)[m.element_dofs]                       # (ne, ns, 2)
        r = np.einsum("pa,eai->epi", N, q)
        t = np.einsum("pa,eai->epi", dN[..., 0], q)
        n = np.stack([-t[..., 1], t[..., 0]], axis=-1) / np.linalg.norm(t, axis=-1, keepdims=True)
        return r + (np.asarray(eta) * m.height)[None, :, None] * n


# -- the section's bending moment, numpy: eta = Y against the thickness change ------------------

def section_energy(material, stretch: float, kappa: float, height: float, points: int = 64,
                   thickness_change: bool = False) -> float:
    """The section's energy per reference length and width, int W_u(lambda(Y)) dY (J/m^2),
    at the centre line's stretch and the rotation per reference length kappa (1/m), by
    Gauss-Legendre with ``points`` across. eta = Y: lambda = s - Y kappa (the cable's
    kinematics). ``thickness_change``: the fibre at Y sits at eta(Y) with d eta / dY =
    lambda^-1/2 (the lateral stretch of incompressible uniaxial stress), eta(0) = 0, so
    lambda = s - eta(Y) kappa, eta by an ODE solved to 1e-12 (scipy)."""
    y, wy = np.polynomial.legendre.leggauss(points)
    Y = 0.5 * height * y
    if thickness_change:
        eta = _eta(stretch, kappa, Y)
    else:
        eta = Y
    lam = stretch - eta * kappa
    return float(0.5 * height * np.sum(wy * _uniaxial(material, lam).v))


def _uniaxial(material, lam) -> Jet:
    """W_u(lam) with its lam-derivatives in the Jet's v, a, aa (numpy's jets)."""
    jl, _ = Jet.variables(np.asarray(lam, float), np.zeros(np.shape(lam)))
    I1, I2 = material.formulation.invariants(jl ** 2 + jl ** -1, jl ** 0.5)
    return material.law.psi(I1, I2, material.constants)


def _eta(stretch: float, kappa: float, Y: np.ndarray) -> np.ndarray:
    """eta(Y) from d eta / dY = (s - eta kappa)^-1/2, eta(0) = 0, at the points Y."""
    from scipy.integrate import solve_ivp

    out = np.zeros_like(Y)
    for sign in (1.0, -1.0):
        pts = Y[Y * sign > 0]
        if len(pts) == 0:
            continue
        order = np.argsort(np.abs(pts))
        sol = solve_ivp(lambda t, z: [(stretch - z[0] * kappa) ** -0.5], (0.0, pts[order][-1]), [0.0],
                        t_eval=pts[order], rtol=1e-12, atol=1e-15)
        vals = np.empty(len(pts))
        vals[order] = sol.y[0]
        out[Y * sign > 0] = vals
    return out


def section_moment(material, kappa: float, height: float, points: int = 64,
                   thickness_change: bool = False) -> dict:
    """The section's bending moment per width M / w (N m / m) at the curvature kappa (1/m)
    with no axial force: the stretch s where dE/ds = 0, then M / w = dE/dkappa (E the
    :func:`section_energy`), both by central differences of step 1e-5 relative (eta = Y:
    exact derivatives instead, int W_u'(lambda) (-Y) dY). Returns moment_per_width,
    stretch (the centre line's at N = 0)."""
    from scipy.optimize import brentq

    y, wy = np.polynomial.legendre.leggauss(points)
    Y, wY = 0.5 * height * y, 0.5 * height * wy
    if not thickness_change:
        def N(s):
            return float(np.sum(wY * _uniaxial(material, s - Y * kappa).a))
        s = brentq(N, 0.9, 1.1, xtol=1e-15, rtol=1e-15)
        M = float(np.sum(wY * _uniaxial(material, s - Y * kappa).a * (-Y)))
        return {"moment_per_width": M, "stretch": s}
    E = lambda s, k: section_energy(material, s, k, height, points, True)
    ds = 1e-5

    def N(s):
        return (E(s + ds, kappa) - E(s - ds, kappa)) / (2 * ds)
    s = brentq(N, 0.9, 1.1, xtol=1e-13, rtol=1e-13)
    dk = 1e-5 * kappa
    return {"moment_per_width": (E(s, kappa + dk) - E(s, kappa - dk)) / (2 * dk), "stretch": s}
