"""Compiled hot loops (numba), generic over elements and laws.

:func:`assemble_force_tangent` takes what the numpy side tabulates once (shape-function
gradients at the quadrature points, weights, element dofs, the band layout) and what it
evaluates per call (deformation gradients and the law's (a, J) derivatives from
:class:`ancf.jet.Jet`), and does the chain rule to P and A, the element integrals
B^T P and B^T A B and the scatter into the force vector and the band storage, in one
pass. A newly registered element or law goes through it without new code; the numpy
implementation in :mod:`ancf.model` is the reference it is tested against.
"""
from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def assemble_force_tangent(F, WD, dN, w, dofs, b, n, with_tangent):
    """F (ne, nq, 4), WD (6, ne, nq) = W and its partials (a, J, aa, aJ, JJ) in the
    invariants a = F:F and J = det F, dN (nq, ns, 2) in 1/m, w (nq) weights times element
    volume, dofs (ne, 2 ns) global dofs in the local order (a, i) -> 2 a + i.
    Returns f (n,) and ab (2 b + 1, n) (zeros if not with_tangent)."""
    ne, nq = F.shape[0], F.shape[1]
    ns = dN.shape[1]
    f = np.zeros(n)
    ab = np.zeros((2 * b + 1, n)) if with_tangent else np.zeros((1, 1))
    A = np.empty((4, 4))
    T = np.empty((ns, 2, 4))
    P = np.empty(4)
    c = np.empty(4)
    for e in range(ne):
        for q in range(nq):
            F0, F1, F2, F3 = F[e, q, 0], F[e, q, 1], F[e, q, 2], F[e, q, 3]
            c[0], c[1], c[2], c[3] = F3, -F2, -F1, F0
            wa, wj = WD[1, e, q], WD[2, e, q]
            for m in range(4):
                P[m] = 2.0 * wa * F[e, q, m] + wj * c[m]
            wq = w[q]
            # f_(a, i) += w dN_a,j P_(i, j)
            for a in range(ns):
                for i in range(2):
                    f[dofs[e, 2 * a + i]] += wq * (dN[q, a, 0] * P[2 * i] + dN[q, a, 1] * P[2 * i + 1])
            if not with_tangent:
                continue
            waa, waj, wjj = WD[3, e, q], WD[4, e, q], WD[5, e, q]
            for m in range(4):
                fm = F[e, q, m]
                for k in range(4):
                    fk = F[e, q, k]
                    A[m, k] = (4.0 * waa * fm * fk + 2.0 * waj * (fm * c[k] + c[m] * fk)
                               + wjj * c[m] * c[k])
                A[m, m] += 2.0 * wa
            A[0, 3] += wj
            A[3, 0] += wj
            A[1, 2] -= wj
            A[2, 1] -= wj
            # K_(a i, b k) = w sum_l T_(a i, k l) dN_b,l,  T_(a i, k l) = sum_j dN_a,j A_(2i+j, 2k+l)
            for a in range(ns):
                for i in range(2):
                    for kl in range(4):
                        T[a, i, kl] = wq * (dN[q, a, 0] * A[2 * i, kl] + dN[q, a, 1] * A[2 * i + 1, kl])
            for a in range(ns):
                for i in range(2):
                    r = dofs[e, 2 * a + i]
                    for bb in range(ns):
                        d0, d1 = dN[q, bb, 0], dN[q, bb, 1]
                        for k in range(2):
                            col = dofs[e, 2 * bb + k]
                            ab[b + r - col, col] += T[a, i, 2 * k] * d0 + T[a, i, 2 * k + 1] * d1
    return f, ab


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
    Returns (negative pivots, smallest |pivot|); a zero pivot stops the count there
    (smallest |pivot| 0: the count is not to be trusted, the caller must decide)."""
    n = upper.shape[1]
    L = np.zeros((b + 1, n))       # L[k, j] = L[j + k, j], k = 1..b
    d = np.zeros(n)
    neg = 0
    small = np.inf
    for j in range(n):
        lo = max(0, j - b)
        dj = upper[b, j] - shift
        for k in range(lo, j):
            ljk = L[j - k, k]
            dj -= ljk * ljk * d[k]
        d[j] = dj
        a = abs(dj)
        if a < small:
            small = a
        if dj == 0.0:
            return neg, 0.0
        if dj < 0.0:
            neg += 1
        for i in range(j + 1, min(n, j + b + 1)):
            s = upper[b + j - i, i]            # A[j, i], j < i
            for k in range(max(0, i - b), j):
                s -= L[i - k, k] * L[j - k, k] * d[k]
            L[i - j, j] = s / dj
    return neg, small
