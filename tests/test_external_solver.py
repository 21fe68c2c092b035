"""Any solver through the harness (:mod:`studies.external`): a stub solver that answers, one
that crashes, one that hangs past its wall time and ones that write no record, not JSON,
NaN or a record with a bad key; each case ends with a status and a reason, never as a
result. The record checker names the bad key; a declaration's error names its key; the
solver's fingerprint follows its declaration, version and adapter, not their comments."""
from __future__ import annotations

import json
import sys
import textwrap
import time

import pytest

from contract import paper
from contract.errors import SceneError
from contract.record import KEYS, new_record
from contract.record_schema import problems, read
from studies.engine.case import make_case
from studies.engine.solvers import SOLVERS
from studies.engine.worker import execute
from studies.external.declaration import load_declaration, unsupported
from studies.external.protocol import ExternalSolver, register_external, retarget


STUB = '''
"""A stub solver: reads the scene, writes a record; its behaviour set by its argv."""
import json, math, sys, time, tomllib
mode, scene_path, out = sys.argv[1], sys.argv[2], sys.argv[3]
scene = tomllib.loads(open(scene_path).read())
rec = {"schema": "ancf-harness/record/1", "solver": "stub", "status": "converged", "reason": None,
       "tip": {"ux": 0.0, "uy": -1e-3 * scene["beam"]["length"]}, "ndof": 12, "newton_iterations": 3,
       "load_steps": 1, "rejected_steps": 0, "stable": True, "cpu_s": 0.01, "wall_s": 0.01, "setup_s": 0.0,
       "effects": ["elastic", "gravity"], "scene": scene, "stub_own_key": 7}
if mode == "crash":
    print("boom: the stub fell over", file=sys.stderr); sys.exit(3)
if mode == "hang":
    time.sleep(60)
if mode == "none":
    sys.exit(0)
if mode == "notjson":
    open(out, "w").write("{not json"); sys.exit(0)
if mode == "nan":
    open(out, "w").write(json.dumps(rec).replace('"ux": 0.0', '"ux": NaN')); sys.exit(0)
if mode == "badkey":
    rec["tip"] = {"ux": "left", "uy": 0.0}; del rec["ndof"]
open(out, "w").write(json.dumps(rec))
'''


def declare(tmp_path, mode: str = "ok", name: str = "stub", wall: float = 20.0, supports: str = "",
            extra: str = "") -> str:
    (tmp_path / "stub.py").write_text(STUB)
    path = tmp_path / f"{name}-{mode}.toml"
    path.write_text(textwrap.dedent(f'''
        [solver]
        name = "{name}-{mode}"
        version = "0.1"
        command = [{json.dumps(sys.executable)}, "-S", "./stub.py", "{mode}", "{{scene}}", "{{out}}"]
        adapter = ["stub.py"]
        wall_time = {wall}
        {extra}
        [supports]
        analysis = ["static"]
        {supports}
    '''))
    return str(path)


@pytest.fixture
def solvers():
    """Registers external solvers for one test and forgets the external ones after it (a
    study imported meanwhile keeps the solvers it registers)."""
    before = set(SOLVERS)
    yield register_external
    for name in set(SOLVERS) - before:
        if isinstance(SOLVERS[name], ExternalSolver):
            del SOLVERS[name]


def scene() -> dict:
    return paper.cantilever_scene("yeoh", "plane-stress", "HB2n-12", 2)


def run(solver, d: dict | None = None) -> dict:
    return execute(make_case("external-test", solver.name, d or scene()))


def test_a_solver_that_answers_gives_its_record_with_the_harness_keys(tmp_path, solvers):
    s = solvers(declare(tmp_path))
    rec = run(s)
    assert rec["status"] == "converged" and not problems(rec)
    assert rec["solver"] == "stub-ok" and rec["scene"]["name"] == scene()["name"] and rec["stub_own_key"] == 7
    assert rec["tip"]["uy"] == pytest.approx(-1e-3 * scene()["beam"]["length"])


@pytest.mark.parametrize("mode,says", [
    ("crash", "exited with status 3: boom: the stub fell over"),
    ("none", "record: no file"),
    ("notjson", "record: not JSON"),
    ("nan", "not JSON"),
    ("badkey", "tip.ux: a number"),
])
def test_a_solver_that_fails_ends_the_case_with_a_status_and_a_reason(tmp_path, solvers, mode, says):
    rec = run(solvers(declare(tmp_path, mode)))
    assert rec["status"] == "failed" and says in rec["reason"], rec["reason"]
    assert rec["tip"] is None and not problems(rec)
    if mode == "badkey":
        assert "ndof: missing" in rec["reason"]


