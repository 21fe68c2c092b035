"""Do the committed records still follow from today's code? Recompute a random sample.

``python -m studies verify --sample N [--seed S] [--budget SECONDS] [--max-case-s SECONDS]
[--reports DIR]`` draws N records from ``DIR/data`` that the engine would reuse today (their
case id is the one today's code gives their case: same scene, options and fingerprint),
runs each case again with today's code (a process pool of one-thread workers, as the
studies run), and compares every result field of the new record with the stored one:

- text, flags and counts exactly (status, the reason's class, stability verdict, step and
  iteration counts, the rule that ran, ...);
- numbers within ``VERIFY_FACTOR x newton_rtol`` of their scale (the run's own Newton
  tolerance, from its scene; 1e-8 when it names none): a rerun of the same code differs
  from its record by round-off, which each Newton solve leaves far below the tolerance it
  stops at; the scale of a number inside a history (a tip path, an energy history) is the
  largest magnitude of that history, of a tip component (``tip``, and the 3D model's
  ``tip_uz``, zero by symmetry) the tip's largest, of any other number its own magnitude;
- two fields whose round-off is larger, each by its own rule. ``newton_iterations``
  within one iteration per Newton solve (each solve stops where its residual crosses the
  tolerance, and round-off, e.g. another CPU's fused multiply-adds in the compiled
  loops, can move that crossing by one iteration): the solves are the record's load
  increments and relaxation steps, or its accepted and rejected time steps.
  ``lowest_eigenvalue`` with the same sign and within ``EIGEN_RTOL``: the smallest
  eigenvalue of a tangent whose condition number reaches 1e12 (a slender beam's
  bending against its stretching) carries a relative round-off of machine epsilon times
  that, 2e-4. Energies (``potential_energy``, the energy history) also within their
  round-off floor, :func:`energy_floor`: a beam bent in the linear regime stores 1e-10 J
  computed from invariants near 3, so its last digits are round-off (seen: a slender
  probe's potential energy, 1.46e-10 J, moved by 1.1e-16 J when an HB2n-20xypm case had
  run before it in the same process; the compiled and the numpy energy of that state
  differ by 4e-16 J).

Timings (every ``*_s`` field, ``timing``, ``effect_costs``, ``cold``) and where it ran
(``host``, ``pid``, ``run``, ``versions``) are not results and are never compared.
Skipped, and said so: records made only to time something (solvers ``ancf-cold`` and
``ancf-effects``), records of MPI launches (``mpi_ranks``), runs stopped by a time limit,
and records drawn past ``--max-case-s`` of their own recorded run time. The draw stops
starting new cases when ``--budget`` seconds have passed. The seed is printed, so a
failure can be drawn again. Exit status 1 names record and field of every mismatch.
"""
from __future__ import annotations

import concurrent.futures as cf
import json
import math
import multiprocessing
import os
import random
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from typing import Callable

from contract.registry import Registry
from reference_fem.backends import BACKENDS

from .case import Case

TIMING_ONLY = ("ancf-cold", "ancf-effects")
NOT_RESULTS = {"pid", "run", "host", "versions", "case", "case_id", "timing", "effect_costs", "cold",
               "traceback", "transient"}


def not_results() -> set[str]:
    """Record keys that are no result: :data:`NOT_RESULTS` and each continuum backend's name
    (a continuum record carries its backend's versions under it), from the backends' registry
    (:data:`reference_fem.backends.BACKENDS`), so a new backend needs no line here."""
    return NOT_RESULTS | set(BACKENDS)
VERIFY_FACTOR = 10.0
DEFAULT_RTOL = 1e-8
EIGEN_RTOL = 1e-3
ENERGY_FLOOR = 10.0


@dataclass
class Drawn:
    study: str
    record: dict
    case: Case


@dataclass
class Outcome:
    seed: int
    candidates: int = 0
    stale: int = 0
    skipped: dict = field(default_factory=dict)
    checked: list = field(default_factory=list)       # (study, name, seconds)
    problems: list = field(default_factory=list)      # "study: name: field: old -> new"
    not_started: int = 0

    @property
    def ok(self) -> bool:
        return not self.problems


