"""Closed forms and published tables that no solver of this project computes: the
references of the benchmark suite (:mod:`studies.verification.benchmarks`).

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
  code_aster validation manual V6.04.138, "Benchmark solution");
- :func:`plane_stress_bending`: the same pure bending of a plane-stress strip (free faces out of
  the plane), whose 2D law is compressible in the plane: not a closed form but a two-point
  boundary-value problem in the thickness, solved by shooting to round-off (its derivation in
  the function); :func:`plane_stress_curvature` inverts it;
- :func:`rivlin_bending`: Rivlin's flexure (1949), the exact plane-strain pure bending of an
  incompressible block for any law of :data:`DERIVATIVES`: at the curvature kappa (bending angle per
  reference length) the face stretches lambda_b = 1 / lambda_a = exp(asinh(kappa h) / 2) and the couple
  M / w = 2 / kappa^2 int_0^asinh(kappa h) (W1 + W2)(1 + 2 cosh s) sinh(s)^2 ds (quadrature);
  :func:`rivlin_curvature` inverts it, :func:`rivlin_moment_mooney_rivlin` is its closed form for the
  Mooney-Rivlin family (neo-Hookean included);
- :func:`rigid_swing_time`: the rigid limit of the pinned pendulum released from the horizontal, the
  time to the vertical K(1/sqrt 2) sqrt(I / (m g c)) (the compound pendulum of amplitude pi / 2, a
  quarter of its period 4 sqrt(I / (m g c)) K(sin(theta_0 / 2)); e.g. Landau and Lifshitz, Mechanics,
  section 11, problem 1), for a bar of length L and height h pinned at the centre of an end face:
  c = L / 2, I / m = L^2 / 3 + h^2 / 12.
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
# Bisshopp and Drucker's (1945) own table of u / L, v / L against alpha is not here: no copy of its
# digits that could be cited exactly was at hand, and none is typed from memory.


def rigid_swing_time(length: float, height: float, g: float) -> float:
    """Seconds from the horizontal (at rest) to the vertical of a rigid bar pinned at the centre of
    an end face (see the module doc); scipy's ellipk takes the parameter m = k^2 = 1 / 2."""
    from scipy.special import ellipk

    return float(ellipk(0.5)) * math.sqrt((length ** 2 / 3 + height ** 2 / 12) / (g * length / 2))


# --- Rivlin's flexure: pure bending of an incompressible block in plane strain -----------------------------

def _plane_strain_G(law: str, constants: Mapping[str, float], I: float) -> float:
    """W1 + W2 at I1 = I2 = I (plane strain, incompressible: both invariants are lambda^2 + lambda^-2 + 1)."""
    W1, W2 = DERIVATIVES[law](I, I, constants)
    return W1 + W2


