"""Newton's method: the one Python loop of both solvers.

The system is anything with ``residual_norm()`` (evaluate the residual at the current
iterate and return its norm) and ``newton_update()`` (solve for one increment, apply it,
return its size; an :class:`ArithmeticError` for a singular or failed solve). Used by
the continuum's statics and time steps (:mod:`reference_fem.statics`,
:mod:`reference_fem.stepper`), by ANCF's Python static Newton
(:func:`ancf.solvers.statics.newton_reference`) and its Python generalized-alpha step
(:class:`ancf.solvers.integrators.GeneralizedAlpha`). ANCF's compiled Newton loops are twins of
these, tested equal: :func:`ancf.solvers.compiled_statics.newton` of the static one,
:func:`ancf.solvers.compiled_steps.step` of the step; the discrete-gradient step
(:class:`ancf.solvers.integrators.DiscreteGradient` and its twin ``compiled_steps.step_dg``) is
a kind of its own (its quasi-Newton stop and iteration count differ).
"""
from __future__ import annotations

import math
from typing import Callable

from .time_loop import StepFailure


def newton(system, r_ref: float, rtol: float, max_iterations: int,
           small_correction: Callable | None = None, diverging: float = 1e4) -> tuple[int, list[float]]:
    """Iterate to ||R|| <= rtol r_ref, or until ``small_correction(system, r, dw)``
    accepts the last correction; return (iterations, residuals), or raise StepFailure
    (non-finite values, divergence: ||R|| > ``diverging`` ||R_0|| from the fourth
    iteration on, a failed solve, no convergence)."""
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
        if it >= 3 and r > diverging * residuals[0]:
            raise StepFailure("diverging", it)
        try:
            dw = system.newton_update()
        except StepFailure:
            raise
        except ArithmeticError as e:
            raise StepFailure(str(e), it) from None
        if not math.isfinite(dw):
            raise StepFailure("non-finite increment", it + 1)
        if small_correction is not None and small_correction(system, r, dw):
            return it + 1, residuals
    raise StepFailure(f"no convergence within {max_iterations} iterations "
                      f"(residual {residuals[-1]:.3e}, target {rtol * r_ref:.3e})", max_iterations)
