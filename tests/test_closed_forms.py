"""Rivlin's plane-strain flexure (studies.verification.closed_forms.rivlin_bending) against its limits and an
independent route. Every tolerance is derived from the numerics in the comment above it.

The laws' constants: the paper's (Table 2) for neo-Hookean, Mooney-Rivlin and Yeoh, Gent's example
(mu = 1.906 MPa, Jm = 0.1, which caps the faces' I1 - 3 = 4 sinh^2(asinh(kappa h) / 2) below Jm:
kappa h < 0.3198)."""
import math

import numpy as np
import pytest

from contract import paper
from mechanics.laws import get_law
from studies.verification.closed_forms import (DERIVATIVES, plane_stress_bending, plane_stress_curvature, rivlin_bending,
                                  rivlin_curvature, rivlin_moment_mooney_rivlin)

from .conftest import tiered

H = 0.005                                            # m, the paper's section height
EPS = np.finfo(float).eps


def _constants(law):
    return dict(get_law("gent").example) if law == "gent" else dict(paper.materials()[law])


LAWS = ["neo-hookean", "mooney-rivlin", "yeoh", "gent"]
# the curvatures kappa h of the exact checks: moderate to large, within each law's domain
CURVATURES = {"neo-hookean": [0.1, 0.5, 1.0], "mooney-rivlin": [0.1, 0.5, 1.0], "yeoh": [0.1, 0.5, 1.0],
              "gent": [0.1, 0.2, 0.3]}


def _small_strain(law, c):
    """(mu, G'(3) / G(3)), G = W1 + W2, from the laws' energies typed again here (not DERIVATIVES)."""
    if law == "neo-hookean":
        return 2.0 * c["C10"], 0.0
    if law == "mooney-rivlin":
        return 2.0 * (c["C10"] + c["C01"]), 0.0
    if law == "yeoh":
        return 2.0 * c["C10"], 2.0 * c["C20"] / c["C10"]
    if law == "gent":
        return c["mu"], 1.0 / c["Jm"]
    raise KeyError(law)


# (a) M / w = mu h^3 kappa / 3 (1 + c x^2 + c2 x^4 + ...), x = kappa h, c = -3/10 + (3/5) G'(3)/G(3)
# (derived in rivlin_bending's doc). Tolerance on the measured c = (ratio - 1) / x^2: the next term
# c2 x^2 / c. Neo-Hookean's series gives c2 = 9/56 (|c2 / c| = 0.54); Gent's expansion parameter is
# x^2 / Jm: its s^7 term 1 / (7 Jm^2) = 14.3 against a^3 / 3 gives c2 ~ 45 and |c2 / c| ~ 8 (c = 5.7);
# Yeoh's is between. At x <= 0.01: |c2 x^2 / c| <= 1e-3. Quadrature (relative 1e-13) on a departure
# c x^2 >= 0.16 * 2.5e-5: <= 3e-8 of it. Tolerance 1e-2 relative on c, at x = 0.01 and 0.005: the same c
# at both is the x^2 law (a departure of order x or x^3 would change c by a factor 2 or 4).
@pytest.mark.parametrize("law", LAWS)
def test_rivlin_small_curvature_is_the_plane_strain_beam_with_a_departure_of_order_kappa_h_squared(law):
    c = _constants(law)
    mu, slope = _small_strain(law, c)
    c_theory = -0.3 + 0.6 * slope
    measured = []
    for x in (0.01, 0.005):
        kappa = x / H
        ratio = rivlin_bending(law, c, kappa, H)["moment_per_width"] / (4.0 * mu * H ** 3 / 12.0 * kappa)
        measured.append((ratio - 1.0) / x ** 2)
        assert abs(ratio - 1.0) <= 1.01 * abs(c_theory) * x ** 2, (law, x, ratio)
    for m in measured:
        assert m == pytest.approx(c_theory, rel=1e-2), (law, measured, c_theory)


