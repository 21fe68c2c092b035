"""A spatial ANCF element as data (:class:`SpatialSpec`), and its shape functions.

As for a planar element (:mod:`ancf.core.spec`), everything follows from the basis
polynomials, the node positions along the element and the kinds of nodal coordinate: the
nodal-coordinate matrix A[m, j] = functional_m(basis_j) is built and inverted in the
dimensionless coordinates xi = x / l_e, eta = y / h, zeta = z / w (the section is h high in
y and w wide in z, centred on the axis), then scaled to physical units. A kind is ``r`` or
``r_`` followed by its derivatives, x's before y's before z's (``r_x``, ``r_yz``, ``r_zz``); its
functional is that derivative of the position at the node, on the beam's axis
(eta = zeta = 0). Local shape function m is node m // len(kinds), kind m % len(kinds); the
element's coordinates are q (n_shape, 3), r(X) = sum_m N_m(X) q_m.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np

from .polynomial import Poly3, parse3


def kind_orders(kind: str) -> tuple[int, int, int]:
    """(derivative order in x, y, z) of a nodal coordinate kind, read from its name."""
    head, _, d = kind.partition("_")
    if head != "r" or (kind != "r" and not d) or d != "".join(sorted(d)) or set(d) - set("xyz"):
        raise ValueError(f"unknown nodal coordinate kind {kind!r}: 'r' or 'r_' and its derivatives, "
                         "x's before y's before z's ('r_x', 'r_yz', 'r_zz')")
    return d.count("x"), d.count("y"), d.count("z")


@dataclass(frozen=True)
class SpatialSpec:
    name: str
    basis: tuple[str, ...]       # polynomials in physical (x, y, z), e.g. "x^2*y"
    nodes: tuple[float, ...]     # node positions xi in [0, 1] on the axis
    kinds: tuple[str, ...]       # nodal coordinate kinds at every node
    reference: str = ""          # where the element is defined (author, year)
    # the element-wise pressure basis (polynomials in x, y, z): the penalty then acts on the
    # L2 projection of J - 1 onto it per element instead of at every point (the u-p mixed
    # form with its pressure condensed, as the planar lock-free elements); empty: pointwise
    pressure: tuple[str, ...] = ()
    # the Gauss points (along, across h, across w) of the element's energy when a run names
    # none, chosen by the rank test (:mod:`.rank`); None: the rule exact for the squared basis
    quadrature: tuple[int, int, int] | None = None

    def __post_init__(self):
        for k in self.kinds:
            kind_orders(k)
        if not (self.nodes[0] == 0.0 and self.nodes[-1] == 1.0 and list(self.nodes) == sorted(self.nodes)):
            raise ValueError(f"element {self.name}: nodes must rise from 0 to 1, got {self.nodes}")
        if len(self.basis) != len(self.nodes) * len(self.kinds):
            raise ValueError(f"element {self.name}: {len(self.basis)} basis functions but "
                             f"{len(self.nodes)} nodes x {len(self.kinds)} kinds")

    @cached_property
    def polys(self) -> tuple[Poly3, ...]:
        return tuple(parse3(b) for b in self.basis)

    @property
    def n_shape(self) -> int:
        """Scalar shape functions per element (dof = 3 n_shape)."""
        return len(self.basis)

    @property
    def dof(self) -> int:
        return 3 * self.n_shape

    @property
    def section_monomials(self) -> list[tuple[int, int]]:
        """The section's fields y^a z^b as (a, b): the kinds without an x derivative."""
        return [kind_orders(k)[1:] for k in self.kinds if kind_orders(k)[0] == 0]

    def default_rule(self) -> tuple[int, int, int]:
        """The declared rule, or the one exact for the squared basis (d + 1 points for degree d)."""
        return tuple(self.quadrature) if self.quadrature else tuple(d + 1 for d in self.degree())

    def degree(self) -> tuple[int, int, int]:
        """Highest power of x, y and z in the basis."""
        d = np.array([p.degree() for p in self.polys])
        return tuple(int(v) for v in d.max(axis=0))

    @lru_cache(maxsize=64)
    def dimensionless(self, length: float, height: float, width: float) -> tuple[tuple[Poly3, ...], np.ndarray]:
        """The basis in (xi, eta, zeta) for an element l_e x h x w, and C such that the
        dimensionless shape function N_m = sum_j basis_j C[j, m]."""
        polys = tuple(p.scaled(length, height, width) for p in self.polys)
        A = np.array([[p(xi, 0.0, 0.0, kind_orders(k)) for p in polys] for xi in self.nodes for k in self.kinds])
        if np.linalg.matrix_rank(A) < len(A):
            raise ValueError(f"element {self.name}: its nodal coordinates do not determine its basis")
        return polys, np.linalg.inv(A)

    def _scale(self, length: float, height: float, width: float) -> np.ndarray:
        """Physical shape function = dimensionless one x l_e^dx h^dy w^dz of its kind."""
        out = []
        for _ in self.nodes:
            for k in self.kinds:
                dx, dy, dz = kind_orders(k)
                out.append(length ** dx * height ** dy * width ** dz)
        return np.array(out)

    def tabulate(self, xi, eta, zeta, length: float, height: float, width: float) -> tuple[np.ndarray, np.ndarray]:
        """Physical shape functions N (npts, n_shape) and their gradients dN (npts, n_shape, 3)
        in 1/m at the points (xi in [0, 1], eta and zeta in [-1/2, 1/2])."""
        xi, eta, zeta = (np.ravel(v).astype(float) for v in np.broadcast_arrays(xi, eta, zeta))
        polys, C = self.dimensionless(float(length), float(height), float(width))
        s = self._scale(length, height, width)
        size = (length, height, width)
        B = np.stack([p(xi, eta, zeta) for p in polys], axis=-1)
        N = (B @ C) * s
        dN = np.stack([(np.stack([p(xi, eta, zeta, tuple(int(a == b) for b in range(3))) for p in polys], axis=-1)
                        / size[a]) @ C * s for a in range(3)], axis=-1)
        return N, dN

    def pressure_tabulate(self, xi, eta, zeta, length: float, height: float, width: float) -> np.ndarray:
        """The pressure basis at the points, (npts, n_pressure), in dimensionless coordinates
        (the projection depends only on the span)."""
        xi, eta, zeta = (np.ravel(v).astype(float) for v in np.broadcast_arrays(xi, eta, zeta))
        return np.stack([parse3(b).scaled(length, height, width)(xi, eta, zeta) for b in self.pressure], axis=-1)

    def reference_coordinates(self, x_node: float) -> np.ndarray:
        """Nodal coordinates (n_kinds, 3) of a straight unstressed beam along x at node x:
        r = (x, 0, 0), r_x, r_y, r_z the unit vectors, every higher derivative zero."""
        ref = {"r": (x_node, 0.0, 0.0), "r_x": (1.0, 0.0, 0.0), "r_y": (0.0, 1.0, 0.0), "r_z": (0.0, 0.0, 1.0)}
        return np.array([ref.get(k, (0.0, 0.0, 0.0)) for k in self.kinds])
