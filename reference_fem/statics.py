"""Newton's method and static load stepping for the continuum (no dolfinx here).

The system is anything with ``residual_norm()``, ``newton_update()`` (solve and apply one
increment, return its norm), ``last_increment()``, ``state_norm()``,
``save()``/``restore()`` and ``reset()``; ``set_load(t)`` sets the load parameter.

:func:`mechanics.newton.newton` is the Newton loop (shared with ANCF's Python paths):
converged when ||R|| <= rtol * r_ref, or when ``small_correction(system, r, ||dw||)``
accepts the last correction (statics: :func:`static_correction`; a time step: the
correction test of :mod:`reference_fem.stepper`). :func:`solve_static` follows the load path by the one
rule of :mod:`mechanics.load_path` (shared with ANCF): a failed increment restores the last
accepted state and is cut, an easy one grows the next.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable

from mechanics.load_path import Attempt, PathCounts, PathFailure, follow
from mechanics.newton import newton
from mechanics.time_loop import StepFailure


def static_correction(rtol: float, r_ref: float) -> Callable:
    """The static correction test: a relative increment ||dw|| <= rtol ||w|| once the
    residual is below sqrt(rtol) ||R_ref|| (quadratic convergence leaves an error of
    order rtol^2 then). Needed where the residual's round-off floor (LU of the
    saddle-point system) lies above rtol ||R_ref||, as for very small loads."""
    def small(system, r: float, dw: float) -> bool:
        return dw <= rtol * system.state_norm() and r <= math.sqrt(rtol) * r_ref
    return small


@dataclass
class StaticResult:
    status: str = "failed"
    reason: str | None = None
    newton_iterations: int = 0
    load_steps: int = 0
    rejected_steps: int = 0
    t_reached: float = 0.0
    cpu_s: float = 0.0
    wall_s: float = 0.0
    history: list = field(default_factory=list)   # (t, iterations) of the accepted increments
    unloaded: bool = False                        # no load: the answer is the reference state
    # (the last failed increment's target load,): for a diagnosis of a failed path; not
    # part of a record
    last_failure: tuple | None = field(default=None, repr=False)


def reference_residual(system, set_load: Callable[[float], None]) -> float:
    """||R|| at full load in the undeformed state: the scale of the equations."""
    saved = system.save()
    system.reset()
    set_load(1.0)
    r = system.residual_norm()
    system.restore(saved)
    set_load(0.0)
    return r


def solve_static(system, set_load, steps: int, rtol: float, max_iterations: int,
                 wall_time: float | None = None) -> StaticResult:
    """Follow the load from t = 0 to 1. An unloaded scene (zero load vector) is
    valid: its answer is the reference state (no increment is taken).

    A system distributed over MPI ranks has ``any_rank(flag)`` (True on every rank if
    any rank's flag is): the wall-time test then goes through it, so that every rank
    stops at the same increment (the Newton decisions read global norms already)."""
    result = StaticResult()
    w0, c0 = time.perf_counter(), time.process_time()
    r_ref = reference_residual(system, set_load)
    counts = PathCounts()
    any_rank = getattr(system, "any_rank", None)
    deadline = None if wall_time is None else w0 + wall_time

    def solve(t0: float, t1: float) -> Attempt:
        if any_rank is not None and deadline is not None and any_rank(time.perf_counter() > deadline):
            raise PathFailure("load", t0, f"wall time reached at t = {t0:.6g} (load) (analysis.wall_time)")
        saved = system.save()
        set_load(t1)
        try:
            its, _ = newton(system, r_ref, rtol, max_iterations, static_correction(rtol, r_ref))
        except StepFailure as e:
            result.last_failure = (t1,)
            system.restore(saved)
            set_load(t0)
            return Attempt(False, e.iterations, str(e))
        return Attempt(True, its)

    try:
        if r_ref > 0:
            for t, attempt in follow(solve, steps, counts, deadline=None if any_rank else deadline):
                result.t_reached = t
                result.history.append((t, attempt.iterations))
        else:
            set_load(1.0)
            result.t_reached, result.unloaded = 1.0, True
        result.status = "converged"
    except PathFailure as e:
        result.reason = e.reason
    result.newton_iterations, result.load_steps, result.rejected_steps = (
        counts.newton_iterations, counts.accepted, counts.rejected)
    result.wall_s = time.perf_counter() - w0
    result.cpu_s = time.process_time() - c0
    return result
