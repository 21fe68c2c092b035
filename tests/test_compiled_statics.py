"""The compiled static Newton (ancf.solvers.compiled_statics) against the Python loop it replaces
(ancf.solvers.statics.newton_reference): the same iterations, residuals and state, for every
registered element, the three formulations, with and without the line search; the
fallback to the pivoted LU when the unpivoted LDL^T meets a zero pivot."""
import numpy as np
import pytest

from ancf.solvers import compiled_statics
from ancf.build import build_model, external_loads, plan
from ancf.checks.element import runs
from ancf.elements import ELEMENTS
from ancf.solvers.statics import newton, newton_reference
from contract import paper
from contract.scene import scene_from_dict

from .conftest import contract_rule


def problem(element, form, law="mooney-rivlin", n=8, quadrature="contract"):
    quadrature = contract_rule(element) if quadrature == "contract" else quadrature
    s = scene_from_dict(paper.cantilever_scene(law, form, element, n, quadrature=quadrature, clamp="all"))
    p = plan(s)
    model = build_model(p)
    f = sum(external_loads(model, p).values())
    scale = np.linalg.norm(np.delete(f, model.fixed))
    return model, f, 1e-8 * scale


def reference_relaxed(model, atol):
    """The unloaded equilibrium (the `paper` form is not stress-free at u = 0)."""
    f0 = model.internal_force(np.zeros(model.mesh.n_dof))
    f0[model.fixed] = 0.0
    if np.linalg.norm(f0) <= atol:
        return np.zeros(model.mesh.n_dof)
    res = newton_reference(model, np.zeros(model.mesh.n_dof), np.zeros_like(f0), atol, 25)
    assert res.converged
    return res.u


@pytest.mark.parametrize("element,form", [(el, f) for f in ["paper", "plane-strain", "plane-stress"]
                                          for el in sorted(ELEMENTS) if runs(el, f)])
@pytest.mark.parametrize("line_search", [False, True])
@pytest.mark.parametrize("fraction", [0.03, 0.3])
def test_compiled_newton_is_the_reference_iteration(element, form, line_search, fraction):
    """From the unloaded equilibrium to a fraction of gravity in one increment: the same
    outcome (converged, or the same reason), the same iteration count, and when
    converged the same residual history (each residual to 1e-6 of the first, or 1e3
    atol near the end, where round-off of the different factorisations shows: LDL^T
    without pivoting against LAPACK's pivoted LU, and the fused assembly's summation
    order; or 1e-5 of the largest residual so far: an iterate's round-off grows with the
    tangent's condition, and HB2n-60p's Jacobi-scaled tangent reaches 1.3e7, 30 times the
    other elements', measured 3e-6 of it along an 11-iteration path, where the others
    differ by nothing above 1e3 atol) and the same state to 1e-9 of its size (measured:
    6e-12 at most). At 30 % most increments fail (diverging, or no convergence with the
    line search): the failures must be the same too."""
    model, f, atol = problem(element, form)
    u0 = reference_relaxed(model, atol)
    target = fraction * f
    ref = newton_reference(model, u0, target, atol, 25, line_search=line_search)
    out = newton(model, u0, target, atol, 25, line_search=line_search)
    assert model.compiled       # (HB2n-40p penalised: its pressure field runs compiled too)
    assert (out.converged, out.reason, out.iterations) == (ref.converged, ref.reason, ref.iterations)
    if ref.converged:
        assert len(out.residuals) == len(ref.residuals)
        tol = np.maximum(np.maximum(1e-6 * ref.residuals[0], 1e3 * atol), 1e-5 * np.maximum.accumulate(ref.residuals))
        assert np.all(np.abs(np.array(out.residuals) - ref.residuals) <= tol)
        # as displacement fields (m) at a grid of points: the nodal coordinates' units
        # differ (r in m, r_yyyy in 1/m^3), and an element's highest kinds are set by
        # Newton only to its round-off (HB2n-40p: r_xyyyy to 2e-9 of its size)
        m = model.mesh
        N, _ = m.element.tabulate(*np.meshgrid(np.linspace(0, 1, 5), np.linspace(-0.5, 0.5, 5)),
                                  m.element_length, m.height)
        field = lambda u: np.einsum("pa,eai->epi", N, u[m.element_dofs])
        assert np.abs(field(out.u - ref.u)).max() <= 1e-9 * np.abs(field(ref.u)).max()


def test_line_search_is_taken_where_the_full_step_overshoots():
    """The comparison above must see the line search scale steps, or it would not test
    it: HB2n-16 `paper` at 3 % of gravity converges in 5 plain iterations and in 19
    searched ones, the same in both loops."""
    model, f, atol = problem("HB2n-16", "paper")
    u0 = reference_relaxed(model, atol)
    plain = newton_reference(model, u0, 0.03 * f, atol, 25)
    searched = newton_reference(model, u0, 0.03 * f, atol, 25, line_search=True)
    out = newton(model, u0, 0.03 * f, atol, 25, line_search=True)
    assert plain.converged and searched.converged and searched.iterations > plain.iterations
    assert out.converged and out.iterations == searched.iterations
    assert np.abs(out.u - searched.u).max() <= 1e-9 * np.abs(searched.u).max()


