"""Polynomials in two variables.

A :class:`Poly` is a mapping {(i, j): coefficient} for sum c x^i y^j; a basis function
of an element may be a sum of monomials (x^2 + y^2 is one basis function). Element
bases are written in the physical coordinates (x, y) and evaluated in the dimensionless
ones (xi = x / l_e, eta = y / h) through :meth:`Poly.scaled`.
"""
from __future__ import annotations

from dataclasses import dataclass
from math import factorial

import numpy as np


@dataclass(frozen=True)
class Poly:
    terms: tuple[tuple[tuple[int, int], float], ...]

    @staticmethod
    def of(terms: dict[tuple[int, int], float]) -> "Poly":
        return Poly(tuple(sorted(terms.items())))

    def __call__(self, xi, eta, dxi: int = 0, deta: int = 0) -> np.ndarray:
        """Value of d^dxi/dxi d^deta/deta of the polynomial at the points (xi, eta)."""
        xi, eta = np.broadcast_arrays(np.asarray(xi, float), np.asarray(eta, float))
        out = np.zeros(xi.shape)
        for (i, j), c in self.terms:
            if i < dxi or j < deta:
                continue
            k = c * factorial(i) / factorial(i - dxi) * factorial(j) / factorial(j - deta)
            out = out + k * xi ** (i - dxi) * eta ** (j - deta)
        return out

    def scaled(self, sx: float, sy: float) -> "Poly":
        """The same function in stretched coordinates: x = sx xi, y = sy eta, normalised
        so that its largest coefficient has magnitude 1 (a basis function's scale is
        irrelevant to the space it spans)."""
        terms = {(i, j): c * sx ** i * sy ** j for (i, j), c in self.terms}
        big = max(abs(c) for c in terms.values())
        return Poly.of({k: c / big for k, c in terms.items()})

    def degree(self) -> tuple[int, int]:
        """Highest power of xi and of eta."""
        return max(i for (i, _), _ in self.terms), max(j for (_, j), _ in self.terms)


def parse(expr: str) -> Poly:
    """'1', 'x', 'x*y', 'x^2 + y^2', 'x*y^2', '2*x^3' as a polynomial in (x, y)."""
    terms: dict[tuple[int, int], float] = {}
    for mono in expr.replace("-", "+-").split("+"):
        mono = mono.strip()
        if not mono:
            continue
        coef, i, j = 1.0, 0, 0
        if mono.startswith("-"):
            coef, mono = -1.0, mono[1:]
        for factor in mono.replace(" ", "").split("*"):
            base, _, power = factor.partition("^")
            p = int(power) if power else 1
            if base == "x":
                i += p
            elif base == "y":
                j += p
            else:
                coef *= float(base)
        terms[(i, j)] = terms.get((i, j), 0.0) + coef
    return Poly.of(terms)
