"""The study grids ask each element only for what it runs.

An element with a pressure field refuses a rule that cannot resolve it (a SceneError from
:func:`ancf.build.check`); a grid lists the rules such an element takes under
``per_element`` (:func:`studies.common.grid.takes`). Here every ANCF case of every study, full
and tiny, passes the same check a run starts with."""
from __future__ import annotations

import json

import pytest

from ancf.build import check
from contract.scene import scene_from_dict
from studies.engine.catalog import load_catalog
from studies.common.grid import counts_of, takes

from .conftest import tiered


# the full grids' cases (about 5 s to expand) in the full tier, the tiny grids' in the quick one
@pytest.mark.parametrize("tiny", tiered([False, True], lambda tiny: not tiny,
                                        "test_every_ancf_case_of_every_study_passes_the_solvers_check"),
                         ids=["full", "tiny"])
def test_every_ancf_case_of_every_study_passes_the_solvers_check(tiny):
    n = 0
    for study in load_catalog(tiny=tiny).values():
        for case in study.cases():
            if case.solver == "ancf":
                check(scene_from_dict(json.loads(case.scene_json)))
                n += 1
    assert n > 100


def test_per_element_rules_and_counts_select_cases():
    grid = {"counts": [4, 8], "per_element": {"HB2n-12": {"quadratures": ["default"], "counts": [4]}}}
    assert takes(grid, "HB2n-12", "default") and not takes(grid, "HB2n-12", [2, 2])
    assert takes(grid, "HB3n-12", [2, 2])
    assert counts_of(grid, "HB2n-12") == [4] and counts_of(grid, "HB3n-12") == [4, 8]


def test_an_element_with_a_pressure_field_takes_its_own_rule_only():
    """[2, 2] cannot resolve a pressure field: the grid asks the element, not a list of names;
    a grid's per_element rules still decide where it gives them."""
    assert takes({}, "HB2n-40p", "default") and not takes({}, "HB2n-40p", [2, 2])
    assert takes({}, "HB2n-20xyp", "default") and not takes({}, "HB2n-20xyp", [3, 2])
    assert takes({"per_element": {"HB2n-40p": {"quadratures": [[6, 5]]}}}, "HB2n-40p", [6, 5])


def test_a_fixed_rule_a_pressure_element_refuses_is_a_scene_error():
    from contract.paper import cantilever_scene
    from contract.scene import SceneError
    with pytest.raises(SceneError, match="ancf.quadrature"):
        check(scene_from_dict(cantilever_scene("yeoh", "plane-strain", "HB2n-40p", 8, quadrature=(2, 2))))


def test_a_check_runs_no_rank_test_and_a_run_records_them(monkeypatch):
    """A study's check of an ANCF case (ancf.build.capacity, through its plan) runs no rank
    test of a rule the scene chose: half a second each, for thousands of cases. A run asks
    the plan for them and records them as warnings."""
    from ancf import build
    from ancf.checks import rank
    from contract.paper import cantilever_scene
    from studies.engine.solvers import get_solver

    ours = get_solver("ancf", "studies.solvers").check
    fixed = cantilever_scene("neo-hookean", "plane-stress", "HB2n-12", 8, quadrature=(3, 3))  # a strain test
    with monkeypatch.context() as m:
        m.setattr(rank, "_strain_test", lambda *a: pytest.fail("a rank test ran in the check"))
        ours(fixed)
        plan = build.plan(scene_from_dict(fixed))
    spurious = build.plan(scene_from_dict(cantilever_scene("neo-hookean", "plane-stress", "HB2n-12", 8,
                                                           quadrature=(2, 1))))
    assert plan.rule_warnings == () and "spurious zero-energy" in spurious.warnings[0]