def rivlin_bending(law: str, constants: Mapping[str, float], kappa: float, height: float) -> dict[str, float]:
    """Pure bending (flexure) of an incompressible isotropic block in plane strain, exact at any curvature.

    Source: R. S. Rivlin (1949), "Large elastic deformations of isotropic materials V. The problem of
    flexure", Proc. R. Soc. Lond. A 195, 463-473; the same solution in R. W. Ogden, Non-linear Elastic
    Deformations (1984), section 5.2 (bending of a rectangular block). The steps below were derived again
    here, not copied (the book's page and equation numbers were not checked).

    Kinematics. The block X in [0, L_b], Y in [-h/2, h/2] goes to polar coordinates (r(Y), theta = kappa X):
    ``kappa`` (1/m) is the INPUT, the bending angle per reference length, psi / L_b: the radial end
    sections turn by kappa L_b relative to each other (a beam's end-face rotation per length). In the polar
    basis F = r'(Y) e_r (x) E_Y + r kappa e_t (x) E_X, so det F = kappa r r' = 1 gives r dr/dY = R0 = 1 / kappa:
    R0 is the radius of the fibre that keeps its length (hoop stretch lambda = r kappa = r / R0, radial
    stretch r' = 1 / lambda, lambda_3 = 1), and lambda^2 = lambda_a^2 + 2 kappa (Y + h/2), whence
    lambda_b^2 - lambda_a^2 = 2 kappa h (a = inner face Y = -h/2, b = outer face Y = h/2).

    Equilibrium. sigma_i = lambda_i dW/dlambda_i - p, so with What(lambda) = W(lambda, 1/lambda, 1),
    sigma_tt - sigma_rr = lambda What'(lambda) = 2 (W1 + W2)(lambda^2 - lambda^-2) (I1 = I2 = I =
    lambda^2 + lambda^-2 + 1). The radial equation d sigma_rr / dr = (sigma_tt - sigma_rr) / r with
    dr / r = dlambda / lambda integrates to sigma_rr = What(lambda) - What(lambda_a) (inner face free).
    The outer face free: What(lambda_b) = What(lambda_a); What depends on lambda through I only, I is even
    in ln(lambda) and What' = 2 (W1 + W2)(lambda - lambda^-3) > 0 for lambda > 1 when W1 + W2 > 0, so the
    one root is lambda_a = 1 / lambda_b. With s = ln(lambda^2): s_b = -s_a = a = asinh(kappa h), i.e.
    lambda_b = exp(a / 2) = (kappa h + sqrt(1 + (kappa h)^2))^(1/2) for every law; I = 1 + 2 cosh s.

    Resultants per width. N = int sigma_tt dr = [r sigma_rr]_a^b = 0 (sigma_tt = d(r sigma_rr)/dr). The
    couple M = int sigma_tt r dr = -int r sigma_rr dr (by parts) = R0^2 int_a^b (lambda^2 / 2) What' dlambda;
    folding [lambda_a, 1] onto [1, lambda_b] (lambda -> 1/lambda) and s = ln(lambda^2) give the positive
    integrand used here, by quadrature (scipy quad, relative tolerance 1e-13) for every law:

        M / w = 2 R0^2 int_0^asinh(kappa h) (W1 + W2)(1 + 2 cosh s) sinh(s)^2 ds.

    A closed form exists for the Mooney-Rivlin family (W1 + W2 constant; :func:`rivlin_moment_mooney_rivlin`,
    the test's check) and, in hyperbolic functions, for Yeoh; neither is used here. Small curvature:
    M / w = mu h^3 kappa / 3 (1 + c (kappa h)^2 + ...), mu = 2 (W1 + W2) at I = 3 (the plane-strain
    modulus 4 mu times h^3 / 12), c = -3/10 + (3/5) G'(3) / G(3), G = W1 + W2.

    Returns (SI): ``moment_per_width`` (N m / m), ``lambda_outer``, ``lambda_inner``, ``thickness_ratio``
    (deformed thickness / h = 2 sinh(a / 2) / (kappa h)), ``radius_unstretched`` (R0, the lambda = 1 fibre),
    ``offset_unstretched`` (its reference Y, m: (1 - sqrt(1 + (kappa h)^2)) / (2 kappa), on the inner side),
    ``radius_mid`` (the reference mid-surface Y = 0: R0 (1 + (kappa h)^2)^(1/4)), ``radius_inner``,
    ``radius_outer``, ``stress_hoop_outer`` and ``stress_hoop_inner`` (Cauchy, Pa: +-4 G(I_b) kappa h) and
    ``axial_force_per_width`` (N/m), a CHECK: int sigma_tt dr by nested quadrature (sigma_rr itself by
    quadrature of G dI), which must vanish. ``kappa`` must be >= 0 (mirror Y to bend the other way); a law
    with a locking stretch (Gent) raises ValueError when the faces reach it.
    """
    from scipy.integrate import quad

    if kappa < 0.0 or height <= 0.0:
        raise ValueError(f"kappa = {kappa!r} must be >= 0 and height = {height!r} > 0")
    if kappa == 0.0:
        return {"kappa": 0.0, "moment_per_width": 0.0, "lambda_outer": 1.0, "lambda_inner": 1.0,
                "thickness_ratio": 1.0, "radius_unstretched": math.inf, "offset_unstretched": 0.0,
                "radius_mid": math.inf, "radius_inner": math.inf, "radius_outer": math.inf,
                "stress_hoop_outer": 0.0, "stress_hoop_inner": 0.0, "axial_force_per_width": 0.0}
    x = kappa * height
    a = math.asinh(x)
    R0 = 1.0 / kappa
    G = lambda s: _plane_strain_G(law, constants, 1.0 + 2.0 * math.cosh(s))
    Gb = G(a)                                   # the faces' I is the largest in the block
    if not (math.isfinite(Gb) and Gb > 0.0):
        raise ValueError(f"{law}: kappa h = {x:g} takes the faces out of the law's domain (W1 + W2 = {Gb!r})")
    moment = 2.0 * R0 ** 2 * quad(lambda s: G(s) * math.sinh(s) ** 2, 0.0, a, epsabs=0.0, epsrel=1e-13,
                                  limit=200)[0]
    sigma_b = 4.0 * Gb * x                      # sigma_tt at the outer face (sigma_rr = 0 there)

    def sigma_rr(s):                            # What(lambda) - What(lambda_a) = -int_|s|^a 2 G sinh t dt
        return -quad(lambda t: 2.0 * G(t) * math.sinh(t), abs(s), a, epsabs=1e-15 * sigma_b, epsrel=1e-13,
                     limit=200)[0]

    # N = int sigma_tt dr, r = R0 e^(s/2), dr = (r / 2) ds, sigma_tt = sigma_rr + 4 G sinh s
    axial = quad(lambda s: (sigma_rr(s) + 4.0 * G(s) * math.sinh(s)) * R0 * math.exp(s / 2.0) / 2.0, -a, a,
                 epsabs=1e-14 * sigma_b * height, epsrel=1e-12, limit=200)[0]
    return {"kappa": kappa, "moment_per_width": moment,
            "lambda_outer": math.exp(a / 2.0), "lambda_inner": math.exp(-a / 2.0),
            "thickness_ratio": 2.0 * math.sinh(a / 2.0) / x,
            "radius_unstretched": R0, "offset_unstretched": -height * x / (2.0 * (1.0 + math.sqrt(1.0 + x * x))),
            "radius_mid": R0 * (1.0 + x * x) ** 0.25,
            "radius_inner": R0 * math.exp(-a / 2.0), "radius_outer": R0 * math.exp(a / 2.0),
            "stress_hoop_outer": sigma_b, "stress_hoop_inner": -sigma_b, "axial_force_per_width": axial}