def _skip_reason(rec: dict, max_case_s: float) -> str | None:
    case = rec.get("case") or {}
    if rec.get("solver") in TIMING_ONLY:
        return "timing only"
    if (case.get("options") or {}).get("mpi_ranks"):
        return "MPI launch"
    if rec.get("timed_out"):
        return "stopped by a time limit"
    if (rec.get("elapsed_s") or 0.0) > max_case_s:
        return f"longer than {max_case_s:g} s"
    return None


# record stores made outside the studies' catalog (the element cards), each a function of
# the reports directory giving {store name: {case id: case}} as today's code makes them
CASE_SOURCES: Registry[Callable[[Path], dict]] = Registry("verify.source", "case source")


def register_case_source(name: str, source: Callable[[Path], dict]) -> None:
    CASE_SOURCES.register(name, source, sys._getframe(1).f_globals.get("__name__", "__main__"))


def todays_cases(reports: Path, catalog_path=None) -> dict[str, dict[str, Case]]:
    """{store name: {case id: case}}: every study's cases (the ``full`` ones too) and those of
    every registered case source (the element cards), as today's code makes them."""
    from .catalog import CASES_TOML, load_catalog

    out = {s.name: {c.id: c for c in s.cases()} for s in load_catalog(False, catalog_path).values()}
    for source in CASE_SOURCES.values():
        out.update(source(Path(reports)))
    return out


def candidates(reports: Path, max_case_s: float, outcome: Outcome, cases: dict | None = None) -> list[Drawn]:
    """Every record of ``reports``/data that today's engine would reuse (its id is that of
    one of today's cases), but the skipped ones."""
    from .store import store_for

    cases = todays_cases(reports) if cases is None else cases
    out = []
    for path in sorted((Path(reports) / "data").glob("*.jsonl")):
        today = cases.get(path.stem, {})
        for cid, rec in store_for(reports, path.stem).read().items():
            if cid not in today:
                outcome.stale += 1
                continue
            why = _skip_reason(rec, max_case_s)
            if why:
                outcome.skipped[why] = outcome.skipped.get(why, 0) + 1
                continue
            out.append(Drawn(path.stem, rec, today[cid]))
    return out


def _rtol(rec: dict) -> float:
    a = (rec.get("scene") or {}).get("analysis") or {}
    return VERIFY_FACTOR * float(a.get("newton_rtol") or DEFAULT_RTOL)


def _scale(x) -> float:
    if isinstance(x, bool) or x is None or isinstance(x, str):
        return 0.0
    if isinstance(x, (int, float)):
        return abs(float(x)) if math.isfinite(x) else 0.0
    if isinstance(x, dict):
        return max((_scale(v) for k, v in x.items() if k not in ("t",)), default=0.0)
    if isinstance(x, list):
        return max((_scale(v) for v in x), default=0.0)
    return 0.0


ENERGIES = ("potential_energy", "energy", "energy_peak")


def energy_floor(rec: dict) -> float:
    """The round-off floor of an energy of the record's scene (J): W(F) is computed from
    invariants near 3 (I1 - 3), so each point's energy carries an absolute round-off of
    about eps x 3 mu x its volume, and a sum over the beam about ``ENERGY_FLOOR`` times
    that over the whole volume (mu the law's small-strain shear modulus). 0 where the
    scene has no beam or law."""
    try:
        from mechanics.laws import get_law

        sc = rec["scene"]
        m, b = sc["material"], sc["beam"]
        constants = {k: v for k, v in m.items() if k not in ("law", "formulation", "density", "penalty")}
        mu = get_law(m["law"]).shear_modulus(constants)
        return ENERGY_FLOOR * sys.float_info.epsilon * 3.0 * mu * b["length"] * b["height"] * b["width"]
    except (KeyError, TypeError, ValueError, LookupError):
        return 0.0


