"""Implicit time integration of M a + f_int(u) = Q_K(t).

The :class:`Integrator` base class owns the loop, the counters, the step clipping to
output times, the step-size control and the failure status. A method implements one
step. To add a method:

1. subclass :class:`Integrator` and give it a ``name``;
2. set its coefficients as class attributes, or compute them in ``coefficients`` (tests
   check them directly);
3. implement ``step(state, dt) -> State | None`` (None when Newton fails), and
   optionally ``error(state, new, dt)``, a local error estimate in m;
4. add it to :data:`INTEGRATORS` (the scene loader lists the names).

The state holds displacements u (m and -), velocities v and accelerations a of the
nodal coordinates.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from .banded import Banded
from .model import BeamModel, InadmissibleState


@dataclass
class State:
    t: float
    u: np.ndarray
    v: np.ndarray
    a: np.ndarray
    iterations: int = 0


@dataclass
class DynamicResult:
    status: str                       # "converged" | "failed"
    reason: str | None
    states: list[State]               # at the output times reached
    steps: int = 0
    rejected_steps: int = 0
    newton_iterations: int = 0
    energy_steps: list = field(default_factory=list)   # (t, kinetic, strain, gravity) every step
    cpu_s: float = 0.0
    wall_s: float = 0.0


class Integrator:
    name = "base"
    # With an energy limit the energy is checked every `energy_check_every` steps and at
    # every output time (an energy evaluation costs about half a Newton iteration).
    energy_check_every = 10
    # Newton also stops when its correction is below utol of the state: in the quadratic
    # regime the error after it is ~du^2 (measured on the pendulum: corrections 4e-4,
    # then 1e-8 .. 5e-8, then 1e-15 of the state), so 1e-6 saves the confirming
    # evaluation and leaves ~1e-12 of the state, far below the 0.1 mm step criterion.
    utol = 1e-6

    def __init__(self, model: BeamModel, M: Banded, f_ext: np.ndarray, rho_inf: float = 0.8,
                 newton_rtol: float = 1e-8, max_iterations: int = 25):
        self.model, self.M, self.f_ext = model, M, f_ext
        self.rho_inf = rho_inf
        self.newton_rtol, self.max_iterations = newton_rtol, max_iterations
        self.free = np.ones(model.mesh.n_dof, bool)
        self.free[model.fixed] = False
        self.coefficients()

    def coefficients(self) -> None:
        """Set the method's coefficients (from rho_inf where it applies)."""

    # -- one step: subclasses ----------------------------------------------------------
    def step(self, s: State, dt: float) -> State | None:
        raise NotImplementedError

    def error(self, s: State, new: State, dt: float) -> float:
        """Local error estimate (m) of the step s -> new; 0 without an estimator."""
        return 0.0

    # -- the loop ------------------------------------------------------------------------
    def initial_state(self, u0: np.ndarray) -> State:
        """At rest at u0; a0 from M a0 = Q_K - f_int(u0) on the free dofs."""
        v0 = np.zeros_like(u0)
        r = np.where(self.free, self.f_ext - self.model.internal_force(u0), 0.0)
        a0 = self.M_constrained().solve(r)
        return State(0.0, u0.copy(), v0, a0)

    def M_constrained(self) -> Banded:
        return Banded(self.M.ab.copy(), self.M.b).constrain(self.model.fixed)

    def energies(self, s: State) -> tuple[float, float, float]:
        """(kinetic, strain, gravity potential) in J; gravity potential -int rho g.r dV =
        -Q_g . (q_ref + u), Q_g the gravity part of Q_K."""
        kinetic = 0.5 * float(s.v @ self.M.matvec(s.v))
        strain = self.model.strain_energy(s.u)
        gravity = -float(self.f_ext @ (self.model.mesh.reference + s.u))
        return kinetic, strain, gravity

    def run(self, u0: np.ndarray, t_end: float, dt: float, output_times=None,
            dt_min: float | None = None, tolerance: float | None = None,
            energy_limit: float | None = None, energy_every_step: bool = False) -> DynamicResult:
        """Integrate from rest at u0 to t_end. Steps are clipped to land on the output
        times. On Newton failure (or a local error above ``tolerance``) a step is
        rejected and retried with half (or the controller's) step, down to ``dt_min``
        (default dt / 1024; with no tolerance the step returns to dt afterwards). Total
        energy rising above E(0) + ``energy_limit`` ends the run: status "failed",
        reason "energy-growth". With a limit the energy is checked every
        ``energy_check_every`` steps and at the output times (a growth is caught at most
        that many steps late); ``energy_every_step`` records it every step."""
        wall0, cpu0 = time.perf_counter(), time.process_time()
        outs = sorted(set(output_times or [t_end]) | {t_end})
        dt_min = dt_min if dt_min is not None else dt / 1024
        s = self.initial_state(u0)
        res = DynamicResult("converged", None, [])
        if outs[0] == 0.0:
            res.states.append(s)
        e0 = sum(self.energies(s))
        res.energy_steps.append((0.0, *self.energies(s)))
        h, k = dt, 0
        while s.t < t_end * (1 - 1e-12):
            while outs[k] <= s.t * (1 + 1e-12):
                k += 1
            remaining = outs[k] - s.t
            land = remaining <= h * (1 + 1e-9)   # snap: no sliver steps from summed round-off
            step_h = remaining if land else h
            new = self._try(s, step_h)
            err = self.error(s, new, step_h) if (new is not None and tolerance) else 0.0
            if new is None or (tolerance and err > tolerance):
                res.rejected_steps += 1
                res.newton_iterations += getattr(self, "_last_iterations", 0)
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
                res.states.append(s)
            check = energy_every_step or (energy_limit is not None and
                                          (land or res.steps % self.energy_check_every == 0))
            if check:
                energies = self.energies(s)
                res.energy_steps.append((s.t, *energies))
                if energy_limit is not None and sum(energies) > e0 + energy_limit:
                    res.status = "failed"
                    res.reason = (f"energy-growth: E rose {sum(energies) - e0:.3g} J above E(0) "
                                  f"at t = {s.t:.6g} s (limit {energy_limit:.3g} J)")
                    break
            if tolerance:
                h = min(step_h * min(2.0, 0.9 * (tolerance / max(err, 1e-300)) ** (1 / 3)), 10 * dt) if not land else h
            else:
                h = min(2 * h, dt) if h < dt else dt
        res.cpu_s, res.wall_s = time.process_time() - cpu0, time.perf_counter() - wall0
        return res

    def _try(self, s: State, dt: float) -> State | None:
        try:
            new = self.step(s, dt)
        except (InadmissibleState, np.linalg.LinAlgError):
            new = None                   # a rejected step, retried smaller
        if new is not None and not all(np.all(np.isfinite(x)) for x in (new.u, new.v, new.a)):
            new = None
        return new


