"""The beam model: strain energy, internal force and tangent, gravity, tip load, mass.

Vectorised over elements x quadrature points. With B (nq, 4, nd) the map from element
displacements to vec(F - I) at each quadrature point (B[q, 2 i + j, 2 a + i] = dN_a/dX_j),
and w the quadrature weights times the element volume l_e h w_b:

    U   = sum_e sum_q w_q W(F_eq)
    f_e = sum_q w_q B_q^T vec P_eq
    K_e = sum_q w_q B_q^T A_eq B_q

:class:`ElementModel` holds what every element's model shares (the compiled energy, force
and tangent through the element interface :mod:`ancf.element_kernels`, gravity, the end
load, the mass, the centre line); :class:`BeamModel` is the continuum-based model above,
:class:`ancf.cable.CableModel` the cable (the same B with its points' (r_x, Y r_xx) in
place of F); :func:`model_for` makes the one an element declares (``ElementSpec.kinematics``).
The loads and the mass are the same integrals for both: a cable's shape functions do not
depend on y, so int rho N^T N dV = rho h w int N^T N dx (no rotary inertia) and the end
traction's work is F . delta r(L).

Only what a scene calls for is built (:mod:`ancf.build` says which effects it built):
the mass matrix only for dynamics, gravity only when the scene has it, the penalty
only in the penalised formulations.

An element with a pressure field (``ElementSpec.pressure``) in a penalised formulation
takes the penalty on the element-wise projection of J - 1 (:mod:`ancf.pressure`, the
numpy reference) instead of at the points: the points then see the material without its
penalty (:attr:`BeamModel.pointwise`), and the compiled loops read the projection as data
(:func:`ancf.element_fields.pressure_arrays` in :attr:`BeamModel.fused`).

An element with an assumed strain (``ElementSpec.assumed``) takes components of C from
sample points along the beam (:mod:`ancf.assumed`): the compiled kernels see the rule's
points followed by the sample points (weight zero) and the sampling T; the numpy
reference is :class:`ancf.assumed.AssumedStrain` (:attr:`BeamModel.assumed`). Its energy
is not a function of (a, J) at each point, so it has no discrete gradient here.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from .banded import Banded, BandedPattern
from .material import Material
from .mesh import Mesh
from .quadrature import Rule, exact_for


class InadmissibleState(ArithmeticError):
    """A deformation gradient with det F <= 0 (or a non-finite one) somewhere."""


def refuse_discrete_gradient(model) -> None:
    """ValueError naming the element if it has an assumed strain or is a cable: the
    discrete gradient needs a and J quadratic in u at every point, and det C_bar is
    quartic, a fibre's stretch not even polynomial."""
    spec = model.mesh.element
    if spec.cable:
        raise ValueError(f"element {spec.name}: a cable has no discrete gradient here (its fibre stretch is not "
                         "quadratic in u); use an alpha-family integrator (generalized-alpha, newmark, hht)")
    if spec.assumed:
        raise ValueError(f"element {spec.name}: an assumed strain ({', '.join(spec.assumed)}) has no discrete "
                         "gradient here; use an alpha-family integrator (generalized-alpha, newmark, hht)")


