"""Contract tests over every law x formulation: Taylor tests, symmetry, objectivity,
the stress-free reference, closed-form uniaxial tension."""
import numpy as np
import pytest

from contract.errors import SceneError
from ancf.core.formulations import FORMULATIONS, get_formulation
from ancf.core.jet import Jet
from mechanics.laws import get_law

from .conftest import ALL_FORMULATIONS, ALL_LAWS, material

CASES = [(law, form) for law in ALL_LAWS for form in ALL_FORMULATIONS]


def random_F(rng, n=6, spread=0.3, m=None):
    """n gradients about I (det F > 0.2); with a material ``m``, inside its law's
    domain (Gent's energy is not a number beyond I1 - 3 = Jm): a gradient outside is
    drawn again closer to I, until twice its distance from I is inside too."""
    F = np.eye(2) + spread * rng.standard_normal((n, 2, 2))
    flip = np.linalg.det(F) <= 0.2
    F[flip] = np.eye(2) + 0.1 * rng.standard_normal((flip.sum(), 2, 2))
    def inside(F):     # the energy defined at F and at twice F's distance from I
        return np.isfinite(m.evaluate(F, tangent=False)[0] + m.evaluate(2 * F - np.eye(2), tangent=False)[0])

    while m is not None and not np.all(ok := inside(F)):
        spread /= 2
        F[~ok] = np.eye(2) + spread * rng.standard_normal(((~ok).sum(), 2, 2))
    return F


def compare_where_defined(got, ref, min_defined=0.3):
    """got equals ref to round-off where ref is a number, and is not a number where ref
    is not (a law's domain); at least ``min_defined`` of the points are defined."""
    ok = np.isfinite(ref[0])
    assert ok.mean() >= min_defined
    np.testing.assert_array_equal(np.isfinite(got[0]), ok)
    np.testing.assert_allclose(got[:, ok], ref[:, ok], rtol=1e-12, atol=1e-12 * np.abs(ref[:, ok]).max())


def taylor_slopes(f, df_dir, x, d, hs):
    """Observed orders of the remainder |f(x + h d) - f(x) - h df(x)[d]|."""
    r = [np.abs(f(x + h * d) - f(x) - h * df_dir).max() for h in hs]
    return np.diff(np.log(r)) / np.diff(np.log(hs)), r


@pytest.mark.parametrize("law,form", CASES)
def test_stress_and_tangent_are_the_energy_derivatives_taylor(law, form, rng):
    """|W(F + h d) - W(F) - h P:d - h^2/2 d:A:d| falls like h^3 (a wrong P leaves an
    O(h) remainder, a wrong A an O(h^2) one). The first-order remainder alone is not
    used: where d:A:d is nearly zero (indefinite A) its slope is meaningless."""
    m = material(law, form, penalty=20e6)   # a moderate penalty keeps the remainder above round-off
    # asymptotic range: c3 h^3 (~1e-2 Pa at h = 1e-3) >> c4 h^4 and >> eps W (~1e-10 Pa)
    hs = np.array([2e-3, 1e-3, 5e-4, 2.5e-4])
    for F in random_F(rng, m=m):
        d = rng.standard_normal((2, 2))
        _, P, A = m.evaluate(F[None])
        W = lambda G: m.evaluate(G[None])[0][0]
        r = [abs(W(F + h * d) - W(F) - h * np.sum(P[0] * d) - 0.5 * h * h * d.ravel() @ A[0] @ d.ravel())
             for h in hs]
        slopes = np.diff(np.log(r)) / np.diff(np.log(hs))
        # wrong P: slope 1, wrong A: slope 2; pre-asymptotic coarse pairs rise towards 3
        assert np.all(slopes > 2.5) and slopes[-1] > 2.8, slopes


