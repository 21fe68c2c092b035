"""The stability verdict counts negative eigenvalues by Sylvester's law of inertia
(banded LDL^T of the Jacobi-scaled tangent); checked here against a dense symmetric
eigen-solve (numpy.linalg.eigh), the independent route, over every registered element x
law x formulation, and on the saddle point the former verdict (shift-invert Lanczos for
the eigenvalue nearest a shift) called stable."""
from __future__ import annotations

import numpy as np
import pytest

from ancf.build import build_model, external_loads, plan
from ancf.checks.element import runs
from ancf.elements import ELEMENTS
from ancf.core.formulations import FORMULATIONS
from mechanics.laws import LAWS
from ancf.simulation import run_scene
from ancf.solvers.stability import SINGULAR_TOL, below, check_stability, lowest_mode
from ancf.solvers.statics import solve_static
from contract import paper
from contract.scene import scene_from_dict

from .conftest import HEAVY_ELEMENTS, contract_rule, law_scene, tiered

# dense eigenvalues of S (||S|| <= ~5) carry an error ~ eps ||S||; a count at a shift is
# compared only where no eigenvalue lies within this of the shift
MARGIN = 1e-12


def scaled_dense(model, u):
    _, K = model.internal_force_and_tangent(u)
    K = K.constrain(model.fixed)
    A = K.to_sparse().toarray()
    d = 1.0 / np.sqrt(np.abs(np.diag(A)))
    return K, np.linalg.eigvalsh(d[:, None] * A * d[None, :])


def states(law, formulation, element):
    """The cantilever (4 elements) at equilibria under 0.3, 1 and 3 times gravity, and
    two states off equilibrium (a deterministic perturbation: indefinite tangents)."""
    d = law_scene(law, formulation, element, 4, quadrature=contract_rule(element), name="inertia")
    scene = scene_from_dict(d)
    p = plan(scene)
    model = build_model(p)
    f = sum(external_loads(model, p).values())
    out = []
    for k in (0.3, 1.0, 3.0):
        res = solve_static(model, k * f)
        assert res.status == "converged", res.reason
        out.append(res.u)
    rng = np.random.default_rng(7)
    for amp in (0.2, 0.6):
        dv = amp * model.mesh.height * rng.standard_normal(out[1].shape)
        dv[model.fixed] = 0.0
        # inside the law's domain (Gent's energy ends at I1 - 3 = Jm): halve the
        # perturbation until the tangent is a number (other laws: never needed)
        while not np.all(np.isfinite(model.internal_force_and_tangent(out[1] + dv)[1].ab)):
            dv = 0.5 * dv
        out.append(out[1] + dv)
    return model, out


@pytest.mark.parametrize("element,law,formulation", tiered(
    [(el, law, f) for f in sorted(FORMULATIONS) for law in sorted(LAWS) for el in sorted(ELEMENTS) if runs(el, f)],
    lambda el, law, f: el in HEAVY_ELEMENTS, "test_inertia_count_agrees_with_a_dense_eigen_solve"))
def test_inertia_count_agrees_with_a_dense_eigen_solve(element, law, formulation):
    model, us = states(law, formulation, element)
    compared = indefinite = 0
    for u in us:
        K, lam = scaled_dense(model, u)
        indefinite += lam[0] < -SINGULAR_TOL
        for shift in (-1e-2, -SINGULAR_TOL, SINGULAR_TOL, 1e-2, 0.5 * lam[0], lam[2] + 1e-6):
            if np.min(np.abs(lam - shift)) < MARGIN:
                continue
            assert below(K, shift) == int(np.sum(lam < shift)), (shift, lam[:4])
            compared += 1
        low, mode = lowest_mode(K, model.fixed, int(np.sum(lam < -SINGULAR_TOL)))
        # both eigen-solves are backward stable: an eigenvalue is known to c n eps ||K||
        # (Wilkinson; n the dimension, c = 8), which for a near-zero lowest eigenvalue is the
        # bound, not the relative one (HB2n-84p: n = 210, ||K|| = 20, differences to 1.7e-12)
        bound = 8 * len(lam) * np.finfo(float).eps * np.max(np.abs(lam))
        assert low == pytest.approx(lam[0], rel=1e-6, abs=max(1e-13, bound))
    assert compared >= 20
    assert indefinite >= 1          # the comparison saw negative eigenvalues too


