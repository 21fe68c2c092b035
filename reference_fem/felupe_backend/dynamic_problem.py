"""The continuum beam in motion on FElupe: one implicit step's residual and tangent, the
initial acceleration, energies and point positions, for :class:`reference_fem.stepper.ContinuumStepper`.

The equations are the DOLFINx backend's (:mod:`reference_fem.dolfinx_backend.dynamic_problem`,
whose docstring derives them), on FElupe's discretisation of the static problem
(:mod:`.problem`: the same mesh, fields, quadrature, supports and consistent nodal loads):

    R_u = M a_(n+1-am) + f_int(u_(n+1-af), lam) - f_ext
    R_p = int dW/dphat(F_*, lam) q dV,   F_* = F(u_(n+1)) (mixed), F(u_(n+1-af)) (penalty)

with a_(n+1) = (u_(n+1) - u_pred) / (beta dt^2) + a_n. Unknowns: w = [u_(n+1), lam]
(displacement node by node, then the corner pressures). f_int and its tangent are FElupe's
assembly of :class:`.problem.MixedMaterial` (tensortrax's derivatives of the energy); M is
the consistent mass int rho N_a N_b dV of the displacement field (same quadrature: exact on
the rectangular Q2 cells). The tangent dR/dw:

    [ c (1 - am) M + (1 - af) K_uu(u_f, lam)    K_up(u_f)           ]
    [ K_pu(u_(n+1))  or  (1 - af) K_pu(u_f)     K_pp                ],   c = 1 / (beta dt^2)

unsymmetric for the mixed model (its constraint row at the new state), solved by SuperLU
in reverse Cuthill-McKee order (:func:`.problem.solve_sparse`).
The Newton scale and test are the DOLFINx backend's (||R|| over the free rows against
||f_ext|| + ||M a_n||).

Supports: the fixed dofs removed, or the hinge's exact elimination u = T w_r
(:class:`.problem.Reduction`; the same T for the step and for the initial acceleration,
the constraint being linear and homogeneous).

Initial acceleration at rest at u0 (the DOLFINx backend's ``start_terms``): plane stress
M a0 = f_ext - f_int(u0); mixed plane strain the saddle point [[M, k/mu K_up], [k/mu K_pu, 0]]
with the multiplier scaled by k = rho hc^2 (then phat0 = k lam0 / mu); penalty the step's
equations without stiffness, [[M, K_up], [0, K_pp]]. All linear in (a0, lam0): one solve.

Energies (full beam, J): kinetic v^T M v / 2, strain int W_stored dV (the law's psi; penalty
+ alpha/2 (J - 1)^2), the dead loads' potentials -f . (X + u) (exact: the consistent nodal
forces integrate the isoparametric X). Positions at any reference point by the cell's
shape functions.
"""
from __future__ import annotations

import numpy as np
from scipy.sparse import bmat, csr_matrix

from mechanics.time_loop import Energies, StepFailure

from ..geometry import geometry_for
from .problem import NewtonSystem, Setup, StaticModel, set_up, solve_sparse


def _assemble(fun, v, dV, u=None, grad_v=None, grad_u=None):
    """FElupe's assembly of one form on single fields (a vector, or a sparse matrix)."""
    import felupe as fe

    form = fe.IntegralForm(fun=[fun], v=fe.FieldContainer([v]), dV=dV,
                           u=None if u is None else fe.FieldContainer([u]),
                           grad_v=grad_v, grad_u=grad_u)
    out = form.assemble()
    return out.tocsr() if u is not None else np.asarray(out.todense()).ravel()


def _det_and_cofactor(F):
    """J and dJ/dF = J F^-T of FElupe's (i, J, q, c) gradients."""
    Fm = np.moveaxis(F, (0, 1), (-2, -1))
    J = np.linalg.det(Fm)
    dJ = J[..., None, None] * np.swapaxes(np.linalg.inv(Fm), -1, -2)
    return J, np.moveaxis(dJ, (-2, -1), (0, 1))


class StepSystem(NewtonSystem):
    """One step's Newton system for :func:`mechanics.newton.newton`: R(w) and its tangent at
    w, the fixed rows removed (their unknowns stay as restored); the problem's ordering of
    the solve is shared by every step."""

    def __init__(self, problem: "DynamicProblem", residual, tangent):
        super().__init__(problem.n_dof, problem.fixed, problem._order, problem.setup.reduction)
        self.residual, self.tangent = residual, tangent


