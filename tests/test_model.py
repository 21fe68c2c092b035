"""Assembly contract tests over every element (and every law x formulation on one):
internal force = energy gradient, tangent = force gradient, rigid motions, mass and
gravity integrate exactly, and only the effects a scene calls for are built."""
import numpy as np
import pytest

from ancf import model as model_module
from ancf.build import build_model
from ancf.mesh import Mesh, fixed_dofs
from ancf.model import BeamModel
from ancf.quadrature import gauss
from ancf.run import run_scene
from contract.scene import scene_from_dict
from ancf.elements import ELEMENTS
from contract import paper

from .conftest import ALL_ELEMENTS, ALL_FORMULATIONS, ALL_LAWS, material

CASES = [(el, "yeoh", f) for el in ALL_ELEMENTS for f in ALL_FORMULATIONS] + \
        [("HB2n-12", law, f) for law in ALL_LAWS if law != "yeoh" for f in ALL_FORMULATIONS]


def make_model(element, law, form, n=3, penalty=20e6):
    mesh = Mesh(ELEMENTS[element], n, 0.16, 0.005, 0.007)
    return BeamModel(mesh, material(law, form, penalty), gauss(3, 2),
                     fixed_dofs(mesh, "clamp", "face"))


def bent_state(model, rng, angle=0.2):
    """An admissible large-deformation state: the centre line bent to a circular arc
    (tip rotation ``angle``), sections stretched 1 % and squeezed 1 %, plus noise."""
    m = model.mesh
    kinds = m.element.kinds
    q = m.reference.reshape(m.n_nodes, -1, 2).copy()
    th = angle * m.node_x / m.length
    R = m.length / angle
    q[:, kinds.index("r")] = np.c_[R * np.sin(th), R * (1 - np.cos(th))]
    if "r_x" in kinds:
        q[:, kinds.index("r_x")] = 1.01 * np.c_[np.cos(th), np.sin(th)]
    q[:, kinds.index("r_y")] = 0.99 * np.c_[-np.sin(th), np.cos(th)]
    return q.reshape(-1) - m.reference + 1e-6 * rng.standard_normal(m.n_dof)


@pytest.mark.parametrize("element,law,form", CASES)
def test_internal_force_is_the_energy_gradient(element, law, form, rng):
    model = make_model(element, law, form)
    u = bent_state(model, rng)
    f = model.internal_force(u)
    hs = np.array([4e-6, 2e-6, 1e-6])
    for _ in range(3):
        d = rng.standard_normal(u.size)
        U0 = model.strain_energy(u)
        r = [abs(model.strain_energy(u + h * d) - U0 - h * f @ d) for h in hs]
        slopes = np.diff(np.log(r)) / np.diff(np.log(hs))
        assert np.all(slopes > 1.8), (slopes, r)


@pytest.mark.parametrize("element,law,form", CASES)
def test_tangent_is_the_force_gradient(element, law, form, rng):
    model = make_model(element, law, form)
    u = bent_state(model, rng)
    f, K = model.internal_force_and_tangent(u)
    Kdense = K.to_sparse().toarray()
    np.testing.assert_allclose(Kdense, Kdense.T, atol=1e-10 * np.abs(Kdense).max())
    hs = np.array([4e-6, 2e-6, 1e-6])
    d = rng.standard_normal(u.size)
    Kd = Kdense @ d
    r = [np.abs(model.internal_force(u + h * d) - f - h * Kd).max() for h in hs]
    slopes = np.diff(np.log(r)) / np.diff(np.log(hs))
    assert np.all(slopes > 1.8), (slopes, r)


def rotate(model, u, t, shift=(0.0, 0.0)):
    """The state rotated by t about the origin and translated: positions and
    gradients rotate, positions also shift."""
    m = model.mesh
    Q = np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])
    q = (m.reference + u).reshape(m.n_nodes, -1, 2) @ Q.T
    q[:, m.element.kinds.index("r")] += shift
    return q.reshape(-1) - m.reference, Q


@pytest.mark.parametrize("element,law,form", CASES)
def test_rigid_motion_leaves_energy_and_rotates_force(element, law, form, rng):
    model = make_model(element, law, form)
    u = bent_state(model, rng)
    U, f = model.strain_energy(u), model.internal_force(u)
    v, Q = rotate(model, u, 0.7, shift=(0.03, -0.2))
    assert model.strain_energy(v) == pytest.approx(U, rel=1e-9)
    fQ = (f.reshape(-1, 2) @ Q.T).reshape(-1)
    np.testing.assert_allclose(model.internal_force(v), fQ, atol=1e-8 * np.abs(f).max())
    # the undeformed beam moved rigidly: zero energy and force when stress-free; the
    # paper's form keeps its reference stress, rotated with the beam
    w, Q = rotate(model, np.zeros_like(u), -1.1, shift=(0.5, 0.1))
    f0 = model.internal_force(np.zeros_like(u))
    if model.material.formulation.stress_free:
        assert abs(model.strain_energy(w)) < 1e-12
        assert np.abs(model.internal_force(w)).max() < 1e-9
        assert np.abs(f0).max() < 1e-9
    else:
        assert np.abs(f0).max() > 1e-3
        np.testing.assert_allclose(model.internal_force(w), (f0.reshape(-1, 2) @ Q.T).reshape(-1),
                                   atol=1e-9 * np.abs(f0).max())


