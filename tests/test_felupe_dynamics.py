"""The pendulum on FElupe ([fem] backend = "felupe", analysis.kind = "dynamic") through the
one time loop and the one continuum stepper: on the same mesh, degree, quadrature and
integrator as DOLFINx the discrete equations are the same, so the two codes give the same
tip history to the Newton tolerance; energy behaviour of Newmark; the record's keys."""
import dataclasses
import math

import numpy as np
import pytest

from .conftest import tiered

from contract import paper
from contract.scene import scene_from_dict
from studies.verification.continuum_gold import pendulum
from studies.verification.continuum_gold.pendulum import pendulum_dict
from reference_fem.settings import fem_settings
from reference_fem.simulation import run_dynamic, run_scene

pytest.importorskip("felupe")

# The coarse mesh of tests/test_reference_fem_dynamics.py: 35 x 2 Q2 cells, a node at the pin
# and at the tip.
COARSE = {"cells_height": 2, "aspect": 4.0}
# The Newton error of a step is below UTOL = 1e-8 of the state (reference_fem.stepper), a
# few 1e-11 m here, over ten steps; the two codes' histories may differ by that (measured:
# 6e-17 m, the same Newton iterates to round-off).
SAME_M = 1e-9


def _scene(law="yeoh", model="plane-stress", incompressibility=None, backend="felupe", loads=None, **kw):
    fem = {"model": "3d", "cell": "hexahedron", "cells_width": 1, "aspect": 8.0} if model == "3d" else {}
    d = pendulum_dict(law, "plane-strain" if model == "3d" else model, cells_height=COARSE["cells_height"],
                      aspect=COARSE["aspect"], **kw)
    d["fem"].update(fem, backend=backend)
    if incompressibility:
        d["fem"]["incompressibility"] = incompressibility
    if loads:
        d["loads"].update(loads)
    return scene_from_dict(d)


def _strip(rec: dict) -> dict:
    """The record without what may differ between the codes: the version key, the backend
    name, the clocks."""
    out = {k: v for k, v in rec.items() if k not in ("dolfinx", "felupe", "cpu_s", "wall_s", "setup_s")}
    out["fem"] = {k: v for k, v in rec["fem"].items() if k != "backend"}
    return out


@pytest.mark.dolfinx
@pytest.mark.parametrize("law, model, inc, integrator, loads", tiered([
    ("yeoh", "plane-stress", None, "generalized-alpha", None),
    # generalized-alpha: alpha_f != 0, the constraint row at the new state (unsymmetric tangent)
    ("mooney-rivlin", "plane-strain", "mixed", "generalized-alpha", None),
    # the penalty's row at u_(n+1-af), and a dead tip force's potential
    ("neo-hookean", "plane-strain", "penalty", "newmark", {"tip_force": [0.0, -0.02]}),
    # the real beam: 70 x 2 x 1 Q2/Q1 hexahedra, pinned along the line (0, 0, z)
    ("yeoh", "3d", "mixed", "generalized-alpha", None),
], lambda law, model, inc, integrator, loads: model == "3d" or inc == "mixed" or integrator == "newmark",
    "test_same_mesh_same_history_as_dolfinx"))
@pytest.mark.dolfinx
def test_same_mesh_same_history_as_dolfinx(law, model, inc, integrator, loads):
    """35 x 2 Q2 (Q2/Q1) cells, dt = 2 ms, 20 ms (3D: 10 ms): the same steps and Newton
    iterations, the same tip history, centre line and energies, and a record with the same
    keys and values but for the code's name and clocks."""
    kw = dict(t_end=0.01 if model == "3d" else 0.02, dt=2e-3, integrator=integrator, rho_inf=0.8 if integrator != "newmark" else 1.0,
              output_times=[0.0, 0.005, 0.01] + ([] if model == "3d" else [0.02]))
    f = run_scene(_scene(law, model, inc, "felupe", loads, **kw))
    d = run_scene(_scene(law, model, inc, "dolfinx", loads, **kw))
    assert f["status"] == d["status"] == "converged", (f["reason"], d["reason"])
    assert f["fem"]["backend"] == "felupe" and f["felupe"] and "dolfinx" not in f
    a, b = _strip(f), _strip(d)
    assert sorted(a) == sorted(b)
    for k in ("steps", "rejected_steps", "newton_iterations", "ndof", "effects", "pin", "integrator",
              "fem", "continuum_model", "incompressibility", "energy_limit", "status"):
        assert a[k] == b[k], k
    for p, q in zip(f["tip_history"], d["tip_history"]):
        assert p["t"] == q["t"] and math.hypot(p["x"] - q["x"], p["y"] - q["y"]) <= SAME_M, (p, q)
    for p, q in zip(f["configurations"], d["configurations"]):
        assert np.abs(np.array([p["x"], p["y"]]) - np.array([q["x"], q["y"]])).max() <= SAME_M
    scale = max(abs(e["gravity"]) for e in d["energy"])
    for p, q in zip(f["energy"], d["energy"]):
        assert sorted(p) == sorted(q)
        for k in p:
            assert p[k] == pytest.approx(q[k], rel=0, abs=1e-9 * scale), (k, p, q)
    # early on the beam falls almost freely (and the tip force bends it further down)
    t = f["tip_history"][-1]["t"]
    assert f["tip_history"][-1]["y"] <= -0.5 * 9.81 * t ** 2 * 0.95


