"""The example element with a sextic section (examples/sextic_section.py, HB2n-84p): its
declared rules pass the rank tests, the cheaper ones fail; and in plane stress its plateau
is below HB2n-60p's (quartic section) and below 0.01 % of the converged continuum, which the
quartic section cannot reach (README "An element for incompressible rubber"); in penalised
plane strain its error against the incompressible continuum falls as the penalty stiffens
(with the richer pressure {1..x^3} x {1..y^4} it grew)."""
import pytest
import json
import math
from pathlib import Path

import examples.sextic_section  # noqa: F401  (registers HB2n-84p)
from ancf.simulation import run_scene
from contract import paper
from contract.scene import scene_from_dict

ELEMENT = "HB2n-84p"
GOLD = json.loads((Path(__file__).parent / "gold" / "fem_cantilever.json").read_text())["cases"]


@pytest.mark.slow(guard="test_the_pendulum_starts")
def test_the_declared_rules_pass_the_rank_tests_and_the_cheaper_ones_fail():
    from ancf.checks.rank import rank_test, strain_test

    def ok(rule, aspect):
        return rank_test(ELEMENT, rule, aspect)["passes"] and strain_test(ELEMENT, rule, aspect)["passes"]
    assert ok((6, 7), 1.0) and not ok((6, 6), 1.0)
    assert ok((6, 7), 0.05) and not ok((6, 7), 0.025) and ok((6, 8), 0.01)


def _tip_error(rec: dict, ref: dict) -> float:
    assert rec["status"] == "converged", rec["reason"]
    return math.hypot(rec["tip"]["ux"] - ref["ux"], rec["tip"]["uy"] - ref["uy"]) / math.hypot(ref["ux"], ref["uy"])


def _plane_stress_error(element: str, n: int) -> float:
    """Relative tip distance, Yeoh, plane stress, default rule, from the continuum's
    committed Richardson value (tests/gold: its estimate 0.006 % of the tip)."""
    d = paper.cantilever_scene("yeoh", "plane-stress", element, n)
    d["ancf"].pop("quadrature")
    rec, _ = run_scene(scene_from_dict(d))
    return _tip_error(rec, GOLD["yeoh/plane-stress"]["tip"])


@pytest.mark.slow(guard="test_the_pendulum_starts")
def test_the_sextic_section_lowers_the_plane_stress_plateau_below_a_hundredth_of_a_percent():
    """At 256 elements both elements are converged along the beam (HB2n-60p moves by 1e-9 m
    from 256 to 512); measured: HB2n-60p 0.0106 %, HB2n-84p 0.0047 %."""
    quartic, sextic = _plane_stress_error("HB2n-60p", 256), _plane_stress_error(ELEMENT, 256)
    assert sextic < 1e-4 < quartic


def _plane_strain_error(n: int, k: float) -> float:
    """Relative tip distance, Yeoh, plane strain with the penalty k C10, default rule, from
    the exactly incompressible continuum's committed Richardson value (estimate 0.0004 %)."""
    d = paper.cantilever_scene("yeoh", "plane-strain", ELEMENT, n, penalty=k * paper.materials()["yeoh"]["C10"])
    d["ancf"].pop("quadrature")
    rec, _ = run_scene(scene_from_dict(d))
    return _tip_error(rec, GOLD["yeoh/plane-strain"]["tip"])


@pytest.mark.slow(guard="test_the_pendulum_starts")
def test_the_plane_strain_error_falls_as_the_penalty_stiffens():
    """The stiff end of the card's sweep (64 elements): from k = 1e4 to 1e5 C10 the
    penalty's own softness (about 0.010 % and 0.001 % of the tip, Yeoh) leaves, and the error
    must fall to the element's own, below 0.01 %. Measured: 0.0153 -> 0.0055 % (the element's
    own +0.0042 % at both k). With the pressure {1..x^3} x {1..y^4} it grew, 0.0118 ->
    0.0215 %: that element is 0.022 % too stiff at 64 elements (at every k from 1e3), which
    the penalty's softness hid at 1e4."""
    e4, e5 = _plane_strain_error(64, 1e4), _plane_strain_error(64, 1e5)
    assert e5 < e4 and e5 < 1e-4


def _pendulum(n: int, t_end: float) -> dict:
    from studies.common.pendulum_cases import pendulum_dict
    return pendulum_dict(ELEMENT, n, "plane-stress", 5e-4, t_end=t_end)


def test_the_initial_acceleration_is_solved_in_the_mass_matrix_own_scale():
    """The sextic coordinates' generalized masses span ~50 orders of magnitude (r_yyyyyy's
    ~h^12 against r's): an unscaled LU solve of M a0 = Q - f_int(u0) left a residual 8e5
    times the load in Jacobi-scaled units (|a0| ~ 2e34; the pendulum then failed at t = 0
    with det F <= 0 on every mesh). Checked here in those units, D^-1/2 (M a0 - r) against
    D^-1/2 r, D = diag M: a solve that respects the scaling leaves round-off."""
    import numpy as np
    from ancf.build import build_integrator, build_model, external_loads, plan
    scene = scene_from_dict(_pendulum(8, 0.01))
    p = plan(scene)
    model = build_model(p)
    M = model.mass_matrix()
    integ = build_integrator(p, model, M, external_loads(model, p))
    u0 = np.zeros(model.mesh.n_dof)
    a0 = integ.initial_state(u0).a
    free = integ.free
    r = np.where(free, integ.f_ext - model.internal_force(u0), 0.0)
    s = 1.0 / np.sqrt(np.abs(M.ab[M.b]))
    res = np.where(free, M.matvec(a0) - r, 0.0)
    assert np.all(np.isfinite(a0))
    assert np.linalg.norm(s * res) <= 1e-10 * np.linalg.norm(s * r)


def test_the_pendulum_starts():
    """Its first 10 ms at 8 elements: converged, no step rejected (before the scaled solve:
    failed at t = 0, step below dt_min)."""
    rec, _ = run_scene(scene_from_dict(_pendulum(8, 0.01)))
    assert rec["status"] == "converged", rec["reason"]
    assert rec["rejected_steps"] == 0