def _shoot(law, c, kappa, h):
    """The radial equilibrium d sigma_rr / dr = (sigma_tt - sigma_rr) / r integrated (solve_ivp, DOP853,
    rtol 1e-12) from a traction-free inner face r_a, with sigma_tt - sigma_rr from the principal Cauchy
    stresses 2 W1 (l1^2 - l2^2) - 2 W2 (l1^-2 - l2^-2), l1 = r / R0 (hoop), l2 = R0 / r (radial), l3 = 1,
    both invariants computed from the three stretches. Only incompressibility is shared with the closed
    form (r_b^2 = r_a^2 + 2 R0 h); neither What nor lambda_a lambda_b = 1 is used: r_a is shot on until
    sigma_rr(r_b) = 0: brentq on the first + to - change of sigma_rr(r_b) in a scan down from lambda_a = 1
    (every fibre stretched: sigma_rr(r_b) > 0) by 0.005, between two lambda_a whose faces are in the law's
    domain (W1 + W2 > 0: Gent's window at kappa h = 0.3 is lambda_a in (0.854, 0.879)).
    Returns (lambda_a, lambda_b, M / w = int sigma_tt r dr, N / w = int sigma_tt dr)."""
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq

    R0 = 1.0 / kappa
    mu = 2.0 * sum(DERIVATIVES[law](3.0, 3.0, c))

    def difference(r):
        l1, l2 = r / R0, R0 / r
        I1, I2 = l1 ** 2 + l2 ** 2 + 1.0, (l1 * l2) ** 2 + l2 ** 2 + l1 ** 2
        W1, W2 = DERIVATIVES[law](I1, I2, c)
        return 2.0 * W1 * (l1 ** 2 - l2 ** 2) - 2.0 * W2 * (l1 ** -2 - l2 ** -2)

    def valid(lam):
        lb = math.sqrt(lam ** 2 + 2.0 * kappa * h)
        return lam > 0.0 and all(0.0 < sum(DERIVATIVES[law](l ** 2 + l ** -2 + 1, l ** 2 + l ** -2 + 1, c))
                                 < math.inf for l in (lam, lb))

    def run(lam_a):
        ra = R0 * lam_a
        rb = math.sqrt(ra ** 2 + 2.0 * R0 * h)

        def rhs(r, y):
            d = difference(r)
            return [d / r, (y[0] + d) * r, y[0] + d]
        sol = solve_ivp(rhs, (ra, rb), [0.0, 0.0, 0.0], method="DOP853", rtol=1e-12,
                        atol=[1e-16 * mu, 1e-16 * mu * R0 * h, 1e-16 * mu * h])
        assert sol.success
        return rb / R0, sol.y[:, -1]

    residual = lambda lam: run(lam)[1][0] / mu
    prev = None                                      # the last valid (lambda_a, residual) of the scan
    for lam in np.arange(1.0, 0.0, -0.005):
        if not valid(lam):
            prev = None
            continue
        f = residual(lam)
        if prev is not None and prev[1] > 0.0 > f:
            lo, hi = lam, prev[0]
            break
        prev = (lam, f)
    else:
        raise AssertionError("no sign change of sigma_rr(r_b) over lambda_a in (0, 1]")
    lam_a = brentq(residual, lo, hi, xtol=1e-15, rtol=1e-15, maxiter=500)
    lam_b, (_, m, n) = run(lam_a)
    return lam_a, lam_b, m, n


# (b) The shot against the closed form. Errors: the ODE's rtol 1e-12 (a local tolerance: allow 100 for
# the global error, 1e-10); the couple about the centre, int sigma_tt r dr, cancels tension against
# compression by |int| / M ~ 3 / (kappa h) <= 30; the root lambda_a moves by the residual's error over
# d residual / d lambda_a ~ 4 G kappa h, relative 1e-12. Expected <= 3e-9; tolerance 1e-8 relative on
# lambda_a, lambda_b and M, and |N| <= 1e-8 sigma_outer h (N's integrand is at most sigma_outer).
@pytest.mark.parametrize("law", LAWS)
def test_rivlin_closed_form_matches_a_shot_on_the_radial_equilibrium(law):
    c = _constants(law)
    for x in CURVATURES[law]:
        ref = rivlin_bending(law, c, x / H, H)
        lam_a, lam_b, m, n = _shoot(law, c, x / H, H)
        assert lam_a == pytest.approx(ref["lambda_inner"], rel=1e-8, abs=0), (law, x)
        assert lam_b == pytest.approx(ref["lambda_outer"], rel=1e-8, abs=0), (law, x)
        assert m == pytest.approx(ref["moment_per_width"], rel=1e-8, abs=0), (law, x)
        assert abs(n) <= 1e-8 * ref["stress_hoop_outer"] * H, (law, x, n)


