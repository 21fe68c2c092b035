"""Every study in tiny mode into a temp dir: records, tables, figures, README; reports
read records only; a warm rerun computes nothing; named values against the gold file."""
from __future__ import annotations

import dataclasses
import json
import subprocess
import sys
from pathlib import Path

import pytest

from studies.engine import solvers
from studies.engine.catalog import load_catalog
from studies.engine.pipeline import REPORTS, build_reports, resolve_out, run_studies
from studies.engine.regression import FILE as GOLD, collect, compare, load_gold
from studies.engine.store import store_for

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    out = tmp_path_factory.mktemp("studies-tiny")
    log = []
    run_studies(["all"], out, tiny=True, executor="serial", progress=False, log=log.append)
    return out, log


def _rebuilt_without_solvers(out, monkeypatch) -> str:
    """The results page rebuilt from the records with every solver refusing to run."""
    def refuse(scene):
        raise AssertionError("a report called a solver")

    for name, s in list(solvers.SOLVERS.items()):
        monkeypatch.setitem(solvers.SOLVERS, name, dataclasses.replace(s, run=refuse))
    build_reports(out, tiny=True)
    return (out / "README.md").read_text()


# the quick tier's tiny run: a static table, with the continuum it needs
FEW = ["table3"]


@pytest.fixture(scope="module")
def few(tmp_path_factory):
    out = tmp_path_factory.mktemp("studies-few")
    log = []
    run_studies(FEW, out, tiny=True, executor="serial", progress=False, log=log.append)
    return out, log


@pytest.mark.dolfinx
def test_a_few_studies_leave_a_record_per_case_reports_from_records_and_their_gold_values(few, monkeypatch):
    """The quick tier's guard of the four tests on every study below: records per case,
    reports from records only, a warm rerun that computes nothing, the gold values."""
    out, _ = few
    catalog = load_catalog(tiny=True)
    ran = [s for s in catalog.values() if store_for(out, s.name).path.exists()]
    assert {s.name for s in ran} == {"continuum", *FEW}
    readme = (out / "README.md").read_text()
    for study in ran:
        assert {c.id for c in study.cases()} == set(store_for(out, study.name).read()), study.name
        assert study.title in readme
    log = []
    run_studies(FEW, out, tiny=True, executor="serial", progress=False, log=log.append)
    assert all(", 0 computed," in x for x in log if " cases, " in x)
    assert _rebuilt_without_solvers(out, monkeypatch) == readme
    gold = {k: v for k, v in load_gold().items() if k.split("/")[0] in {s.name for s in ran}}
    values = collect(out)
    assert gold and not compare({k: v for k, v in values.items() if k.split("/")[0] in {s.name for s in ran}}, gold)


@pytest.mark.slow(guard="test_a_few_studies_leave_a_record_per_case_reports_from_records_and_their_gold_values")
def test_every_study_leaves_a_record_per_case_and_its_report(tiny):
    out, _ = tiny
    catalog = load_catalog(tiny=True)
    readme = (out / "README.md").read_text()
    for study in catalog.values():
        cases = study.cases()
        recs = store_for(out, study.name).read()
        assert {c.id for c in cases} == set(recs), study.name
        assert all(r["case_id"] == r["case"]["id"] for r in recs.values())
        assert study.title in readme
        assert "NaN" not in store_for(out, study.name).path.read_text()
    for line in readme.splitlines():  # every table and figure the README names exists
        for token in line.replace("(", " ").replace(")", " ").split():
            if token.endswith((".png", ".md", ".csv")) and "/" not in token:
                assert (out / token).exists(), token
    assert "Tiny mode" in readme
    assert not str(out).startswith(str(REPORTS))