def compare(old, new, rtol: float, where: str = "", scale: float | None = None, atol: float = 0.0,
            floor: float = 0.0) -> list[str]:
    """Where two records' results differ (see the module doc); ``floor``: the energies'
    round-off floor (:func:`energy_floor`), added to their tolerance."""
    if isinstance(old, dict) and isinstance(new, dict):
        out, skip = [], not_results()
        for k in sorted(set(old) | set(new)):
            if k in skip or k.endswith("_s"):
                continue
            if k not in old or k not in new:
                out.append(f"{where}{k}: {'absent' if k not in old else old[k]!r:.60} -> "
                           f"{'absent' if k not in new else new[k]!r:.60}")
                continue
            a, b = old[k], new[k]
            if k == "reason":
                if (None if a is None else str(a).split(":")[0]) != (None if b is None else str(b).split(":")[0]):
                    out.append(f"{where}reason: {a!r:.80} -> {b!r:.80}")
            elif k == "newton_iterations" and isinstance(a, int) and isinstance(b, int):
                solves = max(1, sum(old.get(c) or 0 for c in ("load_steps", "relax_steps", "steps", "rejected_steps")))
                if abs(a - b) > solves:
                    out.append(f"{where}{k}: {a} -> {b} (more than one per Newton solve, {solves})")
            elif k == "lowest_eigenvalue" and isinstance(a, float) and isinstance(b, float):
                if (a > 0) != (b > 0) or abs(a - b) > EIGEN_RTOL * max(abs(a), abs(b)):
                    out.append(f"{where}{k}: {a!r} -> {b!r} (sign, or beyond {EIGEN_RTOL:g} relative)")
            elif k in ("tip", "tip_uz") and scale is None:     # components at the scale of the tip vector
                s = max(_scale(old.get("tip")), _scale(new.get("tip")), _scale(a), _scale(b))
                out += compare(a, b, rtol, f"{where}{k}.", s, atol, floor)
            else:
                out += compare(a, b, rtol, f"{where}{k}.", scale, floor if k in ENERGIES else atol, floor)
        return out
    if isinstance(old, list) and isinstance(new, list):
        if len(old) != len(new):
            return [f"{where[:-1]}: {len(old)} entries -> {len(new)}"]
        s = max(_scale(old), _scale(new)) if scale is None else scale
        out = []
        for i, (a, b) in enumerate(zip(old, new)):
            out += compare(a, b, rtol, f"{where}{i}.", s, atol, floor)
            if len(out) > 3:
                break
        return out
    numbers = (int, float)
    if isinstance(old, numbers) and isinstance(new, numbers) and not isinstance(old, bool) \
            and not isinstance(new, bool) and (isinstance(old, float) or isinstance(new, float)):
        s = max(abs(old), abs(new)) if scale is None else max(scale, abs(old), abs(new))
        if not (abs(old - new) <= rtol * s + atol):
            return [f"{where[:-1]}: {old!r} -> {new!r} (|diff| {abs(old - new):.3g} > {rtol:.1g} x {s:.3g}"
                    + (f" + {atol:.3g})" if atol else ")")]
        return []
    return [] if old == new else [f"{where[:-1]}: {old!r:.80} -> {new!r:.80}"]


def _run(case: Case) -> dict:
    from .worker import execute

    return execute(case, timeout_s=None)


def verify(reports: Path, sample: int, seed: int | None = None, budget_s: float = 600.0,
           max_case_s: float = 60.0, workers: int = 2, log=print, cases: dict | None = None) -> Outcome:
    """Recompute ``sample`` randomly drawn records (see the module doc)."""
    from .worker import init_pool_worker

    seed = int.from_bytes(os.urandom(4), "little") if seed is None else seed
    outcome = Outcome(seed)
    pool = candidates(reports, max_case_s, outcome, cases)
    outcome.candidates = len(pool)
    drawn = random.Random(seed).sample(pool, min(sample, len(pool)))
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(var, "1")
    t0 = time.perf_counter()
    ctx = multiprocessing.get_context("spawn")
    with cf.ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=init_pool_worker,
                                initargs=(os.getpid(),)) as ex:
        pending = list(drawn)
        running: dict = {}
        while pending or running:
            while pending and len(running) < workers and time.perf_counter() - t0 < budget_s:
                d = pending.pop(0)
                running[ex.submit(_run, d.case)] = (d, time.perf_counter())
            if not running:
                break
            done, _ = cf.wait(running, return_when=cf.FIRST_COMPLETED)
            for fut in done:
                d, started = running.pop(fut)
                rec = fut.result()
                what = compare(d.record, rec, _rtol(d.record), floor=energy_floor(d.record))
                name = d.record["case"]["name"]
                outcome.checked.append((d.study, name, time.perf_counter() - started))
                outcome.problems += [f"{d.study}: {name}: {w}" for w in what]
                log(f"  {'ok  ' if not what else 'DIFF'} {d.study}: {name} ({time.perf_counter() - started:.1f} s)")
        outcome.not_started = len(pending)
    return outcome
