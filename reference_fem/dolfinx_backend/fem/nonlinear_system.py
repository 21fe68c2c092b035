"""The nonlinear system of a problem and its Newton increments: LU (MUMPS) or the Krylov
solver of :mod:`reference_fem.dolfinx_backend.krylov`, with a low-rank term outside the
forms (the end moment's couple) and an exact elimination of linear constraints (the hinge)."""
from __future__ import annotations

import numpy as np
import ufl
from mpi4py import MPI
from petsc4py import PETSc

import dolfinx
import dolfinx.fem
import dolfinx.fem.petsc

from ...couple import Branches
from ..krylov import (AL_GAMMA, ITERATIVE_DEFAULTS, KRYLOV_ATOL_FACTOR, KRYLOV_MAX_IT, KRYLOV_RTOL, OPTIONS_PREFIX,
                      ALPreconditioner, rigid_body_modes, set_defaults)
from ...settings import LINEAR_SOLVERS
from .discretisation import COMM, Discretisation
from .end_face import FaceHinge


def _prolongation(disc: Discretisation, u_map: np.ndarray, bc_dofs: np.ndarray):
    """The interpolation of the vector degree-1 Lagrange space of the mesh into the
    displacement space, as a matrix whose rows are the displacement block's (the owned
    displacement dofs of W, ``u_map`` its sorted local indices, global rows from
    the rank's offset) and whose columns are the degree-1 space's global dofs; rows of the
    Dirichlet dofs ``bc_dofs`` (local indices of W) are zero. Returns the matrix and
    the owned degree-1 node coordinates."""
    W, comm = disc.W, disc.comm
    gdim = disc.mesh.geometry.dim
    V2, u_all = W.sub(0).collapse()
    u_all = np.asarray(u_all, dtype=np.int64)
    V1 = dolfinx.fem.VectorFunctionSpace(disc.mesh, ("Lagrange", 1))
    interp = dolfinx.cpp.fem.petsc.interpolation_matrix(V1._cpp_object, V2._cpp_object)
    interp.assemble()
    ai, aj, av = interp.getValuesCSR()
    n2 = V2.dofmap.index_map.size_local * gdim
    if len(ai) - 1 != n2 or n2 != len(u_map):
        raise RuntimeError("interpolation matrix rows are not the owned displacement dofs")
    pos = np.full(len(disc.w.x.array), -1, dtype=np.int64)
    pos[u_map] = np.arange(len(u_map))
    rows = pos[u_all[:n2]]          # row of the V2 dof j in the displacement block
    bc_rows = pos[bc_dofs]
    bc_rows = bc_rows[bc_rows >= 0]
    if (rows < 0).any():
        raise RuntimeError("an owned displacement dof of V2 is not owned in W")
    order = np.argsort(rows)        # block row i is V2 row order[i]
    lengths = np.diff(ai)[order]
    row_of = np.repeat(np.arange(n2), lengths)
    starts = np.repeat(ai[:-1][order], lengths)
    offsets = np.arange(len(row_of)) - np.repeat(np.cumsum(lengths) - lengths, lengths)
    idx = starts + offsets
    cols, vals = aj[idx], av[idx].copy()
    vals[np.isin(row_of, bc_rows)] = 0.0
    keep = np.abs(vals) > 1e-14
    row_of, cols, vals = row_of[keep], cols[keep], vals[keep]
    indptr = np.concatenate([[0], np.cumsum(np.bincount(row_of, minlength=n2))])
    n1 = V1.dofmap.index_map.size_local * gdim
    N1 = V1.dofmap.index_map.size_global * gdim
    P = PETSc.Mat().createAIJ(size=((n2, PETSc.DECIDE), (n1, N1)), comm=comm,
                              csr=(indptr.astype(PETSc.IntType), cols.astype(PETSc.IntType), vals))
    P.assemble()
    interp.destroy()
    x1 = V1.tabulate_dof_coordinates()[:V1.dofmap.index_map.size_local, :gdim]
    return P, x1