@pytest.mark.parametrize("law,form", CASES)
def test_tangent_is_the_stress_gradient_taylor_and_symmetric(law, form, rng):
    m = material(law, form, penalty=20e6)
    hs = np.array([1e-2, 5e-3, 2.5e-3, 1.25e-3])
    for F in random_F(rng, m=m):
        d = rng.standard_normal((2, 2))
        _, _, A = m.evaluate(F[None])
        np.testing.assert_allclose(A[0], A[0].T, rtol=1e-12, atol=1e-12 * np.abs(A).max())
        AdP = (A[0] @ d.ravel()).reshape(2, 2)
        slopes, _ = taylor_slopes(lambda G: m.evaluate(G[None])[1][0], AdP, F, d, hs)
        assert np.all(slopes > 1.9), slopes


@pytest.mark.parametrize("law,form", CASES)
def test_objectivity(law, form, rng):
    m = material(law, form)
    F = random_F(rng, m=m)
    t = rng.uniform(0, 2 * np.pi)
    Q = np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])
    W, P, _ = m.evaluate(F)
    WQ, PQ, _ = m.evaluate(Q @ F)
    np.testing.assert_allclose(WQ, W, rtol=1e-10, atol=1e-6)
    np.testing.assert_allclose(PQ, Q @ P, rtol=1e-8, atol=1e-8 * np.abs(P).max())


@pytest.mark.parametrize("law,form", CASES)
def test_reference_state(law, form):
    """Stress-free formulations: W = 0 and P = 0 at F = I. The paper's form is not
    stress-free: it relaxes to a uniform contraction with alpha (det F - 1) ~ -(2 W_a + W_J)
    (W_J of the law alone; PAPER.md's 1 - 2 W_a / alpha omits W_J, which is 2 C01 for
    Mooney-Rivlin, whose C01 term is J^2 in 2D)."""
    m = material(law, form)
    W, P, _ = m.evaluate(np.eye(2)[None])
    if FORMULATIONS[form].stress_free:
        assert abs(W[0]) < 1e-9 and np.abs(P).max() < 1e-9 * m.law.shear_modulus(m.constants)
        return
    Wa = m.reference_stress_derivative()
    WJ = float(m.energy_jet(2.0, 1.0).J)   # the penalty's part vanishes at J = 1
    assert np.abs(P).max() > 0.1 * Wa
    # relaxed uniform state s I: P(s I) = 0, solved by Newton on s
    s = 1.0
    for _ in range(30):
        _, P, A = m.evaluate(np.array([[[s, 0.0], [0.0, s]]]))
        r = P[0, 0, 0]
        s -= r / (A[0, 0, 0] + A[0, 0, 3])
    assert s ** 2 == pytest.approx(1 - (2 * Wa + WJ) / m.penalty, abs=10 * (Wa / m.penalty) ** 2)


@pytest.mark.parametrize("law", ALL_LAWS)
def test_plane_stress_uniaxial_tension_closed_form(law):
    """Incompressible uniaxial tension: lambda_2 = lambda_3 = lambda^-1/2,
    P11 = 2 (lambda - lambda^-2) (psi_1 + psi_2 / lambda), P22 = 0."""
    m = material(law, "plane-stress")
    defined = 0
    for lam in (0.7, 0.95, 1.0 + 1e-3, 1.1, 1.5, 2.5):
        F = np.diag([lam, lam ** -0.5])[None]
        with np.errstate(invalid="ignore"):
            W, P, _ = m.evaluate(F)
        I1, I2 = lam ** 2 + 2 / lam, 2 * lam + lam ** -2
        if not np.isfinite(m.law.psi(I1, I2, m.constants)):   # beyond the law's domain
            assert np.isnan(W[0]) and np.all(np.isnan(P))
            continue
        defined += 1
        j1, j2 = Jet.variables(np.array(I1), np.array(I2))   # (I1, I2) as the variables
        psi = m.law.psi(j1, j2, m.constants)
        expected = 2 * (lam - lam ** -2) * (psi.a + psi.J / lam)
        assert P[0, 0, 0] == pytest.approx(float(expected), rel=1e-10)
        assert abs(P[0, 1, 1]) < 1e-9 * abs(P[0, 0, 0]) + 1e-6
    assert defined >= 3


