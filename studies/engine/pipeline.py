"""The pipeline of ``python -m studies run``: the named studies (and those they need)
run into an output directory, then every table, figure and the README rebuilt from the
records. The command line (:mod:`studies.cli`) and the tiny-mode gold check
(:mod:`studies.engine.regression`) both call it.
"""
from __future__ import annotations

import os
import tempfile
import time
from pathlib import Path

from .catalog import CASES_TOML, load_catalog, with_needs
from .worker import DEFAULT_TIMEOUT_S

REPORTS = Path(__file__).resolve().parents[2] / "reports"


def resolve_out(out: str | None, tiny: bool) -> Path:
    if out:
        return Path(out)
    if tiny:
        return Path(tempfile.mkdtemp(prefix="studies-tiny-"))
    return REPORTS


def run_studies(names: list[str], out: Path, tiny: bool = False, force: bool = False,
                executor: str | None = None, workers: int = 2, progress: bool = True,
                log=print, catalog_path: Path = CASES_TOML, timeout_s: float | None = None,
                dry: bool = False) -> dict[str, float]:
    """Run the named studies (``["all"]``: every one but the ``full`` ones outside tiny
    mode; ``["full"]``: the ``full`` ones) and their needs into ``out``,
    then rebuild the reports; return {study: seconds}. ``dry``: say per study how many
    cases would be reused and how many run, and run nothing (no report is rebuilt)."""
    from .scheduler import dry_run, run_cases
    from .store import store_for

    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(var, "1")  # one thread per worker process
    catalog = load_catalog(tiny, catalog_path)
    explicit = ([n for n, s in catalog.items() if s.in_all] if names == ["all"]
                else [n for n, s in catalog.items() if s.full] if names == ["full"] else names)
    times = {}
    for study in with_needs(catalog, explicit):
        cases = study.cases()
        limit = timeout_s or study.grid.get("timeout_s") or DEFAULT_TIMEOUT_S
        if dry:
            s = dry_run(study.name, cases, store_for(out, study.name), force and study.name in explicit, limit)
            log(f"{study.name}: {s.cases} cases, {s.reused} reused, {s.computed} to compute (dry run)")
            times[study.name] = 0.0
            continue
        s = run_cases(study.name, cases, store_for(out, study.name), executor, workers,
                      force=force and study.name in explicit, progress=progress,
                      timeout_s=limit)
        times[study.name] = s.seconds
        log(f"{study.name}: {s.cases} cases, {s.reused} reused, {s.computed} computed, "
            f"{s.failed} failed, {s.seconds:.1f} s")
        for f in s.failures[:20]:
            log(f"  failed: {f}")
    if dry:
        return times
    t0 = time.perf_counter()
    from . import stamp
    if stamp.current(out):
        log("reports: as the last full audit stamped them (records, report code and every report file "
            "unchanged); not rebuilt")
    else:
        build_reports(out, tiny, log, catalog_path)
    _quote(out, log)
    times["(reports)"] = time.perf_counter() - t0
    return times


def build_reports(out: Path, tiny: bool = False, log=print, catalog_path: Path = CASES_TOML) -> Path:
    """Tables, figures and README.md from the records in ``out``/data (no solver runs), and the
    project README's quotes of them (:func:`_quote`)."""
    from .report import Context, write_readme
    from .store import store_for

    catalog = load_catalog(tiny, catalog_path)
    sections = []
    out.mkdir(parents=True, exist_ok=True)
    for study in catalog.values():
        if not store_for(out, study.name).path.exists():
            continue
        try:
            sections.append(study.module.report(Context(study, out, catalog)))
        except Exception as e:  # name the study, then fail loudly
            log(f"{study.name}: report failed: {type(e).__name__}: {e}")
            raise
    path = write_readme(out, sections, tiny)
    _quote(out, log)
    return path


def _quote(out: Path, log=print) -> None:
    """The project README's quotes of the reports rewritten from them, when ``out`` is
    ``reports/`` (every command that rebuilds reports there: a study run, a card, a report)."""
    if Path(out).resolve() == REPORTS.resolve():
        from .readme import refresh
        if refresh():
            log("README.md: its quotes of the reports rewritten")
