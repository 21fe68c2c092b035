"""Implicit time stepping of the continuum (no dolfinx here): the integrator family of
:mod:`ancf.dynamics`, on :class:`reference_fem.dynamic_problem.DynamicProblem`.

Same contract as ANCF's integrators:

- generalized-alpha (Chung-Hulbert) with alpha_m = (2 rho_inf - 1)/(rho_inf + 1),
  alpha_f = rho_inf/(rho_inf + 1), gamma = 1/2 - alpha_m + alpha_f,
  beta = (1 - alpha_m + alpha_f)^2 / 4, and Newmark's average acceleration
  (alpha_m = alpha_f = 0, gamma = 1/2, beta = 1/4); a test checks the coefficients
  against ancf's;
- Newton with the consistent Jacobian (UFL's derivative of the step residual:
  (1 - alpha_m) / (beta dt^2) M + (1 - alpha_f) K, plus the pressure rows);
  predictor a_(n+1) = a_n; convergence as in :func:`reference_fem.newton.newton`
  with the scale ||Q_gravity|| + ||M a_n|| (ANCF's scale);
- steps clipped to land on the output times; a step whose Newton fails (or whose
  local error estimate dt^2 |beta - 1/6| max|a_(n+1) - a_n| exceeds ``tolerance``)
  is rejected and retried with half the step (or the controller's step), down to
  ``dt_min`` (default dt / 1024), then status "failed" with the reason; without a
  tolerance the step grows back to dt (doubling) after a rejection;
- ``energy_limit``: total energy above E(0) + limit ends the run with status "failed",
  reason "energy-growth" (never a silent blow-up); no NaN is ever kept as a state.

The pressure components of the arrays hold the multiplier lam (at t_(n+1-alpha_f));
their "velocity" and "acceleration" components are kept at zero (no inertia).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from .newton import StepFailure

METHODS = ("generalized-alpha", "newmark")


def coefficients(method: str, rho_inf: float) -> dict:
    """{alpha_m, alpha_f, gamma, beta} of ``method``."""
    if method == "generalized-alpha":
        am = (2 * rho_inf - 1) / (rho_inf + 1)
        af = rho_inf / (rho_inf + 1)
        return {"alpha_m": am, "alpha_f": af, "gamma": 0.5 - am + af,
                "beta": 0.25 * (1 - am + af) ** 2}
    if method == "newmark":
        return {"alpha_m": 0.0, "alpha_f": 0.0, "gamma": 0.5, "beta": 0.25}
    raise ValueError(f"integrator {method!r} is not available in reference_fem; "
                     f"allowed: {', '.join(METHODS)}")


@dataclass
class State:
    t: float
    u: np.ndarray
    v: np.ndarray
    a: np.ndarray
    iterations: int = 0


@dataclass
class Output:
    t: float
    tip: tuple[float, float]
    energy: tuple[float, float, float]   # kinetic, strain, gravity (J)
    line: np.ndarray | None = None       # deformed centre line (n, 2), m


@dataclass
class DynamicResult:
    status: str = "converged"
    reason: str | None = None
    outputs: list[Output] = field(default_factory=list)
    steps: int = 0
    rejected_steps: int = 0
    newton_iterations: int = 0
    energy_steps: list = field(default_factory=list)    # (t, kinetic, strain, gravity)
    final: State | None = None
    cpu_s: float = 0.0
    wall_s: float = 0.0


class Integrator:
    def __init__(self, problem, method: str = "generalized-alpha", rho_inf: float = 0.8,
                 newton_rtol: float = 1e-8, max_iterations: int = 25):
        self.problem, self.method, self.rho_inf = problem, method, rho_inf
        self.newton_rtol, self.max_iterations = newton_rtol, max_iterations
        self.coef = coefficients(method, rho_inf)
        self._last_iterations = 0

    def initial_state(self, u0: np.ndarray) -> State:
        a0 = self.problem.initial_acceleration(u0, self.newton_rtol, self.max_iterations)
        u0 = u0.copy()
        mask = self.problem.p_mask
        u0[mask] = a0[mask]           # the multiplier at t = 0
        a0[mask] = 0.0
        return State(0.0, u0, np.zeros_like(u0), a0)

    def step(self, s: State, dt: float) -> State | None:
        c = self.coef
        am, af, g, b = c["alpha_m"], c["alpha_f"], c["gamma"], c["beta"]
        u_pred = s.u + dt * s.v + 0.5 * dt * dt * s.a
        try:
            u, its = self.problem.solve_step(s.u, s.a, u_pred, u_pred, b * dt * dt, am, af,
                                             self.newton_rtol, self.max_iterations)
        except StepFailure as e:
            self._last_iterations = e.iterations
            return None
        a = (u - u_pred) / (b * dt * dt) + s.a
        a[self.problem.p_mask] = 0.0
        v = s.v + dt * ((1 - g) * s.a + g * a)
        v[self.problem.p_mask] = 0.0
        if not all(np.all(np.isfinite(x)) for x in (u, v, a)):
            self._last_iterations = its
            return None
        return State(s.t + dt, u, v, a, its)

    def error(self, s: State, new: State, dt: float) -> float:
        """Zienkiewicz-Xie estimate dt^2 |beta - 1/6| max |a_(n+1) - a_n| (m)."""
        d = self.problem.u_dofs
        return dt * dt * abs(self.coef["beta"] - 1.0 / 6.0) * float(np.abs(new.a[d] - s.a[d]).max())

    def _output(self, s: State) -> Output:
        x, y = self.problem.tip(s.u)
        return Output(s.t, (float(x), float(y)), self.problem.energies(s.u, s.v),
                      self.problem.centre_line(s.u))

    def run(self, u0: np.ndarray, t_end: float, dt: float, output_times=None,
            dt_min: float | None = None, tolerance: float | None = None,
            energy_limit: float | None = None, energy_every_step: bool = False,
            progress=None) -> DynamicResult:
        wall0, cpu0 = time.perf_counter(), time.process_time()
        outs = sorted(set(output_times or [t_end]) | {t_end})
        dt_min = dt_min if dt_min is not None else dt / 1024
        res = DynamicResult()
        try:
            s = self.initial_state(u0)
        except StepFailure as e:
            res.status, res.reason = "failed", f"initial acceleration: {e}"
            return res
        e_start = self.problem.energies(s.u, s.v)
        e0 = sum(e_start)
        res.energy_steps.append((0.0, *e_start))
        if outs[0] == 0.0:
            res.outputs.append(self._output(s))
        h, k = dt, 0
        while s.t < t_end * (1 - 1e-12):
            while outs[k] <= s.t * (1 + 1e-12):
                k += 1
            remaining = outs[k] - s.t
            land = remaining <= h * (1 + 1e-9)
            step_h = remaining if land else h
            new = self.step(s, step_h)
            err = self.error(s, new, step_h) if (new is not None and tolerance) else 0.0
            if new is None or (tolerance and err > tolerance):
                res.rejected_steps += 1
                res.newton_iterations += self._last_iterations if new is None else new.iterations
                h = step_h * (0.5 if new is None else max(0.2, 0.9 * (tolerance / err) ** (1 / 3)))
                if h < dt_min:
                    res.status = "failed"
                    res.reason = (f"step below dt_min = {dt_min:g} s at t = {s.t:.6g} s: "
                                  + ("Newton failed" if new is None else "local error above tolerance"))
                    break
                continue
            res.steps += 1
            res.newton_iterations += new.iterations
            s = new
            if land:
                s.t = outs[k]
                res.outputs.append(self._output(s))
                if progress:
                    progress(res.outputs[-1])
            if energy_limit is not None or energy_every_step:
                energies = self.problem.energies(s.u, s.v)
                res.energy_steps.append((s.t, *energies))
                if not math.isfinite(sum(energies)) or (energy_limit is not None
                                                        and sum(energies) > e0 + energy_limit):
                    res.status, res.reason = "failed", "energy-growth"
                    break
            if tolerance:
                if not land:
                    h = min(step_h * min(2.0, 0.9 * (tolerance / max(err, 1e-300)) ** (1 / 3)), 10 * dt)
            else:
                h = min(2 * h, dt) if h < dt else dt
        res.final = s
        res.cpu_s, res.wall_s = time.process_time() - cpu0, time.perf_counter() - wall0
        return res
