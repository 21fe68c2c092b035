"""The manufactured problems (:mod:`reference_fem.manufactured`) on FElupe, as the backend solves a
beam: the same elements (quad9 / hexahedron27 Q2 displacement, Q1 pressure on the corner
nodes), the same fields (FieldPlaneStrain in plane strain), the same material
(:class:`.problem.MixedMaterial` of :func:`.laws.strain_energy`) and the same Newton system
(:class:`.problem.System`), on the unit square / cube of n cells per side.

The body force enters as consistent nodal forces int N b dV, the constraint source as
int N_p mu g dV (both with the problem's quadrature, the sources' values at its points);
u = u* at every boundary node; in the exactly incompressible models the pressure's
constant (free: Dirichlet data on the whole boundary) is fixed by phat = phat* at the
corner node 0. Newton starts from the interpolant of the exact fields. The L2 errors are
integrated with 5 Gauss points per direction (exact for the Q2 error's polynomial part,
degree 4 per direction, and not the 3 points of the solve).
"""
from __future__ import annotations

import math
import time

import numpy as np

from ..manufactured import Manufactured, boundary, newton_solve
from ..settings import default_quadrature_degree
from .laws import strain_energy
from .problem import MixedMaterial, Setup, System

DEGREE = 2
ERROR_POINTS = 5    # Gauss points per direction of the error integrals


def _meshes(dim: int, n: int):
    import felupe as fe

    if dim == 2:
        lin = fe.Rectangle(n=n + 1)
        quad = fe.mesh.convert(lin, order=2, calc_midfaces=True)
    else:
        lin = fe.Cube(n=n + 1)
        quad = fe.mesh.convert(lin, order=2, calc_midfaces=True, calc_midvolumes=True)
    corner = fe.Mesh(quad.points[:lin.npoints], quad.cells[:, :lin.cells.shape[1]], lin.cell_type)
    return quad, corner


def _regions(dim: int, quad, corner, points: int):
    import felupe as fe

    q = fe.GaussLegendre(order=points - 1, dim=dim)
    if dim == 2:
        return fe.RegionBiQuadraticQuad(quad, quadrature=q), fe.RegionQuad(corner, quadrature=q)
    return fe.RegionTriQuadraticHexahedron(quad, quadrature=q), fe.RegionHexahedron(corner, quadrature=q)


def _points(region, mesh) -> np.ndarray:
    """The physical quadrature points (dim, point, cell)."""
    h = region.h.reshape(region.h.shape[0], region.h.shape[1], -1)[:, :, 0]   # (node, point)
    return np.einsum("aq,cai->iqc", h, mesh.points[mesh.cells])


def _load(region, mesh, values: np.ndarray) -> np.ndarray:
    """int N f dV per node (node, component) of values (component, point, cell)."""
    h = region.h.reshape(region.h.shape[0], region.h.shape[1], -1)[:, :, 0]
    out = np.zeros((mesh.npoints, values.shape[0]))
    for i in range(values.shape[0]):
        np.add.at(out[:, i], mesh.cells, np.einsum("aq,qc->ca", h, values[i] * region.dV))
    return out


def solve(ms: Manufactured, n: int, tol: float = 1e-10, max_iterations: int = 25) -> dict:
    """The manufactured problem on n^dim Q2 (Q2/Q1) cells: {"status", "reason", "cells",
    "ndof", "newton_iterations", "error_u" (m), "error_p" (Pa, or None), "norm_u", "norm_p",
    "wall_s"}; Newton to ||R|| <= tol ||f_ext|| on the free dofs."""
    import felupe as fe

    t0 = time.perf_counter()
    dim, model = ms.dim, ms.model
    quad, corner = _meshes(dim, n)
    region, region_p = _regions(dim, quad, corner, default_quadrature_degree(DEGREE) // 2 + 1)
    if dim == 2:
        u = (fe.Field if model.name == "plane-stress" else fe.FieldPlaneStrain)(region, dim=2)
    else:
        u = fe.Field(region, dim=3)
    fields = fe.FieldContainer([u] + ([fe.Field(region_p, dim=1)] if model.has_pressure else []))
    energy_model = "3d" if dim == 3 else ("plane-stress" if model.name == "plane-stress" else "plane-strain")
    from mechanics.laws import get_law

    material = MixedMaterial(strain_energy(get_law(ms.law), energy_model, ms.constants), ms.mu, ms.alpha,
                             model.has_pressure)
    nu = u.values.size
    npres = corner.npoints if model.has_pressure else 0
    Xq = _points(region, quad)
    f_ext = np.concatenate([_load(region, quad, ms.b(Xq)).ravel(),
                            _load(region_p, corner, ms.mu * ms.g(_points(region_p, corner))).ravel()
                            if model.has_pressure else np.zeros(0)])
    fixed = np.zeros(nu + npres, bool)
    fixed[:nu].reshape(-1, dim)[boundary(quad.points)] = True
    if model.has_pressure and not model.penalty:
        fixed[nu] = True           # the pressure's constant: phat = phat* at corner node 0
    setup = Setup(None, quad, fields, material, fixed, f_ext, ["elastic", "body_force"], ms.mu)
    system = System(setup)
    system.set_load(1.0)
    system.w[:nu] = ms.u(quad.points.T).T.ravel()     # the interpolant: exact boundary values
    if model.has_pressure:
        system.w[nu:] = ms.phat(corner.points.T)[0]
    scale = float(np.linalg.norm(f_ext[~fixed])) or 1.0
    status, reason, it = newton_solve(system, scale, tol, max_iterations)
    system._push()
    out = {"status": status, "reason": reason, "cells": n, "ndof": int(fixed.size),
           "n_free": int((~fixed).sum()), "newton_iterations": it, "error_u": None, "error_p": None,
           "norm_u": None, "norm_p": None}
    if status == "converged":
        out.update(_errors(ms, quad, corner, u.values, fields[1].values if model.has_pressure else None))
    out["wall_s"] = time.perf_counter() - t0
    return out


def _errors(ms: Manufactured, quad, corner, u_values, p_values) -> dict:
    """L2 norms of u_h - u* (m) and of p_h - p* = mu (phat_h - phat*) (Pa; exactly
    incompressible: less its mean, the constant the Dirichlet problem leaves free), and of
    u*, p*."""
    import felupe as fe

    region, region_p = _regions(ms.dim, quad, corner, ERROR_POINTS)
    Xq = _points(region, quad)
    uh = fe.Field(region, dim=ms.dim, values=u_values).interpolate()
    ue = ms.u(Xq)
    out = {"error_u": math.sqrt(float(np.sum(np.sum((uh - ue) ** 2, axis=0) * region.dV))),
           "norm_u": math.sqrt(float(np.sum(np.sum(ue ** 2, axis=0) * region.dV)))}
    if p_values is not None:
        ph = fe.Field(region_p, dim=1, values=p_values).interpolate()[0]
        pe = ms.phat(_points(region_p, corner))[0]
        e = ph - pe
        if not ms.model.penalty:       # the pressure's constant is not the solve's: L2 modulo constants
            e = e - np.sum(e * region_p.dV) / np.sum(region_p.dV)
        out["error_p"] = ms.mu * math.sqrt(float(np.sum(e ** 2 * region_p.dV)))
        out["norm_p"] = ms.mu * math.sqrt(float(np.sum(pe ** 2 * region_p.dV)))
    return out
