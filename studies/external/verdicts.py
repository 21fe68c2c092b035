"""An external solver on the harness's references: the benchmark suite's verdicts
(:func:`studies.verification.benchmarks.rows`, the same references, tolerances and rules)
computed from that solver's records, and what it was not run on, with the reason.

:func:`benchmark_report` writes ``<out>/benchmarks@<solver>.md`` from the records of
``<out>/data/benchmarks@<solver>.jsonl`` alone (no run), so it can be rebuilt at any time.
"""
from __future__ import annotations

from pathlib import Path

from ..engine.catalog import load_catalog
from ..engine.store import store_for
from .declaration import Declaration


class _Records:
    """The little of a report context the benchmark rows read: the study and its records."""

    def __init__(self, study, recs: list[dict]):
        self.study, self._recs = study, recs

    def records(self, name: str | None = None) -> list[dict]:
        return self._recs


def benchmark_rows(out: Path, decl: Declaration, tiny: bool = False) -> list:
    """The benchmark rows of the solver's records, each labelled with the solver (and its
    own element, where it has one)."""
    from ..verification import benchmarks

    study = load_catalog(tiny=tiny)["benchmarks"]
    recs = list(store_for(out, f"benchmarks@{decl.name}").read().values())
    label = f"{decl.name} {decl.element}" if decl.element else decl.name
    ran = {r["scene"]["ancf"]["element"] for r in recs if r.get("scene", {}).get("ancf")}
    rows = [r for r in benchmarks.rows(_Records(study, recs)) if r.solver in ran]
    for r in rows:
        r.solver = label if decl.element else f"{decl.name} {r.solver}"
    return rows


def _fmt(x, spec: str) -> str:
    return "-" if x is None else format(x, spec)


def benchmark_report(out: Path, decl: Declaration, skipped: list[tuple[str, str]], tiny: bool = False) -> Path:
    """``<out>/benchmarks@<solver>.md``: every case the solver ran with its verdict, each
    miss with its cause (the declaration's ``[causes]``: {case kind: why}, else "cause not
    found"), and every case it was not run on with the reason."""
    rows = benchmark_rows(out, decl, tiny)
    causes = decl.causes
    passed = sum(r.verdict == "pass" for r in rows)
    lines = [f"# {decl.name} on the harness's references", "",
             f"The benchmark suite's cases run on `{decl.name}` {decl.version} through its declaration "
             f"(`{decl.path.name}`), judged by the suite's own references and tolerances "
             "(`studies/verification/benchmarks.py`). "
             f"{passed} of {len(rows)} cases run pass; {len(skipped)} cases were not run (outside its declaration).",
             "", "| case | solver | quantity | reference | value | error | tolerance | verdict | cause of a miss |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        cause = ""
        if r.verdict != "pass":
            cause = causes.get(r.case.split()[0]) or r.cause or "cause not found"
        lines.append(f"| {r.case} | {r.solver} | {r.quantity} | {_fmt(r.reference, '.6g')} | {_fmt(r.value, '.6g')} "
                     f"| {_fmt(r.error, '.2e')} | {r.tolerance:.2g} | {r.verdict} | {cause} |")
    if skipped:
        kinds: dict = {}
        for name, why in skipped:
            kinds.setdefault(why, []).append(name)
        lines += ["", "Not run (outside the declaration):", ""]
        lines += [f"- {len(names)} cases: {why} (e.g. `{names[0]}`)" for why, names in sorted(kinds.items())]
    path = Path(out) / f"benchmarks@{decl.name}.md"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n")
    return path
