"""The report audits itself: ``python -m studies audit`` rebuilds every report from its
records and names file and line of each mismatch (issue 19). No solver runs here."""
from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from studies.engine.audit import audit, compare_text

REPORTS = Path(__file__).resolve().parents[1] / "reports"


def test_compare_text_names_the_line():
    exp = "a\n| x | 1.00 |\nc\n"
    assert compare_text("f.md", exp, exp) == []
    got = compare_text("f.md", exp, "a\n| x | 1.01 |\nc\n")
    assert got == ["f.md:2: records give '| x | 1.00 |', report has '| x | 1.01 |'"]
    assert compare_text("f.md", exp, "a\nc\n") == ["f.md:2: missing line (records give '| x | 1.00 |')"]
    assert compare_text("f.md", exp, exp + "typed by hand\n") == ["f.md:4: not derived from the records: 'typed by hand'"]


def _tamper(path: Path, old: str, new: str) -> int:
    """Replace the first ``old`` in ``path`` by ``new``; return its 1-based line."""
    lines = path.read_text().splitlines(keepends=True)
    for i, line in enumerate(lines):
        if old in line:
            lines[i] = line.replace(old, new, 1)
            path.write_text("".join(lines))
            return i + 1
    raise AssertionError(f"{old!r} not in {path}")


@pytest.mark.slow(guard="test_a_tampered_report_is_named_by_file_and_line")
@pytest.mark.skipif(not (REPORTS / "data").is_dir(), reason="no committed records")
def test_committed_reports_pass_and_a_tampered_copy_fails(tmp_path):
    """One rebuild of the committed reports' copy with four changes: a number in a
    table, a number in the README's prose, a hollow point of a figure made filled and a
    solver-run count on an element card (cards are rendered again from their records,
    not copied). The audit names exactly those file:line pairs; everything else (the
    committed reports as they are) passes."""
    copy = tmp_path / "reports"
    shutil.copytree(REPORTS, copy)
    table = copy / "table3.md"
    row = next(ln for ln in table.read_text().splitlines() if ln.startswith("| HB2n-12 `paper`"))
    cell = row.split("|")[3].strip()                 # a tip value, e.g. -27.92
    bumped = f"{float(cell) + 0.01:.2f}"
    l1 = _tamper(table, f"| {cell} |", f"| {bumped} |")
    readme = copy / "README.md"
    text = readme.read_text()
    stat = next(ln for ln in text.splitlines() if "distinct runs hold the bound" in ln)
    n = stat.split()[1]
    l2 = _tamper(readme, stat, stat.replace(f"- {n} of", f"- {int(n) + 1} of", 1))
    fig = copy / "accuracy_cost.figure.csv"
    l3 = _tamper(fig, ",False,", ",True,") if ",False," in fig.read_text() else None
    card = copy / "cards" / "HB2n-12.md"
    runs = next(ln for ln in card.read_text().splitlines() if ln.endswith(" solver runs."))
    n_runs = runs.split()[-3]
    l4 = _tamper(card, f" {n_runs} solver runs.", f" {int(n_runs) + 1} solver runs.")

    res = audit(copy)
    where = sorted({p.split(": ")[0] for p in res.problems})
    want = sorted([f"{table}:{l1}", f"{readme}:{l2}", f"{card}:{l4}"] + ([f"{fig}:{l3}"] if l3 else []))
    assert where == want, "\n".join(res.problems)
    assert any(bumped in p and cell in p for p in res.problems)
    assert "README.md" not in res.not_audited and "table3.md" in res.checked
    assert "cards/HB2n-12.md" in res.checked and not any(f.startswith("cards/") for f in res.not_audited)


def test_a_report_file_the_records_do_not_give_is_named(tmp_path):
    """A missing generated file fails the audit; a file no study writes is listed, not audited."""
    copy = tmp_path / "r"
    (copy / "data").mkdir(parents=True)
    shutil.copy(REPORTS / "data" / "table3.jsonl", copy / "data")
    shutil.copy(REPORTS / "data" / "continuum.jsonl", copy / "data")
    (copy / "notes.md").write_text("typed\n")
    res = audit(copy)
    assert not res.ok
    assert any(p.endswith("table3.md:1: missing (the records give this file)") for p in res.problems)
    assert res.not_audited == ["notes.md"]


def _pt(mesh, err, verdict="stable", config="HB2n-16 q32", time=None):
    return {"solver": "ancf", "config": config, "ndof": mesh * 16, "mesh": mesh, "error": err,
            "verdict": verdict, "time": time if time is not None else mesh * 1e-4}