def rivlin_moment_mooney_rivlin(C10: float, C01: float, kappa: float, height: float) -> float:
    """M / w (N m / m) of :func:`rivlin_bending` in closed form for W = C10 (I1 - 3) + C01 (I2 - 3)
    (neo-Hookean: C01 = 0). W1 + W2 = C10 + C01 is constant and int_0^a sinh^2 = (sinh a cosh a - a) / 2 with
    sinh a = kappa h, so M / w = (C10 + C01) / kappa^2 (kappa h sqrt(1 + (kappa h)^2) - asinh(kappa h)),
    which tends to (C10 + C01) h^2 from below: the plane-strain moment of this family is bounded. Derived
    here from the integral of :func:`rivlin_bending`; loses digits to cancellation as eps / (kappa h)^2."""
    x = kappa * height
    return (C10 + C01) / kappa ** 2 * (x * math.sqrt(1.0 + x * x) - math.asinh(x)) if x else 0.0


def rivlin_curvature(law: str, constants: Mapping[str, float], moment_per_width: float, height: float) -> float:
    """The inverse of :func:`rivlin_bending`: the curvature kappa >= 0 (1/m, bending angle per reference
    length) at which the couple per width is ``moment_per_width`` (N m / m, >= 0). From the small-curvature
    guess kappa = 3 M / (mu h^3) the bracket doubles while M(kappa) rises and stays below the target (halving
    back towards the last good kappa when a law's locking stretch is met), then brentq; the first crossing.
    Raises ValueError when no curvature up to kappa h = 1e4 carries the moment (the Mooney-Rivlin family's
    moment is bounded by (C10 + C01) h^2)."""
    from scipy.optimize import brentq

    if moment_per_width < 0.0:
        raise ValueError(f"moment_per_width = {moment_per_width!r} must be >= 0 (mirror Y)")
    if moment_per_width == 0.0:
        return 0.0
    target = moment_per_width

    def f(x):                                   # in x = kappa h; raises ValueError past a lock
        return rivlin_bending(law, constants, x / height, height)["moment_per_width"] - target

    mu = 2.0 * _plane_strain_G(law, constants, 3.0)
    lo, f_lo = 0.0, -target
    hi = 3.0 * target / (mu * height ** 2)
    while True:
        try:
            f_hi = f(hi)
        except ValueError:                      # past the lock: come back halfway
            if hi - lo <= 1e-15 * hi:
                raise
            hi = lo + 0.5 * (hi - lo)
            continue
        if f_hi >= 0.0:
            x = brentq(f, lo, hi, xtol=1e-16, rtol=1e-14, maxiter=500)
            return x / height
        if hi > 1e4 or f_hi < f_lo:
            raise ValueError(f"{law}: no curvature up to kappa h = {hi:g} carries M / w = {target:g} N m / m")
        lo, f_lo, hi = hi, f_hi, 2.0 * hi


