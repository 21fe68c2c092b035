"""The continuum beam in motion: the residual of one implicit step, its start, energies.

Unknowns per step: the displacement u_(n+1) and, in the models with a pressure field,
the scaled pressure lam (p = mu lam). The forms come from the shared set-up
(:mod:`reference_fem.dolfinx_backend.problem`); energies are for the full beam (J).

One step of the generalized-alpha family (the coefficients and the update of v and a
live in :mod:`reference_fem.stepper`; Newmark is alpha_m = alpha_f = 0):

    a_(n+1)        = (u_(n+1) - u_pred) / (beta dt^2) + a_n,  u_pred = u_n + dt v_n + dt^2/2 a_n
    a_(n+1-am)     = (1 - am) a_(n+1) + am a_n
    u_(n+1-af)     = (1 - af) u_(n+1) + af u_n
    int rho a_(n+1-am) . v  +  int P(F(u_(n+1-af)), lam) : grad v  =  int rho g . v + int tbar . v
    int dW/dlam(F_*, lam) q = 0

Mass: rho times the displacement field, i.e. the consistent mass of the displacement
space (the quadrature of degree 2 p integrates it exactly on the affine cells). The
pressure has no inertia: the mixed system is a DAE (index 2 in the pressure). lam is
*not* interpolated in time: it is the multiplier acting at t_(n+1-af), solved for in
each step without a history (no zig-zag of an interpolated algebraic variable at
rho_inf = 1). The model says where the constraint row is evaluated (F_* =
F(u_(n+1)) for the exactly incompressible model, so every stored state has J = 1, as in
Arnold and Bruls's index-3 generalized-alpha; F(u_(n+1-af)) with the penalty, so that
the force is exactly the penalty force at u_(n+1-af), as ANCF evaluates it).

At t = 0 the state is at rest and stress-free; the initial acceleration solves the
same equations with the inertia term only (the model's ``start_terms``).

Pin: the model geometry's pin (2D: the node at the centre of the left face, both
components zero; the face is otherwise free to rotate and deform). A point support in
a 2D continuum carries its reaction through a logarithmically singular local field;
the mesh sensitivity this causes is measured in reports/reference_fem.md. Hinge: the left
face kept straight through its fixed centre, u(0, Y) = Y a, eliminated exactly in the
step's and the start's Newton systems (:class:`~.fem.FaceHinge`; the constraint is linear
and homogeneous, so the predictor and the updates of the stepper keep it): a support with
a mesh limit (tests/test_reference_fem_hinge.py).
"""
from __future__ import annotations

import numpy as np
import ufl

from mechanics.newton import newton
from mechanics.time_loop import Energies

from . import fem as backend
from .problem import Setup, system