def test_cheapest_does_not_rest_on_cancellation():
    """Issue 19: HB2n-16 q32 x 160 at 0.025 % with finer meshes at 0.065 / 0.086 % must
    not be 'cheapest at 0.05 %'; at 0.1 % it may; a warned or singular point never counts,
    nor a point whose finer mesh is not stable."""
    from studies.design.accuracy_cost_points import cheapest, settled, settled_steps

    curve = [_pt(80, 0.0020), _pt(160, 0.00025), _pt(320, 0.00065), _pt(640, 0.00086)]
    assert cheapest(settled(curve, 0.0005), 0.0005) is None
    assert cheapest(settled(curve, 0.001), 0.001)["mesh"] == 160
    warned = [_pt(160, 0.00025, "warned"), _pt(320, 0.0003), _pt(640, 0.0003)]
    assert cheapest(settled(warned, 0.001), 0.001)["mesh"] == 320
    finer_singular = [_pt(160, 0.00025), _pt(320, 0.0003, "singular")]
    assert settled(finer_singular, 0.001) == []
    # pendulum: every finer mesh and finer step keeps the accuracy
    pend = [{"formulation": "f", "element": "E", "n": n, "dt": dt, "error": e, "verdict": "converged", "time": 1.0}
            for n, dt, e in ((8, 2e-3, 0.004), (8, 1e-3, 0.02), (16, 2e-3, 0.003), (16, 1e-3, 0.003))]
    assert [(p["n"], p["dt"]) for p in settled_steps(pend, 0.01)] == [(16, 2e-3), (16, 1e-3)]


@pytest.mark.skipif(not (REPORTS / "accuracy_cost.csv").exists(), reason="no committed reports")
def test_the_cheapest_rule_recheck_names_a_cell_on_cancellation(tmp_path):
    """The accuracy-cost audit rule, from the written CSVs alone: the committed cells
    pass; the former MR plane-stress 0.1 % cell (HB2n-16 q32 x 160: warned, 0.025 %, its
    finer meshes 0.065 / 0.086 %) put back is named with its line."""
    from types import SimpleNamespace

    from studies.design import accuracy_cost

    for f in ("accuracy_cost.csv", "accuracy_cost_points.csv"):
        shutil.copy(REPORTS / f, tmp_path)
    ctx = SimpleNamespace(out=tmp_path)
    assert accuracy_cost.audit(ctx) == []
    cells = tmp_path / "accuracy_cost.csv"
    lines = cells.read_text().splitlines(keepends=True)
    i = next(k for k, ln in enumerate(lines) if ln.startswith("MR,plane-stress,0.1 %,"))
    parts = lines[i].split(",")
    parts[3] = "HB2n-16 q32 x 160"
    lines[i] = ",".join(parts)
    cells.write_text("".join(lines))
    problems = accuracy_cost.audit(ctx)
    assert len(problems) == 1 and problems[0].startswith(f"accuracy_cost.csv:{i + 1}: ") and "warned" in problems[0]


def test_a_tampered_report_is_named_by_file_and_line(tmp_path):
    """The quick guard of the committed reports' audit: Table 3 and the continuum rebuilt
    from their committed records alone, a number of Table 3 changed; the audit names that
    file and line and nothing of Table 3 else."""
    copy = tmp_path / "r"
    (copy / "data").mkdir(parents=True)
    for name in ("table3.jsonl", "continuum.jsonl"):
        shutil.copy(REPORTS / "data" / name, copy / "data")
    for f in REPORTS.glob("table3*"):
        shutil.copy(f, copy / f.name)
    table = copy / "table3.md"
    row = next(ln for ln in table.read_text().splitlines() if ln.startswith("| HB2n-12 `paper`"))
    cell = row.split("|")[3].strip()
    line = _tamper(table, f"| {cell} |", f"| {float(cell) + 0.01:.2f} |")
    res = audit(copy)
    assert [p.split(": ")[0] for p in res.problems if p.startswith(str(copy / "table3"))] == [f"{table}:{line}"]


def test_a_card_whose_records_are_stale_is_named_with_the_command_that_recomputes_it(tmp_path):
    """A card whose records match none of today's cases (code changed since) cannot be
    rendered again: the audit's hook names it and the command, as one problem, instead of
    a traceback."""
    import json

    from studies.design.card import render_for_audit

    (tmp_path / "data").mkdir()
    (tmp_path / "data" / "card-HB2n-12-checks.json").write_text(json.dumps({"element": "HB2n-12", "tiny": True}))
    with pytest.raises(LookupError, match=r"the cards of HB2n-12 have no records of today's code .*"
                                          r"`python -m studies card HB2n-12`"):
        render_for_audit(tmp_path)