class DynamicProblem:
    """The step equations of the set-up (arrays: [u, lam] as :class:`.problem.System`'s)."""

    def __init__(self, s: Setup, model: str, incompressibility: str, density: float,
                 cell_size: float, height: float):
        import felupe as fe

        self.setup, self.height = s, float(height)
        self.geometry = geometry_for(model)
        self.effects = list(s.effects)
        self.mixed = incompressibility == "mixed"
        self.rho, self.cell_size = float(density), float(cell_size)
        self.u_field = s.fields[0]
        self.p_field = s.fields[1] if len(s.fields.fields) > 1 else None
        self.dV = self.u_field.region.dV
        self.nu = self.u_field.values.size
        self.n_dof = s.ndof
        self.n_free = s.n_free
        self.fixed, self.free = s.fixed, ~s.fixed
        self.u_dofs = np.arange(self.nu)
        self.p_mask = np.zeros(self.n_dof, bool)
        self.p_mask[self.nu:] = True
        gdim = self.u_field.dim
        eye = np.broadcast_to(self.rho * np.eye(gdim)[:, :, None, None], (gdim, gdim) + self.dV.shape)
        self.M = _assemble(np.ascontiguousarray(eye), self.u_field, self.dV, self.u_field,
                           grad_v=[False], grad_u=[False])
        self._fe = fe
        self._points: dict = {}
        self._order: dict = {}
        self.system = None

    # -- fields and FElupe's forms of the material ----------------------------------------------
    def _set(self, u, lam=None) -> None:
        self.u_field.values[:] = u[:self.nu].reshape(self.u_field.values.shape)
        if self.p_field is not None and lam is not None:
            self.p_field.values[:] = lam.reshape(self.p_field.values.shape)

    def _material(self, u, lam, hessian: bool):
        """[dW/dF, dW/dphat] (or the hessian blocks [uu, up, pp]) assembled at (u, lam)."""
        fe, fields = self._fe, self.setup.fields
        self._set(u, lam)
        fun = self.setup.material.evaluate(fields.extract(), hessian)
        form = fe.IntegralForm(fun=fun, v=fields, dV=self.dV, u=fields if hessian else None)
        if hessian:
            return [b.tocsr() for b in form.assemble(block=False)]
        return [np.asarray(b.todense()).ravel() for b in form.assemble(block=False)]

    def _constraint(self, u, hessian: bool):
        """The pressure row's J-part at u: int mu (J - 1) q dV, or its u-block (assembled
        as K_up, the material's F-phat block)."""
        self._set(u)
        J, dJ = _det_and_cofactor(self.u_field.extract())
        mu = self.setup.mu
        if hessian:
            return _assemble(mu * dJ, self.u_field, self.dV, self.p_field, grad_v=[True], grad_u=[False])
        return _assemble(mu * (J - 1.0), self.p_field, self.dV, grad_v=[False])

    def _norm(self, r: np.ndarray) -> float:
        r = r.copy()
        r[self.fixed] = 0.0
        return float(np.linalg.norm(r))

    # -- used by reference_fem.stepper ------------------------------------------------------------
    def initial_acceleration(self, u0: np.ndarray, rtol: float, max_iterations: int) -> np.ndarray:
        """a0 at rest at u0 (pressure components: the multiplier phat0); raises StepFailure."""
        f = self.setup.f_ext
        nu = self.nu
        lam = None if self.p_field is None else np.zeros(self.n_dof - nu)
        if self.p_field is None:
            A = self.M
            b = f - self._material(u0, None, False)[0]
            scale = 1.0
        else:
            g = self._material(u0, lam, False)
            Kuu, Kup, Kpp = self._material(u0, lam, True)
            b = f - np.concatenate(g)
            if self.mixed:     # cof F0 : grad a0 = 0, the multiplier scaled by k = rho hc^2
                scale = self.rho * self.cell_size ** 2 / self.setup.mu
                A = bmat([[self.M, scale * Kup], [scale * Kup.T, None]])
                b[nu:] = 0.0
            else:
                scale = 1.0
                A = bmat([[self.M, Kup], [None, Kpp]])
        red = self.setup.reduction
        x = solve_sparse(red.matrix(csr_matrix(A)), red.vector(b), {})
        if not np.all(np.isfinite(x)):
            raise StepFailure("initial acceleration: singular or failed linear solve (SuperLU)", 1)
        w0 = red.expand(x)
        w0[self.p_mask] *= scale
        return w0

    def solve_step(self, u_n, a_n, u_pred, guess, beta_dt2: float, alpha_m: float, alpha_f: float,
                   rtol: float, max_iterations: int, small_correction) -> tuple[np.ndarray, int]:
        """u_(n+1) (with lam) of one step and its Newton iterations; raises StepFailure."""
        from mechanics.newton import newton

        nu, M, f = self.nu, self.M, self.setup.f_ext
        un, an, up = u_n[:nu], a_n[:nu], u_pred[:nu]
        c = 1.0 / beta_dt2
        pressure = self.p_field is not None
        at_new = pressure and self.mixed and alpha_f != 0.0

        def split(w):
            u = w[:nu]
            return u, (1 - alpha_f) * u + alpha_f * un, (w[nu:] if pressure else None)

        def residual(w):
            u, uf, lam = split(w)
            am_ = (1 - alpha_m) * ((u - up) * c + an) + alpha_m * an
            g = self._material(uf, lam, False)
            r = np.concatenate([M @ am_ + g[0]] + g[1:]) - f
            if at_new:      # the constraint at the new state (lam's own term is zero when mixed)
                r[nu:] = self._constraint(u, False)
            return r

        def tangent(w):
            u, uf, lam = split(w)
            Kuu = c * (1 - alpha_m) * M
            if not pressure:
                return Kuu + (1 - alpha_f) * self._material(uf, None, True)[0]
            K, Kup, Kpp = self._material(uf, lam, True)
            Kpu = self._constraint(u, True).T if at_new else (1 - alpha_f) * Kup.T
            return bmat([[Kuu + (1 - alpha_f) * K, Kup], [Kpu, Kpp]]).tocsr()

        system = StepSystem(self, residual, tangent)
        system.restore(guess)
        self.system = system
        scale = self._norm(f) + self._norm(np.concatenate([M @ an, np.zeros(self.n_dof - nu)]))
        its, _ = newton(system, scale, rtol, max_iterations, small_correction)
        return system.save(), its

    def energies(self, u: np.ndarray, v: np.ndarray) -> Energies:
        """Kinetic, strain and the dead loads' potentials (J, full beam)."""
        import tensortrax as tr

        s, nu = self.setup, self.nu
        width = s.width
        vu = v[:nu]
        kinetic = 0.5 * width * float(vu @ (self.M @ vu))
        self._set(u)
        F = self.u_field.extract()
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            W = tr.function(s.material.psi, ntrax=2)(np.ascontiguousarray(F))
            if s.material.alpha is not None:
                J, _ = _det_and_cofactor(F)
                W = W + s.material.alpha / 2 * (J - 1.0) ** 2
        strain = width * float(np.sum(W * self.dV))
        X = np.concatenate([s.mesh.points.ravel(), np.zeros(self.n_dof - nu)])
        pot = {k: -width * float(fk @ (X + np.concatenate([u[:nu], np.zeros(self.n_dof - nu)])))
               for k, fk in s.loads.items()}
        return Energies(kinetic, strain, pot.get("gravity", 0.0), pot.get("tip_force"))

    def positions(self, u: np.ndarray, points) -> np.ndarray:
        """Deformed positions (n, gdim) in m of reference points (n, gdim) at the state u."""
        points = np.asarray(points, float)
        key = points.tobytes()
        if key not in self._points:
            self._points[key] = self._locate(points)
        cells, N = self._points[key]
        U = u[:self.nu].reshape(self.u_field.values.shape)
        conn = self.setup.mesh.cells[cells]                        # (n, nodes)
        return points + np.einsum("na,nai->ni", N, U[conn])

    def _locate(self, points):
        """(cell, shape function values) of each point: the cells are axis-aligned boxes."""
        mesh = self.setup.mesh
        element = self.u_field.region.element
        corners = mesh.points[mesh.cells]                         # (cells, nodes, gdim)
        lo, hi = corners.min(axis=1), corners.max(axis=1)
        tol = 1e-9 * np.ptp(mesh.points, axis=0).max()
        cells, N = [], []
        for x in points:
            inside = np.flatnonzero(np.all((lo - tol <= x) & (x <= hi + tol), axis=1))
            if not len(inside):
                raise ValueError(f"point {tuple(x)} outside the mesh")
            k = int(inside[0])
            r = np.clip(2.0 * (x - lo[k]) / (hi[k] - lo[k]) - 1.0, -1.0, 1.0)
            cells.append(k)
            N.append(element.function(r))
        return np.array(cells), np.array(N)

    def write(self, path, fmt: str, w: np.ndarray, t: float = 0.0):
        """The corner mesh with the displacement (and pressure) of the state w, by meshio
        (:meth:`.problem.StaticModel.write`); ``t`` is not stored (one state per file)."""
        self._set(w, w[self.nu:] if self.p_field is not None else None)
        return StaticModel(self.setup).write(path, fmt)


def build_dynamic_problem(scene, settings) -> DynamicProblem:
    """The scene's beam (pinned, hinged or clamped at x = 0) as a continuum in motion."""
    b = scene.beam
    return DynamicProblem(set_up(scene, settings), settings.model, settings.incompressibility,
                          scene.material.density, b.height / settings.cells_height, b.height)
