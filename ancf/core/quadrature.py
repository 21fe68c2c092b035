"""Gauss-Legendre rules on the element rectangle xi in [0, 1], eta in [-1/2, 1/2]."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Rule:
    xi: np.ndarray      # (nq,)
    eta: np.ndarray     # (nq,)
    weight: np.ndarray  # (nq,), sums to 1 (the dimensionless area)


def gauss(n_x: int, n_y: int) -> Rule:
    """Tensor rule exact for degree 2 n_x - 1 in xi and 2 n_y - 1 in eta."""
    px, wx = np.polynomial.legendre.leggauss(n_x)
    py, wy = np.polynomial.legendre.leggauss(n_y)
    X, Y = np.meshgrid((px + 1) / 2, py / 2, indexing="ij")
    W = np.outer(wx / 2, wy / 2)
    return Rule(X.ravel(), Y.ravel(), W.ravel())


def exact_for(degree_x: int, degree_y: int) -> Rule:
    """The smallest tensor rule that integrates polynomials of these degrees exactly."""
    return gauss(degree_x // 2 + 1, degree_y // 2 + 1)