class DynamicProblem:
    """The forms of one time step on a set-up, with the functions the integrator fills
    (all arrays are of the space W, pressure included)."""

    def __init__(self, s: Setup, density: float, cell_size: float, height: float):
        self.setup, self.disc = s, s.disc
        self.height = float(height)
        self.rho = s.disc.constant(density)
        self.u_dofs = s.disc.displacement_dofs()
        self.p_mask = np.ones(len(s.disc.w.x.array), bool)
        self.p_mask[self.u_dofs] = False
        self._step_forms()
        self._start_forms(cell_size)
        self._energy_forms()

    def _step_forms(self) -> None:
        s, d = self.setup, self.disc
        self.u_n, self.a_n, self.u_pred = d.function(), d.function(), d.function()
        self.c_beta = d.constant(1.0)     # 1 / (beta dt^2)
        self.am, self.af = d.constant(0.0), d.constant(0.0)
        (un, _), (an, _), (upred, _) = d.split(self.u_n), d.split(self.a_n), d.split(self.u_pred)
        u, lam = d.split(d.w)
        v, q = d.split(d.test)
        a_new = (u - upred) * self.c_beta + an
        a_m = (1 - self.am) * a_new + self.am * an
        u_f = (1 - self.af) * u + self.af * un
        R = self.rho * ufl.dot(a_m, v) * d.dx + ufl.inner(s.stress(u_f, lam), ufl.grad(v)) * d.dx
        work = s.external_work(v)
        if work is not None:
            R = R - work
        row = s.model.constraint_row(s, s.gradient(s.model.constraint_displacement(u, u_f)), lam, q)
        if row is not None:
            R = R + row
        self.system = system(s, R)
        self.load_norm = backend.VectorNorm(work, s.bcs) if work is not None else (lambda: 0.0)
        self.inertia_norm = backend.VectorNorm(self.rho * ufl.dot(an, v) * d.dx, s.bcs)

    def _start_forms(self, cell_size: float) -> None:
        """The initial acceleration: linear in (a0, lam0); u_n holds u0."""
        s, d = self.setup, self.disc
        self.w0 = d.function()
        a0, lam0 = d.split(self.w0)
        v, q = d.split(d.test)
        un, _ = d.split(self.u_n)
        terms, self.start_scale = s.model.start_terms(s, un, a0, lam0, v, q, self.rho, cell_size)
        R0 = self.rho * ufl.dot(a0, v) * d.dx + terms
        work = s.external_work(v)
        if work is not None:
            R0 = R0 - work
        # (u, u) block: the mass matrix, so selfp (B diag(M)^-1 B^T) is the Schur complement's
        # spectral equivalent
        self.start = system(s, R0, unknown=self.w0, pressure_scale=None)

    def _energy_forms(self) -> None:
        """Energies (full beam) of the state held in (ue, ve)."""
        s, d = self.setup, self.disc
        self.ue, self.ve = d.function(), d.function()
        (ue, _), (ve, _) = d.split(self.ue), d.split(self.ve)
        W = s.model.stored_energy(s.law, s.c, s.gradient(ue), s.alpha)
        self.kinetic = backend.Functional(0.5 * s.width * self.rho * ufl.dot(ve, ve) * d.dx)
        self.strain = backend.Functional(s.width * W * d.dx)
        self.potentials = {k: backend.Functional(f) for k, f in s.potentials(ue).items()}

    @property
    def geometry(self):
        """Where the tip, the centre line and the pin are (:mod:`reference_fem.geometry`)."""
        return self.setup.model.geometry

    @property
    def effects(self) -> list:
        return self.setup.effects

    @property
    def n_dof(self) -> int:
        return len(self.disc.w.x.array)

    @property
    def n_free(self) -> int:
        return self.disc.ndof - self.setup.n_fixed

    # -- used by reference_fem.stepper --------------------------------------------------
    def initial_acceleration(self, u0: np.ndarray, rtol: float, max_iterations: int) -> np.ndarray:
        """a0 at rest at u0 (pressure components: the multiplier lam0); raises
        StepFailure."""
        self.u_n.x.array[:] = u0
        self.start.reset()
        newton(self.start, max(self.load_norm(), 1e-300), rtol, max_iterations)
        w0 = self.start.save()
        w0[self.p_mask] *= self.start_scale
        return w0

    def solve_step(self, u_n, a_n, u_pred, guess, beta_dt2: float, alpha_m: float, alpha_f: float,
                   rtol: float, max_iterations: int, small_correction) -> tuple[np.ndarray, int]:
        """u_(n+1) (with lam) of one step and its Newton iterations; raises StepFailure."""
        self.u_n.x.array[:] = u_n
        self.a_n.x.array[:] = a_n
        self.u_pred.x.array[:] = u_pred
        self.c_beta.value = 1.0 / beta_dt2
        self.am.value, self.af.value = alpha_m, alpha_f
        self.system.restore(guess)
        scale = self.load_norm() + self.inertia_norm()
        its, _ = newton(self.system, scale, rtol, max_iterations, small_correction)
        return self.system.save(), its

    def energies(self, u: np.ndarray, v: np.ndarray) -> Energies:
        """Kinetic, strain and the dead loads' potentials (J, full beam)."""
        self.ue.x.array[:] = u
        self.ve.x.array[:] = v
        pot = {k: f() for k, f in self.potentials.items()}
        return Energies(self.kinetic(), self.strain(), pot.get("gravity", 0.0), pot.get("tip_force"))

    def positions(self, u: np.ndarray, points) -> np.ndarray:
        """Deformed positions (n, gdim) in m of reference points (n, gdim) at the state u."""
        return self.disc.positions(u, points)

    def write(self, path, fmt: str, w: np.ndarray, t: float = 0.0):
        """The mesh with the displacement (and pressure) of the state w at time t."""
        self.disc.w.x.array[:] = w
        return self.disc.write(path, fmt, scale=self.setup.mu, t=t)


def build_dynamic_problem(scene, settings) -> DynamicProblem:
    """The scene's beam (pinned, hinged or clamped at x = 0) as a continuum in motion."""
    from .problem import set_up

    b = scene.beam
    return DynamicProblem(set_up(scene, settings), scene.material.density,
                          b.height / settings.cells_height, b.height)
