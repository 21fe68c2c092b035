"""The element report card, tiny grid, for a user's element registered from its own
module: the command runs the module in every worker, and the card states the checks'
verdicts and the runs' numbers from records."""
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SECTIONS = ["## 1. Contract checks", "## 2. Rank tests", "## 3. Conformity", "## 4. Static convergence",
            "## 5. Locking", "## 6. Pendulum", "## 7. Cost", "## 8. Stability"]


def test_a_user_elements_card_regenerates_from_its_records(tmp_path):
    cmd = [sys.executable, "-m", "studies", "card", "HB2n-20", "--import", "examples.transversely_cubic",
           "--tiny", "--out", str(tmp_path), "--no-progress", "--workers", "2"]
    run = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-3000:]
    card = (tmp_path / "cards" / "HB2n-20.md").read_text()
    for s in SECTIONS:
        assert s in card
    # the transversely cubic element conforms (its trace on x = const is its node's alone)
    # and passes every check; all its static runs converge to stable equilibria
    assert "Consistency checks: all pass; patch test: passes; conforming: True" in card
    recs = [json.loads(line) for line in (tmp_path / "data" / "card-HB2n-20.jsonl").read_text().splitlines()]
    assert recs and all(r["status"] == "converged" for r in recs)
    assert all(r["case"]["options"]["imports"] == ["examples.transversely_cubic"] for r in recs)
    static = [r for r in recs if r["scene"]["analysis"]["kind"] == "static"]
    assert f"stable: {len(static)}, unstable: 0" in card
    assert (tmp_path / "cards" / "HB2n-20-rank.png").exists() and (tmp_path / "cards" / "HB2n-20-cost.png").exists()
    # a second run reuses every record and renders the same card
    again = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0 and f"{len(recs)} reused, 0 computed" in again.stdout
    assert (tmp_path / "cards" / "HB2n-20.md").read_text() == card


def test_an_unknown_element_is_refused_with_the_list(tmp_path):
    run = subprocess.run([sys.executable, "-m", "studies", "card", "HB9n-99", "--tiny", "--out", str(tmp_path)],
                         cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert run.returncode == 2 and "HB2n-12" in run.stderr
