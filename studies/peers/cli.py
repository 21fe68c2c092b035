"""``python -m studies peers ...``: the peer benchmark's command lines (``make bench-peers``),
each a plain library function of this folder called with its options:

- ``compare``: our pendulum and Exudyn's side by side, timed in rounds
  (:mod:`studies.peers.compare`; ``--report``: its record and ``reports/peers.md``);
- ``published``: our Exudyn set-up against Exudyn's own published numbers
  (:mod:`studies.peers.exudyn_published`; ``--report``: its record);
- ``work-precision``: both codes on one work-precision diagram per scene, then the
  deciding points' rounds and, where a target is missed, the step cost
  (:mod:`studies.peers.work_precision`, :mod:`studies.peers.step_cost`), then the report
  (:mod:`studies.peers.precision_report`);
- ``step-cost``: the step cost alone, from the grid's records;
- ``thick-reference``: the continuum reference of the thick scene (DOLFINx,
  :mod:`studies.peers.thick_reference`).

Exudyn runs in ``.venv-peers`` (``tools/setup_peers.sh``); timings are written to records,
never asserted.
"""
from __future__ import annotations

import importlib
import json
import os
from pathlib import Path

from . import compare, exudyn_published, step_cost, thick_reference, work_precision
from .precision_grid import COUNTS, MIN_REPEATS, SCENE, SCENES, STEPS_PER_OUTPUT, elements
from .precision_report import report
from .records import costs_path, points_path, read, read_costs, rounds_path, write_costs
from .venv import PEER_PYTHON

ROOT = Path(__file__).resolve().parents[2]


def _compare(a) -> int:
    if a.report_only:
        compare.write_report()
        return 0
    load0 = os.getloadavg()
    elements = a.element or ["HB2n-12", "HB2n-16"]
    p, os_ = None, [None] * len(elements)
    for _ in range(a.rounds):             # interleaved: the machine's speed drifts on a shared host
        p = compare.pool(p, compare.peer(compare.pendulum_scene(a.dt, a.rho_inf), a.repeats, a.peer_python, a.module),
                         {"solve_s": "solve_median_s", "solve_cpu_s": "solve_cpu_median_s", "build_s": "build_median_s"})
        os_ = [compare.pool(o, compare.ours(a.dt, a.rho_inf, a.repeats, element=e), {"wall_s": "wall_median_s",
                                                                                     "cpu_s": "cpu_median_s"})
               for o, e in zip(os_, elements)]
    load1 = os.getloadavg()
    print("\n\n".join(compare.format_table(o, p, (load0, load1), a.rounds) for o in os_))
    result = {"ours": os_, "exudyn": p, "load": [load0, load1], "rounds": a.rounds}
    if a.json:
        a.json.write_text(json.dumps(result, indent=1))
    if a.report:
        compare.RECORD.parent.mkdir(parents=True, exist_ok=True)
        compare.RECORD.write_text(json.dumps(result, indent=1))
        compare.write_report()
    return 0


def _published(a) -> int:
    rec = exudyn_published.record(exudyn_published.run_peer(a.peer_python, a.module))
    print(exudyn_published.published_markdown(rec))
    if a.report:
        exudyn_published.RECORD.parent.mkdir(parents=True, exist_ok=True)
        exudyn_published.RECORD.write_text(json.dumps(rec, indent=1))
    return 0 if all(k["agrees"] for k in rec["checks"]) else 1


def _work_precision(a) -> int:
    for m in a.imports:
        importlib.import_module(m)
    a.element = a.element or elements()      # after the imports: a user's elements join
    path = points_path(a.out)
    recs = (work_precision.rescore(path) if a.rescore else read(path) if a.report_only
            else work_precision.run(a))
    busy = not (a.rescore or a.report_only) and a.rounds > 0
    rounds = work_precision.retime(recs, a, path) if busy else read(rounds_path(path))
    costs = (write_costs(costs_path(a.out), a.scene, step_cost.measure(recs, rounds, a.scene, a))
             if busy else read_costs(costs_path(a.out)))
    print(report(recs, a.out, rounds, costs))
    return 0


def _step_cost(a) -> int:
    path = points_path(a.out)
    recs, rounds = read(path), read(rounds_path(path))
    write_costs(costs_path(a.out), a.scene, step_cost.measure(recs, rounds, a.scene, a))
    return 0


def _thick_reference(a) -> int:
    doc = thick_reference.compute(a.dt, a.cells_height, a.aspect, a.reuse)
    a.out.parent.mkdir(parents=True, exist_ok=True)
    a.out.write_text(json.dumps(doc, indent=1) + "\n")
    print(doc.get("rule"))
    if doc.get("error_estimate_m"):
        print("max error estimate %.4f mm = %.4f %% of L" % (1e3 * doc["max_error_estimate_m"],
                                                             100 * doc["max_error_estimate_m"] / 0.35))
    return 0


