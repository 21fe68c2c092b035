"""The one time loop: implicit integration from rest, for every solver.

A solver plugs in a *stepper* (:class:`Stepper`): its ``initial_state``, one ``step``
(returning the new state or None, and the Newton iterations it spent), a local
``error`` estimate, the ``energies`` of a state and the ``output`` wanted at the output
times (tip, centre line, energies). :func:`integrate` owns everything else, once for
every solver:

- the step-control rules (:func:`next_step`, :func:`after_rejection`,
  :func:`after_acceptance`): steps are clipped to land exactly on the output times; a
  step whose Newton fails (or whose error estimate exceeds ``tolerance``) is rejected
  and retried with half the step (or the controller's step), down to ``dt_min``, then
  the run fails with the reason; without a tolerance the step grows back to dt
  (doubling) after a rejection; with one it follows the controller, at most 10 dt;
- the energy check: with an energy limit, the total energy is checked every
  ``energy_check_every`` accepted steps (default ``ENERGY_CHECK_EVERY``; ANCF: every
  step) and at every output time (a growth is caught at most that many steps late);
  rising above E(0) + limit ends the run, status "failed", reason "energy-growth: ...";
  the largest energy of any check is the record's ``energy_peak``;
- the bounds: at most ``max_steps`` accepted steps and ``wall_time`` seconds (a run
  that reaches either fails with the reason); every loop inside a stepper is bounded
  by its own iteration count;
- the counters (accepted and rejected steps, Newton iterations of both) and the
  dynamic keys of the record (:func:`record_keys`);
- progress: ``progress(t, result)`` after every accepted step (the caller throttles).

A stepper may also offer ``advance(s, h, t_out, dt, budget, offset, energy_every,
energy_max)``: many steps in compiled code by these same rules (ANCF's generalized-alpha
family, :mod:`ancf.solvers.compiled_steps`, which compiles :func:`next_step` and
:func:`after_acceptance` from here). :func:`integrate` then hands it every stretch up
to the next output time and is entered back at the output time, at a rejected step
(halved here, checked against ``dt_min``), at an energy growth, or after at most
``budget`` steps (``max_steps``, ``wall_time`` and progress are checked then). Without a
tolerance and without ``energy_every_step`` it is used unless ``compiled=False``; the
energies between output times are then checked in the compiled loop and not kept in
``energy_steps``.

The states hold displacements u, velocities v and accelerations a of the unknowns.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable, Protocol

import numpy as np

# With an energy limit the energy is checked every this many steps and at every output
# time (an energy evaluation costs about half a Newton iteration of the ANCF model).
ENERGY_CHECK_EVERY = 10
# A step lands on an output time when the time left is within this fraction of the step
# (no sliver steps from summed round-off).
LAND = 1e-9
# A compiled stepper returns to the loop at least this often (progress, wall time, Ctrl-C).
STEPS_PER_CALL = 2000


class StepFailure(ArithmeticError):
    """A solve that did not converge, with the Newton iterations it spent."""

    def __init__(self, reason: str, iterations: int = 0):
        super().__init__(reason)
        self.iterations = iterations


@dataclass
class State:
    t: float
    u: np.ndarray
    v: np.ndarray
    a: np.ndarray


@dataclass
class Energies:
    """J, for the full beam. ``gravity`` = -int rho g . r dV; ``tip_force`` = -F . r(L, 0)
    of a dead tip load (None without one): the potentials of the dead loads."""
    kinetic: float
    strain: float
    gravity: float = 0.0
    tip_force: float | None = None

    @property
    def total(self) -> float:
        return self.kinetic + self.strain + self.gravity + (self.tip_force or 0.0)

    def to_dict(self, t: float) -> dict:
        d = {"t": t, "kinetic": self.kinetic, "strain": self.strain, "gravity": self.gravity}
        if self.tip_force is not None:
            d["tip_force"] = self.tip_force
        d["total"] = self.total
        return d


@dataclass
class Output:
    """What a solver reports at an output time."""
    t: float
    tip: tuple[float, float]          # position of the free-end centre point (m)
    energy: Energies
    line: np.ndarray | None = None    # deformed centre line (n, 2), m
    state: State | None = None        # kept for VTK output


class Stepper(Protocol):
    def initial_state(self, u0: np.ndarray) -> State: ...            # may raise StepFailure
    def step(self, s: State, dt: float) -> tuple[State | None, int]: ...
    def error(self, s: State, new: State, dt: float) -> float: ...
    def energies(self, s: State) -> Energies: ...
    def output(self, s: State) -> Output: ...


@dataclass
class DynamicResult:
    status: str = "converged"
    reason: str | None = None
    outputs: list[Output] = field(default_factory=list)
    steps: int = 0
    rejected_steps: int = 0
    newton_iterations: int = 0
    energy_steps: list = field(default_factory=list)    # (t, Energies) at every check
    # (t, total) of the largest total energy at any check (every ``energy_check_every``
    # accepted steps and every output time; compiled stretches included)
    energy_peak: tuple[float, float] | None = None
    energy_check_every: int | None = ENERGY_CHECK_EVERY   # None: energies at the output times only
    final: State | None = None
    cpu_s: float = 0.0
    wall_s: float = 0.0


# -- the step-control rules ---------------------------------------------------------------
def next_step(t: float, h: float, t_out: float) -> tuple[float, bool]:
    """(the step to take from t, does it land on the output time t_out)."""
    remaining = t_out - t
    land = remaining <= h * (1.0 + LAND)
    return (remaining if land else h), land


def after_rejection(step_h: float, err: float, tolerance: float | None, failed: bool) -> float:
    """The step to retry with: half after a failed Newton, else the controller's."""
    if failed:
        return 0.5 * step_h
    return step_h * max(0.2, 0.9 * (tolerance / err) ** (1.0 / 3.0))


