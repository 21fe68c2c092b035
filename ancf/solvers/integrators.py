"""Implicit integrators of M a + f_int(u) = Q_K for the ANCF beam: one step each.

:func:`mechanics.time_loop.integrate` owns the loop (landing, rejection, energy check,
counters); an integrator here is a stepper for it. To add a method:

1. subclass :class:`Integrator` and give it a ``name``;
2. give it ``coefficients(rho_inf)`` (a classmethod; tests check them directly; the
   generalized-alpha family's are :mod:`mechanics.alpha_family`'s, which the continuum
   steps too);
3. implement ``step(state, dt) -> (State | None, iterations)`` (None when Newton
   fails) and optionally ``error(state, new, dt)``, a local error estimate in m;
4. list it in :data:`INTEGRATORS` (scenes name it; unknown names list these).

A method whose step the compiled loop runs says so in ``compiled`` (the
generalized-alpha family by its coefficients, as Newmark does; the discrete gradient);
a subclass of one of them with a step of its own sets ``compiled = None``, or the
compiled loop would step it instead.

The state holds displacements u (m and -), velocities v and accelerations a of the
nodal coordinates.
"""
from __future__ import annotations

import math
from functools import cached_property

import numpy as np

from contract.registry import Registry
from mechanics import alpha_family
from mechanics.newton import newton
from mechanics.time_loop import Energies, Output, State, StepFailure, acceleration_error

from ..core.banded import Banded
from ..kinematics.section.model import BeamModel, InadmissibleState
from .compiled_steps import KAPPA, CompiledLoop   # KAPPA: the compiled step's contraction test, the same iterations


