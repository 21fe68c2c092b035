"""What every element's model shares: :class:`ElementModel`, the interface the solvers, loads,
supports and checks use (the mesh, the material, the elastic rule and the fixed dofs; the
strain energy, internal force and tangent by the compiled element interface,
:mod:`ancf.kinematics.kernels`; gravity, the end load and the mass integrated exactly; the
centre line). The continuum-based model is :class:`ancf.kinematics.section.model.BeamModel`, the cable's
:class:`ancf.kinematics.cable.model.CableModel`; :func:`ancf.build.model_for` makes the one an element declares.
The loads and the mass are the same integrals for both: a cable's shape functions do not
depend on y, so int rho N^T N dV = rho h w int N^T N dx (no rotary inertia) and the end
traction's work is F . delta r(L).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..core.banded import Banded, BandedPattern
from ..core.material import Material
from ..core.mesh import Mesh
from ..core.errors import InadmissibleState
from ..core.quadrature import Rule, exact_for


def refuse_discrete_gradient(model) -> None:
    """ValueError naming the element if it cannot take the discrete gradient (its kinematics'
    :meth:`ancf.kinematics.family.Kinematics.refused_integrators`, the one rule; a scene that
    asks for it is refused before, by the scene check, :mod:`ancf.admission`)."""
    spec = model.mesh.element
    why = spec.family.refused_integrators(spec).get("discrete-gradient")
    if why is not None:
        raise ValueError(f"element {spec.name}: {why}")


@dataclass
class ElementModel:
    """What every element's model has (the interface the solvers, loads, supports and
    checks use): the mesh, the material, the elastic rule and the fixed dofs; the strain
    energy, internal force and tangent by the compiled element interface
    (:mod:`ancf.kinematics.kernels`, from :attr:`fused`); gravity, the end load and the mass
    integrated exactly; the centre line. A subclass gives the element's data: ``_dN``
    (the two vectors each point's gradient is made of, per shape function), ``_tape`` (the
    law as the points see it), :attr:`fused`, and the numpy references. :class:`BeamModel`
    is the continuum-based one, :class:`ancf.kinematics.cable.model.CableModel` the cable;
    :func:`ancf.build.model_for` makes the one a mesh's element declares."""
    mesh: Mesh
    material: Material
    rule: Rule                 # quadrature of the elastic terms
    fixed: np.ndarray          # fixed global dofs (homogeneous)

    INADMISSIBLE = "det F or det C_bar <= 0 (or not finite) at a quadrature point"

    @property
    def compiled(self) -> bool:
        """Can the compiled loops (:mod:`ancf.solvers.compiled_statics`, :mod:`ancf.solvers.compiled_steps`)
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
        (:func:`ancf.kinematics.kernels.element_energy`, the energy the compiled loops check);
        :meth:`strain_energy_numpy` is the reference. InadmissibleState at an inadmissible
        state (det F <= 0 at a point; a cable: a fibre's stretch <= 0)."""
        from .kernels import element_energy, element_work
        from .section.kernels import live_tape
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
        (:mod:`ancf.kinematics.section.kernels`, :mod:`ancf.kinematics.kernels`); :meth:`internal_force_and_tangent_numpy`
        is the reference."""
        return self._kernel(u, with_tangent=True)

    @cached_property
    def static_kernel(self):
        """The arrays of the compiled static Newton (:mod:`ancf.solvers.compiled_statics`)."""
        from ..solvers.compiled_statics import StaticKernel
        return StaticKernel(self)

    def _kernel(self, u: np.ndarray, with_tangent: bool):
        """(f, K or None) at u: the compiled loops' assembly (:meth:`_kernel_fused`)."""
        return self._kernel_fused(u, with_tangent)

    def _kernel_fused(self, u: np.ndarray, with_tangent: bool):
        """:meth:`_kernel` by the compiled loops' assembly (:func:`ancf.kinematics.kernels.element_assemble`),
        its upper column band made a general band: the route of an assumed strain and of a
        cable."""
        from .kernels import element_assemble, element_work
        from .section.kernels import OK
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
