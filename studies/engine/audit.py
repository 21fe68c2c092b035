"""``python -m studies audit``: the reports re-derived from their records and compared.

Every report file a study writes (tables as Markdown and CSV, the data of every figure,
the prose of ``README.md`` and of the one-page reports) comes from a study's report
function reading records only. The audit copies ``DIR/data`` into a temporary directory,
rebuilds every report there with the same functions (no solver runs: the records are read
as they are; the element cards first, from their cases and checks records, since the
README lists them), and compares each text file line by line with the one in ``DIR``: a
changed number, a missing row or a verdict typed by hand is a mismatch named by file and
line. Figures are compared by the data they draw
(``<name>.figure.csv``: every point, its label and whether its marker is hollow), not by
their pixels. Then each study's own audit rules (``audit(ctx) -> [problem]`` in its module,
see :mod:`.catalog`) check what a referee would recompute: counts against lists, verdicts
against the records. Reports drawn outside the study pipeline are audited by the rules
their owners register (:func:`register_rule`: the peer reports, :mod:`studies.peers.audit`),
and what the rebuilt tree needs first by the hooks they register (:func:`register_prebuild`:
the element cards, :mod:`studies.design.card`).

What it cannot check: that the records themselves are right (the solvers' tests and
``python -m studies diff`` do that), files no study writes (listed as not audited), and
PNG pixels beyond their data.
"""
from __future__ import annotations

import difflib
import shutil
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from contract.registry import Registry

from .catalog import CASES_TOML, load_catalog
from .report import FIGURE_DATA, Context

MAX_PER_FILE = 10      # mismatching lines named per file (then a count)
COPIED = ("data",)


@dataclass
class AuditResult:
    problems: list[str] = field(default_factory=list)   # "file:line: what" (each fails the audit)
    checked: list[str] = field(default_factory=list)    # files compared
    not_audited: list[str] = field(default_factory=list)  # files in DIR that no study writes

    @property
    def ok(self) -> bool:
        return not self.problems


def _files(root: Path) -> set[str]:
    return {str(p.relative_to(root)) for p in root.rglob("*")
            if p.is_file() and p.relative_to(root).parts[0] not in COPIED}


def compare_text(name: str, expected: str, found: str) -> list[str]:
    """Mismatches of ``found`` (the file in the reports) against ``expected`` (rebuilt
    from records), as "name:line: ..." with the line number in ``found``."""
    a, b = expected.splitlines(), found.splitlines()
    out: list[str] = []
    for tag, i1, i2, j1, j2 in difflib.SequenceMatcher(None, a, b, autojunk=False).get_opcodes():
        if tag == "equal":
            continue
        if tag in ("replace", "insert"):
            for k, j in enumerate(range(j1, j2)):
                want = a[i1 + k] if i1 + k < i2 else None
                out.append(f"{name}:{j + 1}: " + (f"records give {want!r}, report has {b[j]!r}" if want is not None
                                                  else f"not derived from the records: {b[j]!r}"))
            for i in range(i1 + (j2 - j1), i2):
                out.append(f"{name}:{j2 + 1}: missing line (records give {a[i]!r})")
        else:   # delete
            for i in range(i1, i2):
                out.append(f"{name}:{j1 + 1}: missing line (records give {a[i]!r})")
    if len(out) > MAX_PER_FILE:
        out = out[:MAX_PER_FILE] + [f"{name}: ... and {len(out) - MAX_PER_FILE} more mismatching lines"]
    return out


# what is rendered or audited outside the studies' pipeline, registered by its owner:
# PREBUILD(tmp) renders into the rebuilt tree first (the element cards, which the README lists);
# RULES(reports, res) compares reports drawn by their own functions (the peer reports) and
# returns the files it covers
PREBUILD: Registry[Callable[[Path], object]] = Registry("audit.prebuild", "pre-build hook")
RULES: Registry[Callable[[Path, "AuditResult"], set]] = Registry("audit.rule", "audit rule")


def register_prebuild(name: str, hook: Callable[[Path], object]) -> None:
    PREBUILD.register(name, hook, sys._getframe(1).f_globals.get("__name__", "__main__"))


def register_rule(name: str, rule: Callable[[Path, "AuditResult"], set]) -> None:
    RULES.register(name, rule, sys._getframe(1).f_globals.get("__name__", "__main__"))


def audit(reports: Path, catalog_path: Path = CASES_TOML, tiny: bool = False, log=None) -> AuditResult:
    """Rebuild every report of ``reports`` from ``reports/data`` in a temporary directory
    and compare; never runs a solver."""
    from .pipeline import build_reports

    reports = Path(reports)
    try:
        reports = reports.resolve().relative_to(Path.cwd())   # names as a user types them
    except ValueError:
        pass
    res = AuditResult()
    if not (reports / "data").is_dir():
        res.problems.append(f"{reports}: no data/ directory of records")
        return res
    with tempfile.TemporaryDirectory(prefix="studies-audit-") as tmp:
        tmp = Path(tmp)
        for d in COPIED:
            if (reports / d).is_dir():
                shutil.copytree(reports / d, tmp / d)
        for hook in PREBUILD.values():
            try:
                hook(tmp)
            except LookupError as e:         # records that cannot render (a stale card): a problem, named
                res.problems.append(f"{reports}: {e}")
        build_reports(tmp, tiny, log or (lambda *a, **k: None), catalog_path)
        made, have = _files(tmp), _files(reports)
        for name in sorted(made):
            if name.endswith(".png"):
                if name not in have:
                    res.problems.append(f"{reports / name}: figure missing")
                if name[:-4] + FIGURE_DATA not in made:
                    res.problems.append(f"{reports / name}: figure without its data file {FIGURE_DATA}")
                continue
            res.checked.append(name)
            if name not in have:
                res.problems.append(f"{reports / name}:1: missing (the records give this file)")
                continue
            res.problems += compare_text(str(reports / name), (tmp / name).read_text(), (reports / name).read_text())
        covered = set().union(*(rule(reports, res) for rule in RULES.values()))
        res.not_audited = sorted(have - made - covered)
        catalog = load_catalog(tiny, catalog_path)
        for study in catalog.values():
            rules = getattr(study.module, "audit", None)
            if rules is None or not (reports / "data" / f"{study.name}.jsonl").exists():
                continue
            ctx = Context(study, tmp, catalog)
            res.problems += [f"{study.name}: {p}" for p in rules(ctx)]
    return res