class Integrator:
    name = "base"
    # Newton also stops when its correction is below utol of the state: in the quadratic
    # regime the error after it is ~du^2 (measured on the pendulum: corrections 4e-4,
    # then 1e-8 .. 5e-8, then 1e-15 of the state), so 1e-6 saves the confirming
    # evaluation and leaves ~1e-12 of the state, far below the 0.1 mm step criterion.
    utol = 1e-6

    # which step of the compiled loop (:mod:`ancf.solvers.compiled_steps`) this method is:
    # "alpha-family" (from its coefficients) or "discrete-gradient"; None: Python steps only
    compiled: str | None = None
    # the generalized-alpha family: the forces at the ends of the step (Arnold-Bruls), not at
    # the configuration u_(n+1-alpha_f) between them (Chung-Hulbert)
    forces_at_ends = False

    @cached_property
    def _loop(self):
        return CompiledLoop(self.model, self.M, self.f_ext, self.coefficients(self.rho_inf), self.newton,
                            self.newton_rtol, self.max_iterations, self.utol,
                            discrete_gradient=self.compiled == "discrete-gradient",
                            forces_at_ends=self.forces_at_ends)

    @property
    def advance(self):
        """Compiled steps from s towards t_out (:meth:`ancf.solvers.compiled_steps.CompiledLoop.advance`),
        for a model the compiled loop can run (:attr:`BeamModel.compiled`; another model steps
        in Python); None: Python steps."""
        return self._loop.advance if self.compiled and getattr(self.model, "compiled", False) else None

    def __init__(self, model: BeamModel, M: Banded, loads: dict[str, np.ndarray], rho_inf: float = 0.5,
                 newton_rtol: float = 1e-8, max_iterations: int = 25, line_points: int = 4,
                 newton: str = "chord"):
        """``loads``: the dead load vectors Q by effect ("gravity", "tip_force"), N.
        ``newton``: the compiled loop's Newton variant (:data:`ancf.solvers.compiled_steps.NEWTON`) of
        the generalized-alpha family; the discrete gradient (compiled or not) and the
        Python steps (adaptive steps) are full Newton."""
        self.model, self.M, self.loads = model, M, loads
        self.newton = newton
        self.f_ext = sum(loads.values(), np.zeros(model.mesh.n_dof))
        self.rho_inf = rho_inf
        self.newton_rtol, self.max_iterations = newton_rtol, max_iterations
        self.line_points = line_points
        self.free = np.ones(model.mesh.n_dof, bool)
        self.free[model.fixed] = False
        for k, v in self.coefficients(rho_inf).items():
            setattr(self, k, v)
        m = model.mesh
        self.position_dofs = np.concatenate([m.dofs(n, ["r"]) for n in range(m.n_nodes)])

    @classmethod
    def coefficients(cls, rho_inf: float) -> dict:
        """{alpha_m, alpha_f, gamma, beta} of the method (at rho_inf where it applies)."""
        raise NotImplementedError

    def describe(self) -> dict:
        """The record's ``integrator`` entry."""
        return {"name": self.name, "rho_inf": self.rho_inf, **self.coefficients(self.rho_inf)}

    def warm(self, u0: np.ndarray) -> None:
        """Load what the first step needs (compiled code from numba's disk cache), so that
        it does not land in the solve time: the initial state, one output (its centre-line
        shape functions are tabulated once per model), and one compiled step."""
        s = self.initial_state(u0)
        self.output(s)
        if self.advance is not None:
            self.advance(s, 1e-6, 1e-6, 1e-6, 1)
            self._loop.reset()

    # -- one step: subclasses ----------------------------------------------------------
    def step(self, s: State, dt: float) -> tuple[State | None, int]:
        raise NotImplementedError

    def error(self, s: State, new: State, dt: float) -> float:
        """Local error estimate (m) of the step s -> new; 0 without an estimator."""
        return 0.0

    # -- what the loop asks for ----------------------------------------------------------
    def initial_state(self, u0: np.ndarray) -> State:
        """At rest at u0; a0 from M a0 = Q_K - f_int(u0) on the free dofs, in one compiled
        call where the compiled loop runs (:func:`ancf.solvers.compiled_steps.start`: the fused
        force, M constrained and factorised by LDL^T), else, and at det F <= 0 (the model
        then names the point), by the model's force and :meth:`M_constrained`."""
        a0 = None
        if self.advance is not None:
            self._loop.reset()               # a new run: no factorisation kept
            a0 = self._loop.initial_acceleration(u0)     # None: the route below says why
        if a0 is None:
            f = self.model.internal_force(u0)
            a0 = self.M_constrained().solve(np.where(self.free, self.f_ext - f, 0.0))
        return State(0.0, u0.copy(), np.zeros_like(u0), a0)

    def M_constrained(self) -> Banded:
        """M with the fixed dofs' rows and columns those of the identity: the Python route
        of :meth:`initial_state` (factorised at the start of a run without the compiled
        loop, in its timed solve, as a peer computing initial accelerations does)."""
        return Banded(self.M.ab.copy(), self.M.b).constrain(self.model.fixed)

    def energies(self, s: State) -> Energies:
        """Kinetic, strain, and the potential -Q . (q_ref + u) of each dead load."""
        pot = {k: -float(q @ s.u) - q_ref for k, (q, q_ref) in self._load_potentials.items()}
        kinetic, strain = self._loop.energies(s.u, s.v) if self.advance is not None else (math.nan, math.nan)
        if not math.isfinite(strain):        # no compiled loop, or det F <= 0 (the model names the point)
            kinetic, strain = 0.5 * float(s.v @ self.M.matvec(s.v)), self.model.strain_energy(s.u)
        return Energies(float(kinetic), float(strain), pot.get("gravity", 0.0), pot.get("tip_force"))

    @cached_property
    def _load_potentials(self) -> dict[str, tuple[np.ndarray, float]]:
        """{load: (Q, Q . q_ref)}: a dead load's potential at u is -Q . u - Q . q_ref."""
        return {k: (q, float(q @ self.model.mesh.reference)) for k, q in self.loads.items()}

    def output(self, s: State) -> Output:
        m = self.model
        tip = np.array([m.mesh.length, 0.0]) + m.tip_displacement(s.u)
        return Output(s.t, (float(tip[0]), float(tip[1])), self.energies(s),
                      m.centre_line(s.u, per_element=self.line_points), s)

    def _scale(self, s: State) -> float:
        """Newton's force scale: ||Q_K|| + ||M a_n|| on the free dofs."""
        return max(np.linalg.norm(np.where(self.free, self.f_ext, 0.0))
                   + np.linalg.norm(np.where(self.free, self.M.matvec(s.a), 0.0)), 1e-30)

    @staticmethod
    def _finite(s: State | None) -> State | None:
        if s is not None and not all(np.all(np.isfinite(x)) for x in (s.u, s.v, s.a)):
            return None
        return s


