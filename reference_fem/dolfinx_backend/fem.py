"""Every DOLFINx call of reference_fem, written against DOLFINx 0.5.2.

A newer DOLFINx changes this module only (gmsh import, element constructors, point
evaluation, assembly and PETSc glue). The 2D meshes are built on ``MPI.COMM_SELF``, so
cases can run side by side in separate processes or threads of a study. The 3D mesh
(:func:`box_mesh`) is distributed over ``MPI.COMM_WORLD`` when the process was started
by ``mpiexec -n N`` with N > 1 (else ``COMM_SELF``); everything else takes its
communicator from the mesh, and every number a decision reads (norms, counts, point
values) is global and the same on every rank.

Interface:

- :func:`rectangle_mesh`: a structured gmsh mesh of [0, L] x [-h/2, h/2];
  :func:`box_mesh`: the 3D beam, built on rank 0 and distributed;
- :class:`Discretisation`: displacement (and optionally scaled pressure) space on a
  mesh, the unknown, test functions, measures, constants, Dirichlet conditions,
  point evaluation and output;
- :class:`NonlinearSystem`: residual, Newton increment (LU), state save/restore;
- :class:`Functional`, :class:`VectorNorm`: a compiled scalar form's value, the norm
  of an assembled vector form (for energies and Newton scales in dynamics);
- :class:`PointwiseEvaluator`: a UFL expression of a constant F (and phat) evaluated
  as numbers, for checking the UFL laws against :mod:`ancf`.
"""
from __future__ import annotations

from pathlib import Path
from typing import Callable, Sequence

import numpy as np
import ufl
from mpi4py import MPI
from petsc4py import PETSc

import dolfinx
import dolfinx.fem
import dolfinx.fem.petsc
import dolfinx.geometry
import dolfinx.io
import dolfinx.io.gmshio
import dolfinx.mesh

from ..couple import Branches
from .meshing import structured_box, structured_rectangle
from .krylov import (AL_GAMMA, ITERATIVE_DEFAULTS, KRYLOV_ATOL_FACTOR, KRYLOV_MAX_IT, KRYLOV_RTOL, OPTIONS_PREFIX,
                     ALPreconditioner, rigid_body_modes, set_defaults)
from ..settings import LINEAR_SOLVERS

VERSION = dolfinx.__version__
COMM = MPI.COMM_SELF
Locator = Callable[[np.ndarray], np.ndarray]  # x (3, n) -> bool (n,)


def rectangle_mesh(length: float, height: float, nx: int, ny: int, cell: str):
    """Structured mesh of [0, L] x [-h/2, h/2]: nx x ny quadrilaterals, or each split
    into two triangles with alternating diagonals."""
    with structured_rectangle(length, height, nx, ny, cell) as model:
        mesh, _, _ = dolfinx.io.gmshio.model_to_mesh(model, COMM, 0, gdim=2)
    return mesh


def solver_comm():
    """COMM_WORLD under an MPI launch of several ranks, else COMM_SELF."""
    return MPI.COMM_WORLD if MPI.COMM_WORLD.size > 1 else COMM


def box_mesh(length: float, height: float, width: float, nx: int, ny: int, nz: int, cell: str,
             progression: float = 1.0):
    """Structured mesh of [0, L] x [-h/2, h/2] x [-w/2, w/2]: nx x ny x nz hexahedra (or
    6 tetrahedra each), meshed by gmsh on rank 0 and distributed over :func:`solver_comm`."""
    comm = solver_comm()
    with structured_box(length, height, width, nx, ny, nz, cell, progression, build=comm.rank == 0) as model:
        mesh, _, _ = dolfinx.io.gmshio.model_to_mesh(model, comm, 0, gdim=3)
    n = comm.allreduce(mesh.topology.index_map(3).size_local)
    expected = nx * ny * nz * (1 if cell == "hexahedron" else 6)
    if n != expected:
        raise RuntimeError(f"gmsh made {n} cells, expected {expected}")
    return mesh


def beam_mesh(geometry, beam, settings):
    """The mesh of the scene's beam in ``geometry`` (2D: :func:`rectangle_mesh`; 3D:
    :func:`box_mesh`) with the cell counts and type of the [fem] ``settings``."""
    if geometry.gdim == 3:
        return box_mesh(beam.length, beam.height, beam.width, *settings.cells(3), settings.cell,
                        settings.progression)
    return rectangle_mesh(beam.length, beam.height, settings.cells_length, settings.cells_height, settings.cell)


