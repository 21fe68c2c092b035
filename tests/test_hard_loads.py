"""The hard-load sweep (the full tier, ``make test-full``): the cantilever under a tip force up to 200 N
and gravity up to 1000 g, every law and element, ANCF and the continuum. Every run ends
with a status (a failure names its reason; every run is bounded by wall_time, so none
hangs), and where both models converge the higher-order elements agree with the
continuum as at the paper's load."""
from __future__ import annotations

import pytest

from studies.engine.catalog import load_catalog
from studies.verification.hard_loads import rows_of
from studies.engine.pipeline import run_studies
from studies.engine.report import Context

from .conftest import LOCK_FREE


# The formulation study puts the converged plane-stress ANCF elements within 0.5 % of the
# continuum at 1 g; at 32 elements / 64 x 4 cells the discretisation adds about as much.
AGREE = 0.01


@pytest.fixture(scope="module")
def rows(tmp_path_factory):
    out = tmp_path_factory.mktemp("hard-loads")
    run_studies(["hard-loads"], out, executor="pool", progress=False, log=lambda *a: None)
    catalog = load_catalog()
    return rows_of(Context(catalog["hard-loads"], out, catalog)), catalog["hard-loads"].grid


@pytest.mark.slow(guard="test_hostile.py::test_loads_that_looped_end_with_a_status_in_bounded_time")
def test_every_run_ends_with_a_status_and_a_reason_when_failed(rows):
    rows, grid = rows
    n = len(grid["formulations"]) * len(grid["laws"]) * len(grid["elements"]) * (
        len(grid["gravity_factors"]) + len(grid["tip_forces"]) + len(grid["end_moment_turns"]))
    assert len(rows) == n
    for x in rows:
        for r in (x["ancf"], x["continuum"]):
            assert r is not None and r["status"] in ("converged", "failed")
            assert r["status"] == "converged" or r["reason"], r["scene"]["name"]
            assert r["status"] != "converged" or r["tip"] is not None


@pytest.mark.slow(guard="test_hostile.py::test_the_20_newton_tip_force_agrees_with_the_continuum")
def test_where_both_converge_the_higher_order_elements_agree_with_the_continuum(rows):
    """Plane stress: every higher-order element under gravity and the end load. Plane strain
    (the paper's penalty): the lock-free elements only; the paper's elements lock there
    (HB2n-16 ~10 % off, the locking verdict of the formulation and card studies), which is not
    this claim. The end moment (constant curvature, up to a full turn): the lock-free elements
    in both formulations; the paper's are shown, not claimed (HB3n-12 at 32 elements bends
    6 % off there, beyond its 4 % at the paper's load)."""
    rows, grid = rows
    hard = [x for x in rows if x["distance"] is not None and x["element"] not in grid["low_order"]
            and not (x["kind"] == "gravity" and x["size"] == 1.0)
            and (x["formulation"] == "plane-stress" or x["element"] in LOCK_FREE)
            and (x["kind"] != "end_moment" or x["element"] in LOCK_FREE)]
    assert {x["kind"] for x in hard} == {"gravity", "tip_force", "end_moment"}
    assert {x["formulation"] for x in hard} == {"plane-stress", "plane-strain"}
    bad = [(x["law"], x["formulation"], x["element"], x["load"], x["distance"]) for x in hard if x["distance"] > AGREE]
    assert not bad, bad