class GeneralizedAlpha(Integrator):
    """Chung-Hulbert generalized-alpha: alpha_m = (2 rho_inf - 1)/(rho_inf + 1),
    alpha_f = rho_inf/(rho_inf + 1), gamma = 1/2 - alpha_m + alpha_f,
    beta = (1 - alpha_m + alpha_f)^2 / 4; solves
    M a_(n+1-alpha_m) + f_int(u_(n+1-alpha_f)) = Q_K with x_(n+1-alpha) = (1 - alpha) x_(n+1) + alpha x_n
    by Newton on u_(n+1) with the consistent Jacobian
    (1 - alpha_m) / (beta dt^2) M + (1 - alpha_f) K."""

    name = "generalized-alpha"
    compiled = "alpha-family"

    @classmethod
    def coefficients(cls, rho_inf: float) -> dict:
        return alpha_family.coefficients(cls.name, rho_inf)

    def step(self, s: State, dt: float) -> tuple[State | None, int]:
        system = _AlphaStep(self, s, dt)
        try:
            its, _ = newton(system, self._scale(s), self.newton_rtol, self.max_iterations,
                            system.small_correction, diverging=math.inf)
        except InadmissibleState:
            return None, system.evaluations - 1     # a rejected step, retried smaller
        except StepFailure as e:
            return None, e.iterations
        return self._finite(self._state(s, dt, system.u, system.u_pred)), its

    def _state(self, s: State, dt: float, u, u_pred) -> State:
        a, v = alpha_family.update(u, u_pred, s.v, s.a, dt, self.beta, self.gamma)
        return State(s.t + dt, u, v, a)

    def error(self, s: State, new: State, dt: float) -> float:
        """Zienkiewicz-Xie estimate over the position dofs."""
        p = self.position_dofs
        return acceleration_error(self.beta, dt, s.a[p], new.a[p])


class ArnoldBruls(GeneralizedAlpha):
    """Generalized-alpha in Arnold and Bruls's form: the coefficients of Chung and Hulbert
    at rho_inf, and the equations of motion at t_(n+1),

        M acc_(n+1) + f_int(u_(n+1)) = Q_K,
        (1 - alpha_m) a_(n+1) + alpha_m a_n = (1 - alpha_f) acc_(n+1) + alpha_f acc_n,

    with Newmark's relations on the pseudo-acceleration a (the state's a). With M acc_k =
    Q_K - f_int(u_k) at both ends this is

        M a_(n+1-alpha_m) + (1 - alpha_f) f_int(u_(n+1)) + alpha_f f_int(u_n) = Q_K,

    solved by Newton on u_(n+1) with the same Jacobian as Chung-Hulbert's, K at u_(n+1).
    Forces are taken only at configurations the beam passes through, never at
    u_(n+1-alpha_f), the chord between two rotated configurations, which is strained: on a
    near-rigid pendulum that chord's strain energy is what Chung-Hulbert's form pumps into
    the motion. Second order (gamma = 1/2 - alpha_m + alpha_f); at rho_inf = 1 (alpha_m =
    alpha_f = 1/2) the mean of a over the step is the mean of acc, and the method is
    Newmark's average acceleration.

    Source: M. Arnold and O. Bruls (2007), Convergence of the generalized-alpha scheme for
    constrained mechanical systems, Multibody Syst. Dyn. 18, 185-202 (the scheme without
    constraints)."""

    name = "arnold-bruls"
    forces_at_ends = True

    @classmethod
    def coefficients(cls, rho_inf: float) -> dict:
        return alpha_family.generalized_alpha(rho_inf)


