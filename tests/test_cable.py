"""The hyperelastic ANCF cable HC2n-8 (ancf.kinematics.cable.model): its section law, its contract, its
supports and loads, its runs, and what its section model costs.

Tolerances are derived in each docstring before the numbers they bound; measured values are
quoted where they set a bound's margin. The contract checks shared with every element
(force = energy gradient, tangent = force gradient, rigid motions, compiled = numpy, for
every law) run the cable in tests/test_beam.py; the inertia count in
tests/test_stability_inertia.py."""
from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from ancf.checks import element as checks
from ancf.build import model_for, plan
from ancf.build import build_model, external_loads, static_loading
from ancf.kinematics.cable.model import section_moment
from ancf.checks.element import bent_state, paper_material, small_model
from ancf.elements import ElementSpec, get_element
from ancf.core.mesh import Mesh
from ancf.core.quadrature import gauss
from ancf.simulation import run_scene
from contract import paper
from contract.errors import SceneError
from contract.scene import scene_from_dict
from mechanics.laws import LAWS

ROOT = Path(__file__).resolve().parent.parent
CABLE = "HC2n-8"
H, W = 0.005, 0.007
PAPER_LAWS = ("neo-hookean", "mooney-rivlin", "yeoh")


def constants(law: str) -> tuple[dict, float]:
    c = dict(checks.law_constants(law))
    return c, c.pop("density")


def EI_per_width(law: str) -> float:
    """3 mu h^3 / 12: the small-strain bending stiffness per width (E = 3 mu, incompressible)."""
    c, _ = constants(law)
    return 3.0 * LAWS[law].shear_modulus(c) * H ** 3 / 12.0


# -- the element's definition -------------------------------------------------------------------

