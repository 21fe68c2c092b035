"""The loops record: the README quotes its rendering, and the audit holds the quote to it."""
import json

from studies.loops import BEGIN, END, _pytest_seconds, markdown, readme_problems, write_readme

REC = {"schema": "ancf-harness/loops/1", "date": "2026-11-27", "commit": "abc1234", "machine": {"cpus": 2},
       "setup_s": 201.3, "first_run": {"scenes": {"a.toml": 1.1, "b.toml": 1.6}, "max_s": 1.6},
       "tests": {"command_s": 130.2, "pytest_s": [104.0, 7.0]}, "verify": {"sample": 20, "seconds": 41.0},
       "study_cold_s": 790.0, "study_reused_s": 11.0}


def test_the_readme_quotes_the_record_and_a_changed_figure_is_named(tmp_path):
    record, readme = tmp_path / "loops.json", tmp_path / "README.md"
    record.write_text(json.dumps(REC))
    readme.write_text("# Title\n\nsome text\n")
    write_readme(REC, readme)
    text = readme.read_text()
    assert BEGIN in text and END in text and "13 min 10 s" in text and "1.1 to 1.6 s (2 scenes)" in text
    assert readme_problems(readme, record) == []
    readme.write_text(text.replace("13 min 10 s", "12 min 10 s"))
    assert readme_problems(readme, record) == [f"{readme}:5: the loops figures differ from loops.json "
                                               "(make loops writes both)"]
    write_readme(REC, readme)                      # the block is replaced, not appended again
    assert readme.read_text() == text and markdown(REC) in text


def test_pytest_time_is_read_from_each_summary_line():
    out = "1180 passed, 4 warnings in 104.00s (0:01:44)\n...\n1 passed, 1379 deselected, 1 warning in 7.00s\n"
    assert _pytest_seconds(out) == [104.0, 7.0]
