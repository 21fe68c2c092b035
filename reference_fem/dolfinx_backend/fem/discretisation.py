"""The meshes of the beam and the discretisation on them (DOLFINx 0.5.2).

- :func:`rectangle_mesh`: a structured gmsh mesh of [0, L] x [-h/2, h/2], on
  ``COMM_SELF``; :func:`box_mesh`: the 3D beam, built on rank 0 and distributed over
  :func:`solver_comm`; :func:`beam_mesh`: the one of a scene;
- :class:`Discretisation`: displacement (and optionally scaled pressure) space on a
  mesh, the unknown, test functions, measures, constants, Dirichlet conditions, point
  evaluation and output; :func:`fixed_dof_count`: how many dofs conditions fix.
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
import dolfinx.geometry
import dolfinx.io
import dolfinx.io.gmshio
import dolfinx.mesh

from ..meshing import structured_box, structured_rectangle

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