@pytest.mark.parametrize("model, t_end", [pytest.param("plane-stress", 0.1, marks=pytest.mark.slow(
    guard="test_newmark_conserves_energy_to_second_order")), ("plane-strain", 0.05)])
def test_newmark_conserves_energy_to_second_order(model, t_end):
    """FElupe alone (no DOLFINx): Newmark (no numerical dissipation) keeps |E(t) - E(0)|
    below the issue's bound 1e-3 m g L / 2 at every step, with the motion releasing
    far more than it, and the drift shrinks like dt^2: halving dt divides it by 2.5 to 6
    (4 for second order; measured 4.0 in both models, as on DOLFINx). Plane strain is
    the exactly incompressible mixed model."""
    drifts = []
    for dt in (2e-3, 1e-3):
        scene = _scene("yeoh", model, t_end=t_end, dt=dt, integrator="newmark", rho_inf=1.0)
        rec = run_dynamic(scene, fem_settings(scene), energy_every_step=True)
        assert rec["status"] == "converged", rec["reason"]
        e = np.array([x["total"] for x in rec["energy_steps"]])
        assert len(e) == rec["steps"] + 1
        assert -rec["energy"][-1]["gravity"] > 50 * pendulum.energy_bound("yeoh")
        for x in rec["energy_steps"]:
            assert x["total"] == pytest.approx(x["kinetic"] + x["strain"] + x["gravity"], abs=1e-15)
        drifts.append(np.abs(e - e[0]).max())
        assert drifts[-1] <= pendulum.energy_bound("yeoh")
    assert 2.5 < drifts[0] / drifts[1] < 6, drifts


def test_output_holds_the_final_state_and_the_pin(tmp_path):
    """generalized-alpha (rho_inf = 0.8, the gold's) on FElupe: the energy stays within the
    issue's bound (measured 3e-9 J against 4.5e-5 J); --output writes the final state:
    the pin node stays at the origin, the tip node carries the record's tip."""
    import meshio

    scene = _scene("yeoh", "plane-stress", t_end=0.02, dt=2e-3)
    rec = run_scene(scene, output=tmp_path)
    assert rec["status"] == "converged", rec["reason"]
    assert all(abs(e["total"] - rec["energy"][0]["total"]) <= pendulum.energy_bound("yeoh") for e in rec["energy"])
    out = meshio.read(rec["output"])
    pts, u = out.points[:, :2], out.point_data["displacement"]
    pin = int(np.argmin(np.linalg.norm(pts, axis=1)))
    tip = int(np.argmin(np.linalg.norm(pts - [scene.beam.length, 0.0], axis=1)))
    assert np.abs(u[pin]).max() == 0.0
    assert np.allclose(u[tip], [rec["tip"]["ux"], rec["tip"]["uy"]], rtol=0, atol=1e-15)


@pytest.mark.parametrize("model, n", [("plane-strain", 3), ("plane-stress", 2), ("3d", 3)])
@pytest.mark.parametrize("law", ["neo-hookean", "mooney-rivlin", "yeoh", "gent"])
def test_chain_rule_derivatives_are_tensortraxs(law, model, n):
    """The material's closed-form chain rule through (I1, I2, J) gives tensortrax's
    gradient and hessian of W(F) (with the mixed term w_J (J - 1)) to round-off (measured
    1e-15 relative), at random gradients with J > 0.2."""
    import tensortrax as tr
    import tensortrax.math as tm

    from mechanics.laws import get_law
    from reference_fem.felupe_backend.laws import strain_energy

    L = get_law(law)
    c = dict(L.example or paper.materials()[law])
    W = strain_energy(L, model, c)
    rng = np.random.default_rng(7)
    F = np.eye(n)[:, :, None, None] + 0.2 * rng.standard_normal((n, n, 4, 6))
    if model == "plane-strain":
        F[2, :], F[:, 2], F[2, 2] = 0.0, 0.0, 1.0
    J = np.linalg.det(np.moveaxis(F, (0, 1), (-2, -1)))
    F = np.where(J > 0.2, F, np.eye(n)[:, :, None, None])
    w_J = 0.3 * L.shear_modulus(c)
    ref = (lambda F: W(F) + w_J * (tm.linalg.det(F) - 1.0))
    for mine, theirs in ((W.gradient(F, w_J), tr.gradient(ref, ntrax=2)(F)),
                         (W.hessian(F, w_J), tr.hessian(ref, ntrax=2)(F))):
        assert np.abs(mine - theirs).max() <= 1e-12 * np.abs(theirs).max()
