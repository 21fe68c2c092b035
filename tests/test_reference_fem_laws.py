"""The shared laws (mechanics.laws) in UFL (reference_fem) against the same laws on
ANCF's jets, pointwise: one energy function, two algebras, two derivations of the
invariants."""
import numpy as np
import pytest

from ancf.build import build_material
from ancf.checks.element import law_constants
from ancf.core.jet import Jet
from contract import paper
from contract.scene import MaterialSpec
from mechanics.laws import LAWS
pytest.importorskip("ufl", reason="needs the FEniCSx stack (DOLFINx, UFL): the Debian route or conda-forge")
from reference_fem.dolfinx_backend.models import MODELS  # noqa: E402

PENALTY = paper.PENALTY

pytestmark = pytest.mark.dolfinx


@pytest.mark.parametrize("law", sorted(LAWS))
def test_one_energy_on_jets_in_ufl_and_as_floats(law):
    """The law's one energy function gives the same value on floats, on ANCF's jets and
    in UFL (evaluated by UFL's own algebra at constant invariants), and its derived
    shear modulus is the jet's 2 (psi_1 + psi_2) at rest."""
    import ufl
    from reference_fem.dolfinx_backend.laws import energy

    L = LAWS[law]
    c = {k: v for k, v in law_constants(law).items() if k in L.constants}
    I1, I2 = 3.04, 3.05         # inside every example domain (Gent: I1 - 3 < Jm = 0.1)
    fl = L.psi(I1, I2, c)
    a, b = Jet.variables(I1, I2)          # the jet's variables stand in for (I1, I2)
    jet = L.psi(a, b, c)
    assert float(jet.v) == pytest.approx(fl, rel=1e-14)
    uv = energy(L, ufl.as_ufl(I1), ufl.as_ufl(I2), c)     # UFL folds constant arithmetic
    assert float(uv if isinstance(uv, float) else uv(())) == pytest.approx(fl, rel=1e-14)
    rest = L.psi(*Jet.variables(3.0, 3.0), c)
    assert L.shear_modulus(c) == pytest.approx(2.0 * float(rest.a + rest.J), rel=1e-14)


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

    mat = law_constants(law)
    rho = mat.pop("density")
    ufl_law = LAWS[law]
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
