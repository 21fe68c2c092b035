"""Reports print what their records say: Table 4's warm-up column shows a millisecond warm-up
as its value, not 0.00; the hard-load table says where a distance lies within the continuum
reference's own error bar. No solver runs."""
from __future__ import annotations

import math

import pytest


def test_table4_prints_a_small_warm_up_time_with_its_digits():
    from studies.paper import table4

    rung = {"ndof": 52, "dt": 1e-3, "steps": 500, "newton": 998, "verdict": "converged",
            "timing": {"median_s": 0.0104, "warmup_s": 0.0023456}}
    sel = [{"formulation": "plane-stress", "element": "HB2n-12", "n": 8, "rung": rung, "diff": 5e-5,
            "rungs": [rung], "smallest": 1e-3}]
    rows, _ = table4._rows(sel, {("HB2n-12", 8): 1293.55})
    t = table4.table(rows)
    col = t.header.index("warm-up s (a two-element copy)")
    cell = t.markdown().splitlines()[2].split(" | ")[col]
    assert float(cell) == pytest.approx(0.0023456, rel=0.03)      # two significant digits
    assert t.cell(col, 1.234) == "1.2"                              # and a slow one (code loaded) as well


@pytest.mark.parametrize("compare", ["both", "uy"])
def test_a_hard_load_distance_within_the_references_error_bar_is_flagged(compare):
    from studies.verification.hard_loads import UNRESOLVED, _flagged, error_bar, resolution

    ref = {"tip": (-0.15, -0.2), "error": 2e-4, "compare": compare}    # m: the Richardson estimate
    bar = error_bar(ref)
    assert bar == pytest.approx(2e-4 / (0.2 if compare == "uy" else math.hypot(0.15, 0.2)))
    small, large = 0.5 * bar, 20.0 * bar
    assert resolution(small, bar) == UNRESOLVED
    assert resolution(large, bar) == "20 x the bar"
    assert "below the reference's error bar" in _flagged({"distance": small, "error_bar": bar})
    assert "below" not in _flagged({"distance": large, "error_bar": bar})
    assert resolution(small, error_bar({**ref, "error": None})) == "no error bar (one mesh)"
    assert resolution(None, bar) == ""
