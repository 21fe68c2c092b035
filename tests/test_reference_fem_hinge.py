"""The hinge support (``supports.left = "hinge"``, contract.loads) in the continuum reference:
the left face kept straight through its fixed centre, u(0, Y) = Y a for one free vector a,
eliminated exactly in both backends (DOLFINx: u = T w_r with the face slaved to its top
node, T^T K T by MatPtAP; FElupe: T onto (free dofs, a) by scipy.sparse), statics and
dynamics. Unlike the point pin (a singular support in the 2D continuum, whose pendulum
has no mesh limit), the hinge has one: the hinged pendulum converges under refinement.
"""
import math

import numpy as np
import pytest

from contract.errors import SceneError
from contract.scene import scene_from_dict
from reference_fem.convergence import richardson
from studies.verification.continuum_gold.pendulum import pendulum_dict

pytestmark = pytest.mark.dolfinx

C10 = 0.5e6            # Pa, neo-Hookean
L, H, W = 0.1, 0.01, 0.02


def _tension(backend: str, cells_height: int, P: float):
    return scene_from_dict({
        "name": "hinged-tension", "beam": {"length": L, "height": H, "width": W},
        "material": {"law": "neo-hookean", "formulation": "plane-stress", "density": 1000.0, "C10": C10},
        "supports": {"left": "hinge"}, "loads": {"tip_force": [P * H * W, 0.0]},
        "analysis": {"kind": "static", "load_steps": 4, "newton_rtol": 1e-10},
        "fem": {"cells_height": cells_height, "cells_length": 4, "backend": backend}})


def _model(scene):
    from reference_fem.settings import fem_settings
    from reference_fem.simulation import backend

    return backend(scene.fem["backend"]).static_model(scene, fem_settings(scene))


@pytest.mark.parametrize("backend", ["dolfinx", "felupe"])
@pytest.mark.parametrize("cells_height", [1, 2, 3])
def test_hinged_strip_in_tension_is_homogeneous_uniaxial_tension(backend, cells_height):
    """A tip traction P = 0.5 MPa along x on the hinged plane-stress strip (4 x n Q2 cells; 1
    and 3 cells across have no node at the face centre, which the hinge does not need): the
    hinge lets the face contract uniformly, so the state is homogeneous uniaxial tension,
    lambda from :func:`studies.verification.closed_forms.uniaxial_stretch` and lambda_2 = lambda^(-1/2).
    The homogeneous field is in Q2 and its discrete residual vanishes at every quadrature
    point, so the FE state equals it to Newton's tolerance (rtol 1e-10 on the residual: a
    stretch error ~1e-10; allowed 1e-8, as tests/test_reference_fem_tension.py). (The
    rigid turn about the centre is a zero-stiffness mode at the stress-free start; the load
    does no work on it and Newton's first solve leaves it at round-off.) The face: its
    centre fixed, its corners moved by (0, +-(lambda_2 - 1) h / 2); the record's ndof is
    the unknowns less the face's displacements plus a's two, and its pin note names the hinge."""
    from reference_fem.simulation import run_scene
    from studies.verification.closed_forms import uniaxial_stretch

    P = 0.5e6
    lam = uniaxial_stretch("neo-hookean", {"C10": C10}, "plane-stress", P)
    rec = run_scene(_tension(backend, cells_height, P))
    assert rec["status"] == "converged", rec["reason"]
    assert 1.0 + rec["tip"]["ux"] / L == pytest.approx(lam, rel=1e-8)
    assert abs(rec["tip"]["uy"]) <= 1e-8 * H
    model = _model(_tension(backend, cells_height, P))
    from reference_fem.statics import solve_static

    assert solve_static(model.system, model.set_load, 4, 1e-10, 25).status == "converged"
    lam2 = lam ** -0.5
    for point, want in [((0.0, H / 2), (0.0, (lam2 - 1) * H / 2)), ((0.0, -H / 2), (0.0, -(lam2 - 1) * H / 2)),
                        ((L, H / 2), ((lam - 1) * L, (lam2 - 1) * H / 2))]:
        np.testing.assert_allclose(model.displacement(np.array(point)), want, rtol=0, atol=1e-8 * L)
    nodes = (4 * 2 + 1) * (2 * cells_height + 1)
    assert rec["ndof"] == 2 * nodes - 2 * (2 * cells_height + 1) + 2
    assert rec["pin"].startswith("hinge")


def _pendulum(backend: str, left: str, cells_height: int, t_end: float = 0.1, dt: float = 5e-3):
    """The paper's Yeoh plane-stress pendulum (L = 350 mm, h = 5 mm) on ``left``, cells of
    aspect 2, a short run at a coarse fixed step."""
    d = pendulum_dict("yeoh", "plane-stress", dt=dt, cells_height=cells_height, aspect=2.0, t_end=t_end,
                      output_times=[0.0, t_end])
    d["supports"] = {"left": left}
    d["fem"]["backend"] = backend
    return scene_from_dict(d)


