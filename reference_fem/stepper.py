"""Implicit time stepping of the continuum (no finite-element code here): a stepper of the
generalized-alpha family for the one time loop of :mod:`mechanics.time_loop`, on a
backend's dynamic problem (``dynamic_model(scene, settings)`` of
:mod:`reference_fem.dolfinx_backend` or :mod:`reference_fem.felupe_backend`): ``geometry``,
``height``, ``u_dofs``, ``p_mask``, ``initial_acceleration``, ``solve_step``, ``energies``,
``positions``.

- The methods, their coefficients, the predictor and the update are the shared ones of
  :mod:`mechanics.alpha_family` (generalized-alpha, Newmark), which ANCF steps too;
- Newton with the consistent Jacobian (the backend's derivative of the step residual:
  (1 - alpha_m) / (beta dt^2) M + (1 - alpha_f) K, plus the pressure rows); predictor
  a_(n+1) = a_n; converged when ||R|| <= rtol (||Q|| + ||M a_n||) (ANCF's scale) or when
  the correction of the displacements is below UTOL of the state (ANCF's rule, with a
  tighter UTOL: see below);
- the local error estimate is ANCF's (Zienkiewicz-Xie, over the displacements);
- landing, rejection, the energy check and the counters are the time loop's.

The pressure components of the arrays hold the multiplier lam (at t_(n+1-alpha_f));
their "velocity" and "acceleration" components are kept at zero (no inertia).
"""
from __future__ import annotations

import numpy as np

from mechanics import alpha_family as family
from mechanics.time_loop import Output, State, StepFailure, acceleration_error

# Newton's correction test of a step: 1e-8 of the state or of the beam height (4 nm at
# 0.35 m, against the 0.1 mm criterion). Deliberately 100 x tighter than ANCF's 1e-6
# (ancf.solvers.integrators.Integrator.utol): the continuum is the reference the elements are
# judged against, so its Newton error stays far below any element's; its Newton
# iterations are few next to its assembly, so the confirming iteration costs little.
UTOL = 1e-8
# Centre-line points in the records' configurations.
LINE_POINTS = 65


def alpha_family() -> dict:
    """{name: coefficient rule} of the methods the continuum steps."""
    return dict(family.METHODS)


class ContinuumStepper:
    def __init__(self, problem, method: str = "generalized-alpha", rho_inf: float = 0.8,
                 newton_rtol: float = 1e-8, max_iterations: int = 25, beam=None):
        self.problem, self.method, self.rho_inf = problem, method, rho_inf
        self.newton_rtol, self.max_iterations = newton_rtol, max_iterations
        self.coef = family.coefficients(method, rho_inf)
        self.beam = beam
        geometry = problem.geometry
        self.tip_point = geometry.tip_point(beam)
        self.line = geometry.line_points(beam, LINE_POINTS)

    def describe(self) -> dict:
        return {"name": self.method, "rho_inf": self.rho_inf, **self.coef}

    def _small_correction(self, system, r: float, dw: float) -> bool:
        d = self.problem.u_dofs
        w = system.save()[d]
        return np.abs(system.last_increment()[d]).max() <= UTOL * max(np.abs(w).max(), self.problem.height)

    def initial_state(self, u0: np.ndarray) -> State:
        a0 = self.problem.initial_acceleration(u0, self.newton_rtol, self.max_iterations)
        u0 = u0.copy()
        mask = self.problem.p_mask
        u0[mask] = a0[mask]           # the multiplier at t = 0
        a0[mask] = 0.0
        return State(0.0, u0, np.zeros_like(u0), a0)

    def step(self, s: State, dt: float) -> tuple[State | None, int]:
        c = self.coef
        am, af, g, b = c["alpha_m"], c["alpha_f"], c["gamma"], c["beta"]
        u_pred = family.predict(s.u, s.v, s.a, dt)
        try:
            u, its = self.problem.solve_step(s.u, s.a, u_pred, u_pred, b * dt * dt, am, af,
                                             self.newton_rtol, self.max_iterations, self._small_correction)
        except StepFailure as e:
            return None, e.iterations
        a, v = family.update(u, u_pred, s.v, s.a, dt, b, g)
        a[self.problem.p_mask] = 0.0
        v[self.problem.p_mask] = 0.0
        if not all(np.all(np.isfinite(x)) for x in (u, v, a)):
            return None, its
        return State(s.t + dt, u, v, a), its

    def error(self, s: State, new: State, dt: float) -> float:
        d = self.problem.u_dofs
        return acceleration_error(self.coef["beta"], dt, s.a[d], new.a[d])

    def energies(self, s: State):
        return self.problem.energies(s.u, s.v)

    def output(self, s: State) -> Output:
        tip = self.problem.positions(s.u, [self.tip_point])[0]
        line = self.problem.positions(s.u, self.line)
        return Output(s.t, (float(tip[0]), float(tip[1])), self.energies(s), line[:, :2], s)