@dataclass
class ElementModel:
    """What every element's model has (the interface the solvers, loads, supports and
    checks use): the mesh, the material, the elastic rule and the fixed dofs; the strain
    energy, internal force and tangent by the compiled element interface
    (:mod:`ancf.element_kernels`, from :attr:`fused`); gravity, the end load and the mass
    integrated exactly; the centre line. A subclass gives the element's data: ``_dN``
    (the two vectors each point's gradient is made of, per shape function), ``_tape`` (the
    law as the points see it), :attr:`fused`, and the numpy references. :class:`BeamModel`
    is the continuum-based one, :class:`ancf.cable.CableModel` the cable;
    :func:`model_for` makes the one a mesh's element declares."""
    mesh: Mesh
    material: Material
    rule: Rule                 # quadrature of the elastic terms
    fixed: np.ndarray          # fixed global dofs (homogeneous)

    INADMISSIBLE = "det F or det C_bar <= 0 (or not finite) at a quadrature point"

    @property
    def compiled(self) -> bool:
        """Can the compiled loops (:mod:`ancf.compiled_statics`, :mod:`ancf.compiled_steps`)
        run this model? Every beam model: a pressure field is data to them
        (:attr:`fused`). (The Python solvers remain the reference they are tested against.)"""
        return True

    @property
    def elastic_effects(self) -> list[str]:
        """The internal-force terms: the elastic energy, and the penalty where the
        formulation has one."""
        return ["elastic"] + (["penalty"] if self.material.formulation.penalised else [])

    # -- tabulation ------------------------------------------------------------------
    @cached_property
    def _B(self) -> np.ndarray:
        """(nq, 4, nd): the map from element displacements to vec(G - G_ref) at each point,
        G the point's two vectors (a continuum's F; a cable's (r_x, Y r_xx)):
        B[q, 2 i + j, 2 a + i] = dN[q, a, j]."""
        dN = self._dN
        nq, ns = dN.shape[:2]
        B = np.zeros((nq, 2, 2, ns, 2))  # q, i, j, a, i'
        for i in range(2):
            B[:, i, :, :, i] = np.swapaxes(dN, 1, 2)
        return B.reshape(nq, 4, 2 * ns)

    @cached_property
    def _w(self) -> np.ndarray:
        m = self.mesh
        return self.rule.weight * m.element_length * m.height * m.width

    @cached_property
    def _Bw_flat(self) -> np.ndarray:
        """(nq * 4, nd): rows of B, each scaled by its quadrature weight."""
        return (self._B * self._w[:, None, None]).reshape(-1, self._B.shape[-1])

    @cached_property
    def _B_flat(self) -> np.ndarray:
        return self._B.reshape(-1, self._B.shape[-1])

    @cached_property
    def _dofs(self) -> np.ndarray:
        return self.mesh.element_dofs.reshape(self.mesh.n_elements, -1)

    @cached_property
    def pattern(self) -> BandedPattern:
        return BandedPattern.of(self._dofs, self.mesh.n_dof, self.mesh.bandwidth)

    @property
    def n_free(self) -> int:
        return self.mesh.n_dof - len(self.fixed)

    # -- kinematics ------------------------------------------------------------------
    def strain_variation(self, v: np.ndarray) -> np.ndarray:
        """vec(grad v) at every element and elastic quadrature point, (ne, nq * 4): the
        strain a displacement field v produces where the rule looks."""
        return v[self._dofs] @ self._B_flat.T

    # -- elastic terms -----------------------------------------------------------------
    def strain_energy(self, u: np.ndarray) -> float:
        """Strain energy (J) at u, pressure field included, by the compiled element interface
        (:func:`ancf.element_kernels.element_energy`, the energy the compiled loops check);
        :meth:`strain_energy_numpy` is the reference. InadmissibleState at an inadmissible
        state (det F <= 0 at a point; a cable: a fibre's stretch <= 0)."""
        from .element_kernels import element_energy, element_work
        from .kernels import live_tape
        if "_energy_data" not in self.__dict__:
            dN, w, dofs, ops, consts, pr, _ = self.fused
            ops, consts = live_tape(ops, consts)
            self._energy_data = (dN, w, dofs, ops, consts, pr, *element_work(ops, dN, pr))
        U = element_energy(np.ascontiguousarray(u, dtype=float), *self._energy_data)
        if not np.isfinite(U):
            self._admissible(u)                        # names the point
            raise InadmissibleState(f"strain energy {U} at an admissible state")
        return float(U)

    def _admissible(self, u: np.ndarray) -> None:
        """InadmissibleState naming why u is not admissible (the numpy route's test)."""
        raise NotImplementedError

    def internal_force(self, u: np.ndarray) -> np.ndarray:
        """Internal force (N) at u, by the compiled kernel without the tangent."""
        return self._kernel(u, with_tangent=False)[0]

    def internal_force_and_tangent(self, u: np.ndarray) -> tuple[np.ndarray, Banded]:
        """Internal force (N) and tangent (N/m) at u, by the compiled kernel
        (:mod:`ancf.kernels`, :mod:`ancf.element_kernels`); :meth:`internal_force_and_tangent_numpy`
        is the reference."""
        return self._kernel(u, with_tangent=True)

    @cached_property
    def static_kernel(self):
        """The arrays of the compiled static Newton (:mod:`ancf.compiled_statics`)."""
        from .compiled_statics import StaticKernel
        return StaticKernel(self)

    def _kernel(self, u: np.ndarray, with_tangent: bool):
        """(f, K or None) at u: the compiled loops' assembly (:meth:`_kernel_fused`)."""
        return self._kernel_fused(u, with_tangent)

    def _kernel_fused(self, u: np.ndarray, with_tangent: bool):
        """:meth:`_kernel` by the compiled loops' assembly (:func:`ancf.element_kernels.element_assemble`),
        its upper column band made a general band: the route of an assumed strain and of a
        cable."""
        from .element_kernels import element_assemble, element_work
        from .kernels import OK
        dN, w, dofs, ops, consts, pr, _ = self.fused
        m, b = self.mesh, self.mesh.bandwidth
        u = np.ascontiguousarray(u, dtype=float)
        f, Kc = np.zeros(m.n_dof), np.zeros((m.n_dof, b + 1))
        scratch = element_work(ops, dN, pr)
        if element_assemble(u, u, 0.0, dN, w, dofs, ops, consts, pr, f, Kc, with_tangent, *scratch) != OK:
            raise InadmissibleState(self.INADMISSIBLE)
        if not with_tangent:
            return f, None
        ab = np.zeros((2 * b + 1, m.n_dof))
        ab[:b + 1] = Kc.T                               # K[c - d, c] = Kc[c, b - d]
        for d in range(1, b + 1):                       # K[c + d, c] = K[c, c + d] = Kc[c + d, b - d]
            ab[b + d, :m.n_dof - d] = Kc[d:, b - d]
        return f, Banded(ab, b)

    # -- loads and inertia (integrated exactly, whatever the elastic rule) ------------
    @cached_property
    def _exact(self):
        m = self.mesh
        dx, dy = m.element.degree()
        return exact_for(2 * dx, 2 * dy)

    def gravity_force(self, g) -> np.ndarray:
        """Q_g = int rho N^T g dV (N), exact."""
        m, rule = self.mesh, self._exact
        N, _ = m.element.tabulate(rule.xi, rule.eta, m.element_length, m.height)
        vol = m.element_length * m.height * m.width
        intN = self.material.density * vol * (rule.weight @ N)           # (ns,)
        fe = intN[None, :, None] * np.asarray(g, float)[None, None, :]   # (1, ns, 2)
        fe = np.broadcast_to(fe, self.mesh.element_dofs.shape)
        return np.bincount(self.mesh.element_dofs.ravel(), fe.ravel(), minlength=m.n_dof)

    def tip_force(self, force) -> np.ndarray:
        """The end load (N) as :mod:`contract.loads` defines it: the uniform dead traction
        F / (h w) on the free end face, its nodal forces the exact virtual work
        int N(L, y)^T t w dy (Gauss across the thickness, exact for the basis in y)."""
        from contract.loads import end_traction

        m = self.mesh
        rule = exact_for(0, m.element.degree()[1])
        N, _ = m.element.tabulate(np.ones_like(rule.eta), rule.eta, m.element_length, m.height)
        t = end_traction(force, m.height, m.width)
        face = m.height * m.width * (rule.weight / rule.weight.sum()) @ N    # int N w dy, (ns,)
        f = np.zeros(m.n_dof)
        np.add.at(f, m.element_dofs[-1], face[:, None] * t[None, :])
        return f

    def mass_matrix(self) -> Banded:
        """M = int rho S^T S dV (kg), exact."""
        m, rule = self.mesh, self._exact
        N, _ = m.element.tabulate(rule.xi, rule.eta, m.element_length, m.height)
        vol = m.element_length * m.height * m.width
        Ms = self.material.density * vol * np.einsum("q,qa,qb->ab", rule.weight, N, N)
        Me = np.kron(Ms, np.eye(2))                                       # local order (a, i)
        return self.pattern.assemble(np.broadcast_to(Me, (m.n_elements,) + Me.shape))

    # -- outputs -------------------------------------------------------------------------
    def _centre_shapes(self, per_element: int) -> np.ndarray:
        """Shape functions at per_element + 1 points of the centre line, tabulated once
        (outputs are taken at every output time)."""
        cache = self.__dict__.setdefault("_centre_cache", {})
        if per_element not in cache:
            m = self.mesh
            xi = np.linspace(0.0, 1.0, per_element + 1)
            cache[per_element] = m.element.tabulate(xi, np.zeros_like(xi), m.element_length, m.height)[0]
        return cache[per_element]

    def tip_displacement(self, u: np.ndarray) -> np.ndarray:
        """r(L, 0) - (L, 0) in m."""
        return self._centre_shapes(1)[-1] @ u[self.mesh.element_dofs[-1]]

    def centre_line(self, u: np.ndarray, per_element: int = 8) -> np.ndarray:
        """Deformed centre-line points (n, 2) in m."""
        m = self.mesh
        N = self._centre_shapes(per_element)
        q = m.reference + u
        pts = np.matmul(N, q[m.element_dofs])           # (elements, points, 2)
        return np.concatenate([pts[:, :-1].reshape(-1, 2), pts[-1, -1:]])

    @property
    def full_rule(self) -> Rule:
        """A rule exact for the squared polynomials of the element (the stability check's
        measure of what a mode strains)."""
        dx, dy = self.mesh.element.degree()
        return exact_for(2 * dx, 2 * dy)


