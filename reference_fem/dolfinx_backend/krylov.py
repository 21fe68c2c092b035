"""The iterative Newton solver's PETSc side (``[fem] linear_solver = "iterative"``): its
default options, the rigid-body modes, and :class:`ALPreconditioner`. Only petsc4py: the
DOLFINx calls it needs (index sets, the degree-1 interpolation, the pressure mass) stay
in :mod:`reference_fem.dolfinx_backend.fem.nonlinear_system`, which builds and drives it
(:class:`~reference_fem.dolfinx_backend.fem.nonlinear_system.NonlinearSystem`). Measurements:
``experiments/iterative_fieldsplit.md`` and README, "A 100-million-unknown reference on a
cluster"."""
from __future__ import annotations

import numpy as np
from petsc4py import PETSc

# PETSc options prefix of the iterative solver's KSP: every default below can be overridden
# from the command line or PETSC_OPTIONS, e.g. -fem_ksp_monitor, -fem_ksp_rtol 1e-8,
# -fem_fieldsplit_u_pc_type hypre, -fem_pc_fieldsplit_schur_fact_type upper.
OPTIONS_PREFIX = "fem_"
# Relative Krylov tolerance. The Newton loop stops at ||R|| <= rtol r_ref (rtol 1e-8 by
# default) and starts every increment from ||R|| <= r_ref; a linear residual <= 1e-10 ||R||
# adds <= 1e-10 r_ref to the next Newton residual, 1 % of the smallest target: the Newton
# iterations (and so the load path) are those of the direct solver.
KRYLOV_RTOL = 1e-10
# Absolute floor: 1e-12 x the first right-hand side solved (~ r_ref / load_steps in statics:
# the first Newton update of the first increment): 1e-4 of the Newton target, and above the
# round-off floor of the last, already tiny, Newton residuals (where a purely relative 1e-10
# would stagnate). Not the largest one: a diverging trial increment would raise the floor
# above later Newton residuals, whose updates then stay zero.
KRYLOV_ATOL_FACTOR = 1e-12
KRYLOV_MAX_IT = 1000
AL_GAMMA = 3.0
# Defaults of the iterative solver (options database, set only where the user has not):
# FGMRES on the monolithic matrix. The fieldsplit_* keys apply to the PCFIELDSPLIT
# variants only (-fem_schur al-fieldsplit | mass, and the initial-acceleration system of
# dynamics, "selfp"): Schur (full factorisation) over the displacement and pressure dofs,
# displacement block: one V-cycle of GAMG with the rigid-body modes. The default
# (-fem_schur al) is ALPreconditioner (PMG_DEFAULTS).
ITERATIVE_DEFAULTS = {
    "ksp_type": "fgmres",
    "ksp_gmres_restart": "200",
    # classical Gram-Schmidt with a second pass always: without it the Arnoldi basis loses
    # orthogonality on these ill-conditioned systems (cond ~1e7-1e8: slender bending) and
    # FGMRES stalls near 1e-5 relative until the restart (measured 8 x 1 x 1: max 234 ->
    # 44 iterations per Newton update)
    "ksp_gmres_cgs_refinement_type": "refine_always",
    "pc_fieldsplit_schur_fact_type": "full",
    "fieldsplit_u_ksp_type": "preonly",
    "fieldsplit_u_pc_type": "gamg",
    "fieldsplit_u_pc_gamg_threshold": "0.02",
    "fieldsplit_u_mg_levels_ksp_type": "chebyshev",
    "fieldsplit_u_mg_levels_ksp_max_it": "4",
    "fieldsplit_u_mg_levels_pc_type": "sor",
    "fieldsplit_p_ksp_type": "preonly",
    "fieldsplit_p_pc_type": "jacobi",
}


