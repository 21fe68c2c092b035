"""ANCF beam elements as data, and the shape functions derived from them.

An element is a :class:`ElementSpec`: basis polynomials (the same for both position
components), node positions along the element and the nodal coordinate kinds at each
node. Everything else is derived: the nodal-coordinate matrix A[k, j] = functional_k
(basis_j) is built and inverted in the dimensionless coordinates xi = x / l_e and
eta = y / h (in metres it is badly conditioned), then scaled to physical units. The
basis is written in physical (x, y): x^2 + y^2 is l_e^2 xi^2 + h^2 eta^2, so the
derived shape functions depend on the aspect ratio h / l_e.

To add an element, register a spec::

    register_element(ElementSpec(
        name="HB2n-cubic", basis=("1", "x", "y", "x*y", "x^2", "y^2", "x*y^2", "x^3", "y^3", "x*y^3"),
        nodes=(0.0, 1.0), kinds=("r", "r_x", "r_y", "r_yy", "r_yyy")))

(only if its kinds are known to :data:`KINDS`); scenes can then name it.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np

from contract.errors import UnknownName
from .polynomial import Poly, parse

# Nodal coordinate kind -> (derivative order in x, in y). Physical value = dimensionless
# value / (l_e^dx h^dy), so the physical shape function is the dimensionless one
# times l_e^dx h^dy.
KINDS: dict[str, tuple[int, int]] = {
    "r": (0, 0), "r_x": (1, 0), "r_y": (0, 1), "r_yy": (0, 2), "r_yyy": (0, 3),
    "r_xx": (2, 0), "r_xy": (1, 1),
}


@dataclass(frozen=True)
class ElementSpec:
    name: str
    basis: tuple[str, ...]       # polynomials in physical (x, y), e.g. "x^2 + y^2"
    nodes: tuple[float, ...]     # node positions xi in [0, 1] on the centre line (eta = 0)
    kinds: tuple[str, ...]       # nodal coordinate kinds at every node
    reference: str = ""
    # the default elastic rule, chosen by the rank tests of ancf.rank: entries
    # (penalised formulation?, smallest l_e / h, (points along x, across the thickness)),
    # the first that matches a scene wins; empty: the rule exact for the basis (safe, dear)
    quadrature: tuple[tuple[bool, float, tuple[int, int]], ...] = ()

    def __post_init__(self):
        unknown = [k for k in self.kinds if k not in KINDS]
        if unknown:
            raise ValueError(f"element {self.name}: unknown kinds {unknown}; known: {sorted(KINDS)}")
        if not (self.nodes[0] == 0.0 and self.nodes[-1] == 1.0 and list(self.nodes) == sorted(self.nodes)):
            raise ValueError(f"element {self.name}: nodes must rise from 0 to 1, got {self.nodes}")
        if len(self.basis) != len(self.nodes) * len(self.kinds):
            raise ValueError(f"element {self.name}: {len(self.basis)} basis functions but "
                             f"{len(self.nodes)} nodes x {len(self.kinds)} kinds")

    @cached_property
    def polys(self) -> tuple[Poly, ...]:
        return tuple(parse(b) for b in self.basis)

    @property
    def n_shape(self) -> int:
        """Scalar shape functions per element (dof = 2 n_shape)."""
        return len(self.basis)

    @property
    def dof(self) -> int:
        return 2 * self.n_shape

    @lru_cache(maxsize=64)
    def dimensionless(self, length: float, height: float) -> tuple[tuple[Poly, ...], np.ndarray]:
        """Basis in (xi, eta) for an element l_e x h, and C such that the dimensionless
        shape function N_k(xi, eta) = sum_j basis_j(xi, eta) C[j, k]."""
        polys = tuple(p.scaled(length, height) for p in self.polys)
        A = np.array([[p(xi, 0.0, *KINDS[k]) for p in polys]
                      for xi in self.nodes for k in self.kinds])
        if np.linalg.matrix_rank(A) < len(A):
            raise ValueError(f"element {self.name}: nodal coordinates do not determine the basis")
        return polys, np.linalg.inv(A)

    def degree(self) -> tuple[int, int]:
        d = np.array([p.degree() for p in self.polys])
        return int(d[:, 0].max()), int(d[:, 1].max())

    def tabulate(self, xi, eta, length: float, height: float):
        """Physical shape functions and their gradients at points (xi, eta).

        Returns N (npts, n_shape) and dN (npts, n_shape, 2) with dN[..., 0] = dN/dx,
        dN[..., 1] = dN/dy in 1/m, for element length l_e = ``length`` and thickness h.
        Local shape function k is node k // len(kinds), kind k % len(kinds).
        """
        xi, eta = np.ravel(xi), np.ravel(eta)
        polys, C = self.dimensionless(float(length), float(height))
        scale = np.array([length ** KINDS[k][0] * height ** KINDS[k][1]
                          for _ in self.nodes for k in self.kinds])
        B = np.stack([p(xi, eta) for p in polys], axis=-1)
        Bx = np.stack([p(xi, eta, 1, 0) for p in polys], axis=-1) / length
        By = np.stack([p(xi, eta, 0, 1) for p in polys], axis=-1) / height
        N = (B @ C) * scale
        dN = np.stack([(Bx @ C) * scale, (By @ C) * scale], axis=-1)
        return N, dN

    def reference_coordinates(self, x_node: float) -> np.ndarray:
        """Nodal coordinates (n_kinds, 2) of a straight, unstressed beam at node x."""
        ref = {"r": (x_node, 0.0), "r_x": (1.0, 0.0), "r_y": (0.0, 1.0)}
        return np.array([ref.get(k, (0.0, 0.0)) for k in self.kinds])


ELEMENTS: dict[str, ElementSpec] = {}


def register_element(spec: ElementSpec) -> ElementSpec:
    if spec.name in ELEMENTS:
        raise ValueError(f"element {spec.name!r} is registered already")
    spec.dimensionless(1.0, 1.0)  # fail at registration, not at first use
    ELEMENTS[spec.name] = spec
    return spec


def get_element(name: str) -> ElementSpec:
    try:
        return ELEMENTS[name]
    except KeyError:
        raise UnknownName("ancf.element", name, ELEMENTS) from None


register_element(ElementSpec(
    "LB2n-12", ("1", "x", "y", "x*y", "x^2", "x^3"), (0.0, 1.0), ("r", "r_x", "r_y"),
    "Omar & Shabana 2001 (linear across the thickness)",
    ((False, 0.0, (3, 2)), (True, 0.0, (3, 2)))))
register_element(ElementSpec(
    "HB2n-12", ("1", "x", "y", "x*y", "x^2 + y^2", "x^3"), (0.0, 1.0), ("r", "r_x", "r_y"),
    "Zhao et al. 2021", ((False, 0.3, (3, 2)), (False, 0.0, (3, 3)), (True, 0.1, (3, 2)), (True, 0.0, (3, 3)))))
register_element(ElementSpec(
    "HB3n-12", ("1", "x", "y", "x*y", "x^2 + y^2", "x^2*y"), (0.0, 0.5, 1.0), ("r", "r_y"),
    "Zhao et al. 2021", ((False, 0.1, (3, 2)), (False, 0.0, (3, 3)), (True, 0.1, (3, 2)), (True, 0.0, (3, 3)))))
register_element(ElementSpec(
    "HB2n-16", ("1", "x", "y", "x*y", "x^2", "y^2", "x*y^2", "x^3"), (0.0, 1.0),
    ("r", "r_x", "r_y", "r_yy"), "Patel & Shabana 2018",
    ((False, 0.3, (3, 2)), (False, 0.0, (3, 3)), (True, 0.3, (3, 2)), (True, 0.0, (3, 3)))))
