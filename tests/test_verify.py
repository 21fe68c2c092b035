"""`python -m studies verify`: committed records recomputed with today's code and compared
field by field; a record the code no longer reproduces is named with its field."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

from studies.engine.scheduler import run_cases
from studies.engine.store import store_for
from studies.engine.verify import compare, verify
from studies.common.grid import cantilever_case

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    out = tmp_path_factory.mktemp("verify")
    cases = [cantilever_case("t", "yeoh", "plane-stress", "HB3n-12", n, (3, 2), "face") for n in (2, 3)]
    cases.append(cantilever_case("t", "yeoh", "plane-stress", "HB3n-12", 4, (3, 2), "face",
                                 {"timing": {"repeats": 1, "budget_s": 0.1}}))
    run_cases("t", cases, store_for(out, "t"), executor="serial", progress=False)
    return out, {"t": {c.id: c for c in cases}}


def test_records_of_todays_code_reproduce(out):
    out, cases = out
    res = verify(out, sample=3, seed=1, log=lambda s: None, cases=cases)
    assert res.ok and len(res.checked) == 3 and res.candidates == 3 and res.stale == 0


# in the full tier (about 3 s); today's records reproducing keeps the comparison in the quick one
@pytest.mark.slow(guard="test_records_of_todays_code_reproduce")
def test_a_record_the_code_does_not_reproduce_is_named_with_its_field(out, tmp_path):
    out, cases = out
    data = tmp_path / "data"
    data.mkdir()
    recs = [json.loads(x) for x in (out / "data" / "t.jsonl").read_text().splitlines()]
    recs[0]["tip"]["uy"] *= 1.0 + 1e-6             # beyond 10 x newton_rtol (1e-8)
    recs[1]["newton_iterations"] += 1 + recs[1]["load_steps"] + recs[1]["relax_steps"]   # beyond one per solve
    (data / "t.jsonl").write_text("".join(json.dumps(r) + "\n" for r in recs))
    res = verify(tmp_path, sample=3, seed=1, log=lambda s: None, cases=cases)
    assert not res.ok and len(res.problems) == 2
    assert any(recs[0]["case"]["name"] in p and "tip.uy" in p for p in res.problems)
    assert any(recs[1]["case"]["name"] in p and "newton_iterations" in p for p in res.problems)


def test_timings_and_round_off_are_not_mismatches():
    path = {"newton_iterations": 50, "load_steps": 8, "relax_steps": 1, "lowest_eigenvalue": 2.6384e-13}
    assert compare(path, {**path, "newton_iterations": 41, "lowest_eigenvalue": 2.6387e-13}, 1e-7) == []
    assert compare(path, {**path, "newton_iterations": 40}, 1e-7)
    assert compare(path, {**path, "lowest_eigenvalue": -2.6384e-13}, 1e-7)
    a = {"tip": {"ux": 1.0, "uy": -2.0}, "wall_s": 1.0, "timing": {"median_s": 3.0},
         "tip_history": [{"t": 0.0, "x": 1.0, "y": 0.0}, {"t": 0.1, "x": 0.5, "y": -0.8}]}
    b = {"tip": {"ux": 1.0 + 1e-12, "uy": -2.0}, "wall_s": 9.0, "timing": {"median_s": 1.0},
         "tip_history": [{"t": 0.0, "x": 1.0, "y": 1e-13}, {"t": 0.1, "x": 0.5, "y": -0.8}]}
    assert compare(a, b, 1e-7) == []
    assert compare({"tip": {"ux": 0.1, "uy": -0.2}, "tip_uz": -8.5e-17}, {"tip": {"ux": 0.1, "uy": -0.2},
                   "tip_uz": 6.6e-17}, 1e-7) == []           # zero by symmetry: at the tip's scale
    b["tip_history"][1]["y"] = -0.9
    assert compare(a, b, 1e-7) == ["tip_history.1.y: -0.8 -> -0.9 (|diff| 0.1 > 1e-07 x 1)"]


def test_an_energy_is_compared_above_its_round_off_floor():
    """The slender probe's potential energy (1.46e-10 J, the linear regime) moved by
    1.1e-16 J between two processes: round-off of energies computed from I1 - 3."""
    from studies.design.card import slender_scene
    from studies.engine.verify import energy_floor
    rec = {"scene": slender_scene("HB2n-12", 35.0, 8), "potential_energy": -1.4584609850303182e-10}
    floor = energy_floor(rec)
    assert 1e-15 < floor < 1e-11
    moved = {**rec, "potential_energy": -1.4584621121961868e-10}
    assert compare(rec, moved, 1e-7, floor=floor) == []
    assert compare(rec, {**rec, "potential_energy": -1.47e-10}, 1e-7, floor=floor)   # 1.2e-12 J


@pytest.mark.parametrize("args, says", [
    (["--sample", "0"], "--sample: must be a whole number > 0, got '0'"),
    (["--sample", "x"], "--sample: must be a whole number > 0, got 'x'"),
    (["--sample", "2", "--budget", "-1"], "--budget: must be a number > 0, got '-1'"),
    ([], "the following arguments are required: --sample"),
])
def test_bad_arguments_are_one_clear_line(args, says):
    p = subprocess.run([sys.executable, "-m", "studies", "verify", *args], cwd=ROOT, capture_output=True, text=True)
    assert p.returncode == 2 and says in p.stderr and len(p.stderr.strip().splitlines()) <= 2
