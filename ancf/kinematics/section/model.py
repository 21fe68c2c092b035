"""The beam model: strain energy, internal force and tangent, gravity, tip load, mass.

Vectorised over elements x quadrature points. With B (nq, 4, nd) the map from element
displacements to vec(F - I) at each quadrature point (B[q, 2 i + j, 2 a + i] = dN_a/dX_j),
and w the quadrature weights times the element volume l_e h w_b:

    U   = sum_e sum_q w_q W(F_eq)
    f_e = sum_q w_q B_q^T vec P_eq
    K_e = sum_q w_q B_q^T A_eq B_q

:class:`BeamModel` is the continuum-based model above, on what every element's model
shares (:class:`ancf.kinematics.model.ElementModel`: the compiled energy, force and tangent
through the element interface, gravity, the end load, the mass, the centre line);
:class:`ancf.kinematics.cable.model.CableModel` is the cable (the same B with its points' (r_x, Y r_xx) in
place of F).

Only what a scene calls for is built (:mod:`ancf.build` says which effects it built):
the mass matrix only for dynamics, gravity only when the scene has it, the penalty
only in the penalised formulations.

An element with a pressure field (``ElementSpec.pressure``) in a penalised formulation
takes the penalty on the element-wise projection of J - 1 (:mod:`ancf.kinematics.section.pressure`, the
numpy reference) instead of at the points: the points then see the material without its
penalty (:attr:`BeamModel.pointwise`), and the compiled loops read the projection as data
(:func:`ancf.kinematics.section.fields.pressure_arrays` in :attr:`BeamModel.fused`).

An element with an assumed strain (``ElementSpec.assumed``) takes components of C from
sample points along the beam (:mod:`ancf.kinematics.section.assumed`): the compiled kernels see the rule's
points followed by the sample points (weight zero) and the sampling T; the numpy
reference is :class:`ancf.kinematics.section.assumed.AssumedStrain` (:attr:`BeamModel.assumed`). Its energy
is not a function of (a, J) at each point, so it has no discrete gradient here.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from ...core.banded import Banded
from ...core.material import Material


from ..model import ElementModel, refuse_discrete_gradient  # noqa: F401  (the names beam.py always had)
from ...core.errors import InadmissibleState  # noqa: F401


@dataclass
class BeamModel(ElementModel):
    """A continuum-based element's model: F = I + grad u at the rule's points of the
    section, W(F) by the law in the scene's formulation."""
    @cached_property
    def pressure(self):
        """The projected penalty (:class:`ancf.kinematics.section.pressure.ProjectedPenalty`) of an element
        with a pressure field in a penalised formulation; None: the penalty, if any, is
        pointwise."""
        m = self.mesh
        if not (m.element.pressure and self.material.formulation.penalised):
            return None
        from .pressure import ProjectedPenalty
        q = m.element.pressure_tabulate(self.rule.xi, self.rule.eta, m.element_length, m.height)
        return ProjectedPenalty(q, self._w, self._B, self.material.penalty)

    @cached_property
    def pointwise(self) -> Material:
        """The material the quadrature points see: without its penalty where the pressure
        field carries it."""
        return self.material if self.pressure is None else replace(self.material, penalty=0.0)

    @cached_property
    def sampled(self):
        """(points, T) of an element with an assumed strain (:func:`ancf.kinematics.section.assumed.sampling`:
        the rule's points then the sample points, and C_bar's sampling); None without one."""
        spec = self.mesh.element
        if not spec.assumed:
            return None
        from .assumed import sampling
        return sampling(spec.assumed, spec.assumed_points, self.rule)

    @cached_property
    def assumed(self):
        """The numpy reference of the assumed strain (:class:`ancf.kinematics.section.assumed.AssumedStrain`),
        or None."""
        if self.sampled is None:
            return None
        from .assumed import AssumedStrain
        points, T = self.sampled
        m = self.mesh
        _, dN = m.element.tabulate(points.xi, points.eta, m.element_length, m.height)
        w = points.weight * m.element_length * m.height * m.width
        return AssumedStrain(self.pointwise, dN, w, T, self.pressure)

    # -- kinematics ------------------------------------------------------------------
    def gradients(self, u: np.ndarray) -> np.ndarray:
        """F at every element and quadrature point, (ne, nq, 2, 2)."""
        gradu = self.strain_variation(u)                    # (ne, nq * 4)
        return gradu.reshape(len(gradu), -1, 2, 2) + np.eye(2)

    def _admissible(self, u: np.ndarray) -> None:
        self._checked(self.gradients(u))

    def _checked(self, F: np.ndarray) -> np.ndarray:
        J = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
        if not np.all(np.isfinite(F)) or J.min() <= 0.0:
            raise InadmissibleState(f"det F = {J.min():.3g} <= 0 at a quadrature point")
        return F

    # -- elastic terms -----------------------------------------------------------------
    def strain_energy_numpy(self, u: np.ndarray) -> float:
        if self.assumed is not None:
            return self.assumed.energy(u[self._dofs])
        F = self._checked(self.gradients(u))
        f = F.reshape(F.shape[0], F.shape[1], 4)
        a = np.einsum("eqi,eqi->eq", f, f)
        J = f[..., 0] * f[..., 3] - f[..., 1] * f[..., 2]
        U = float(np.sum(self.energy_derivatives(a, J)[0] * self._w))
        return U if self.pressure is None else U + self.pressure.energy(F)

    def internal_force_numpy(self, u: np.ndarray) -> np.ndarray:
        if self.assumed is not None:
            fe = self.assumed.element_terms(u[self._dofs], tangent=False)[0]
            return np.bincount(self._dofs.ravel(), fe.ravel(), minlength=self.mesh.n_dof)
        F = self._checked(self.gradients(u))
        _, P, _ = self.pointwise.evaluate(F, tangent=False)
        fe = P.reshape(P.shape[0], -1) @ self._Bw_flat      # (ne, nd)
        if self.pressure is not None:
            fe = fe + self.pressure.element_terms(F, tangent=False)[0]
        return np.bincount(self._dofs.ravel(), fe.ravel(), minlength=self.mesh.n_dof)

    @cached_property
    def _dN(self) -> np.ndarray:
        """(nq, n_shape, 2) physical shape-function gradients at the elastic rule's points."""
        m = self.mesh
        _, dN = m.element.tabulate(self.rule.xi, self.rule.eta, m.element_length, m.height)
        return np.ascontiguousarray(dN)

    @cached_property
    def _tape(self):
        """The material's energy traced once (:mod:`ancf.core.tape`), replayed compiled."""
        from ...core.tape import trace
        return trace(self.pointwise)

    @cached_property
    def fused(self) -> tuple:
        """What the compiled loops (:mod:`ancf.solvers.compiled_steps`, :mod:`ancf.solvers.compiled_statics`)
        read of the model, contiguous: shape-function gradients, weights, element dofs, the
        law's tape (ops, consts), the element pressure field and assumed strain
        (:func:`ancf.kinematics.section.fields.pressure_arrays`: empty without them; with an assumed
        strain dN and w run over the sample points too, which weigh zero) and the band
        envelope (:func:`ancf.core.bandsolve.envelope`)."""
        from ...core.bandsolve import envelope
        from .fields import pressure_arrays
        ops, consts = self._tape
        dN, w, T = self._dN, self._w, None
        if self.sampled is not None:                    # the rule's points, then the sample points
            dN, w, T = self.assumed.dN, np.concatenate([self._w, np.zeros(len(self.assumed.dN) - len(self._w))]), \
                self.sampled[1]
        return (np.ascontiguousarray(dN), np.ascontiguousarray(w, dtype=float),
                np.ascontiguousarray(self._dofs, dtype=np.int64), np.ascontiguousarray(ops),
                np.ascontiguousarray(consts, dtype=float), pressure_arrays(self.pressure, dN.shape[0], T),
                envelope(self._dofs, self.mesh.n_dof))

    def roundoff_floor(self, u: np.ndarray) -> float:
        """eps ||sum of |terms| of f_int(u)||_2 over the free dofs (N): the size of the
        force's round-off; nan if det F <= 0 at u."""
        if self.compiled:
            return self.static_kernel.roundoff_floor(u)
        try:
            F = self._checked(self.gradients(u))
        except InadmissibleState:
            return float("nan")
        _, P, _ = self.pointwise.evaluate(F, tangent=False)
        fe = np.abs(P.reshape(P.shape[0], -1)) @ np.abs(self._Bw_flat)
        if self.pressure is not None:
            fe = fe + self.pressure.magnitudes(F)
        out = np.bincount(self._dofs.ravel(), fe.ravel(), minlength=self.mesh.n_dof)
        out[self.fixed] = 0.0
        return float(np.finfo(float).eps * np.linalg.norm(out))

    def energy_derivatives(self, a: np.ndarray, J: np.ndarray) -> np.ndarray:
        """W and its (a, J) partials, (6, *a.shape), by the compiled tape (the numpy
        :meth:`Material.energy_jet` is the reference)."""
        from ...core.tape import evaluate
        shape = np.shape(a)
        a2 = np.ascontiguousarray(np.reshape(a, (-1, shape[-1])), dtype=float)
        J2 = np.ascontiguousarray(np.reshape(J, (-1, shape[-1])), dtype=float)
        return evaluate(*self._tape, a2, J2).reshape((6,) + shape)

    def _kernel(self, u: np.ndarray, with_tangent: bool):
        from .kernels import assemble_force_tangent

        if self.sampled is not None:
            return self._kernel_fused(u, with_tangent)
        F = self._checked(self.gradients(u))
        ne, nq = F.shape[:2]
        f4 = np.ascontiguousarray(F.reshape(ne, nq, 4))
        a = np.einsum("eqi,eqi->eq", f4, f4)
        J = f4[..., 0] * f4[..., 3] - f4[..., 1] * f4[..., 2]
        WD = self.energy_derivatives(a, J)   # (6, ne, nq) = W and its (a, J) partials
        m = self.mesh
        f, ab = assemble_force_tangent(f4, WD, self._dN, self._w, self._dofs, m.bandwidth,
                                       m.n_dof, with_tangent)
        K = Banded(ab, m.bandwidth) if with_tangent else None
        if self.pressure is not None:
            fe, Ke = self.pressure.element_terms(F, with_tangent)
            f = f + np.bincount(self._dofs.ravel(), fe.ravel(), minlength=m.n_dof)
            if with_tangent:
                K = Banded(K.ab + self.pattern.assemble(Ke).ab, m.bandwidth)
        return f, K

    def discrete_gradient_force_and_tangent(self, u0: np.ndarray, u1: np.ndarray):
        """f_dg(u0, u1) with (u1 - u0) . f_dg = U(u1) - U(u0), and the midpoint tangent / 2.

        In 2D, a = F:F and J = det F are quadratic in F, so with F_m = (F0 + F1) / 2,
        a1 - a0 = 2 F_m : dF and J1 - J0 = cof F_m : dF exactly. The symmetric discrete
        gradient W^_a = [W(a1, J0) - W(a0, J0) + W(a1, J1) - W(a0, J1)] / (2 da) (and W^_J
        alike) is evaluated as line integrals of W_a and W_J by 3-point Gauss in s:
        exact up to O(d^6), far below round-off for a time step, and free of the
        cancellation of the quotients (which left a 1e-10 noise floor in Newton). Then
        P = 2 W^_a F_m + W^_J cof F_m goes through the same compiled kernel. Not for an
        element with an assumed strain (its det C_bar is not quadratic in u)."""
        from .kernels import assemble_force_tangent

        refuse_discrete_gradient(self)

        F0, F1 = self._checked(self.gradients(u0)), self._checked(self.gradients(u1))
        ne, nq = F0.shape[:2]
        f0, f1 = F0.reshape(ne, nq, 4), F1.reshape(ne, nq, 4)
        fm = np.ascontiguousarray(0.5 * (f0 + f1))
        a0, a1 = np.einsum("eqi,eqi->eq", f0, f0), np.einsum("eqi,eqi->eq", f1, f1)
        J0 = f0[..., 0] * f0[..., 3] - f0[..., 1] * f0[..., 2]
        J1 = f1[..., 0] * f1[..., 3] - f1[..., 1] * f1[..., 2]
        am, Jm = 0.5 * (a0 + a1), 0.5 * (J0 + J1)
        s3 = 0.5 + np.array([-1.0, 0.0, 1.0]) * np.sqrt(0.15)
        w3 = np.array([5.0, 8.0, 5.0]) / 18.0
        a_line = a0 + s3[:, None, None] * (a1 - a0)            # (3, ne, nq)
        J_line = J0 + s3[:, None, None] * (J1 - J0)
        A = np.concatenate([am[None], a_line, a_line, np.broadcast_to(a0, J_line.shape),
                            np.broadcast_to(a1, J_line.shape)])
        Jv = np.concatenate([Jm[None], np.broadcast_to(J0, a_line.shape),
                             np.broadcast_to(J1, a_line.shape), J_line, J_line])
        WD = self.energy_derivatives(A, Jv)                    # (6, 13, ne, nq)
        D = np.ascontiguousarray(WD[:, 0])                     # midpoint second derivatives
        D[1] = 0.5 * np.einsum("k,keq->eq", w3, WD[1, 1:4] + WD[1, 4:7])
        D[2] = 0.5 * np.einsum("k,keq->eq", w3, WD[2, 7:10] + WD[2, 10:13])
        m = self.mesh
        f, ab = assemble_force_tangent(fm, D, self._dN, self._w, self._dofs, m.bandwidth, m.n_dof, True)
        K = Banded(0.5 * ab, m.bandwidth)
        if self.pressure is not None:                          # its own exact discrete gradient
            fe, Ke = self.pressure.discrete_gradient_terms(F0, F1)
            f = f + np.bincount(self._dofs.ravel(), fe.ravel(), minlength=m.n_dof)
            K = Banded(K.ab + self.pattern.assemble(Ke).ab, m.bandwidth)
        return f, K

    def internal_force_and_tangent_numpy(self, u: np.ndarray) -> tuple[np.ndarray, Banded]:
        if self.assumed is not None:
            fe, Ke = self.assumed.element_terms(u[self._dofs])
            f = np.bincount(self._dofs.ravel(), fe.ravel(), minlength=self.mesh.n_dof)
            return f, self.pattern.assemble(Ke)
        F = self._checked(self.gradients(u))
        _, P, A = self.pointwise.evaluate(F, tangent=True)
        ne, nq = P.shape[:2]
        fe = P.reshape(ne, -1) @ self._Bw_flat
        AB = A @ self._B[None]                              # (ne, nq, 4, nd)
        Ke = self._Bw_flat.T @ AB.reshape(ne, nq * 4, -1)   # (ne, nd, nd)
        if self.pressure is not None:
            fp, Kp = self.pressure.element_terms(F)
            fe, Ke = fe + fp, Ke + Kp
        f = np.bincount(self._dofs.ravel(), fe.ravel(), minlength=self.mesh.n_dof)
        return f, self.pattern.assemble(Ke)
