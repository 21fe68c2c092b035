"""The study runner: reuse, --force, failure records, interruption safety, serial timings,
and a run through mpiexec (mpi4py.futures)."""
from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from studies.engine import solvers
from studies.engine.case import make_case
from studies.common.grid import cantilever_case
from studies.engine.scheduler import dry_run, run_cases
from studies.engine.store import RecordStore

ROOT = Path(__file__).resolve().parent.parent
PY = sys.executable


def small_cases(study="t", counts=(2, 3, 4), **kw):
    return [cantilever_case(study, "yeoh", "plane-stress", "HB3n-12", n, (3, 2), "face", **kw) for n in counts]


@pytest.fixture
def fake_solver(monkeypatch):
    """Register a solver "fake" whose behaviour a test sets: fake.behaviour(scene) -> record."""
    class Fake:
        calls = 0

        def behaviour(self, scene):
            raise AssertionError("set behaviour")

    fake = Fake()

    def run(scene):
        fake.calls += 1
        return fake.behaviour(scene)

    monkeypatch.setitem(solvers.SOLVERS, "fake", solvers.Solver("fake", run, lambda scene: None))
    return fake


def test_second_run_reuses_every_record_and_a_changed_case_alone_runs(tmp_path):
    store = RecordStore(tmp_path / "t.jsonl")
    cases = small_cases()
    first = run_cases("t", cases, store, executor="pool", progress=False)
    assert (first.computed, first.reused, first.failed) == (3, 0, 0)
    recs = store.read()
    assert {c.id for c in cases} == set(recs)
    assert all(r["status"] == "converged" and r["run"]["executor"] == "pool" for r in recs.values())
    assert all(r["pid"] != os.getpid() for r in recs.values())  # ran in pool workers
    before = store.path.read_text()
    second = run_cases("t", cases, store, executor="pool", progress=False)
    assert (second.computed, second.reused) == (0, 3)
    assert store.path.read_text() == before
    changed = small_cases(counts=(2, 3, 5))
    dry = dry_run("t", changed, store)
    assert (dry.cases, dry.computed, dry.reused) == (3, 1, 2)
    assert store.path.read_text() == before                      # a dry run writes nothing
    assert dry_run("t", changed, store, force=True).computed == 3
    third = run_cases("t", changed, store, executor="serial", progress=False)
    assert (third.computed, third.reused) == (1, 2)
    assert set(store.read()) == {c.id for c in changed}  # compacted to the current list


def test_force_recomputes_and_keeps_one_record_per_case(tmp_path):
    store = RecordStore(tmp_path / "t.jsonl")
    cases = small_cases(counts=(2, 3))
    run_cases("t", cases, store, executor="serial", progress=False)
    old = {k: r["elapsed_s"] for k, r in store.read().items()}
    s = run_cases("t", cases, store, executor="serial", force=True, progress=False)
    assert (s.computed, s.reused) == (2, 0)
    lines = store.path.read_text().splitlines()
    assert len(lines) == 2
    new = {json.loads(x)["case_id"]: json.loads(x)["elapsed_s"] for x in lines}
    assert new.keys() == old.keys() and new != old


def test_case_id_changes_with_scene_options_and_solver_source(monkeypatch):
    a, b = small_cases(counts=(2, 3))
    assert a.id != b.id and a.id == small_cases(counts=(2,))[0].id
    timed = small_cases(counts=(2,), options={"timing": {"repeats": 1}})[0]
    assert timed.id != a.id
    from studies.engine import case as case_mod
    before = a.id
    case_mod._memo_id.cache_clear()
    monkeypatch.setattr(case_mod, "solver_fingerprint", lambda *a: {"code": "other source", "packages": {}})
    assert small_cases(counts=(2,))[0].id != before
    assert a.id == before and a.sources_changed()     # a made case keeps the id it was made with
    monkeypatch.undo()
    case_mod._memo_id.cache_clear()
    assert small_cases(counts=(2,))[0].id == before and not a.sources_changed()