class NonlinearSystem:
    """R(w) = 0 with homogeneous Dirichlet conditions; Newton increments by LU (MUMPS)
    or, with ``linear_solver = "iterative"``, by a Krylov method (:meth:`_iterative`).

    ``low_rank``: a term of rank k outside the forms (the end moment's couple), an object
    with ``vectors`` (k PETSc vectors U, zero at the Dirichlet dofs) and
    ``coefficients(x) -> (c (k,), C (k, k))`` at the state x: R += U c, K += U C U^T. The
    increment solves (K + U C U^T) dw = R exactly by Sherman-Morrison-Woodbury with the
    one factorisation of K: y = K^-1 R, Z = K^-1 U (k more solves),
    dw = y - Z C (I + U^T Z C)^-1 U^T y. ``reduction``: an exact elimination of linear
    constraints (the hinge, :class:`FaceHinge`): the residual T^T R, the tangent
    T^T K T, the increment T dw_r (direct solver only). ``save`` and ``restore`` keep the
    low-rank term's path state (``branch``, the end moment's continued rotation) with the
    state.

    ``unknown``: the function of W solved for (default ``disc.w``). ``pressure_scale``:
    the iterative solver's Schur-complement approximation -pressure_scale M (M the mass
    matrix of the scaled pressure; the modulus mu of p = mu phat), or None for PETSc's
    "selfp" (the system of the initial acceleration, whose (u, u) block is a mass
    matrix)."""

    def __init__(self, disc: Discretisation, residual, bcs, unknown=None, linear_solver: str = "direct",
                 pressure_scale: float | None = None, low_rank=None, reduction: FaceHinge | None = None):
        if linear_solver not in LINEAR_SOLVERS:
            raise ValueError(f"linear_solver: {linear_solver!r}; allowed: {LINEAR_SOLVERS}")
        if reduction is not None and linear_solver != "direct":
            raise ValueError("a constraint reduction (the hinge) needs the direct linear solver")
        self.low_rank, self.reduction = low_rank, reduction
        self._C = None
        self._branches = Branches(low_rank)   # the low-rank term's path state beside the saved states
        self.disc = disc
        self.w = disc.w if unknown is None else unknown
        self.bcs = list(bcs)
        self.linear_solver = linear_solver
        self.pressure_scale = pressure_scale
        jacobian = ufl.derivative(residual, self.w, disc.trial)
        self.R = dolfinx.fem.form(residual)
        self.K = dolfinx.fem.form(jacobian)
        self.b = dolfinx.fem.petsc.create_vector(self.R)
        self.A = dolfinx.fem.petsc.create_matrix(self.K)
        self.dx = self.b.duplicate()
        self.krylov_iterations: list[int] = []   # per Newton update (iterative solver)
        if reduction is not None:
            self.b_r, self.dx_r = self.b.duplicate(), self.b.duplicate()
        if low_rank is not None:
            self._U = [self._restricted(u) for u in low_rank.vectors]
            self._Z = [u.duplicate() for u in self._U]
        self._rhs_max = 0.0
        if linear_solver == "iterative":
            self._split_sets()
        self.ksp = self._new_ksp()

    def _new_ksp(self):
        return self._lu(self.disc.comm) if self.linear_solver == "direct" else self._iterative()

    @staticmethod
    def _lu(comm=COMM):
        ksp = PETSc.KSP().create(comm)
        ksp.setType("preonly")
        pc = ksp.getPC()
        pc.setType("lu")
        pc.setFactorSolverType("mumps")
        return ksp

    # -- the iterative solver ------------------------------------------------------------
    def _split_sets(self) -> None:
        """Index sets (global PETSc rows, owned) of the displacement and the pressure dofs,
        the rigid-body modes as the displacement block's near-nullspace, and the assembled
        pressure mass matrix (on the pressure rows)."""
        disc, W = self.disc, self.disc.W
        comm = disc.comm
        gdim = disc.mesh.geometry.dim
        imap = W.dofmap.index_map
        n_owned, offset = imap.size_local * W.dofmap.index_map_bs, imap.local_range[0] * W.dofmap.index_map_bs
        if disc.pressure:
            V, u_all = W.sub(0).collapse()
            u_all = np.asarray(u_all, dtype=np.int64)    # V dof (node-major) -> W dof
            nodes = u_all.reshape(-1, gdim)
            owned = np.nonzero((nodes < n_owned).all(axis=1))[0]
            # PCFIELDSPLIT wants sorted sets; a node's components are consecutive in W,
            # so sorting by node keeps the blocks (block size gdim for GAMG)
            owned_nodes = owned[np.argsort(nodes[owned, 0])]
            u_map = nodes[owned_nodes].reshape(-1)
            if not (np.diff(u_map) > 0).all():
                raise RuntimeError("displacement dofs of a node are not consecutive in W")
            _, p_map = W.sub(1).collapse()
            p_map = np.asarray(p_map, dtype=np.int64)
            p_map = np.sort(p_map[p_map < n_owned])
            self.is_u = PETSc.IS().createGeneral((u_map + offset).astype(PETSc.IntType), comm=comm)
            self.is_u.setBlockSize(gdim)
            self.is_p = PETSc.IS().createGeneral((p_map + offset).astype(PETSc.IntType), comm=comm)
        else:
            V = W
            self.is_u = self.is_p = None
        # rigid-body modes of the owned displacement nodes, in the displacement block's
        # layout (node-major: the order of is_u, or W's own without a pressure)
        x = V.tabulate_dof_coordinates()[:, :gdim]
        template = dolfinx.fem.Function(W).vector
        if disc.pressure:
            sub = template.getSubVector(self.is_u)
            layout = sub.copy()
            template.restoreSubVector(self.is_u, sub)
            x = x[owned_nodes]
        else:
            layout = template.copy()
            x = x[: n_owned // gdim]
        self.near_nullspace = rigid_body_modes(x, gdim, layout)
        self.M = None
        if disc.pressure:
            _, q = ufl.split(disc.test)
            _, p = ufl.split(disc.trial)
            Mform = dolfinx.fem.form(p * q * disc.dx)
            full = dolfinx.fem.petsc.assemble_matrix(Mform)
            full.assemble()
            self.M = full.createSubMatrix(self.is_p, self.is_p)
            full.destroy()
            lumped = dolfinx.fem.petsc.assemble_vector(dolfinx.fem.form(q * disc.dx))
            lumped.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
            self.lumped = lumped    # row sums of the pressure mass at the pressure rows, 0 elsewhere
            self.is_u.compose("nearnullspace", self.near_nullspace)
            bc_dofs = np.concatenate([bc.dof_indices()[0][:bc.dof_indices()[1]] for bc in self.bcs] or
                                     [np.zeros(0, dtype=np.int64)])
            self.prolong, self.coarse_x = _prolongation(disc, u_map, bc_dofs)
        self._Sp = None
        self.P = None

    @property
    def schur(self) -> str:
        """The Schur approach: "al" (default: :class:`ALPreconditioner`), "al-fieldsplit"
        (the same augmented matrix through PCFIELDSPLIT/selfp with GAMG on the displacement
        block: the previous default, kept for comparison), "mass" (-mu M), or "selfp" (no
        pressure scale given); option -fem_schur."""
        if self.pressure_scale is None:
            return "selfp"
        return PETSc.Options().getString(OPTIONS_PREFIX + "schur", "al")

    def _iterative(self):
        """A Krylov solver (FGMRES) with PCFIELDSPLIT (Schur) on the mixed matrix, or GAMG
        with the rigid-body modes on a displacement-only one; options prefix
        :data:`OPTIONS_PREFIX` (``setFromOptions`` last: the user's options win)."""
        ksp = PETSc.KSP().create(self.disc.comm)
        ksp.setOptionsPrefix(OPTIONS_PREFIX)
        set_defaults(OPTIONS_PREFIX, ITERATIVE_DEFAULTS)
        ksp.setTolerances(rtol=KRYLOV_RTOL, atol=0.0, max_it=KRYLOV_MAX_IT)
        pc = ksp.getPC()
        if self.disc.pressure and self.schur == "al":
            gamma = PETSc.Options().getReal(OPTIONS_PREFIX + "al_gamma", AL_GAMMA)
            self.al = ALPreconditioner(self.is_u, self.is_p, self.lumped, self.pressure_scale, gamma,
                                       self.prolong, self.coarse_x, self.disc.mesh.geometry.dim)
            pc.setType("python")
            pc.setPythonContext(self.al)
        elif self.disc.pressure:
            pc.setType("fieldsplit")
            if self.schur == "al-fieldsplit":
                pc.setFieldSplitIS(("p", self.is_p), ("u", self.is_u))
            else:
                pc.setFieldSplitIS(("u", self.is_u), ("p", self.is_p))
            pc.setFieldSplitType(PETSc.PC.CompositeType.SCHUR)
        else:
            pc.setType("gamg")
        return ksp

    def _configure(self) -> None:
        """Per assembled matrix: the Schur preconditioner's matrix, tolerances."""
        pc = self.ksp.getPC()
        schur = self.schur if self.disc.pressure else None
        if schur == "al":
            pass    # ALPreconditioner.setUp, at the solve
        elif schur == "al-fieldsplit":
            gamma = PETSc.Options().getReal(OPTIONS_PREFIX + "al_gamma", AL_GAMMA)
            if self.P is None:
                self.P = self.A.duplicate(copy=True)
                self._D = self.lumped.copy()
                self._D.scale(-self.pressure_scale / gamma)
            else:
                self.A.copy(self.P, structure=PETSc.Mat.Structure.SAME_NONZERO_PATTERN)
            self.P.setDiagonal(self._D, addv=PETSc.InsertMode.ADD_VALUES)
            self.ksp.setOperators(self.A, self.P)
            pc.setFieldSplitSchurPreType(PETSc.PC.SchurPreType.SELFP)
        elif schur == "selfp":
            pc.setFieldSplitSchurPreType(PETSc.PC.SchurPreType.SELFP)
        elif schur is not None:
            if self._Sp is None:
                # -mu M + the Jacobian's own (p, p) block (zero for the exact
                # constraint, the constant -mu^2/alpha M of the penalty)
                self._Sp = self.A.createSubMatrix(self.is_p, self.is_p)
                self._Sp.axpy(-self.pressure_scale, self.M)
            pc.setFieldSplitSchurPreType(PETSc.PC.SchurPreType.USER, self._Sp)
        else:
            self.A.setNearNullSpace(self.near_nullspace)
        rtol, _, dtol, max_it = self.ksp.getTolerances()
        self.ksp.setTolerances(rtol=rtol, atol=KRYLOV_ATOL_FACTOR * self._rhs_max, divtol=dtol, max_it=max_it)
        self.ksp.setFromOptions()
        if schur == "al-fieldsplit":
            # the displacement block is the Schur complement of the diagonal pressure
            # block, assembled by selfp inside PCFIELDSPLIT: its near-nullspace can be set
            # only once the split exists
            self.ksp.setUp()
            _, sub = pc.getFieldSplitSubKSP()
            Su = sub.getOperators()[1]
            if Su.getNearNullSpace() is None or Su.getNearNullSpace().handle != self.near_nullspace.handle:
                Su.setNearNullSpace(self.near_nullspace)
                Su.assemble()   # a new state: GAMG (set up by setUp) is rebuilt with the modes

    @property
    def any_rank(self):
        """None on one rank; over several, flag -> True on every rank if any rank's is."""
        comm = self.disc.comm
        if comm.size == 1:
            return None
        return lambda flag: bool(comm.allreduce(bool(flag), op=MPI.LOR))

    @property
    def x(self):
        return self.w.vector

    def _restricted(self, v):
        """T^T v (a new vector) with a reduction, else v itself."""
        if self.reduction is None:
            return v
        out = v.duplicate()
        self.reduction.restrict(v, out)
        return out

    def residual_norm(self) -> float:
        """Assemble R at the current state (zero rows at fixed dofs; with a low-rank term
        its U c; with a reduction T^T R); its 2-norm."""
        with self.b.localForm() as loc:
            loc.set(0.0)
        dolfinx.fem.petsc.assemble_vector(self.b, self.R)
        dolfinx.fem.petsc.apply_lifting(self.b, [self.K], bcs=[self.bcs], x0=[self.x], scale=-1.0)
        self.b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        dolfinx.fem.petsc.set_bc(self.b, self.bcs, self.x, -1.0)
        if self.low_rank is not None:
            c, self._C = self.low_rank.coefficients(self.x)
            for ck, u in zip(c, self.low_rank.vectors):
                self.b.axpy(float(ck), u)
        if self.reduction is not None:
            self.reduction.restrict(self.b, self.b_r)
            return float(self.b_r.norm())
        return float(self.b.norm())

    def _assemble_tangent(self):
        """K at the current state (identity rows at the fixed dofs), reduced to T^T K T
        with a reduction: the operator of the linear solves."""
        self.A.zeroEntries()
        dolfinx.fem.petsc.assemble_matrix(self.A, self.K, bcs=self.bcs)
        self.A.assemble()
        op = self.A if self.reduction is None else self.reduction.matrix(self.A)
        self.ksp.setOperators(op)
        if self.linear_solver == "iterative":
            if self._rhs_max == 0.0:
                self._rhs_max = float(self.b.norm())
            self._configure()

    def _solve_one(self, rhs, out) -> int:
        """out = K^-1 rhs by the current operator; its Krylov iterations (0 for LU)."""
        if self.linear_solver == "iterative":
            out.set(0.0)
        self.ksp.solve(rhs, out)
        reason = self.ksp.getConvergedReason()
        if reason < 0:
            # a failed factorisation (or Krylov solve) sticks to the PC (every later solve
            # fails at once, however small the next load increment): start from a fresh one
            self.ksp.destroy()
            self.ksp = self._new_ksp()
            raise ArithmeticError(f"linear solve failed (PETSc reason {reason})")
        return self.ksp.getIterationNumber() if self.linear_solver == "iterative" else 0

    def _solve(self, rhs, out) -> None:
        """out = (K + U C U^T)^-1 rhs: Sherman-Morrison-Woodbury on the factorisation of K
        (k + 1 solves), or K^-1 rhs without a low-rank term."""
        its = self._solve_one(rhs, out)
        if self.low_rank is not None:
            C = np.asarray(self._C, float)
            for u, z in zip(self._U, self._Z):
                its += self._solve_one(u, z)
            k = len(self._U)
            UtZ = np.array([[u.dot(z) for z in self._Z] for u in self._U])
            Uty = np.array([u.dot(out) for u in self._U])
            coef = C @ np.linalg.solve(np.eye(k) + UtZ @ C, Uty)
            for cj, z in zip(coef, self._Z):
                out.axpy(-float(cj), z)
        if self.linear_solver == "iterative":
            self.krylov_iterations.append(its)

    def newton_update(self) -> float:
        """Solve K dw = R (R from the last :meth:`residual_norm`), w -= dw; ||dw||."""
        self._assemble_tangent()
        if self.reduction is None:
            self._solve(self.b, self.dx)
        else:
            self._solve(self.b_r, self.dx_r)
            self.reduction.expand(self.dx_r, self.dx)
        self.x.axpy(-1.0, self.dx)
        self.x.ghostUpdate(addv=PETSc.InsertMode.INSERT, mode=PETSc.ScatterMode.FORWARD)
        return float(self.dx.norm())

    def tangent_solve(self, rhs: np.ndarray) -> np.ndarray:
        """K_total^-1 rhs at the current state (an array of W, reduced by T^T with a
        reduction, the answer expanded by T): the Newton increment's linear map, for
        checking the tangent against differences of the residual. Needs a
        :meth:`residual_norm` at the current state first (the low-rank coefficients)."""
        b = self.b.duplicate()
        b.array[:] = rhs
        self._assemble_tangent()
        out = self.b.duplicate()
        if self.reduction is None:
            self._solve(b, out)
            return out.array.copy()
        br, xr = b.duplicate(), b.duplicate()
        self.reduction.restrict(b, br)
        self._solve(br, xr)
        self.reduction.expand(xr, out)
        return out.array.copy()

    def residual(self) -> np.ndarray:
        """The last assembled residual (an array of W; with a reduction T^T R)."""
        return (self.b if self.reduction is None else self.b_r).array.copy()

    def state_norm(self) -> float:
        return float(self.x.norm())

    def unstable_directions(self) -> int | None:
        """How many directions the tangent at the current state is not positive definite in:
        the negative pivots of its LDL^T (MUMPS, INFOG(12)), less the pressure unknowns'
        own (a saddle-point tangent has one negative eigenvalue per free pressure unknown
        where the constrained stiffness is positive definite). 0: a stable equilibrium.
        None for a system with a low-rank term or a reduction (the end moment's couple, the
        hinge): K's pivots are not those of the system's tangent there."""
        if self.low_rank is not None or self.reduction is not None:
            return None
        self.residual_norm()
        self.A.zeroEntries()
        dolfinx.fem.petsc.assemble_matrix(self.A, self.K, bcs=self.bcs)
        self.A.assemble()
        self.A.setOption(PETSc.Mat.Option.SYMMETRIC, True)
        ksp = PETSc.KSP().create(self.disc.comm)
        ksp.setType("preonly")
        pc = ksp.getPC()
        pc.setType("cholesky")
        pc.setFactorSolverType("mumps")
        ksp.setOperators(self.A)
        pc.setUp()
        neg = int(pc.getFactorMatrix().getMumpsInfog(12))
        ksp.destroy()
        if self.disc.pressure:
            _, pdofs = self.disc.W.sub(1).collapse()
            pdofs = np.asarray(pdofs)
            n_owned = self.disc.W.dofmap.index_map.size_local * self.disc.W.dofmap.index_map_bs
            fixed = np.concatenate([bc.dof_indices()[0][:bc.dof_indices()[1]] for bc in self.bcs] or [[]])
            free_p = np.setdiff1d(pdofs[pdofs < n_owned], fixed)
            neg -= int(self.disc.comm.allreduce(len(free_p)))
        return neg

    def last_increment(self) -> np.ndarray:
        """The last Newton increment dw (array of W)."""
        return self.dx.getArray(readonly=True)

    def save(self) -> np.ndarray:
        saved = self.w.x.array.copy()
        self._branches.save(saved)
        return saved

    def restore(self, saved: np.ndarray) -> None:
        self.w.x.array[:] = saved
        self._branches.restore(saved)

    def reset(self) -> None:
        self.w.x.array[:] = 0.0
        self._branches.reset()