# The default preconditioner ("-fem_schur al"): :class:`ALPreconditioner`, a Python PC on
# the monolithic matrix. Its displacement solve (options prefix fem_pmg_) is one V-cycle of
# a two-level p-multigrid: 6 Chebyshev/Jacobi sweeps (pre and post) on the degree-2
# augmented block, and the Galerkin product P^T A P on the vector degree-1 space of the
# same mesh (P the interpolation matrix) as the coarse level, factored by MUMPS (1/8 of
# the displacement unknowns, ~1/7 of the nonzeros per row). The coarse level may be
# indefinite (Newton iterates off the equilibrium path: measured), so no CG there.
# Scalable but weaker (measured, experiments/iterative_fieldsplit.md): GMRES to 1e-3 with GAMG
# on the coarse level, -fem_pmg_mg_coarse_ksp_type gmres -fem_pmg_mg_coarse_ksp_rtol 1e-3
# -fem_pmg_mg_coarse_pc_type gamg -fem_pmg_mg_coarse_pc_gamg_square_graph 0
# -fem_pmg_mg_coarse_pc_gamg_threshold 0.05 -fem_pmg_mg_coarse_mg_levels_ksp_max_it 4
# (the rigid-body modes of the degree-1 nodes are attached to the coarse matrix).
PMG_PREFIX = OPTIONS_PREFIX + "pmg_"
PMG_DEFAULTS = {
    "ksp_type": "preonly",
    "mg_levels_ksp_type": "chebyshev",
    "mg_levels_pc_type": "jacobi",
    "mg_levels_ksp_max_it": "6",
    "mg_coarse_ksp_type": "preonly",
    "mg_coarse_pc_type": "lu",
    "mg_coarse_pc_factor_mat_solver_type": "mumps",
}


def set_defaults(prefix: str, defaults: dict) -> None:
    """Put ``defaults`` into PETSc's options database under ``prefix``, each only where
    the user has not set it (the command line and PETSC_OPTIONS win)."""
    opts = PETSc.Options()
    for k, v in defaults.items():
        if not opts.hasName(prefix + k):
            opts.setValue(prefix + k, v)


def rigid_body_modes(x: np.ndarray, gdim: int, template) -> PETSc.NullSpace:
    """Orthonormal rigid-body modes of the nodes ``x`` (owned, (n, >= gdim), node-major
    vectors laid out like ``template``)."""
    modes = [np.eye(gdim)[i] * np.ones((len(x), gdim)) for i in range(gdim)]
    for i, j in ([(0, 1)] if gdim == 2 else [(0, 1), (1, 2), (2, 0)]):
        m = np.zeros((len(x), gdim))
        m[:, i], m[:, j] = -x[:, j], x[:, i]
        modes.append(m)
    vecs = []
    for m in modes:
        v = template.duplicate()
        v.setArray(m.reshape(-1))
        for u in vecs:
            v.axpy(-v.dot(u), u)
        v.normalize()
        vecs.append(v)
    return PETSc.NullSpace().create(vectors=vecs, comm=template.getComm())