def add_commands(sub) -> None:
    """The ``peers`` command and its sub-commands, on the sub-parsers of ``python -m studies``."""
    pe = sub.add_parser("peers", help="the pendulum beside Exudyn's ANCF cable (in .venv-peers): make bench-peers")
    verbs = pe.add_subparsers(dest="peers_command", required=True)

    c = verbs.add_parser("compare", help="our pendulum and Exudyn's side by side, timed in rounds "
                          "(reports/peers.md)")
    c.set_defaults(peers_run=_compare)
    c.add_argument("--dt", type=float, default=1e-3, help="fixed step, s (default 1e-3: the converged "
                   "step of the 32 x HB2n-12 pendulum)")
    c.add_argument("--rho-inf", type=float, default=0.8, help="generalized-alpha spectral radius (default 0.8)")
    c.add_argument("--repeats", type=int, default=5, help="timed warm runs per solver and round (default 5)")
    c.add_argument("--rounds", type=int, default=7, help="rounds, Exudyn and ours in turn; the medians are "
                   "over all rounds' runs, the verdict over the rounds' ratios (default 7: on 2026-11-26 "
                   "three rounds of one run gave HB2n-12 0.77, 0.39 and 0.86, the machine's speed halving "
                   "and doubling within seconds)")
    c.add_argument("--peer-python", type=Path, default=PEER_PYTHON)
    c.add_argument("--module", choices=("fast", "regular"), default="fast",
                   help="Exudyn's compiled module (default fast: no range checks, AVX2)")
    c.add_argument("--element", action="append", help="our element (repeatable; default HB2n-12 and HB2n-16)")
    c.add_argument("--json", type=Path, help="also write both results as JSON here")
    c.add_argument("--report", action="store_true", help=f"write the record to {compare.RECORD.relative_to(ROOT)} "
                   "and reports/peers.md from it (peers_markdown)")
    c.add_argument("--report-only", action="store_true", help="redraw reports/peers.md from the record, no runs")

    p = verbs.add_parser("published", help="our Exudyn set-up against Exudyn's own published numbers "
                            "(the last section of reports/peers.md)")
    p.set_defaults(peers_run=_published)
    p.add_argument("--module", choices=("fast", "regular"), default="fast",
                   help="Exudyn's compiled module (default fast, as the pendulum comparison)")
    p.add_argument("--peer-python", type=Path, default=None)
    p.add_argument("--report", action="store_true", help=f"write the record {exudyn_published.RECORD.relative_to(ROOT)} "
                   "(`python -m studies peers compare --report-only` then redraws reports/peers.md with its section)")

    w = verbs.add_parser("work-precision", help="both codes on one work-precision diagram per scene "
                                 "(reports/peers_work_precision.md)")
    w.set_defaults(peers_run=_work_precision)
    w.add_argument("--scene", choices=sorted(SCENES), default=SCENE, help="pendulum (h = 5 mm, default) or thick "
                   "(h = 20 mm)")
    w.add_argument("--counts", type=int, nargs="+", default=list(COUNTS))
    w.add_argument("--element", action="append", help="our element (repeatable; default: every registered "
                   "element that runs plane stress, but one tagged locking)")
    w.add_argument("--rho-inf", type=float, default=0.5, help="generalized-alpha spectral radius (default 0.5, "
                   "Table 4's)")
    w.add_argument("--steps-per-output", type=int, nargs="+", default=list(STEPS_PER_OUTPUT),
                   help="the step ladder: dt = 0.1 s / k for each k (default 10 20 40 80 160 320)")
    w.add_argument("--repeats", type=int, default=MIN_REPEATS, help=f"timed warm runs per point (default {MIN_REPEATS})")
    w.add_argument("--peer-python", type=Path, default=PEER_PYTHON)
    w.add_argument("--out", type=Path, default=ROOT / "reports")
    w.add_argument("--import", dest="imports", action="append", default=[],
                   help="a module that registers a user's element (repeatable)")
    w.add_argument("--rounds", type=int, default=7, help="re-time each accuracy's two cheapest points "
                   "alternately in this many rounds after the grid (default %(default)s; 0: none)")
    w.add_argument("--calls", type=int, default=20000, help="calls per compiled timing loop of the step split "
                   "(studies.peers.step_cost, after the rounds, for each row whose target they miss)")
    w.add_argument("--force", action="store_true", help="redo every point (and the rounds)")
    w.add_argument("--report-only", action="store_true", help="redraw the table and figure from the records")
    w.add_argument("--rescore", action="store_true", help="recompute every record's error from its tip history "
                   "against its scene's current reference (no solver runs), then redraw")

    s = verbs.add_parser("step-cost", help="why a missed target is missed, measured from the grid's "
                            "records (data/peers/peers-step-cost.json)")
    s.set_defaults(peers_run=_step_cost)
    s.add_argument("--scene", choices=sorted(SCENES), default=SCENE)
    s.add_argument("--rounds", type=int, default=5)
    s.add_argument("--repeats", type=int, default=5)
    s.add_argument("--calls", type=int, default=20000)
    s.add_argument("--rho-inf", type=float, default=0.5)
    s.add_argument("--peer-python", type=Path, default=PEER_PYTHON)
    s.add_argument("--out", type=Path, default=ROOT / "reports")

    t = verbs.add_parser("thick-reference", help="the thick scene's continuum reference (DOLFINx; "
                                  "data/peers/thick-pendulum-reference.json)")
    t.set_defaults(peers_run=_thick_reference)
    t.add_argument("--cells-height", type=int, default=8)
    t.add_argument("--aspect", type=float, default=2.0)
    t.add_argument("--dt", type=float, default=1e-3)
    t.add_argument("--out", type=Path, default=thick_reference.PATH)
    t.add_argument("--reuse", type=Path, nargs="*", default=[], help="earlier files of this command whose runs "
                   "(same cells and dt) are taken instead of recomputed")


def run(args) -> int:
    """The chosen ``peers`` sub-command."""
    return args.peers_run(args)
