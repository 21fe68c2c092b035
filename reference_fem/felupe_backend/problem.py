"""The static continuum problem on FElupe: mesh, fields, energy, supports, loads and the
Newton system that :func:`reference_fem.statics.solve_static` drives.

The total potential is the DOLFINx backend's (:mod:`reference_fem.dolfinx_backend.problem`):

    Pi(u, phat) = int W(F, phat) dV - t * ( int rho g . u dV + int tbar . u dA )

with W = psi(invariants of the model) (+ mu phat (J - 1) for a pressure field, and
- (mu phat)^2 / (2 alpha) for the penalty): the pressure p = mu phat is scaled by the
law's shear modulus as there. Meshes are structured grids of degree-2 Lagrange cells
(FElupe's quad9 and hexahedron27, from its Rectangle and Cube converted to order 2), the
pressure field (Taylor-Hood Q2/Q1) lives on the cells' corner nodes. Quadrature: Gauss-
Legendre with ``quadrature_degree // 2 + 1`` points per direction (exact to degree
``quadrature_degree`` and one more, as DOLFINx's choice for the same degree on quads and
hexahedra). The 3D mesh is graded along x as gmsh's "Progression" (cell lengths growing
by ``progression`` from the clamp).

Dead loads as consistent nodal forces: gravity int N rho g dV (FElupe's shape functions
and quadrature), the tip traction int N tbar dA on the end face (composite Simpson
weights, exact for the face's quadratic shape functions). Supports as in the DOLFINx
backend: clamp = every node of the face x = 0; pin = the nodes at (0, 0) (3D: the line
(0, 0, z)); ``side_faces = "plane-strain"`` fixes u_z on z = +-w/2; ``hinge`` (2D): the
face's nodal displacements u = Y a eliminated exactly for the free vector a
(:class:`Reduction`: u = T w_r, the tangent T^T K T and the residual T^T R by
scipy.sparse; any number of cells across).

The end moment (``loads.end_moment``, static): the couple -t M theta(d) of
:mod:`reference_fem.couple`, with the end face's first moment d = d0 + G^T w from the same
Simpson weights (:class:`FirstMoment`: exact, the face's shape functions times Y are
cubic); its rank-2 tangent G C G^T is added to the sparse tangent as the dense block of
the end face's unknowns (exact; the face has 2 (2 n_y + 1) displacement unknowns in 2D).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from contract.errors import SceneError
from contract.loads import end_traction, face_moment_weight
from contract.scene import Scene
from mechanics.laws import get_law

from ..couple import Branches, EndMoment
from ..geometry import check_support
from ..settings import FemSettings
from .laws import strain_energy

CELLS = {"plane-strain": "quadrilateral", "plane-stress": "quadrilateral", "3d": "hexahedron"}
DEGREES = (2,)


def check_settings(settings: FemSettings) -> None:
    """What FElupe's backend offers (a SceneError naming the field otherwise)."""
    want = CELLS[settings.model]
    if settings.cell != want:
        raise SceneError(f"fem.cell: {settings.cell!r} with fem.backend = \"felupe\"; allowed for "
                         f"{settings.model}: {want!r}")
    if settings.degree not in DEGREES:
        raise SceneError(f"fem.degree: {settings.degree} with fem.backend = \"felupe\"; allowed: 2")
    if settings.linear_solver != "direct":
        raise SceneError("fem.linear_solver: \"iterative\" with fem.backend = \"felupe\"; allowed: 'direct'")


def _graded(n: int, length: float, q: float) -> np.ndarray:
    """n + 1 points on [0, length], cell lengths growing by q (gmsh's "Progression")."""
    if q == 1.0:
        return np.linspace(0.0, length, n + 1)
    return length * (q ** np.arange(n + 1) - 1.0) / (q ** n - 1.0)