def test_a_solver_that_hangs_is_stopped_at_its_wall_time(tmp_path, solvers):
    t0 = time.perf_counter()
    rec = run(solvers(declare(tmp_path, "hang", wall=0.25)))
    assert time.perf_counter() - t0 < 10.0
    assert rec["status"] == "failed" and "past its wall time of 0.25 s" in rec["reason"]


def test_what_a_solver_does_not_declare_is_skipped_with_the_reason(tmp_path, solvers):
    s = solvers(declare(tmp_path, supports='loads = ["tip_force"]'))
    assert "does not take loads 'gravity'" in unsupported(s.declaration, scene())
    with pytest.raises(SceneError, match="supports.loads"):
        make_case("external-test", s.name, scene())
    pendulum = paper.pendulum_scene("yeoh", "plane-stress", 1e-3, "HB2n-12", 2)
    ancf = [make_case("t", "ancf", scene()), make_case("t", "ancf", pendulum), make_case("t", "continuum",
                                                                                          {**scene(), "fem": {}})]
    taken, skipped = retarget(ancf, solvers(declare(tmp_path, name="stub2")))
    assert [c.solver for c in taken] == ["stub2-ok"] and taken[0].study == "t@stub2-ok"
    assert [why for _, why in skipped] == ["stub2-ok does not take analysis 'dynamic' (its declaration's "
                                           "supports.analysis: static)"]


def test_the_fingerprint_follows_declaration_version_and_adapter_not_comments(tmp_path, solvers):
    path = declare(tmp_path)
    fp = lambda: ExternalSolver("x", None, None, declaration=load_declaration(path)).fingerprint(scene())
    base = fp()
    text = open(path).read()
    open(path, "w").write("# a comment\n" + text)
    assert fp() == base
    open(path, "w").write(text.replace('version = "0.1"', 'version = "0.2"'))
    assert fp() != base
    open(path, "w").write(text)
    stub = (tmp_path / "stub.py").read_text()
    (tmp_path / "stub.py").write_text(stub + "\n# a comment\n")
    assert fp() == base
    (tmp_path / "stub.py").write_text(stub.replace("1e-3", "2e-3"))
    assert fp() != base


def test_a_python_entry_point_is_a_solver_too(tmp_path, solvers, monkeypatch):
    monkeypatch.syspath_prepend(str(tmp_path))
    (tmp_path / "py_stub.py").write_text(textwrap.dedent('''
        from contract.record import new_record
        def run(scene):
            rec = new_record("py", scene)
            rec.update(status="converged", reason=None, tip={"ux": 0.0, "uy": -0.001})
            return rec
        def boom(scene):
            raise RuntimeError("the entry point fell over")
    '''))
    for fn, status in (("run", "converged"), ("boom", "failed")):
        path = tmp_path / f"py-{fn}.toml"
        path.write_text(f'[solver]\nname = "py-{fn}"\nversion = "1"\npython = "py_stub:{fn}"\n')
        rec = run(solvers(str(path)))
        assert rec["status"] == status, rec["reason"]
    assert "the entry point fell over" in rec["reason"]
    sys.modules.pop("py_stub", None)


@pytest.mark.parametrize("body,says", [
    ('[solver]\nname = "a"\ncommand = ["x {scene} {out}"]\n', "solver.version"),
    ('[solver]\nname = "a"\nversion = "1"\n', "solver.command: give exactly one"),
    ('[solver]\nname = "a b"\nversion = "1"\npython = "m:f"\n', "solver.name"),
    ('[solver]\nname = "a"\nversion = "1"\ncommand = ["x", "{scene}"]\n', "must contain {out}"),
    ('[solver]\nname = "a"\nversion = "1"\npython = "m:f"\n[supports]\nloads = ["wind"]\n',
     "supports.loads: unknown value 'wind'; allowed: 'gravity', 'tip_force', 'end_moment'"),
    ('[solver]\nname = "a"\nversion = "1"\npython = "m:f"\nwall_time = -1\n', "solver.wall_time"),
    ('[solver]\nname = "a"\nversion = "1"\npython = "m:f"\n[extra]\n', "extra: unknown table"),
])
def test_a_bad_declaration_names_its_key(tmp_path, body, says):
    path = tmp_path / "d.toml"
    path.write_text(body)
    with pytest.raises(SceneError, match=".*".join(map(__import__("re").escape, says.split("*")))):
        load_declaration(path)


