"""Running one case: the worker function (any process) and the serial timed run.

:func:`execute` runs a case once and returns its record: the solver's record plus
``case_id``, ``case`` and ``versions`` (of the packages its solver uses). A case whose options name ``imports`` (modules that register a
user's element or law) imports them first, in whatever process runs it. A case that raises is recorded, not lost:
status "failed" and the exception as the reason (:func:`contract.record.sanitize` later
turns any NaN into null).

:func:`execute_timed` is for cases with a ``timing`` option: a warm-up (for a solver
that has one, :attr:`studies.engine.solvers.Solver.warm`, the compiled code loaded by a
small copy of the scene; else one full run: caches, JIT, imports), then up to ``repeats``
runs while their total stays within ``budget_s`` (at least one), each timed around the
whole solver call (build + solve + tip) in this one process; the record gets ``timing``
with every sample, the median and how it was warmed. The runner calls it serially,
outside any pool.

:func:`init_pool_worker` starts each pool worker: it ignores Ctrl-C (the runner decides
what an interrupt ends, :func:`studies.engine.scheduler._stop_pool`) and dies with its
parent: ``prctl(PR_SET_PDEATHSIG, SIGKILL)`` on Linux, and everywhere a watchdog thread
that ends the process once its parent is gone (a runner killed with ``kill -9`` leaves
no worker computing for nobody).
"""
from __future__ import annotations

import importlib
import os
import signal
import statistics
import sys
import threading
import time
import traceback

from contract.record import new_record

from .case import Case, packages
from .solvers import get_solver

DEFAULT_REPEATS = 3
DEFAULT_BUDGET_S = 5.0
DEFAULT_TIMEOUT_S = 300.0  # a run longer than this is stopped and recorded as failed


PR_SET_PDEATHSIG = 1          # <linux/prctl.h>
WATCHDOG_PERIOD_S = 0.5


def _die_with_parent_linux() -> bool:
    """Ask the kernel for SIGKILL when the parent dies; False where there is no prctl."""
    if not sys.platform.startswith("linux"):
        return False
    import ctypes
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        return libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


def _watch_parent(parent: int, period_s: float) -> None:
    while os.getppid() == parent:
        time.sleep(period_s)
    os._exit(1)   # reparented: the runner is gone, nobody reads this result


def init_pool_worker(parent: int) -> None:
    """The initializer of every pool worker (see the module doc); ``parent`` is the
    runner's pid, passed in so that a parent that died before this ran is noticed."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if hasattr(signal, "pthread_sigmask"):   # started with SIGINT blocked (the runner's submit)
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
    _die_with_parent_linux()
    if os.getppid() != parent:
        os._exit(1)
    threading.Thread(target=_watch_parent, args=(parent, WATCHDOG_PERIOD_S), name="parent-watchdog",
                     daemon=True).start()


class CaseTimeout(Exception):
    pass


def _alarm(signum, frame):
    raise CaseTimeout("stopped by the runner's time limit")


def _failed(case: Case, exc: BaseException) -> dict:
    rec = new_record(case.solver, case.scene)
    rec["reason"] = f"{type(exc).__name__}: {exc}"[:2000]
    rec["traceback"] = traceback.format_exc(limit=6)[-4000:]
    return rec


def annotate(rec: dict, case: Case, started: float) -> dict:
    if case.sources_changed():   # edited while the study ran: keep the result, never reuse it
        rec["transient"] = True
        rec["note"] = "the solver's sources changed while this case ran; the next run recomputes it"
    rec["case_id"] = case.id
    rec["case"] = case.to_dict()
    rec["versions"] = packages(case)
    rec["elapsed_s"] = time.perf_counter() - started
    rec["pid"] = os.getpid()
    return rec


def _run_launched(case: Case, timeout_s: float | None) -> tuple[dict, float]:
    """A case with the ``mpi_ranks`` option: ``python -m reference_fem run`` under
    mpiexec (or srun) on that many ranks, in a temporary directory; its record."""
    import tempfile

    from reference_fem.launch import run_launched

    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="case-mpi-") as tmp:
        rec = run_launched(case.scene, int(case.options["mpi_ranks"]), tmp, timeout_s)
    return rec, time.perf_counter() - t0


def _import_user_modules(case: Case) -> None:
    """The modules imported beside the case (``options.imports``): user modules that
    register elements and laws, imported before the solver sees the scene."""
    for module in case.options.get("imports", ()):
        importlib.import_module(module)


def _run_once(case: Case, timeout_s: float | None = None) -> tuple[dict, float]:
    """One solver call; a solver error or a run beyond ``timeout_s`` (SIGALRM, main
    thread: pool and MPI workers run tasks there) gives a failed record."""
    if case.options.get("mpi_ranks"):
        return _run_launched(case, timeout_s)
    _import_user_modules(case)
    run = get_solver(case.solver, case.solver_module).run
    armed = bool(timeout_s) and hasattr(signal, "setitimer")
    if armed:
        previous = signal.signal(signal.SIGALRM, _alarm)
        signal.setitimer(signal.ITIMER_REAL, timeout_s)
    t0 = time.perf_counter()
    try:
        rec = run(case.scene)
    except Exception as e:  # recorded, never lost: the study goes on
        rec = _failed(case, e)
        if isinstance(e, CaseTimeout):
            rec["reason"] = f"timeout: stopped after {timeout_s:g} s"
            rec["timed_out"] = True
            rec["timeout_s"] = float(timeout_s)
    finally:
        if armed:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, previous)
    return rec, time.perf_counter() - t0


def execute(case: Case, timeout_s: float | None = DEFAULT_TIMEOUT_S) -> dict:
    """Run ``case`` once; return its record (never raises for a solver error)."""
    t0 = time.perf_counter()
    rec, _ = _run_once(case, timeout_s)
    return annotate(rec, case, t0)


def execute_timed(case: Case, timeout_s: float | None = DEFAULT_TIMEOUT_S) -> dict:
    """Warm-up, then the median of up to N timed runs (see the module doc)."""
    t0 = time.perf_counter()
    opts = case.timing or {}
    repeats = int(opts.get("repeats", DEFAULT_REPEATS))
    budget = float(opts.get("budget_s", DEFAULT_BUDGET_S))
    warmer = get_solver(case.solver, case.solver_module).warm
    samples, solve = [], []
    if warmer is not None and not case.options.get("mpi_ranks"):
        # the compiled code loaded by a small copy of the scene; the first full run is a sample
        _import_user_modules(case)
        t1 = time.perf_counter()
        warmer(case.scene)
        warm, how = time.perf_counter() - t1, "compiled code loaded by a two-element copy"
        rec, dt = _run_once(case, timeout_s)
        if rec.get("status") == "converged":
            samples.append(dt)
            solve.append(rec.get("wall_s"))
    else:
        rec, warm = _run_once(case, timeout_s)
        how = "one full run"
    if rec.get("status") == "converged":
        while len(samples) < repeats and (not samples or sum(samples) + samples[-1] <= budget):
            rec, dt = _run_once(case, timeout_s)
            samples.append(dt)
            solve.append(rec.get("wall_s"))
    rec["timing"] = {
        "warmup": how, "warmup_s": warm, "samples_s": samples, "repeats": len(samples),
        "median_s": statistics.median(samples) if samples else None,
        "solve_samples_s": solve,
        "solve_median_s": statistics.median(solve) if solve and None not in solve else None,
        "serial": True,
    }
    return annotate(rec, case, t0)
