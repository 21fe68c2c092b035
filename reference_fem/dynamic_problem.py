"""The continuum beam in motion: the residual of one implicit step, its start, energies.

Unknowns per step: the displacement u_(n+1) and, in the plane strain models, the
scaled pressure lam (p = mu lam) of the Taylor-Hood pair. Per unit width (the 2D
problem); energies are multiplied by the width w (J for the full beam).

One step of the generalized-alpha family (the coefficients and the update of v and a
live in :mod:`reference_fem.dynamics`; Newmark is alpha_m = alpha_f = 0):

    a_(n+1)        = (u_(n+1) - u_pred) / (beta dt^2) + a_n,  u_pred = u_n + dt v_n + dt^2/2 a_n
    a_(n+1-am)     = (1 - am) a_(n+1) + am a_n
    u_(n+1-af)     = (1 - af) u_(n+1) + af u_n
    int rho a_(n+1-am) . v  +  int P(F(u_(n+1-af)), lam) : grad v  =  int rho g . v
    int dW/dlam(F_*, lam) q = 0

Mass: rho times the displacement field, i.e. the consistent mass of the Q2 (P2)
displacement space (the quadrature of degree 2 p integrates it exactly on the
affine cells). The pressure has no inertia: the mixed system is a DAE (index 2 in
the pressure). lam is *not* interpolated in time: it is the multiplier acting at
t_(n+1-af), solved for in each step without a history (no zig-zag of an
interpolated algebraic variable at rho_inf = 1). The constraint row is evaluated
at

- ``mixed`` (exactly incompressible): F_* = F(u_(n+1)), so every stored state has
  J = 1 (the constraint is enforced where the state is kept, as in Arnold and
  Bruls's index-3 generalized-alpha; the constraint force acts at n+1-af);
- ``penalty``: F_* = F(u_(n+1-af)): mu lam = alpha (J - 1) at n+1-af, so the force is
  exactly the penalty force alpha (J - 1) cof F at u_(n+1-af), as ANCF's
  generalized-alpha evaluates its elastic force.

Plane stress has no pressure. At t = 0 the state is at rest and stress-free; the
initial acceleration solves the same equations with the inertia term only
(``initial_acceleration``): int rho a0 . v + int P(F0, lam0) : grad v = int rho g . v,
and for ``mixed`` the second time derivative of the constraint at rest,
cof F0 : grad a0 = 0, with lam0 its multiplier.

Pin: the one node at the centre of the left face (0, 0) has zero displacement (both
components, a homogeneous Dirichlet condition on that vertex's dofs); the face is
otherwise free to rotate and deform. A point support in a 2D continuum carries its
reaction through a logarithmically singular local field; the mesh sensitivity this
causes is measured in reports/reference_fem.md.
"""
from __future__ import annotations

import numpy as np
import ufl

from ancf.scene import Scene

from . import dolfinx_backend as backend
from .energies import INCOMPRESSIBILITIES, get_law_ufl
from .newton import StepFailure, newton, newton_dynamic

# Newton's correction test of a step (as ancf.dynamics.Integrator.utol): 1e-8 of the
# state or of the beam height (4 nm at 0.35 m, against the 0.1 mm criterion).
UTOL = 1e-8
from .problem import beam_supports
from .settings import FemSettings


