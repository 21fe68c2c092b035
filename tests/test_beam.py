"""Assembly contract tests over every element (and every law x formulation on one), the
measurements of ancf.checks.element:
internal force = energy gradient, tangent = force gradient, rigid motions, mass and
gravity integrate exactly, and only the effects a scene calls for are built."""
import numpy as np
import pytest

from ancf.checks import element as checks
from ancf.checks.element import bent_state, rotate, small_model
from ancf.kinematics.section.model import BeamModel
from ancf.simulation import run_scene
from contract.scene import scene_from_dict
from contract import paper

from .conftest import ALL_ELEMENTS, ALL_FORMULATIONS, ALL_LAWS

# every element in every formulation it runs (a cable: plane stress, ancf.checks.element.runs)
CASES = [(el, "yeoh", f) for el in ALL_ELEMENTS for f in ALL_FORMULATIONS if checks.runs(el, f)] + \
        [("HB2n-12", law, f) for law in ALL_LAWS if law != "yeoh" for f in ALL_FORMULATIONS] + \
        [("HC2n-8", law, "plane-stress") for law in ALL_LAWS if law != "yeoh"]


def make_model(element, law, form, n=3, penalty=20e6):
    return small_model(element, law, form, n, penalty)


@pytest.mark.parametrize("element,law,form", CASES)
def test_internal_force_is_the_energy_gradient(element, law, form, rng):
    """Taylor test: the remainder of U(u + h d) - U(u) - h f.d falls like h^2."""
    res = checks.energy_gradient(make_model(element, law, form), rng)
    assert res["passes"], res


@pytest.mark.parametrize("element,law,form", CASES)
def test_tangent_is_the_force_gradient(element, law, form, rng):
    """Taylor test of the tangent, and its symmetry."""
    res = checks.tangent_gradient(make_model(element, law, form), rng)
    assert res["passes"], res


@pytest.mark.parametrize("element,law,form", CASES)
def test_rigid_motion_leaves_energy_and_rotates_force(element, law, form, rng):
    model = make_model(element, law, form)
    res = checks.rigid_motion(model, rng)
    assert res["passes"], res
    u = bent_state(model, rng)
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
    f_dg -> f_int at the midpoint as u1 -> u0 (second order). An element with an assumed
    strain has none (det C_bar is quartic in u), nor has a cable (its fibre stretch is not
    polynomial in u): both routes refuse them, naming the element."""
    model = make_model(element, law, form)
    u0 = bent_state(model, rng, angle=0.2)
    u1 = bent_state(model, rng, angle=0.25)
    spec = model.mesh.element
    if spec.family.refused_integrators(spec):
        from ancf.solvers.compiled_steps import CompiledLoop
        why = "a cable's fibre stretch" if spec.kinematics == "cable" else "an assumed strain"
        with pytest.raises(ValueError, match=f"element {element}: {why}"):
            model.discrete_gradient_force_and_tangent(u0, u1)
        with pytest.raises(ValueError, match=f"element {element}: {why}"):
            CompiledLoop(model, model.mass_matrix(), np.zeros_like(u0), {}, discrete_gradient=True)
        return
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


@pytest.mark.parametrize("element,law,form", CASES)
def test_compiled_strain_energy_matches_the_numpy_reference(element, law, form, rng):
    """strain_energy (the compiled kernel, pressure field included) equals the numpy
    reference strain_energy_numpy at a bent state, and an inverted state raises
    InadmissibleState on both (a cable: a bent arc shrunk 1000 times, where its inner
    fibres' stretch is < 0: ancf.checks.element.inadmissible_state)."""
    from ancf.kinematics.section.model import InadmissibleState

    model = make_model(element, law, form)
    u = bent_state(model, rng)
    ref = model.strain_energy_numpy(u)
    assert model.strain_energy(u) == pytest.approx(ref, rel=1e-12)
    inverted = np.zeros_like(u)                    # every vector coordinate mirrored in y: det F = -1
    inverted[1::2] = -2.0 * model.mesh.reference[1::2]
    if model.mesh.element.family.mirror_admissible:   # (a cable's reference has no y; mirrored, it stays admissible)
        inverted = checks.inadmissible_state(model)
    for energy in (model.strain_energy, model.strain_energy_numpy):
        with pytest.raises(InadmissibleState):
            energy(inverted)


@pytest.mark.parametrize("element,law,form", CASES)
def test_fused_kernel_matches_the_numpy_reference(element, law, form, rng):
    """The chain rule is written three times: Material.evaluate (numpy, the reference),
    kernels.assemble_force_tangent (band storage, the Python solvers) and
    kernels.element_terms (column storage, inside assemble_fused of the compiled steps
    and statics). This holds the third equal to the first, force and tangent; with an
    element pressure field (HB2n-40p, penalised) the reference includes
    ancf.kinematics.section.pressure.ProjectedPenalty, which the fused kernel reads as data. Called through
    the loops' entry, ancf.kinematics.kernels.element_assemble, which sends a cable to its own
    kernel (ancf.kinematics.cable.kernels; its reference is CableModel's numpy chain rule)."""
    from ancf.core.bandsolve import col_matvec
    from ancf.kinematics.kernels import element_assemble as assemble_fused, element_work
    from ancf.kinematics.section.kernels import OK

    model = make_model(element, law, form)
    u = bent_state(model, rng)
    dN, w, dofs, ops, consts, pr, first = model.fused
    assert model.compiled and (pr[2].shape[0] > 0) == (model.pressure is not None)
    n, b = u.size, int(model.mesh.bandwidth)
    f, Kc = np.empty(n), np.zeros((n, b + 1))
    assert assemble_fused(u, u, 0.0, dN, w, dofs, ops, consts, pr, f, Kc, True,
                          *element_work(ops, dN, pr)) == OK
    f_ref, K_ref = model.internal_force_and_tangent_numpy(u)
    K_ref = K_ref.to_sparse()
    np.testing.assert_allclose(f, f_ref, rtol=0, atol=1e-12 * np.abs(f_ref).max())
    x, y = rng.standard_normal(n), np.empty(n)
    col_matvec(Kc, first, x, y)
    np.testing.assert_allclose(y, K_ref @ x, rtol=0, atol=1e-12 * abs(K_ref).max() * np.abs(x).sum())
