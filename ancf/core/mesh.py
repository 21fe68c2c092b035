"""A uniform straight mesh of one element type along x and its dof numbering (the dofs a
support fixes: the element's kinematics, :meth:`ancf.kinematics.family.Kinematics.fixed_dofs`).

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

from .spec import ElementSpec


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