def beam_meshes(scene: Scene, settings: FemSettings):
    """(displacement mesh of degree 2, corner mesh for the pressure; the same points first)."""
    import felupe as fe

    b = scene.beam
    if settings.model == "3d":
        nx, ny, nz = settings.cells(3)
        lin = fe.Cube(a=(0.0, -b.height / 2, -b.width / 2), b=(b.length, b.height / 2, b.width / 2),
                      n=(nx + 1, ny + 1, nz + 1))
        x = lin.points[:, 0] / b.length * nx   # the grid index along x
        lin.points[:, 0] = _graded(nx, b.length, settings.progression)[np.rint(x).astype(int)]
        quad = fe.mesh.convert(lin, order=2, calc_midfaces=True, calc_midvolumes=True)
    else:
        nx, ny = settings.cells(2)
        lin = fe.Rectangle(a=(0.0, -b.height / 2), b=(b.length, b.height / 2), n=(nx + 1, ny + 1))
        quad = fe.mesh.convert(lin, order=2, calc_midfaces=True)
    corner = fe.Mesh(quad.points[:lin.npoints], quad.cells[:, :lin.cells.shape[1]], lin.cell_type)
    return quad, corner


class MixedMaterial:
    """W(F, phat) = psi(F) + mu phat (J - 1) [- (mu phat)^2 / (2 alpha)]: FElupe's material
    interface (``gradient``/``hessian`` of the extracted fields [F, phat]); the
    F-derivatives by the chain rule through the invariants (:class:`.laws.InvariantEnergy`,
    the law's part by tensortrax; equal to tensortrax's derivatives of W(F) to round-off),
    the phat-derivatives in closed form. Without a pressure field (plane stress): W = psi(F)."""

    def __init__(self, psi, mu: float, alpha: float | None, has_pressure: bool):
        self.psi, self.mu, self.alpha, self.has_pressure = psi, mu, alpha, has_pressure

    def evaluate(self, x, hessian: bool):
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            F = np.ascontiguousarray(x[0])
            if not self.has_pressure:
                return [self.psi.hessian(F) if hessian else self.psi.gradient(F)]
            phat = np.ascontiguousarray(x[1][0])
            if hessian:
                J = np.linalg.det(np.moveaxis(F, (0, 1), (-2, -1)))
                dJ = J * np.moveaxis(np.linalg.inv(np.moveaxis(F, (0, 1), (-2, -1))), (-1, -2), (0, 1))
                App = np.zeros_like(phat) if self.alpha is None else -self.mu ** 2 / self.alpha * np.ones_like(phat)
                return [self.psi.hessian(F, self.mu * phat), self.mu * dJ, App]
            J = np.linalg.det(np.moveaxis(F, (0, 1), (-2, -1)))
            dp = self.mu * (J - 1.0)
            if self.alpha is not None:
                dp = dp - self.mu ** 2 * phat / self.alpha
            return [self.psi.gradient(F, self.mu * phat), dp]


def _simpson(coords: np.ndarray) -> np.ndarray:
    """Weights of int f ds over sorted node coordinates of a row of quadratic elements
    (2 n + 1 nodes: ends and midpoints)."""
    w = np.zeros(len(coords))
    for k in range(0, len(coords) - 2, 2):
        d = coords[k + 2] - coords[k]
        w[k:k + 3] += np.array([1.0, 4.0, 1.0]) * d / 6.0
    return w