def test_a_source_edit_during_a_run_loses_no_record_and_the_next_run_redoes_them(tmp_path, monkeypatch):
    """Records carry the id their case was made with (not one a worker re-derives from
    edited sources, which compaction used to delete); what ran on changed sources is kept
    but marked transient, so the next run recomputes it."""
    from studies.engine import case as case_mod
    store = RecordStore(tmp_path / "t.jsonl")
    cases = small_cases(counts=(2, 3))
    monkeypatch.setattr(case_mod, "solver_fingerprint", lambda *a: {"code": "edited while running", "packages": {}})
    s = run_cases("t", cases, store, executor="serial", progress=False)
    recs = store.read()
    assert s.computed == 2 and set(recs) == {c.id for c in cases}
    assert all(r["transient"] and "changed" in r["note"] for r in recs.values())
    monkeypatch.undo()
    again = run_cases("t", cases, store, executor="serial", progress=False)
    assert (again.computed, again.reused) == (2, 0)
    assert not any(r.get("transient") for r in store.read().values())


def test_unknown_solver_names_the_valid_ones():
    with pytest.raises(ValueError, match="solver: unknown value 'abaqus'; allowed: 'ancf', 'ancf-cold', 'ancf-effects', ") as e:
        make_case("t", "abaqus", small_cases()[0].scene)
    assert "'continuum'" in str(e.value)


def test_a_raising_case_is_recorded_as_failed_and_the_others_finish(tmp_path, fake_solver):
    scene = small_cases()[0].scene
    good = small_cases(counts=(2, 3))
    bad = make_case("t", "fake", scene)

    def boom(scene):
        raise FloatingPointError("tangent exploded at step 3")

    fake_solver.behaviour = boom
    store = RecordStore(tmp_path / "t.jsonl")
    s = run_cases("t", [good[0], bad, good[1]], store, executor="serial", progress=False)
    assert (s.computed, s.failed) == (3, 1)
    rec = store.read()[bad.id]
    assert rec["status"] == "failed" and rec["case_id"] == bad.id
    assert "FloatingPointError: tangent exploded at step 3" in rec["reason"]
    assert rec["tip"] is None
    assert all(store.read()[c.id]["status"] == "converged" for c in good)
    # a failure is a result: the rerun reuses it
    assert run_cases("t", [bad], store, executor="serial", progress=False).computed == 0


def test_a_non_finite_result_is_stored_as_failed_never_as_nan(tmp_path, fake_solver):
    from contract.record import new_record

    def nan_tip(scene):
        rec = new_record("fake", scene)
        rec.update(status="converged", reason=None, tip={"ux": float("nan"), "uy": -0.1})
        return rec

    fake_solver.behaviour = nan_tip
    case = make_case("t", "fake", small_cases()[0].scene)
    store = RecordStore(tmp_path / "t.jsonl")
    run_cases("t", [case], store, executor="serial", progress=False)
    text = store.path.read_text()
    assert "NaN" not in text
    rec = json.loads(text)
    assert rec["status"] == "failed" and rec["tip"]["ux"] is None and "non-finite" in rec["reason"]


def test_an_interrupted_run_keeps_finished_records_and_the_rerun_does_the_rest(tmp_path, fake_solver):
    from contract.record import new_record

    cases = [make_case("t", "fake", {**small_cases()[0].scene, "name": f"c{i}"}) for i in range(5)]

    def interrupt_third(scene):
        if scene["name"] == "c2":
            raise KeyboardInterrupt
        rec = new_record("fake", scene)
        rec.update(status="converged", reason=None, tip={"ux": 0.0, "uy": -1.0})
        return rec

    fake_solver.behaviour = interrupt_third
    store = RecordStore(tmp_path / "t.jsonl")
    with pytest.raises(KeyboardInterrupt):
        run_cases("t", cases, store, executor="serial", progress=False)
    assert set(store.read()) == {cases[0].id, cases[1].id}
    fake_solver.behaviour = lambda scene: interrupt_third({**scene, "name": "ok"})
    fake_solver.calls = 0
    s = run_cases("t", cases, store, executor="serial", progress=False)
    assert (s.reused, s.computed, fake_solver.calls) == (2, 3, 3)


def test_a_torn_last_line_is_skipped_and_does_not_swallow_the_next_record(tmp_path):
    store = RecordStore(tmp_path / "t.jsonl")
    cases = small_cases(counts=(2, 3))
    run_cases("t", cases[:1], store, executor="serial", progress=False)
    with open(store.path, "a") as f:
        f.write('{"case_id": "x", "status": "conv')  # a writer killed mid-line
    assert len(store.read()) == 1 and store.skipped_lines == 1
    run_cases("t", cases, store, executor="serial", progress=False)
    assert set(store.read()) == {c.id for c in cases}


