"""The cable ("cable"): a centre line r(x) alone, basis and kinds in x only; the section is no
field but is integrated, fibre by fibre, from the centre line's stretch and curvature with
the law's exact incompressible uniaxial energy (free lateral faces: plane stress alone).

Its package: the model (:mod:`.model`, :class:`CableModel`) and its compiled kernels
(:mod:`.kernels`).
"""
from __future__ import annotations

import numpy as np

from ...core.spec import KINDS, ElementSpec
from ..face import EndFace
from ..family import Kinematics, register_kinematics
from .model import CableModel


class Cable(Kinematics):
    name = "cable"
    summary = ("cable: a centre line in x alone (Euler-Bernoulli); the section integrated fibre by fibre "
               "from its stretch and curvature with the law's uniaxial energy (plane stress only)")
    formulations = ("plane-stress",)
    formulations_why = "the section's fibres in uniaxial stress with free faces"
    section_field = False                 # positions r(x): nothing varies across the section
    reference_gradient = np.diag([1.0, 0.0])   # its point data (r_x, Y r_xx) at rest
    section_slope = 0                     # its section is r_x's normal: r_x jumps, or not
    mirror_admissible = True              # a mirrored or folded cable keeps its fibres' stretch
    patch_test = "uniaxial"

    def check(self, spec: ElementSpec) -> None:
        ybasis = [b for b in spec.basis if "y" in b]
        ykinds = [k for k in spec.kinds if k in KINDS and KINDS[k][1] > 0]
        if ybasis or ykinds or spec.pressure or spec.assumed:
            raise ValueError(f"element {spec.name}: a cable's basis and kinds are in x alone, with no pressure "
                             f"field or assumed strain; got basis in y {ybasis}, kinds in y {ykinds}, "
                             f"pressure {list(spec.pressure)}, assumed {list(spec.assumed)}")

    def refused_integrators(self, spec: ElementSpec) -> dict[str, str]:
        """The discrete gradient needs the invariants quadratic in u at every point: a cable's
        fibre stretch is not even polynomial."""
        return {"discrete-gradient": "a cable's fibre stretch is not quadratic in u: no exact discrete gradient here"}

    def model(self, mesh, material, rule, fixed):
        return CableModel(mesh, material, rule, fixed)

    def fixed_dofs(self, mesh, left: str, clamp: str | None) -> np.ndarray:
        """Its section is the segment r + Y n normal to r_x, so

        - ``clamp`` (``face``): the face fixed: r, and r_x's y-component (its direction; its
          length, the centre line's stretch, stays free as the face's contraction does in the
          continuum); ``clamp = "all"``: every nodal coordinate of the node (r and r_x);
        - ``pin``, ``hinge``: r (the section turns with r_x; a cable's section is straight and
          free to stretch: the hinge is the pin);
        - ``slide``: the face on the plane x = 0 (u_x = 0 over it: r_x horizontal and r_x(0) on
          the plane) and its centre held (u_y = 0): r and r_x's y-component, the clamp."""
        r = mesh.dofs(0, ("r",))
        if left in ("pin", "hinge"):
            return r
        if left == "clamp" and clamp == "all":
            return mesh.dofs(0, mesh.element.kinds)
        return np.sort(np.concatenate([r, mesh.dofs(0, ("r_x",))[1:]]))

    def end_face(self, model) -> EndFace:
        """Its section is r(L) + Y n(L), n = R90 r_x / |r_x|, whose first moment
        (12 / h^3) int (r + Y n) Y dY is n; d = R90 r_x(L) = (-r_x,y, r_x,x) has n's direction
        (its length, the stretch, does not enter theta): linear in u, rows the last node's
        r_x, A = [[0, -1], [1, 0]], d0 = (0, 1)."""
        m = model.mesh
        rows = m.dofs(m.n_nodes - 1, ("r_x",)).astype(np.int64)
        A = np.array([[0.0, -1.0], [1.0, 0.0]])
        return EndFace(rows, A, A @ m.reference[rows])

    def section_points(self, model, u, xi, eta):
        return model.section_points(u, xi, eta)

    def point_data(self, spec, xi, eta, length, height):
        """(npts, n_shape, 2): N_s'(x) and y N_s''(x) at (xi, eta), y = eta h, so that
        r_x = sum_s [..., 0] q_s and y r_xx = sum_s [..., 1] q_s take the places of F's two
        columns (:mod:`.model`)."""
        _, d1 = spec.tabulate(xi, eta, length, height)
        d2 = spec.tabulate_derivative(xi, eta, length, height, 2)
        return np.ascontiguousarray(np.stack([d1[..., 0], (np.ravel(eta) * height)[:, None] * d2], axis=-1))

    def exact_degree(self, spec):
        """Its small strain u_x' - y u_y'' squared: linear in y, so degree 2 across."""
        return 2 * spec.degree()[0], 2

    def small_strain(self, dN):
        """Its fibres' alone: eps_xx = u_x' - y u_y'' (the linearised stretch |r_x| - y theta_x)."""
        nq, ns = dN.shape[:2]
        B = np.zeros((nq, 3, ns, 2))
        B[:, 0, :, 0] = dN[:, :, 0]
        B[:, 0, :, 1] = -dN[:, :, 1]
        return B

    def finite_strain(self, q, dN, T=None):
        """The fibre strain lambda - 1 (npts, 1) for displacements q (ns, 2): e = (1, 0) +
        r_x part, g = y r_xx, lambda = |e| - e x g / |e|^2."""
        G = np.einsum("qaj,ai->qij", dN, q)
        e, g = G[:, :, 0] + np.array([1.0, 0.0]), G[:, :, 1]
        s2 = np.einsum("qi,qi->q", e, e)
        return (np.sqrt(s2) - (e[:, 0] * g[:, 1] - e[:, 1] * g[:, 0]) / s2 - 1.0)[:, None]


CABLE = register_kinematics(Cable())
