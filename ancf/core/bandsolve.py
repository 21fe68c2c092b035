"""Compiled band linear algebra (numba), beside the compiled element loops of
:mod:`ancf.kinematics.section.kernels`:

- LAPACK's general and upper band forms (the Python solvers, :mod:`ancf.core.banded`):
  :func:`band_matvec`, :func:`band_ldlt_inertia` (Sylvester's inertia count);
- column band storage (the compiled step and static loops): products, constraints, the
  LDL^T factorisation without pivoting and its solve, and the envelope they start from.

Column band storage. A symmetric matrix with half-bandwidth b is kept as its upper
triangle, column by column: ``C[j, b + i - j] = S[i, j]`` for ``j - b <= i <= j``
(shape (n, b + 1): LAPACK's upper band form transposed, so that one column of the band
is contiguous in memory). ``first[j]`` (:func:`envelope`) is the first row of column
j's nonzeros (the first dof of the elements holding dof j); the LDL^T factor has no
fill above it, so the factorisation, solves and products skip the band's structural
zeros (~25 % of the work for the node-block structure).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .tape import FASTMATH


@njit(cache=True)
def band_matvec(ab, b, x):
    """y = K x for K in general band storage ab[b + i - j, j]."""
    n = x.shape[0]
    y = np.zeros(n)
    for j in range(n):
        xj = x[j]
        lo = max(0, j - b)
        hi = min(n, j + b + 1)
        for i in range(lo, hi):
            y[i] += ab[b + i - j, j] * xj
    return y


@njit(cache=True)
def band_ldlt_inertia(upper, b, shift):
    """Inertia of A - shift I for symmetric A in LAPACK's upper band form
    ``upper[b + i - j, j] = A[i, j]`` (i <= j), by an LDL^T factorisation without
    pivoting (a band stays a band): A - shift I = L D L^T, so by Sylvester's law of
    inertia the number of negative pivots d_j is the number of eigenvalues below shift.
    Returns (negative pivots, smallest |pivot|, growth); a zero pivot stops the count
    there (smallest |pivot| 0: the count is not to be trusted, the caller must decide).
    growth = max_j sum_k L_jk^2 |d_k| (L_jj = 1), the diagonal of |L| |D| |L|^T, which
    bounds the factorisation's backward error (c eps growth): it equals the diagonal of
    A - shift I (1 here) when no pivot cancels, and grows when a tiny pivot makes the
    factors large."""
    n = upper.shape[1]
    L = np.zeros((b + 1, n))       # L[k, j] = L[j + k, j], k = 1..b
    d = np.zeros(n)
    neg = 0
    small = np.inf
    growth = 0.0
    for j in range(n):
        lo = max(0, j - b)
        dj = upper[b, j] - shift
        gj = 0.0
        for k in range(lo, j):
            ljk = L[j - k, k]
            dj -= ljk * ljk * d[k]
            gj += ljk * ljk * abs(d[k])
        d[j] = dj
        a = abs(dj)
        gj += a
        if gj > growth:
            growth = gj
        if a < small:
            small = a
        if dj == 0.0:
            return neg, 0.0, np.inf
        if dj < 0.0:
            neg += 1
        for i in range(j + 1, min(n, j + b + 1)):
            s = upper[b + j - i, i]            # A[j, i], j < i
            for k in range(max(0, i - b), j):
                s -= L[i - k, k] * L[j - k, k] * d[k]
            L[i - j, j] = s / dj
    return neg, small, growth


@njit(cache=True, fastmath=FASTMATH)
def col_matvec(C, first, x, y):
    """y = S x, S symmetric in column band storage C (n, b + 1), envelope first."""
    n, b1 = C.shape
    b = b1 - 1
    for j in range(n):
        y[j] = 0.0
    for j in range(n):
        xj = x[j]
        acc = C[j, b] * xj
        for i in range(first[j], j):
            v = C[j, b + i - j]
            y[i] += v * xj
            acc += v * x[i]
        y[j] += acc


@njit(cache=True, fastmath=FASTMATH)
def col_matvec_split(C, first, x, y):
    """:func:`col_matvec` for a matrix that couples only dofs of the same component
    (a mass matrix M = M_s (x) I_2 in the node order (a, i) -> 2 a + i: its entries between
    an x and a y dof are zero, :func:`same_component_only`): the same products without
    those zeros, half the work. Column j's loop starts at the first row of j's parity at
    or after first[j]."""
    n, b1 = C.shape
    b = b1 - 1
    for j in range(n):
        y[j] = 0.0
    for j in range(n):
        xj = x[j]
        acc = C[j, b] * xj
        i0 = first[j] + ((j - first[j]) & 1)
        for i in range(i0, j, 2):
            v = C[j, b + i - j]
            y[i] += v * xj
            acc += v * x[i]
        y[j] += acc


def same_component_only(C: np.ndarray) -> bool:
    """Are all entries of the column band C between dofs of different parity zero (a
    mass matrix M_s (x) I_2, :func:`col_matvec_split`)?"""
    b = C.shape[1] - 1
    return not np.any(C[:, b - 1::-2])


@njit(cache=True)
def col_constrain(C, fixed):
    """Rows and columns of the fixed dofs replaced by those of the identity."""
    n, b1 = C.shape
    b = b1 - 1
    for k in fixed:
        for r in range(b + 1):
            C[k, r] = 0.0                         # column k above the diagonal
        for j in range(k + 1, min(n, k + b + 1)):
            C[j, b + k - j] = 0.0                 # row k right of the diagonal
        C[k, b] = 1.0


@njit(cache=True, fastmath=FASTMATH)
def col_ldlt(C, first, wk):
    """In place: C (column band, upper) <- the factors of S = U^T D U, U unit upper
    triangular (its strict upper part overwrites S's) and 1 / D on the diagonal.
    Left-looking by columns, no pivoting, so the band is kept; column j is processed
    from row first[j] (its envelope: no fill above it) and the inner products run over
    contiguous memory. wk (2, n) is work space. Returns the number of negative pivots
    (the number of negative eigenvalues of S, by Sylvester's law of inertia), or
    -(j + 1) if the pivot of column j is (near) zero, |D_j| <= 1e-12 |S_jj|, or not
    finite: S is singular to working precision.

    Two columns that start on the same row (columns of one node) are taken together:
    their entries are independent inner products over the same rows of U, computed in
    one pass as two chains, where one column's single chain waits on each product's
    latency (32 x HB2n-12: 11 -> 8 us, 32 x HB2n-16: 22 -> 15 us). Every inner product
    keeps its order: the factors are the one-column loop's to the bit.

    Why not Cholesky: S = (1 - alpha_f) K + c M is symmetric but need not be positive
    definite at a Newton iterate. In the stiff case (plane strain, penalty 1e5 C10,
    Newmark, 8 elements) the predictor's S has an eigenvalue -1.3e-2 against a largest
    2e8 (the converged states' S are positive definite): the current code's LU takes
    it, and a Cholesky that rejected such steps made 988 rejections where the current
    loop makes none. LDL^T takes it too, at the cost of a Cholesky (a little less: no
    square roots)."""
    n, b1 = C.shape
    b = b1 - 1
    w, w2 = wk[0], wk[1]
    negative = 0
    j = 0
    while j < n:
        i0 = first[j]
        cj = C[j]
        oj = b - j
        if j + 1 < n and first[j + 1] == i0:
            # columns j and j + 1: rows i0 .. j - 1 of both in one pass
            ck = C[j + 1]
            ok = oj - 1
            for i in range(i0, j):
                ci = C[i]
                oi = b - i
                s = cj[oj + i]
                t = ck[ok + i]
                for k in range(max(i0, first[i]), i):
                    c = ci[oi + k]
                    s -= c * w[k]
                    t -= c * w2[k]
                w[i] = s                              # D_i U_ij
                w2[i] = t
                cj[oj + i] = s * ci[b]                # U_ij; ci[b] holds 1 / D_i
                ck[ok + i] = t * ci[b]
            # the pivot of column j, and row j of column j + 1 (the same rows i0 .. j - 1)
            d = cj[b]
            s = d
            t = ck[ok + j]
            for k in range(i0, j):
                c = cj[oj + k]
                s -= c * w[k]
                t -= c * w2[k]
            if not (abs(s) > 1e-12 * abs(d) and abs(s) < 1e300):
                return -(j + 1)
            if s < 0.0:
                negative += 1
            cj[b] = 1.0 / s
            w2[j] = t
            ck[ok + j] = t * cj[b]
            # the pivot of column j + 1
            d = ck[b]
            s = d
            for k in range(i0, j + 1):
                s -= ck[ok + k] * w2[k]
            if not (abs(s) > 1e-12 * abs(d) and abs(s) < 1e300):
                return -(j + 2)
            if s < 0.0:
                negative += 1
            ck[b] = 1.0 / s
            j += 2
            continue
        for i in range(i0, j):
            ci = C[i]
            oi = b - i
            s = cj[oj + i]
            for k in range(max(i0, first[i]), i):
                s -= ci[oi + k] * w[k]
            w[i] = s
            cj[oj + i] = s * ci[b]
        d = cj[b]
        s = d
        for k in range(i0, j):
            s -= cj[oj + k] * w[k]
        if not (abs(s) > 1e-12 * abs(d) and abs(s) < 1e300):
            return -(j + 1)
        if s < 0.0:
            negative += 1
        cj[b] = 1.0 / s
        j += 1
    return negative


@njit(cache=True, fastmath=FASTMATH)
def col_ldlt_solve(C, first, x):
    """In place: x <- S^-1 x with C the factors from :func:`ldlt`."""
    n, b1 = C.shape
    b = b1 - 1
    for j in range(n):                          # U^T z = x (unit)
        cj = C[j]
        s = x[j]
        for k in range(first[j], j):
            s -= cj[b + k - j] * x[k]
        x[j] = s
    for j in range(n):                          # y = D^-1 z
        x[j] *= C[j, b]
    for j in range(n - 1, -1, -1):              # U x = y (unit), column-oriented
        cj = C[j]
        xj = x[j]
        for k in range(first[j], j):
            x[k] -= cj[b + k - j] * xj


def envelope(dofs: np.ndarray, n: int) -> np.ndarray:
    """first[j]: the smallest dof coupled to dof j by an element (>= j - b): the first
    row of column j's nonzeros. Band LDL^T has no fill above it, so the loops start
    there (the node-block structure: ~8 of b = 11 rows for HB2n-12, 11 of 15 for HB2n-16)."""
    first = np.arange(n, dtype=np.int64)
    for d in dofs:
        np.minimum.at(first, d, d.min())
    return first
