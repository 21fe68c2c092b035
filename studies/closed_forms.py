"""Closed forms and published tables that no solver of this project computes: the
references of the benchmark suite (:mod:`studies.benchmarks`).

Written from the textbook formulas, not from the solvers' code: each law's derivatives
W1 = dW/dI1 and W2 = dW/dI2 are typed here again (:data:`DERIVATIVES`), so a slip in
``mechanics.laws`` cannot hide in both sides of a comparison.

- :func:`uniaxial_stretch`: homogeneous uniaxial tension of an incompressible isotropic
  solid, in plane stress (free lateral faces, lambda_2 = lambda_3 = lambda^(-1/2)) and in
  plane strain (lambda_3 = 1, lambda_2 = 1 / lambda): the stretch lambda at which the
  nominal stress is P (Ogden, *Non-linear elastic deformations*, 1984, section 7.2.2:
  P = 2 (lambda - lambda^-2)(W1 + W2 / lambda) and P = 2 (lambda - lambda^-3)(W1 + W2));
- :func:`simple_shear_stress`: the shear stress of simple shear, tau = 2 gamma (W1 + W2),
  I1 = I2 = 3 + gamma^2 (Ogden 1984, section 5.3);
- :func:`elastica_tip_load`: the inextensible, unshearable cantilever under a dead tip
  load P perpendicular to its undeformed axis, by elliptic integrals (Bisshopp and
  Drucker 1945, Quart. Appl. Math. 3(3) 272-275): for alpha = P L^2 / (EI) the tip angle
  theta_0 solves sqrt(alpha) = K(k) - F(phi_1, k) with k^2 = (1 + sin theta_0) / 2 and
  sin phi_1 = 1 / (k sqrt 2); then u / L = 1 - sqrt(2 sin theta_0 / alpha) and
  v / L = 1 - (2 / sqrt(alpha)) (E(k) - E(phi_1, k)). :data:`MATTIASSON_1981` holds the
  published table it is checked against;
- :func:`elastica_end_moment`: the same cantilever under an end couple M, a circular arc
  of angle phi = M L / (EI): x / L = sin(phi) / phi, y / L = (1 - cos phi) / phi (Euler;
  code_aster validation manual V6.04.138, "Benchmark solution").
"""
from __future__ import annotations

import math
from typing import Callable, Mapping

# dW/dI1, dW/dI2 of each law, from its textbook energy (constants in Pa)
DERIVATIVES: dict[str, Callable[[float, float, Mapping[str, float]], tuple[float, float]]] = {
    # W = C10 (I1 - 3)
    "neo-hookean": lambda I1, I2, c: (c["C10"], 0.0),
    # W = C10 (I1 - 3) + C01 (I2 - 3)
    "mooney-rivlin": lambda I1, I2, c: (c["C10"], c["C01"]),
    # W = C10 (I1 - 3) + C20 (I1 - 3)^2 + C30 (I1 - 3)^3 (Yeoh 1993)
    "yeoh": lambda I1, I2, c: (c["C10"] + 2 * c["C20"] * (I1 - 3) + 3 * c["C30"] * (I1 - 3) ** 2, 0.0),
    # W = -mu Jm / 2 ln(1 - (I1 - 3) / Jm) (Gent 1996)
    "gent": lambda I1, I2, c: (0.5 * c["mu"] / (1.0 - (I1 - 3.0) / c["Jm"]), 0.0),
}


def nominal_stress(law: str, constants: Mapping[str, float], formulation: str, lam: float) -> float:
    """P (Pa, force per undeformed area) of incompressible uniaxial tension at stretch lam."""
    if formulation == "plane-stress":
        I1, I2 = lam ** 2 + 2.0 / lam, 2.0 * lam + lam ** -2
        W1, W2 = DERIVATIVES[law](I1, I2, constants)
        return 2.0 * (lam - lam ** -2) * (W1 + W2 / lam)
    if formulation == "plane-strain":
        I1 = I2 = lam ** 2 + lam ** -2 + 1.0
        W1, W2 = DERIVATIVES[law](I1, I2, constants)
        return 2.0 * (lam - lam ** -3) * (W1 + W2)
    raise ValueError(f"formulation: {formulation!r}; allowed: plane-stress, plane-strain")


