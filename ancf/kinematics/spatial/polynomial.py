"""Polynomials in three variables, the spatial counterpart of :mod:`ancf.core.polynomial`.

A :class:`Poly3` is {(i, j, k): coefficient} for sum c x^i y^j z^k; a basis function may be
a sum of monomials. Written in physical (x, y, z), evaluated in the dimensionless
(xi, eta, zeta) = (x / l_e, y / h, z / w) through :meth:`Poly3.scaled`.
"""
from __future__ import annotations

from dataclasses import dataclass
from math import factorial

import numpy as np


@dataclass(frozen=True)
class Poly3:
    terms: tuple[tuple[tuple[int, int, int], float], ...]

    @staticmethod
    def of(terms: dict[tuple[int, int, int], float]) -> "Poly3":
        return Poly3(tuple(sorted((k, c) for k, c in terms.items() if c != 0.0)))

    def __call__(self, xi, eta, zeta, d: tuple[int, int, int] = (0, 0, 0)) -> np.ndarray:
        """The derivative d^(d0 + d1 + d2) / dxi^d0 deta^d1 dzeta^d2 at the points."""
        xi, eta, zeta = np.broadcast_arrays(*(np.asarray(v, float) for v in (xi, eta, zeta)))
        out = np.zeros(xi.shape)
        for powers, c in self.terms:
            if any(p < q for p, q in zip(powers, d)):
                continue
            k = c
            for p, q in zip(powers, d):
                k *= factorial(p) / factorial(p - q)
            out = out + k * xi ** (powers[0] - d[0]) * eta ** (powers[1] - d[1]) * zeta ** (powers[2] - d[2])
        return out

    def scaled(self, sx: float, sy: float, sz: float) -> "Poly3":
        """The same function in stretched coordinates (x = sx xi, ...), its largest
        coefficient normalised to magnitude 1 (a basis function's scale does not change the
        space it spans)."""
        terms = {(i, j, k): c * sx ** i * sy ** j * sz ** k for (i, j, k), c in self.terms}
        big = max(abs(c) for c in terms.values())
        return Poly3.of({p: c / big for p, c in terms.items()})

    def degree(self) -> tuple[int, int, int]:
        """Highest power of each variable."""
        return tuple(max(p[a] for p, _ in self.terms) for a in range(3))


def parse3(expr: str) -> Poly3:
    """'1', 'x', 'x*y', 'x^2*z', 'y^2 + z^2', '2*x^3' as a polynomial in (x, y, z)."""
    terms: dict[tuple[int, int, int], float] = {}
    for mono in expr.replace("-", "+-").split("+"):
        mono = mono.strip()
        if not mono:
            continue
        coef, powers = 1.0, [0, 0, 0]
        if mono.startswith("-"):
            coef, mono = -1.0, mono[1:]
        for factor in mono.replace(" ", "").split("*"):
            base, _, power = factor.partition("^")
            p = int(power) if power else 1
            if base in ("x", "y", "z"):
                powers["xyz".index(base)] += p
            else:
                coef *= float(base)
        key = tuple(powers)
        terms[key] = terms.get(key, 0.0) + coef
    return Poly3.of(terms)