@pytest.mark.parametrize("element", ALL_ELEMENTS)
def test_mass_and_gravity_are_exact(element):
    """Translation vectors: 1^T M 1 = rho A L per direction, gravity resultant rho g V;
    M is symmetric positive definite whatever the elastic rule."""
    mesh = Mesh(ELEMENTS[element], 5, 0.35, 0.005, 0.007)
    model = BeamModel(mesh, material("yeoh", "plane-stress"), gauss(1, 1), np.array([], int))
    M = model.mass_matrix()
    assert M.is_positive_definite()
    ex = np.zeros(mesh.n_dof)
    for node in range(mesh.n_nodes):
        ex[mesh.dofs(node, ["r"])[0]] = 1.0      # unit translation along x
    ey = np.roll(ex, 1)                           # ... along y
    mass = model.material.density * 0.35 * 0.005 * 0.007
    assert ex @ M.matvec(ex) == pytest.approx(mass, rel=1e-12)
    assert ey @ M.matvec(ey) == pytest.approx(mass, rel=1e-12)
    assert abs(ex @ M.matvec(ey)) < 1e-15 * mass
    Mfull = M.to_sparse().toarray()
    np.testing.assert_allclose(Mfull, Mfull.T, atol=1e-15 * np.abs(Mfull).max())
    g = model.gravity_force((0.0, -9.81))
    assert g @ ey == pytest.approx(-9.81 * mass, rel=1e-12)
    assert abs(g @ ex) < 1e-15 * 9.81 * mass


def _scene(**over):
    s = paper.cantilever_scene("yeoh", over.pop("formulation", "plane-stress"), "HB2n-12", 4)
    for k, v in over.items():
        s[k] = v
    return scene_from_dict(s)


def test_static_scene_builds_no_mass_matrix(monkeypatch):
    def forbidden(self):
        raise AssertionError("a static scene assembled the mass matrix")
    monkeypatch.setattr(BeamModel, "mass_matrix", forbidden)
    rec, _ = run_scene(_scene())
    assert rec["status"] == "converged"
    assert rec["effects"] == ["elastic", "gravity"]


def test_scene_without_gravity_never_evaluates_it(monkeypatch):
    def forbidden(self, g):
        raise AssertionError("gravity evaluated without [loads] gravity")
    monkeypatch.setattr(BeamModel, "gravity_force", forbidden)
    rec, _ = run_scene(_scene(loads={"tip_force": [0.0, -0.01]}))
    assert rec["status"] == "converged"
    assert rec["effects"] == ["elastic", "tip_force"]


@pytest.mark.parametrize("form,expected", [
    ("plane-stress", ["elastic", "gravity"]),
    ("plane-strain", ["elastic", "gravity", "penalty"]),
    ("paper", ["elastic", "gravity", "penalty"]),
])
def test_penalty_only_where_the_formulation_has_one(form, expected):
    rec, _ = run_scene(_scene(formulation=form))
    assert rec["effects"] == expected


@pytest.mark.parametrize("element,law,form", CASES)
def test_compiled_kernel_matches_the_numpy_reference(element, law, form, rng):
    """The numba kernel is generic: every registered element and law goes through it
    and must agree with the numpy implementation to round-off."""
    model = make_model(element, law, form)
    u = bent_state(model, rng)
    f, K = model.internal_force_and_tangent(u)
    f_ref, K_ref = model.internal_force_and_tangent_numpy(u)
    np.testing.assert_allclose(f, f_ref, rtol=0, atol=1e-12 * np.abs(f_ref).max())
    np.testing.assert_allclose(K.ab, K_ref.ab, rtol=0, atol=1e-12 * np.abs(K_ref.ab).max())
    x = rng.standard_normal(u.size)
    np.testing.assert_allclose(K.matvec(x), K_ref.to_sparse() @ x, rtol=0,
                               atol=1e-12 * np.abs(K_ref.ab).max() * np.abs(x).sum())


@pytest.mark.parametrize("element,law,form", CASES)
def test_discrete_gradient_identity(element, law, form, rng):
    """(u1 - u0) . f_dg(u0, u1) = U(u1) - U(u0) to round-off for a finite step, and
    f_dg -> f_int at the midpoint as u1 -> u0 (second order)."""
    model = make_model(element, law, form)
    u0 = bent_state(model, rng, angle=0.2)
    u1 = bent_state(model, rng, angle=0.25)
    f, _ = model.discrete_gradient_force_and_tangent(u0, u1)
    dU = model.strain_energy(u1) - model.strain_energy(u0)
    scale = abs(model.strain_energy(u1)) + abs(model.strain_energy(u0))
    assert (u1 - u0) @ f == pytest.approx(dU, abs=1e-11 * scale)
    errs = []
    for h in (1e-3, 5e-4):
        v = u0 + h * (u1 - u0)
        fdg, _ = model.discrete_gradient_force_and_tangent(u0, v)
        errs.append(np.abs(fdg - model.internal_force(0.5 * (u0 + v))).max())
    assert errs[1] < 0.3 * errs[0] or errs[1] < 1e-9 * np.abs(f).max()


@pytest.mark.parametrize("element,law,form", CASES)
def test_compiled_force_only_path_matches_the_numpy_reference(element, law, form, rng):
    """internal_force (kernel without the tangent, used by line searches, descents and
    initial accelerations) equals the numpy reference internal_force_numpy."""
    model = make_model(element, law, form)
    u = bent_state(model, rng)
    ref = model.internal_force_numpy(u)
    np.testing.assert_allclose(model.internal_force(u), ref, rtol=0, atol=1e-12 * np.abs(ref).max())
