"""A straight beam of spatial elements: its strain energy, internal force and tangent.

The beam lies along x from 0 to ``length``, its section ``height`` (y) by ``width`` (z)
centred on the axis, cut into ``elements`` elements that share their end nodes (a
three-node element's middle node is its own), equal ones or, with ``grading`` g, each g
times as long as the one before it from x = 0 (g > 1: finer towards the clamp at x = 0), and
with ``both_ends`` from both ends to the middle (fine at both, for two supports).
Its coordinates are q (n_global, 3), the nodal vectors of every node in turn (node-major,
kinds in the element's order); flattened, component i of vector m is entry 3 m + i. The
energy is the integral of :func:`.energy.stress`'s W over the reference volume by a Gauss
rule of ``points`` (along, across the height, across the width), a product rule on each
element; the force is its gradient, the tangent its Hessian, dense
(:meth:`SpatialBeam.tangent`) or in band storage (:meth:`SpatialBeam.tangent_banded`,
:class:`ancf.core.banded.Banded`: the coordinates are numbered along the beam, so an
element's couple only neighbouring nodes, and the band's LU is what the statics solve).
numpy over all elements at once, not the compiled loop; the tangent by sum factorisation when
the element's shape functions are products of an along and a section factor (:mod:`.product`).

An element with a pressure basis (``SpatialSpec.pressure``, p_k) takes the penalty on the
element-wise L2 projection of J - 1: alpha / 2 b^T M^-1 b with b_k = int p_k (J - 1) dV and
M = int p p^T dV (the law's isochoric part stays pointwise), the mixed u-p form with its
pressure alpha M^-1 b condensed per element.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Mapping

import numpy as np

from ...core.banded import Banded, BandedPattern
from . import product
from .energy import density, density_jet, invariant_derivatives, stress, stress_of
from .spec import SpatialSpec


def gauss_box(points: tuple[int, int, int]) -> tuple[np.ndarray, np.ndarray]:
    """Points (npts, 3) in xi in [0, 1], eta, zeta in [-1/2, 1/2] and weights summing to 1."""
    rules = [np.polynomial.legendre.leggauss(n) for n in points]
    xs = [(rules[0][0] + 1.0) / 2.0, rules[1][0] / 2.0, rules[2][0] / 2.0]
    ws = [r[1] / 2.0 for r in rules]
    X = np.stack(np.meshgrid(*xs, indexing="ij"), axis=-1).reshape(-1, 3)
    W = np.einsum("i,j,k->ijk", *ws).ravel()
    return X, W


def graded_lengths(n: int, grading: float, length: float, both_ends: bool = False) -> np.ndarray:
    """The lengths of n elements (or cells) over ``length``, each ``grading`` times the one before
    it from x = 0, or with ``both_ends`` from both ends to the middle (mirrored)."""
    if both_ends:
        half = grading ** np.arange((n + 1) // 2)
        r = np.concatenate([half, half[::-1][n % 2:]])
    else:
        r = grading ** np.arange(n)
    return length * r / r.sum()


@dataclass(frozen=True)
class SpatialBeam:
    spec: SpatialSpec
    length: float
    height: float
    width: float
    elements: int
    law: str
    constants: Mapping[str, float] = field(hash=False)
    alpha: float                        # the volumetric penalty, Pa
    points: tuple[int, int, int] | None = None      # the Gauss rule; None: the element's default_rule
    grading: float = 1.0                # each element this times as long as the one before it
    both_ends: bool = False             # the grading from both ends to the middle (mirrored)

    def __post_init__(self):
        if self.points is None:
            object.__setattr__(self, "points", self.spec.default_rule())
        if not self.grading > 0.0:
            raise ValueError(f"grading: a ratio of element lengths above 0, got {self.grading!r}")

    @cached_property
    def lengths(self) -> np.ndarray:
        """The elements' lengths from x = 0 (m)."""
        return graded_lengths(self.elements, self.grading, self.length, self.both_ends)

    @property
    def le(self) -> float:
        """The element length of a beam of equal elements."""
        if self.grading != 1.0 and len(set(self.lengths)) > 1:
            raise ValueError("le: a graded beam's elements differ; see lengths")
        return self.length / self.elements

    @property
    def nodes(self) -> int:
        """Nodes of the whole beam."""
        return self.elements * (len(self.spec.nodes) - 1) + 1

    @property
    def n_global(self) -> int:
        return self.nodes * len(self.spec.kinds)

    @property
    def dof(self) -> int:
        return 3 * self.n_global

    @cached_property
    def _tables(self) -> dict:
        """(N, dN, weights) at the rule's points of an element of each length."""
        X, w = gauss_box(self.points)
        out = {}
        for le in dict.fromkeys(self.lengths):
            N, dN = self.spec.tabulate(X[:, 0], X[:, 1], X[:, 2], le, self.height, self.width)
            out[le] = (N, dN, w * le * self.height * self.width)
        return out

    def table(self, e: int):
        """(N (npts, n), dN (npts, n, 3), weights (npts,)) of element ``e``."""
        return self._tables[self.lengths[e]]

    @cached_property
    def _pressures(self) -> dict | None:
        if not self.spec.pressure:
            return None
        X, _ = gauss_box(self.points)
        out = {}
        for le, (_, _, w) in self._tables.items():
            p = self.spec.pressure_tabulate(X[:, 0], X[:, 1], X[:, 2], le, self.height, self.width)
            out[le] = p, np.linalg.inv(np.einsum("q,qk,ql->kl", w, p, p))
        return out

    def _pressure(self, e: int):
        """(p at the points (npts, n_p), M^-1) of element ``e``'s pressure basis, or None."""
        return None if self._pressures is None else self._pressures[self.lengths[e]]

    @property
    def _pointwise_alpha(self) -> float:
        return 0.0 if self.spec.pressure else self.alpha

    def element_rows(self, e: int) -> np.ndarray:
        """Global shape-function indices of element ``e``'s local ones."""
        k = len(self.spec.kinds)
        first = e * (len(self.spec.nodes) - 1)
        return np.array([(first + a) * k + b for a in range(len(self.spec.nodes)) for b in range(k)])

    def node_positions(self) -> np.ndarray:
        """x of every node of the beam."""
        ends = np.concatenate([[0.0], np.cumsum(self.lengths)])
        xs = [0.0]
        for e in range(self.elements):
            xs += [ends[e] + xi * self.lengths[e] for xi in self.spec.nodes[1:]]
        return np.array(xs)

    def reference(self) -> np.ndarray:
        """q (n_global, 3) of the straight unstressed beam."""
        return np.concatenate([self.spec.reference_coordinates(x) for x in self.node_positions()])

    def gradients(self, q: np.ndarray, e: int) -> np.ndarray:
        """F (npts, 3, 3) at element ``e``'s quadrature points."""
        _, dN, _ = self.table(e)
        return np.einsum("mi,pmJ->piJ", np.asarray(q).reshape(-1, 3)[self.element_rows(e)], dN)

    @cached_property
    def _stacked(self) -> dict:
        """Every element's tables at once: dN (E, npts, n, 3), w (E, npts), rows (E, n), wdN and,
        with a pressure basis, p (E, npts, n_p) and M^-1 (E, n_p, n_p)."""
        E = range(self.elements)
        out = {"dN": np.stack([self.table(e)[1] for e in E]), "w": np.stack([self.table(e)[2] for e in E]),
               "rows": np.stack([self.element_rows(e) for e in E])}
        # w dN_nL as (E, npts * 3 (p, L), n): the tangent's second factor
        out["wdN"] = (out["w"][:, :, None, None] * out["dN"]).transpose(0, 1, 3, 2).reshape(len(E), -1, out["dN"].shape[2])
        if self._pressures is not None:
            out["p"] = np.stack([self._pressure(e)[0] for e in E])
            out["Minv"] = np.stack([self._pressure(e)[1] for e in E])
        return out

    def _all_gradients(self, q: np.ndarray) -> np.ndarray:
        """F (E * npts, 3, 3) at every element's points, element-major."""
        st = self._stacked
        qe = np.asarray(q).reshape(-1, 3)[st["rows"]]                  # (E, n, 3)
        return np.matmul(np.swapaxes(qe, 1, 2)[:, None], st["dN"]).reshape(-1, 3, 3)

    def _assemble_vector(self, P: np.ndarray, dN: np.ndarray) -> np.ndarray:
        """sum over points of w P_iJ dN_mJ, assembled (dof,): P (E * npts, 3, 3) without w."""
        st = self._stacked
        E, npts, n, _ = dN.shape
        wP = (st["w"].reshape(-1)[:, None, None] * P).reshape(E, npts, 3, 3)
        fe = np.matmul(dN.transpose(0, 2, 1, 3).reshape(E, n, 3 * npts), wP.transpose(0, 1, 3, 2).reshape(E, 3 * npts, 3))
        f = np.zeros((self.n_global, 3))
        np.add.at(f, st["rows"], fe)
        return f.ravel()

    def _condensed(self, J: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """b_k = int p_k (J - 1) dV and the pressures lambda = alpha M^-1 b, each (E, n_p),
        from J (E * npts)."""
        st = self._stacked
        b = np.einsum("epk,ep->ek", st["p"], st["w"] * (J.reshape(st["w"].shape) - 1.0))
        return b, self.alpha * np.einsum("ekl,el->ek", st["Minv"], b)

    def _point_pressures(self, lam: np.ndarray) -> np.ndarray:
        """p . lambda_e at every point (E * npts)."""
        return np.einsum("epk,ek->ep", self._stacked["p"], lam).reshape(-1)

    def energy(self, q: np.ndarray) -> float:
        """The strain energy (J)."""
        F = self._all_gradients(q)
        total = self._stacked["w"].reshape(-1) @ density(self.law, self.constants, self._pointwise_alpha, F)
        if self._pressures is not None:
            b, lam = self._condensed(invariant_derivatives(F, 0)[0][2])
            total += 0.5 * np.sum(b * lam)
        return float(total)

    def force(self, q: np.ndarray) -> np.ndarray:
        """dE/dq (dof,), N."""
        F = self._all_gradients(q)
        _, P, _ = stress(self.law, self.constants, self._pointwise_alpha, F, tangent=False)
        if self._pressures is not None:
            inv, d, _ = invariant_derivatives(F, 1)
            P = P + self._point_pressures(self._condensed(inv[2])[1])[:, None, None] * d[2]
        return self._assemble_vector(P, self._stacked["dN"])

    def force_magnitude(self, q: np.ndarray) -> np.ndarray:
        """The internal force assembled from the magnitudes of its terms (dof,), N: per point
        sum_k |dW/dI_k| |dI_k/dF| (the chain rule's terms in the invariants I1, I2, J) plus the
        penalty's alpha (|J| + 1) |cof F| (its two terms alpha J cof F and alpha cof F, whose
        difference is the stress: its round-off is eps times this, whatever J - 1 is), against
        |dN| w. eps times its norm over the free dofs is the size of the force's round-off."""
        inv, d, _ = invariant_derivatives(self._all_gradients(q), 1)
        g = density_jet(self.law, self.constants, self._pointwise_alpha, *inv).gradient()
        Pm = np.einsum("ap,apiJ->piJ", np.abs(g), np.abs(d))
        Pm = Pm + self.alpha * (np.abs(inv[2]) + 1.0)[:, None, None] * np.abs(d[2])
        return self._assemble_vector(Pm, np.abs(self._stacked["dN"]))

    def element_dofs(self, e: int) -> np.ndarray:
        """Global dof indices of element ``e``'s local ones (3 m + i, m its local vectors)."""
        return (3 * self.element_rows(e)[:, None] + np.arange(3)[None, :]).ravel()

    @cached_property
    def _band(self) -> BandedPattern:
        dofs = np.stack([self.element_dofs(e) for e in range(self.elements)])
        return BandedPattern.of(dofs, self.dof, int((dofs.max(axis=1) - dofs.min(axis=1)).max()))

    def tangent(self, q: np.ndarray, pressure: np.ndarray | None = None) -> np.ndarray:
        """d2E/dq2 (dof, dof), N/m (``pressure``: see :meth:`element_tangents`)."""
        K = np.zeros((self.dof, self.dof))
        for e, Ke in enumerate(self.element_tangents(q, pressure)):
            d = self.element_dofs(e)
            K[np.ix_(d, d)] += Ke
        return K

    def tangent_banded(self, q: np.ndarray, pressure: np.ndarray | None = None) -> Banded:
        """d2E/dq2 in band storage (half-bandwidth: the largest dof distance inside an element)."""
        return self._band.assemble(self.element_tangents(q, pressure))

    def pressures(self, q: np.ndarray) -> np.ndarray | None:
        """The element pressures' coefficients lambda_e = alpha M^-1 b_e (elements, n_p) at q
        (the pressure at a point is p . lambda_e), or None without a pressure basis."""
        if self._pressures is None:
            return None
        return self._condensed(invariant_derivatives(self._all_gradients(q), 0)[0][2])[1]

    def linearised_pressures(self, q: np.ndarray, dq: np.ndarray) -> np.ndarray | None:
        """lambda_e(q) + dlambda_e/dq dq (elements, n_p): the pressures' linearisation in a step
        dq from q, the pressure unknowns' Newton update of the mixed (u, p) form condensed per
        element (:mod:`ancf.kinematics.spatial.statics`); None without a pressure basis."""
        if self._pressures is None:
            return None
        inv, d, _ = invariant_derivatives(self._all_gradients(q), 1)
        dF = self._all_gradients(dq)
        return self._condensed(inv[2] + np.einsum("piJ,piJ->p", d[2], dF))[1]

    @cached_property
    def _product(self) -> product.Factors | None:
        """The product split of the shape functions on the rule (:mod:`.product`), or None."""
        N = np.stack([self.table(e)[0] for e in range(self.elements)])
        return product.factors(N, self._stacked["dN"], self.points, self.lengths, self.height, self.width)

    def element_tangents(self, q: np.ndarray, pressure: np.ndarray | None = None, split: bool = True) -> np.ndarray:
        """Every element's block of d2E/dq2, (elements, nd, nd) over :meth:`element_dofs`. With
        ``pressure`` (elements, n_p), the pressure's geometric term (p . lambda_e) d2J/dF2 takes
        these coefficients instead of q's own (:meth:`pressures`): the condensed tangent of the
        mixed form at an iterate (q, lambda) off the constraint lambda = alpha M^-1 b(q). Per
        point the 9 x 9 A, then sum_p w dN_mJ A_iJkL dN_nL: by sum factorisation over the
        section and along the beam when the element's shape functions are products
        (:mod:`.product`; ``split`` False: never), otherwise for all elements at once as two
        batched products (J first, then p and L together)."""
        st = self._stacked
        dN, w = st["dN"], st["w"]
        E, npts, n, _ = dN.shape
        inv, d, dd = invariant_derivatives(self._all_gradients(q), 2)
        _, _, A = stress_of(self.law, self.constants, self._pointwise_alpha, inv, d, dd)
        if self._pressures is not None:
            at = self._point_pressures(self._condensed(inv[2])[1] if pressure is None else pressure)
            A = A + at[:, None, None, None, None] * dd[2]
        if split and self._product is not None:
            wA = (w.reshape(-1)[:, None, None, None, None] * A).reshape(E, self.points[0], -1, 3, 3, 3, 3)
            K = product.element_tangents(self._product, wA)
        else:
            # (E, p, J, i kL), then T_e,p,m,ikL = sum_J dN_mJ A_iJkL
            A = A.reshape(E, npts, 3, 3, 9).transpose(0, 1, 3, 2, 4).reshape(E, npts, 3, 27)
            T = np.matmul(dN, A).reshape(E, npts, n, 3, 3, 3).transpose(0, 2, 3, 4, 1, 5).reshape(E, 9 * n, 3 * npts)
            K = np.matmul(T, st["wdN"])                                                        # (E, m i k, n)
            K = K.reshape(E, n, 3, 3, n).transpose(0, 1, 2, 4, 3).reshape(E, 3 * n, 3 * n)
        if self._pressures is not None:
            # alpha G^T M^-1 G, G_k,mi = db_k / dq_mi = int p_k cof(F)_iJ dN_mJ
            Z = np.matmul(dN, np.swapaxes(d[2].reshape(E, npts, 3, 3), 2, 3))                  # (E, p, m, i)
            G = np.matmul(np.swapaxes(w[:, :, None] * st["p"], 1, 2), Z.reshape(E, npts, 3 * n))
            K += self.alpha * np.matmul(np.swapaxes(G, 1, 2), np.matmul(st["Minv"], G))
        return K
