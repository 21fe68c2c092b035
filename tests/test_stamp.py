"""The audit's stamp: while the reports' inputs (records, report code, data files) and
every report file are as the last passing full audit found them, the reports are not
rebuilt; any changed byte of either makes the next audit a full one."""
import shutil
from pathlib import Path

from studies.engine import stamp

REPORTS = Path(__file__).resolve().parents[1] / "reports"


def test_a_changed_record_or_report_file_voids_the_stamp(tmp_path):
    r = tmp_path / "reports"
    (r / "data").mkdir(parents=True)
    shutil.copy(REPORTS / "data" / "table3.jsonl", r / "data")
    shutil.copy(REPORTS / "table3.md", r)
    assert not stamp.current(r)                    # never audited
    stamp.write(r)
    assert stamp.current(r)
    text = (r / "table3.md").read_text()
    (r / "table3.md").write_text(text.replace("|", "| ", 1))
    assert not stamp.current(r)                    # a report edited by hand
    (r / "table3.md").write_text(text)
    assert stamp.current(r)
    with open(r / "data" / "table3.jsonl", "a") as f:
        f.write("\n")
    assert not stamp.current(r)                    # a record file changed
    (r / "table3.md").unlink()
    stamp.write(r)
    (r / "table3.md").write_text(text)
    assert not stamp.current(r)                    # a report file the audit did not see
