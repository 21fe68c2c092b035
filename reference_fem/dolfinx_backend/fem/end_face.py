"""The end face's terms that are not forms: its first moment, linear in the unknowns (the
end moment's rotation, :mod:`reference_fem.couple`), and the hinge's exact elimination
of the face's displacements but two (``supports.left = "hinge"``)."""
from __future__ import annotations

import numpy as np
import ufl
from petsc4py import PETSc

import dolfinx
import dolfinx.fem
import dolfinx.fem.petsc
import dolfinx.mesh

from .discretisation import COMM, Discretisation, Locator
from .forms import Functional


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

