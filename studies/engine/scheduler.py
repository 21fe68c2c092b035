"""The runner: map a study's cases over an executor, store each record as it finishes.

1. Read the study's record store; a case whose id already has a record is reused
   (nothing recomputed) unless ``force``; a record marked ``transient`` (its worker
   died) is always recomputed.
2. Cases without a ``timing`` option go to the executor:

   - ``pool``: a local process pool (``workers``, default 2; spawned processes);
   - ``mpi``: ``mpi4py.futures.MPIPoolExecutor``, for clusters; start the run as
     ``mpiexec -n N python -m mpi4py.futures -m studies run NAME --executor mpi``
     (rank 0 runs this program, the other ranks are the workers);
   - ``serial``: this process (tests, debugging).

   Each record is appended (flush + fsync) the moment its future completes. A run
   longer than ``timeout_s`` is stopped inside its worker and recorded as failed.
3. Cases with a ``timing`` option then run serially in this process, after the pool
   has shut down (warm-up, median of N: :func:`studies.engine.worker.execute_timed`), so that
   timings never come from a busy machine. Cases with an ``mpi_ranks`` option (the 3D
   continuum) run one after another, each launched by ``mpiexec -n N`` (``srun`` under
   Slurm; :mod:`reference_fem.launch`) with the machine to themselves.
4. The store is compacted to the current case list.

All of it under the study's lock (:meth:`RecordStore.lock`): a second runner on the same
study waits, says so on stderr, and then finds the first one's records. Under faults: the
pool's workers die with the runner (:func:`studies.engine.worker.init_pool_worker`); a
Ctrl-C anywhere in the pool phase cancels what has not started, ends and waits for the
workers, stores every record that finished, and only then goes on up (exit 130); a
record is written whole even when the Ctrl-C lands in its append.
"""
from __future__ import annotations

import concurrent.futures as cf
import multiprocessing
import os
import signal
import threading
import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Iterable, Sequence

from .case import Case
from .worker import DEFAULT_TIMEOUT_S, execute, execute_timed
from .store import RecordStore

EXECUTORS = ("pool", "mpi", "serial")
DEFAULT_WORKERS = 2


@dataclass
class RunSummary:
    study: str
    cases: int = 0
    reused: int = 0
    computed: int = 0
    failed: int = 0
    seconds: float = 0.0
    failures: list[str] = field(default_factory=list)


def default_executor() -> str:
    """"mpi" when started by mpiexec with more than one rank, else "pool"."""
    for var in ("OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS"):
        if int(os.environ.get(var, "1") or 1) > 1:
            return "mpi"
    return "pool"


def _make_executor(kind: str, workers: int):
    if kind == "pool":
        from .worker import init_pool_worker
        return cf.ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("spawn"),
                                      initializer=init_pool_worker, initargs=(os.getpid(),))
    if kind == "mpi":
        from mpi4py.futures import MPIPoolExecutor
        return MPIPoolExecutor()
    raise ValueError(f"executor: unknown {kind!r}; allowed: {', '.join(EXECUTORS)}")


def _stop_pool(ex) -> None:
    """After a Ctrl-C: cancel what has not started, end the pool's workers (SIGTERM, then
    SIGKILL after 5 s) and wait until they are gone, so the command returns with no worker
    left; a second Ctrl-C meanwhile is ignored. An MPI pool is shut down without waiting
    for its queue."""
    main = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN) if main else None
    try:
        _end_workers(ex)
    finally:
        if main:
            signal.signal(signal.SIGINT, previous)


def _end_workers(ex) -> None:
    procs = list((getattr(ex, "_processes", None) or {}).values())
    for p in procs:
        if p.is_alive():
            p.terminate()
    deadline = time.monotonic() + 5.0
    for p in procs:
        p.join(max(0.0, deadline - time.monotonic()))
        if p.is_alive():
            p.kill()
            p.join()
    ex.shutdown(wait=True, cancel_futures=True)


