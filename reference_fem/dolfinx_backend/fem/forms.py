"""Compiled forms as numbers: a scalar form's value, an assembled vector form's norm, and
UFL expressions of a constant gradient evaluated pointwise (the UFL laws against :mod:`ancf`)."""
from __future__ import annotations

from typing import Callable

import numpy as np
import ufl
from petsc4py import PETSc

import dolfinx
import dolfinx.fem
import dolfinx.fem.petsc
import dolfinx.mesh

from .discretisation import COMM


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
