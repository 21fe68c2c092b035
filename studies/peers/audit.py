"""The audit of the peer reports: ``peers.md`` and ``peers_work_precision.md``, which
``make bench-peers`` writes outside the study pipeline, rebuilt from their records in
``DIR/data/peers/`` by their own plain functions (:data:`PEER_REPORTS`) and compared line
by line, with the data of the work-precision figures (each scene's lead figure and its
full cloud; registered as a rule of :mod:`studies.engine.audit`)."""
from __future__ import annotations

import json
from pathlib import Path

from ..engine.audit import AuditResult, compare_text, register_rule
from ..engine.report import FIGURE_DATA
from .compare import peers_markdown
from .exudyn_published import RECORD as PUBLISHED, read_record
from .precision_report import figure_csv, figure_name, report_markdown, scenes_of
from .records import COSTS, read, read_costs, rounds_path


def _peer_markdown(kind: str, path: Path) -> str:
    if kind == "compare":          # with the published checks' section where their record is beside it
        return peers_markdown(json.loads(path.read_text()), read_record(path.with_name(PUBLISHED.name)))
    return report_markdown(read(path), read(rounds_path(path)), read_costs(path.with_name(COSTS)))


# peer report -> (its record under DIR/data/peers/, the function that draws it)
PEER_REPORTS = {"peers.md": ("peers-compare.json", "compare"),
                "peers_work_precision.md": ("peers-work-precision.jsonl", "work_precision")}


def audit_peers(reports: Path, res: AuditResult) -> set[str]:
    """The peer rule: each peer report that exists is redrawn from its record and compared,
    and so is the data of every work-precision figure (one per scene). Returns the files
    the rule covers."""
    covered = set()
    for name, (record, kind) in PEER_REPORTS.items():
        if not (reports / name).exists():
            continue
        covered.add(name)
        rec = reports / "data" / "peers" / record
        if not rec.exists():
            res.problems.append(f"{reports / name}:1: its record data/peers/{record} is missing")
            continue
        res.checked.append(name)
        res.problems += compare_text(str(reports / name), _peer_markdown(kind, rec), (reports / name).read_text())
        if kind == "work_precision":
            recs = read(rec)
            for scene in scenes_of(recs):
                for every in (False, True):        # the lead figure and the full cloud
                    png = figure_name(scene, every)
                    data = png[:-4] + FIGURE_DATA
                    covered |= {png, data}
                    if not (reports / data).exists():
                        res.problems.append(f"{reports / data}:1: missing (the records give this file)")
                        continue
                    res.checked.append(data)
                    res.problems += compare_text(str(reports / data), figure_csv(recs, scene, every),
                                                 (reports / data).read_text())
    return covered


register_rule("peers", audit_peers)