def after_acceptance(h: float, step_h: float, err: float, tolerance: float | None, dt: float,
                     land: bool) -> float:
    """The next step after an accepted one: without a tolerance back to dt (doubling);
    with one the controller's (at most 10 dt), unchanged after a landing."""
    if tolerance:
        if land:
            return h
        return min(step_h * min(2.0, 0.9 * (tolerance / max(err, 1e-300)) ** (1.0 / 3.0)), 10.0 * dt)
    return min(2.0 * h, dt) if h < dt else dt


def acceleration_error(beta: float, dt: float, a_old: np.ndarray, a_new: np.ndarray) -> float:
    """Zienkiewicz-Xie local error estimate dt^2 |beta - 1/6| max |a_(n+1) - a_n| (m)
    over the given (position) components."""
    return dt * dt * abs(beta - 1.0 / 6.0) * float(np.abs(a_new - a_old).max())


# -- the loop -------------------------------------------------------------------------------
def integrate(stepper: Stepper, u0: np.ndarray, t_end: float, dt: float, output_times=None,
              dt_min: float | None = None, tolerance: float | None = None,
              energy_limit: float | None = None, energy_every_step: bool = False,
              energy_check_every: int = ENERGY_CHECK_EVERY,
              max_steps: int | None = None, wall_time: float | None = None,
              progress: Callable[[float, DynamicResult], None] | None = None,
              compiled: bool = True) -> DynamicResult:
    """Integrate from rest at u0 to t_end (see the module doc for the rules).
    ``dt_min`` defaults to dt / 1024, ``max_steps`` to MAX_STEPS; ``energy_every_step``
    records E at every step; ``compiled=False`` steps in Python even where the stepper
    has a compiled ``advance``."""
    from contract.scene import MAX_STEPS

    wall0, cpu0 = time.perf_counter(), time.process_time()
    max_steps = max_steps or MAX_STEPS
    outs = sorted(set(output_times or [t_end]) | {t_end})
    dt_min = dt_min if dt_min is not None else dt / 1024
    res = DynamicResult()
    try:
        s = stepper.initial_state(u0)
    except StepFailure as e:
        res.status, res.reason = "failed", f"initial acceleration: {e}"
        return res
    e0 = stepper.energies(s)
    res.energy_steps.append((0.0, e0))
    res.energy_peak = (0.0, e0.total)
    res.energy_check_every = 1 if energy_every_step else energy_check_every if energy_limit is not None else None
    every = res.energy_check_every or energy_check_every

    def peak(t: float, total: float) -> None:
        if not total <= res.energy_peak[1]:
            res.energy_peak = (t, total)
    if outs[0] == 0.0:
        res.outputs.append(stepper.output(s))
    advance = getattr(stepper, "advance", None) if compiled and not (tolerance or energy_every_step) else None
    if advance is None and getattr(stepper, "newton", None) == "linear":
        raise ValueError("newton 'linear' (one solve per step, no convergence test) is a step of the compiled loop; "
                         "this run steps in Python (an adaptive step, the energy at every step, or a model without "
                         "compiled kernels): choose 'chord', 'full' or 'modified'")
    h, k = dt, 0
    while s.t < t_end * (1 - 1e-12):
        if res.steps >= max_steps:
            res.status, res.reason = "failed", (f"step limit: {res.steps} accepted steps at t = {s.t:.6g} s "
                                                f"(analysis.max_steps)")
            break
        if wall_time is not None and time.perf_counter() - wall0 > wall_time:
            res.status, res.reason = "failed", (f"wall time: {wall_time:g} s reached at t = {s.t:.6g} s "
                                                f"(analysis.wall_time)")
            break
        while outs[k] <= s.t * (1 + 1e-12):
            k += 1
        if advance is not None:           # compiled steps up to outs[k], by the same rules
            adv = advance(s, h, outs[k], dt, min(max_steps - res.steps, STEPS_PER_CALL), res.steps,
                          every if energy_limit is not None else 0,
                          e0.total + energy_limit if energy_limit is not None else math.inf)
            res.newton_iterations += adv.iterations
            res.steps += adv.steps
            s, h, land = adv.state, adv.h, adv.outcome == "landed"
            if adv.peak > -math.inf or math.isnan(adv.peak):
                peak(s.t, adv.peak)     # (at the stretch's end: the step of the peak is not kept)
            if adv.outcome == "energy-growth":
                res.status, res.reason = "failed", _energy_growth(adv.energy, e0.total, s.t, energy_limit)
                break
            if adv.outcome == "rejected":
                res.rejected_steps += 1
                h = after_rejection(h, 0.0, None, True)
                if h < dt_min:
                    res.status = "failed"
                    res.reason = f"step below dt_min = {dt_min:g} s at t = {s.t:.6g} s: {adv.reason}"
                    break
                continue
            if not land:
                if progress:
                    progress(s.t, res)
                continue
        else:
            step_h, land = next_step(s.t, h, outs[k])
            new, iterations = stepper.step(s, step_h)
            res.newton_iterations += iterations
            err = stepper.error(s, new, step_h) if (new is not None and tolerance) else 0.0
            if new is None or (tolerance and err > tolerance):
                res.rejected_steps += 1
                h = after_rejection(step_h, err, tolerance, new is None)
                if h < dt_min:
                    res.status = "failed"
                    res.reason = (f"step below dt_min = {dt_min:g} s at t = {s.t:.6g} s: "
                                  + ("Newton failed" if new is None else "local error above tolerance"))
                    break
                continue
            res.steps += 1
            s = new
        energy = None
        if land:
            s.t = outs[k]
            out = stepper.output(s)
            res.outputs.append(out)
            energy = out.energy
        if energy_every_step or (energy_limit is not None and (land or res.steps % every == 0)):
            energy = energy or stepper.energies(s)
            res.energy_steps.append((s.t, energy))
        if energy is not None:
            peak(s.t, energy.total)
        if energy is not None and energy_limit is not None:
            if not energy.total <= e0.total + energy_limit:
                res.status, res.reason = "failed", _energy_growth(energy.total, e0.total, s.t, energy_limit)
                break
        if advance is None:               # (the compiled loop has already set h)
            h = after_acceptance(h, step_h, err, tolerance, dt, land)
        if progress:
            progress(s.t, res)
    res.final = s
    res.cpu_s, res.wall_s = time.process_time() - cpu0, time.perf_counter() - wall0
    return res