def test_jet_against_finite_differences(rng):
    a0, J0 = 2.3, 0.9

    def g(a, J):
        ja, jJ = Jet.variables(np.array(a), np.array(J))
        return (ja * jJ ** -2 + jJ ** (-2 / 3) * (ja + 1.0)) ** 3 - 2.0 / ja + (ja * jJ).log()

    v = g(a0, J0)
    h = 1e-4
    fd_a = (g(a0 + h, J0).v - g(a0 - h, J0).v) / (2 * h)
    fd_J = (g(a0, J0 + h).v - g(a0, J0 - h).v) / (2 * h)
    fd_aa = (g(a0 + h, J0).a - g(a0 - h, J0).a) / (2 * h)
    fd_aJ = (g(a0, J0 + h).a - g(a0, J0 - h).a) / (2 * h)
    fd_JJ = (g(a0, J0 + h).J - g(a0, J0 - h).J) / (2 * h)
    for got, fd in [(v.a, fd_a), (v.J, fd_J), (v.aa, fd_aa), (v.aJ, fd_aJ), (v.JJ, fd_JJ)]:
        assert float(got) == pytest.approx(float(fd), rel=1e-6)


def test_unknown_names_list_the_allowed_ones():
    with pytest.raises(SceneError, match="material.law.*mooney-rivlin"):
        get_law("ogden")
    with pytest.raises(SceneError, match="material.formulation.*plane-stress"):
        get_formulation("axisymmetric")


@pytest.mark.parametrize("law,form", CASES)
def test_compiled_tape_matches_the_numpy_jet(law, form, rng):
    """The energy traced into a tape and replayed by the compiled interpreter gives W
    and its (a, J) partials equal to the numpy jet's, to round-off, for every
    registered law x formulation (a new one is covered by being registered)."""
    from ancf.core.tape import evaluate, trace
    m = material(law, form)
    a = 2.0 + 0.5 * rng.random((7, 5)) ** 2     # denser near the reference state (a, J) = (2, 1)
    J = 1.0 + 0.2 * (rng.random((7, 5)) - 0.5) ** 3
    with np.errstate(invalid="ignore"):
        ref = m.energy_jet(a, J).D
    compare_where_defined(evaluate(*trace(m), a, J), ref)


@pytest.mark.parametrize("law,form", CASES)
def test_batched_tape_matches_the_numpy_jet(law, form, rng):
    """The compiled step's batched replay (:func:`ancf.core.tape.tape_batch`, log included)
    gives the numpy jet's W and partials at every order it is asked for."""
    from ancf.core.tape import tape_batch, trace
    m = material(law, form)
    ops, consts = trace(m)
    a = 2.0 + 0.5 * rng.random(9) ** 2
    J = 1.0 + 0.2 * (rng.random(9) - 0.5) ** 3
    with np.errstate(invalid="ignore"):
        ref = m.energy_jet(a, J).D
    for order, nc in ((0, 1), (1, 3), (2, 6)):
        R = np.zeros((len(ops), 6, 9))
        tape_batch(ops, consts, a, J, R, 9, order)
        compare_where_defined(R[-1, :nc], ref[:nc])


def test_a_log_outside_its_domain_is_not_a_number_everywhere(rng):
    """Gent's energy beyond its limit (I1 - 3 >= Jm) is NaN in the jet, the tape and the
    batched tape alike (never a silent finite value), which the solvers reject as an
    inadmissible state."""
    from ancf.core.tape import evaluate, tape_batch, trace
    m = material("gent", "plane-stress")
    a, J = np.array([[2.0, 3.5]]), np.array([[1.0, 1.0]])   # I1 - 3 = 0 and 1.5 > Jm = 0.1
    jet = m.energy_jet(a, J).D
    tape = evaluate(*trace(m), a, J)
    R = np.zeros((len(trace(m)[0]), 6, 2))
    tape_batch(*trace(m), a[0], J[0], R, 2, 2)
    for got in (jet[:, 0, 0], tape[:, 0, 0], R[-1, :, 0]):   # at rest: W and its partials
        assert np.all(np.isfinite(got))
    for got in (jet[:, 0, 1], tape[:, 0, 1], R[-1, :, 1]):   # beyond the limit: none of them
        assert np.all(np.isnan(got))