class Discretisation:
    """Lagrange displacement of ``degree`` (vector), plus a continuous scaled pressure
    of ``degree - 1`` when ``pressure`` (Taylor-Hood), on ``mesh``."""

    def __init__(self, mesh, degree: int, pressure: bool, quadrature_degree: int):
        self.mesh = mesh
        self.comm = mesh.comm
        cell = mesh.ufl_cell()
        Ve = ufl.VectorElement("Lagrange", cell, degree)
        self.pressure = pressure
        if pressure:
            Qe = ufl.FiniteElement("Lagrange", cell, degree - 1)
            self.W = dolfinx.fem.FunctionSpace(mesh, ufl.MixedElement([Ve, Qe]))
            self.Wu = self.W.sub(0)
        else:
            self.W = dolfinx.fem.FunctionSpace(mesh, Ve)
            self.Wu = self.W
        self.w = dolfinx.fem.Function(self.W)
        self.test = ufl.TestFunction(self.W)
        self.trial = ufl.TrialFunction(self.W)
        if pressure:
            self.u, self.phat = ufl.split(self.w)
            self.v, _ = ufl.split(self.test)
        else:
            self.u, self.phat, self.v = self.w, None, self.test
        self.metadata = {"quadrature_degree": quadrature_degree}
        self.dx = ufl.Measure("dx", domain=mesh, metadata=self.metadata)
        self._zeros: list = []  # keep the bc value functions alive

    # -- data ----------------------------------------------------------------------
    def function(self):
        """A new function of the (mixed) space, zero."""
        return dolfinx.fem.Function(self.W)

    def split(self, f):
        """(displacement, scaled pressure or None) of a function or argument of W."""
        if self.pressure:
            return ufl.split(f)
        return f, None

    def displacement_dofs(self) -> np.ndarray:
        """Indices of the displacement components in the arrays of W."""
        if not self.pressure:
            return np.arange(len(self.w.x.array))
        _, dofs = self.W.sub(0).collapse()
        return np.asarray(dofs, dtype=np.int64)

    @property
    def ndof(self) -> int:
        imap = self.W.dofmap.index_map
        return imap.size_global * self.W.dofmap.index_map_bs

    def constant(self, value):
        return dolfinx.fem.Constant(self.mesh, PETSc.ScalarType(value))

    def boundary_measure(self, where: Locator):
        """ds restricted to the boundary facets where ``where`` holds."""
        fdim = self.mesh.topology.dim - 1
        facets = dolfinx.mesh.locate_entities_boundary(self.mesh, fdim, where)
        order = np.argsort(facets)
        tags = dolfinx.mesh.meshtags(self.mesh, fdim, facets[order],
                                     np.ones(len(facets), dtype=np.int32))
        return ufl.Measure("ds", domain=self.mesh, subdomain_data=tags,
                           metadata=self.metadata)(1)

    # -- Dirichlet conditions (homogeneous) ----------------------------------------------
    def fix(self, where: Locator, components: Sequence[int] = (0, 1), on: str = "facets"):
        """Zero displacement components on boundary facets (``on="facets"``) or at the
        nodes (``on="points"``) where ``where`` holds; returns a list of conditions."""
        bcs = []
        for i in components:
            sub = self.Wu.sub(i)
            V, _ = sub.collapse()
            if on == "facets":
                fdim = self.mesh.topology.dim - 1
                facets = dolfinx.mesh.locate_entities_boundary(self.mesh, fdim, where)
                dofs = dolfinx.fem.locate_dofs_topological((sub, V), fdim, facets)
            elif on == "points":
                dofs = dolfinx.fem.locate_dofs_geometrical((sub, V), where)
            else:
                raise ValueError(f"on: {on!r}; allowed: 'facets', 'points'")
            if self.comm.allreduce(len(dofs[0])) == 0:
                raise ValueError(f"no degrees of freedom found for the condition on {on}")
            zero = dolfinx.fem.Function(V)
            self._zeros.append(zero)
            bcs.append(dolfinx.fem.dirichletbc(zero, dofs, sub))
        return bcs

    # -- results ---------------------------------------------------------------------
    def displacement(self):
        return self.w.sub(0).collapse() if self.pressure else self.w

    def point_displacement(self, points) -> np.ndarray:
        """u at points (n, gdim) in the reference configuration -> (n, gdim)."""
        points = np.asarray(points, float)
        gdim = self.mesh.geometry.dim
        pts = np.zeros((len(points), 3))
        pts[:, :points.shape[1]] = points
        if self.comm.size > 1:
            return self._point_displacement_parallel(pts)[:, :gdim]
        tree = dolfinx.geometry.BoundingBoxTree(self.mesh, self.mesh.topology.dim)
        candidates = dolfinx.geometry.compute_collisions(tree, pts)
        cells = dolfinx.geometry.compute_colliding_cells(self.mesh, candidates, pts)
        first = [cells.links(i)[0] for i in range(len(pts))]
        values = self.displacement().eval(pts, np.array(first, dtype=np.int32))
        return np.asarray(values).reshape(len(pts), -1)[:, :gdim]

    def _point_displacement_parallel(self, pts) -> np.ndarray:
        """Each rank evaluates the points in its owned cells (ghosts excluded), the values
        are gathered, and the lowest rank holding a point gives it: the same numbers on
        every rank."""
        u = self.displacement()
        owned = self.mesh.topology.index_map(self.mesh.topology.dim).size_local
        tree = dolfinx.geometry.BoundingBoxTree(self.mesh, self.mesh.topology.dim,
                                                np.arange(owned, dtype=np.int32))
        candidates = dolfinx.geometry.compute_collisions(tree, pts)
        cells = dolfinx.geometry.compute_colliding_cells(self.mesh, candidates, pts)
        dim = u.function_space.dofmap.index_map_bs
        mine = np.full((len(pts), dim), np.nan)
        for i in range(len(pts)):
            c = cells.links(i)
            if len(c):
                mine[i] = np.asarray(u.eval(pts[i:i + 1], np.array([c[0]], np.int32))).reshape(dim)
        out = np.full((len(pts), dim), np.nan)
        for values in self.comm.allgather(mine):
            take = np.isnan(out[:, 0]) & np.isfinite(values[:, 0])
            out[take] = values[take]
        if np.isnan(out).any():
            raise ValueError("a point is outside the mesh")
        return out

    def cell_minimum(self, expr, n: int = 10) -> tuple[float, np.ndarray]:
        """The minimum of a scalar UFL expression over an equispaced lattice of every owned
        cell (n intervals per edge, the cell's boundary included), and the point where it
        is (reference coordinates); global over the ranks. Not only at the quadrature
        points: a cell can be inverted (det F < 0) between them, which the discrete energy
        does not see (the clamp's compressed corner under the hard loads)."""
        import basix

        key = (id(expr), n)
        cache = self.__dict__.setdefault("_cell_minimum", {})
        if key not in cache:
            cell = basix.cell.string_to_type(self.mesh.topology.cell_type.name)
            pts = basix.create_lattice(cell, n, basix.LatticeType.equispaced, True)
            cache[key] = (expr, dolfinx.fem.Expression(expr, pts),
                          dolfinx.fem.Expression(ufl.SpatialCoordinate(self.mesh), pts), len(pts))
        _, e, ex, npts = cache[key]
        tdim = self.mesh.topology.dim
        cells = np.arange(self.mesh.topology.index_map(tdim).size_local, dtype=np.int32)
        v = np.asarray(e.eval(cells)).reshape(len(cells), npts) if len(cells) else np.full((1, 1), np.inf)
        i = np.unravel_index(np.argmin(v), v.shape)
        gdim = self.mesh.geometry.dim
        x = (np.asarray(ex.eval(cells[i[0]:i[0] + 1])).reshape(npts, gdim)[i[1]] if len(cells)
             else np.zeros(gdim))
        best = (float(v[i]), x)
        if self.comm.size > 1:
            best = min(self.comm.allgather(best), key=lambda b: b[0])
        return best

    def dof_point(self, values: np.ndarray) -> np.ndarray:
        """The reference point of the displacement node where |values| (an array of W, e.g.
        a Newton increment) is largest (this rank's share)."""
        dofs = self.displacement_dofs()
        gdim = self.mesh.geometry.dim
        V = self.W.sub(0).collapse()[0] if self.pressure else self.W
        x = V.tabulate_dof_coordinates()[:, :gdim]
        mag = np.linalg.norm(np.asarray(values)[dofs].reshape(-1, gdim), axis=1)
        return x[int(np.argmax(mag))]

    def positions(self, w: np.ndarray, points) -> np.ndarray:
        """Deformed positions (n, gdim) in m of reference points (n, gdim) at the state w
        (an array of W); the current state is kept."""
        points = np.asarray(points, float)
        saved = self.w.x.array.copy()
        self.w.x.array[:] = w
        d = self.point_displacement(points)
        self.w.x.array[:] = saved
        return points + d

    def write(self, path: Path, fmt: str, scale: float = 1.0, t: float = 0.0) -> Path:
        """Write the mesh (its reference geometry) with the displacement (and the pressure
        p = scale * phat) interpolated to degree 1 as point data: ParaView's "Warp By
        Vector" (displacement, scale 1) shows the deformed beam. ANCF's --vtk writes
        the same."""
        V1 = dolfinx.fem.VectorFunctionSpace(self.mesh, ("Lagrange", 1))
        u1 = dolfinx.fem.Function(V1, name="displacement")
        u1.interpolate(self.displacement())
        fields = [u1]
        if self.pressure:
            Q1 = dolfinx.fem.FunctionSpace(self.mesh, ("Lagrange", 1))
            p1 = dolfinx.fem.Function(Q1, name="pressure")
            p1.interpolate(self.w.sub(1).collapse())
            p1.x.array[:] *= scale
            fields.append(p1)
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        if fmt == "xdmf":
            with dolfinx.io.XDMFFile(self.comm, str(path.with_suffix(".xdmf")), "w") as f:
                f.write_mesh(self.mesh)
                for field in fields:
                    f.write_function(field, t)
            return path.with_suffix(".xdmf")
        if fmt == "vtk":
            with dolfinx.io.VTKFile(self.comm, str(path.with_suffix(".pvd")), "w") as f:
                f.write_function(fields, t)
            return path.with_suffix(".pvd")
        raise ValueError(f"format {fmt!r}; allowed: 'vtk', 'xdmf'")