class GeneralizedAlpha(Integrator):
    """Chung-Hulbert generalized-alpha: alpha_m = (2 rho_inf - 1)/(rho_inf + 1),
    alpha_f = rho_inf/(rho_inf + 1), gamma = 1/2 - alpha_m + alpha_f,
    beta = (1 - alpha_m + alpha_f)^2 / 4; solves
    M a_(n+1-alpha_m) + f_int(u_(n+1-alpha_f)) = Q_K with x_(n+1-alpha) = (1 - alpha) x_(n+1) + alpha x_n
    by Newton on u_(n+1) with the consistent Jacobian
    (1 - alpha_m) / (beta dt^2) M + (1 - alpha_f) K."""

    name = "generalized-alpha"

    def coefficients(self):
        r = self.rho_inf
        self.alpha_m = (2 * r - 1) / (r + 1)
        self.alpha_f = r / (r + 1)
        self.gamma = 0.5 - self.alpha_m + self.alpha_f
        self.beta = 0.25 * (1 - self.alpha_m + self.alpha_f) ** 2

    def step(self, s: State, dt: float) -> State | None:
        am, af, g, b = self.alpha_m, self.alpha_f, self.gamma, self.beta
        M, fixed, free = self.M, self.model.fixed, self.free
        # predictor: a_(n+1) = a_n
        u_pred = s.u + dt * s.v + dt * dt * 0.5 * s.a
        u = u_pred.copy()
        scale = np.linalg.norm(np.where(free, self.f_ext, 0.0)) + np.linalg.norm(np.where(free, M.matvec(s.a), 0.0))
        atol = self.newton_rtol * max(scale, 1e-30)
        c = (1 - am) / (b * dt * dt)
        self._last_iterations = 0
        for it in range(self.max_iterations + 1):
            a = (u - u_pred) / (b * dt * dt) + s.a
            f, K = self.model.internal_force_and_tangent((1 - af) * u + af * s.u)
            R = M.matvec((1 - am) * a + am * s.a) + f - self.f_ext
            R[fixed] = 0.0
            self._last_iterations = it
            if np.linalg.norm(R) <= atol:
                v = s.v + dt * ((1 - g) * s.a + g * a)
                return State(s.t + dt, u, v, a, it)
            if it == self.max_iterations:
                return None
            du = Banded((1 - af) * K.ab + c * M.ab, K.b).constrain(fixed).solve(-R)
            u = u + du
            if np.abs(du).max() <= self.utol * max(np.abs(u).max(), self.model.mesh.height):
                a = (u - u_pred) / (b * dt * dt) + s.a
                v = s.v + dt * ((1 - g) * s.a + g * a)
                return State(s.t + dt, u, v, a, it + 1)
        return None

    def error(self, s: State, new: State, dt: float) -> float:
        """Zienkiewicz-Xie estimate dt^2 |(beta - 1/6)(a_(n+1) - a_n)| over the position dofs."""
        pos = self._position_dofs()
        return dt * dt * abs(self.beta - 1.0 / 6.0) * float(np.abs(new.a[pos] - s.a[pos]).max())

    def _position_dofs(self):
        if not hasattr(self, "_pos"):
            m = self.model.mesh
            self._pos = np.concatenate([m.dofs(n, ["r"]) for n in range(m.n_nodes)])
        return self._pos