def _catalog(tmp_path: Path, counts=(2, 3, 4, 6, 8, 12)) -> Path:
    p = tmp_path / "cases.toml"
    p.write_text(f"""
[table3]
module = "paper.table3"
laws = ["yeoh", "neo-hookean"]
elements = ["HB3n-12", "HB2n-12"]
formulations = ["plane-stress", "paper", "plane-strain"]
counts = {{ HB3n-12 = {counts[0]}, HB2n-12 = {counts[1]} }}
settings = {{ paper = {{ quadrature = [2, 2], clamp = "all" }}, plane-strain = {{ quadrature = [3, 2], clamp = "face" }}, plane-stress = {{ quadrature = [3, 2], clamp = "face" }} }}
""")
    return p


@pytest.mark.slow(guard="test_runner_faults.py::test_kill_9_of_the_runner_takes_its_workers_and_the_resource_tracker_with_it")
def test_a_killed_run_loses_no_finished_record(tmp_path):
    """SIGKILL the whole run (main process and pool workers) once records exist; every
    line on disk is whole or skipped, and the rerun computes only what is missing."""
    cat, out = _catalog(tmp_path, counts=(40, 40)), tmp_path / "out"
    data = out / "data" / "table3.jsonl"
    cmd = [PY, "-m", "studies", "run", "table3", "--catalog", str(cat), "--out", str(out), "--no-progress"]
    p = subprocess.Popen(cmd, cwd=ROOT, start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    t0 = time.time()
    while time.time() - t0 < 60 and (not data.exists() or len(data.read_text().splitlines()) < 2):
        time.sleep(0.05)
    os.killpg(p.pid, signal.SIGKILL)
    p.wait()
    store = RecordStore(data)
    have = store.read()
    assert 2 <= len(have) < 12, "the run was to be killed half way"
    assert all(r["status"] == "converged" for r in have.values())
    from studies.engine.catalog import load_catalog
    from studies.engine.scheduler import run_cases as rerun
    cases = load_catalog(path=cat)["table3"].cases()
    s = rerun("table3", cases, store, executor="serial", progress=False)
    assert (s.reused, s.computed) == (len(have), 12 - len(have))


def test_timed_cases_run_serially_in_this_process_after_a_warm_up(tmp_path):
    store = RecordStore(tmp_path / "t.jsonl")
    timed = small_cases(counts=(2,), options={"timing": {"repeats": 3, "budget_s": 10.0}})
    plain = small_cases(counts=(3,))
    run_cases("t", timed + plain, store, executor="pool", progress=False)
    recs = store.read()
    t, p = recs[timed[0].id], recs[plain[0].id]
    assert t["pid"] == os.getpid() and t["run"]["executor"] == "serial-timed"
    assert p["pid"] != os.getpid()
    tm = t["timing"]
    assert tm["repeats"] == 3 and len(tm["samples_s"]) == 3 and tm["warmup_s"] > 0
    assert tm["median_s"] == sorted(tm["samples_s"])[1]
    assert "timing" not in p


@pytest.mark.slow(guard="test_reference_fem_3d.py::test_two_ranks_give_the_one_rank_tip_and_one_record")
@pytest.mark.mpi
@pytest.mark.skipif(shutil.which("mpiexec") is None, reason="mpiexec not installed")
def test_a_tiny_study_runs_through_mpiexec(tmp_path):
    cat, out = _catalog(tmp_path), tmp_path / "out"
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMP_NUM_THREADS="1")
    cmd = ["mpiexec", "-n", "2", "--oversubscribe", PY, "-m", "mpi4py.futures", "-m", "studies", "run", "table3",
           "--catalog", str(cat), "--out", str(out), "--executor", "mpi", "--no-progress"]
    r = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    recs = RecordStore(out / "data" / "table3.jsonl").read()
    assert len(recs) == 12
    assert all(x["status"] == "converged" and x["run"]["executor"] == "mpi" for x in recs.values())
    assert (out / "table3.md").exists() and (out / "README.md").exists()