def fixed_dof_count(bcs, comm=COMM) -> int:
    """How many degrees of freedom a list of Dirichlet conditions fixes (owned ones,
    summed over the ranks of ``comm``)."""
    return int(comm.allreduce(sum(bc.dof_indices()[1] for bc in bcs)))


class FaceFirstMoment:
    """The first moment of a face about its centre line, per unit ``1 / weight``:

        d = weight * int_face (X + u) Y dA = d0 + G^T w,   G = [g_x, g_y],
        g_i = weight * int_face v_i Y dA (assembled, zero at the Dirichlet dofs),

    d0 = weight * int_face X Y dA ((0, 1) for the symmetric face with weight = 1 / int Y^2 dA);
    d is linear in the unknowns w (the pressure components of G are zero). The vectors G
    are the columns of the end moment's rank-2 tangent (:mod:`contract.loads`)."""

    def __init__(self, disc: Discretisation, where: Locator, weight: float, bcs=()):
        ds = disc.boundary_measure(where)
        X = ufl.SpatialCoordinate(disc.mesh)
        v, _ = disc.split(disc.test)
        c = disc.constant(weight)
        self.vectors = []
        for i in range(2):
            g = dolfinx.fem.petsc.assemble_vector(dolfinx.fem.form(c * v[i] * X[1] * ds))
            g.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
            dolfinx.fem.petsc.set_bc(g, list(bcs), scale=0.0)
            self.vectors.append(g)
        self.d0 = np.array([Functional(c * X[i] * X[1] * ds)() for i in range(2)])

    def __call__(self, x) -> np.ndarray:
        """d (2,) at the state x (the PETSc vector of W)."""
        return self.d0 + np.array([g.dot(x) for g in self.vectors])


