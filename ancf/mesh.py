"""A uniform straight mesh of one element type along x, its dof numbering and supports.

Global nodes run along the beam; each carries the element's nodal coordinate kinds, each
kind two components. Global dof of (node n, kind k, component i) is
(n * n_kinds + k) * 2 + i, so the tangent is banded. The unknowns are displacements
u = q - q_ref of the nodal coordinates (positions and gradients): deformation gradients
are then F = I + grad u, computed without the round-off of subtracting positions of
order L at elements of a fraction of a millimetre.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .elements import KINDS, ElementSpec


@dataclass(frozen=True)
class Mesh:
    element: ElementSpec
    n_elements: int
    length: float  # m
    height: float  # m, in plane
    width: float   # m, out of plane

    @property
    def element_length(self) -> float:
        return self.length / self.n_elements

    @property
    def nodes_per_element(self) -> int:
        return len(self.element.nodes)

    @property
    def n_nodes(self) -> int:
        return self.n_elements * (self.nodes_per_element - 1) + 1

    @property
    def n_kinds(self) -> int:
        return len(self.element.kinds)

    @property
    def n_dof(self) -> int:
        return 2 * self.n_kinds * self.n_nodes

    @cached_property
    def node_x(self) -> np.ndarray:
        """Reference x of every global node (m)."""
        le = self.element_length
        xi = np.asarray(self.element.nodes)
        x = (np.arange(self.n_elements)[:, None] + xi[None, :]) * le
        out = np.empty(self.n_nodes)
        out[self.element_nodes] = x
        out[-1] = self.length  # exactly L at the free end
        return out

    @cached_property
    def element_nodes(self) -> np.ndarray:
        """(n_elements, nodes_per_element) global node numbers."""
        m = self.nodes_per_element - 1
        return np.arange(self.n_elements)[:, None] * m + np.arange(m + 1)[None, :]

    @cached_property
    def element_dofs(self) -> np.ndarray:
        """(n_elements, n_shape, 2) global dofs in the element's local order."""
        nk = self.n_kinds
        node = self.element_nodes[:, :, None]
        slot = node * nk + np.arange(nk)[None, None, :]          # (ne, nn, nk)
        slot = slot.reshape(self.n_elements, -1)                  # local shape k
        return slot[:, :, None] * 2 + np.arange(2)[None, None, :]

    @cached_property
    def bandwidth(self) -> int:
        d = self.element_dofs.reshape(self.n_elements, -1)
        return int((d.max(axis=1) - d.min(axis=1)).max())

    @cached_property
    def reference(self) -> np.ndarray:
        """Reference nodal coordinates q_ref (n_dof,)."""
        q = np.stack([self.element.reference_coordinates(x) for x in self.node_x])
        return q.reshape(-1)

    def dofs(self, node: int, kinds) -> np.ndarray:
        """Global dofs (both components) of the given kinds present at a node."""
        ks = [self.element.kinds.index(k) for k in kinds if k in self.element.kinds]
        return np.array([(node * self.n_kinds + k) * 2 + i for k in ks for i in (0, 1)], dtype=int)


# Which nodal coordinate kinds each support fixes at x = 0: the face clamp fixes the
# end face, r(0, y) = (0, y) for every y, so every pure y-derivative kind (r, r_y, r_yy,
# ...: no x-derivative) of the element, whatever its degree in y.
SUPPORT_KINDS = {
    ("clamp", "face"): "face",                         # the end face: all y-derivatives
    ("clamp", "all"): None,                            # every nodal coordinate of the node
    ("pin", None): ("r",),
}


def fixed_dofs(mesh: Mesh, left: str, clamp: str | None) -> np.ndarray:
    """The dofs a support fixes at x = 0 (:data:`contract.loads.SUPPORTS`). ``slide``: the
    face on the plane x = 0, r_x(0, y) = 0 for every y, so the x-components of every pure
    y-derivative kind, and the centre's y-component. ``hinge``: the face straight through
    its fixed centre, r(0, y) = y a, so r and every pure y-derivative kind but r_y. A cable
    (:func:`cable_fixed_dofs`) has no section coordinates: its supports act on r and r_x."""
    if mesh.element.cable:
        return cable_fixed_dofs(mesh, left, clamp)
    face = tuple(k for k in mesh.element.kinds if KINDS[k][0] == 0)
    if left == "slide":
        return np.sort(np.concatenate([mesh.dofs(0, face)[0::2], mesh.dofs(0, ("r",))[1:]]))
    if left == "hinge":
        return np.sort(mesh.dofs(0, tuple(k for k in face if KINDS[k][1] != 1)))
    kinds = SUPPORT_KINDS[(left, clamp if left == "clamp" else None)]
    if kinds == "face":
        kinds = face
    return mesh.dofs(0, mesh.element.kinds if kinds is None else kinds)


def cable_fixed_dofs(mesh: Mesh, left: str, clamp: str | None) -> np.ndarray:
    """A cable's supports at x = 0: its section is the segment r + Y n normal to r_x, so

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
