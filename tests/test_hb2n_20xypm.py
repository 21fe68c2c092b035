"""The built-in HB2n-20xypm (ancf/elements/): HB2n-20xyp with an assumed membrane stretch,
C_xx from three Gauss points along the beam (ancf/kinematics/section/assumed.py), the cure for the membrane
locking of the slender pendulum's coarse meshes that the prototype tests/oracles/assumed_membrane.py found.

Its compiled kernel against the numpy reference, and both against the energy, are held for
every element by tests/test_beam.py. Here: the sampling's algebra, the element against the
prototype (a second route: its own C, exact force by einsum and finite-difference tangent,
its own step loop), the small-strain stiffness it shares with HB2n-20xyp (why it keeps the
rank tests' verdicts), and the measured effect on the pendulum."""
import numpy as np
import pytest

from ancf.kinematics.section.assumed import sampling
from ancf.build import build_model, plan
from ancf.checks.element import bent_state
from ancf.elements import ElementSpec, get_element
from ancf.core.quadrature import gauss
from contract.scene import scene_from_dict
from studies.peers.work_precision import scene_dict

from .oracles.assumed_membrane import AssumedStrain, pendulum_error
from .test_example_assumed_membrane import harness_error

ELEMENT, BASE = "HB2n-20xypm", "HB2n-20xyp"


def _model(element: str, n: int = 2):
    return build_model(plan(scene_from_dict(scene_dict(element, n, 2.5e-3, 0.5))))


def test_the_sampling_interpolates_along_and_keeps_the_other_components():
    """T's assumed rows are quadratic Lagrange weights from the 3 points to the rule's 4 in
    each row across: they reproduce 1, x and x^2 and read only the same row; the other
    components are the identity on the rule's own points. With 3 points along in the rule
    as well, the assumed strain is the plain one (T the identity on the sample points)."""
    rule = gauss(4, 2)
    points, T = sampling(("xx",), 3, rule)
    assert np.array_equal(points.weight[8:], np.zeros(6)) and np.array_equal(points.xi[:8], rule.xi)
    for k in range(3):
        np.testing.assert_allclose(T[0] @ points.xi ** k, rule.xi ** k, atol=1e-14)
    rows = np.equal.outer(rule.eta.round(12), points.eta.round(12))
    assert np.all((T[0] == 0) | rows)
    np.testing.assert_array_equal(T[1][:, :8], np.eye(8))
    np.testing.assert_array_equal(T[2][:, :8], np.eye(8))
    assert not T[1][:, 8:].any() and not T[2][:, 8:].any()
    points3, T3 = sampling(("xx",), 3, gauss(3, 3))
    np.testing.assert_allclose(T3[0][:, 9:], np.eye(9), atol=1e-13)


def test_a_bad_assumed_component_is_refused_with_the_allowed_ones():
    with pytest.raises(ValueError, match="xx, yy, xy"):
        ElementSpec("bad", ("1", "x"), (0.0, 1.0), ("r",), assumed=("zz",))


@pytest.mark.slow(guard="test_the_small_strain_stiffness_is_hb2n_20xyps")
def test_the_element_is_the_prototype():
    """The force at a bent, stretched state (ancf.checks.element.bent_state with noise 1e-3): the
    compiled kernel against the prototype's numpy einsum (round-off), and the 2-element
    pendulum's error against the prototype's own step loop (each solves its steps to rtol
    1e-8; 1e-7 relative, as the prototype's own test against the plain harness)."""
    model = _model(ELEMENT, 3)
    u = bent_state(model, np.random.default_rng(3), angle=0.5, noise=1e-3)
    f_proto = AssumedStrain(model, "xx").force(u)
    np.testing.assert_allclose(model.internal_force(u), f_proto, rtol=0, atol=1e-12 * np.abs(f_proto).max())
    assert harness_error(2, element=ELEMENT) == pytest.approx(pendulum_error(2, "xx"), rel=1e-7)


def test_the_small_strain_stiffness_is_hb2n_20xyps():
    """At u = 0 the element's eps_xx is quadratic along x, so the three points carry it
    exactly: K is HB2n-20xyp's to round-off, and with it the rank tests' eigenvalues."""
    K, K0 = (m.internal_force_and_tangent(np.zeros(m.mesh.n_dof))[1].to_sparse().toarray()
             for m in (_model(ELEMENT), _model(BASE)))
    np.testing.assert_allclose(K, K0, rtol=0, atol=1e-12 * np.abs(K0).max())


def test_the_assumed_stretch_relieves_the_slender_pendulums_coarse_meshes():
    """Measured at dt = 2.5 ms (error / L against the continuum): 2 / 4 / 8 elements 5.39 /
    0.454 / 0.041 %, HB2n-20xyp 7.42 / 1.196 / 0.033 % (the rule [5, 2] at 2 and 4 elements,
    l_e / h >= 15; under [4, 2] 5.23 / 0.447 and 7.25 / 1.18 %): the cure is at the coarse meshes;
    at 8 elements both are converged in the mesh to the step's and the section's error."""
    e2, e4 = (harness_error(n, element=ELEMENT) for n in (2, 4))
    b2, b4 = (harness_error(n, element=BASE) for n in (2, 4))
    assert e4 < 0.5 * b4 and e2 < 0.8 * b2


@pytest.mark.slow(guard="test_the_sampling_interpolates_along_and_keeps_the_other_components")
def test_the_finite_strain_rank_test_sees_the_assumed_strain():
    """ancf.checks.rank's finite-strain test reads E_bar = (C_bar - I) / 2 at the rule's points for
    an element with an assumed strain. Second route: the numpy reference's C_bar
    (AssumedStrain) at a random state of one element. Measured: at l_e / h = 10 the worst
    state shows [4, 2] 0.44 of its strain through C_bar (HB2n-20xyp's own points 0.51);
    [3, 3] samples along at its own points, so both see the same 0.86 at 0.1; the declared
    rules pass where they are declared."""
    from ancf.checks import rank
    from ancf.kinematics.section.assumed import AssumedStrain as Reference

    el, aspect = get_element(ELEMENT), 3.0
    points, T = sampling(el.assumed, el.assumed_points, gauss(4, 2))
    _, dN = el.tabulate(points.xi, points.eta, aspect, 1.0)
    q = 0.1 * np.random.default_rng(5).standard_normal((el.n_shape, 2))
    _, Cbar, _, _ = Reference(None, dN, points.weight, T)._kinematics(q.reshape(1, -1))
    Ebar = 0.5 * (Cbar[0] - [1.0, 1.0, 0.0]) * [1.0, 1.0, np.sqrt(2.0)]
    np.testing.assert_allclose(el.family.finite_strain(q, dN, T), Ebar, rtol=0, atol=1e-14)

    ratio = {name: rank.strain_test(name, (4, 2), 10.0)["ratio"] for name in (ELEMENT, BASE)}
    assert ratio[ELEMENT] < ratio[BASE] - 0.03, ratio
    assert rank.strain_test(ELEMENT, (3, 3), 0.1)["ratio"] == pytest.approx(rank.strain_test(BASE, (3, 3), 0.1)["ratio"])
    for aspect in (10.0, 1.0, 0.1):
        rule = rank.default_quadrature(el, False, aspect)
        assert rank.rank_test(el, rule, aspect)["passes"] and rank.strain_test(ELEMENT, rule, aspect)["passes"]
