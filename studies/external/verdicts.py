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
    lines += _not_run(skipped)
    path = Path(out) / f"benchmarks@{decl.name}.md"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n")
    return path


def dynamic_rows(out: Path, decl: Declaration, element: str, tiny: bool = False) -> list[list]:
    """[case, solver, quantity, reference, measured, relative error, tolerance, verdict] of the
    solver's dynamic-benchmark records: the rigid swing and the clamped beam's frequency, each
    scene found by the name the study gives it for ``element`` (the discrete gradient's
    energy case is an element's integrator, not a solver's: not judged here)."""
    from ..verification import dynamic_benchmarks as db
    from ..verification.dynamics_stability import SWING_TOL, rigid_swing_reference, swing_time

    g = load_catalog(tiny=tiny)["dynamic-benchmarks"].grid
    recs = {r["scene"]["name"]: r for r in store_for(out, f"dynamic-benchmarks@{decl.name}").read().values()}
    label = f"{decl.name} {element}"
    rows = []
    rec = recs.get(db.swing_scene(g, element)["name"])
    if rec is not None:
        T = rigid_swing_reference()
        ts = swing_time(rec) if rec.get("status") == "converged" else None
        err = None if ts is None else ts / T - 1
        rows.append(["rigid-swing", label, "swing time (s)", T, ts, err, SWING_TOL, db._verdict(err, SWING_TOL, rec)])
    for ratio in g["ratios"]:
        rec = recs.get(db.frequency_scene(g, ratio, element)["name"])
        if rec is None:
            continue
        ref = db.frequency_reference(g, ratio)
        om = db.measured_frequency(rec)
        err = None if om is None else om / ref["timoshenko"] - 1
        rows.append([f"clamped-frequency L/h {ratio:g}", label, "omega_1 (rad/s)", ref["timoshenko"], om, err,
                     ref["tolerance"], db._verdict(err, ref["tolerance"], rec)])
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
        cause = "" if verdict == "meets" else decl.causes.get(case.split()[0]) or "cause not found"
        lines.append(f"| {case} | {solver} | {quantity} | {_fmt(ref, '.6g')} | {_fmt(val, '.6g')} | {_fmt(err, '+.2e')} "
                     f"| {tol:.2e} | {verdict} | {cause} |")
    lines += _not_run(skipped)
    path = Path(out) / f"dynamic-benchmarks@{decl.name}.md"
    path.write_text("\n".join(lines) + "\n")
    return path


def _not_run(skipped: list[tuple[str, str]]) -> list[str]:
    if not skipped:
        return []
    kinds: dict = {}
    for name, why in skipped:
        kinds.setdefault(why, []).append(name)
    return (["", "Not run (outside the declaration):", ""]
            + [f"- {len(names)} cases: {why} (e.g. `{names[0]}`)" for why, names in sorted(kinds.items())])
