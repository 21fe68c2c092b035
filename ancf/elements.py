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

(a kind is "r" and its derivatives, :data:`KINDS`); scenes can then name it.

An element may carry a pressure field (``pressure``: polynomials in x, y, one field per
element, discontinuous between elements). In a penalised formulation the penalty then
acts on the element-wise L2 projection of J - 1 onto that field instead of at every
point: the u-p mixed form with its pressure condensed per element
(:mod:`ancf.pressure`), the remedy for volumetric locking.

An element may take components of C from fewer points along the beam (``assumed``:
an assumed strain, :mod:`ancf.assumed`), the remedy for membrane locking.

An element declares its kinematics (``kinematics``, :data:`KINEMATICS`): "continuum"
(the default: its shape functions span the plane, F = I + grad u at every point, the
elements above) or "cable" (a centre line r(x) alone, basis and kinds in x only: the
section is no field but is integrated, fibre by fibre, from the centre line's stretch and
curvature, :mod:`ancf.cable`). The model, the supports, the end face and the contract
checks read it; the compiled loops see it only as data (:mod:`ancf.element_kernels`).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np

from contract.registry import Registry
from .polynomial import Poly, parse

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

# An element's kinematics -> what it is (``ElementSpec.kinematics``).
KINEMATICS = {
    "continuum": "continuum-based: shape functions in (x, y), F = I + grad u at points of the section",
    "cable": "cable: a centre line in x alone (Euler-Bernoulli); the section integrated fibre by fibre "
             "from its stretch and curvature with the law's uniaxial energy (plane stress only)",
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
    # the element-wise pressure basis of the mixed form (penalised formulations); empty:
    # the penalty at every quadrature point
    pressure: tuple[str, ...] = ()
    # components of C ("xx", "yy", "xy") the elastic rule takes from ``assumed_points``
    # Gauss points along the beam instead of its own points (:mod:`ancf.assumed`); empty:
    # C at the rule's points
    assumed: tuple[str, ...] = ()
    assumed_points: int = 3
    # :data:`KINEMATICS`: "continuum" (shape functions in x and y) or "cable" (a centre line:
    # basis and kinds in x only, the section integrated by the rule's points across it)
    kinematics: str = "continuum"

    def __post_init__(self):
        if self.kinematics not in KINEMATICS:
            raise ValueError(f"element {self.name}: kinematics {self.kinematics!r}; allowed: "
                             f"{', '.join(KINEMATICS)}")
        if self.kinematics == "cable":
            ybasis = [b for b in self.basis if "y" in b]
            ykinds = [k for k in self.kinds if k in KINDS and KINDS[k][1] > 0]
            if ybasis or ykinds or self.pressure or self.assumed:
                raise ValueError(f"element {self.name}: a cable's basis and kinds are in x alone, with no pressure "
                                 f"field or assumed strain; got basis in y {ybasis}, kinds in y {ykinds}, "
                                 f"pressure {list(self.pressure)}, assumed {list(self.assumed)}")
        from .assumed import COMPONENTS
        bad = [c for c in self.assumed if c not in COMPONENTS]
        if bad or len(set(self.assumed)) != len(self.assumed) or self.assumed_points < 1:
            raise ValueError(f"element {self.name}: assumed {list(self.assumed)} with {self.assumed_points} points; "
                             f"assumed components are distinct ones of {', '.join(COMPONENTS)}, points >= 1")
        unknown = [k for k in self.kinds if k not in KINDS]
        if unknown:
            raise ValueError(f"element {self.name}: unknown kinds {unknown}; a kind is 'r' or 'r_' and "
                             "its derivatives, x's before y's ('r_x', 'r_yy', 'r_xyy')")
        if not (self.nodes[0] == 0.0 and self.nodes[-1] == 1.0 and list(self.nodes) == sorted(self.nodes)):
            raise ValueError(f"element {self.name}: nodes must rise from 0 to 1, got {self.nodes}")
        if len(self.basis) != len(self.nodes) * len(self.kinds):
            raise ValueError(f"element {self.name}: {len(self.basis)} basis functions but "
                             f"{len(self.nodes)} nodes x {len(self.kinds)} kinds")

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
    def cable(self) -> bool:
        """A centre-line element (``kinematics = "cable"``)?"""
        return self.kinematics == "cable"

    @property
    def formulations(self) -> tuple[str, ...] | None:
        """The formulations the element can run (None: every one). A cable integrates the
        law's incompressible uniaxial energy, with free lateral faces: plane stress alone."""
        return ("plane-stress",) if self.cable else None

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

    def cable_gradients(self, xi, eta, length: float, height: float) -> np.ndarray:
        """A cable's point data (npts, n_shape, 2): N_s'(x) and y N_s''(x) at (xi, eta), y =
        eta h, so that r_x = sum_s [..., 0] q_s and y r_xx = sum_s [..., 1] q_s take the places
        of F's two columns (:mod:`ancf.cable`)."""
        _, d1 = self.tabulate(xi, eta, length, height)
        d2 = self.tabulate_derivative(xi, eta, length, height, 2)
        return np.ascontiguousarray(np.stack([d1[..., 0], (np.ravel(eta) * height)[:, None] * d2], axis=-1))

    def reference_coordinates(self, x_node: float) -> np.ndarray:
        """Nodal coordinates (n_kinds, 2) of a straight, unstressed beam at node x."""
        ref = {"r": (x_node, 0.0), "r_x": (1.0, 0.0), "r_y": (0.0, 1.0)}
        return np.array([ref.get(k, (0.0, 0.0)) for k in self.kinds])


# (ELEMENTS.origin: element name -> the module that registered it, what a fresh process
# imports to have it)
ELEMENTS: Registry[ElementSpec] = Registry("ancf.element", "element")


def register_element(spec: ElementSpec) -> ElementSpec:
    import sys

    spec.dimensionless(1.0, 1.0)  # fail at registration, not at first use
    return ELEMENTS.register(spec.name, spec, sys._getframe(1).f_globals.get("__name__", "__main__"))


def get_element(name: str) -> ElementSpec:
    return ELEMENTS.lookup(name)


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


register_element(ElementSpec(
    "LB2n-12", ("1", "x", "y", "x*y", "x^2", "x^3"), (0.0, 1.0), ("r", "r_x", "r_y"),
    "Omar & Shabana 2001 (linear across the thickness)",
    rules((0.0, (3, 2)))))
register_element(ElementSpec(
    "HB2n-12", ("1", "x", "y", "x*y", "x^2 + y^2", "x^3"), (0.0, 1.0), ("r", "r_x", "r_y"),
    "Zhao et al. 2021", rules((0.3, (3, 2)), (0.0, (3, 3)), penalised=((0.1, (3, 2)), (0.0, (3, 3))))))
register_element(ElementSpec(
    "HB3n-12", ("1", "x", "y", "x*y", "x^2 + y^2", "x^2*y"), (0.0, 0.5, 1.0), ("r", "r_y"),
    "Zhao et al. 2021", rules((0.1, (3, 2)), (0.0, (3, 3)))))
register_element(ElementSpec(
    "HB2n-16", ("1", "x", "y", "x*y", "x^2", "y^2", "x*y^2", "x^3"), (0.0, 1.0),
    ("r", "r_x", "r_y", "r_yy"), "Patel & Shabana 2018",
    rules((0.3, (3, 2)), (0.0, (3, 3)))))
# Found with the harness (issue 20; README "An element for incompressible rubber"): HB2n-16
# made cubic along the beam in every cross-section mode and quartic across it (kinds r, r_y,
# ..., r_yyyy and their x-slopes: 10 kinds, 40 dof), with an element pressure linear in x and
# quadratic in y that carries the penalty (ancf.pressure). Pressure spaces measured (paper's
# cantilever, Yeoh, plane strain at the paper's penalty against the penalised continuum, 32 /
# 64 / 160 / 320 / 640 elements): {1, x} x {1, y, y^2}: 0.018 / 0.034 / 0.0095 / 0.0024 /
# 0.0014 %; x {1, ..., y^3}: 0.010 / 0.015 / 0.022 / 0.038 / 0.042 % (locks as l_e / h
# falls); {1, x, y, xy}: 0.021 / 0.038 / 0.014 / 0.0069 / 0.0059 %; with x^2 in the pressure
# it locks (0.69 % at 32, penalty 1e4 C10); {1} or {1, x}: 57 % too soft (J - 1 free to vary
# across the section). The rules: [4, 5] is the exact rule of the basis and the cheapest
# without spurious modes; the finite-strain test wants [5, 5] below l_e / h = 1 (seen/true
# 0.18 at 0.3 with [4, 5], 0.47 with [5, 5] down to 0.1) and [5, 6] below 0.1 (0.40 at 0.05;
# every rule tried falls under 0.3 at l_e / h <= 0.025). Slender elements, l_e / h >= 15:
# [5, 5]. There the test finds a stretch of both directions that varies along the element
# like a quartic through the 4 points along, seen/true about 5 / (l_e / h) under [4, 5]
# (0.33 at 15, 0.28 at 17.5, 0.15 at 35); [5, 5] sees it (0.55-0.57 from 15 to 70). The same
# family and the same 15 for every element with a rule exact along (HB2n-20xyp, HB2n-60p).
register_element(ElementSpec(
    "HB2n-40p", tuple(f"x^{i}*y^{j}" for j in range(5) for i in range(4)), (0.0, 1.0),
    ("r", "r_x", "r_y", "r_xy", "r_yy", "r_xyy", "r_yyy", "r_xyyy", "r_yyyy", "r_xyyyy"),
    "this harness: cubic Hermite along, quartic across, element pressure {1, x} x {1, y, y^2}",
    rules((SLENDER, (5, 5)), (1.0, (4, 5)), (0.1, (5, 5)), (0.0, (5, 6))),
    pressure=("1", "x", "y", "x*y", "y^2", "x*y^2")))
# Found with the harness (issue 20): HB2n-40p made quintic along the beam (Hermite: r, r_x,
# r_xx in every cross-section mode r, r_y, ..., r_yyyy: 15 kinds, 60 dof), quartic across,
# with an element pressure two degrees below the displacement in each direction, {1, x, x^2,
# x^3} x {1, y, y^2}. Measured on the paper's cantilever (face clamp, gravity, default rules)
# against the converged continuum: plane stress at 32 elements NH 0.028 / MR 0.017 / Yeoh
# 0.022 % (HB2n-40p: 0.087 / 0.054 / 0.069 %); exactly incompressible plane strain, penalty
# 1e4 C10, NH 0.21 / 0.027 / 0.014 % at 16 / 32 / 64. Pressure spaces: with HB2n-40p's
# {1, x} x {1, y, y^2} it stalls at 0.136 % (Yeoh, penalised plane strain, 16 and 32
# elements), with {1, x, x^2} x {1, y, y^2} at 0.068 %; {1, ..., x^4} x {1, y, y^2}: 0.42 /
# 0.11 / 0.016 %. The rules, from the rank tests: [6, 5] (exact for the basis) for
# l_e / h >= 1 (seen/true 0.39 at 1; [5, 5] fails there with 0.22, [6, 5] at 0.3 with 0.29),
# [6, 6] down to 0.05 (0.41; 0.21 at 0.025), [6, 7] below (>= 0.57 down to 0.01); [8, 5] from
# l_e / h = 15 (HB2n-40p's slender family: [6, 5] 0.33 at 15, 0.15 at 35; [7, 5] 0.21 at
# 35; [8, 5] 0.66 from 15 to 70).
register_element(ElementSpec(
    "HB2n-60p", tuple(f"x^{i}*y^{j}" for j in range(5) for i in range(6)), (0.0, 1.0),
    tuple(f"r{'_' if (a or b) else ''}{'x' * a}{'y' * b}" for b in range(5) for a in range(3)),
    "this harness: quintic Hermite along, quartic across, element pressure {1, .., x^3} x {1, y, y^2}",
    rules((SLENDER, (8, 5)), (1.0, (6, 5)), (0.05, (6, 6)), (0.0, (6, 7))),
    pressure=tuple(f"x^{i}*y^{j}" for j in range(3) for i in range(4))))
# Found with the harness (issue 20): the cheap lock-free element, HB2n-16 with the mixed slope
# r_xy (so the cross-section field r_y is cubic along the beam like the centre line; HB2n-16's
# linear r_y makes a coarse mesh too stiff in bending: 8 elements, pendulum tip 2.0 % of L
# off) and an element pressure {1, y} that carries the penalty. Without the pressure (the
# example HB2n-20xy, examples/cubic_slope.py) it locks in penalised plane strain, 27 % at 64
# elements; bending makes J - 1 linear across the section, so the pressure needs y ({1} or
# {1, x}: 56 % too soft), and every richer space stiffens it ({1, x} x {1, y}: 1.9 % at 32;
# any y^2: 26-29 %, locked). Measured (paper's cantilever, face clamp, gravity, default rule,
# Yeoh, penalty 1e4 C10 against the exactly incompressible continuum): 1.69 / 0.69 / 0.43 /
# 0.21 % at 16 / 32 / 64 / 160 elements; from k = 1e4 to 1e5 its tip moves 0.008-0.017 %,
# the continuum's own 1/k term. Order about 1 (the face clamp fixes r_yy, linear along an
# element) to its quadratic section's plateau (plane stress 0.09 %, plane strain 0.13-0.17 %),
# so it meets no static target of the issue; on the slender pendulum it is the cheapest at
# 0.1 % (8 elements, dt 2.5 ms: 0.033 %; README "At equal accuracy"). In plane stress the
# pressure carries nothing and it is HB2n-20xy to the bit. The rules, from the rank tests:
# [4, 2] for l_e / h >= 1 (mu_min 0.37 at 1; [3, 2] fails at 10), [3, 3] below ([4, 2] fails
# at 0.5); both resolve the pressure's {1, y} (the exact rule is [4, 3]); [5, 2] from l_e / h
# = 15 (HB2n-40p's slender family: [4, 2] 0.36 at 15, 0.16 at 35; [5, 2] 0.87-0.89 from 15
# to 140; the slender pendulum hardly feels the rule, tests/test_example_along_rule.py).
register_element(ElementSpec(
    "HB2n-20xyp", ("1", "x", "x^2", "x^3", "y", "x*y", "x^2*y", "x^3*y", "y^2", "x*y^2"), (0.0, 1.0),
    ("r", "r_x", "r_y", "r_xy", "r_yy"),
    "this harness: HB2n-16 with r_xy (cubic r_y along the beam), element pressure {1, y}",
    rules((SLENDER, (5, 2)), (1.0, (4, 2)), (0.0, (3, 3))),
    pressure=("1", "y")))
# Found with the harness (issue 20): HB2n-20xyp with an assumed membrane stretch, C_xx taken
# from 3 Gauss points along the beam at each row across and carried to the rule's points by
# quadratic Lagrange (ancf.assumed). A cubic centre line in large rotation cannot keep its
# stretch at 1 at 4 points of an element and bends too stiffly (membrane locking); in small
# strain eps_xx is quadratic along x, so the 3 points see it exactly and the stiffness at
# u = 0 (the rank tests) is HB2n-20xyp's. Measured in the numpy prototype
# (experiments/assumed_membrane.py) under [4, 2], slender pendulum, dt 2.5 ms: 2 / 4 elements 5.23
# / 0.447 % of L (HB2n-20xyp 7.25 / 1.18 %); with C_xy assumed as well 2.57 / 0.442 %, which changes
# the stiffness at u = 0 (not taken). The rules are HB2n-20xyp's ([4, 2] 0.31 at 15, 0.14
# at 35; [5, 2] 0.32-0.43 from 15 to 140: its 3 samples of C_xx bound what more points see).
register_element(ElementSpec(
    "HB2n-20xypm", ("1", "x", "x^2", "x^3", "y", "x*y", "x^2*y", "x^3*y", "y^2", "x*y^2"), (0.0, 1.0),
    ("r", "r_x", "r_y", "r_xy", "r_yy"),
    "this harness: HB2n-20xyp with an assumed membrane stretch C_xx (3 points along)",
    rules((SLENDER, (5, 2)), (1.0, (4, 2)), (0.0, (3, 3))),
    pressure=("1", "y"), assumed=("xx",)))

# Found with the harness (issue: the cheapest element at every accuracy): the planar ANCF
# cable (r and r_x at two nodes, cubic Hermite along: Gerstmayr & Irschik 2008's centre
# line, Exudyn's ObjectANCFCable2D's dofs) whose section integrates the law's exact
# incompressible uniaxial energy fibre by fibre (ancf.cable), instead of a linear
# EA eps^2 / 2 + EI kappa^2 / 2. H: its section law is the hyperelastic one (beside the
# linear cable of the peers' runs); C: a cable (centre line only, Euler-Bernoulli, no
# section coordinates, so the B of the continuum-based elements' names does not fit);
# 2n, 8: two nodes, 8 dof. Its rule: points along x points across the section. Along: the
# small strain u_x' (quadratic) needs 3 points ([2, .]: one spurious mode; [3, 1] two, the
# bending unseen at y = 0); [3, 2] and up are exact at u = 0 (mu_min 1). Across: the section's
# energy int W_u(s - y kappa) dy by Gauss, against 64 points at kappa h = 0.1 / 0.3 / 0.5
# (neo-Hookean; Yeoh and Mooney-Rivlin alike): 2 points 8.9e-4 / 7.9e-3 / 2.1e-2 of M, as large
# as the section model's own error 0.225 (kappa h)^2 (tests/test_cable.py); 3 points 8.6e-7 /
# 6.8e-5 / 5.0e-4, under 1 % of it to kappa h = 0.3, 2 % at 0.5: [3, 3]. The finite-strain
# test finds, with 3 or 4 points along, the membrane stretch between the points unseen at slender elements
# (seen/true 0.33 / 0.19 / 0.09 at l_e / h = 10 / 17.5 / 35; [5, 3] 0.93); seeing it is the
# cubic cable's membrane locking: on the paper's cantilever (NH, plane stress) [3, 3] is off the
# continuum by 4.7 / 0.39 / 0.044 / 0.033 % at 2 / 4 / 8 / 32 elements, [5, 3] by 6.1 / 0.79 /
# 0.055 / 0.033 %; on the pendulum (Yeoh) 2.4 / 0.46 / 0.081 % at 2 / 4 / 8 elements against 6.7 /
# 0.90 / 0.091 %, no unstable equilibrium either way: [3, 3] at every l_e / h.
register_element(ElementSpec(
    "HC2n-8", ("1", "x", "x^2", "x^3"), (0.0, 1.0), ("r", "r_x"),
    "this harness: ANCF cable (cubic Hermite centre line), section integrated with the law's incompressible "
    "uniaxial energy", rules((0.0, (3, 3))), kinematics="cable"))

# the elements of this package; any other was registered by a user's module
BUILTIN = ELEMENTS.freeze_builtin()