def uniaxial_stretch(law: str, constants: Mapping[str, float], formulation: str, P: float) -> float:
    """The stretch lambda >= 1 at which the nominal stress is P > 0: the first crossing,
    bracketed by stretches 1 + 0.05 2^k rising while P(lambda) rises, then bisection."""
    from scipy.optimize import brentq

    f = lambda lam: nominal_stress(law, constants, formulation, lam) - P
    lo, k = 1.0, 0
    while True:
        hi = 1.0 + 0.05 * 2 ** k
        if f(hi) >= 0.0:
            return brentq(f, lo, hi, xtol=1e-15, rtol=1e-15, maxiter=500)
        if k > 8 or f(hi) < f(lo):
            raise ValueError(f"{law} {formulation}: no stretch up to {hi:g} carries P = {P:g} Pa")
        lo, k = hi, k + 1


def simple_shear_stress(law: str, constants: Mapping[str, float], gamma: float) -> float:
    """tau = 2 gamma (W1 + W2) at I1 = I2 = 3 + gamma^2 (Pa)."""
    I = 3.0 + gamma ** 2
    W1, W2 = DERIVATIVES[law](I, I, constants)
    return 2.0 * gamma * (W1 + W2)


def elastica_tip_load(alpha: float) -> tuple[float, float, float]:
    """(u / L, v / L, theta_0): the shortening, the deflection along the load and the tip
    angle (rad) of the inextensible cantilever at alpha = P L^2 / (EI) (see the module doc)."""
    from scipy.optimize import brentq
    from scipy.special import ellipe, ellipeinc, ellipk, ellipkinc

    def parts(th0):
        m = (1.0 + math.sin(th0)) / 2.0                # scipy's parameter m = k^2
        return m, math.asin(1.0 / math.sqrt(2.0 * m))

    def residual(th0):
        m, phi1 = parts(th0)
        return ellipk(m) - ellipkinc(phi1, m) - math.sqrt(alpha)

    th0 = brentq(residual, 1e-14, math.pi / 2 - 1e-15, xtol=1e-16, rtol=1e-15, maxiter=500)
    m, phi1 = parts(th0)
    u = 1.0 - math.sqrt(2.0 * math.sin(th0) / alpha)
    v = 1.0 - 2.0 / math.sqrt(alpha) * (ellipe(m) - ellipeinc(phi1, m))
    return u, v, th0


def elastica_end_moment(phi: float) -> tuple[float, float]:
    """(x / L, y / L) of the tip of a cantilever bent by an end couple into an arc of angle
    phi = M L / (EI) (rad)."""
    return (math.sin(phi) / phi, (1.0 - math.cos(phi)) / phi) if phi else (1.0, 0.0)


# Mattiasson, K. (1981), "Numerical results from large deflection beam and frame problems
# analysed by means of elliptic integrals", Int. J. Numer. Meth. Engng 17(1) 145-153, Table 1
# (cantilever, tip load): alpha = P L^2 / (EI) -> (u / L, v / L), five decimals. Not read
# from the paper: the rows as two open-source test suites quote them with that citation
# (Alex1977-code/Statikprogramm tests/test_theorie3.py at 1745c7b: alpha = 1 with the tip
# angle 0.46135 rad; a skyframe test file: alpha = 1, 2, 5, 10).
MATTIASSON_1981 = {1.0: (0.05643, 0.30172), 2.0: (0.16064, 0.49346), 5.0: (0.38763, 0.71379),
                   10.0: (0.55500, 0.81061)}
MATTIASSON_1981_DIGITS = 5
