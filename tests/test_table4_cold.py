"""Table 4's cold start (solver ancf-cold): the first run after installing, in a fresh process
with an empty numba cache. Its cases are a study of their own (table4-cold, in `make
study-full`: each compiles the loops), none in tiny mode, and Table 4's step ladder holds none."""
from __future__ import annotations

import json

import pytest

from studies.engine.catalog import load_catalog
from studies.engine.solvers import get_solver
from studies.paper.table4_cold import COLD


def test_one_cold_case_per_element_in_the_full_grid_none_in_tiny():
    catalog = load_catalog(tiny=False)
    full = catalog["table4-cold"]
    cold = full.cases()
    assert all(c.solver == COLD for c in cold) and full.full and not full.in_all
    assert sorted(json.loads(c.scene_json)["ancf"]["element"] for c in cold) == sorted(full.grid["elements"])
    assert all(c.timing == {"repeats": 1, "budget_s": 0.0} for c in cold)      # run serially, twice
    assert not load_catalog(tiny=True)["table4-cold"].cases()
    assert not [c for c in catalog["table4"].cases() if c.solver == COLD]


@pytest.mark.slow(guard="test_one_cold_case_per_element_in_the_full_grid_none_in_tiny")
def test_a_cold_run_returns_the_solvers_record_and_its_process_times():
    """About 17 s: the solver's own record, with the process's times beside it (measured,
    never compared here)."""
    from studies.common.pendulum_cases import pendulum_dict

    rec = get_solver(COLD).run(pendulum_dict("HB2n-12", 4, "plane-stress", 1e-3, rho_inf=0.5, t_end=0.05))
    assert rec["status"] == "converged"
    assert rec["cold"]["process_s"] > 0 and rec["cold"]["import_build_solve_s"] > 0 and rec["wall_s"] > 0
    assert rec["tip_history"] and rec["solver"] == "ancf"
