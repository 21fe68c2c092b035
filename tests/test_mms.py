"""Manufactured solutions (reference_fem/manufactured.py and each backend's manufactured.py): the body force
by a second route, and each code's observed orders on two small levels.

The second route: P from FElupe's material (tensortrax's derivatives of the backend's
energy, not sympy's) at F(X) = I + grad u*(X), its divergence by fourth-order central
differences in X; b = -Div P must match the sympy body force to the differences' error
(h = 1e-3: truncation ~ h^4 |P^(5)| and round-off ~ eps |P| / h, both below 1e-8 of |b|)."""
from __future__ import annotations

import numpy as np
import pytest

from .conftest import tiered

from contract import paper
from contract.errors import SceneError, UnknownName
from reference_fem.manufactured import EXPECTED_ORDER, MODELS, manufactured, observed_orders

LAWS = ("neo-hookean", "mooney-rivlin", "yeoh")
TOL = 0.3     # the study's bar: observed >= expected - 0.3 (studies/verification/manufactured.py ORDER_TOLERANCE)


def constants(law: str) -> dict:
    return {k: v for k, v in paper.materials()[law].items() if k != "density"}


def problem(law: str, model: str):
    return manufactured(law, constants(law), model, alpha=paper.PENALTY)


def _tensortrax_stress(ms, X: np.ndarray) -> np.ndarray:
    """P (dim, dim, n) at points X (dim, n) from the FElupe backend's MixedMaterial."""
    from mechanics.laws import get_law
    from reference_fem.felupe_backend.laws import strain_energy
    from reference_fem.felupe_backend.problem import MixedMaterial

    dim, model = ms.dim, ms.model
    F = ms.grad_u(X).reshape(dim, dim, -1) + np.eye(dim)[:, :, None]
    kind = "3d" if dim == 3 else ("plane-stress" if model.name == "plane-stress" else "plane-strain")
    if kind == "plane-strain":     # FElupe's plane-strain field: F33 = 1
        F3 = np.zeros((3, 3, F.shape[-1]))
        F3[:2, :2], F3[2, 2] = F, 1.0
        F = F3
    mat = MixedMaterial(strain_energy(get_law(ms.law), kind, ms.constants), ms.mu, ms.alpha, model.has_pressure)
    x = [F[:, :, :, None]] + ([ms.phat(X)[:, :, None]] if model.has_pressure else [])
    return mat.evaluate(x, False)[0][:dim, :dim, :, 0]


@pytest.mark.parametrize("law, model", tiered([(law, m) for m in MODELS for law in LAWS],
                                               lambda law, m: m == "3d" or law != "yeoh",
                                               "test_body_force_is_minus_the_divergence_of_the_backends_stress"))
def test_body_force_is_minus_the_divergence_of_the_backends_stress(law, model):
    pytest.importorskip("felupe")
    ms = problem(law, model)
    X0 = np.array([0.31, 0.62, 0.47][:ms.dim])
    h = 1e-3
    div = np.zeros(ms.dim)
    for j in range(ms.dim):
        e = np.zeros(ms.dim)
        e[j] = h
        X = np.stack([X0 + k * e for k in (-2, -1, 1, 2)], axis=1)
        P = _tensortrax_stress(ms, X)[:, j]                        # P_ij at the four points
        div += (P[:, 0] - 8 * P[:, 1] + 8 * P[:, 2] - P[:, 3]) / (12 * h)
    b = ms.b(X0[:, None])[:, 0]
    assert np.allclose(b, -div, rtol=0, atol=1e-7 * np.abs(b).max()), (b, -div)
    # and the stress itself: sympy's against tensortrax's
    Pt = _tensortrax_stress(ms, X0[:, None])[:, :, 0]
    ph = ms.phat(X0[:, None])[0] if ms.model.has_pressure else np.zeros(1)
    Ps = ms.stress(ms.grad_u(X0[:, None]) + np.eye(ms.dim).reshape(-1, 1), ph).reshape(ms.dim, ms.dim)
    assert np.allclose(Ps, Pt, rtol=0, atol=1e-10 * np.abs(Pt).max())