# -- pure bending in plane stress ---------------------------------------------------------------

def _plane_stress_partials(law: str, constants: Mapping[str, float], t: float, r: float) -> tuple[float, float]:
    """(dW/dt, dW/dr) of the plane-stress energy W(t, r) = W(lambda_1 = t, lambda_2 = r,
    lambda_3 = 1 / (t r)) (free faces out of the plane, incompressible): I1 = t^2 + r^2 +
    (t r)^-2, I2 = t^2 r^2 + t^-2 + r^-2."""
    I1 = t * t + r * r + 1.0 / (t * r) ** 2
    I2 = (t * r) ** 2 + 1.0 / (t * t) + 1.0 / (r * r)
    W1, W2 = DERIVATIVES[law](I1, I2, constants)
    return (W1 * (2.0 * t - 2.0 / (t ** 3 * r * r)) + W2 * (2.0 * t * r * r - 2.0 / t ** 3),
            W1 * (2.0 * r - 2.0 / (r ** 3 * t * t)) + W2 * (2.0 * r * t * t - 2.0 / r ** 3))


def plane_stress_bending(law: str, constants: Mapping[str, float], kappa: float, height: float) -> dict[str, float]:
    """The exact pure bending of a plane-stress strip (incompressible, free faces out of the
    plane and across the thickness) at the bending angle per reference length kappa (1/m).

    The strip's reference point (X, Y) goes to polar (r(Y), kappa X), so the hoop stretch
    is t = kappa r and the radial stretch r'(Y); the energy per reference length and width,
    E = int W(kappa r, r') dY over Y in [-h/2, h/2], is stationary in r(Y) (the same
    argument as Rivlin's flexure, for a 2D law that is compressible in the plane: the
    thickness out of the plane takes up the change of area): with the radial nominal
    stress P_r = dW/dr,

        r' = the radial stretch at which dW/dr = P_r,    P_r' = kappa dW/dt,

    and P_r = 0 on both faces (traction-free). Solved by shooting on r(-h/2) (scipy's
    solve_ivp, DOP853, rtol 1e-12; brentq for the radial stretch at each point and for the
    shot). The couple is M / w = dE / dkappa = int dW/dt r dY (the envelope theorem), the
    axial force N / w = int dW/dt dY = [P_r] = 0 (a check). Only the law's W1 and W2 are
    used (:data:`DERIVATIVES`); rivlin_bending is the plane-strain twin, in closed form.

    Returns moment_per_width (N m / m), axial_force_per_width (N / m, ~0), lambda_mid (the
    hoop stretch of the reference mid-line Y = 0), lambda_outer and lambda_inner (hoop
    stretches of the faces), thickness_ratio (r(h/2) - r(-h/2)) / h, kappa."""
    from scipy.integrate import quad, solve_ivp
    from scipy.optimize import brentq

    if kappa <= 0.0:
        raise ValueError(f"kappa: must be > 0, got {kappa!r}")
    h, k = float(height), float(kappa)

    def radial_stretch(t: float, P: float) -> float:
        """The radial stretch at which dW/dr = P, bracketed from the free face's t^-1/2 by
        steps of 1 % (a law with a lock, Gent's, is not monotone past it)."""
        f = lambda r: _plane_stress_partials(law, constants, t, r)[1] - P
        lo = hi = 1.0 / math.sqrt(t)
        for _ in range(500):
            if f(lo) <= 0.0 <= f(hi):
                return brentq(f, lo, hi, xtol=1e-15, rtol=1e-15, maxiter=200)
            lo, hi = (lo / 1.01, hi) if f(lo) > 0.0 else (lo, hi * 1.01 if f(hi) < 0.0 else hi)
        raise ValueError(f"{law}: no radial stretch carries P = {P:g} Pa at the hoop stretch {t:g}")

    def rhs(Y, y):
        r, P = y
        t = k * r
        lr = radial_stretch(t, P)
        return [lr, k * _plane_stress_partials(law, constants, t, lr)[0]]

    def shot(r0: float):
        return solve_ivp(rhs, (-h / 2, h / 2), [r0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14 * h,
                         dense_output=True)

    # the inner face lies inside the fibre of unit stretch (1 / kappa), less than 3 h / 4 inside it
    R0 = 1.0 / k
    r_inner = brentq(lambda r0: shot(r0).y[1, -1], max(R0 - 0.75 * h, 0.05 * R0), R0, xtol=1e-15 * R0, rtol=1e-15,
                     maxiter=200)
    sol = shot(r_inner)

    def hoop(Y: float) -> float:
        r, P = sol.sol(Y)
        return _plane_stress_partials(law, constants, k * r, radial_stretch(k * r, P))[0]

    W1, W2 = DERIVATIVES[law](3.0, 3.0, constants)
    scale = 2.0 * (W1 + W2) * h                       # mu h: N's scale (N is 0 up to round-off)
    M = quad(lambda Y: hoop(Y) * sol.sol(Y)[0], -h / 2, h / 2, epsabs=1e-13 * scale * h, epsrel=1e-12, limit=200)[0]
    N = quad(hoop, -h / 2, h / 2, epsabs=1e-13 * scale, epsrel=1e-12, limit=200)[0]
    r_out = float(sol.y[0, -1])
    return {"moment_per_width": M, "axial_force_per_width": N, "lambda_mid": k * float(sol.sol(0.0)[0]),
            "lambda_outer": k * r_out, "lambda_inner": k * r_inner, "thickness_ratio": (r_out - r_inner) / h,
            "kappa": k}


def plane_stress_curvature(law: str, constants: Mapping[str, float], moment_per_width: float,
                           height: float) -> float:
    """kappa (1/m) of :func:`plane_stress_bending` at the couple M / w (N m / m), > 0: from the
    small-curvature guess M / (3 mu h^3 / 12) (mu = 2 (W1 + W2) at the reference state),
    bracketed by factors of 1.5 and found by brentq."""
    from scipy.optimize import brentq

    W1, W2 = DERIVATIVES[law](3.0, 3.0, constants)
    guess = moment_per_width / (3.0 * 2.0 * (W1 + W2) * height ** 3 / 12.0)
    f = lambda k: plane_stress_bending(law, constants, k, height)["moment_per_width"] - moment_per_width
    lo, hi = guess / 1.5, guess * 1.5
    while f(lo) > 0.0:
        lo /= 1.5
    while f(hi) < 0.0:
        hi *= 1.5
    return brentq(f, lo, hi, xtol=1e-14 * guess, rtol=1e-13, maxiter=100)