def test_zero_pivot_falls_back_to_the_pivoted_lu(monkeypatch):
    """An attempt whose LDL^T meets a zero pivot is redone by the reference loop, which
    decides: the result is the reference's."""
    model, f, atol = problem("HB2n-12", "plane-stress")
    calls = []

    def unpivoted(self, u0, target, atol, max_iterations, utol, line_search=False):
        calls.append(1)
        return compiled_statics.UNPIVOTED, np.full_like(u0, np.nan), 1, [1.0]
    monkeypatch.setattr(compiled_statics.StaticKernel, "newton", unpivoted)
    u0 = np.zeros(model.mesh.n_dof)
    out = newton(model, u0, 0.03 * f, atol, 25)
    ref = newton_reference(model, u0, 0.03 * f, atol, 25)
    assert calls and out.converged and out.iterations == ref.iterations
    assert np.array_equal(out.u, ref.u)


def test_failures_name_their_reason():
    """No convergence within max_iterations is reported as such, never as converged."""
    model, f, atol = problem("HB2n-12", "plane-stress")
    out = newton(model, np.zeros(model.mesh.n_dof), f, atol * 1e-30, 2)
    ref = newton_reference(model, np.zeros(model.mesh.n_dof), f, atol * 1e-30, 2)
    assert not out.converged and out.reason == ref.reason == "no convergence within max_iterations"


def test_residual_tolerance_respects_the_roundoff_floor():
    """A slender cantilever under a linear-regime load (L/h = 70, the card's shear-locking
    probe): rtol |f_ext| (9e-15 N) lies below the force's round-off. The residual of
    converged Newton iterates stalls between 0.01 and ROUNDOFF_FLOOR times the estimate
    eps |f_int|_terms (measured 0.2 to 1.1), so the floor neither accepts an unconverged
    state (a floor 100 times the stall) nor leaves the tolerance unreachable; with it the
    whole load path converges (without it, the compiled loop's increments stalled and
    the path failed)."""
    from ancf.solvers.statics import ROUNDOFF_FLOOR, solve_static
    from studies.design.card import slender_scene
    s = scene_from_dict(slender_scene("HB2n-12", 70, 8))
    p = plan(s)
    model = build_model(p)
    f = sum(external_loads(model, p).values())
    u0 = np.zeros(model.mesh.n_dof)
    floor = model.static_kernel.roundoff_floor(u0)
    free = np.ones(len(f), bool)
    free[model.fixed] = False
    assert 1e-8 * np.linalg.norm(f[free]) < floor
    for loop in (newton, newton_reference):
        tail = loop(model, u0, f, 0.0, 12, utol=-1.0).residuals[-4:]   # no correction stop
        assert 0.01 * floor < min(tail) and max(tail) < ROUNDOFF_FLOOR * floor
    res = solve_static(model, f)
    assert res.status == "converged" and res.newton_iterations < 30


@pytest.mark.parametrize("element,form", [("HB2n-12", "plane-stress"), ("HB2n-40p", "plane-strain")])
def test_roundoff_floor_numpy_branch_equals_the_compiled_one(element, form, monkeypatch):
    """BeamModel.roundoff_floor's numpy branch (a model the compiled loops cannot run) and
    the compiled one agree, with and without an element pressure field."""
    from ancf.kinematics.section.model import BeamModel
    model, f, _ = problem(element, form)
    u = 1e-3 * np.sin(np.arange(model.mesh.n_dof))
    u[model.fixed] = 0.0
    compiled = model.roundoff_floor(u)
    monkeypatch.setattr(BeamModel, "compiled", property(lambda self: False))
    assert model.roundoff_floor(u) == pytest.approx(compiled, rel=1e-10)


def test_slender_path_converges_above_the_floor(monkeypatch):
    """HB2n-20 (examples/transversely_cubic.py) on the same probe: with the floor the
    path converges in a few iterations; without it (ROUNDOFF_FLOOR = 0) the compiled
    loop's increments stall at the round-off and the path fails (the card's 7 slender
    cells failed so before the floor)."""
    import examples.transversely_cubic  # noqa: F401 (registers HB2n-20)
    from ancf.solvers import statics
    from studies.design.card import slender_scene
    s = scene_from_dict(slender_scene("HB2n-20", 70, 8))
    p = plan(s)
    model = build_model(p)
    f = sum(external_loads(model, p).values())
    res = statics.solve_static(model, f)
    assert res.status == "converged" and res.newton_iterations < 30
    monkeypatch.setattr(statics, "ROUNDOFF_FLOOR", 0.0)
    assert statics.solve_static(build_model(p), f).status == "failed"
