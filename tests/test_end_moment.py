"""The end moment (contract.loads): a conservative couple on the rotation of the end face's
first moment, in ANCF (ancf.solvers.couple). For every registered element the face's first moment
reads a rigid rotation exactly; the couple's force is the gradient of its potential and
its stiffness the force's gradient; the compiled Newton is the Python one with it; the
load path continues the rotation past pi; and the hinge fixes what contract.loads says."""
import math

import numpy as np
import pytest

from ancf.build import build_model, external_loads, plan, static_loading
from ancf.elements import ELEMENTS, KINDS
from ancf.simulation import run_scene
from ancf.solvers.statics import newton, newton_reference
from contract import paper
from contract.errors import SceneError
from contract.scene import scene_from_dict

MU = 2 * paper.materials()["neo-hookean"]["C10"]


def _scene(element: str = "HB2n-40p", n: int = 4, moment: float = 0.01, left: str = "slide",
           form: str = "plane-stress", length: float = 0.16) -> dict:
    d = paper.cantilever_scene("neo-hookean", form, element, n, quadrature=None)
    d["beam"]["length"] = length
    d["supports"] = {"left": left}
    d["loads"] = {"end_moment": moment}
    return d


def _rotated(model, phi: float, stretch: float = 1.0) -> np.ndarray:
    """u of the whole beam turned rigidly by phi about the origin, its thickness scaled by
    ``stretch`` (r(x, y) = R(phi) (x, stretch y)): every kind's value from the map's
    derivatives."""
    m = model.mesh
    R = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
    q = np.zeros((m.n_nodes, m.n_kinds, 2))
    for node, x in enumerate(m.node_x):
        for k, kind in enumerate(m.element.kinds):
            dx, dy = KINDS[kind]
            if (dx, dy) == (0, 0):
                q[node, k] = R @ (x, 0.0)
            elif (dx, dy) == (1, 0):
                q[node, k] = R @ (1.0, 0.0)
            elif (dx, dy) == (0, 1):
                q[node, k] = R @ (0.0, stretch)
    return q.reshape(-1) - m.reference


@pytest.mark.parametrize("element", [el for el in sorted(ELEMENTS) if ELEMENTS[el].kinematics != "cable"])
def test_the_face_moment_reads_a_rigid_turn_and_a_thickness_stretch_exactly(element):
    """d = R(phi) (0, s) for r = R(phi) (x, s y): theta = phi (mod 2 pi), |d| = s, to round-off.
    (A cable's face, d = R90 r_x: tests/test_cable.py.)"""
    s = scene_from_dict(_scene(element))
    p = plan(s)
    model = build_model(p)
    face = static_loading(model, {}, p).face
    assert np.allclose(face.first_moment(np.zeros(model.mesh.n_dof)), (0.0, 1.0), atol=1e-13)
    for phi in (0.3, 2.5, -3.0):
        u = _rotated(model, phi, stretch=0.9)
        d = face.first_moment(u)
        assert face.rotation(u) == pytest.approx(phi, abs=1e-12)
        assert np.linalg.norm(d) == pytest.approx(0.9, rel=1e-12)


@pytest.mark.parametrize("element", ["HB2n-12", "HB2n-16", "HB2n-40p"])
def test_the_couple_is_the_gradient_of_its_potential_and_its_stiffness_the_force_gradient(element):
    """At a deformed state (a turn of 2 rad and noise): the force's work on v against central
    differences of -M theta (step 1e-6 of the state: truncation ~1e-12, round-off ~1e-10
    relative; tolerance 1e-7), the stiffness against differences of the force (same)."""
    s = scene_from_dict(_scene(element, moment=0.3))
    p = plan(s)
    model = build_model(p)
    loading = static_loading(model, external_loads(model, p), p)
    rng = np.random.default_rng(3)
    u = _rotated(model, 2.0) + 1e-3 * rng.standard_normal(model.mesh.n_dof)
    v = rng.standard_normal(model.mesh.n_dof)
    eps = 1e-6
    dtheta = (loading.face.rotation(u + eps * v) - loading.face.rotation(u - eps * v)) / (2 * eps)
    f = loading.force(u) - loading.Q
    assert f @ v == pytest.approx(loading.M * dtheta, rel=1e-7)
    rows = loading.face.rows
    Kv = (loading.force(u + eps * v) - loading.force(u - eps * v)) / (2 * eps)
    assert np.allclose(loading.stiffness(u) @ v[rows], Kv[rows], rtol=1e-7, atol=1e-7 * np.abs(Kv).max())
    assert np.allclose(np.delete(Kv, rows), 0.0)