def test_a_user_law_with_a_log_reaches_both_solvers_through_one_table():
    """One registered energy serves ANCF (jet, tape) and the continuum (UFL): the
    continuum's scene check reads the same table."""
    from mechanics.laws import LAWS
    from reference_fem.simulation import check as fem_check
    from contract.scene import scene_from_dict
    from contract import paper
    t = paper.cantilever_scene("neo-hookean", "plane-stress", element="HB2n-12", elements=4)
    t["material"] = {"law": "gent", "formulation": "plane-stress", "density": 2150.0, "mu": 1.9e6, "Jm": 0.1}
    t["fem"] = {"model": "plane-stress"}
    fem_check(scene_from_dict(t))
    assert "gent" in LAWS
    t["material"]["Jm"] = -1.0
    with pytest.raises(SceneError, match="material.Jm"):
        fem_check(scene_from_dict(t))


def test_tracing_rejects_what_it_cannot_compile():
    from ancf.core.tape import Tape
    t = Tape()
    a, J = t.push(0), t.push(1)
    with pytest.raises(TypeError, match="constant exponents"):
        a ** J


@pytest.mark.slow(guard="test_a_user_law_with_a_log_reaches_both_solvers_through_one_table")
def test_a_user_law_given_by_import_runs_in_both_solvers(tmp_path):
    """A law of the user's own (a module registering it, given with --import) runs in
    ANCF and in the continuum from the same scene file: one table, no solver edited.
    The law C10 (I1 - 3) + K log(I1 - 2) has the paper's neo-Hookean stiffness at rest
    (C10 + K = 0.953018 MPa); HB2n-12 x 8 is 6.5 % stiffer than the continuum for that
    law (reports/law_gent_cantilever.md, tiny grid), so the tips agree within 10 %."""
    import json
    import subprocess
    import sys
    from pathlib import Path
    root = Path(__file__).resolve().parents[1]
    (tmp_path / "my_log_law.py").write_text(
        "from mechanics.laws import MATH, Law, register_law\n"
        "register_law(Law('log-test', ('C10', 'K'), "
        "lambda I1, I2, c, m=MATH: c['C10'] * (I1 - 3.0) + c['K'] * m.log(I1 - 2.0)))\n")
    scene = (root / "scenes" / "cantilever-gent.toml").read_text()
    scene = scene.replace('law = "gent"', 'law = "log-test"').replace("mu = 1.906036e6", "C10 = 0.5e6")
    scene = scene.replace("Jm = 0.1 ", "K = 0.453018e6 ").replace("elements = 16", "elements = 8")
    (tmp_path / "s.toml").write_text(scene)
    env = {**__import__("os").environ, "PYTHONPATH": f"{tmp_path}:{root}"}
    tips = {}
    for prog in ("ancf", "reference_fem"):
        p = subprocess.run([sys.executable, "-m", prog, "run", str(tmp_path / "s.toml"), "--import", "my_log_law",
                            "--json", str(tmp_path / f"{prog}.json"), "--quiet"],
                           capture_output=True, text=True, cwd=tmp_path, env=env)
        assert p.returncode == 0, p.stderr
        tips[prog] = json.loads((tmp_path / f"{prog}.json").read_text())["tip"]["uy"]
    assert tips["ancf"] < -0.08 and tips["reference_fem"] < -0.08       # the beam bends ~0.1 m
    assert tips["ancf"] == pytest.approx(tips["reference_fem"], rel=0.1)
    p = subprocess.run([sys.executable, "-m", "ancf", "run", str(tmp_path / "s.toml"), "--import", "no_such_law"],
                       capture_output=True, text=True, cwd=tmp_path, env=env)
    assert p.returncode == 2 and "--import: no module named 'no_such_law'" in p.stderr