@pytest.mark.slow(guard="test_felupe_backend.py::test_same_mesh_same_tip_as_dolfinx_gold_2d")
def test_the_two_continuum_codes_agree_within_their_bars(tiny):
    """continuum-agreement's check on the tiny meshes: every row within its bar."""
    out, _ = tiny
    readme = (out / "README.md").read_text()
    section = readme[readme.index("Continuum agreement: DOLFINx and FElupe"):]
    assert section.split("\n## ")[0].count("Check: **PASS**") == 1


@pytest.mark.slow(guard="test_a_few_studies_leave_a_record_per_case_reports_from_records_and_their_gold_values")
def test_timed_cases_carry_serial_warm_timings(tiny):
    out, _ = tiny
    recs = store_for(out, "accuracy-cost").read().values()
    assert recs and all(r["run"]["executor"] == "serial-timed" for r in recs)
    ok = [r for r in recs if r["status"] == "converged"]
    assert ok and all(r["timing"]["median_s"] > 0 and r["timing"]["warmup_s"] > 0 for r in ok)


@pytest.mark.slow(guard="test_a_few_studies_leave_a_record_per_case_reports_from_records_and_their_gold_values")
def test_reports_read_records_only(tiny, monkeypatch):
    out, _ = tiny
    before = (out / "README.md").read_text()
    assert _rebuilt_without_solvers(out, monkeypatch) == before


@pytest.mark.slow(guard="test_a_few_studies_leave_a_record_per_case_reports_from_records_and_their_gold_values")
def test_a_warm_rerun_computes_nothing(tiny):
    out, _ = tiny
    log = []
    run_studies(["all"], out, tiny=True, executor="serial", progress=False, log=log.append)
    summaries = [x for x in log if " cases, " in x]
    assert len(summaries) == len(load_catalog(tiny=True))
    assert all(", 0 computed," in x for x in summaries), summaries


@pytest.mark.slow(guard="test_a_few_studies_leave_a_record_per_case_reports_from_records_and_their_gold_values")
def test_tiny_values_match_the_gold_file(tiny):
    out, _ = tiny
    problems = compare(collect(out), load_gold())
    assert not problems, "\n".join(problems)


def test_a_gold_mismatch_names_the_value_and_the_difference():
    gold = {"table3/HB3n-12/paper/Yeoh/uy": {"value": -0.1194, "tolerance": 1e-7},
            "continuum/NH/plane-stress/ux": {"value": -0.0394, "tolerance": 1e-8}}
    values = {"table3/HB3n-12/paper/Yeoh/uy": (-0.1195, 1e-7), "new/value": (1.0, 0.1)}
    problems = compare(values, gold)
    assert any("table3/HB3n-12/paper/Yeoh/uy" in p and "-1.000e-04" in p for p in problems)
    assert any(p.startswith("continuum/NH/plane-stress/ux: missing") for p in problems)
    assert any(p.startswith("new/value: new value") for p in problems)
    assert compare({k: (v["value"] + 0.5 * v["tolerance"], 0) for k, v in gold.items()}, gold) == []


def test_the_gold_file_has_named_values_with_tolerances():
    doc = json.loads(GOLD.read_text())
    assert "--refresh" in doc["description"]
    vals = doc["values"]
    assert len(vals) > 50 and any(k.startswith("table3/") for k in vals) and any(k.startswith("continuum/") for k in vals)
    assert all(0 < v["tolerance"] < 1e-3 * abs(v["value"]) + 1e-8 for v in vals.values())


def test_cli_lists_the_studies_and_tiny_output_defaults_to_a_temp_dir(capsys):
    from studies.cli import main
    assert main(["list"]) == 0
    listed = capsys.readouterr().out
    for name in load_catalog():
        assert name in listed
    tmp = resolve_out(None, tiny=True)
    assert tmp.is_dir() and not str(tmp).startswith(str(REPORTS))
    tmp.rmdir()
    assert main(["run", "no-such-study", "--tiny"]) == 2
    err = capsys.readouterr().err
    assert "study: unknown 'no-such-study'; allowed: " in err and all(n in err for n in ("continuum", "table3"))