@pytest.mark.parametrize("element", ["HB2n-12", "HB2n-16", "HB2n-20xyp", "HB2n-40p"])
def test_the_compiled_newton_is_the_python_newton_with_a_couple(element):
    """From rest to a couple that turns the end by about 0.3 rad in one increment: the same
    outcome and iterations, the state to 1e-9 of its size (the factorisations differ in
    round-off only)."""
    s = scene_from_dict(_scene(element, n=8, moment=0.3 * 3 * MU * 0.007 * 0.005 ** 3 / 12 / 0.16))
    p = plan(s)
    model = build_model(p)
    loading = static_loading(model, external_loads(model, p), p)
    u0 = np.zeros(model.mesh.n_dof)
    atol = 1e-8 * np.linalg.norm(np.delete(loading.force(u0), model.fixed))
    ref = newton_reference(model, u0, loading, atol, 25)
    out = newton(model, u0, loading, atol, 25)
    assert (out.converged, out.iterations) == (ref.converged, ref.iterations)
    assert ref.converged
    assert np.abs(out.u - ref.u).max() <= 1e-9 * np.abs(ref.u).max()
    assert 0.25 < loading.face.rotation(out.u) < 0.35


def test_the_rotation_is_continued_past_pi_and_the_beam_rolls_up():
    """A couple of 2 pi EI / L (E = 3 mu: plane stress, incompressible) rolls a strip of
    L / h = 70 into a circle: theta about 2 pi (not folded back into (-pi, pi]) and the tip
    back near the root. (The benchmark suite measures the departure from the elastica.)"""
    L, h, w = 0.35, 0.005, 0.007
    M = 2 * math.pi * 3 * MU * w * h ** 3 / 12 / L
    rec, _ = run_scene(scene_from_dict(_scene("HB2n-40p", n=16, moment=M, length=L)))
    assert rec["status"] == "converged" and rec["stable"]
    assert rec["tip"]["rotation"] == pytest.approx(2 * math.pi, rel=0.01)
    assert math.hypot(L + rec["tip"]["ux"], rec["tip"]["uy"]) < 0.01 * L
    assert "end_moment" in rec["effects"]


def test_an_end_moment_in_a_dynamic_scene_is_refused():
    d = paper.pendulum_scene("neo-hookean", "plane-stress", 1e-3, "HB2n-12", 4)
    d["loads"]["end_moment"] = 1.0
    with pytest.raises(SceneError, match="loads.end_moment: a static load only"):
        scene_from_dict(d)


@pytest.mark.parametrize("element", sorted(ELEMENTS))
def test_the_hinge_fixes_r_and_the_y_kinds_of_order_two_or_more(element):
    """r(0, y) = y a: r_y of the first node stays free, every other pure y-kind is fixed; an
    element linear in y is then pinned (the paper's pin)."""
    model = build_model(plan(scene_from_dict(_scene(element, left="hinge"))))
    kinds = [k for k in model.mesh.element.kinds if KINDS[k][0] == 0 and KINDS[k][1] != 1]
    assert sorted(model.fixed.tolist()) == sorted(model.mesh.dofs(0, kinds).tolist())
    if max(KINDS[k][1] for k in model.mesh.element.kinds) <= 1:
        pinned = build_model(plan(scene_from_dict(_scene(element, left="pin"))))
        assert sorted(model.fixed.tolist()) == sorted(pinned.fixed.tolist())
