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


@pytest.mark.skipif(not (REPORTS / "data").is_dir(), reason="no committed records")
def test_committed_reports_pass_and_a_tampered_copy_fails(tmp_path):
    """One rebuild of the committed reports' copy with three changes: a number in a
    table, a number in the README's prose and a hollow point of a figure made filled.
    The audit names exactly those three file:line pairs; everything else (the committed
    reports as they are) passes."""
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

    res = audit(copy)
    where = sorted({p.split(": ")[0] for p in res.problems})
    want = sorted([f"{table}:{l1}", f"{readme}:{l2}"] + ([f"{fig}:{l3}"] if l3 else []))
    assert where == want, "\n".join(res.problems)
    assert any(bumped in p and cell in p for p in res.problems)
    assert "README.md" not in res.not_audited and "table3.md" in res.checked


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