@dataclass
class Setup:
    settings: FemSettings
    mesh: object
    fields: object            # FElupe FieldContainer [u] or [u, phat]
    material: MixedMaterial
    fixed: np.ndarray         # bool mask of the global dofs the supports fix
    f_ext: np.ndarray         # consistent nodal forces at full load (N per unit width in 2D)
    effects: list
    mu: float
    loads: dict = None        # {"gravity" | "tip_force": its nodal forces}, f_ext their sum
    width: float = 1.0        # factor from the problem's energies to the full beam's
    reduction: "Reduction" = None        # the unknowns of the solve (None: the free dofs)
    moment: float | None = None          # the end moment M_p (N m; per unit width in 2D)
    first_moment: "FirstMoment" = None   # the end face's first moment d(w)

    def __post_init__(self):
        if self.reduction is None:
            self.reduction = Reduction(self.fixed)

    @property
    def ndof(self) -> int:
        return sum(f.values.size for f in self.fields.fields)

    @property
    def n_free(self) -> int:
        return int(self.ndof - self.fixed.sum() - self.reduction.n_eliminated)

    def point_displacement(self, point) -> np.ndarray:
        """The displacement of the mesh node at ``point`` (reference coordinates)."""
        pts = self.mesh.points
        d = np.linalg.norm(pts - np.asarray(point), axis=1)
        k = int(np.argmin(d))
        if d[k] > 1e-9 * np.ptp(pts[:, 0]):
            raise SceneError(f"fem: no mesh node at {tuple(point)} (tip); use an even fem.cells_height")
        return self.fields[0].values[k].copy()


def _face_weights(pts: np.ndarray, face: np.ndarray, gdim: int) -> np.ndarray:
    """int N_a dA over a face x = const of the structured Q2 mesh, per face node (the
    composite Simpson weights of each direction across, multiplied)."""
    w = np.ones(len(face))
    for axis in range(1, gdim):
        c = np.unique(pts[face, axis])
        w *= _simpson(c)[np.searchsorted(c, pts[face, axis])]
    return w


class FirstMoment:
    """The end face's first moment d = weight int_face (X + u) Y dA = d0 + G^T w: with the
    face's Simpson weights w_a (exact: N_a Y is cubic along each cell edge),
    g_i[(a, i)] = weight w_a Y_a and d0 = weight sum_a w_a X_a Y_a. ``G`` (n, 2) sparse."""

    def __init__(self, pts: np.ndarray, face: np.ndarray, gdim: int, n: int, weight: float):
        from scipy.sparse import csr_matrix

        wa = weight * _face_weights(pts, face, gdim) * pts[face, 1]
        rows = np.concatenate([face * gdim + i for i in range(2)])
        cols = np.repeat([0, 1], len(face))
        self.G = csr_matrix((np.concatenate([wa, wa]), (rows, cols)), shape=(n, 2))
        self.vectors = [self.G[:, i].toarray().ravel() for i in range(2)]
        self.d0 = np.array([wa @ pts[face, i] for i in range(2)])

    def __call__(self, w: np.ndarray) -> np.ndarray:
        return self.d0 + self.G.T @ w


class Reduction:
    """The unknowns of a Newton solve: w = T w_r. Without a hinge T selects the free dofs
    (the ``fixed`` ones removed: K[free][:, free], R[free], as before); with the hinge
    (``hinge`` = the left face's nodes and their Y), each face node's displacement is
    Y a for the two unknowns a = (a_x, a_y), so T maps (free dofs off the face, a) to w:
    the tangent T^T K T, the residual T^T R, the increment T dw_r (scipy.sparse), exact.
    The pressure dofs are identity columns."""

    def __init__(self, fixed: np.ndarray, hinge: tuple[np.ndarray, np.ndarray, int] | None = None):
        from scipy.sparse import csr_matrix

        self.fixed, self.free = fixed, ~fixed
        self.T = None
        self.n_eliminated = 0
        if hinge is None:
            return
        nodes, Y, gdim = hinge
        face = np.zeros(fixed.size, bool)
        face_dofs = [nodes * gdim + c for c in range(gdim)]
        face[np.concatenate(face_dofs)] = True
        keep = np.flatnonzero(self.free & ~face)
        rows = np.concatenate([keep] + face_dofs)
        cols = np.concatenate([np.arange(len(keep))] + [np.full(len(nodes), len(keep) + c) for c in range(gdim)])
        vals = np.concatenate([np.ones(len(keep))] + [Y] * gdim)
        self.T = csr_matrix((vals, (rows, cols)), shape=(fixed.size, len(keep) + gdim))
        self.n_eliminated = int(face.sum()) - gdim

    def matrix(self, K):
        return K[self.free][:, self.free] if self.T is None else (self.T.T @ K @ self.T).tocsr()

    def vector(self, r: np.ndarray) -> np.ndarray:
        return r[self.free] if self.T is None else self.T.T @ r

    def expand(self, x: np.ndarray) -> np.ndarray:
        if self.T is not None:
            return self.T @ x
        out = np.zeros(self.fixed.size)
        out[self.free] = x
        return out


