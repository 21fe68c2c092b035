"""The compiled time loop (ancf.solvers.compiled_steps) against the Python loop it replaces: the same
steps, rejections and tips; the chord Newton default within 0.01 mm; Newmark's energy
drift still O(dt^2) with it; a user-registered element and law through it; the fused
kernel and the column-band LDL^T against the reference ones."""
import numpy as np
import pytest

from ancf.core.banded import Banded
from ancf.build import build_integrator, build_model, external_loads, plan
from ancf.kinematics.section.dg_kernels import assemble_dg, dg_scratch
from ancf.core.bandsolve import (col_constrain, col_ldlt, col_ldlt_solve, col_matvec, col_matvec_split, envelope,
                            same_component_only)
from ancf.kinematics.section.kernels import INADMISSIBLE, OK, assemble_fused, step_scratch, strain_energy_fused
from ancf.checks.element import inadmissible_state
from ancf.elements import ELEMENTS
from mechanics.laws import LAWS, Law, register_law
from ancf.solvers.compiled_steps import column_band
from mechanics.time_loop import integrate
from contract import paper
from contract.errors import SceneError
from contract.scene import scene_from_dict

from .test_elements import cubic_element  # noqa: F401 (a fixture)

TIP = 1e-5          # m: 0.01 mm, the record tolerance


def scene(n=8, t_end=0.1, dt=1e-3, law="yeoh", element="HB2n-12", material=None, ancf=None, **analysis):
    return scene_from_dict({
        "name": "pendulum", "beam": dict(paper.PENDULUM),
        "material": material or paper.material_table(law, "plane-stress"),
        "ancf": ancf or {"element": element, "elements": n},
        "supports": {"left": "pin"}, "loads": {"gravity": [0.0, -paper.GRAVITY]},
        "analysis": {"kind": "dynamic", "t_end": t_end, "dt": dt,
                     "output_times": list(np.round(np.linspace(0, t_end, 6), 12)), **analysis}})


def run(sc, compiled=True, energy_limit=1e-3, max_steps=None):
    p = plan(sc)
    model = build_model(p)
    integ = build_integrator(p, model, model.mass_matrix(), external_loads(model, p))
    a = sc.analysis
    return integrate(integ, np.zeros(model.mesh.n_dof), a.t_end, a.dt, a.output_times, a.dt_min,
                     energy_limit=energy_limit, max_steps=max_steps, compiled=compiled), integ


def tip_difference(r1, r2) -> float:
    assert [o.t for o in r1.outputs] == [o.t for o in r2.outputs]
    return max(float(np.hypot(a.tip[0] - b.tip[0], a.tip[1] - b.tip[1])) for a, b in zip(r1.outputs, r2.outputs))