def _energy_growth(total: float, e0: float, t: float, limit: float) -> str:
    """The reason of a run stopped by the energy check."""
    if not math.isfinite(total):
        return f"energy-growth: non-finite energy at t = {t:.6g} s"
    return f"energy-growth: E rose {total - e0:.3g} J above E(0) at t = {t:.6g} s (limit {limit:.3g} J)"


def energy_limit(scene) -> float:
    """The scene's energy limit (J), or the default 1e-3 m |g| L / 2: a thousandth of a
    pendulum's potential-energy scale; inf (no check) without gravity."""
    a, b = scene.analysis, scene.beam
    if a.energy_limit is not None:
        return a.energy_limit
    if scene.loads.gravity is None:
        return math.inf
    mass = scene.material.density * b.length * b.height * b.width
    return 1e-3 * mass * math.hypot(*scene.loads.gravity) * b.length / 2


def record_keys(res: DynamicResult, integrator: dict, energy_limit: float, length: float) -> dict:
    """The dynamic keys of a record (both solvers): counters, ``integrator`` (name,
    rho_inf, coefficients), ``energy_limit`` (J; null: no check), ``tip_history``
    [{t, x, y}], ``configurations`` [{t, x: [...], y: [...]}] and ``energy``
    [{t, kinetic, strain, gravity, (tip_force,) total}] at the output times, and ``tip``
    (displacement of the free-end centre point at the last output time) when converged."""
    d = {"status": res.status, "reason": res.reason, "newton_iterations": res.newton_iterations,
         "steps": res.steps, "rejected_steps": res.rejected_steps, "cpu_s": res.cpu_s,
         "wall_s": res.wall_s, "integrator": integrator,
         "energy_limit": energy_limit if math.isfinite(energy_limit) else None,
         "tip_history": [{"t": o.t, "x": o.tip[0], "y": o.tip[1]} for o in res.outputs],
         "configurations": [{"t": o.t, "x": o.line[:, 0].tolist(), "y": o.line[:, 1].tolist()}
                            for o in res.outputs if o.line is not None],
         "energy": [o.energy.to_dict(o.t) for o in res.outputs]}
    if res.energy_peak is not None:     # the energy verdict's input: the largest E checked, not sampled
        t, e = res.energy_peak
        e0 = res.energy_steps[0][1].total
        d["energy_peak"] = {"t": t, "total": e, "rise": e - e0, "checked_every_steps": res.energy_check_every}
    if res.status == "converged" and res.outputs:
        x, y = res.outputs[-1].tip
        d["tip"] = {"ux": x - length, "uy": y}
    return d
