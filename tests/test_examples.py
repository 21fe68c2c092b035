"""The example element the harness found (examples/cubic_slope.py, HB2n-20xy: HB2n-16 with
r_xy, a cubic cross-section field r_y): it passes the contract checks, and it removes the
coarse-mesh bending stiffness that keeps 8 HB2n-16 elements 2 % off on the pendulum."""
import pytest
import numpy as np

import examples.cubic_slope  # noqa: F401  (registers HB2n-20xy)
from ancf.checks import element as checks
from ancf.simulation import run_scene
from contract.scene import scene_from_dict
from studies.peers.work_precision import error
from studies.common.pendulum_cases import pendulum_dict

ELEMENT = "HB2n-20xy"


def test_the_example_element_passes_the_contract_checks():
    rng = np.random.default_rng(0)
    assert checks.nodality(ELEMENT)["passes"] and checks.reference_state(ELEMENT)["passes"]
    assert checks.mass(ELEMENT)["passes"] and checks.patch(ELEMENT)["passes"]
    assert checks.conformity(ELEMENT)["conforming"]
    for form in ("plane-stress", "plane-strain", "paper"):
        model = checks.small_model(ELEMENT, formulation=form)
        for check in (checks.energy_gradient, checks.tangent_gradient, checks.rigid_motion):
            assert check(model, rng)["passes"], (form, check.__name__)


def test_eight_elements_reach_a_tenth_of_a_percent_on_the_pendulum():
    """Measured: 0.03 % of L for HB2n-20xy against 2.0 % for HB2n-16, 8 elements each (the
    continuum gold's own error estimate is up to 0.025 % of L, so 0.1 % is the bound a
    converged model must meet)."""
    errs = {}
    for el in (ELEMENT, "HB2n-16"):
        rec, _ = run_scene(scene_from_dict(pendulum_dict(el, 8, "plane-stress", 1.25e-3, rho_inf=0.5)))
        assert rec["status"] == "converged"
        errs[el] = error(rec["tip_history"])
    assert errs[ELEMENT] < 1e-3 < 1e-2 < errs["HB2n-16"]


@pytest.mark.slow(guard="test_rank.py::test_each_declared_default_passes_the_u0_test_where_it_is_declared")
def test_the_declared_rules_pass_the_rank_tests_and_the_cheaper_ones_fail():
    from ancf.checks.rank import rank_test, strain_test

    def ok(rule, aspect):
        return rank_test(ELEMENT, rule, aspect)["passes"] and strain_test(ELEMENT, rule, aspect)["passes"]
    assert all(ok((4, 2), a) for a in (10.0, 3.0, 1.0)) and not ok((3, 2), 10.0)
    assert all(ok((3, 3), a) for a in (0.9, 0.3, 0.1, 0.01)) and not ok((4, 2), 0.5) and not ok((3, 2), 0.3)
