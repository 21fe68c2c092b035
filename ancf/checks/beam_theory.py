"""Closed-form and beam-theory references for the checks (no dolfinx needed).

- :func:`effective_modulus`: the uniaxial in-plane modulus E of a formulation at small
  strain, mu = 2 (C10 + C01) (for ``paper``, mu = 2 dW/d(tr C) at tr C = 2):
  plane stress 3 mu; penalised plane strain 4 mu (K + mu/3) / (K + 4 mu/3), K = alpha;
  ``paper`` 4 mu (alpha + mu) / (alpha + 2 mu) (2D Lame lambda = alpha), i.e. 8 W_a as
  alpha / mu -> infinity.
- :func:`cantilever_tip_deflection`: Euler-Bernoulli plus Timoshenko shear deflection
  of a clamped-free beam under a uniform load.
- :func:`elastica_self_weight` and :func:`elastica_tip_load`: the inextensible,
  unshearable elastica (solved as boundary-value problems) for large deflections.
"""
from __future__ import annotations

import numpy as np

from scipy.integrate import solve_bvp

from ..core.material import Material

# the trapezoidal rule: numpy 2 names it trapezoid and no longer has trapz (a plain venv's
# numpy from PyPI), numpy 1.24 (Debian's) has trapz alone
_trapezoid = getattr(np, "trapezoid", None) or np.trapz


def effective_modulus(material: Material) -> float:
    form = material.formulation.name
    if form == "paper":
        mu = 2.0 * material.reference_stress_derivative()
        a = material.penalty
        return 4 * mu * (a + mu) / (a + 2 * mu)
    mu = material.law.shear_modulus(material.constants)
    if form == "plane-stress":
        return 3.0 * mu
    K = material.penalty
    return 4 * mu * (K + mu / 3) / (K + 4 * mu / 3)


def shear_modulus(material: Material) -> float:
    if material.formulation.name == "paper":
        return 2.0 * material.reference_stress_derivative()
    return material.law.shear_modulus(material.constants)


def cantilever_tip_deflection(q: float, L: float, E: float, G: float, h: float, w: float,
                              kappa: float = 5.0 / 6.0) -> float:
    """Tip deflection (m, along the load) under a uniform load q (N/m):
    q L^4 / (8 E I) + q L^2 / (2 kappa G A)."""
    I, A = w * h ** 3 / 12.0, w * h
    return q * L ** 4 / (8 * E * I) + q * L ** 2 / (2 * kappa * G * A)


def _tip(theta_sol, L):
    s = np.linspace(0.0, L, 4001)
    th = theta_sol.sol(s)[0]
    x = _trapezoid(np.cos(th), s)
    y = _trapezoid(np.sin(th), s)
    return x - L, y


def elastica_self_weight(q: float, L: float, EI: float) -> tuple[float, float]:
    """Tip displacement (ux, uy) of a clamped inextensible elastica under its own
    weight q (N/m, acting along -y): EI theta'' = q (L - s) cos theta, theta(0) = 0,
    theta'(L) = 0."""
    s = np.linspace(0.0, L, 401)

    def f(s, y):
        return np.vstack([y[1], q * (L - s) * np.cos(y[0]) / EI])

    def bc(ya, yb):
        return np.array([ya[0], yb[1]])

    guess = np.vstack([-q * L ** 3 / (6 * EI) * (s / L), np.zeros_like(s)])
    sol = solve_bvp(f, bc, s, guess, tol=1e-10, max_nodes=100000)
    if not sol.success:
        raise RuntimeError(f"elastica BVP: {sol.message}")
    return _tip(sol, L)


def elastica_tip_load(P: float, L: float, EI: float, side: float = 1.0) -> tuple[float, float]:
    """Tip displacement of a clamped inextensible elastica under a dead axial
    compressive tip load P (N, along -x), on its first buckled branch (P > P_cr):
    EI theta'' = -P sin theta, theta(0) = 0, theta'(L) = 0, solved by shooting on the
    root curvature (the first sign change of theta'(L), then Brent's method); ``side``
    (+1 / -1) picks the direction it bends to."""
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq

    def shoot(k, dense=False):
        return solve_ivp(lambda s, y: [y[1], -P * np.sin(y[0]) / EI], [0.0, L], [0.0, k],
                         rtol=1e-12, atol=1e-14, dense_output=dense)

    ks = np.linspace(1e-6, 60.0, 121) / L
    ends = [shoot(k).y[1, -1] for k in ks]
    i = next(i for i in range(len(ks) - 1) if ends[i] < 0 <= ends[i + 1])
    k = brentq(lambda k: shoot(k).y[1, -1], ks[i], ks[i + 1], xtol=1e-14)
    sol = shoot(k, dense=True)
    s = np.linspace(0.0, L, 4001)
    th = np.sign(side) * sol.sol(s)[0]
    return _trapezoid(np.cos(th), s) - L, _trapezoid(np.sin(th), s)