class Newmark(GeneralizedAlpha):
    """Newmark's average acceleration: gamma = 1/2, beta = 1/4, no alpha terms
    (energy-conserving for linear problems; no numerical dissipation)."""

    name = "newmark"


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
    compiled = "discrete-gradient"

    @classmethod
    def coefficients(cls, rho_inf: float) -> dict:
        return alpha_family.newmark()     # the predictor's and the error estimate's beta

    def step(self, s: State, dt: float) -> tuple[State | None, int]:
        M, fixed = self.M, self.model.fixed
        u = alpha_family.predict(s.u, s.v, s.a, dt)
        atol = self.newton_rtol * self._scale(s)
        c = 2.0 / (dt * dt)
        it = 0
        r_prev = math.inf
        try:
            for it in range(self.max_iterations + 1):
                f, K = self.model.discrete_gradient_force_and_tangent(s.u, u)
                R = M.matvec(c * (u - s.u) - 2.0 / dt * s.v) + f - self.f_ext
                R[fixed] = 0.0
                rn = np.linalg.norm(R)
                if rn <= atol:
                    break
                if it == self.max_iterations:
                    return None, it
                du = Banded(K.ab + c * M.ab, K.b).constrain(fixed).solve(-R)
                u = u + du
                # quasi-Newton (linear rate): a tighter stop, unless the residual stopped
                # contracting (its round-off floor): then the alpha family's correction test
                stalled = rn > KAPPA * r_prev
                r_prev = rn
                if np.abs(du).max() <= (1.0 if stalled else 1e-3) * self.utol * max(np.abs(u).max(),
                                                                                    self.model.mesh.height):
                    break
        except (InadmissibleState, np.linalg.LinAlgError):
            return None, it
        a, v = alpha_family.midpoint(s.u, u, s.v, dt)
        return self._finite(State(s.t + dt, u, v, a)), it + 1


class _AlphaStep:
    """One generalized-alpha step as a system of :func:`mechanics.newton.newton`:
    M a_(n+1-alpha_m) + f_int(u_(n+1-alpha_f)) - Q on the free dofs, with the consistent
    Jacobian (1 - alpha_m) / (beta dt^2) M + (1 - alpha_f) K, from the predictor."""

    def __init__(self, method: GeneralizedAlpha, s: State, dt: float):
        self.m, self.s, self.dt = method, s, dt
        self.u_pred = alpha_family.predict(s.u, s.v, s.a, dt)
        self.u = self.u_pred.copy()
        self.c = (1 - method.alpha_m) / (method.beta * dt * dt)
        self.evaluations = 0
        # Arnold-Bruls: the force at u_n, weighted alpha_f; the force at u_(n+1) (1 - alpha_f)
        self.f_n = method.model.internal_force(s.u) if method.forces_at_ends else None

    def residual_norm(self) -> float:
        m, s = self.m, self.s
        self.evaluations += 1
        a = (self.u - self.u_pred) / (m.beta * self.dt * self.dt) + s.a
        if self.f_n is None:
            f, self.K = m.model.internal_force_and_tangent((1 - m.alpha_f) * self.u + m.alpha_f * s.u)
        else:
            f, self.K = m.model.internal_force_and_tangent(self.u)
            f = (1 - m.alpha_f) * f + m.alpha_f * self.f_n
        self.R = m.M.matvec((1 - m.alpha_m) * a + m.alpha_m * s.a) + f - m.f_ext
        self.R[m.model.fixed] = 0.0
        return float(np.linalg.norm(self.R))

    def newton_update(self) -> float:
        m = self.m
        try:
            du = Banded((1 - m.alpha_f) * self.K.ab + self.c * m.M.ab, self.K.b).constrain(m.model.fixed).solve(-self.R)
        except np.linalg.LinAlgError:
            raise ArithmeticError("singular step matrix") from None
        self.u = self.u + du
        self.du_max = float(np.abs(du).max())
        return self.du_max

    def small_correction(self, system, r: float, dw: float) -> bool:
        return self.du_max <= self.m.utol * max(np.abs(self.u).max(), self.m.model.mesh.height)


INTEGRATORS: Registry[type[Integrator]] = Registry("analysis.integrator", "integrator")
for _cls in (GeneralizedAlpha, ArnoldBruls, Newmark, DiscreteGradient):
    INTEGRATORS.register(_cls.name, _cls)
INTEGRATORS.freeze_builtin()