@pytest.mark.parametrize("analysis", [
    dict(dt=3e-3),                                   # 3 ms does not divide the outputs: landing steps
    dict(integrator="newmark"),
    dict(integrator="arnold-bruls", dt=3e-3),        # the forces at the step's ends, carried
    dict(integrator="arnold-bruls", max_iterations=1),
    dict(max_iterations=1),                          # every other step rejected and halved
    dict(integrator="discrete-gradient", dt=3e-3),
    dict(integrator="discrete-gradient", max_iterations=2),
], ids=["ga-landing", "newmark", "ab-landing", "ab-rejections", "rejections", "dg-landing", "dg-rejections"])
def test_full_newton_reproduces_the_python_loop_step_for_step(analysis):
    """newton = "full" is the Python loop's method: the same accepted and rejected steps,
    the same Newton iterations, tips equal to round-off (measured 1e-12 mm). The
    discrete-gradient step is compiled as its Python step (full Newton whatever
    ``newton`` says)."""
    sc = scene(newton="full", **analysis)
    py, _ = run(sc, compiled=False)
    cc, integ = run(sc)
    assert integ.advance is not None
    assert cc.status == py.status == "converged"
    assert (cc.steps, cc.rejected_steps, cc.newton_iterations) == (py.steps, py.rejected_steps, py.newton_iterations)
    if "max_iterations" in analysis:
        assert cc.rejected_steps > 0
    assert tip_difference(py, cc) < 1e-3 * TIP
    for o1, o2 in zip(py.outputs, cc.outputs):
        assert o2.energy.total == pytest.approx(o1.energy.total, rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("integrator", ["generalized-alpha", "arnold-bruls", "discrete-gradient"])
def test_a_pressure_element_steps_as_the_python_loop(integrator):
    """HB2n-40p in penalised plane strain (its pressure field in the compiled kernels as
    data): full Newton step for step as the Python loop, whose force, tangent and energy
    come from ancf.kinematics.section.pressure.ProjectedPenalty."""
    sc = scene(n=4, t_end=0.05, element="HB2n-40p", material=paper.material_table("yeoh", "plane-strain"),
               newton="full", integrator=integrator)
    py, _ = run(sc, compiled=False)
    cc, integ = run(sc)
    assert integ.advance is not None and integ.model.pressure is not None
    assert cc.status == py.status == "converged"
    assert (cc.steps, cc.rejected_steps, cc.newton_iterations) == (py.steps, py.rejected_steps, py.newton_iterations)
    assert tip_difference(py, cc) < 1e-3 * TIP
    for o1, o2 in zip(py.outputs, cc.outputs):
        assert o2.energy.total == pytest.approx(o1.energy.total, rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("newton", ["chord", "modified"])
def test_reused_factorisations_agree_with_the_python_loop(newton):
    sc = scene(newton=newton, dt=3e-3)
    py, _ = run(sc, compiled=False)
    cc, integ = run(sc)
    assert cc.status == "converged" and cc.steps == py.steps
    assert tip_difference(py, cc) < TIP
    stats = integ._loop.stats
    assert stats["factorisations"] < stats["iterations"]        # a factorisation serves several


def test_chord_is_the_default_and_newton_is_validated():
    assert scene().analysis.newton == "chord"
    with pytest.raises(SceneError, match=r"analysis\.newton: unknown value 'quasi'; allowed: "
                                         r"'chord', 'full', 'linear', 'modified'"):
        scene(newton="quasi")


def test_linear_newton_is_one_solve_per_step_as_accurate_as_the_step():
    """newton = "linear": one assembly (force and tangent at the predictor) and one solve
    per step, no verifying residual (chord takes two assemblies per step), and the answer
    of a converged Newton to well within the step's own error: the tip differs from full
    Newton's by less than a tenth of what halving dt changes (stated before the run: the
    linear step's error is the square of a correction of order beta h^3 |da/dt|)."""
    kw = dict(n=8, t_end=0.2, dt=4e-3)
    lin, li = run(scene(newton="linear", **kw), energy_limit=None)
    chord, ci = run(scene(newton="chord", newton_rtol=1e-3, **kw), energy_limit=None)
    full, _ = run(scene(newton="full", **kw), energy_limit=None)
    half, _ = run(scene(newton="full", n=8, t_end=0.2, dt=2e-3), energy_limit=None)
    assert lin.status == chord.status == full.status == half.status == "converged"
    s, c = li._loop.stats, ci._loop.stats
    assert s["residuals"] == s["tangents"] == s["solves"] == s["steps"] == lin.steps
    assert c["residuals"] >= 2 * c["steps"]
    assert tip_difference(lin, full) < 0.1 * tip_difference(full, half)


def test_linear_newton_checks_the_state_and_refuses_what_it_cannot_run():
    """The linear step's admissibility check (ancf.kinematics.kernels.element_admissible) on the
    reference state and on a folded one, for a continuum-based element and a cable; the
    scene refuses a tolerance it would not use and an integrator that is not of the alpha
    family; the Python loop refuses to run it."""
    from ancf.kinematics.kernels import element_admissible, element_work

    for element in ("HB2n-12", "HC2n-8"):
        model = build_model(plan(scene(n=2, element=element)))
        dN, w, dofs, ops, consts, pr, first = model.fused
        chunk, R, Fb, ab, Jb, ew = element_work(ops, dN, pr)
        u = np.zeros(model.mesh.n_dof)
        assert element_admissible(u, dN, dofs, ops, pr, chunk, Fb, ab, Jb) == OK
        collapsed = -np.asarray(model.mesh.reference, dtype=float)   # q = 0: F = 0, r_x = 0
        assert element_admissible(collapsed, dN, dofs, ops, pr, chunk, Fb, ab, Jb) == INADMISSIBLE
        if element == "HB2n-12":
            mirrored = np.zeros(model.mesh.n_dof)
            mirrored[0::2] = -2.0 * np.asarray(model.mesh.reference, dtype=float)[0::2]   # x -> -x: det F = -1
            assert element_admissible(mirrored, dN, dofs, ops, pr, chunk, Fb, ab, Jb) == INADMISSIBLE
    with pytest.raises(SceneError, match=r"analysis\.newton_rtol: not used with analysis\.newton = 'linear'"):
        scene(newton="linear", newton_rtol=1e-3)
    with pytest.raises(SceneError, match=r"analysis\.tolerance: not used with analysis\.newton = 'linear'"):
        scene(newton="linear", tolerance=1e-4)
    with pytest.raises(SceneError, match=r"analysis\.newton: 'linear' .* 'discrete-gradient' runs full Newton"):
        build_model(plan(scene(newton="linear", integrator="discrete-gradient")))
    with pytest.raises(ValueError, match="newton 'linear'"):
        run(scene(newton="linear"), compiled=False)


def test_newmark_energy_drift_stays_second_order_with_the_chord_default():
    """Newmark conserves energy up to O(dt^2) (the trapezoidal rule's error) plus the work
    of the residual Newton leaves; the chord default stops on the residual, so that work
    stays ~1e-12 J and the drift falls 4 times per halving of dt (measured 3.97, 3.99)."""
    drift = []
    for dt in (2e-3, 1e-3, 5e-4):
        res, _ = run(scene(t_end=0.2, dt=dt, integrator="newmark", output_times=list(np.round(
            np.linspace(0, 0.2, 21), 12))), energy_limit=None)
        assert res.status == "converged"
        e = np.array([o.energy.total for o in res.outputs])
        drift.append(np.abs(e - e[0]).max())
    ratios = [drift[i] / drift[i + 1] for i in range(2)]
    assert all(3.5 < r < 4.5 for r in ratios), (drift, ratios)


def test_energy_growth_and_step_limit_stop_the_compiled_loop():
    """A limit below E(0) trips the first check inside the compiled loop (step 10, not an
    output time): the same reason as the Python loop's."""
    res, _ = run(scene(), energy_limit=-1.0)
    py, _ = run(scene(), energy_limit=-1.0, compiled=False)
    assert res.status == "failed" and res.reason.startswith("energy-growth: E rose")
    assert "at t = 0.01 s" in res.reason and res.steps == py.steps == 10
    assert res.reason.split(" J above")[1] == py.reason.split(" J above")[1]
    res, _ = run(scene(), max_steps=30)
    assert res.status == "failed" and "step limit: 30 accepted steps" in res.reason


@pytest.fixture
def user_element_and_law(cubic_element):
    """test_elements' user-defined cubic element and a law defined here (a quartic
    term: the tape's generic power, whose derivative once divided by I1 - 3 = 0 at rest)."""
    law = register_law(Law("quartic (compiled step test)", ("C10", "C20"),
                           lambda I1, I2, c, m: c["C10"] * (I1 - 3.0) + c["C20"] * (I1 - 3.0) ** 4))
    yield cubic_element.name, law.name
    del LAWS[law.name]


def test_a_user_registered_element_and_law_run_through_the_compiled_loop(user_element_and_law):
    element, law = user_element_and_law
    material = {"law": law, "formulation": "plane-stress", "C10": 0.4e6, "C20": 0.2e6, "density": 1100.0}
    sc = scene(material=material, ancf={"element": element, "elements": 4, "quadrature": [4, 3]}, t_end=0.05)
    py, _ = run(sc, compiled=False)
    cc, integ = run(sc)
    assert cc.status == py.status == "converged"
    assert integ._loop.stats["steps"] == cc.steps
    assert tip_difference(py, cc) < TIP


@pytest.mark.parametrize("element", sorted(ELEMENTS))
def test_fused_tangent_of_every_element_in_either_dof_numbering(element):
    """The fused kernel (the loops' entry, ancf.kinematics.kernels.element_assemble) gives the
    model's force and upper band for every registered element, with the mesh's numbering
    (each element's dofs contiguous: the kernel's direct scatter) and with the numbering
    reversed (dofs descending: its general scatter), which permutes f and K."""
    from ancf.kinematics.kernels import element_assemble as assemble_fused, element_work
    sc = scene(material=paper.material_table("mooney-rivlin", "plane-stress"), element=element, n=3)
    model = build_model(plan(sc))
    n, b = model.mesh.n_dof, model.mesh.bandwidth
    u, un = (1e-4 * np.random.default_rng(5).standard_normal(n) for _ in range(2))
    f_ref, K_ref = model.internal_force_and_tangent(0.6 * u + 0.4 * un)
    ops, consts = model._tape
    dN, w = model.fused[:2]                         # with an assumed strain, the sample points too
    scratch = element_work(ops, dN, model.fused[5])
    rev = n - 1 - np.arange(n)
    for dofs, perm in ((model._dofs.astype(np.int64), np.arange(n)), ((n - 1 - model._dofs).astype(np.int64), rev)):
        f, Kc = np.empty(n), np.empty((n, b + 1))
        assert assemble_fused(u[perm], un[perm], 0.4, dN, w, dofs, ops, consts, model.fused[5], f,
                              Kc, True, *scratch) == OK
        np.testing.assert_allclose(f, f_ref[perm], rtol=0, atol=1e-12 * np.abs(f_ref).max())
        f_only = np.empty(n)                        # the force alone: element_forces, its own work arrays
        assert assemble_fused(u[perm], un[perm], 0.4, dN, w, dofs, ops, consts, model.fused[5], f_only,
                              np.empty((0, 0)), False, *scratch) == OK
        np.testing.assert_allclose(f_only, f_ref[perm], rtol=0, atol=1e-12 * np.abs(f_ref).max())
        dense = np.zeros((n, n))
        for j in range(n):
            for r in range(max(0, j - b), j + 1):
                dense[r, j] = dense[j, r] = Kc[j, b + r - j]
        expect = _dense(K_ref.ab, b)[np.ix_(perm, perm)]
        np.testing.assert_allclose(dense, expect, rtol=0, atol=1e-12 * np.abs(expect).max())


@pytest.mark.parametrize("element", ["HB2n-16", "HB2n-40p"])
@pytest.mark.parametrize("law", ["neo-hookean", "mooney-rivlin", "yeoh"])
@pytest.mark.parametrize("form", ["paper", "plane-strain", "plane-stress"])
def test_discrete_gradient_kernel_equals_the_model(element, law, form):
    """The compiled discrete-gradient force and midpoint tangent (assemble_dg) equal
    BeamModel.discrete_gradient_force_and_tangent (numpy jets; with HB2n-40p's pressure
    field in the penalised forms, ProjectedPenalty.discrete_gradient_terms); the force's
    energy identity du . f_dg = U(u1) - U(u0) holds to round-off."""
    model = build_model(plan(scene(material=paper.material_table(law, form), element=element, n=4)))
    assert (model.pressure is not None) == (element == "HB2n-40p" and form != "plane-stress")
    n, b = model.mesh.n_dof, model.mesh.bandwidth
    rng = np.random.default_rng(1)
    u0 = 1e-4 * rng.standard_normal(n)
    u1 = u0 + 1e-5 * rng.standard_normal(n)
    f_ref, K_ref = model.discrete_gradient_force_and_tangent(u0, u1)
    dN, w, dofs, ops, consts, pr, _ = model.fused
    f, Kc = np.empty(n), np.empty((n, b + 1))
    assert assemble_dg(u0, u1, dN, w, dofs, ops, consts, pr, f, Kc, *dg_scratch(ops.shape[0], dN, pr)) == OK
    np.testing.assert_allclose(f, f_ref, rtol=0, atol=1e-12 * np.abs(f_ref).max())
    np.testing.assert_allclose(0.5 * Kc, column_band(K_ref.ab, b), rtol=0, atol=1e-12 * np.abs(K_ref.ab).max())
    dU = model.strain_energy(u1) - model.strain_energy(u0)
    assert (u1 - u0) @ f == pytest.approx(dU, rel=1e-8)


def _dense(ab, b):
    """The symmetric matrix of a LAPACK general band ab (2 b + 1, n)."""
    n = ab.shape[1]
    out = np.zeros((n, n))
    for j in range(n):
        for i in range(max(0, j - b), min(n, j + b + 1)):
            out[i, j] = ab[b + i - j, j]
    return out


@pytest.mark.parametrize("element", ["HB2n-16", "HB2n-40p"])
@pytest.mark.parametrize("law", ["neo-hookean", "mooney-rivlin", "yeoh"])
@pytest.mark.parametrize("form", ["paper", "plane-strain", "plane-stress"])
def test_fused_kernel_and_ldlt_equal_the_reference(element, law, form):
    """Force, tangent (upper band) and energy of the fused kernel equal the model's
    kernel at ue = 0.7 u + 0.3 u_n (with HB2n-40p's pressure field in the penalised
    forms: the band kernel plus ProjectedPenalty); LDL^T on the column band (HB2n-16)
    solves like gbsv and counts the negative pivots (the inertia)."""
    sc = scene(material=paper.material_table(law, form), element=element, n=4)
    model = build_model(plan(sc))
    n, b = model.mesh.n_dof, model.mesh.bandwidth
    rng = np.random.default_rng(3)
    u, un = (1e-4 * rng.standard_normal(n) for _ in range(2))
    u[model.fixed] = un[model.fixed] = 0.0
    f_ref, K_ref = model.internal_force_and_tangent(0.7 * u + 0.3 * un)
    ops, consts = model._tape
    f, Kc = np.empty(n), np.empty((n, b + 1))
    scratch = step_scratch(ops.shape[0], model._dN, model.fused[5])
    args = (model._dN, model._w, model._dofs.astype(np.int64), ops, consts, model.fused[5])
    assert assemble_fused(u, un, 0.3, *args, f, Kc, True, *scratch) == OK
    np.testing.assert_allclose(f, f_ref, rtol=0, atol=1e-12 * np.abs(f_ref).max())
    np.testing.assert_allclose(Kc, column_band(K_ref.ab, b), rtol=0, atol=1e-12 * np.abs(K_ref.ab).max())
    assert strain_energy_fused(u, *args, *scratch) == pytest.approx(model.strain_energy(u), rel=1e-12)
    if element != "HB2n-16":
        return          # the LDL^T checks below are about the factorisation, on HB2n-16's S
    M = model.mass_matrix()
    first = envelope(model._dofs, n)
    S = column_band(0.6 * K_ref.ab + 4e6 * M.ab, b)
    col_constrain(S, model.fixed.astype(np.int64))
    rhs = np.arange(n, dtype=float) % 7
    rhs[model.fixed] = 0.0
    x_ref = Banded(0.6 * K_ref.ab + 4e6 * M.ab, b).constrain(model.fixed).solve(rhs)
    assert col_ldlt(S, first, np.empty((2, n))) == 0
    col_ldlt_solve(S, first, rhs)
    np.testing.assert_allclose(rhs, x_ref, rtol=1e-10, atol=1e-12 * np.abs(x_ref).max())
    S2 = column_band(K_ref.ab + 4e6 * M.ab, b)
    S2[:, b] -= 1e12 * np.abs(S2).max()                       # every free pivot negative
    col_constrain(S2, model.fixed.astype(np.int64))
    assert col_ldlt(S2, first, np.empty((2, n))) == n - len(model.fixed)
    S3 = np.zeros_like(S2)
    S3[:, b] = 1.0
    S3[5, b] = 0.0                                            # singular: the step is rejected
    assert col_ldlt(S3, first, np.empty((2, n))) == -6


@pytest.mark.parametrize("element", ["HB2n-12", "HB3n-12", "HB2n-16"])
def test_mass_matvec_without_the_cross_component_zeros(element):
    """Every element's mass matrix couples only dofs of the same component, so the step
    loop multiplies by it without those zeros: the same product as the whole band; a
    tangent (x-y coupled) is not taken for one."""
    model = build_model(plan(scene(element=element, n=4)))
    n, b = model.mesh.n_dof, model.mesh.bandwidth
    Mc = column_band(model.mass_matrix().ab, b)
    first = envelope(model._dofs, n)
    assert same_component_only(Mc)
    x = np.random.default_rng(5).standard_normal(n)
    y, y_ref = np.empty(n), np.empty(n)
    col_matvec(Mc, first, x, y_ref)
    col_matvec_split(Mc, first, x, y)
    np.testing.assert_allclose(y, y_ref, rtol=1e-14, atol=1e-14 * np.abs(y_ref).max())
    np.testing.assert_allclose(y_ref, model.mass_matrix().matvec(x), rtol=1e-12)
    _, K = model.internal_force_and_tangent(1e-3 * x)
    assert not same_component_only(column_band(K.ab, b))


@pytest.mark.parametrize("law", ["neo-hookean", "mooney-rivlin", "yeoh"])
@pytest.mark.parametrize("form", ["paper", "plane-strain", "plane-stress"])
def test_live_tape_replays_the_same_numbers(law, form):
    """The tape without its dead instructions (the compiled loops' tape) gives W and its
    derivatives of the whole tape to the bit; Yeoh in plane stress loses its unused I2."""
    from ancf.kinematics.section.kernels import live_tape
    from ancf.core.tape import evaluate
    model = build_model(plan(scene(material=paper.material_table(law, form), n=2)))
    ops, consts = model._tape
    lops, lconsts = live_tape(ops, consts)
    assert len(lops) <= len(ops) and lops[-1][0] == ops[-1][0]
    rng = np.random.default_rng(2)
    a = 2.0 + 0.1 * rng.random((3, 4))
    J = 1.0 + 0.05 * rng.random((3, 4))
    np.testing.assert_array_equal(evaluate(lops, lconsts, a, J), evaluate(ops, consts, a, J))
    if law == "yeoh" and form == "plane-stress":
        assert len(lops) == len(ops) - 3


@pytest.mark.parametrize("element", ["HB2n-12", "HB2n-20xyp", "HB2n-40p"])
@pytest.mark.parametrize("form", ["plane-strain", "plane-stress"])
def test_the_initial_force_of_the_loop_equals_the_model(element, form):
    """The initial acceleration's internal force comes from the loop's fused assembly
    (:func:`ancf.solvers.compiled_steps.internal_force`, called by the run's compiled start; no
    numpy kernel in the timed solve): the model's force at a deformed state, pressure field
    included, to round-off; at det F <= 0 it returns INADMISSIBLE (the start then defers to
    the Python route, which names the point: the next test)."""
    from ancf.solvers.compiled_steps import internal_force as fused_force
    sc = scene(material=paper.material_table("yeoh", form), element=element, n=4)
    _, integ = run(sc, max_steps=1)
    model = integ.model
    rng = np.random.default_rng(5)
    u = 1e-4 * rng.standard_normal(model.mesh.n_dof)
    f_ref = model.internal_force(u)
    f = np.empty(u.size)
    assert fused_force(u, *integ._loop.data[:6], f) == OK
    np.testing.assert_allclose(f, f_ref, rtol=0, atol=1e-12 * np.abs(f_ref).max())
    mirrored = np.where(np.arange(u.size) % 2 == 0, -2.0 * model.mesh.reference, 0.0)    # x -> -x: det F = -1
    assert fused_force(mirrored, *integ._loop.data[:6], f) == INADMISSIBLE


@pytest.mark.parametrize("element", sorted(set(ELEMENTS) | {"HB2n-84p"}))
def test_the_loops_start_and_energies_equal_the_python_route(element):
    """A run's start (initial accelerations, :func:`ancf.solvers.compiled_steps.start`: M
    constrained and factorised by LDL^T in compiled code) and the energies of its outputs
    (:meth:`CompiledLoop.energies`) against the Python route they replace (the scaled
    banded LU of :meth:`Integrator.M_constrained` on the same right-hand side, the model's
    strain energy, 1/2 v.Mv), on every registered element and the sextic section
    (generalized masses ~1e-50 of a position dof's): the accelerations agree in the
    Jacobi-scaled unknowns sqrt(M_ii) a_i to the scaled mass matrix's condition number
    times round-off, the energies to round-off; at det F <= 0 the start defers to the
    Python route, which names the point."""
    import examples.sextic_section  # noqa: F401  (registers HB2n-84p)
    from ancf.kinematics.section.model import InadmissibleState
    from ancf.solvers.compiled_steps import internal_force as fused_force
    sc = scene(element=element, n=3, material=paper.material_table("yeoh", "plane-stress"))
    _, integ = run(sc, max_steps=1)
    model, loop = integ.model, integ._loop
    rng = np.random.default_rng(11)
    u = 1e-4 * rng.standard_normal(model.mesh.n_dof)
    u[model.fixed] = 0.0
    v = rng.standard_normal(model.mesh.n_dof)
    a = loop.initial_acceleration(u)
    assert a is not None                                             # the compiled start, not the fallback
    Mc = integ.M_constrained()
    # the same right-hand side (the loop's force equals the model's to round-off: above)
    f = np.empty(u.size)
    assert fused_force(u, *loop.data[:6], f) == OK
    a_ref = Mc.solve(np.where(integ.free, integ.f_ext - f, 0.0))
    s = np.sqrt(np.abs(Mc.to_sparse().diagonal()))
    dense = (Mc.to_sparse().toarray() / s[:, None]) / s[None, :]
    bound = np.linalg.cond(dense) * np.finfo(float).eps * 10
    np.testing.assert_allclose(s * a, s * a_ref, rtol=0, atol=bound * np.abs(s * a_ref).max())
    assert np.all(a[model.fixed] == 0.0)
    kinetic, strain = loop.energies(u, v)
    assert strain == model.strain_energy(u)                          # the same kernel
    assert kinetic == pytest.approx(0.5 * float(v @ integ.M.matvec(v)), rel=1e-13)
    e = integ.energies(integ.initial_state(u))
    assert e.strain == strain and e.kinetic == 0.0
    mirrored = inadmissible_state(model)            # x -> -x: det F = -1 (a cable: a fibre's stretch < 0)
    assert loop.initial_acceleration(mirrored) is None
    with pytest.raises(InadmissibleState):
        integ.initial_state(mirrored)