@pytest.mark.parametrize("law, negatives", [("yeoh", 2), ("mooney-rivlin", 1)])
def test_the_paper_saddle_is_found_and_left(law, negatives):
    """Paper constants, HB2n-16 x 32, quadrature [2, 2], clamp "all", gravity: Newton
    converges to a state whose tangent has negative eigenvalues (dense: -5.8e-3 and
    -8.4e-4 for Yeoh). The verdict counts them; the solver leaves along the lowest mode
    to a state that a dense eigen-solve confirms stable."""
    d = paper.cantilever_scene(law, "paper", "HB2n-16", 32, quadrature=(2, 2), clamp="all", name="saddle")
    rec, (model, res) = run_scene(scene_from_dict(d))
    assert rec["status"] == "converged"
    assert f"tangent has {negatives} negative eigenvalue" in rec["stability"]
    assert rec["stable"] is True and rec["negative_eigenvalues"] == 0
    _, lam = scaled_dense(model, res.u)
    assert lam[0] > SINGULAR_TOL


def test_the_saddle_itself_is_called_unstable():
    """The Newton end state before the escape: the verdict is unstable with the two
    negative eigenvalues of the dense solve, whatever the nearest-to-a-shift eigenvalue."""
    d = paper.cantilever_scene("yeoh", "paper", "HB2n-16", 32, quadrature=(2, 2), clamp="all", name="saddle")
    scene = scene_from_dict(d)
    p = plan(scene)
    model = build_model(p)
    f = sum(external_loads(model, p).values())
    from mechanics.load_path import PathCounts, follow
    from ancf.solvers.statics import increment_solver
    free = np.setdiff1d(np.arange(model.mesh.n_dof), model.fixed)
    solve, state = increment_solver(model, lambda t: f * t, np.zeros(model.mesh.n_dof),
                                    1e-8 * np.linalg.norm(f[free]), 25)
    for _ in follow(solve, 10, PathCounts(), "load"):
        pass
    v = check_stability(model, state["u"])
    _, lam = scaled_dense(model, state["u"])
    assert v.kind == "unstable" and v.negative == int(np.sum(lam < -SINGULAR_TOL)) == 2
    assert v.lowest == pytest.approx(lam[0], rel=1e-6)


def test_a_zero_energy_mode_at_round_off_is_called_singular():
    """`paper` Neo-Hookean, HB2n-16 x 16, [2, 2], face clamp: two eigenvalues of S at
    1.6e-16 and 2.2e-16 (dense), the spurious modes the rank test counts for [2, 2]. The
    lowest eigenpair must still be found (S - lo I is singular to working precision),
    and the verdict is singular, not undetermined."""
    d = paper.cantilever_scene("neo-hookean", "paper", "HB2n-16", 16, quadrature=(2, 2), clamp="face", name="zero")
    rec, (model, res) = run_scene(scene_from_dict(d))
    _, lam = scaled_dense(model, res.u)
    assert abs(lam[0]) < SINGULAR_TOL and lam[2] > 1e-9
    assert rec["stable"] is False and "zero-energy mode" in rec["stability"]
    assert any("2 spurious zero-energy mode" in w for w in rec["warnings"])


def test_the_factor_growth_decides_whether_a_tiny_pivot_spoils_the_count():
    """A nearly singular but definite matrix has a tiny pivot and no growth (its count
    is trusted); a tiny pivot that makes the factors large is reported as growth (the
    count then goes to LAPACK's bisection). Both counts are known in closed form."""
    from ancf.core.bandsolve import band_ldlt_inertia

    def band(a, c):          # [[a, c], [c, a]] in upper band form, b = 1
        return np.array([[0.0, c], [a, a]])

    neg, small, growth = band_ldlt_inertia(band(1.0, 1.0 - 1e-10), 1, 0.0)
    assert (neg, growth) == (0, pytest.approx(1.0)) and small < 1e-9     # eigenvalues 1e-10, 2
    neg, small, growth = band_ldlt_inertia(band(1.0, 1e4), 1, 0.0)
    assert neg == 1 and growth > 1e7                                       # eigenvalues 1 -+ 1e4


def test_the_banded_solve_keeps_every_scale():
    """Banded.solve on a symmetric band matrix whose diagonal spans 50 orders of magnitude
    (as position and high-order slope dofs do): each unknown to round-off, relatively.
    Without the Jacobi scaling, LU with partial pivoting loses the small-scaled unknowns
    (their part of the matrix is below its backward error)."""
    import numpy as np
    from ancf.core.banded import Banded
    rng = np.random.default_rng(0)
    n, b = 30, 4
    A = np.zeros((n, n))
    for i in range(n):
        for j in range(max(0, i - b), min(n, i + b + 1)):
            A[i, j] = rng.normal()
    A = A + A.T + 20 * np.eye(n)                       # well conditioned once scaled
    d = 10.0 ** rng.uniform(-45, 5, n)
    A *= np.sqrt(np.outer(d, d))
    ab = np.zeros((2 * b + 1, n))
    for i in range(n):
        for j in range(max(0, i - b), min(n, i + b + 1)):
            ab[b + i - j, j] = A[i, j]
    x = rng.normal(size=n) / np.sqrt(d)
    y = Banded(ab, b).solve(A @ x)
    assert np.max(np.abs(y - x) / np.abs(x)) < 1e-12