@dataclass
class BeamModel(ElementModel):
    """A continuum-based element's model: F = I + grad u at the rule's points of the
    section, W(F) by the law in the scene's formulation."""
    @cached_property
    def pressure(self):
        """The projected penalty (:class:`ancf.pressure.ProjectedPenalty`) of an element
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
        """(points, T) of an element with an assumed strain (:func:`ancf.assumed.sampling`:
        the rule's points then the sample points, and C_bar's sampling); None without one."""
        spec = self.mesh.element
        if not spec.assumed:
            return None
        from .assumed import sampling
        return sampling(spec.assumed, spec.assumed_points, self.rule)

    @cached_property
    def assumed(self):
        """The numpy reference of the assumed strain (:class:`ancf.assumed.AssumedStrain`),
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
        """The material's energy traced once (:mod:`ancf.tape`), replayed compiled."""
        from .tape import trace
        return trace(self.pointwise)

    @cached_property
    def fused(self) -> tuple:
        """What the compiled loops (:mod:`ancf.compiled_steps`, :mod:`ancf.compiled_statics`)
        read of the model, contiguous: shape-function gradients, weights, element dofs, the
        law's tape (ops, consts), the element pressure field and assumed strain
        (:func:`ancf.element_fields.pressure_arrays`: empty without them; with an assumed
        strain dN and w run over the sample points too, which weigh zero) and the band
        envelope (:func:`ancf.bandsolve.envelope`)."""
        from .bandsolve import envelope
        from .element_fields import pressure_arrays
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
        from .tape import evaluate
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


def model_for(mesh: Mesh, material: Material, rule: Rule, fixed: np.ndarray) -> ElementModel:
    """The model of the kinematics the mesh's element declares (``ElementSpec.kinematics``):
    :class:`ancf.cable.CableModel` for a cable, :class:`BeamModel` otherwise."""
    if mesh.element.cable:
        from .cable import CableModel
        return CableModel(mesh, material, rule, fixed)
    return BeamModel(mesh, material, rule, fixed)