def test_the_cable_is_registered_listed_and_declares_its_kinematics():
    spec = get_element(CABLE)
    assert spec.kinematics == "cable" and spec.family.name == "cable" and spec.dof == 8
    assert spec.kinds == ("r", "r_x") and spec.family.formulations == ("plane-stress",)
    p = subprocess.run([sys.executable, "-m", "ancf", "elements"], capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0 and any(line.startswith(CABLE) for line in p.stdout.splitlines())


def test_a_cable_with_a_section_coordinate_is_refused():
    with pytest.raises(ValueError, match="a cable's basis and kinds are in x alone"):
        ElementSpec("bad-cable", ("1", "x", "y", "x*y"), (0.0, 1.0), ("r", "r_y"), kinematics="cable")
    with pytest.raises(ValueError, match="element bad: ancf.element.kinematics: unknown value 'shell'; allowed: 'cable', 'continuum'"):
        ElementSpec("bad", ("1", "x"), (0.0, 1.0), ("r",), kinematics="shell")


def test_the_fibre_energy_is_the_laws_incompressible_uniaxial_energy():
    """The tape of the fibre (ancf.core.tape.trace_uniaxial: the plane-stress W at F = diag(lambda,
    lambda^-1/2)) replayed compiled, against the independently typed nominal stress of
    studies.verification.closed_forms (P = 2 (lambda - lambda^-2)(W1 + W2 / lambda)): W_u' = P for every law,
    1e-12 relative (both explicit formulas: round-off); W_u(1) = 0, W_u'(1) = 0 and
    W_u''(1) = 3 mu (E of an incompressible solid), 1e-12."""
    from ancf.core.tape import evaluate, trace_uniaxial
    from studies.verification.closed_forms import nominal_stress

    for law in LAWS:
        c, _ = constants(law)
        ops, consts = trace_uniaxial(paper_material(law, "plane-stress"))
        lam = np.array([[1.0, 0.8, 0.95, 1.05, 1.3, 1.6]] if law != "gent" else   # (Gent: within its lock,
                       [[1.0, 0.9, 0.95, 1.05, 1.1, 1.15]])                    # I1 - 3 < Jm = 0.1)
        R = evaluate(ops, consts, lam, np.ones_like(lam))
        P = np.array([nominal_stress(law, c, "plane-stress", v) for v in lam[0]])
        mu = LAWS[law].shear_modulus(c)
        np.testing.assert_allclose(R[1, 0, 1:], P[1:], rtol=1e-12)
        assert abs(R[0, 0, 0]) < 1e-12 * mu and abs(R[1, 0, 0]) < 1e-12 * mu
        assert R[3, 0, 0] == pytest.approx(3.0 * mu, rel=1e-12)
        assert np.all(R[2] == 0.0) and np.all(R[4:] == 0.0)       # no J: the tape's one variable is lambda


# -- contract ------------------------------------------------------------------------------------

@pytest.mark.parametrize("law", PAPER_LAWS)
def test_force_is_the_central_difference_of_the_energy_and_tangent_of_the_force(law, rng):
    """Central differences at step eps = 1e-7 (the state's dofs: m and -) at a bent state:
    truncation eps^2 U''' / 6, measured as 2.8e-6 relative at 1e-5 (falling 100 x per decade:
    second order), so 3e-10 at 1e-7; round-off eps_mach U / eps ~ 1e-11 relative. Tolerance
    1e-8 of the largest term (the Taylor tests of tests/test_beam.py take the slopes)."""
    model = small_model(CABLE, law, "plane-stress")
    u = bent_state(model, rng)
    f, K = model.internal_force_and_tangent(u)
    eps = 1e-7
    for d in rng.standard_normal((2, u.size)):
        fd = (model.strain_energy(u + eps * d) - model.strain_energy(u - eps * d)) / (2 * eps)
        assert fd == pytest.approx(f @ d, rel=1e-8, abs=1e-8 * np.abs(f).max() * np.abs(d).sum())
        dfd = (model.internal_force(u + eps * d) - model.internal_force(u - eps * d)) / (2 * eps)
        np.testing.assert_allclose(dfd, K.matvec(d), rtol=0, atol=1e-8 * np.abs(K.ab).max() * np.abs(d).sum())


def test_rigid_motions_carry_no_energy_and_no_force():
    """The reference cable rotated by any angle and shifted: zero energy (1e-12 J against
    O(1e-3) J at the bent state) and zero force (1e-9 N against O(10) N)."""
    model = small_model(CABLE, "yeoh", "plane-stress")
    for t in (0.3, 2.0, -2.9):
        w, _ = checks.rotate(model, np.zeros(model.mesh.n_dof), t, shift=(0.2, -0.1))
        assert abs(model.strain_energy(w)) < 1e-12 and np.abs(model.internal_force(w)).max() < 1e-9


def test_mass_and_gravity_are_the_closed_form_integrals():
    """M = rho h w int N^T N dx and Q_g = rho h w g int N dx against the cubic Hermite's
    closed forms (rho A l_e / 420 [[156, 22 l, 54, -13 l], ...]; rho A g l_e (1/2, l/12, 1/2,
    -l/12)) per element, assembled: exact integrals of polynomials, so round-off, 1e-13 of
    the largest entry. No rotary inertia: the section's int rho y^2 is not in M."""
    mesh = Mesh(get_element(CABLE), 5, 0.35, H, W)
    mat = paper_material("yeoh", "plane-stress")
    model = model_for(mesh, mat, gauss(3, 3), np.array([], int))
    le, rA = mesh.element_length, mat.density * H * W
    l = le
    Me = rA * le / 420.0 * np.array([[156, 22 * l, 54, -13 * l], [22 * l, 4 * l * l, 13 * l, -3 * l * l],
                                     [54, 13 * l, 156, -22 * l], [-13 * l, -3 * l * l, -22 * l, 4 * l * l]])
    M = np.zeros((mesh.n_dof, mesh.n_dof))
    g = np.array([0.0, -9.81])
    Q = np.zeros(mesh.n_dof)
    Ne = rA * le * np.array([0.5, l / 12, 0.5, -l / 12])
    for dofs in mesh.element_dofs:                      # (4, 2): shape function, component
        for i in range(2):
            M[np.ix_(dofs[:, i], dofs[:, i])] += Me
            Q[dofs[:, i]] += Ne * g[i]
    Mm = model.mass_matrix().to_sparse().toarray()
    np.testing.assert_allclose(Mm, M, rtol=0, atol=1e-13 * np.abs(M).max())
    np.testing.assert_allclose(model.gravity_force(g), Q, rtol=0, atol=1e-13 * np.abs(Q).max())
    assert checks.mass(CABLE)["passes"]


def test_the_axial_patch_test_and_uniaxial_tension_against_the_closed_form():
    """A uniform stretch is in the cable's space: (1) the free cable's force at r = (1.3 x, 0)
    is P h w at the ends and zero elsewhere (ancf.checks.element.axial_patch: 1e-6 of P h w, its P by
    central differences to ~1e-9); (2) a strip on ``slide`` under the end load F = P h w
    stretches to the closed-form lambda(P) of plane-stress uniaxial tension (Ogden;
    studies.verification.closed_forms.uniaxial_stretch), every law: Newton stops at 1e-8 of the load, so
    1e-6 on lambda - 1 (the benchmark's tension tolerance)."""
    from studies.verification.closed_forms import uniaxial_stretch

    res = checks.patch(CABLE)
    assert res["passes"] and res["error"] < 1e-6
    for law in PAPER_LAWS:
        c, rho = constants(law)
        P = 3e6
        d = {"name": "tension", "beam": {"length": 0.16, "height": H, "width": W},
             "material": {"law": law, "formulation": "plane-stress", "density": rho, **c},
             "ancf": {"element": CABLE, "elements": 4}, "supports": {"left": "slide"},
             "loads": {"tip_force": [P * H * W, 0.0]}, "analysis": {"kind": "static"}}
        rec, _ = run_scene(scene_from_dict(d))
        lam = uniaxial_stretch(law, c, "plane-stress", P)
        assert rec["status"] == "converged"
        assert abs(1.0 + rec["tip"]["ux"] / 0.16 - lam) < 1e-6 * (lam - 1.0), law
        assert abs(rec["tip"]["uy"]) < 1e-12


# -- the compiled loops ------------------------------------------------------------------------------

def test_the_compiled_loops_run_the_cable_with_the_continuum_elements_specialisations():
    """One element interface (ancf.kinematics.kernels): after a continuum element's static and
    dynamic runs, the cable's add no compiled specialisation of the static Newton or the
    step loop (the data have the same types; the kernel is chosen from them)."""
    from ancf.solvers import compiled_statics
    from ancf.solvers import compiled_steps
    from studies.common.pendulum_cases import pendulum_dict

    def runs(element):
        run_scene(scene_from_dict(paper.cantilever_scene("yeoh", "plane-stress", element, 2, quadrature=None)))
        run_scene(scene_from_dict(pendulum_dict(element, 2, "plane-stress", 1e-3, t_end=2e-3)))

    runs("HB2n-16")
    before = {f: len(getattr(m, f).signatures) for m, f in ((compiled_statics, "newton"), (compiled_steps, "advance"))}
    runs(CABLE)
    after = {f: len(getattr(m, f).signatures) for m, f in ((compiled_statics, "newton"), (compiled_steps, "advance"))}
    assert before == after and all(v >= 1 for v in after.values())


def test_the_loops_kernel_equals_the_numpy_reference_at_a_large_deformation(rng):
    """Force, tangent and energy of the loops' entry (element_assemble / element_energy, with
    alpha_f blending two states) against CableModel's numpy chain rule at the same blended
    state: round-off, 1e-12 of the largest term."""
    from ancf.core.bandsolve import col_matvec
    from ancf.kinematics.kernels import element_assemble, element_energy, element_work
    from ancf.kinematics.section.kernels import OK, live_tape

    model = small_model(CABLE, "mooney-rivlin", "plane-stress", n=4)
    u, un = bent_state(model, rng, angle=2.5), bent_state(model, rng, angle=2.0)
    dN, w, dofs, ops, consts, pr, first = model.fused
    ops, consts = live_tape(ops, consts)
    n, b = u.size, model.mesh.bandwidth
    f, Kc = np.empty(n), np.empty((n, b + 1))
    sc = element_work(ops, dN, pr)
    assert element_assemble(u, un, 0.3, dN, w, dofs, ops, consts, pr, f, Kc, True, *sc) == OK
    ue = 0.7 * u + 0.3 * un
    f_ref, K_ref = model.internal_force_and_tangent_numpy(ue)
    np.testing.assert_allclose(f, f_ref, rtol=0, atol=1e-12 * np.abs(f_ref).max())
    x, y = rng.standard_normal(n), np.empty(n)
    col_matvec(Kc, first, x, y)
    np.testing.assert_allclose(y, K_ref.to_sparse() @ x, rtol=0, atol=1e-12 * np.abs(K_ref.ab).max() * np.abs(x).sum())
    assert element_energy(ue, dN, w, dofs, ops, consts, pr, *sc) == pytest.approx(model.strain_energy_numpy(ue),
                                                                                  rel=1e-12)
    assert model.roundoff_floor(ue) > 0.0


# -- supports, loads and what the cable refuses ----------------------------------------------------

def test_supports_fix_the_cables_coordinates():
    """Node 0's dofs are r (0, 1) and r_x (2, 3): the clamp (and the slide, the same for a
    cable) fixes r and r_x's y-component, the direction; clamp = "all" both of r_x; the pin
    and the hinge fix r."""
    mesh = Mesh(get_element(CABLE), 3, 0.16, H, W)
    assert list(mesh.element.family.fixed_dofs(mesh, "clamp", "face")) == [0, 1, 3]
    assert list(mesh.element.family.fixed_dofs(mesh, "slide", None)) == [0, 1, 3]
    assert list(mesh.element.family.fixed_dofs(mesh, "clamp", "all")) == [0, 1, 2, 3]
    assert list(mesh.element.family.fixed_dofs(mesh, "pin", None)) == [0, 1]
    assert list(mesh.element.family.fixed_dofs(mesh, "hinge", None)) == [0, 1]


def _couple_scene(M=0.0, n=4, L=0.16, law="neo-hookean", tip=None):
    c, rho = constants(law)
    loads = {"end_moment": M} if M else {}
    if tip is not None:
        loads["tip_force"] = tip
    return scene_from_dict({"name": "couple", "beam": {"length": L, "height": H, "width": W},
                            "material": {"law": law, "formulation": "plane-stress", "density": rho, **c},
                            "ancf": {"element": CABLE, "elements": n}, "supports": {"left": "slide"},
                            "loads": loads or {"tip_force": [0.0, 0.0]}, "analysis": {"kind": "static", "load_steps": 10}})


def test_the_end_face_is_the_normal_of_r_x_and_the_couple_the_gradient_of_its_potential(rng):
    """The face d = R90 r_x(L): a rigid turn phi reads theta = phi to round-off (|d| = the
    stretch, 1e-12); at a deformed state the couple's force on v against central differences
    of -M theta (step 1e-6: truncation ~1e-12, round-off ~1e-10: 1e-7), its stiffness against
    differences of the force (the same)."""
    s = _couple_scene(M=0.01)
    p = plan(s)
    model = build_model(p)
    loading = static_loading(model, external_loads(model, p), p)
    face = loading.face
    for phi in (0.3, 2.5, -3.0):
        w, _ = checks.rotate(model, np.zeros(model.mesh.n_dof), phi)
        assert face.rotation(w) == pytest.approx(phi, abs=1e-12)
        assert np.linalg.norm(face.first_moment(w)) == pytest.approx(1.0, rel=1e-12)
    u = bent_state(model, rng, angle=2.0) + 1e-3 * rng.standard_normal(model.mesh.n_dof)
    v = rng.standard_normal(model.mesh.n_dof)
    eps = 1e-6
    dtheta = (face.rotation(u + eps * v) - face.rotation(u - eps * v)) / (2 * eps)
    assert (loading.force(u) - loading.Q) @ v == pytest.approx(loading.M * dtheta, rel=1e-7)
    Kv = (loading.force(u + eps * v) - loading.force(u - eps * v)) / (2 * eps)
    np.testing.assert_allclose(loading.stiffness(u) @ v[face.rows], Kv[face.rows], rtol=1e-7,
                               atol=1e-7 * np.abs(Kv).max())


def test_the_end_load_does_the_work_of_the_uniform_traction_on_the_end_section():
    """The uniform dead traction F / (h w) on the end section r(L) + Y n does the work
    F . delta r(L) (int Y dY = 0): the load vector is F on the last node's r, zero elsewhere."""
    s = _couple_scene(tip=[0.3, -0.2])
    p = plan(s)
    model = build_model(p)
    f = external_loads(model, p)["tip_force"]
    expect = np.zeros(model.mesh.n_dof)
    expect[model.mesh.dofs(model.mesh.n_nodes - 1, ("r",))] = [0.3, -0.2]
    np.testing.assert_allclose(f, expect, rtol=0, atol=1e-15)


@pytest.mark.parametrize("form", ["plane-strain", "paper"])
def test_a_formulation_the_cable_cannot_run_is_refused_naming_it(form, tmp_path):
    """In the API (SceneError) and on the command line (exit 2, one line, no traceback)."""
    d = paper.cantilever_scene("yeoh", form, CABLE, 4, quadrature=None)
    with pytest.raises(SceneError, match=rf"material.formulation: '{form}' cannot run element {CABLE}.*"
                                         r"allowed for it: 'plane-stress'"):
        run_scene(scene_from_dict(d))
    text = (ROOT / "scenes" / "cantilever-yeoh-cable.toml").read_text()
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace('formulation = "plane-stress"', f'formulation = "{form}"\npenalty = 1.0e9'))
    p = subprocess.run([sys.executable, "-m", "ancf", "run", str(bad)], capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 2 and "Traceback" not in p.stderr
    assert len(p.stderr.strip().splitlines()) == 1 and "material.formulation" in p.stderr
    assert "'plane-stress'" in p.stderr


def test_the_discrete_gradient_is_refused_naming_the_integrators_it_takes():
    from studies.common.pendulum_cases import pendulum_dict

    d = pendulum_dict(CABLE, 2, "plane-stress", 1e-3, integrator="discrete-gradient")
    with pytest.raises(SceneError, match=r"analysis.integrator: 'discrete-gradient' cannot run element HC2n-8"):
        run_scene(scene_from_dict(d))


# -- the section's bending moment --------------------------------------------------------------------

def _element_moment(law: str, kh: float, elements: int = 8, lengths: int = 8):
    """The couple M (N m) of the cable's section at kappa h (:func:`ancf.kinematics.cable.model.section_moment`,
    64 points) applied to a strip of ``lengths`` h on ``slide``, and the curvature the element
    takes under it (tip rotation / L: uniform bending)."""
    mat = paper_material(law, "plane-stress")
    k = kh / H
    M = W * section_moment(mat, k, H)["moment_per_width"]
    rec, _ = run_scene(_couple_scene(M=M, n=elements, L=lengths * H, law=law))
    assert rec["status"] == "converged"
    return M / W, rec["tip"]["rotation"] / (lengths * H)


def test_the_bending_moment_leaves_the_linear_EI_kappa_with_the_laws_own_coefficient():
    """Not a linear EA eps^2 / 2 + EI kappa^2 / 2 (whose M / (EI kappa) is 1 at every kappa):
    the cable's M / (EI kappa) = 1 + c (kappa h)^2 at N = 0, with c = 1/30 for neo-Hookean
    (derived: W_u' = 2 C10 (3 e - 3 e^2 + 4 e^3 ...), e = delta - Y kappa, N = 0 sets
    delta = (kappa h)^2 / 12, then M = EI kappa (3 - 1/2 (kappa h)^2 + 3/5 (kappa h)^2) / 3).
    Measured through the element (8 elements over 8 h under the section's couple; the
    curvature from the tip's rotation, which matches the section's kappa to 8e-7 at
    kappa h = 0.1): c within 2 % of 1/30 at kappa h = 0.1 and 0.2 (the next order, c falling
    0.0333 -> 0.0328 from kappa h = 0.05 to 0.5, and the 3-point section rule, 1e-5 of M at
    0.2, i.e. 0.75 % of c, bound it). Yeoh's own c is 0.134 (its C20 stiffens the fibres)."""
    EI = EI_per_width("neo-hookean")
    for kh in (0.1, 0.2):
        M, kappa = _element_moment("neo-hookean", kh)
        c = (M / (EI * kappa) - 1.0) / (kappa * H) ** 2
        assert c == pytest.approx(1.0 / 30.0, rel=0.02), kh
    M, kappa = _element_moment("yeoh", 0.2)
    c = (M / (EI_per_width("yeoh") * kappa) - 1.0) / (kappa * H) ** 2
    assert c == pytest.approx(0.134, rel=0.02)


def test_the_section_model_is_stiffer_than_the_exact_plane_stress_bending_by_0_225_kappa_h_squared():
    """Against the exact pure bending of a plane-stress strip (studies.verification.closed_forms.
    plane_stress_bending, a two-point problem across the thickness shot to round-off:
    M / (EI kappa) = 1 - 0.19 (kappa h)^2 for neo-Hookean), the cable's uniaxial fibres
    (no radial stress; eta = Y) make M too large by (M_cable / M_exact - 1) / (kappa h)^2 =
    0.225 (neo-Hookean, Yeoh) and 0.245 (Mooney-Rivlin) at kappa h = 0.05 ... 0.3 (measured
    0.2248 to 0.2273, 0.2431 to 0.2449; with the thickness change d eta / dY = lambda^-1/2
    0.150 for all three, the test below). Bound: [0.215, 0.255] at kappa h = 0.1 and 0.2 (the
    next order moves it by < 1 % there)."""
    from studies.verification.closed_forms import plane_stress_bending

    for law in PAPER_LAWS:
        c, _ = constants(law)
        mat = paper_material(law, "plane-stress")
        for kh in (0.1, 0.2):
            k = kh / H
            ratio = section_moment(mat, k, H)["moment_per_width"] / plane_stress_bending(law, c, k, H)["moment_per_width"]
            assert 0.215 <= (ratio - 1.0) / kh ** 2 <= 0.255, (law, kh, ratio)
    M, kappa = _element_moment("neo-hookean", 0.2)              # and through the element
    exact = plane_stress_bending("neo-hookean", constants("neo-hookean")[0], kappa, H)["moment_per_width"]
    assert 0.215 <= (M / exact - 1.0) / (kappa * H) ** 2 <= 0.25


def test_keeping_eta_equal_to_Y_costs_a_third_of_the_section_models_error():
    """The cable keeps eta = Y (each fibre at its reference height). With the thickness change
    of uniaxial stress, d eta / dY = lambda^-1/2 (:func:`ancf.kinematics.cable.model.section_moment`,
    thickness_change: an ODE per section), M / (EI kappa) = 1 - (kappa h)^2 / 24 for
    neo-Hookean against eta = Y's 1 + (kappa h)^2 / 30: eta = Y costs 0.075 (kappa h)^2 of M
    (measured 0.0750 at kappa h = 0.1 for neo-Hookean and Yeoh, 0.0949 Mooney-Rivlin), a third
    of the model's 0.225 (0.245); the other 0.150, the radial stress, is in both. Bounds: the
    coefficients within 3 % at kappa h = 0.1."""
    mat = paper_material("neo-hookean", "plane-stress")
    kh = 0.1
    k = kh / H
    EI = EI_per_width("neo-hookean")
    keep = section_moment(mat, k, H)["moment_per_width"] / (EI * k)
    thick = section_moment(mat, k, H, thickness_change=True)["moment_per_width"] / (EI * k)
    assert (keep - 1) / kh ** 2 == pytest.approx(1 / 30, rel=0.03)
    assert (thick - 1) / kh ** 2 == pytest.approx(-1 / 24, rel=0.03)
    for law, expected in (("neo-hookean", 0.075), ("mooney-rivlin", 0.095), ("yeoh", 0.075)):
        m = paper_material(law, "plane-stress")
        cost = (section_moment(m, k, H)["moment_per_width"]
                / section_moment(m, k, H, thickness_change=True)["moment_per_width"] - 1) / kh ** 2
        assert cost == pytest.approx(expected, rel=0.03), law


def test_three_section_points_resolve_the_section_to_a_hundredth_of_the_models_error():
    """The default rule's 3 points across against 64 (Gauss; W_u is not polynomial): the
    moment's quadrature error is below 1 % of the section model's own error 0.225 (kappa h)^2
    to kappa h = 0.3 and below 2 % at 0.5 (measured at 0.1 / 0.3 / 0.5: neo-Hookean 8.6e-7 /
    6.8e-5 / 5.0e-4, Mooney-Rivlin 1.3e-6 / 1.0e-4 / 7.3e-4, Yeoh 1.6e-6 / 1.3e-4 / 9.3e-4,
    the last 1.7 % of 0.056); 2 points' is not (8.9e-4 at 0.1: 40 % of it)."""
    assert get_element(CABLE).quadrature[0][2] == (3, 3)
    for law in PAPER_LAWS:
        mat = paper_material(law, "plane-stress")
        for kh, share in ((0.1, 0.01), (0.3, 0.01), (0.5, 0.02)):
            k = kh / H
            ref = section_moment(mat, k, H, points=64)["moment_per_width"]
            err3 = abs(section_moment(mat, k, H, points=3)["moment_per_width"] / ref - 1)
            assert err3 < share * 0.225 * kh ** 2, (law, kh, err3)
        err2 = abs(section_moment(mat, 0.1 / H, H, points=2)["moment_per_width"] /
                   section_moment(mat, 0.1 / H, H, points=64)["moment_per_width"] - 1)
        assert err2 > 0.1 * 0.225 * 0.1 ** 2


@pytest.mark.parametrize("rule,spurious", [((2, 3), 1), ((3, 1), 2), ((3, 2), 0), ((3, 3), 0)])
def test_the_rank_tests_spurious_count_matches_the_cables_tangent(rule, spurious):
    """Zero eigenvalues of one free cable's Jacobi-scaled tangent at u = 0 (neo-Hookean) beyond
    the rigid three, against ancf.checks.rank's count on the fibre strain u_x' - y u_y'': 2 points
    along leave the axial quadratic unseen, 1 across the bending (y = 0)."""
    from ancf.checks.rank import rank_test

    mat = paper_material("neo-hookean", "plane-stress")
    mesh = Mesh(get_element(CABLE), 1, H, H, W)
    m = model_for(mesh, mat, gauss(*rule), np.array([], int))
    K = m.internal_force_and_tangent(np.zeros(mesh.n_dof))[1].to_sparse().toarray()
    full = model_for(mesh, mat, gauss(6, 6), np.array([], int)).internal_force_and_tangent(np.zeros(mesh.n_dof))[1]
    s = 1.0 / np.sqrt(np.diag(full.to_sparse().toarray()))
    lam = np.linalg.eigvalsh(s[:, None] * (0.5 * (K + K.T)) * s)
    zeros = int(np.sum(np.abs(lam) < 1e-10 * lam[-1]))
    assert zeros - 3 == spurious == rank_test(CABLE, rule, 1.0)["spurious"]


def test_three_points_along_leave_the_membrane_stretch_between_them_unseen_and_the_default_keeps_them():
    """The finite-strain test (ancf.checks.rank.strain_test on the fibre strain lambda - 1) at the slender
    pendulum's l_e / h = 35: [3, 3] sees 9 % of the worst state's strain (a stretch between the
    points along), [5, 3] 93 % (measured 0.09 and 0.93: bounds 0.2 and 0.8). The default keeps
    [3, 3] at every l_e / h all the same: seeing that stretch is the cubic cable's membrane
    locking, coarse meshes 2-3 times further from the continuum with [5, 3] and the same
    converged tip (ancf/elements/, HC2n-8's note; the card's rank section)."""
    from ancf.checks.rank import ASPECTS, default_quadrature, strain_test

    assert strain_test(CABLE, (3, 3), 35.0)["ratio"] < 0.2 < 0.8 < strain_test(CABLE, (5, 3), 35.0)["ratio"]
    assert {default_quadrature(get_element(CABLE), False, a) for a in ASPECTS + (140.0,)} == {(3, 3)}


# -- runs -----------------------------------------------------------------------------------------------

def test_the_shipped_cantilever_runs_through_ancf_run_within_0_1_percent_of_the_continuum(tmp_path):
    """scenes/cantilever-yeoh-cable.toml (16 elements) by the command line, against the
    converged plane-stress continuum (tests/gold/fem_cantilever.json, Richardson value, its
    error estimate 1e-5 relative): the cable's model error is of order (h / L)^2 ~ 1e-3 (no
    shear, uniaxial fibres: 0.225 (kappa h)^2), its discretisation at 16 elements 1e-5 of it
    (measured 0.074 %, 0.073 % converged): tolerance 0.1 %."""
    out = tmp_path / "r.json"
    p = subprocess.run([sys.executable, "-m", "ancf", "run", str(ROOT / "scenes" / "cantilever-yeoh-cable.toml"),
                        "--json", str(out), "--quiet"], capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    rec = json.loads(out.read_text())
    assert rec["status"] == "converged" and rec["stable"] is True and rec["ndof"] == 17 * 4 - 3
    gold = json.loads((ROOT / "tests" / "gold" / "fem_cantilever.json").read_text())["cases"]["yeoh/plane-stress"]
    ref = np.array([gold["tip"]["ux"], gold["tip"]["uy"]])
    err = np.linalg.norm(np.array([rec["tip"]["ux"], rec["tip"]["uy"]]) - ref) / np.linalg.norm(ref)
    assert err < 1e-3


def test_the_shipped_pendulum_runs_through_ancf_run_within_0_2_percent_of_l_of_the_continuum(tmp_path):
    """scenes/pendulum-yeoh-cable.toml (8 elements, dt 1 ms) by the command line, with VTK
    output (the section drawn as r + Y n), against the converged continuum pendulum
    (tests/gold/fem_pendulum.json): the tip at every output time within 0.2 % of L (measured
    0.081 % at t = 0.4 s; 16 elements 0.056 %: the cable's model error, as on the cantilever,
    of order 1e-3, plus the time step's)."""
    from studies.common.pendulum_cases import continuum_pendulum, describe_dynamic, tip_errors

    out, vtk = tmp_path / "r.json", tmp_path / "vtk"
    p = subprocess.run([sys.executable, "-m", "ancf", "run", str(ROOT / "scenes" / "pendulum-yeoh-cable.toml"),
                        "--json", str(out), "--vtk", str(vtk), "--quiet"], capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    rec = json.loads(out.read_text())
    d = describe_dynamic(rec)
    assert d["ok"] and rec["effects"] == ["elastic", "gravity", "inertia"]
    errs = tip_errors(d["tips"], continuum_pendulum()[("yeoh", "plane-stress")].tips)
    assert len(errs) == 5 and max(errs.values()) < 2e-3, errs
    assert len(sorted(vtk.glob("*.vtu"))) == 6


def test_the_element_converges_to_its_own_limit_fast_on_the_cantilever():
    """The tip of the paper's cantilever (neo-Hookean) at 4, 8, 16, 32 elements: successive
    differences fall by >= 8 per doubling (cubic Hermite: order 3 to 4 in the tip; measured
    2.2e-3, 7.9e-5, 1.8e-6 m ratios 28 and 44)."""
    tips = []
    for n in (4, 8, 16, 32):
        rec, _ = run_scene(scene_from_dict(paper.cantilever_scene("neo-hookean", "plane-stress", CABLE, n,
                                                                  quadrature=None)))
        tips.append(np.array([rec["tip"]["ux"], rec["tip"]["uy"]]))
    d = [np.linalg.norm(tips[i + 1] - tips[i]) for i in range(3)]
    assert d[0] / d[1] > 8 and d[1] / d[2] > 8, d


def test_the_slender_limit_is_the_elastica_and_eulers_arc_within_the_benchmarks_tolerances():
    """The benchmark suite's slender cases (studies.verification.benchmark_scenes, their tolerances fixed there:
    the elastica 2 (0.9 + alpha/12 + alpha^2/4) (h/L)^2; the arc twice the exact plane-stress
    bending's own departure from it, + 1e-6) on the cable, 32 elements, L / h = 50: the
    elastica under alpha = 5 (measured 1.8e-4 of L against 6.1e-3) and the full roll-up under
    an end couple, phi = 2 pi (5.3e-4 against 6.1e-3). The cable has no shear, so its
    distance is its stretch and its law's."""
    from studies.verification import benchmark_scenes as B
    from studies.verification.benchmarks import STUDY
    from studies.verification.closed_forms import elastica_end_moment, elastica_tip_load

    g, L = STUDY["grid"], B.SLENDER_BEAM["length"]
    rec, _ = run_scene(scene_from_dict(B.elastica_scene(g, 5.0, 50.0, CABLE)))
    u, v, _ = elastica_tip_load(5.0)
    assert math.hypot(rec["tip"]["ux"] / L + u, rec["tip"]["uy"] / L + v) < B.elastica_tolerance(5.0, 50.0)
    phi = 2 * math.pi
    rec, _ = run_scene(scene_from_dict(B.arc_scene(g, phi, 50.0, CABLE)))
    x, y = elastica_end_moment(phi)
    assert rec["status"] == "converged" and rec["tip"]["rotation"] == pytest.approx(phi, rel=0.01)
    assert math.hypot(1 + rec["tip"]["ux"] / L - x, rec["tip"]["uy"] / L - y) < 2 * B.arc_departure(phi, 50.0) + 1e-6