def set_up(scene: Scene, settings: FemSettings) -> Setup:
    import felupe as fe

    check_settings(settings)
    g, b, m, loads = settings.geometry, scene.beam, scene.material, scene.loads
    quad, corner = beam_meshes(scene, settings)
    gdim = g.gdim
    q = fe.GaussLegendre(order=settings.quadrature_degree // 2, dim=gdim)
    if gdim == 3:
        region = fe.RegionTriQuadraticHexahedron(quad, quadrature=q)
        region_p = fe.RegionHexahedron(corner, quadrature=q)
        u = fe.Field(region, dim=3)
    else:
        region = fe.RegionBiQuadraticQuad(quad, quadrature=q)
        region_p = fe.RegionQuad(corner, quadrature=q)
        u = (fe.FieldPlaneStrain if settings.model == "plane-strain" else fe.Field)(region, dim=2)
    fields = [u] + ([fe.Field(region_p, dim=1)] if settings.has_pressure else [])
    container = fe.FieldContainer(fields)

    law = get_law(m.law)
    constants = dict(m.constants)
    mu = law.shear_modulus(constants)
    alpha = m.penalty if settings.incompressibility == "penalty" else None
    psi = strain_energy(law, settings.model, constants)
    material = MixedMaterial(psi, mu, alpha, settings.has_pressure)

    # supports
    pts = quad.points
    nu = u.values.size
    fixed = np.zeros(nu + (corner.npoints if settings.has_pressure else 0), bool)
    fixed_u = fixed[:nu].reshape(-1, gdim)
    left = scene.supports.left
    check_support(left, g, settings)
    hinge = None
    if left == "clamp":
        fixed_u[g.at_left(b)(pts.T)] = True
    elif left == "slide":
        fixed_u[g.at_left(b)(pts.T), 0] = True
        fixed_u[g.pin(b)(pts.T), 1] = True
    elif left == "hinge":
        nodes = np.flatnonzero(g.at_left(b)(pts.T))
        hinge = (nodes, pts[nodes, 1], gdim)
    else:
        fixed_u[g.pin(b)(pts.T)] = True
    if gdim == 3 and settings.side_faces == "plane-strain":
        fixed_u[g.sides(b)(pts.T), 2] = True

    # loads
    forces = {}
    if loads.gravity is not None:
        f = np.zeros((quad.npoints, gdim))
        body = m.density * g.vector(loads.gravity)
        h = region.h.reshape(region.h.shape[0], region.h.shape[1], -1)[:, :, 0]   # (node, point)
        per_node = np.einsum("aq,qc->ca", h, region.dV)                            # (cell, node)
        for i in range(gdim):
            np.add.at(f[:, i], quad.cells, per_node * body[i])
        forces["gravity"] = f
    if loads.tip_force is not None:
        f = np.zeros((quad.npoints, gdim))
        tbar = g.vector(end_traction(loads.tip_force, b.height, b.width))
        end = np.flatnonzero(g.at_right(b)(pts.T))
        f[end] += _face_weights(pts, end, gdim)[:, None] * tbar
        forces["tip_force"] = f
    forces = {k: np.concatenate([f.ravel(), np.zeros(fixed.size - nu)]) for k, f in forces.items()}
    f_ext = sum(forces.values(), np.zeros(fixed.size))
    effects = ["elastic"] + (["penalty"] if alpha is not None else []) + list(forces)
    moment = first_moment = None
    if loads.end_moment is not None:
        moment = loads.end_moment / g.width_factor(b)
        weight = face_moment_weight(b.height) / (b.width if gdim == 3 else 1.0)
        first_moment = FirstMoment(pts, np.flatnonzero(g.at_right(b)(pts.T)), gdim, fixed.size, weight)
        effects.append("end_moment")
    return Setup(settings, quad, container, material, fixed, f_ext, effects, mu, forces, g.width_factor(b),
                 Reduction(fixed, hinge), moment, first_moment)


def solve_sparse(K, b: np.ndarray, cache: dict) -> np.ndarray:
    """K^-1 b by SuperLU with partial pivoting, the unknowns in reverse Cuthill-McKee order
    (a band; computed once per sparsity pattern, kept in ``cache``). On the pendulum's
    140 x 4 Q2/Q1 tangent (5761 unknowns) 11 ms against 47 ms in SuperLU's default column
    order (COLAMD); its minimum-degree orders are faster only without pivoting, which the
    saddle point's zero pressure block forbids (with pivoting: 2.3 s)."""
    from scipy.sparse.csgraph import reverse_cuthill_mckee
    from scipy.sparse.linalg import spsolve

    K = K.tocsr()
    key = (K.shape, K.nnz)
    if cache.get("key") != key:
        cache.update(key=key, perm=reverse_cuthill_mckee(K, symmetric_mode=False))
    perm = cache["perm"]
    x = np.empty_like(b)
    with np.errstate(all="ignore"):
        x[perm] = spsolve(K[perm][:, perm].tocsc(), b[perm], permc_spec="NATURAL")
    return x


class NewtonSystem:
    """A Newton system for :func:`mechanics.newton.newton` (and the static load stepping):
    the unknowns w (all of them, the fixed ones kept as set), ``residual(w)`` and
    ``tangent(w)`` of a subclass; reduced to the solve's unknowns by ``reduction``
    (:class:`Reduction`: the fixed rows removed, or the hinge's T^T K T), the increment
    solved by :func:`solve_sparse`; the state saved, restored and reset for the steppers
    (with the end moment's branch, ``couple``)."""

    def __init__(self, n: int, fixed: np.ndarray, order: dict | None = None,
                 reduction: Reduction | None = None, couple: EndMoment | None = None):
        self.w = np.zeros(n)
        self.fixed, self.free = fixed, ~fixed
        self.reduction = reduction if reduction is not None else Reduction(fixed)
        self._branches = Branches(couple)
        self._R = None
        self._dw = np.zeros(n)
        self._order = {} if order is None else order     # the solve's ordering, kept across systems

    def residual(self, w: np.ndarray) -> np.ndarray:
        raise NotImplementedError

    def tangent(self, w: np.ndarray):
        raise NotImplementedError

    def residual_norm(self) -> float:
        r = self.residual(self.w)
        r[self.fixed] = 0.0
        self._R = r
        if self.reduction.T is not None:
            return float(np.linalg.norm(self.reduction.vector(r)))
        return float(np.linalg.norm(r))

    def newton_update(self) -> float:
        red = self.reduction
        dw = solve_sparse(red.matrix(self.tangent(self.w)), red.vector(self._R), self._order)
        if not np.all(np.isfinite(dw)):
            raise ArithmeticError("singular or failed linear solve (SuperLU)")
        self._dw[:] = red.expand(dw)
        self.w -= self._dw
        return float(np.linalg.norm(self._dw))

    def last_increment(self) -> np.ndarray:
        return self._dw

    def state_norm(self) -> float:
        return float(np.linalg.norm(self.w))

    def save(self) -> np.ndarray:
        saved = self.w.copy()
        self._branches.save(saved)
        return saved

    def restore(self, saved: np.ndarray) -> None:
        self.w[:] = saved
        self._branches.restore(saved)

    def reset(self) -> None:
        self.w[:] = 0.0
        self._branches.reset()


class System(NewtonSystem):
    """The Newton system of the static problem for :func:`reference_fem.statics.solve_static`:
    R(w) = f_int(w) - t f_ext (+ G c, the end moment) on the free dofs; K = dR/dw (FElupe's
    assembly of the material's gradient and hessian, + G C G^T: the end face's dense block)."""

    def __init__(self, setup: Setup):
        self.couple = None
        if setup.moment is not None:
            self.couple = EndMoment(setup.first_moment, setup.moment, lambda: self.t)
        super().__init__(setup.ndof, setup.fixed, reduction=setup.reduction, couple=self.couple)
        self.s = setup
        self.t = 0.0
        self._offsets = np.cumsum([0] + [f.values.size for f in setup.fields.fields])

    def set_load(self, t: float) -> None:
        self.t = float(t)

    def _push(self) -> None:
        for f, a, b in zip(self.s.fields.fields, self._offsets[:-1], self._offsets[1:]):
            f.values[:] = self.w[a:b].reshape(f.values.shape)

    def _forms(self, hessian: bool):
        import felupe as fe

        self._push()
        fields = self.s.fields
        x = fields.extract()
        fun = self.s.material.evaluate(x, hessian)
        dV = fields[0].region.dV
        if hessian:
            return fe.IntegralForm(fun=fun, v=fields, u=fields, dV=dV).assemble().tocsr()
        return np.asarray(fe.IntegralForm(fun=fun, v=fields, dV=dV).assemble().todense()).ravel()

    def residual(self, w: np.ndarray) -> np.ndarray:
        r = self._forms(False) - self.t * self.s.f_ext
        if self.couple is not None:
            c, _ = self.couple.coefficients(w)
            r += self.s.first_moment.G @ c
        return r

    def tangent(self, w: np.ndarray):
        from scipy.sparse import csr_matrix

        K = self._forms(True)
        if self.couple is not None:
            G = self.s.first_moment.G
            _, C = self.couple.coefficients(w)
            K = (K + G @ csr_matrix(C) @ G.T).tocsr()
        return K


class StaticModel:
    """What the one static driver (:func:`reference_fem.simulation.run_scene`) reads of a
    backend: the Newton system, the load parameter, the unknowns, the effects, the
    processes (FElupe runs on one), the displacement at a point, the output files."""

    ranks = 1
    end_moment_method = ("FElupe: G from the end face's Simpson weights; the rank-2 tangent added to the "
                         "sparse tangent as the end face's dense block")

    def __init__(self, setup: Setup):
        self.setup = setup
        self.system = System(setup)
        self.n_free = setup.n_free
        self.effects = setup.effects
        self.set_load = self.system.set_load

    def rotation(self) -> float | None:
        """theta (rad) of the end face, continued along the load path (with an end moment)."""
        c = self.system.couple
        return None if c is None else c.rotation(self.system.w)

    def displacement(self, point) -> np.ndarray:
        """u (m) at a mesh node of the reference configuration."""
        return self.setup.point_displacement(point)

    def write(self, path, fmt: str):
        """The corner mesh (reference geometry) with the displacement and the pressure
        p = mu phat at its points, as DOLFINx's output writes degree 1 ("vtk": .vtu,
        "xdmf": .xdmf), by meshio."""
        from pathlib import Path

        import meshio

        s = self.setup
        corner = s.fields[-1].region.mesh if s.settings.has_pressure else None
        quad = s.fields[0].region.mesh
        n = corner.npoints if corner is not None else quad.npoints
        cells = corner.cells if corner is not None else quad.cells
        cell_type = corner.cell_type if corner is not None else quad.cell_type
        data = {"displacement": s.fields[0].values[:n]}
        if corner is not None:
            data["pressure"] = s.mu * s.fields[1].values[:, 0]
        path = Path(path).with_suffix(".vtu" if fmt == "vtk" else ".xdmf")
        path.parent.mkdir(parents=True, exist_ok=True)
        meshio.write(path, meshio.Mesh(quad.points[:n], [(cell_type, cells)], point_data=data))
        return path


def static_model(scene: Scene, settings: FemSettings) -> StaticModel:
    """The backend's static model of the scene."""
    return StaticModel(set_up(scene, settings))