def test_a_run_beyond_the_time_limit_is_stopped_and_recorded(tmp_path, fake_solver):
    def forever(scene):
        while True:
            time.sleep(0.01)

    fake_solver.behaviour = forever
    case = make_case("t", "fake", small_cases()[0].scene)
    store = RecordStore(tmp_path / "t.jsonl")
    t0 = time.perf_counter()
    s = run_cases("t", [case], store, executor="serial", progress=False, timeout_s=0.3)
    assert time.perf_counter() - t0 < 5 and s.failed == 1
    rec = store.read()[case.id]
    assert rec["status"] == "failed" and rec["timed_out"] and "timeout" in rec["reason"]
    # reused under the same limit; rerun under a longer one (and then it finishes)
    assert run_cases("t", [case], store, executor="serial", progress=False, timeout_s=0.3).computed == 0
    from contract.record import new_record

    def quick(scene):
        rec = new_record("fake", scene)
        rec.update(status="converged", reason=None, tip={"ux": -0.01, "uy": -0.1})
        return rec
    fake_solver.behaviour = quick
    s = run_cases("t", [case], store, executor="serial", progress=False, timeout_s=30.0)
    assert s.computed == 1 and store.read()[case.id]["status"] == "converged"


def test_a_user_element_is_identified_by_its_specification(tmp_path, monkeypatch):
    """A user's element is part of what a record depends on: edit its specification and
    the case is a new one (the study reruns it) rather than a stale record reused; edit
    the module elsewhere, or import another module beside it, and the records stand."""
    import sys
    from ancf import elements
    from studies.engine import case as case_mod

    def register(rule: str, comment: str) -> None:
        (tmp_path / "my_user_element.py").write_text(
            f"# {comment}\nfrom ancf.elements import ElementSpec, register_element, rules\n"
            "register_element(ElementSpec('HB2n-user', ('1', 'x', 'y', 'x*y', 'x^2', 'x^3'), (0.0, 1.0), "
            f"('r', 'r_x', 'r_y'), quadrature=rules((0.0, {rule}))))\n")
        elements.ELEMENTS.pop("HB2n-user", None)
        sys.modules.pop("my_user_element", None)
        __import__("my_user_element")

    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setattr(elements, "ELEMENTS", elements.ELEMENTS.copy())
    scene = small_cases()[0].scene
    scene["ancf"]["element"] = "HB2n-user"
    ident = lambda opts: case_mod._fresh_id("ancf", json.dumps(scene), json.dumps(opts))
    register("(3, 2)", "first")
    a = ident({"imports": ["my_user_element"]})
    assert ident({"imports": ["my_user_element", "examples.cubic_slope"]}) == a   # an unrelated import
    register("(3, 2)", "an edit of a comment")
    assert ident({"imports": ["my_user_element"]}) == a
    register("(4, 2)", "an edit of the default rule")
    assert ident({"imports": ["my_user_element"]}) != a
    sys.modules.pop("my_user_element", None)


def test_a_user_law_is_identified_by_the_code_of_its_module(tmp_path, monkeypatch):
    """A user's law is code: an edit of its energy recomputes, a comment does not."""
    import sys
    from mechanics import laws
    from studies.engine import case as case_mod
    from studies.engine import fingerprint as fp

    def register(energy: str, comment: str) -> None:
        (tmp_path / "my_user_law.py").write_text(
            f"# {comment}\nfrom mechanics.laws import MATH, Law, register_law\n"
            f"register_law(Law('law-user', ('C10',), lambda I1, I2, c, m=MATH: {energy}))\n")
        laws.LAWS.pop("law-user", None)
        sys.modules.pop("my_user_law", None)
        fp.clear_caches()
        __import__("my_user_law")

    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setattr(laws, "LAWS", laws.LAWS.copy())
    scene = small_cases()[0].scene
    scene["material"] = {"law": "law-user", "formulation": "plane-stress", "density": 2150.0, "C10": 0.5e6}
    ident = lambda: case_mod._fresh_id("ancf", json.dumps(scene), json.dumps({"imports": ["my_user_law"]}))
    register("c['C10'] * (I1 - 3.0)", "first")
    a = ident()
    register("c['C10'] * (I1 - 3.0)", "a comment edited")
    assert ident() == a
    register("c['C10'] * (I1 - 3.0) * 1.01", "the energy edited")
    assert ident() != a
    sys.modules.pop("my_user_law", None)
    fp.clear_caches()