# (c) M / w = (C10 + C01) / kappa^2 (x sqrt(1 + x^2) - asinh x) by hand against the quadrature. The
# closed form cancels two terms ~ x to leave (2/3) x^3: relative rounding 3 eps / x^2 (6.7e-12 at
# x = 0.1); the quadrature's relative 1e-13. Tolerance 1e-12 + 30 eps / x^2 (7e-11 at x = 0.1, 1e-12
# at x >= 1).
@pytest.mark.parametrize("law", ["neo-hookean", "mooney-rivlin"])
def test_rivlin_moment_in_closed_form_matches_the_quadrature(law):
    c = _constants(law)
    for x in (0.1, 0.5, 1.0, 2.0, 5.0):
        closed = rivlin_moment_mooney_rivlin(c["C10"], c.get("C01", 0.0), x / H, H)
        quad = rivlin_bending(law, c, x / H, H)["moment_per_width"]
        assert quad == pytest.approx(closed, rel=1e-12 + 30 * EPS / x ** 2, abs=0), (law, x)
    # bounded by (C10 + C01) h^2 from below: the inverse must refuse a larger couple
    with pytest.raises(ValueError):
        rivlin_curvature(law, c, 1.001 * (c["C10"] + c.get("C01", 0.0)) * H ** 2, H)


# (d) N / w by nested quadrature (inner relative 1e-13 of sigma_outer, outer absolute 1e-14 sigma_outer h):
# |N| <= 1e-11 sigma_outer h. The inverse: brentq to 1e-14 in kappa h on a couple known to 1e-13,
# amplified by 1 / (dln M / dln kappa) >= 1/2 for these curvatures (Gent's grows near its lock):
# tolerance 1e-11 relative on kappa. The kinematic outputs against identities of r^2 = r_a^2 + 2 R0 (Y + h/2)
# (exact formulas, rounding only): relative 1e-13.
@pytest.mark.parametrize("law", LAWS)
def test_rivlin_axial_force_vanishes_the_inverse_round_trips_and_the_kinematics_hold(law):
    c = _constants(law)
    for x in CURVATURES[law] + [0.01] + ([0.319] if law == "gent" else [2.0]):
        kappa = x / H
        r = rivlin_bending(law, c, kappa, H)
        assert abs(r["axial_force_per_width"]) <= 1e-11 * r["stress_hoop_outer"] * H, (law, x)
        assert rivlin_curvature(law, c, r["moment_per_width"], H) == pytest.approx(kappa, rel=1e-11, abs=0)
        R0, ra, rb = r["radius_unstretched"], r["radius_inner"], r["radius_outer"]
        assert (rb ** 2 - ra ** 2) == pytest.approx(2.0 * R0 * H, rel=1e-13)
        assert r["radius_mid"] ** 2 == pytest.approx(ra ** 2 + R0 * H, rel=1e-13)
        assert R0 ** 2 == pytest.approx(ra ** 2 + 2.0 * R0 * (r["offset_unstretched"] + H / 2), rel=1e-13)
        assert r["thickness_ratio"] == pytest.approx((rb - ra) / H, rel=1e-13)
        assert r["lambda_outer"] * r["lambda_inner"] == pytest.approx(1.0, rel=1e-15)
    assert rivlin_bending(law, c, 0.0, H)["moment_per_width"] == 0.0 == rivlin_curvature(law, c, 0.0, H)


def test_rivlin_gent_refuses_a_curvature_past_its_lock():
    c = _constants("gent")
    x_lock = math.sinh(math.acosh(1.0 + c["Jm"] / 2.0))        # the faces' I1 - 3 = 2 cosh(a) - 2 = Jm
    rivlin_bending("gent", c, 0.999 * x_lock / H, H)
    with pytest.raises(ValueError):
        rivlin_bending("gent", c, 1.001 * x_lock / H, H)


# -- pure bending in plane stress (plane_stress_bending) -----------------------------------------