@pytest.mark.parametrize("backend", ["dolfinx", "felupe"])
def test_the_hinged_face_stays_straight_through_its_centre_while_it_turns(backend):
    """After 50 ms of the hinged pendulum (70 x 2 cells, dt = 5 ms) the left face's
    displacement is Y a at any Y (nodes and between them): u(0, Y) - (Y / (h/2)) u(0, h/2)
    vanishes to round-off (1e-12 of h; measured 1e-16), the centre stays at the origin, the
    face has turned with the falling beam (its top corner moves along +x: measured a =
    (0.2297, -0.0270), a turn of 0.23 rad) and changed its height, which the hinge leaves free
    (|e_y + a| = 0.99975: a turn-only constraint would hold it at 1; asked to differ by 1e-6)."""
    from mechanics.time_loop import integrate
    from reference_fem.settings import fem_settings
    from reference_fem.simulation import backend as backend_of
    from reference_fem.stepper import ContinuumStepper

    scene = _pendulum(backend, "hinge", 2, t_end=0.05)
    prob = backend_of(backend).dynamic_model(scene, fem_settings(scene))
    res = integrate(ContinuumStepper(prob, beam=scene.beam), np.zeros(prob.n_dof), 0.05, 5e-3, [0.05])
    assert res.status == "converged"
    h = scene.beam.height
    Y = np.array([-0.5, -0.37, -0.25, 0.0, 0.1, 0.25, 0.5]) * h
    pts = np.column_stack([np.zeros_like(Y), Y])
    u = prob.positions(res.final.u, pts) - pts
    a = u[-1] / (h / 2)
    assert np.abs(u - Y[:, None] * a).max() <= 1e-12 * h
    assert np.abs(u[3]).max() <= 1e-12 * h
    assert u[-1, 0] > 1e-7
    assert abs(math.hypot(a[0], 1.0 + a[1]) - 1.0) > 1e-6


def test_hinged_pendulum_has_the_same_history_in_both_codes():
    """Same mesh (70 x 2 Q2), step and integrator: the same discrete equations, so the same
    steps, iterations and tip history to the Newton tolerance (UTOL 1e-8 of the state per
    step: allowed 1e-9 m, as tests/test_felupe_dynamics.py); the records' ndof and pin note."""
    from reference_fem.simulation import run_scene

    a, b = (run_scene(_pendulum(k, "hinge", 2, t_end=0.05)) for k in ("dolfinx", "felupe"))
    assert a["status"] == b["status"] == "converged"
    for k in ("steps", "newton_iterations", "ndof", "pin"):
        assert a[k] == b[k], k
    assert a["pin"].startswith("hinge")
    for p, q in zip(a["tip_history"], b["tip_history"]):
        assert p["t"] == q["t"] and math.hypot(p["x"] - q["x"], p["y"] - q["y"]) <= 1e-9


def _tips(left: str, levels) -> list[tuple[float, float]]:
    from reference_fem.simulation import run_scene

    out = []
    for n in levels:
        rec = run_scene(_pendulum("dolfinx", left, n))
        assert rec["status"] == "converged", rec["reason"]
        out.append((rec["tip_history"][-1]["x"], rec["tip_history"][-1]["y"]))
    return out


@pytest.mark.slow(guard="test_hinged_pendulum_has_the_same_history_in_both_codes")
def test_hinged_pendulum_converges_under_refinement_and_the_pinned_one_does_not():
    """The pendulum's tip at t = 0.1 s (dt = 5 ms fixed: the same time discretisation at every
    level, so the levels differ by the mesh only) on three meshes of cells halved each time.
    Hinge, 1, 2, 4 cells across: successive differences fall at least as the element's
    order, 2^2 = 4 per halving (measured: 3.1e-6, 2.2e-7 m, a factor 14.3: order 3.84, the
    tip's superconvergence; a fourth level, 8 across, differs by 1.35e-8, factor 16.0;
    Richardson value (0.33897350, -0.05015590) m, estimated error of the 4-across tip
    7e-8 m at the trusted order 2). Point pin, 2, 4, 8 across: the tip moves by the same
    3.4e-6 m at each halving (its logarithmic singularity: no mesh limit): the factor is
    below 1.5 (measured 0.99), and its last difference is more than 10 times the hinge's
    (measured 16 times)."""
    hinge = _tips("hinge", (1, 2, 4))
    r = richardson(*hinge)
    assert r.order is not None and r.order >= 2.0, r
    d = [math.dist(p, q) for p, q in zip(hinge, hinge[1:])]
    pin = _tips("pin", (2, 4, 8))
    dp = [math.dist(p, q) for p, q in zip(pin, pin[1:])]
    assert dp[0] / dp[1] < 1.5, dp
    assert dp[1] > 10 * d[1]


@pytest.mark.parametrize("backend", ["dolfinx", "felupe"])
def test_a_3d_hinge_is_refused_by_name(backend):
    from reference_fem.simulation import run_scene

    d = pendulum_dict("yeoh", "plane-strain", cells_height=2, aspect=8.0, t_end=0.01)
    d["supports"] = {"left": "hinge"}
    d["fem"].update(model="3d", cell="hexahedron", cells_width=1, backend=backend)
    with pytest.raises(SceneError, match=r"supports\.left: \"hinge\" is not offered by the 3D continuum model"):
        run_scene(scene_from_dict(d))


def test_the_hinge_with_the_iterative_solver_is_refused_by_name():
    d = _tension("dolfinx", 2, 1e5).to_dict()
    d["fem"]["linear_solver"] = "iterative"
    with pytest.raises(SceneError, match=r"fem\.linear_solver: \"iterative\" with supports\.left = \"hinge\""):
        _model(scene_from_dict(d))
