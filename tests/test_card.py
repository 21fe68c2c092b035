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
    assert "### Shear locking" in card and "No shear locking" in card


def test_an_unknown_element_is_refused_with_the_list(tmp_path):
    run = subprocess.run([sys.executable, "-m", "studies", "card", "HB9n-99", "--tiny", "--out", str(tmp_path)],
                         cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert run.returncode == 2 and "HB2n-12" in run.stderr


def _probe(element: str, ratio: float, n: int) -> dict:
    from ancf.simulation import run_scene
    from contract.scene import scene_from_dict
    from studies.card import slender_scene

    d = slender_scene(element, ratio, n)
    rec, _ = run_scene(scene_from_dict(d))
    rec["case"] = {"name": d["name"]}
    return rec


def test_the_shear_locking_verdict_and_its_signature():
    """The card's verdict (error growth with L/h at fixed n) against a second route: a
    locking element's error is a function of l_e / h alone (equal at equal l_e / h), a
    locking-free one's of n alone; LB2n-12's error does not fall under refinement."""
    from studies.card_report import shear_locking

    hb12 = [_probe("HB2n-12", r, n) for r, n in ((35, 8), (140, 8), (70, 16), (140, 32))]
    v = shear_locking(hb12)
    assert v["locks"]
    e = v["rows"]
    assert abs(e[16][70] - e[32][140]) < 0.01 * abs(e[32][140]) and abs(e[32][140]) > 0.05   # l_e/h = 0.3125
    hb16 = [_probe("HB2n-16", r, n) for r, n in ((35, 8), (140, 8), (35, 16))]
    v = shear_locking(hb16)
    assert not v["locks"] and v["converges"]
    assert abs(v["rows"][8][35] - v["rows"][8][140]) < 0.02 * abs(v["rows"][8][35])
    lb = shear_locking([_probe("LB2n-12", 35, n) for n in (16, 32)])
    assert not lb["converges"] and abs(lb["rows"][32][35] + 0.25) < 0.005     # 1 - (1 - nu^2), nu = 1/2