class FaceHinge:
    """The face kept straight through its fixed centre: u(0, Y) = Y a, eliminated exactly.

    Each displacement component c of the face's nodes is slaved to the face's top node
    (Y_m = h/2): u_c(Y_i) = (Y_i / Y_m) u_c(Y_m), so the top node's two components carry
    a = u(Y_m) / Y_m (for Lagrange elements the face's displacement, interpolating nodal
    values of a linear function, is then Y a along the whole face; the centre node, if
    any, is fixed). Written as the square matrix T of W's layout, u = T w_r with
    T = I but for the slave rows (T_sm = Y_s / Y_m, T_ss = 1: a dummy unknown w_s, held
    at zero by an identity row): the reduced tangent T^T K T (PETSc's MatPtAP, the
    product's pattern reused) with the slave rows and columns replaced by the identity,
    the reduced residual T^T R zero at the slaves, and the increment T dw_r. The pressure
    dofs of a mixed model are rows of the identity. Serial (the 2D meshes are)."""

    def __init__(self, disc: Discretisation, where: Locator):
        if disc.comm.size > 1:
            raise ValueError("the hinge's elimination is serial (2D meshes only)")
        n = len(disc.w.x.array)
        fdim = disc.mesh.topology.dim - 1
        facets = dolfinx.mesh.locate_entities_boundary(disc.mesh, fdim, where)
        rows = [[(i, 1.0)] for i in range(n)]
        slaves = []
        scale = max(1e-300, float(np.ptp(disc.mesh.geometry.x[:, 1])))
        for c in range(disc.mesh.geometry.dim):
            sub = disc.Wu.sub(c)
            V, _ = sub.collapse()
            dofs, vdofs = dolfinx.fem.locate_dofs_topological((sub, V), fdim, facets)
            y = V.tabulate_dof_coordinates()[vdofs, 1]
            m = int(np.argmax(y))
            if not y[m] > 0:
                raise ValueError("the hinge's face has no node above its centre")
            for i, yi in zip(dofs, y):
                if i == dofs[m]:
                    continue
                slaves.append(int(i))
                if abs(yi) > 1e-12 * scale:
                    rows[i].append((int(dofs[m]), yi / y[m]))
        indptr = np.cumsum([0] + [len(r) for r in rows])
        cols = np.array([j for r in rows for j, _ in r], dtype=PETSc.IntType)
        vals = np.array([v for r in rows for _, v in r])
        self.T = PETSc.Mat().createAIJ(size=(n, n), csr=(indptr.astype(PETSc.IntType), cols, vals), comm=COMM)
        self.T.assemble()
        self.slaves = np.array(sorted(slaves), dtype=PETSc.IntType)
        self.n_eliminated = len(self.slaves)     # the face's displacement dofs but the two of a
        self._Ar = None

    def matrix(self, A):
        """T^T A T with identity rows and columns at the slaves."""
        if self._Ar is None:
            self._Ar = A.PtAP(self.T)
            self._Ar.setOption(PETSc.Mat.Option.KEEP_NONZERO_PATTERN, True)
        else:
            A.PtAP(self.T, result=self._Ar)
        self._Ar.zeroRowsColumns(self.slaves, 1.0)
        return self._Ar

    def restrict(self, b, out) -> None:
        """out = T^T b, zero at the slaves."""
        self.T.multTranspose(b, out)
        out.setValues(self.slaves, np.zeros(len(self.slaves)))
        out.assemble()

    def expand(self, xr, out) -> None:
        """out = T xr."""
        self.T.mult(xr, out)


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