def test_the_record_checker_names_each_bad_key(tmp_path):
    good = new_record("x", scene())
    assert problems(good) == []                       # a failed record that says why
    bad = {**good, "status": "done", "ndof": -1, "stable": "yes", "cpu_s": "fast", "effects": "gravity"}
    del bad["wall_s"]
    found = "\n".join(problems(bad))
    for key in ("status: one of", "ndof: a non-negative integer", "stable: true, false or null",
                "cpu_s: a non-negative number", "effects: a list", "wall_s: missing"):
        assert key in found
    assert "tip: a converged record has finite" in "\n".join(problems({**good, "status": "converged",
                                                                        "reason": None}))
    assert problems({**good, "schema": "ancf-harness/record/2"})[0].startswith("schema:")
    assert set(KEYS) <= set(good)
    path = tmp_path / "r.json"
    path.write_text('{"tip": NaN}')
    assert "not JSON" in read(path)[1][0]


def test_a_study_runs_on_the_solver_and_a_second_run_reuses_it(tmp_path, solvers):
    """``studies external``: every ANCF case of the named studies on the stub; the
    dynamic ones (table4) skipped with the reason; the second run reuses every record."""
    from studies.external.protocol import run_study

    path = declare(tmp_path)
    lines = []
    first = run_study(path, ["hard-loads", "table4"], tmp_path / "out", tiny=True, log=lines.append)
    hard, t4 = first["hard-loads"], first["table4"]
    assert hard["cases"] > 0 and hard["computed"] == hard["cases"] and hard["failed"] == 0
    assert t4["cases"] == 0 and t4["skipped"] and all("analysis 'dynamic'" in why for _, why in t4["skipped"])
    recs = [json.loads(x) for x in (tmp_path / "out" / "data" / "hard-loads@stub-ok.jsonl").read_text().splitlines()]
    assert len(recs) == hard["cases"] and {r["solver"] for r in recs} == {"stub-ok"}
    assert any("skipped" in line and "analysis 'dynamic'" in line for line in lines)
    again = run_study(path, ["hard-loads"], tmp_path / "out", tiny=True, log=lines.append)
    assert again["hard-loads"]["reused"] == hard["cases"] and again["hard-loads"]["computed"] == 0


def test_check_record_on_the_command_line_names_the_key_and_exits_1(tmp_path, capsys):
    from studies.cli import main

    good, bad = tmp_path / "good.json", tmp_path / "bad.json"
    good.write_text(json.dumps(new_record("x", scene())))
    bad.write_text(json.dumps({**new_record("x", scene()), "ndof": 1.5}))
    assert main(["check-record", str(good)]) == 0
    assert main(["check-record", str(good), str(bad)]) == 1
    assert "bad.json: ndof: a non-negative integer or null, got 1.5" in capsys.readouterr().out


def test_the_benchmark_suite_on_a_solver_with_its_own_element_gives_its_verdicts(tmp_path, solvers):
    """A solver with an element of its own runs each distinct scene once; its report lists
    every case it ran with the suite's verdict, each miss with the declared cause (or
    'cause not found'), and what it was not run on, with the reason."""
    from studies.external.protocol import run_study

    path = declare(tmp_path, supports='supports = ["slide"]\nloads = ["tip_force", "gravity"]',
                   extra='element = "StubCable"\n[causes]\nelastica = "the stub returns a made-up tip"')
    summary = run_study(path, ["benchmarks"], tmp_path / "out", tiny=True, log=lambda *_: None)["benchmarks"]
    recs = [json.loads(x) for x in (tmp_path / "out" / "data" / "benchmarks@stub-ok.jsonl").read_text().splitlines()]
    assert {r["scene"]["ancf"]["element"] for r in recs} == {"StubCable"}
    assert len({json.dumps({**r["scene"], "name": None}, sort_keys=True) for r in recs}) == len(recs)
    report = (tmp_path / "out" / "benchmarks@stub-ok.md").read_text()
    assert "| stub-ok StubCable |" in report and "FAIL | the stub returns a made-up tip |" in report
    assert summary["skipped"] and "Not run (outside the declaration)" in report
    assert "does not take loads 'end_moment'" in report


# in the full tier (the cable's 3 s, mostly the suite's cases made afresh; the beam's 18 s, its
# arc rows' tolerances are the suite's shooting); the stub's benchmark verdicts keep a verdict
# page rendered from records in the quick tier
@pytest.mark.slow(guard="test_the_benchmark_suite_on_a_solver_with_its_own_element_gives_its_verdicts")
@pytest.mark.parametrize("name", ["exudyn", "exudyn-beam2d"])
def test_the_committed_exudyn_reports_are_their_records_verdicts(tmp_path, name):
    """``reports/external/benchmarks@<solver>.md`` and ``dynamic-benchmarks@<solver>.md`` of
    the Exudyn declarations (the cable, the geometrically exact beam) rebuilt from their
    committed records alone (no Exudyn run: the cases skipped come from the declaration, the
    verdicts from the records) are the committed pages, line for line."""
    import shutil
    from pathlib import Path

    from studies.engine.catalog import load_catalog
    from studies.external.verdicts import benchmark_report, dynamic_report

    root = Path(__file__).resolve().parents[1]
    catalog = load_catalog()
    (tmp_path / "data").mkdir()
    solver = register_external(root / "studies" / "peers" / f"{name}.toml")
    try:
        for study, report in (("benchmarks", benchmark_report), ("dynamic-benchmarks", dynamic_report)):
            shutil.copy(root / "reports" / "external" / "data" / f"{study}@{name}.jsonl", tmp_path / "data")
            _, skipped = retarget(catalog[study].cases(), solver)
            page = report(tmp_path, solver.declaration, skipped)
            assert page.read_text() == (root / "reports" / "external" / page.name).read_text(), page.name
    finally:
        del SOLVERS[solver.name]