def test_constraint_source_is_J_minus_one_and_the_penalty():
    X = np.array([[0.2], [0.7]])
    mixed, pen = problem("yeoh", "plane-strain"), problem("yeoh", "plane-strain-penalty")
    J = np.linalg.det(mixed.grad_u(X).reshape(2, 2) + np.eye(2))
    assert mixed.g(X)[0, 0] == pytest.approx(J - 1.0, rel=1e-12)
    assert pen.g(X)[0, 0] == pytest.approx(J - 1.0 - pen.mu * pen.phat(X)[0, 0] / paper.PENALTY, rel=1e-12)
    assert problem("yeoh", "plane-stress").g is None


def test_bad_input_names_the_field():
    with pytest.raises(UnknownName, match="mms.model"):
        manufactured("yeoh", constants("yeoh"), "plane-strain-exact")
    with pytest.raises(ValueError, match="penalty alpha"):
        manufactured("yeoh", constants("yeoh"), "plane-strain-penalty")
    from studies.verification.manufactured import check, scene
    sc = scene("felupe", "plane-strain", "yeoh", [4, 8])
    sc["mms"]["levels"] = [8, 4]
    with pytest.raises(SceneError, match="mms.levels"):
        check(sc)
    sc = scene("abaqus", "plane-strain", "yeoh", [4, 8])
    with pytest.raises(SceneError, match="mms.code"):
        check(sc)


def test_observed_orders():
    assert observed_orders([2, 4, 6], [8.0, 1.0, None]) == [3.0, None]
    assert observed_orders([3, 9], [9.0, 1.0]) == pytest.approx([2.0])


# two small levels per model: 2D n = 4, 8 (u: 2.98, p: 2.2 measured), 3D n = 2, 3 (u, p: 2.8)
SMALL = {"plane-strain": ("mooney-rivlin", [4, 8]), "plane-strain-penalty": ("yeoh", [4, 8]),
         "plane-stress": ("yeoh", [4, 8]), "3d": ("neo-hookean", [2, 3])}


def _orders(solve, model):
    law, levels = SMALL[model]
    ms = problem(law, model)
    res = [solve(ms, n) for n in levels]
    assert all(r["status"] == "converged" for r in res), res
    ou = observed_orders(levels, [r["error_u"] for r in res])[0]
    assert ou >= EXPECTED_ORDER["u"] - TOL
    if ms.model.has_pressure:
        assert observed_orders(levels, [r["error_p"] for r in res])[0] >= EXPECTED_ORDER["p"] - TOL
    return res


@pytest.mark.parametrize("model", tiered(list(SMALL), lambda m: m in ("3d", "plane-strain-penalty"), "test_felupe_orders"))
def test_felupe_orders(model):
    pytest.importorskip("felupe")
    from reference_fem.felupe_backend.manufactured import solve

    _orders(solve, model)


@pytest.mark.dolfinx
@pytest.mark.parametrize("model", tiered(list(SMALL), lambda m: m in ("3d", "plane-strain"),
                                          "test_dolfinx_orders_and_the_same_errors_as_felupe"))
def test_dolfinx_orders_and_the_same_errors_as_felupe(model):
    """Both codes discretise alike (Q2/Q1 on the same grid, the same quadrature): their
    errors agree to the Newton tolerance (measured: 1e-9 relative and below)."""
    pytest.importorskip("dolfinx")
    from reference_fem.dolfinx_backend.manufactured import solve

    res = _orders(solve, model)
    try:
        from reference_fem.felupe_backend.manufactured import solve as solve_felupe
    except ImportError:
        return
    law, levels = SMALL[model]
    other = solve_felupe(problem(law, model), levels[0])
    assert other["error_u"] == pytest.approx(res[0]["error_u"], rel=1e-6)
    if other["error_p"] is not None:
        assert other["error_p"] == pytest.approx(res[0]["error_p"], rel=1e-6)


@pytest.mark.parametrize("code", ["dolfinx", "felupe"])
def test_the_studys_run_solves_every_level_through_the_backend(code):
    """The study's solver end to end, two levels in one process (the second level once
    failed: the backend package's function was rebound to its submodule by the first)."""
    from studies.verification.manufactured import run, scene
    rec = run(scene(code, "plane-strain", "neo-hookean", [2, 4]))
    assert rec["status"] == "converged", rec["reason"]
    assert [lv["cells"] for lv in rec["mms"]["levels"]] == [2, 4] and len(rec["mms"]["orders_u"]) == 1