@contextmanager
def _deferred_interrupt():
    """A Ctrl-C during the block is raised right after it (main thread; a handler swap,
    since a signal mask is per thread and the pool's threads would take the signal)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    hit = []
    previous = signal.signal(signal.SIGINT, lambda signum, frame: hit.append(signum))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if hit and callable(previous):
            previous(signal.SIGINT, None)   # the default handler raises KeyboardInterrupt


@contextmanager
def _children_without_sigint():
    """SIGINT blocked in this thread for the block: processes spawned in it inherit the
    mask, so a Ctrl-C to the group cannot interrupt a pool worker's start-up (its
    initializer then ignores SIGINT and unblocks it). A Ctrl-C meanwhile stays pending
    or reaches another thread: it is raised in the main thread all the same."""
    if not hasattr(signal, "pthread_sigmask"):
        yield
        return
    old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


def _progress(total: int, desc: str, enabled: bool):
    from tqdm import tqdm
    return tqdm(total=total, desc=desc, unit="case", disable=not enabled or total == 0,
                dynamic_ncols=True, leave=True)


def _mark_worker_death(case: Case, exc: BaseException) -> dict:
    from contract.record import new_record
    from .worker import annotate
    rec = new_record(case.solver, case.scene)
    rec.update(reason=f"worker process died: {type(exc).__name__}: {exc}", transient=True)
    return annotate(rec, case, time.perf_counter())


def _result(fut, case: Case) -> dict:
    try:
        return fut.result()
    except Exception as e:  # the worker itself died (e.g. killed, segfault)
        return _mark_worker_death(case, e)


def _run_pool(cases: list[Case], executor: str, workers: int, timeout_s: float | None, done,
              recorded: set[str]) -> None:
    """The cases on a pool, each record stored (``done``) as its future completes. On
    Ctrl-C (or any error): the records that finished are stored, the workers ended and
    waited for (:func:`_stop_pool`), then the interrupt goes on up."""
    ex = _make_executor(executor, workers)
    futures: dict = {}
    try:
        with _children_without_sigint():   # the workers are spawned by submit
            for c in cases:
                futures[ex.submit(execute, c, timeout_s)] = c
        for fut in cf.as_completed(futures):
            done(_result(fut, futures[fut]), executor)
    except BaseException:
        finished = [f for f in futures if f.done() and not f.cancelled() and f.exception() is None]
        _stop_pool(ex)
        for f in finished:
            if f.result()["case_id"] not in recorded:
                done(f.result(), executor)
        raise
    ex.shutdown(wait=True)


def pending(cases: Sequence[Case], store: RecordStore, force: bool = False,
            timeout_s: float | None = None) -> list[Case]:
    """The cases that need a run: all with ``force``, else those without a reusable
    record. A run stopped by a timeout is reusable only under a timeout no longer than
    the one that stopped it (a record from before that was written down: the default)."""
    if force:
        return list(cases)
    have = store.read()

    def stale(r: dict) -> bool:
        return bool(r.get("transient")) or (bool(r.get("timed_out")) and (
            not timeout_s or timeout_s > r.get("timeout_s", DEFAULT_TIMEOUT_S)))
    return [c for c in cases if c.id not in have or stale(have[c.id])]


def dry_run(study: str, cases: Iterable[Case], store: RecordStore, force: bool = False,
            timeout_s: float | None = DEFAULT_TIMEOUT_S) -> RunSummary:
    """What :func:`run_cases` would do, run nothing: ``computed`` counts the cases it would
    run (no record of today's code, or a transient one), ``reused`` the rest."""
    cases = list(dict.fromkeys(cases))
    todo = pending(cases, store, force, timeout_s)
    return RunSummary(study, cases=len(cases), reused=len(cases) - len(todo), computed=len(todo))


def run_cases(study: str, cases: Iterable[Case], store: RecordStore, executor: str | None = None,
              workers: int = DEFAULT_WORKERS, force: bool = False, progress: bool = True,
              timeout_s: float | None = DEFAULT_TIMEOUT_S) -> RunSummary:
    t0 = time.perf_counter()
    cases = list(dict.fromkeys(cases))  # the same case twice runs once
    with store.lock():   # another runner on this study: wait for it, then reuse its records
        todo = pending(cases, store, force, timeout_s)
        summary = RunSummary(study, cases=len(cases), reused=len(cases) - len(todo))
        launched = [c for c in todo if c.options.get("mpi_ranks")]
        pooled = [c for c in todo if not c.timing and c not in launched]
        timed = [c for c in todo if c.timing and c not in launched]
        executor = executor or default_executor()

        recorded: set[str] = set()

        def done(rec: dict, how: str) -> None:
            rec["run"] = {"executor": how, "workers": workers if how == "pool" else None}
            with _deferred_interrupt():   # a record is written whole and counted, or not at all
                rec = store.append(rec)
                recorded.add(rec["case_id"])
            summary.computed += 1
            if rec.get("status") != "converged":
                summary.failed += 1
                summary.failures.append(f"{rec['case']['name']}: {rec.get('status')} ({rec.get('reason')})")
            bar.update(1)

        with _progress(len(todo), study, progress) as bar:
            if pooled and (executor == "serial" or (executor == "pool" and workers <= 1)):
                for c in pooled:
                    done(execute(c, timeout_s), "serial")
            elif pooled:
                _run_pool(pooled, executor, workers, timeout_s, done, recorded)
            for c in launched:
                done(execute(c, timeout_s), f"mpi-{c.options['mpi_ranks']}")
            for c in timed:
                done(execute_timed(c, timeout_s), "serial-timed")
        store.compact(c.id for c in cases)
    summary.seconds = time.perf_counter() - t0
    return summary
