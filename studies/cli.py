"""``python -m studies``: list, run and report the studies (each declared in its module: ``STUDY``).

- ``list``: the studies, their case counts and what each needs;
- ``run NAME [NAME ...] | all | full``: run the studies (and those they need; ``all``: every
  one but the ``full = true`` ones; ``full``: those, as ``make study-full`` runs them), reusing finished
  records; ``--force`` recomputes the named ones; ``--tiny`` runs the CI grids into
  ``--out DIR`` (default: a new temporary directory, never reports/); then rebuilds
  every table, figure and the README from the records; prints the time per study;
- ``report``: rebuild tables, figures and README from the records only;
- ``gold [--refresh]``: run every study in tiny mode and compare its named values with
  tests/gold/studies_tiny.json (``--refresh`` rewrites that file instead);
- ``audit [--reports DIR] [--full]``: every report of DIR (default reports/) rebuilt from
  DIR/data in a temporary directory and compared line by line (:mod:`studies.engine.audit`);
  exits 1 naming file and line of each mismatch; never runs a solver; a pass stamps the
  inputs and the reports (:mod:`studies.engine.stamp`), and while both are unchanged the
  next audit says so without rebuilding (``--full``: rebuild anyway); without ``--reports`` it
  first checks README.md and the documentation pages: their quotes of the reports, their
  numbers (:mod:`studies.engine.claims`) and their comparisons in words
  (:mod:`studies.engine.comparisons`);
- ``diff OLD NEW``: the records of two output directories compared case by case
  (:mod:`studies.engine.diff`): which results changed, and by how much;
- ``verify --sample N [--seed S] [--budget S] [--max-case-s S]``: N randomly drawn committed
  records recomputed with today's code and compared field by field
  (:mod:`studies.engine.verify`); exits 1 naming record and field of each mismatch;
- ``card NAME [NAME ...] [--import MODULE]``: the element report card (:mod:`studies.design.card`),
  ``paper`` for the four paper elements; written to ``<out>/cards/``; ``card --solver
  DECLARATION``: an external solver's element, the sections that need only runs
  (:mod:`studies.external.card`);
- ``external DECLARATION NAME [NAME ...] [--out DIR]``: the ANCF cases of the named studies
  run on an external solver declared in a TOML file (:mod:`studies.external`), those it
  does not declare skipped with the reason; records in ``DIR/data/<study>@<solver>.jsonl``;
- ``check-record FILE [FILE ...]``: a record checked against the schema
  (:mod:`contract.record_schema`), each problem naming its key; exits 1 if any;
- ``peers compare | published | work-precision | step-cost | thick-reference``: the
  pendulum beside Exudyn's ANCF cable, in ``.venv-peers`` (:mod:`studies.peers.cli`;
  ``make bench-peers``);
- ``bench [table3 | penalty | pendulum | kernels | all]``: timings of the paper's cells, the
  penalty sweep, the Table 4 grid and the compiled kernels (:mod:`studies.design.bench`;
  ``make bench``, ``make bench-penalty``);
- ``loops [--keep DIR]``: the five loops a user waits on, in a fresh clone
  (:mod:`studies.loops`; ``make loops``);
- ``slenderness-gold [--laws L ...] [--out FILE]``: the continuum references of the cards'
  slenderness sweep, tests/gold/fem_slenderness.json (:mod:`studies.verification.slenderness_gold`);
- ``continuum gold | pendulum | report``: the continuum's gold files (tests/gold/fem_*.json),
  the pendulum's convergence check and the gold files' tables
  (:mod:`studies.verification.continuum_gold.cli`).

Clusters: ``mpiexec -n N python -m mpi4py.futures -m studies run all --executor mpi``.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from contract.console import command

from .engine.catalog import CASES_TOML, get_study, load_catalog
from .engine.worker import DEFAULT_TIMEOUT_S
from .engine.pipeline import build_reports, resolve_out, run_studies
from . import loops
from .design import bench
from .peers import cli as peers
from .verification import slenderness_gold
from .verification.continuum_gold import cli as continuum

def _list(args) -> int:
    catalog = load_catalog(args.tiny, args.catalog)
    for s in catalog.values():
        needs = f"  (needs {', '.join(s.needs)})" if s.needs else ""
        needs += "  [not in 'all': make study-full]" if not s.in_all else ""
        print(f"{s.name:15s} {len(s.cases()):5d} cases  {s.title}{needs}")
    return 0


def _run(args) -> int:
    from contract.console import import_modules

    from .engine import catalog as catalogs

    out = resolve_out(args.out, args.tiny)
    import_modules(args.imports)
    catalogs.IMPORTED.extend(args.imports)        # their elements join the studies
    catalog = load_catalog(args.tiny, args.catalog)
    if args.names not in (["all"], ["full"]):
        for n in args.names:
            get_study(catalog, n)
    print(f"output: {out}")
    t0 = time.perf_counter()
    times = run_studies(args.names, out, args.tiny, args.force, args.executor, args.workers,
                        progress=not args.no_progress, catalog_path=args.catalog, timeout_s=args.timeout,
                        dry=args.dry_run)
    if args.dry_run:
        return 0
    print("\ntime per study:")
    for k, v in times.items():
        print(f"  {k:15s} {v:8.1f} s")
    print(f"  {'total':15s} {time.perf_counter() - t0:8.1f} s")
    print(f"report: {out / 'README.md'}")
    return 0


def _report(args) -> int:
    out = resolve_out(args.out, False) if not args.tiny or args.out else None
    if out is None:
        print("report --tiny needs --out DIR (the directory of a tiny run)", file=sys.stderr)
        return 2
    print(build_reports(out, args.tiny, catalog_path=args.catalog))
    return 0


def _diff(args) -> int:
    from .engine.diff import diff

    rename = {}
    for pair in args.rename:
        old, sep, new = pair.partition("=")
        if not (sep and old and new):
            print(f"--rename: {pair!r}; expected OLD=NEW", file=sys.stderr)
            return 2
        rename[old] = new
    changes, summary = diff(Path(args.old), Path(args.new), args.rtol, args.atol, rename)
    for c in changes:
        print(c)
    print(f"{'study':15s} {'matched':>8s} {'only old':>9s} {'only new':>9s} {'changed':>8s}")
    for study, (m, a, b, c) in summary.items():
        print(f"{study:15s} {m:8d} {a:9d} {b:9d} {c:8d}")
    return 1 if changes else 0


def _audit(args) -> int:
    from .engine.audit import audit
    from .engine.pipeline import REPORTS

    from .engine import stamp

    reports = Path(args.reports) if args.reports else REPORTS
    if not args.reports:      # the README's quotes of the reports and the loops record, the pages' numbers
        from .engine import claims, comparisons    # and comparisons in words, at every audit
        from .engine.readme import problems
        from .loops import record_problems
        quote = problems() + record_problems() + claims.problems() + comparisons.problems()
        for p in quote:
            print(p)
        if quote:
            return 1
    if not args.full and stamp.current(reports):
        print(f"audit: {reports}: the records, the report code and every report file are as the last full "
              f"audit stamped them ({stamp.path(reports).name}); OK (--full rebuilds anyway)")
        return 0
    res = audit(reports, args.catalog, args.tiny)
    for p in res.problems:
        print(p)
    if res.not_audited:
        print(f"not audited (no study writes them): {', '.join(res.not_audited)}")
    print(f"audit: {len(res.checked)} files rebuilt from the records of {reports / 'data'}; "
          + ("OK" if res.ok else f"{len(res.problems)} mismatch(es)"))
    if res.ok:
        stamp.write(reports)
    return 0 if res.ok else 1


def _verify(args) -> int:
    from .engine.pipeline import REPORTS
    from .engine.verify import verify

    reports = Path(args.reports) if args.reports else REPORTS
    t0 = time.perf_counter()
    res = verify(reports, args.sample, args.seed, args.budget, args.max_case_s, args.workers)
    print(f"verify: seed {res.seed}; {res.candidates} records reusable today ({res.stale} not: their code or "
          f"scene changed), skipped: {', '.join(f'{v} {k}' for k, v in sorted(res.skipped.items())) or 'none'}")
    for p in res.problems:
        print(p)
    print(f"verify: {len(res.checked)} recomputed in {time.perf_counter() - t0:.0f} s"
          + (f", {res.not_started} not started (budget {args.budget:g} s)" if res.not_started else "")
          + (": OK" if res.ok else f": {len(res.problems)} mismatch(es)"))
    return 0 if res.ok else 1


def _positive(kind):
    def parse(text: str):
        try:
            v = kind(text)
        except ValueError:
            v = None
        if v is None or not v > 0:
            raise argparse.ArgumentTypeError(f"must be a {'whole ' if kind is int else ''}number > 0, got {text!r}")
        return v
    return parse


def _gold(args) -> int:
    from .engine.regression import check_gold, refresh_gold

    out = resolve_out(args.out, True)
    if args.refresh:
        path = refresh_gold(out)
        print(f"wrote {path}")
        return 0
    problems = check_gold(out)
    for p in problems:
        print(p)
    print("gold: OK" if not problems else f"gold: {len(problems)} mismatch(es)")
    return 1 if problems else 0


def _card(args) -> int:
    from ancf.elements import select
    from contract.console import import_modules

    from .design.card import run_cards

    if args.solver:
        from .external.card import run_external_cards

        out = Path(args.out) if args.out else Path("reports") / "external"
        for path in run_external_cards(args.solver, args.names, out, args.tiny, args.force, args.dry_run):
            print(f"card: {path}")
        return 0
    if not args.names:
        raise SystemExit("card: name an element, 'paper' or 'all' (or --solver DECLARATION)")
    out = resolve_out(args.out, args.tiny)
    import_modules(args.imports)          # before "all": the user's elements are registered
    groups = {"paper": select("paper"), "all": select()}
    names = list(dict.fromkeys(e for n in args.names for e in groups.get(n, (n,))))
    for path in run_cards(names, out, args.tiny, args.imports, args.workers, not args.no_progress, args.force,
                          dry=args.dry_run):
        print(f"card: {path}")
    return 0


class _Parser(argparse.ArgumentParser):
    """A bad command line is one line: the command and what is wrong (``-h`` shows usage)."""

    def error(self, message: str):
        self.exit(2, f"{self.prog}: {message} (-h: usage)\n")


def parser() -> argparse.ArgumentParser:
    """The command line's parser (importable: the documentation renders it)."""
    p = _Parser(prog="python -m studies", description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="command", required=True)
    ls = sub.add_parser("list", help="name the studies")
    ls.add_argument("--tiny", action="store_true")
    r = sub.add_parser("run", help="run studies (NAME ..., all: the main job's, full: the others)")
    r.add_argument("names", nargs="+", metavar="NAME")
    r.add_argument("--tiny", action="store_true", help="CI grids (few elements, coarse meshes)")
    r.add_argument("--out", help="output directory (default reports/, or a temp dir with --tiny)")
    r.add_argument("--force", action="store_true", help="recompute the named studies' cases")
    r.add_argument("--executor", choices=("pool", "mpi", "serial"),
                   help="default: mpi under mpiexec, else a local process pool")
    r.add_argument("--workers", type=int, default=2, help="pool size (default 2)")
    r.add_argument("--no-progress", action="store_true")
    r.add_argument("--dry-run", action="store_true",
                   help="say per study how many cases would be reused and how many computed; run nothing")
    r.add_argument("--timeout", type=float, default=None,
                   help="seconds per solver run before it is stopped and recorded as failed (default: the "
                        f"study's grid key timeout_s, else {DEFAULT_TIMEOUT_S:g})")
    r.add_argument("--import", dest="imports", action="append", default=[], metavar="MODULE",
                   help="import a module first: the elements it registers join every study that runs them "
                        "(repeatable; write to another --out than reports/)")
    rp = sub.add_parser("report", help="rebuild tables, figures and README from records")
    rp.add_argument("--tiny", action="store_true")
    rp.add_argument("--out")
    df = sub.add_parser("diff", help="compare the records of two output directories case by case")
    df.add_argument("old")
    df.add_argument("new")
    df.add_argument("--rtol", type=float, default=1e-6, help="relative tolerance of tips and energies")
    df.add_argument("--atol", type=float, default=1e-9, help="absolute tolerance (m, J)")
    df.add_argument("--rename", action="append", default=[], metavar="OLD=NEW",
                    help="a solver or study renamed between the two (repeatable): the old records paired under "
                         "the new name")
    au = sub.add_parser("audit", help="rebuild every report from its records and compare, naming file and line")
    au.add_argument("--reports", help="the reports directory (default reports/)")
    au.add_argument("--tiny", action="store_true", help="the reports of a tiny run")
    au.add_argument("--full", action="store_true", help="rebuild and compare even when the stamp of the last "
                                                        "full audit matches")
    g = sub.add_parser("gold", help="tiny-mode golden values: check, or --refresh")
    g.add_argument("--refresh", action="store_true", help="rewrite tests/gold/studies_tiny.json")
    g.add_argument("--out", help="directory for the tiny run (default: a temp dir)")
    v = sub.add_parser("verify", help="recompute N randomly drawn committed records and compare every result field")
    v.add_argument("--sample", type=_positive(int), required=True, metavar="N", help="how many records")
    v.add_argument("--seed", type=int, help="the draw's seed (default: a new one, printed)")
    v.add_argument("--budget", type=_positive(float), default=600.0, metavar="SECONDS",
                   help="start no case after this many seconds (default %(default)g)")
    v.add_argument("--max-case-s", type=_positive(float), default=60.0, metavar="SECONDS",
                   help="draw only records whose run took at most this long (default %(default)g)")
    v.add_argument("--reports", help="the reports directory (default reports/)")
    v.add_argument("--workers", type=_positive(int), default=2)
    c = sub.add_parser("card", help="element report cards (NAME ..., or paper)")
    c.add_argument("names", nargs="*", metavar="NAME",
                   help="an element, 'paper' (the paper's four) or 'all' (every registered element, the "
                        "--import modules' too); with --solver, the elements it runs by name (none for a "
                        "solver with its own element)")
    c.add_argument("--solver", metavar="DECLARATION", action="append",
                   help="the card's run-only sections on an external solver declared in a TOML file "
                        "(repeatable; default --out reports/external)")
    c.add_argument("--import", dest="imports", action="append", default=[], metavar="MODULE",
                   help="a module to import first (it registers the user's element); repeatable")
    c.add_argument("--tiny", action="store_true", help="the CI grid")
    c.add_argument("--out", help="output directory (default reports/, or a temp dir with --tiny)")
    c.add_argument("--force", action="store_true", help="recompute the cards' runs and checks")
    c.add_argument("--workers", type=int, default=2)
    c.add_argument("--no-progress", action="store_true")
    c.add_argument("--dry-run", action="store_true",
                   help="say per card how many runs would be reused and computed and whether its checks are "
                        "current; run nothing")
    x = sub.add_parser("external", help="run studies' ANCF cases on an external solver declared in a TOML file")
    x.add_argument("declaration", help="the solver's declaration (TOML)")
    x.add_argument("names", nargs="+", metavar="NAME", help="studies whose ANCF cases it runs")
    x.add_argument("--out", help="output directory (default reports/external)")
    x.add_argument("--tiny", action="store_true", help="the studies' CI grids")
    cr = sub.add_parser("check-record", help="check record files against the record schema, naming each bad key")
    cr.add_argument("files", nargs="+", metavar="FILE")
    continuum.add_commands(sub)
    peers.add_commands(sub)
    bench.add_commands(sub)
    loops.add_commands(sub)
    slenderness_gold.add_commands(sub)
    for sp in (ls, r, rp, au):
        sp.add_argument("--catalog", type=Path, default=CASES_TOML,
                        help="a TOML file of study tables to run instead of the studies declared in their modules "
                             "(a test's case list)")
    return p


def _external(args) -> int:
    from .external.protocol import run_study

    out = Path(args.out) if args.out else Path("reports") / "external"
    summary = run_study(args.declaration, args.names, out, tiny=args.tiny)
    print(f"records: {out / 'data'} ({sum(s['failed'] for s in summary.values())} failed runs, each with its "
          "status and reason)")
    return 0


def _check_record(args) -> int:
    from contract.record_schema import read

    bad = 0
    for path in args.files:
        _, found = read(path)
        for p in found:
            print(f"{path}: {p}")
        if not found:
            print(f"{path}: OK")
        bad += bool(found)
    return 1 if bad else 0


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    run = {"list": _list, "run": _run, "report": _report, "gold": _gold, "diff": _diff, "card": _card,
           "audit": _audit, "verify": _verify, "external": _external, "check-record": _check_record,
           "continuum": continuum.run, "peers": peers.run,
           "bench": bench.command, "loops": loops.command, "slenderness-gold": slenderness_gold.command}[args.command]
    return command("studies", lambda: run(args), errors=(ValueError, ImportError),
                   interrupt_note=" (every finished record is kept; a rerun does the rest)")


if __name__ == "__main__":
    sys.exit(main())