def _neo_hookean_second_order(C10: float, kappa: float, h: float) -> tuple[float, float]:
    """An independent route for neo-Hookean: the Euler-Lagrange equation of the same energy
    written as a second-order ODE in r(Y) with W's second derivatives by hand,
    W(t, r) = C10 (t^2 + r^2 + (t r)^-2 - 3): r'' = kappa (W_t - W_rt r') / W_rr, the faces'
    radial stretch from W_r = 0 (r = t^-1/2), shooting on r(-h/2); (M / w, lambda_mid)."""
    from scipy.integrate import quad, solve_ivp
    from scipy.optimize import brentq

    Wt = lambda t, r: C10 * (2 * t - 2 / (t ** 3 * r * r))
    Wr = lambda t, r: C10 * (2 * r - 2 / (r ** 3 * t * t))
    Wrr = lambda t, r: C10 * (2 + 6 / (r ** 4 * t * t))
    Wrt = lambda t, r: C10 * 4 / (r ** 3 * t ** 3)

    def shot(rb):
        f = lambda Y, y: [y[1], kappa * (Wt(kappa * y[0], y[1]) - Wrt(kappa * y[0], y[1]) * y[1])
                          / Wrr(kappa * y[0], y[1])]
        return solve_ivp(f, (-h / 2, h / 2), [rb, (kappa * rb) ** -0.5], method="DOP853", rtol=1e-12,
                         atol=1e-14 * h, dense_output=True)

    rb = brentq(lambda rb: Wr(kappa * shot(rb).y[0, -1], shot(rb).y[1, -1]), max(1 / kappa - h, 0.05 / kappa),
                1 / kappa, xtol=1e-15 / kappa)
    s = shot(rb)
    M = quad(lambda Y: Wt(kappa * s.sol(Y)[0], s.sol(Y)[1]) * s.sol(Y)[0], -h / 2, h / 2, epsrel=1e-12)[0]
    return M, kappa * s.sol(0.0)[0]


# The two routes integrate the same problem to rtol 1e-12 (and shoot to 1e-15): agreement to
# 1e-9 relative leaves three orders for the solvers' error growth over the thickness.
@pytest.mark.parametrize("x", [0.05, 0.5, 1.0])
def test_plane_stress_bending_agrees_with_the_second_order_route(x):
    c = _constants("neo-hookean")
    r = plane_stress_bending("neo-hookean", c, x / H, H)
    M, lam_mid = _neo_hookean_second_order(c["C10"], x / H, H)
    assert r["moment_per_width"] == pytest.approx(M, rel=1e-9)
    assert r["lambda_mid"] == pytest.approx(lam_mid, rel=1e-9)


# Small curvature: M / w -> 3 mu h^3 / 12 kappa (plane stress, incompressible: E = 3 mu), with a
# departure of order (kappa h)^2: its coefficient measured at x = 0.01 and 0.005 agrees to 1 %
# (the next term is O(x^2) smaller: 1e-4). The axial force vanishes to its quadrature's 1e-12 mu h;
# the faces are uniaxial (their radial stress is 0): for neo-Hookean their radial stretch is
# t^-1/2 exactly, which the solver's shot meets to 1e-10 relative. The inverse: brentq to 1e-13.
# neo-Hookean's exact faces in the quick tier, the other laws' shots (about 2.5 s each) in the full one
@pytest.mark.parametrize("law", tiered(LAWS, lambda law: law != "neo-hookean",
                                       "test_plane_stress_bending_small_curvature_limit_zero_axial_force_and_inverse"))
def test_plane_stress_bending_small_curvature_limit_zero_axial_force_and_inverse(law):
    c = _constants(law)
    W1, W2 = DERIVATIVES[law](3.0, 3.0, c)
    mu = 2 * (W1 + W2)
    coef = []
    for x in (0.01, 0.005):
        r = plane_stress_bending(law, c, x / H, H)
        coef.append((r["moment_per_width"] / (mu * H ** 3 / 4 * x / H) - 1) / x ** 2)
        assert abs(r["axial_force_per_width"]) <= 1e-11 * mu * H
    assert coef[0] == pytest.approx(coef[1], rel=1e-2)
    x = min(CURVATURES[law])
    r = plane_stress_bending(law, c, x / H, H)
    assert plane_stress_curvature(law, c, r["moment_per_width"], H) == pytest.approx(x / H, rel=1e-10)
