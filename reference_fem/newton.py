"""Static load stepping: Newton's method with step cutting (no dolfinx here).

The system is anything with ``residual_norm()``, ``newton_update()`` (solve and
apply one increment, return its norm), ``save()``/``restore()`` and ``reset()``;
``set_load(t)`` sets the load parameter. :func:`load_path` is a generator of
accepted increments; :func:`solve_static` runs it to t = 1 and counts.

Convergence: ||R|| <= rtol * ||R_ref||, R_ref the residual of the full load at the
undeformed state (the external load vector), or a relative increment
||dw|| <= rtol ||w|| once the residual is below sqrt(rtol) ||R_ref|| (quadratic
convergence leaves an error of order rtol^2 then). The second test is needed where
the residual's round-off floor (LU of the saddle-point system) lies above
rtol ||R_ref||, as for very small loads.
Failure (no convergence within ``max_iterations``, a diverging or non-finite
residual, a failed linear solve) restores the last accepted state and halves the
increment; easy convergence (<= 4 iterations) grows it by 1.5. Below ``min_step``
the run fails with the reason.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable, Iterator

import numpy as np


@dataclass
class Increment:
    t: float
    iterations: int
    residuals: list[float]


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
    history: list = field(default_factory=list)


class StepFailure(ArithmeticError):
    def __init__(self, reason: str, iterations: int = 0):
        super().__init__(reason)
        self.iterations = iterations


def newton(system, r_ref: float, rtol: float, max_iterations: int) -> tuple[int, list[float]]:
    """Iterate to convergence at the current load; raise StepFailure if it does not."""
    residuals: list[float] = []
    for it in range(max_iterations + 1):
        r = system.residual_norm()
        residuals.append(r)
        if not math.isfinite(r):
            raise StepFailure("non-finite residual", it)
        if r <= rtol * r_ref:
            return it, residuals
        if it == max_iterations:
            break
        if it >= 3 and r > 1e4 * residuals[0]:
            raise StepFailure("diverging", it)
        try:
            dw = system.newton_update()
        except ArithmeticError as e:
            raise StepFailure(str(e), it) from None
        if not math.isfinite(dw):
            raise StepFailure("non-finite increment", it + 1)
        if dw <= rtol * system.state_norm() and r <= math.sqrt(rtol) * r_ref:
            residuals.append(system.residual_norm())
            return it + 1, residuals
    raise StepFailure(f"no convergence within {max_iterations} iterations "
                      f"(residual {residuals[-1]:.3e}, target {rtol * r_ref:.3e})", max_iterations)


def newton_dynamic(system, r_ref: float, rtol: float, max_iterations: int, dofs, utol: float,
                   length: float) -> int:
    """Newton for one time step, with ANCF's stopping rule (ancf.dynamics): ||R|| <=
    rtol * r_ref, or a correction max|dw| over ``dofs`` (the displacements) <= utol *
    max(max|w|, length). The second rule is the one that ends stiff runs, whose residual
    has a round-off floor eps ||K|| ||u|| above rtol * r_ref (constants x 1e6). Returns
    the iterations; raises StepFailure (non-finite values, divergence, no convergence)."""
    residuals: list[float] = []
    for it in range(max_iterations + 1):
        r = system.residual_norm()
        residuals.append(r)
        if not math.isfinite(r):
            raise StepFailure("non-finite residual", it)
        if r <= rtol * r_ref:
            return it
        if it == max_iterations:
            break
        if it >= 3 and r > 1e4 * residuals[0]:
            raise StepFailure("diverging", it)
        try:
            system.newton_update()
        except ArithmeticError as e:
            raise StepFailure(str(e), it) from None
        dw = np.abs(system.last_increment()[dofs])
        if not np.all(np.isfinite(dw)):
            raise StepFailure("non-finite increment", it + 1)
        w = system.save()[dofs]
        if dw.max() <= utol * max(np.abs(w).max(), length):
            return it + 1
    raise StepFailure(f"no convergence within {max_iterations} iterations "
                      f"(residual {residuals[-1]:.3e}, target {rtol * r_ref:.3e})", max_iterations)


def reference_residual(system, set_load: Callable[[float], None]) -> float:
    """||R|| at full load in the undeformed state: the scale of the equations."""
    saved = system.save()
    system.reset()
    set_load(1.0)
    r = system.residual_norm()
    system.restore(saved)
    set_load(0.0)
    return r


def load_path(system, set_load, steps: int, rtol: float, max_iterations: int,
              result: StaticResult, min_step: float = 1e-4) -> Iterator[Increment]:
    r_ref = reference_residual(system, set_load)
    if not r_ref > 0:
        raise StepFailure("no load: the external load vector is zero")
    t, dt = 0.0, 1.0 / steps
    while t < 1.0 - 1e-14:
        dt = min(dt, 1.0 - t)
        saved = system.save()
        set_load(t + dt)
        try:
            its, res = newton(system, r_ref, rtol, max_iterations)
        except StepFailure as e:
            result.newton_iterations += e.iterations
            result.rejected_steps += 1
            system.restore(saved)
            set_load(t)
            dt *= 0.5
            if dt < min_step:
                raise StepFailure(f"load step below {min_step:g} at t = {t:.4g} ({e})") from None
            continue
        t += dt
        result.newton_iterations += its
        result.load_steps += 1
        result.t_reached = t
        if its <= 4:
            dt *= 1.5
        yield Increment(t, its, res)


def solve_static(system, set_load, steps: int, rtol: float, max_iterations: int) -> StaticResult:
    result = StaticResult()
    w0, c0 = time.perf_counter(), time.process_time()
    try:
        for inc in load_path(system, set_load, steps, rtol, max_iterations, result):
            result.history.append(inc)
        result.status = "converged"
    except StepFailure as e:
        result.reason = str(e)
    result.wall_s = time.perf_counter() - w0
    result.cpu_s = time.process_time() - c0
    return result
