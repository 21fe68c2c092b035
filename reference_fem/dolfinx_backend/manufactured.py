"""The manufactured problems (:mod:`reference_fem.manufactured`) on DOLFINx, as the backend solves a
beam: the same spaces (:class:`.fem.Discretisation`: Taylor-Hood Q2/Q1, or Q2 alone in
plane stress), the same energies (:mod:`.models`, UFL laws of :mod:`.laws`), the same
Newton system (:class:`.fem.NonlinearSystem`, MUMPS), on DOLFINx's structured unit
square / cube of n quadrilaterals / hexahedra per side.

The sources are the shared module's numbers, not UFL: the body force b and the
constraint source mu g are quadrature functions holding their values at the solve's
quadrature points (a ``Quadrature`` element of the problem's degree), so the residual
is int P : grad v dV - int b . v dV [+ int (dW/dphat - mu g) q dV]. u = u* on the
boundary facets (inhomogeneous Dirichlet data: the interpolant of u*); in the exactly
incompressible models the pressure's constant by phat = phat* at the corner X = 0.
Newton starts from the interpolant of the exact fields. The L2 errors are integrated
with quadrature degree 8 (5 Gauss points per direction), the exact fields again as
quadrature functions.
"""
from __future__ import annotations

import math
import time

import numpy as np
import ufl

import basix
import dolfinx
import dolfinx.fem
import dolfinx.mesh

from mechanics.laws import get_law

from ..manufactured import Manufactured, newton_solve
from ..settings import default_quadrature_degree
from .fem import COMM, Discretisation, Functional, NonlinearSystem, VectorNorm
from .models import get_model

DEGREE = 2
ERROR_DEGREE = 8    # quadrature degree of the error integrals

# the backend's (model, incompressibility) of each manufactured model
BACKEND_MODEL = {"plane-strain": ("plane-strain", "mixed"), "plane-strain-penalty": ("plane-strain", "penalty"),
                 "plane-stress": ("plane-stress", "exact"), "3d": ("3d", "mixed")}


def unit_mesh(dim: int, n: int):
    """n x n (x n) quadrilaterals (hexahedra) on the unit square (cube)."""
    if dim == 2:
        return dolfinx.mesh.create_unit_square(COMM, n, n, dolfinx.mesh.CellType.quadrilateral)
    return dolfinx.mesh.create_unit_cube(COMM, n, n, n, dolfinx.mesh.CellType.hexahedron)


class QuadratureData:
    """Functions of X given by their values at the quadrature points of ``degree``."""

    def __init__(self, mesh, degree: int):
        self.mesh, self.degree = mesh, degree
        cell = basix.cell.string_to_type(mesh.topology.cell_name())
        points, _ = basix.make_quadrature(cell, degree)
        tdim = mesh.topology.dim
        self.ncells = mesh.topology.index_map(tdim).size_local + mesh.topology.index_map(tdim).num_ghosts
        self.npoints = len(points)
        gdim = mesh.geometry.dim
        x = dolfinx.fem.Expression(ufl.SpatialCoordinate(mesh), points)
        xq = x.eval(np.arange(self.ncells, dtype=np.int32)).reshape(self.ncells, self.npoints, gdim)
        self.X = np.moveaxis(xq, -1, 0)           # (gdim, cell, point)

    def function(self, values: np.ndarray):
        """A Quadrature function of values (components, cell, point) (1 component: scalar)."""
        ncomp = values.shape[0]
        cell = self.mesh.ufl_cell()
        if ncomp == 1:
            element = ufl.FiniteElement("Quadrature", cell, self.degree, quad_scheme="default")
        else:
            element = ufl.VectorElement("Quadrature", cell, self.degree, dim=ncomp, quad_scheme="default")
        V = dolfinx.fem.FunctionSpace(self.mesh, element)
        f = dolfinx.fem.Function(V)
        dofs = V.dofmap.list.array.reshape(self.ncells, self.npoints)
        f.x.array.reshape(-1, ncomp)[dofs] = np.moveaxis(values, 0, -1)
        return f


def _interpolate(disc: Discretisation, index: int, fn):
    """The interpolant of fn (X (3, n) -> (components, n)) into sub-space ``index`` of W
    (collapsed) and the map of its dofs into W."""
    V, dofs = disc.W.sub(index).collapse() if disc.pressure else (disc.W, np.arange(len(disc.w.x.array)))
    f = dolfinx.fem.Function(V)
    f.interpolate(fn)
    return f, np.asarray(dofs)


