"""An ANCF element as data (:class:`ElementSpec`), and the shape functions derived from it.

An element is basis polynomials (the same for both position components), node positions
along the element and the nodal coordinate kinds at each node. Everything else is
derived: the nodal-coordinate matrix A[k, j] = functional_k (basis_j) is built and
inverted in the dimensionless coordinates xi = x / l_e and eta = y / h (in metres it is
badly conditioned), then scaled to physical units. The basis is written in physical
(x, y): x^2 + y^2 is l_e^2 xi^2 + h^2 eta^2, so the derived shape functions depend on the
aspect ratio h / l_e.

An element may carry a pressure field (``pressure``: polynomials in x, y, one field per
element, discontinuous between elements). In a penalised formulation the penalty then
acts on the element-wise L2 projection of J - 1 onto that field instead of at every
point: the u-p mixed form with its pressure condensed per element
(:mod:`ancf.kinematics.section.pressure`), the remedy for volumetric locking.

An element may take components of C from fewer points along the beam (``assumed``:
an assumed strain, :mod:`ancf.kinematics.section.assumed`), the remedy for membrane
locking.

An element declares its kinematics (``kinematics``), a name in :data:`KINEMATICS`, which
:mod:`ancf.kinematics` fills: "continuum" (the default: shape functions spanning the
plane, F = I + grad u at every point) or "cable" (a centre line r(x) alone). The
kinematics checks the spec (:meth:`ancf.kinematics.Kinematics.check`) and owns what
follows from it: the model, the supports, the end face, what it admits
(:attr:`ElementSpec.family`). The registry of elements is :mod:`ancf.elements`.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, lru_cache
from typing import TYPE_CHECKING

import numpy as np

from contract.errors import UnknownName
from contract.registry import Registry
from .polynomial import Poly, parse

if TYPE_CHECKING:
    from ..kinematics.family import Kinematics

# kinematics name -> its :class:`ancf.kinematics.Kinematics` (filled by ancf.kinematics)
KINEMATICS: Registry = Registry("ancf.element.kinematics", "kinematics")

class _Kinds(dict):
    """Nodal coordinate kind -> (derivative order in x, in y), read from the name: "r",
    then "_" and the derivatives, x's before y's ("r_x", "r_yy", "r_xyy", ...).
    Physical value = dimensionless value / (l_e^dx h^dy), so the physical shape
    function is the dimensionless one times l_e^dx h^dy."""

    def __missing__(self, kind: str) -> tuple[int, int]:
        head, _, d = kind.partition("_")
        nx = len(d) - len(d.lstrip("x"))
        if head != "r" or not d or d != "x" * nx + "y" * (len(d) - nx):
            raise KeyError(kind)
        self[kind] = (nx, len(d) - nx)
        return self[kind]

    def __contains__(self, kind) -> bool:
        try:
            self[kind]
        except KeyError:
            return False
        return True


KINDS: dict[str, tuple[int, int]] = _Kinds({"r": (0, 0)})

# what an element's tags say (``ElementSpec.tags``): which studies take it is read from
# them (:func:`ancf.elements.select`), never from a list of names
TAGS = {
    "paper": "one of the paper's four elements: the studies that reproduce the paper take these alone",
    "locking": "an element that locks: drawn apart and kept out of the findings about the lock-free ones",
    "costly": "its runs take most of a sweep's time: a sweep that must stay quick leaves it to its reference study",
}

@dataclass(frozen=True)
class ElementSpec:
    name: str
    basis: tuple[str, ...]       # polynomials in physical (x, y), e.g. "x^2 + y^2"
    nodes: tuple[float, ...]     # node positions xi in [0, 1] on the centre line (eta = 0)
    kinds: tuple[str, ...]       # nodal coordinate kinds at every node
    reference: str = ""
    # the default elastic rule, chosen by the rank tests of ancf.checks.rank: entries
    # (penalised formulation?, smallest l_e / h, (points along x, across the thickness)),
    # the first that matches a scene wins; empty: the rule exact for the basis (safe, dear)
    quadrature: tuple[tuple[bool, float, tuple[int, int]], ...] = ()
    # the element-wise pressure basis of the mixed form (penalised formulations); empty:
    # the penalty at every quadrature point
    pressure: tuple[str, ...] = ()
    # components of C ("xx", "yy", "xy") the elastic rule takes from ``assumed_points``
    # Gauss points along the beam instead of its own points (:mod:`ancf.kinematics.section.assumed`); empty:
    # C at the rule's points
    assumed: tuple[str, ...] = ()
    assumed_points: int = 3
    # a registered kinematics (:data:`KINEMATICS`): "continuum" (shape functions in x and y)
    # or "cable" (a centre line: basis and kinds in x only)
    kinematics: str = "continuum"
    # what it is, for the studies (:data:`TAGS`); untagged, an element takes part in every
    # study that runs its kinematics and formulations
    tags: tuple[str, ...] = ()

    def __post_init__(self):
        unknown = [k for k in self.kinds if k not in KINDS]
        if unknown:
            raise ValueError(f"element {self.name}: unknown kinds {unknown}; a kind is 'r' or 'r_' and "
                             "its derivatives, x's before y's ('r_x', 'r_yy', 'r_xyy')")
        if not (self.nodes[0] == 0.0 and self.nodes[-1] == 1.0 and list(self.nodes) == sorted(self.nodes)):
            raise ValueError(f"element {self.name}: nodes must rise from 0 to 1, got {self.nodes}")
        if len(self.basis) != len(self.nodes) * len(self.kinds):
            raise ValueError(f"element {self.name}: {len(self.basis)} basis functions but "
                             f"{len(self.nodes)} nodes x {len(self.kinds)} kinds")
        odd = [t for t in self.tags if t not in TAGS]
        if odd:
            raise ValueError(f"element {self.name}: unknown tags {odd}; tags are {sorted(TAGS)}")
        try:
            family = KINEMATICS.lookup(self.kinematics)
        except UnknownName as e:
            raise ValueError(f"element {self.name}: {e}") from None
        family.check(self)                       # what its kinematics asks of it

    @cached_property
    def polys(self) -> tuple[Poly, ...]:
        return tuple(parse(b) for b in self.basis)

    @cached_property
    def pressure_polys(self) -> tuple[Poly, ...]:
        return tuple(parse(b) for b in self.pressure)

    def pressure_tabulate(self, xi, eta, length: float, height: float) -> np.ndarray:
        """The pressure basis at points (xi, eta), (npts, n_pressure), in the coordinates
        of the displacement basis (the projection depends only on the span)."""
        xi, eta = np.ravel(xi), np.ravel(eta)
        return np.stack([p.scaled(length, height)(xi, eta) for p in self.pressure_polys], axis=-1)

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

    @property
    def family(self) -> Kinematics:
        """The kinematics this element declares (:data:`KINEMATICS`): its model, supports, end
        face, admissible formulations and integrators, its checks' data."""
        return KINEMATICS.lookup(self.kinematics)

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

    def tabulate_derivative(self, xi, eta, length: float, height: float, dx: int, dy: int = 0) -> np.ndarray:
        """The physical shape functions' derivative d^(dx + dy) N / dx^dx dy^dy at points
        (xi, eta), (npts, n_shape) in 1/m^(dx + dy) (:meth:`tabulate` has the first ones;
        a cable's curvature needs N_xx)."""
        xi, eta = np.ravel(xi), np.ravel(eta)
        polys, C = self.dimensionless(float(length), float(height))
        scale = np.array([length ** KINDS[k][0] * height ** KINDS[k][1]
                          for _ in self.nodes for k in self.kinds])
        B = np.stack([p(xi, eta, dx, dy) for p in polys], axis=-1) / (length ** dx * height ** dy)
        return (B @ C) * scale

    def reference_coordinates(self, x_node: float) -> np.ndarray:
        """Nodal coordinates (n_kinds, 2) of a straight, unstressed beam at node x."""
        ref = {"r": (x_node, 0.0), "r_x": (1.0, 0.0), "r_y": (0.0, 1.0)}
        return np.array([ref.get(k, (0.0, 0.0)) for k in self.kinds])


# From l_e / h = 15 a rule exact along the beam misses a finite-strain stretch family (both
# directions, quartic along through the rule's points; seen/true about 5 / (l_e / h)): the
# elements that have it declare one more point along (two for the quintic one) from there.
SLENDER = 15.0


def rules(*entries: tuple[float, tuple[int, int]],
          penalised: tuple[tuple[float, tuple[int, int]], ...] | None = None
          ) -> tuple[tuple[bool, float, tuple[int, int]], ...]:
    """An element's default rules (:attr:`ElementSpec.quadrature`) from entries (smallest
    l_e / h, (points along, across)), most slender first, for plane stress and, unless
    ``penalised`` gives others, the same for the penalised formulations."""
    return (tuple((False, s, r) for s, r in entries)
            + tuple((True, s, r) for s, r in (entries if penalised is None else penalised)))