def test_a_card_on_an_external_solver_judges_its_runs_and_names_what_it_left_out(tmp_path, solvers):
    """``studies card --solver``: the card's run-only sections from the stub's records (its
    made-up tip is judged, not passed: the convergence plateau is its distance to the
    continuum's gold), what the declaration does not take skipped and named (plane strain,
    so the locking sweep; the pendulum), the sections that need the element's internals
    listed as left out; a second run would reuse every record (its dry run)."""
    from studies.common.gold import gold_references
    from studies.design.card_report import FEM_STATIC
    from studies.engine.report import vec_error
    from studies.external.card import elements_of, run_external_cards

    path = declare(tmp_path, supports='formulations = ["plane-stress"]', extra='element = "StubCable"')
    lines = []
    [card] = run_external_cards(path, [], tmp_path / "out", tiny=True, log=lines.append)
    assert card.name == "stub-ok-StubCable.md" and "0 reused" in lines[0] and "0 without a result" in lines[0]
    text = card.read_text()
    for s in ("## Left out", "## 4.", "## 5.", "### Shear locking", "## 6.", "## 7.", "## 8.", "## 9.", "## 10."):
        assert s in text, s
    assert "1. contract checks" in text and "2. rank tests" in text and "## 1. Contract" not in text
    assert "Volumetric locking: not run: stub-ok does not take formulations 'plane-strain'" in text
    assert "## 6. Pendulum against the continuum\n\nNot run: stub-ok does not take analysis 'dynamic'" in text
    L = paper.CANTILEVER["length"]
    err = vec_error({"ux": 0.0, "uy": -1e-3 * L}, gold_references(FEM_STATIC)[("neo-hookean", "plane-stress")])
    assert f"| NH | plane-stress | 16 | 0.00, {-1e-3 * L * 1e3:.2f} | {100 * err:.3f} % |" in text
    recs = [json.loads(x) for x in (tmp_path / "out" / "data" / "card-stub-ok-StubCable.jsonl").read_text().splitlines()]
    assert recs and {r["scene"]["ancf"]["element"] for r in recs} == {"StubCable"}
    assert {r["scene"]["material"]["formulation"] for r in recs} == {"plane-stress"}
    run_external_cards(path, [], tmp_path / "out", tiny=True, dry=True, log=lines.append)
    assert f"{len(recs)} reused, 0 to compute" in lines[-1]
    with pytest.raises(ValueError, match="name the elements to card"):
        elements_of(load_declaration(declare(tmp_path, name="byname")), [])


# in the full tier (the cable's 2.6 s, the beam's 15 s: its benchmark section's arc
# tolerances); the stub's card keeps a card rendered from records in the quick tier
@pytest.mark.slow(guard="test_a_card_on_an_external_solver_judges_its_runs_and_names_what_it_left_out")
@pytest.mark.parametrize("name, element", [("exudyn", "ObjectANCFCable2D"),
                                           ("exudyn-beam2d", "ObjectBeamGeometricallyExact2D")])
def test_the_committed_exudyn_cards_are_their_records_cards(tmp_path, name, element):
    """``reports/external/cards/<solver>-<element>.md`` rendered again from its committed
    records alone (no Exudyn run) is the committed card, line for line (the cost figure draws
    every card of the directory: both cards' records are copied)."""
    import shutil
    from pathlib import Path

    from studies.external.card import render

    root = Path(__file__).resolve().parents[1]
    (tmp_path / "data").mkdir()
    for f in ("card-exudyn-ObjectANCFCable2D.jsonl", "card-exudyn-beam2d-ObjectBeamGeometricallyExact2D.jsonl",
              f"benchmarks@{name}.jsonl"):
        shutil.copy(root / "reports" / "external" / "data" / f, tmp_path / "data")
    solver = register_external(root / "studies" / "peers" / f"{name}.toml")
    try:
        card = render(solver.declaration, element, tmp_path)
    finally:
        del SOLVERS[solver.name]
    assert card.read_text() == (root / "reports" / "external" / "cards" / card.name).read_text()