class Functional:
    """A compiled scalar form; calling it assembles its value (summed over the ranks)."""

    def __init__(self, expr):
        self.form = dolfinx.fem.form(expr)
        self.comm = self.form.mesh.comm

    def __call__(self) -> float:
        value = float(dolfinx.fem.assemble_scalar(self.form))
        return value if self.comm.size == 1 else float(self.comm.allreduce(value))


class VectorNorm:
    """The 2-norm of an assembled vector form, zero at the Dirichlet dofs."""

    def __init__(self, expr, bcs):
        self.form = dolfinx.fem.form(expr)
        self.bcs = list(bcs)
        self.b = dolfinx.fem.petsc.create_vector(self.form)

    def __call__(self) -> float:
        with self.b.localForm() as loc:
            loc.set(0.0)
        dolfinx.fem.petsc.assemble_vector(self.b, self.form)
        self.b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        dolfinx.fem.petsc.set_bc(self.b, self.bcs, scale=0.0)
        return float(self.b.norm())


class PointwiseEvaluator:
    """Numbers from UFL expressions of a constant 2 x 2 gradient F and scalar phat.

    ``build(F, phat)`` returns a list of UFL scalars; ``F`` is a ``ufl.variable`` so
    that ``ufl.diff(W, F)`` works. Compiled once; :meth:`__call__` evaluates at
    numeric F (2, 2) and phat.
    """

    def __init__(self, build: Callable):
        mesh = dolfinx.mesh.create_unit_square(COMM, 1, 1)
        self._F = dolfinx.fem.Constant(mesh, PETSc.ScalarType(np.eye(2)))
        self._p = dolfinx.fem.Constant(mesh, PETSc.ScalarType(0.0))
        self.mesh = mesh
        exprs = build(ufl.variable(self._F), self._p, mesh)
        self._expr = dolfinx.fem.Expression(ufl.as_vector(exprs), np.array([[1.0 / 3, 1.0 / 3]]))

    def __call__(self, F: np.ndarray, phat: float = 0.0) -> np.ndarray:
        self._F.value = np.asarray(F, float)
        self._p.value = float(phat)
        return np.asarray(self._expr.eval(np.array([0], dtype=np.int32))).reshape(-1)