def solve(ms: Manufactured, n: int, tol: float = 1e-10, max_iterations: int = 25) -> dict:
    """The manufactured problem on n^dim Q2 (Q2/Q1) cells: {"status", "reason", "cells",
    "ndof", "newton_iterations", "error_u" (m), "error_p" (Pa, or None), "norm_u", "norm_p",
    "wall_s"}; Newton to ||R|| <= tol ||F_ext|| (the sources' vector, boundary rows zero)."""
    t0 = time.perf_counter()
    dim, mm = ms.dim, ms.model
    model = get_model(*BACKEND_MODEL[mm.name])
    mesh = unit_mesh(dim, n)
    qdeg = default_quadrature_degree(DEGREE)
    disc = Discretisation(mesh, DEGREE, model.has_pressure, qdeg)
    law = get_law(ms.law)
    c = {k: disc.constant(v) for k, v in ms.constants.items()}
    mu = disc.constant(ms.mu)
    alpha = disc.constant(ms.alpha) if ms.alpha else None

    q = QuadratureData(mesh, qdeg)
    b = q.function(ms.b(q.X))
    F = ufl.Identity(dim) + ufl.grad(disc.u)
    Pi = model.energy(law, c, F, disc.phat, mu, alpha) * disc.dx
    residual = ufl.derivative(Pi, disc.w, disc.test)
    v, qp = disc.split(disc.test)
    sources = ufl.inner(b, v) * disc.dx
    if model.has_pressure:
        sources = sources + mu * q.function(ms.g(q.X)) * qp * disc.dx
    residual = residual - sources

    u_exact = lambda x: ms.u(x[:dim])
    fdim = mesh.topology.dim - 1
    mesh.topology.create_connectivity(fdim, mesh.topology.dim)
    facets = dolfinx.mesh.exterior_facet_indices(mesh.topology)
    uD, u_map = _interpolate(disc, 0, u_exact)
    sub = disc.Wu
    bcs = [dolfinx.fem.dirichletbc(uD, dolfinx.fem.locate_dofs_topological((sub, uD.function_space), fdim, facets),
                                   sub)]
    disc.w.x.array[u_map] = uD.x.array
    if model.has_pressure:
        pD, p_map = _interpolate(disc, 1, lambda x: ms.phat(x[:dim]))
        disc.w.x.array[p_map] = pD.x.array
        if mm.penalty is False:
            corner = lambda x: np.all(np.isclose(x[:dim], 0.0), axis=0)
            dofs = dolfinx.fem.locate_dofs_geometrical((disc.W.sub(1), pD.function_space), corner)
            bcs.append(dolfinx.fem.dirichletbc(pD, dofs, disc.W.sub(1)))
    system = NonlinearSystem(disc, residual, bcs)
    scale = VectorNorm(sources, bcs)() or 1.0
    status, reason, it = newton_solve(system, scale, tol, max_iterations)
    out = {"status": status, "reason": reason, "cells": n, "ndof": int(disc.ndof),
           "n_free": int(disc.ndof - sum(bc.dof_indices()[1] for bc in bcs)), "newton_iterations": it,
           "error_u": None, "error_p": None, "norm_u": None, "norm_p": None}
    if status == "converged":
        out.update(_errors(ms, disc))
    out["wall_s"] = time.perf_counter() - t0
    return out


def _errors(ms: Manufactured, disc: Discretisation) -> dict:
    """L2 norms of u_h - u* (m) and of p_h - p* = mu (phat_h - phat*) (Pa; exactly
    incompressible: less its mean, the constant the Dirichlet problem leaves free), and of
    u*, p*."""
    q = QuadratureData(disc.mesh, ERROR_DEGREE)
    dx = ufl.Measure("dx", domain=disc.mesh, metadata={"quadrature_degree": ERROR_DEGREE})
    ue = q.function(ms.u(q.X))
    out = {"error_u": math.sqrt(Functional(ufl.inner(disc.u - ue, disc.u - ue) * dx)()),
           "norm_u": math.sqrt(Functional(ufl.inner(ue, ue) * dx)())}
    if disc.pressure:
        pe = q.function(ms.phat(q.X))
        e = disc.phat - pe
        if not ms.model.penalty:       # the pressure's constant is not the solve's: L2 modulo constants
            e = e - Functional(e * dx)() / Functional(disc.constant(1.0) * dx)()
        out["error_p"] = ms.mu * math.sqrt(Functional(e ** 2 * dx)())
        out["norm_p"] = ms.mu * math.sqrt(Functional(pe ** 2 * dx)())
    return out
