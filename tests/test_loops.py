"""The loops record: loops.md renders it, the README quotes loops.md and any other report
between include markers, and the audit holds both to their sources."""
import json

from studies.engine.readme import problems, refresh
from studies.loops import _pytest_seconds, markdown, record_problems

REC = {"schema": "ancf-harness/loops/1", "date": "2026-11-27", "commit": "abc1234", "machine": {"cpus": 2},
       "setup_s": 201.3, "first_run": {"scenes": {"a.toml": 1.1, "b.toml": 1.6}, "max_s": 1.6},
       "tests": {"command_s": 130.2, "pytest_s": [104.0, 7.0]}, "verify": {"sample": 20, "seconds": 41.0},
       "study_cold_s": 790.0, "study_reused_s": 11.0}


def test_the_readme_quotes_a_report_and_a_changed_line_is_named(tmp_path):
    (tmp_path / "reports").mkdir()
    page = tmp_path / "reports" / "loops.md"
    page.write_text(markdown(REC))
    readme = tmp_path / "README.md"
    readme.write_text("# Title\n\ntext\n<!-- include reports/loops.md -->\n<!-- /include -->\nmore\n")
    assert refresh(readme, tmp_path) and problems(readme, tmp_path) == []
    text = readme.read_text()
    assert "13 min 10 s" in text and "1.1 to 1.6 s (2 scenes)" in text and text.endswith("<!-- /include -->\nmore\n")
    readme.write_text(text.replace("13 min 10 s", "12 min 10 s"))
    assert problems(readme, tmp_path) == [f"{readme}:4: the quote of reports/loops.md differs from the file "
                                          "(studies run rewrites it)"]
    assert refresh(readme, tmp_path) and readme.read_text() == text and not refresh(readme, tmp_path)


def test_the_page_is_the_rendering_of_the_record(tmp_path):
    record, page = tmp_path / "loops.json", tmp_path / "loops.md"
    record.write_text(json.dumps(REC))
    page.write_text(markdown(REC))
    assert record_problems(record, page) == []
    page.write_text(markdown(REC).replace("2 scenes", "3 scenes"))
    assert record_problems(record, page)


def test_pytest_time_is_read_from_each_summary_line():
    out = "1180 passed, 4 warnings in 104.00s (0:01:44)\n...\n1 passed, 1379 deselected, 1 warning in 7.00s\n"
    assert _pytest_seconds(out) == [104.0, 7.0]


def test_an_empty_block_of_a_file_not_yet_written_quotes_nothing(tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text("<!-- include reports/loops.md -->\n<!-- /include -->\n")
    assert problems(readme, tmp_path) == [] and not refresh(readme, tmp_path)
    readme.write_text("<!-- include reports/loops.md -->\n| stale |\n<!-- /include -->\n")
    assert problems(readme, tmp_path) == [f"{readme}:1: quotes reports/loops.md, which is missing"]