class DiscreteGradient(Integrator):
    """Energy-conserving midpoint scheme with a discrete gradient of the strain energy.

        u_(n+1) - u_n = dt (v_n + v_(n+1)) / 2
        M (v_(n+1) - v_n) / dt + f_dg(u_n, u_(n+1)) = Q_K

    In 2D both invariants are quadratic in F, so with F_m = (F_n + F_(n+1)) / 2 exactly
    a_(n+1) - a_n = 2 F_m : dF and J_(n+1) - J_n = cof(F_m) : dF. The symmetric discrete
    gradient in (a, J),

        W^_a = [W(a1, J0) - W(a0, J0) + W(a1, J1) - W(a0, J1)] / (2 da)
        W^_J = [W(a0, J1) - W(a0, J0) + W(a1, J1) - W(a1, J0)] / (2 dJ)

    (evaluated by the model: :meth:`BeamModel.discrete_gradient_force_and_tangent`),
    gives P = 2 W^_a F_m + W^_J cof F_m and f_dg = sum w B^T P with
    W^_a da + W^_J dJ = W(a1, J1) - W(a0, J0):
    strain plus kinetic energy minus the work of constant loads is conserved to the
    Newton tolerance, whatever the law and however stiff the penalty. Second order;
    no numerical dissipation (rho_inf does not apply). Newton uses the midpoint tangent
    K(u_m) / 2 + 2 M / dt^2 (exact as du -> 0)."""

    name = "discrete-gradient"

    def coefficients(self):
        self.alpha_m = self.alpha_f = 0.0
        self.gamma, self.beta = 0.5, 0.25

    def step(self, s: State, dt: float) -> State | None:
        M, fixed = self.M, self.model.fixed
        u = s.u + dt * s.v + 0.5 * dt * dt * s.a         # predictor
        scale = np.linalg.norm(np.where(self.free, self.f_ext, 0.0)) + \
            np.linalg.norm(np.where(self.free, M.matvec(s.a), 0.0))
        atol = self.newton_rtol * max(scale, 1e-30)
        c = 2.0 / (dt * dt)
        for it in range(self.max_iterations + 1):
            f, K = self.model.discrete_gradient_force_and_tangent(s.u, u)
            R = M.matvec(c * (u - s.u) - 2.0 / dt * s.v) + f - self.f_ext
            R[fixed] = 0.0
            self._last_iterations = it
            if np.linalg.norm(R) <= atol:
                break
            if it == self.max_iterations:
                return None
            du = Banded(K.ab + c * M.ab, K.b).constrain(fixed).solve(-R)
            u = u + du
            if np.abs(du).max() <= 1e-3 * self.utol * max(np.abs(u).max(), self.model.mesh.height):
                break                    # quasi-Newton (linear rate): a tighter stop
        v = 2.0 / dt * (u - s.u) - s.v
        a = (v - s.v) / dt
        return State(s.t + dt, u, v, a, it + 1)


class Newmark(GeneralizedAlpha):
    """Newmark's average acceleration: gamma = 1/2, beta = 1/4, no alpha terms
    (energy-conserving for linear problems; no numerical dissipation)."""

    name = "newmark"

    def coefficients(self):
        self.alpha_m, self.alpha_f, self.gamma, self.beta = 0.0, 0.0, 0.5, 0.25


INTEGRATORS = {cls.name: cls for cls in (GeneralizedAlpha, Newmark, DiscreteGradient)}
