"""Homogeneous uniaxial tension against the closed-form incompressible stress.

A unit square on rollers (u_x = 0 on x = 0, u_y = 0 on y = -1/2) pulled by the dead
nominal traction P11 on x = 1. The exact solution is homogeneous (affine), which the
Q2 space holds exactly and the quadrature integrates exactly, so the finite element
stretch equals the closed-form one up to the Newton tolerance: the tolerance 1e-8
on the stretch is round-off and Newton (rtol 1e-10 on the residual), not modelling.

Closed forms (sigma = -p I + 2 W1 B - 2 W2 B^-1, lateral stresses zero, P11 = sigma11 / lam):
- plane stress (lam2 = lam3 = lam^-1/2): sigma11 = 2 (lam^2 - 1/lam) (W1 + W2 / lam);
- plane strain, incompressible (lam2 = 1/lam, lam3 = 1): sigma11 = 2 (lam^2 - lam^-2) (W1 + W2);
- plane strain with the penalty alpha/2 (J - 1)^2: no closed form; lam2 from P22 = 0
  with ancf's numpy material (a cross-check of the two codes).
"""
import numpy as np
import pytest
from scipy.optimize import brentq

from ancf.build import build_material
from contract import paper
from contract.scene import MaterialSpec

PENALTY = paper.PENALTY

pytestmark = pytest.mark.dolfinx

STRETCH = 1.5


def _w1_w2(law, c, I1, I2):
    if law == "neo-hookean":
        return c["C10"], 0.0
    if law == "mooney-rivlin":
        return c["C10"], c["C01"]
    d = I1 - 3.0
    return c["C10"] + 2 * c["C20"] * d + 3 * c["C30"] * d ** 2, 0.0


def closed_form(law, c, model, inc, lam):
    """(P11, lam2) of uniaxial tension at stretch lam."""
    if model == "plane-stress":
        W1, W2 = _w1_w2(law, c, lam ** 2 + 2 / lam, 2 * lam + lam ** -2)
        return 2 * (lam ** 2 - 1 / lam) * (W1 + W2 / lam) / lam, lam ** -0.5
    if inc == "mixed":
        I = lam ** 2 + lam ** -2 + 1
        W1, W2 = _w1_w2(law, c, I, I)
        return 2 * (lam ** 2 - lam ** -2) * (W1 + W2) / lam, 1 / lam
    mat = build_material(MaterialSpec(law, "plane-strain", 1.0, c, PENALTY))
    P = lambda l2: mat.evaluate(np.diag([lam, l2])[None], tangent=False)[1][0]
    l2 = brentq(lambda l2: P(l2)[1, 1], 0.5 / lam, 2.0 / lam, xtol=1e-15)
    return P(l2)[0, 0], l2


@pytest.mark.parametrize("law", ["neo-hookean", "mooney-rivlin", "yeoh"])
@pytest.mark.parametrize("model, inc", [("plane-strain", "mixed"), ("plane-strain", "penalty"),
                                        ("plane-stress", "exact")])
def test_uniaxial_tension(law, model, inc):
    from reference_fem.dolfinx_backend import fem as backend
    from mechanics.laws import get_law
    from reference_fem.dolfinx_backend.models import get_model
    from reference_fem.statics import solve_static
    from reference_fem.dolfinx_backend.problem import Setup, static_problem

    c = {k: v for k, v in paper.materials()[law].items() if k != "density"}
    P11, lam2 = closed_form(law, c, model, inc, STRETCH)
    mesh = backend.rectangle_mesh(1.0, 1.0, 2, 2, "quadrilateral")
    m = get_model(model, inc)
    disc = backend.Discretisation(mesh, 2, m.has_pressure, 4)
    bcs = (disc.fix(lambda x: np.abs(x[0]) < 1e-12, components=(0,))
           + disc.fix(lambda x: np.abs(x[1] + 0.5) < 1e-12, components=(1,)))
    setup = Setup(m, get_law(law), disc, c, bcs, traction=np.array([P11, 0.0]),
                  traction_where=lambda x: np.abs(x[0] - 1.0) < 1e-12, penalty=PENALTY)
    prob = static_problem(setup)
    res = solve_static(prob.system, prob.set_load, 5, 1e-10, 25)
    assert res.status == "converged", res.reason
    u = disc.point_displacement(np.array([[1.0, 0.5], [0.5, 0.0], [0.25, -0.25]]))
    X = np.array([[1.0, 1.0], [0.5, 0.5], [0.25, 0.25]])  # (x, y + 1/2)
    np.testing.assert_allclose(u, X * [STRETCH - 1.0, lam2 - 1.0], rtol=0, atol=1e-8)
