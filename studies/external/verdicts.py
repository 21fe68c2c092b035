"""An external solver on the harness's references: the benchmark suite's verdicts
(:func:`studies.verification.benchmarks.rows`, the same references, tolerances and rules)
and the dynamic benchmarks' (:mod:`studies.verification.dynamic_benchmarks`: the same scenes,
references, tolerances and verdict words) computed from that solver's records, and what it
was not run on, with the reason.

:func:`benchmark_report` writes ``<out>/benchmarks@<solver>.md`` from the records of
``<out>/data/benchmarks@<solver>.jsonl`` alone (no run), so it can be rebuilt at any time;
:func:`dynamic_report` writes ``<out>/dynamic-benchmarks@<solver>.md`` likewise.
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
    from ..verification.benchmark_rows import bending_rows

    study = load_catalog(tiny=tiny)["benchmarks"]
    recs = list(store_for(out, f"benchmarks@{decl.name}").read().values())
    label = f"{decl.name} {decl.element}" if decl.element else decl.name
    ran = {r["scene"]["ancf"]["element"] for r in recs if r.get("scene", {}).get("ancf")}
    ctx = _Records(study, recs)
    rows = [r for r in benchmarks.rows(ctx) if r.solver in ran]
    if decl.element:     # the pure-bending pairs are found by their element's name
        taken = lambda feature, v: v in decl.supports.get(feature, (v,))
        rows += [r for r in bending_rows(ctx, lambda form: [decl.element])
                 if taken("laws", r.case.split()[1]) and taken("formulations", r.case.split()[2])
                 and taken("loads", "end_moment") and taken("supports", "slide")]
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
            cause = cause_of_miss(decl, r.case, r.cause)
        lines.append(f"| {r.case} | {r.solver} | {r.quantity} | {_fmt(r.reference, '.6g')} | {_fmt(r.value, '.6g')} "
                     f"| {_fmt(r.error, '.2e')} | {r.tolerance:.2g} | {r.verdict} | {cause} |")
    lines += _not_run(skipped)
    path = Path(out) / f"benchmarks@{decl.name}.md"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n")
    return path


def dynamic_rows(out: Path, decl: Declaration, element: str, tiny: bool = False) -> list[list]:
    """The dynamic benchmarks' rows (:func:`studies.verification.dynamic_benchmarks.rows`) of
    the solver's records, for the scenes the study names after ``element`` that it ran (the
    discrete gradient's energy case is an element's integrator, not a solver's: not judged
    here), each labelled with the solver."""
    from ..verification import dynamic_benchmarks

    study = load_catalog(tiny=tiny)["dynamic-benchmarks"]
    recs = list(store_for(out, f"dynamic-benchmarks@{decl.name}").read().values())
    rows = [r for r in dynamic_benchmarks.rows(_Records(study, recs), [element]) if r[-1] != "no record"]
    for r in rows:
        r[1] = f"{decl.name} {element}"
    return rows


def dynamic_report(out: Path, decl: Declaration, skipped: list[tuple[str, str]], tiny: bool = False) -> Path:
    """``<out>/dynamic-benchmarks@<solver>.md``: every dynamic benchmark the solver ran, its
    verdict and each miss's declared cause, and what it was not run on, with the reason."""
    element = decl.element or "its element"
    rows = dynamic_rows(out, decl, element, tiny)
    met = sum(r[-1] == "meets" for r in rows)
    lines = [f"# {decl.name} on the harness's dynamic references", "",
             f"The dynamic benchmarks run on `{decl.name}` {decl.version} through its declaration "
             f"(`{decl.path.name}`), judged by the study's own references and tolerances "
             "(`studies/verification/dynamic_benchmarks.py`): the near-rigid pendulum's swing time against the rigid "
             "compound pendulum's, a clamped beam's first frequency against Timoshenko's. "
             f"{met} of {len(rows)} cases run meet their reference.", "",
             "| case | solver | quantity | reference | measured | relative error | tolerance | verdict | cause of a miss |",
             "|---|---|---|---|---|---|---|---|---|"]
    for case, solver, quantity, ref, val, err, tol, verdict in rows:
        cause = "" if verdict == "meets" else cause_of_miss(decl, case)
        lines.append(f"| {case} | {solver} | {quantity} | {_fmt(ref, '.6g')} | {_fmt(val, '.6g')} | {_fmt(err, '+.2e')} "
                     f"| {tol:.2e} | {verdict} | {cause} |")
    lines += _not_run(skipped)
    path = Path(out) / f"dynamic-benchmarks@{decl.name}.md"
    path.write_text("\n".join(lines) + "\n")
    return path


def not_run_lines(skipped: list[tuple[str, str]], noun: str = "cases") -> list[str]:
    """One line per reason of what was not run: how many, why, an example."""
    kinds: dict = {}
    for name, why in skipped:
        kinds.setdefault(why, []).append(name)
    return [f"- {len(names)} {noun}: {why} (e.g. `{names[0]}`)" for why, names in sorted(kinds.items())]


def _not_run(skipped: list[tuple[str, str]]) -> list[str]:
    return ["", "Not run (outside the declaration):", "", *not_run_lines(skipped)] if skipped else []


def cause_of_miss(decl: Declaration, case: str, found: str = "") -> str:
    """Why the solver misses ``case``: the declaration's cause for its kind (its first word),
    else the one the suite found (``found``), else "cause not found"."""
    return decl.causes.get(case.split()[0]) or found or "cause not found"
