"""The one static load-path rule, for every solver: adaptive increments of a path
parameter t from 0 to 1.

The solver supplies ``solve(t_from, t_to) -> Attempt``: try to reach the equilibrium
at t_to from the accepted one at t_from, keeping its own state (and keeping the last
accepted state when the attempt fails). :func:`follow` owns the rule:

- start with increments of 1 / ``steps``;
- an increment that fails is halved (x ``CUT``) and retried; below ``min_step`` the
  path fails with a :class:`PathFailure` naming the last reason;
- an increment that converged within ``EASY`` Newton iterations grows the next one
  (x ``GROW``).

The loop is bounded: every attempt either advances t or halves the increment; with a
``wall_time`` (s) the path also fails once that much time has passed.
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Callable, Iterator

CUT = 0.5
GROW = 1.5
# Grow after at most 6 iterations (was 4): full Newton on the near-singular [2,2] tangents
# of Table 3 takes 5 to 7 iterations per increment whatever its size, so 4 never let the
# increments grow there (640 x HB2n-16 Mooney-Rivlin: 37 increments, 235 iterations; with
# 6: 20 and 183). The twelve Table 3 tips moved by less than 1e-5 mm (studies.design.bench).
EASY = 6
MIN_STEP = 1e-6


@dataclass
class Attempt:
    converged: bool
    iterations: int
    reason: str | None = None


@dataclass
class PathCounts:
    newton_iterations: int = 0
    accepted: int = 0
    rejected: int = 0


class PathFailure(Exception):
    def __init__(self, phase: str, t: float, reason: str):
        super().__init__(reason)
        self.phase, self.t, self.reason = phase, t, reason


def follow(solve: Callable[[float, float], Attempt], steps: int, counts: PathCounts,
           phase: str = "load", min_step: float = MIN_STEP,
           deadline: float | None = None) -> Iterator[tuple[float, Attempt]]:
    """Yield (t, attempt) for every accepted increment, up to t = 1; ``deadline``: a
    time.perf_counter() value after which the path fails."""
    t, dt = 0.0, 1.0 / steps
    while t < 1.0 - 1e-14:
        if deadline is not None and time.perf_counter() > deadline:
            raise PathFailure(phase, t, f"wall time reached at t = {t:.6g} ({phase}) (analysis.wall_time)")
        dt = min(dt, 1.0 - t)
        attempt = solve(t, t + dt)
        counts.newton_iterations += attempt.iterations
        if not attempt.converged:
            counts.rejected += 1
            dt *= CUT
            if dt < min_step:
                raise PathFailure(phase, t, f"load increment below {min_step:g} at t = {t:.6g} "
                                            f"({phase}): {attempt.reason}")
            continue
        t += dt
        counts.accepted += 1
        yield t, attempt
        if attempt.iterations <= EASY:
            dt *= GROW