class DynamicProblem:
    """The forms of one law and continuum model on a mesh, with the functions the
    integrator fills (all arrays are of the space W, pressure included)."""

    def __init__(self, disc: backend.Discretisation, law_name: str, constants: dict, model: str,
                 incompressibility: str, bcs, density: float, gravity, width: float,
                 penalty: float | None = None, tip_point=(0.0, 0.0), cell_height: float | None = None,
                 height: float = 1.0):
        self.disc, self.bcs, self.width = disc, list(bcs), width
        self.height = float(height)
        self.tip_point = np.asarray(tip_point, float)
        law = get_law_ufl(law_name)
        inc = INCOMPRESSIBILITIES[(model, incompressibility)]
        if inc.has_pressure != disc.pressure:
            raise ValueError("the discretisation's pressure field does not match the model")
        self.effects = ["elastic", "gravity", "inertia"] + (["penalty"] if incompressibility == "penalty" else [])
        c = {k: disc.constant(constants[k]) for k in law.constants}
        self.pressure_scale = 2.0 * (constants.get("C10", 0.0) + constants.get("C01", 0.0))
        mu = disc.constant(self.pressure_scale)
        alpha = disc.constant(penalty) if incompressibility == "penalty" else None
        rho = disc.constant(density)
        g = disc.constant(np.asarray(gravity, float))
        dx = disc.dx
        I = ufl.Identity(2)

        def energy(F, lam):
            return inc.energy(law, c, F, lam, mu, alpha)

        def stress(u, lam):
            F = ufl.variable(I + ufl.grad(u))
            return ufl.diff(energy(F, lam), F)

        def constraint(F, lam):
            lv = ufl.variable(lam)
            return ufl.diff(energy(F, lv), lv)

        # -- the state the integrator sets ------------------------------------------------
        self.u_n, self.a_n, self.u_pred = disc.function(), disc.function(), disc.function()
        self.c_beta = disc.constant(1.0)     # 1 / (beta dt^2)
        self.am, self.af = disc.constant(0.0), disc.constant(0.0)
        un, _ = disc.split(self.u_n)
        an, _ = disc.split(self.a_n)
        upred, _ = disc.split(self.u_pred)
        u, lam = disc.split(disc.w)
        v, q = disc.split(disc.test)

        # -- one step ---------------------------------------------------------------------
        a_new = (u - upred) * self.c_beta + an
        a_m = (1 - self.am) * a_new + self.am * an
        u_f = (1 - self.af) * u + self.af * un
        R = rho * ufl.dot(a_m, v) * dx + ufl.inner(stress(u_f, lam), ufl.grad(v)) * dx \
            - rho * ufl.dot(g, v) * dx
        if disc.pressure:
            F_star = I + ufl.grad(u if incompressibility == "mixed" else u_f)
            R = R + constraint(F_star, lam) * q * dx
        self.system = backend.NonlinearSystem(disc, R, self.bcs)
        self.gravity_norm = backend.VectorNorm(rho * ufl.dot(g, v) * dx, self.bcs)
        self.inertia_norm = backend.VectorNorm(rho * ufl.dot(an, v) * dx, self.bcs)

        # -- the initial acceleration (linear in (a0, lam0); u_n holds u0) ----------------
        # For ``mixed`` the multiplier of the constraint rows is s lam0 with the scale
        # s = rho hc^2 (hc the cell height) instead of mu: the mass block (~ rho hc^2)
        # and the constraint block then have the same size (with mu, 1e6 times larger,
        # MUMPS reports a failed factorisation); lam0 is converted back afterwards.
        self.w0 = disc.function()
        a0, lam0 = disc.split(self.w0)
        self.start_scale = 1.0
        if disc.pressure and incompressibility == "mixed":
            F0 = I + ufl.grad(un)
            self.start_scale = density * (cell_height or 1.0) ** 2 / self.pressure_scale
            s = rho * disc.constant((cell_height or 1.0) ** 2)
            R0 = rho * ufl.dot(a0, v) * dx + ufl.inner(stress(un, 0.0), ufl.grad(v)) * dx \
                + s * lam0 * ufl.inner(ufl.cofac(F0), ufl.grad(v)) * dx \
                + s * ufl.inner(ufl.cofac(F0), ufl.grad(a0)) * q * dx - rho * ufl.dot(g, v) * dx
        else:
            R0 = rho * ufl.dot(a0, v) * dx + ufl.inner(stress(un, lam0), ufl.grad(v)) * dx \
                - rho * ufl.dot(g, v) * dx
            if disc.pressure:
                R0 = R0 + constraint(I + ufl.grad(un), lam0) * q * dx
        self.start = backend.NonlinearSystem(disc, R0, self.bcs, unknown=self.w0)

        # -- energies (full width) of the state in (ue, ve) --------------------------------
        self.ue, self.ve = disc.function(), disc.function()
        ue, _ = disc.split(self.ue)
        ve, _ = disc.split(self.ve)
        Fe = I + ufl.grad(ue)
        if disc.pressure:
            W_strain = inc.energy(law, c, Fe, 0.0, mu, None) if incompressibility == "mixed" else \
                energy(Fe, 0.0) + alpha / 2 * (ufl.det(Fe) - 1) ** 2
        else:
            W_strain = energy(Fe, None)
        X = ufl.SpatialCoordinate(disc.mesh)
        self.kinetic = backend.Functional(0.5 * width * rho * ufl.dot(ve, ve) * dx)
        self.strain = backend.Functional(width * W_strain * dx)
        self.gravity = backend.Functional(-width * rho * ufl.dot(g, X + ue) * dx)
        self.u_dofs = disc.displacement_dofs()
        self.p_mask = np.ones(len(disc.w.x.array), bool)
        self.p_mask[self.u_dofs] = False

    @property
    def n_dof(self) -> int:
        return len(self.disc.w.x.array)

    @property
    def n_free(self) -> int:
        return self.disc.ndof - backend.fixed_dof_count(self.bcs)

    # -- used by reference_fem.dynamics --------------------------------------------------
    def initial_acceleration(self, u0: np.ndarray, rtol: float, max_iterations: int) -> np.ndarray:
        """a0 at rest at u0 (pressure components: the multiplier lam0)."""
        self.u_n.x.array[:] = u0
        self.start.reset()
        newton(self.start, max(self.gravity_norm(), 1e-300), rtol, max_iterations)
        w0 = self.start.save()
        w0[self.p_mask] *= self.start_scale
        return w0

    def solve_step(self, u_n, a_n, u_pred, guess, beta_dt2: float, alpha_m: float, alpha_f: float,
                   rtol: float, max_iterations: int) -> tuple[np.ndarray, int]:
        """u_(n+1) (with lam) of one step; raises StepFailure."""
        self.u_n.x.array[:] = u_n
        self.a_n.x.array[:] = a_n
        self.u_pred.x.array[:] = u_pred
        self.c_beta.value = 1.0 / beta_dt2
        self.am.value, self.af.value = alpha_m, alpha_f
        self.system.restore(guess)
        scale = self.gravity_norm() + self.inertia_norm()
        its = newton_dynamic(self.system, scale, rtol, max_iterations, self.u_dofs, UTOL, self.height)
        return self.system.save(), its

    def energies(self, u: np.ndarray, v: np.ndarray) -> tuple[float, float, float]:
        """(kinetic, strain, gravity potential -int rho g . r dV) in J, full width."""
        self.ue.x.array[:] = u
        self.ve.x.array[:] = v
        return self.kinetic(), self.strain(), self.gravity()

    def positions(self, u: np.ndarray, points) -> np.ndarray:
        """Deformed positions (n, 2) in m of reference points (n, 2) at the state u."""
        points = np.asarray(points, float)
        saved = self.disc.w.x.array.copy()
        self.disc.w.x.array[:] = u
        d = self.disc.point_displacement(points)
        self.disc.w.x.array[:] = saved
        return points + d

    def centre_line(self, u: np.ndarray, n: int = 65) -> np.ndarray:
        """Deformed positions (n, 2) in m of n points of the centre line y = 0."""
        return self.positions(u, np.c_[np.linspace(0.0, self.tip_point[0], n), np.zeros(n)])

    def tip(self, u: np.ndarray) -> np.ndarray:
        """Position (x, y) of the free-end centre point (L, 0) in m."""
        return self.positions(u, [self.tip_point])[0]


def build_dynamic_problem(scene: Scene, settings: FemSettings) -> DynamicProblem:
    """The scene's beam (pinned or clamped at x = 0) as a continuum in motion."""
    b, m, loads = scene.beam, scene.material, scene.loads
    mesh = backend.rectangle_mesh(b.length, b.height, settings.cells_length,
                                  settings.cells_height, settings.cell)
    disc = backend.Discretisation(mesh, settings.degree, settings.has_pressure,
                                  settings.quadrature_degree)
    gravity = loads.gravity if loads.gravity is not None else (0.0, 0.0)
    if loads.tip_force is not None:
        from ancf.errors import SceneError
        raise SceneError("loads.tip_force: not available in reference_fem dynamics (gravity only)")
    return DynamicProblem(disc, m.law, dict(m.constants), settings.model, settings.incompressibility,
                          beam_supports(disc, scene, settings), m.density, gravity, b.width,
                          penalty=m.penalty, tip_point=(b.length, 0.0),
                          cell_height=b.height / settings.cells_height, height=b.height)


__all__ = ["DynamicProblem", "build_dynamic_problem", "StepFailure"]
