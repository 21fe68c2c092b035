"""Banded symmetric matrices: assembly from element blocks, solve, stability check.

Global dofs are numbered along the beam, so every tangent and mass matrix here is
banded with half-bandwidth b (the largest dof distance inside one element). Storage is
LAPACK's general band form ``ab[b + i - j, j] = K[i, j]``; its upper b + 1 rows are the
upper form that the banded Cholesky factorisation takes.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.linalg import cho_solve_banded, cholesky_banded
from scipy.linalg.lapack import dgbsv as _gbsv
from scipy.sparse import dia_matrix


@dataclass(frozen=True)
class BandedPattern:
    """Where each entry of each element block lands in the band storage."""

    n: int
    b: int
    index: np.ndarray  # (n_elements, nd, nd) flat indices into ab

    @staticmethod
    def of(element_dofs: np.ndarray, n: int, b: int) -> "BandedPattern":
        d = element_dofs.reshape(element_dofs.shape[0], -1)
        r, c = d[:, :, None], d[:, None, :]
        return BandedPattern(n, b, (b + r - c) * n + c)

    def assemble(self, blocks: np.ndarray) -> "Banded":
        ab = np.bincount(self.index.ravel(), weights=blocks.ravel(),
                         minlength=(2 * self.b + 1) * self.n)
        return Banded(ab.reshape(2 * self.b + 1, self.n), self.b)


@dataclass
class Banded:
    ab: np.ndarray  # (2 b + 1, n)
    b: int

    @property
    def n(self) -> int:
        return self.ab.shape[1]

    def constrain(self, fixed: np.ndarray) -> "Banded":
        """Rows and columns of fixed dofs replaced by those of the identity (in place)."""
        self.ab.flat[_constrained_entries(self.b, self.n, fixed.tobytes())] = 0.0
        self.ab[self.b, fixed] = 1.0
        return self

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """K^-1 rhs = s (S^-1 (s rhs)) with S = D^-1/2 K D^-1/2, s = D^-1/2 (the scaling of
        :meth:`scaled_upper`), by LAPACK's banded LU (gbsv) of S; LinAlgError if K is
        singular. Why the scaling: partial pivoting picks pivots by size, so its backward
        error is relative to the largest entries; a section of degree 6 has generalized
        masses ~1e-50 of a position dof's, whose unknowns an unscaled LU loses entirely
        (HB2n-84p: M a0 = r solved with a Jacobi-scaled residual 8e5 times r)."""
        b, n = self.b, self.n
        s = self.jacobi_scale()
        lu = np.empty((3 * b + 1, n), order="F")
        np.multiply(self.ab, _scaling(s, b), out=lu[b:])
        _, _, x, info = _gbsv(b, b, lu, s * rhs, overwrite_ab=True, overwrite_b=True)
        if info > 0:
            raise np.linalg.LinAlgError("singular matrix")
        if info < 0:
            raise ValueError(f"gbsv: illegal argument {-info}")
        return s * x

    def jacobi_scale(self) -> np.ndarray:
        """s = D^-1/2, D = |diag K| with a zero diagonal entry counted as the smallest
        nonzero one."""
        d = np.abs(self.ab[self.b])
        floor = d[d > 0].min() if np.any(d > 0) else 1.0
        return 1.0 / np.sqrt(np.maximum(d, floor))

    def scaled_upper(self) -> tuple[np.ndarray, np.ndarray]:
        """The upper band (b + 1, n) of S = D^-1/2 K D^-1/2 with D = |diag K| (a zero
        diagonal entry counts as the smallest nonzero one), and s = D^-1/2. A congruence
        with a positive diagonal: S has K's inertia, and the spread between position and
        gradient dofs, which would make a factorisation fail on round-off alone, is gone."""
        s = self.jacobi_scale()
        return self.ab[: self.b + 1] * _scaling(s, self.b)[: self.b + 1], s

    def scaled_norm(self) -> float:
        """||S||_inf, a bound of |lambda| of S: S + sigma I is positive definite for
        any sigma above it."""
        upper, _ = self.scaled_upper()
        rows = np.zeros(self.n)
        for k in range(self.b + 1):
            off = self.b - k
            a = np.abs(upper[k, off:])
            rows[off:] += a                   # entry (j - off, j) in row j ...
            if off:
                rows[: self.n - off] += a     # ... and, by symmetry, in row j - off
        return float(rows.max())

    def scaled_cholesky(self, shift: float = 0.0):
        """Banded Cholesky factor of S + shift I (:meth:`scaled_upper`) and s, or
        (None, None) if that is not positive definite."""
        upper, s = self.scaled_upper()
        upper[self.b] += shift
        try:
            return cholesky_banded(upper, lower=False, check_finite=False), s
        except np.linalg.LinAlgError:
            return None, None

    def scaled_inertia(self, shift: float = 0.0) -> tuple[int, float, float]:
        """(how many eigenvalues of S = D^-1/2 K D^-1/2 lie below ``shift``, smallest
        |pivot|, growth of the factors) by a banded LDL^T of S - shift I (Sylvester's law
        of inertia; :func:`ancf.core.bandsolve.band_ldlt_inertia`). S is congruent to K, so at
        shift 0 the count is K's number of negative eigenvalues."""
        from .bandsolve import band_ldlt_inertia
        upper, _ = self.scaled_upper()
        neg, small, growth = band_ldlt_inertia(upper, self.b, float(shift))
        return int(neg), float(small), float(growth)

    def is_positive_definite(self, shift: float = 0.0) -> bool:
        """Is D^-1/2 K D^-1/2 + shift I positive definite? (shift < 0 asks for a margin)"""
        return self.scaled_cholesky(shift)[0] is not None

    def solve_shifted(self, rhs: np.ndarray, shift: float):
        """x = (K + shift D)^-1 rhs with D = |diag K|, if K + shift D is positive definite
        (else None): the step of a shifted (Levenberg-Marquardt) Newton method."""
        c, s = self.scaled_cholesky(shift)
        if c is None:
            return None
        return s * cho_solve_banded((c, False), s * rhs, check_finite=False)

    def to_sparse(self):
        offsets = np.arange(self.b, -self.b - 1, -1)
        return dia_matrix((self.ab, offsets), shape=(self.n, self.n)).tocsc()

    def matvec(self, x: np.ndarray) -> np.ndarray:
        from .bandsolve import band_matvec
        return band_matvec(self.ab, self.b, np.ascontiguousarray(x, dtype=float))


def _scaling(s: np.ndarray, b: int) -> np.ndarray:
    """(2 b + 1, n): s_i s_j at entry (i, j)'s place in the band storage, row k holding
    (j + k - b, j); rows outside the matrix take a neighbour's s (their entries are not
    read)."""
    n = s.shape[0]
    rows = np.clip(np.arange(n) + np.arange(-b, b + 1)[:, None], 0, n - 1)
    return s[rows] * s


@lru_cache(maxsize=64)
def _constrained_entries(b: int, n: int, fixed_bytes: bytes) -> np.ndarray:
    """Flat indices into ab (2 b + 1, n) of the entries in a fixed row or column."""
    fixed = np.frombuffer(fixed_bytes, dtype=int)
    idx = []
    for off in range(-b, b + 1):   # entries (i, j) with i - j = off, stored at column j
        j = np.concatenate([fixed, fixed - off])
        j = j[(j >= 0) & (j < n)]
        idx.append((b + off) * n + j)
    return np.unique(np.concatenate(idx))