class ALPreconditioner:
    """The augmented-Lagrangian block preconditioner of the Newton matrix K = [[A, B^T],
    [B, 0]] (displacement u, scaled pressure p), a Python PC (petsc4py) on the monolithic
    matrix: the exact inverse of [[A, B^T], [B, -(s/gamma) M_L]] (M_L the lumped pressure
    mass, s the pressure scale mu) by block elimination of the diagonal pressure block,

        y_u = A_gamma^-1 (r_u + (gamma/s) B^T M_L^-1 r_p),  A_gamma = A + (gamma/s) B^T M_L^-1 B,
        y_p = -(gamma/s) M_L^-1 (r_p - B y_u),

    with A_gamma^-1 replaced by a KSP of prefix fem_pmg_ (default one two-level p-multigrid
    V-cycle, :data:`PMG_DEFAULTS`: the interpolation ``prolong`` from the vector degree-1
    space, whose rigid-body modes ``coarse_modes`` GAMG is given)."""

    def __init__(self, is_u, is_p, lumped, scale: float, gamma: float, prolong, coarse_x, gdim: int):
        self.is_u, self.is_p, self.gamma, self.scale = is_u, is_p, gamma, scale
        self.prolong, self.coarse_x, self.gdim = prolong, coarse_x, gdim
        lp = lumped.getSubVector(is_p)
        self.dinv = lp.copy()                      # -(gamma/s) M_L^-1
        self.dinv.reciprocal()
        self.dinv.scale(-gamma / scale)
        lumped.restoreSubVector(is_p, lp)
        self.ksp = None
        self.Auu = self.Aup = self.Apu = self.Aug = self.coarse = None
        self.inner_iterations = 0

    def setUp(self, pc):
        A = pc.getOperators()[0]
        self.Auu = A.createSubMatrix(self.is_u, self.is_u, submat=self.Auu)
        self.Aup = A.createSubMatrix(self.is_u, self.is_p, submat=self.Aup)
        self.Apu = A.createSubMatrix(self.is_p, self.is_u, submat=self.Apu)
        scaled = self.Apu.copy()
        d = self.dinv.copy()
        d.scale(-1.0)
        scaled.diagonalScale(L=d)
        bt = self.Aup.matMult(scaled)
        scaled.destroy()
        if self.Aug is not None:
            self.Aug.destroy()
        self.Aug = self.Auu.copy()
        self.Aug.axpy(1.0, bt, structure=PETSc.Mat.Structure.DIFFERENT_NONZERO_PATTERN)
        bt.destroy()
        self.Aug.setBlockSize(self.gdim)
        if self.coarse is not None:
            self.coarse.destroy()
        self.coarse = self.Aug.ptap(self.prolong)
        self.coarse.setBlockSize(self.gdim)
        self.coarse.setNearNullSpace(rigid_body_modes(self.coarse_x, self.gdim, self.coarse.createVecRight()))
        # a new inner solver per matrix: a reused one keeps stale state (measured on 16 x 1
        # x 1: 26 -> 61 mean FGMRES iterations, growing along the load path; not traced,
        # suspect the Chebyshev smoother's eigenvalue bounds)
        if self.ksp is not None:
            self.ksp.destroy()
        set_defaults(PMG_PREFIX, PMG_DEFAULTS)
        self.ksp = PETSc.KSP().create(A.getComm())
        self.ksp.setOptionsPrefix(PMG_PREFIX)
        mg = self.ksp.getPC()
        mg.setType("mg")
        mg.setMGLevels(2)
        mg.setMGType(PETSc.PC.MGType.MULTIPLICATIVE)
        mg.setMGInterpolation(1, self.prolong)
        self.ksp.setFromOptions()
        self.ru, self.yu = self.Aug.createVecs()
        self.tp = self.dinv.duplicate()
        self.ksp.setOperators(self.Aug)
        mg = self.ksp.getPC()
        mg.getMGSmoother(1).setOperators(self.Aug)
        mg.getMGCoarseSolve().setOperators(self.coarse)
        self.ksp.setUp()

    def apply(self, pc, r, y):
        ru, rp = r.getSubVector(self.is_u), r.getSubVector(self.is_p)
        tp, tu = self.tp, self.ru
        tp.pointwiseMult(self.dinv, rp)        # D^-1 r_p
        self.Aup.mult(tp, tu)
        tu.aypx(-1.0, ru)                      # r_u - B^T D^-1 r_p
        self.ksp.solve(tu, self.yu)
        self.inner_iterations += self.ksp.getIterationNumber()
        self.Apu.mult(self.yu, tp)
        tp.aypx(-1.0, rp)
        r.restoreSubVector(self.is_u, ru)
        r.restoreSubVector(self.is_p, rp)
        yu, yp = y.getSubVector(self.is_u), y.getSubVector(self.is_p)
        self.yu.copy(yu)
        yp.pointwiseMult(self.dinv, tp)        # D^-1 (r_p - B y_u)
        y.restoreSubVector(self.is_u, yu)
        y.restoreSubVector(self.is_p, yp)

    def destroy(self, pc=None):
        for m in (self.ksp, self.Auu, self.Aup, self.Apu, self.Aug, self.coarse):
            if m is not None:
                m.destroy()
        self.ksp = self.Auu = self.Aup = self.Apu = self.Aug = self.coarse = None
