"""The continuum-based planar section ("continuum"): shape functions in (x, y) spanning the
plane, F = I + grad u at points of the section, every formulation.

Its package: the model (:mod:`.model`, :class:`BeamModel`), its compiled kernels
(:mod:`.kernels`, the discrete gradient's :mod:`.dg_kernels`), the element pressure field of
the mixed form (:mod:`.pressure`, compiled in :mod:`.fields`) and the assumed strain
(:mod:`.assumed`, :mod:`.assumed_kernels`).
"""
from __future__ import annotations

import numpy as np

from ...core.quadrature import exact_for
from ...core.spec import KINDS, ElementSpec
from ..face import EndFace
from ..family import Kinematics, register_kinematics
from .assumed import COMPONENTS
from .model import BeamModel
from contract.loads import face_moment_weight

# Which nodal coordinate kinds each support fixes at x = 0: the face clamp fixes the
# end face, r(0, y) = (0, y) for every y, so every pure y-derivative kind (r, r_y, r_yy,
# ...: no x-derivative) of the element, whatever its degree in y.
SUPPORT_KINDS = {
    ("clamp", "face"): "face",                         # the end face: all y-derivatives
    ("clamp", "all"): None,                            # every nodal coordinate of the node
    ("pin", None): ("r",),
}


class Section(Kinematics):
    name = "continuum"
    summary = "continuum-based: shape functions in (x, y), F = I + grad u at points of the section"
    # the checks' data are the defaults: positions N(x, y), F = I at rest, r_y the section's
    # slope, a mirrored state inadmissible (x -> -x makes det F = -1), the stress patch test

    def check(self, spec: ElementSpec) -> None:
        bad = [c for c in spec.assumed if c not in COMPONENTS]
        if bad or len(set(spec.assumed)) != len(spec.assumed) or spec.assumed_points < 1:
            raise ValueError(f"element {spec.name}: assumed {list(spec.assumed)} with {spec.assumed_points} points; "
                             f"assumed components are distinct ones of {', '.join(COMPONENTS)}, points >= 1")

    def refused_integrators(self, spec: ElementSpec) -> dict[str, str]:
        """The discrete gradient needs the invariants a and J quadratic in u at every point:
        an assumed strain's det C_bar is quartic."""
        if not spec.assumed:
            return {}
        return {"discrete-gradient": f"an assumed strain ({', '.join(spec.assumed)}) makes det C quartic in u: "
                                     "no exact discrete gradient here"}

    def model(self, mesh, material, rule, fixed):
        return BeamModel(mesh, material, rule, fixed)

    def fixed_dofs(self, mesh, left: str, clamp: str | None) -> np.ndarray:
        """``slide``: the face on the plane x = 0, r_x(0, y) = 0 for every y, so the
        x-components of every pure y-derivative kind, and the centre's y-component.
        ``hinge``: the face straight through its fixed centre, r(0, y) = y a, so r and every
        pure y-derivative kind but r_y."""
        face = tuple(k for k in mesh.element.kinds if KINDS[k][0] == 0)
        if left == "slide":
            return np.sort(np.concatenate([mesh.dofs(0, face)[0::2], mesh.dofs(0, ("r",))[1:]]))
        if left == "hinge":
            return np.sort(mesh.dofs(0, tuple(k for k in face if KINDS[k][1] != 1)))
        kinds = SUPPORT_KINDS[(left, clamp if left == "clamp" else None)]
        if kinds == "face":
            kinds = face
        return mesh.dofs(0, mesh.element.kinds if kinds is None else kinds)

    def end_face(self, model) -> EndFace:
        """A[i, (s, i)] = c_s, c_s = (12 / h^3) int N_s(L, y) y dy over the last element's
        shape functions (Gauss across the thickness exact for y times the basis in y)."""
        m = model.mesh
        rule = exact_for(0, m.element.degree()[1] + 1)
        N, _ = m.element.tabulate(np.ones_like(rule.eta), rule.eta, m.element_length, m.height)
        y = rule.eta * m.height
        c = face_moment_weight(m.height) * m.height * ((rule.weight / rule.weight.sum()) * y) @ N   # (ns,)
        dofs = m.element_dofs[-1]                                         # (ns, 2)
        keep = np.abs(c) > 1e-12 * np.abs(c).max()
        c, dofs = c[keep], dofs[keep]
        rows = dofs.reshape(-1).astype(np.int64)                          # (s, x), (s, y), ...
        A = np.zeros((2, len(rows)))
        A[0, 0::2], A[1, 1::2] = c, c
        d0 = A @ m.reference[rows]
        return EndFace(rows, A, d0)

    def section_points(self, model, u, xi, eta):
        m = model.mesh
        N, _ = m.element.tabulate(xi, eta, m.element_length, m.height)
        return np.einsum("pa,eai->epi", N, (m.reference + u)[m.element_dofs])

    def point_data(self, spec, xi, eta, length, height):
        return spec.tabulate(xi, eta, length, height)[1]

    def exact_degree(self, spec):
        dx, dy = spec.degree()
        return 2 * dx, 2 * dy

    def small_strain(self, dN):
        nq, ns = dN.shape[:2]
        B = np.zeros((nq, 3, ns, 2))
        B[:, 0, :, 0] = dN[:, :, 0]
        B[:, 1, :, 1] = dN[:, :, 1]
        B[:, 2, :, 0] = dN[:, :, 1]
        B[:, 2, :, 1] = dN[:, :, 0]
        return B

    def finite_strain(self, q, dN, T=None):
        """[E_xx, E_yy, sqrt(2) E_xy] at the points of dN, or, with an assumed strain's T
        (:func:`.assumed.sampling`; dN at its points), the assumed E_bar = (C_bar - I) / 2
        at the rule's (T's rows reproduce constants, so E_bar = T E)."""
        G = np.einsum("qaj,ai->qij", dN, q)
        F = G + np.eye(2)
        E = 0.5 * (np.einsum("qki,qkj->qij", F, F) - np.eye(2))
        E = np.stack([E[:, 0, 0], E[:, 1, 1], np.sqrt(2.0) * E[:, 0, 1]], axis=1)
        return E if T is None else np.stack([T[c] @ E[:, c] for c in range(3)], axis=1)


SECTION = register_kinematics(Section())
