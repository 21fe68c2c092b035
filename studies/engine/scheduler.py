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
"""
from __future__ import annotations

import concurrent.futures as cf
import multiprocessing
import os
import time
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
        return cf.ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("spawn"))
    if kind == "mpi":
        from mpi4py.futures import MPIPoolExecutor
        return MPIPoolExecutor()
    raise ValueError(f"executor: unknown {kind!r}; allowed: {', '.join(EXECUTORS)}")


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


def run_cases(study: str, cases: Iterable[Case], store: RecordStore, executor: str | None = None,
              workers: int = DEFAULT_WORKERS, force: bool = False, progress: bool = True,
              timeout_s: float | None = DEFAULT_TIMEOUT_S) -> RunSummary:
    t0 = time.perf_counter()
    cases = list(dict.fromkeys(cases))  # the same case twice runs once
    todo = pending(cases, store, force, timeout_s)
    summary = RunSummary(study, cases=len(cases), reused=len(cases) - len(todo))
    launched = [c for c in todo if c.options.get("mpi_ranks")]
    pooled = [c for c in todo if not c.timing and c not in launched]
    timed = [c for c in todo if c.timing and c not in launched]
    executor = executor or default_executor()

    def done(rec: dict, how: str) -> None:
        rec["run"] = {"executor": how, "workers": workers if how == "pool" else None}
        rec = store.append(rec)
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
            with _make_executor(executor, workers) as ex:
                futures = {ex.submit(execute, c, timeout_s): c for c in pooled}
                for fut in cf.as_completed(futures):
                    try:
                        rec = fut.result()
                    except Exception as e:  # the worker itself died (e.g. killed, segfault)
                        rec = _mark_worker_death(futures[fut], e)
                    done(rec, executor)
        for c in launched:
            done(execute(c, timeout_s), f"mpi-{c.options['mpi_ranks']}")
        for c in timed:
            done(execute_timed(c, timeout_s), "serial-timed")
    store.compact(c.id for c in cases)
    summary.seconds = time.perf_counter() - t0
    return summary
