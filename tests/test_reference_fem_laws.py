"""The UFL laws of reference_fem against the numpy laws of ancf, pointwise."""
import numpy as np
import pytest

from ancf.build import build_material
from ancf.laws import LAWS
from contract import paper
from contract.scene import MaterialSpec
from reference_fem.dolfinx_backend.laws import LAWS_UFL
from reference_fem.dolfinx_backend.models import MODELS

PENALTY = paper.PENALTY

pytestmark = pytest.mark.dolfinx


def test_same_laws_same_constants():
    """The intended twin of the two solvers: every law in numpy (ancf) and in UFL, with
    the same names, constants and small-strain shear modulus."""
    assert set(LAWS_UFL) == set(LAWS)
    for name, law in LAWS_UFL.items():
        assert law.constants == LAWS[name].constants
        c = {k: 1.0 + i for i, k in enumerate(law.constants)}
        assert law.shear_modulus(c) == LAWS[name].shear_modulus(c)


def _random_gradients(n, seed=0):
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        F = np.eye(2) + 0.35 * rng.standard_normal((2, 2))
        if np.linalg.det(F) > 0.3:
            out.append(F)
    return out


# (model, incompressibility) -> the ancf formulation whose energy it must reproduce
CASES = [("plane-strain", "mixed"), ("plane-strain", "penalty"), ("plane-stress", "exact")]


@pytest.mark.parametrize("law", sorted(LAWS))
@pytest.mark.parametrize("model, inc", CASES)
def test_energy_and_stress_match_ancf(law, model, inc):
    """W and P = dW/dF at random F (det F > 0). Plane strain: with the pressure at its
    penalty value phat = alpha (J - 1) / mu, both the mixed and the perturbed-Lagrangian
    energies reduce to ancf's psi(I1bar, I2bar) + alpha/2 (J - 1)^2, and dW/dphat = 0
    there, so P (at fixed phat) is the full derivative. Mixed: W differs from ancf's by
    the constant-in-F term alpha/2 (J - 1)^2 vs phat mu (J - 1); P agrees."""
    from reference_fem.dolfinx_backend.fem import PointwiseEvaluator
    import ufl

    mat = dict(paper.materials()[law])
    rho = mat.pop("density")
    ufl_law = LAWS_UFL[law]
    mu = ufl_law.shear_modulus(mat)
    energy = MODELS[(model, inc)].energy

    def build(F, phat, mesh):
        W = energy(ufl_law, mat, F, phat, mu, PENALTY)
        P = ufl.diff(W, F)
        return [W, P[0, 0], P[0, 1], P[1, 0], P[1, 1]]

    evaluate = PointwiseEvaluator(build)
    ancf_mat = build_material(MaterialSpec(law, model, rho, mat, PENALTY if model == "plane-strain" else None))
    for F in _random_gradients(5):
        J = np.linalg.det(F)
        phat = PENALTY * (J - 1.0) / mu
        got = evaluate(F, phat)
        W, P, _ = ancf_mat.evaluate(F[None], tangent=False)
        scale = np.abs(P).max()
        np.testing.assert_allclose(got[1:], P[0].ravel(), rtol=0, atol=1e-11 * scale)
        if inc != "mixed":
            np.testing.assert_allclose(got[0], W[0], rtol=1e-11, atol=1e-11 * scale)
        else:
            W_iso = W[0] - 0.5 * PENALTY * (J - 1.0) ** 2
            np.testing.assert_allclose(got[0] - mu * phat * (J - 1.0), W_iso, rtol=1e-9,
                                       atol=1e-11 * scale)
