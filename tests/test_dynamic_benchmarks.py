"""The dynamic benchmarks' references by second routes: Timoshenko's frequency determinant against
a Ritz solution of the same beam and against Euler-Bernoulli's limit, the matrix pencil on a
synthetic history, and the cases' scenes (admitted by both solvers, the swing case's output)."""
import math

import numpy as np
import pytest
from numpy.polynomial import legendre

from studies.verification import dynamic_benchmarks as D


def ritz_timoshenko(L, EI, kGA, rhoA, rhoI, degree=14) -> float:
    """omega_1 of the clamped-free Timoshenko beam by Ritz: w and psi as xi P_k(2 xi - 1), xi = x / L,
    k < ``degree`` (Legendre polynomials: both vanish at the clamp), energies by Gauss-Legendre
    quadrature."""
    xg, wg = legendre.leggauss(40)
    xi = (xg + 1) / 2
    wq = wg * L / 2
    n = degree
    Pk = np.array([legendre.legval(2 * xi - 1, np.eye(n)[k]) for k in range(n)])
    dPk = np.array([legendre.legval(2 * xi - 1, legendre.legder(np.eye(n)[k])) for k in range(n)])
    P = xi * Pk
    dP = (Pk + 2 * xi * dPk) / L
    Z = np.zeros((n, n))
    # unknowns (a: w, c: psi); U = 1/2 int EI psi'^2 + kGA (w' - psi)^2, T = 1/2 int rhoA w^2 + rhoI psi^2
    Kww = kGA * (dP * wq) @ dP.T
    Kwp = -kGA * (dP * wq) @ P.T
    Kpp = EI * (dP * wq) @ dP.T + kGA * (P * wq) @ P.T
    K = np.block([[Kww, Kwp], [Kwp.T, Kpp]])
    M = np.block([[rhoA * (P * wq) @ P.T, Z], [Z, rhoI * (P * wq) @ P.T]])
    from scipy.linalg import eigh

    return math.sqrt(eigh(K, M, eigvals_only=True)[0])


def test_timoshenkos_frequency_by_a_second_route_and_its_euler_bernoulli_limit():
    """The transfer-matrix root against Ritz (degree 14: converged to 1e-9 on mode 1) at L/h 5, 10
    and 20, and the limit of no shear compliance and no rotary inertia against cos bL cosh bL = -1
    (bL = 1.8751040687...)."""
    g = D.STUDY["grid"]
    for ratio in (5, 10, 20):
        s = D._section(g, ratio)
        args = (s["L"], s["E"] * s["I"], D.KAPPA * s["G"] * s["A"], s["rho"] * s["A"], s["rho"] * s["I"])
        assert D.timoshenko_frequency(*args) == pytest.approx(ritz_timoshenko(*args), rel=1e-8)
    s = D._section(g, 10)
    EI, rhoA = s["E"] * s["I"], s["rho"] * s["A"]
    eb = D.euler_bernoulli_frequency(s["L"], EI, rhoA)
    assert eb == pytest.approx(1.8751040687119611 ** 2 / s["L"] ** 2 * math.sqrt(EI / rhoA), rel=1e-12)
    assert D.timoshenko_frequency(s["L"], EI, 1e6 * EI / s["h"] ** 2, rhoA, 1e-12 * rhoA * s["h"] ** 2) == \
        pytest.approx(eb, rel=1e-6)


def test_the_matrix_pencil_recovers_a_constant_plus_modes():
    t = np.arange(200) * 1e-3
    om = [26.1, 163.0, 455.0]
    y = 0.3 + 1e-3 * np.cos(om[0] * t) - 2e-4 * np.cos(om[1] * t + 0.3) + 5e-5 * np.sin(om[2] * t)
    got = D.pencil_frequencies(t, y, modes=4)
    assert got[0] == pytest.approx(om[0], rel=1e-9)
    assert any(abs(o / om[1] - 1) < 1e-8 for o in got)


def test_the_cases_are_admitted_by_their_solvers():
    """Every case's scene passes its solver's checks (ANCF's admission; the continuum's settings),
    and the swing case's outputs are fine enough for its cubic reading."""
    from contract.scene import scene_from_dict
    from ancf.admission import check
    from reference_fem.settings import fem_settings

    from studies.engine.catalog import load_catalog

    g = load_catalog()["dynamic-benchmarks"].grid
    for s in D._solvers(g):
        for d in [D.swing_scene(g, s)] + [D.frequency_scene(g, r, s) for r in g["ratios"]]:
            sc = scene_from_dict(d)
            if s in D._codes(g):
                fem_settings(sc)
            else:
                check(sc)
    assert g["swing_every"] <= 0.005
