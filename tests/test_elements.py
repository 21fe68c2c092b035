"""Contract tests over every registered element: a new element is tested by being
registered."""
import numpy as np
import pytest

from ancf import beam_theory as bt
from ancf.elements import ELEMENTS, KINDS, ElementSpec, get_element, register_element
from contract.errors import SceneError
from ancf.polynomial import parse
from ancf.run import run_scene
from contract.scene import scene_from_dict
from contract import paper

from .conftest import ALL_ELEMENTS, material

GEOMETRIES = [(0.160 / 16, 0.005), (0.160 / 640, 0.005), (0.350 / 4, 0.005)]


def _nodal_values(spec: ElementSpec, field_polys, length):
    """Nodal coordinates (n_shape, 2) of a vector field given as two physical polynomials."""
    vals = []
    for xi in spec.nodes:
        for k in spec.kinds:
            dx, dy = KINDS[k]
            vals.append([p(xi * length, 0.0, dx, dy) for p in field_polys])
    return np.array(vals)


@pytest.mark.parametrize("name", ALL_ELEMENTS)
@pytest.mark.parametrize("length,height", GEOMETRIES)
def test_shape_functions_reproduce_every_basis_function(name, length, height, rng):
    """Nodality and exact reproduction: interpolating the nodal coordinates of any
    field in the element's span gives back the field and its gradient everywhere."""
    spec = ELEMENTS[name]
    xi, eta = rng.uniform(0, 1, 20), rng.uniform(-0.5, 0.5, 20)
    N, dN = spec.tabulate(xi, eta, length, height)
    x, y = xi * length, eta * height
    for j, p in enumerate(spec.polys):
        q = _nodal_values(spec, (p, p), length)[:, 0]
        # round-off scale: the size of the terms summed, not of the (possibly zero) sum
        for M, expected in [(N, p(x, y)), (dN[:, :, 0], p(x, y, 1, 0)), (dN[:, :, 1], p(x, y, 0, 1))]:
            terms = (np.abs(M) @ np.abs(q)).max()
            np.testing.assert_allclose(M @ q, expected, rtol=0, atol=1e-11 * terms)


@pytest.mark.parametrize("name", ALL_ELEMENTS)
def test_reference_configuration_is_reproduced(name):
    """q_ref (positions and unit gradients) interpolates r = (x, y): F = I."""
    spec = ELEMENTS[name]
    le, h = 0.01, 0.005
    q = np.concatenate([spec.reference_coordinates(x * le) for x in spec.nodes])
    xi = np.linspace(0, 1, 7)
    N, dN = spec.tabulate(xi, np.full(7, 0.3), le, h)
    np.testing.assert_allclose(N @ q, np.c_[xi * le, np.full(7, 0.3 * h)], atol=1e-15)
    F = np.einsum("pai,paj->pij", q[None].repeat(7, 0), dN)
    np.testing.assert_allclose(F, np.broadcast_to(np.eye(2), F.shape), atol=1e-12)


@pytest.mark.parametrize("name", ALL_ELEMENTS)
def test_conformity_across_element_faces(name):
    """Whether the field on a face x = const depends only on that face's node: true for
    LB2n-12 and HB2n-16; false for HB2n-12 and HB3n-12, whose x^2 + y^2 basis function
    ties the trace's y^2 part to every node (the field jumps across element faces off
    the centre line). A property of the paper's elements, recorded here so that a change
    to it is noticed."""
    spec = ELEMENTS[name]
    eta = np.linspace(-0.5, 0.5, 5)
    N, _ = spec.tabulate(np.ones(5), eta, 0.01, 0.005)      # right face
    others = N[:, : -len(spec.kinds)]                          # every function but the right node's
    conforming = np.abs(others).max() < 1e-12
    assert conforming == (name in ("LB2n-12", "HB2n-16"))
    # on the centre line every element is conforming (nodal positions are shared)
    N0, _ = spec.tabulate([1.0], [0.0], 0.01, 0.005)
    assert np.abs(N0[0, : -len(spec.kinds)]).max() < 1e-12


def test_basis_in_physical_coordinates_depends_on_aspect_ratio():
    """x^2 + y^2 is a physical-coordinate function: in (xi, eta) it is l^2 xi^2 + h^2 eta^2."""
    p = parse("x^2 + y^2").scaled(2.0, 0.5)
    assert dict(p.terms) == pytest.approx({(2, 0): 1.0, (0, 2): 0.0625})


def test_unknown_element_lists_the_registered_ones():
    with pytest.raises(SceneError, match="ancf.element.*HB2n-12"):
        get_element("HB9n-99")


@pytest.mark.parametrize("kwargs,message", [
    (dict(basis=("1", "x"), nodes=(0.0, 1.0), kinds=("r", "r_q")), "unknown kinds"),
    (dict(basis=("1", "x", "y"), nodes=(0.0, 1.0), kinds=("r", "r_x")), "basis functions"),
    (dict(basis=("1", "x", "x^2", "x^3"), nodes=(0.0, 1.0), kinds=("r", "r_y")), "do not determine"),
    (dict(basis=("1", "x"), nodes=(0.5, 1.0), kinds=("r",)), "nodes must rise"),
])
def test_bad_element_specs_fail_at_registration(kwargs, message):
    with pytest.raises(ValueError, match=message):
        register_element(ElementSpec("bad", **kwargs))
    assert "bad" not in ELEMENTS


@pytest.fixture
def cubic_element():
    """A transversely cubic element, defined by a user in a few lines."""
    spec = register_element(ElementSpec(
        name="HB2n-20 (test)",
        basis=("1", "x", "y", "x*y", "x^2", "y^2", "x*y^2", "x^3", "y^3", "x*y^3"),
        nodes=(0.0, 1.0), kinds=("r", "r_x", "r_y", "r_yy", "r_yyy")))
    yield spec
    del ELEMENTS[spec.name]


def test_a_user_defined_element_runs_in_a_scene(cubic_element):
    """Registered by name, used by name: the transversely cubic element solves the
    small-load cantilever (plane stress) within 5e-3 of Euler-Bernoulli + Timoshenko
    (model error O((h/L)^2) = 1e-3; measured 3.3e-3 at 128 elements) and no worse than
    HB2n-16, whose bending fields its space contains, on the same mesh."""
    m = material("neo-hookean", "plane-stress")
    g, (L, h, w) = 0.0981, (paper.CANTILEVER[k] for k in ("length", "height", "width"))
    exact = bt.cantilever_tip_deflection(m.density * g * h * w, L, bt.effective_modulus(m),
                                         bt.shear_modulus(m), h, w)

    def error(element):
        s = paper.cantilever_scene("neo-hookean", "plane-stress", element, 128, gravity=g,
                                   quadrature=(4, 3))
        rec, _ = run_scene(scene_from_dict(s))
        assert rec["status"] == "converged", rec["reason"]
        return abs(-rec["tip"]["uy"] / exact - 1)

    e = error(cubic_element.name)
    assert e < 5e-3
    assert e <= error("HB2n-16")
