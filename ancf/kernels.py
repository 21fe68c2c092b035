"""Compiled hot loops (numba), generic over elements and laws.

:func:`assemble_force_tangent` takes what the numpy side tabulates once (shape-function
gradients at the quadrature points, weights, element dofs, the band layout) and what it
evaluates per call (deformation gradients and the law's (a, J) derivatives from
:class:`ancf.jet.Jet`), and does the chain rule to P and A, the element integrals
B^T P and B^T A B and the scatter into the force vector and the band storage, in one
pass. A newly registered element or law goes through it without new code.

The chain rule from (a, J) to P and A has three twins: :meth:`ancf.material.Material.evaluate`
(numpy, the reference), :func:`assemble_force_tangent` (band storage, for the Python
solvers) and :func:`element_terms` (column storage, inside :func:`assemble_fused` of the
compiled steps and statics). tests/test_beam.py holds both compiled ones equal to the
reference to round-off for every element, law and formulation.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .tape import FASTMATH, tape_batch


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


# -- the fused step kernels of the compiled time loop (:mod:`ancf.compiled_steps`) ---------------
# Status codes of the compiled loop (the fused assembly returns OK or INADMISSIBLE).
OK, NEWTON_FAILED, SINGULAR, INADMISSIBLE, ENERGY_GROWTH, BUDGET = range(6)
#
# Column band storage. A symmetric matrix with half-bandwidth b is kept as its upper
# triangle, column by column: ``C[j, b + i - j] = S[i, j]`` for ``j - b <= i <= j``
# (shape (n, b + 1): LAPACK's upper band form transposed, so that one column of the band
# is contiguous in memory). ``first[j]`` (:func:`envelope`) is the first row of column
# j's nonzeros (the first dof of the elements holding dof j); the LDL^T factor has no
# fill above it, so the factorisation, solves and products skip the band's structural
# zeros (~25 % of the work for the node-block structure).


def live_tape(ops: np.ndarray, consts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The energy tape (:func:`ancf.tape.trace`) without the instructions its result does
    not depend on (a formulation's I2 where the law reads only I1, e.g. Yeoh: 3 of 16),
    operands renumbered; the result stays the last instruction. The replay computes the
    same numbers at fewer passes over the points."""
    n = ops.shape[0]
    live = np.zeros(n, bool)
    live[n - 1] = True
    for k in range(n - 1, -1, -1):
        if live[k]:
            for x in ops[k, 1:3]:
                if x >= 0:
                    live[x] = True
    index = np.cumsum(live) - 1
    kept = ops[live].copy()
    for col in (1, 2):
        kept[:, col] = np.where(kept[:, col] >= 0, index[np.maximum(kept[:, col], 0)], kept[:, col])
    return np.ascontiguousarray(kept), np.ascontiguousarray(consts[live])


@njit(cache=True)
def step_scratch(n_ops, dN, pr):
    """Work arrays of the element loop for chunks of about 192 points: (chunk, R (n_ops,
    6, m) tape jets, Fb (m, 4) deformation gradients, ab, Jb (m,) invariants, ew the
    element work of :func:`element_scratch`), m = chunk * nq; dN (nq, ns, 2) the shape
    gradients, pr the element pressure field (:func:`pressure_arrays`)."""
    nq = dN.shape[0]
    chunk = max(1, 192 // nq)
    m = chunk * nq
    return chunk, np.empty((n_ops, 6, m)), np.empty((m, 4)), np.empty(m), np.empty(m), element_scratch(dN, pr)


@njit(cache=True)
def element_scratch(dN, pr):
    """The work arrays of :func:`element_forces`, made once per loop rather than at every
    assembly: (fl (nd,), gk, pk (nk,), pf (nq,)). :func:`element_terms` (the tangent) and
    :func:`point_gradients` keep making theirs: made inside a kernel, the compiler knows
    they alias nothing (measured with theirs passed in as well: the 32 x HB2n-12 tangent
    33 -> 39 us; with point_gradients' ue passed in, the 32 x HB2n-12 pendulum 2 to 3 %
    slower, at the edge of the machine's noise)."""
    nq, ns = dN.shape[0], dN.shape[1]
    nd, nk = 2 * ns, pr[3].shape[1]
    return np.empty(nd), np.empty(nk), np.empty(nk), np.empty(nq)


@njit(cache=True, fastmath=FASTMATH)
def point_gradients(u, u_n, alpha_f, dN, dofs, e0, e1, Fb, ab, Jb):
    """F = I + grad ue, ue = (1 - alpha_f) u + alpha_f u_n, at the points of elements
    e0 .. e1 - 1 into Fb (F00, F01, F10, F11), a = F:F into ab, J = det F into Jb.
    Returns the number of points, or -1 if det F <= 0 (or is not finite) somewhere."""
    nd = dofs.shape[1]
    nq, ns = dN.shape[0], dN.shape[1]
    g = 1.0 - alpha_f
    ue = np.empty(nd)
    m = 0
    for e in range(e0, e1):
        for k in range(nd):                  # the element's ue, once for all its points
            d = dofs[e, k]
            ue[k] = g * u[d] + alpha_f * u_n[d]
        for q in range(nq):
            F00, F01, F10, F11 = 1.0, 0.0, 0.0, 1.0
            for s in range(ns):
                ux, uy = ue[2 * s], ue[2 * s + 1]
                g0, g1 = dN[q, s, 0], dN[q, s, 1]
                F00 += g0 * ux
                F01 += g1 * ux
                F10 += g0 * uy
                F11 += g1 * uy
            J = F00 * F11 - F01 * F10
            if not (J > 0.0 and J < 1e300):
                return -1
            Fb[m, 0], Fb[m, 1], Fb[m, 2], Fb[m, 3] = F00, F01, F10, F11
            ab[m] = F00 * F00 + F01 * F01 + F10 * F10 + F11 * F11
            Jb[m] = J
            m += 1
    return m


@njit(cache=True, fastmath=FASTMATH)
def assemble_fused(u, u_n, alpha_f, dN, w, dofs, ops, consts, pr, f, Kc, with_tangent, chunk, R, Fb, ab, Jb, ew):
    """Internal force at ue = (1 - alpha_f) u + alpha_f u_n into f (n,), and, if
    with_tangent, the upper half of the tangent into Kc (column band, (n, b + 1)).
    Per chunk of elements: F at all points, the tape over all of them, then per
    element P (and A = dP/dF), the element force and the upper half of the element
    tangent by 2 x 2 node blocks, and one scatter per element. pr: the element
    pressure field's arrays (:func:`pressure_arrays`; empty without one); chunk, R, Fb,
    ab, Jb, ew: :func:`step_scratch` for these dN and pr. Returns OK, or INADMISSIBLE if
    det F <= 0 (or is not finite) at a point."""
    ne = dofs.shape[0]
    f[:] = 0.0
    if with_tangent:
        Kc[:, :] = 0.0
    for e0 in range(0, ne, chunk):
        e1 = min(ne, e0 + chunk)
        m = point_gradients(u, u_n, alpha_f, dN, dofs, e0, e1, Fb, ab, Jb)
        if m < 0:
            return INADMISSIBLE
        tape_batch(ops, consts, ab, Jb, R, m, 2 if with_tangent else 1)
        if with_tangent:
            element_terms(Fb, R[ops.shape[0] - 1], Jb, e0, e1, dN, w, dofs, pr, f, Kc)
        else:
            element_forces(Fb, R[ops.shape[0] - 1], Jb, e0, e1, dN, w, dofs, pr, f, ew)
    return OK


def pressure_arrays(penalty, nq: int) -> tuple:
    """The element pressure field as the compiled kernels read it (``pr``): q (nq, nk)
    the pressure basis at the points, wq (nq, nk) the basis times the weights,
    pm (nk, nk) = alpha M^-1 and wl = wq L (nq, nk), pm = L L^T (Cholesky: the tangent's
    G^T pm G = (L^T G)^T (L^T G), L^T G = wl^T dJ/du), from a
    :class:`ancf.pressure.ProjectedPenalty`; with ``penalty`` None (no pressure field, or
    no penalty) nk = 0 and the kernels' pressure loops run zero times: one code path for
    every element."""
    if penalty is None:
        q, wq, pm, wl = np.zeros((nq, 0)), np.zeros((nq, 0)), np.zeros((0, 0)), np.zeros((nq, 0))
    else:
        q, wq, pm = penalty.q, penalty.wq, penalty.alpha * penalty.minv
        wl = wq @ np.linalg.cholesky(0.5 * (pm + pm.T))
    return tuple(np.ascontiguousarray(x, dtype=float) for x in (q, wq, pm, wl))


@njit(cache=True, fastmath=FASTMATH)
def element_pressures(pr, Jb, p0, nq, g, pk, out):
    """The element pressure at the element's points p0 .. p0 + nq - 1 into out (nq,), from
    the J there (Jb): g = wq^T (J - 1), its coefficients pk = alpha M^-1 g
    (:class:`ancf.pressure.ProjectedPenalty`). Returns the element's U_vol = g . pk / 2."""
    pq, pw, pm = pr[0], pr[1], pr[2]
    nk = pm.shape[0]
    for k in range(nk):
        g[k] = 0.0
    for q in range(nq):
        d = Jb[p0 + q] - 1.0
        for k in range(nk):
            g[k] += pw[q, k] * d
    U = 0.0
    for k in range(nk):
        s = 0.0
        for l in range(nk):
            s += pm[k, l] * g[l]
        pk[k] = s
        U += 0.5 * s * g[k]
    for q in range(nq):
        s = 0.0
        for k in range(nk):
            s += pq[q, k] * pk[k]
        out[q] = s
    return U


@njit(cache=True, fastmath=FASTMATH, inline="always")
def _piola(wq, Wa, WJ, F00, F01, F10, F11):
    """w P at a point, P = 2 W_a F + W_J cof F (F = [[F00, F01], [F10, F11]]), as (P00,
    P01, P10, P11): the one copy of the stress for the force and the tangent."""
    return (wq * (2.0 * Wa * F00 + WJ * F11), wq * (2.0 * Wa * F01 - WJ * F10),
            wq * (2.0 * Wa * F10 - WJ * F01), wq * (2.0 * Wa * F11 + WJ * F00))


@njit(cache=True, fastmath=FASTMATH)
def element_forces(Fb, W, Jb, e0, e1, dN, w, dofs, pr, f, ew):
    """Add the force of elements e0 .. e1 - 1 to f: :func:`element_terms` without the
    tangent (the same arithmetic, tested equal), on the work arrays ew of
    :func:`element_scratch` (for these dN and pr). Measured on 2 x HB2n-20xyp: 2.5 ->
    1.8 us, the arrays element_terms makes at each call being most of the difference."""
    nd = dofs.shape[1]
    nq, ns = dN.shape[0], dN.shape[1]
    fl, gk, pk, pf = ew
    nk = pr[3].shape[1]
    if fl.shape[0] != nd or gk.shape[0] != nk or pf.shape[0] != nq:
        raise ValueError("element_forces: work arrays made for another element or pressure field")
    if nk == 0:
        pf[:] = 0.0
    p = 0
    for e in range(e0, e1):
        fl[:] = 0.0
        if nk > 0:
            element_pressures(pr, Jb, p, nq, gk, pk, pf)
        for q in range(nq):
            F00, F01, F10, F11 = Fb[p, 0], Fb[p, 1], Fb[p, 2], Fb[p, 3]
            P0, P1, P2, P3 = _piola(w[q], W[1, p], W[2, p] + pf[q], F00, F01, F10, F11)
            for s in range(ns):
                g0, g1 = dN[q, s, 0], dN[q, s, 1]
                fl[2 * s] += g0 * P0 + g1 * P1
                fl[2 * s + 1] += g0 * P2 + g1 * P3
            p += 1
        for i in range(nd):
            f[dofs[e, i]] += fl[i]


@njit(cache=True, fastmath=FASTMATH)
def element_terms(Fb, W, Jb, e0, e1, dN, w, dofs, pr, f, Kc):
    """Add the force and the upper half of the tangent of elements e0 .. e1 - 1 to f and
    Kc (the force alone: :func:`element_forces`), from F at their points (Fb, in
    :func:`point_gradients`' order) and the energy's (a, J) derivatives there,
    W (6, m) = (W, W_a, W_J, W_aa, W_aJ, W_JJ).

    A node block's four entries are contiguous (Kb[s, s2, 2i + k]) and the loops over
    them read only scalars hoisted out of the arrays, so the compiler packs each block
    update into one vector operation; an element whose dofs are contiguous and
    ascending (the mesh's numbering) is scattered without index arrays or branches.
    Together: the 32 x HB2n-16 tangent 65 -> 46 us (force 17 us).

    The element pressure field pr (:func:`pressure_arrays`, nk functions; nothing to do
    if nk = 0), :class:`ancf.pressure.ProjectedPenalty` compiled: its force
    G^T p = sum_q w_q p(x_q) cof F_q : dF/du is the pointwise W_J term with W_J + p(x_q),
    so the pressure at the points is added to W_J in P, that from the J in Jb (the
    discrete gradient passes the mean of the two states' J there: the pressure of the
    mean g, exactly the projected penalty's discrete gradient); its tangent
    G^T alpha M^-1 G + sum_q w_q p(x_q) B^T d2J/dF2 B adds the pressure of det F_q to
    W_J in the d cof/dF term of A (and Jb = det Fb outside the discrete gradient: the
    same pressure) and the element's rank-nk matrix G^T alpha M^-1 G = Gl^T Gl,
    Gl = L^T G = sum_q wl_q^T cof F_q : dF_q/du (alpha M^-1 = L L^T), accumulated at the
    points, four entries at a time (the tangent of 640 x HB2n-40p, 30 points, 6 pressure
    functions: 6.7 ms without the field, 9.4 ms with it; with G and alpha M^-1 G by plain
    loops, which the compiler did not vectorise, 12.3 ms)."""
    nd = dofs.shape[1]
    nq, ns = dN.shape[0], dN.shape[1]
    b = Kc.shape[1] - 1
    fl = np.empty(nd)
    Kb = np.empty((ns, ns, 4))   # node blocks s <= s2: Kb[s, s2, 2i + k] = K_(2s+i, 2s2+k)
    Tv = np.empty((ns, 2, 4))    # Tv[s, l, 2i + k] = sum_j dN_s,j A_(2i+j, 2k+l)
    Av = np.empty((2, 2, 4))     # Av[j, l, 2i + k] = A_(2i+j, 2k+l)
    A = np.empty((4, 4))
    Fv = np.empty(4)
    cof = np.empty(4)
    wl = pr[3]
    nk = wl.shape[1]
    gk, pk = np.empty(nk), np.empty(nk)
    pf = np.zeros(nq)            # the pressure at the points: in P (from Jb) ...
    pt = np.zeros(nq)            # ... and in the tangent (from det Fb)
    Jt = np.empty(nq)
    dj = np.empty(nd)            # dJ/du_e at a point
    Gl = np.empty((nk, nd))      # L^T dg/du_e
    tail = nd - nd % 4
    p = 0
    for e in range(e0, e1):
        fl[:] = 0.0
        Kb[:, :, :] = 0.0
        if nk > 0:
            element_pressures(pr, Jb, p, nq, gk, pk, pf)
            for q in range(nq):
                Jt[q] = Fb[p + q, 0] * Fb[p + q, 3] - Fb[p + q, 1] * Fb[p + q, 2]
            element_pressures(pr, Jt, 0, nq, gk, pk, pt)
            Gl[:, :] = 0.0
        for q in range(nq):
            F00, F01, F10, F11 = Fb[p, 0], Fb[p, 1], Fb[p, 2], Fb[p, 3]
            Wa, wq = W[1, p], w[q]
            P0, P1, P2, P3 = _piola(wq, Wa, W[2, p] + pf[q], F00, F01, F10, F11)     # f_(s, i) += w dN_s,j P_ij
            for s in range(ns):
                g0, g1 = dN[q, s, 0], dN[q, s, 1]
                fl[2 * s] += g0 * P0 + g1 * P1
                fl[2 * s + 1] += g0 * P2 + g1 * P3
            # A = 4 W_aa F F + 2 W_aJ (F cof + cof F) + W_JJ cof cof + 2 W_a I + W_J dcof/dF
            Waa, WaJ, WJJ = W[3, p], W[4, p], W[5, p]
            Fv[0], Fv[1], Fv[2], Fv[3] = F00, F01, F10, F11
            cof[0], cof[1], cof[2], cof[3] = F11, -F10, -F01, F00
            for i in range(4):
                fi, ci = Fv[i], cof[i]
                for k in range(i, 4):
                    fk, ck = Fv[k], cof[k]
                    v = wq * (4.0 * Waa * fi * fk + 2.0 * WaJ * (fi * ck + ci * fk) + WJJ * ci * ck)
                    A[i, k] = v
                    A[k, i] = v
                A[i, i] += wq * 2.0 * Wa
            WJt = W[2, p] + pt[q]
            A[0, 3] += wq * WJt
            A[3, 0] += wq * WJt
            A[1, 2] -= wq * WJt
            A[2, 1] -= wq * WJt
            if nk > 0:
                # dJ/du_(s, i) = cof F : dF/du_(s, i) = sum_j cof_ij dN_s,j at this point,
                # Gl += wl_q^T dJ/du (four entries at a time: one vector operation)
                for s in range(ns):
                    g0, g1 = dN[q, s, 0], dN[q, s, 1]
                    dj[2 * s] = F11 * g0 - F10 * g1
                    dj[2 * s + 1] = F00 * g1 - F01 * g0
                for k in range(nk):
                    c = wl[q, k]
                    Gk = Gl[k]
                    for j in range(0, tail, 4):
                        d0, d1, d2, d3 = dj[j], dj[j + 1], dj[j + 2], dj[j + 3]
                        Gk[j] += c * d0
                        Gk[j + 1] += c * d1
                        Gk[j + 2] += c * d2
                        Gk[j + 3] += c * d3
                    for j in range(tail, nd):
                        Gk[j] += c * dj[j]
            for j in range(2):
                for l in range(2):
                    Av[j, l, 0] = A[j, l]
                    Av[j, l, 1] = A[j, 2 + l]
                    Av[j, l, 2] = A[2 + j, l]
                    Av[j, l, 3] = A[2 + j, 2 + l]
            for l in range(2):
                p0, p1, p2, p3 = Av[0, l, 0], Av[0, l, 1], Av[0, l, 2], Av[0, l, 3]
                r0, r1, r2, r3 = Av[1, l, 0], Av[1, l, 1], Av[1, l, 2], Av[1, l, 3]
                for s in range(ns):
                    g0, g1 = dN[q, s, 0], dN[q, s, 1]
                    Tv[s, l, 0] = g0 * p0 + g1 * r0
                    Tv[s, l, 1] = g0 * p1 + g1 * r1
                    Tv[s, l, 2] = g0 * p2 + g1 * r2
                    Tv[s, l, 3] = g0 * p3 + g1 * r3
            for s in range(ns):
                x0, x1, x2, x3 = Tv[s, 0, 0], Tv[s, 0, 1], Tv[s, 0, 2], Tv[s, 0, 3]
                y0, y1, y2, y3 = Tv[s, 1, 0], Tv[s, 1, 1], Tv[s, 1, 2], Tv[s, 1, 3]
                for s2 in range(s, ns):
                    h0, h1 = dN[q, s2, 0], dN[q, s2, 1]
                    Kb[s, s2, 0] += x0 * h0 + y0 * h1
                    Kb[s, s2, 1] += x1 * h0 + y1 * h1
                    Kb[s, s2, 2] += x2 * h0 + y2 * h1
                    Kb[s, s2, 3] += x3 * h0 + y3 * h1
            p += 1
        if nk > 0:
            # the pressure's rank-nk part G^T pm G = Gl^T Gl, into the upper node blocks
            for s in range(ns):
                for k in range(nk):
                    x0, x1 = Gl[k, 2 * s], Gl[k, 2 * s + 1]
                    for s2 in range(s, ns):
                        h0, h1 = Gl[k, 2 * s2], Gl[k, 2 * s2 + 1]
                        Kb[s, s2, 0] += x0 * h0
                        Kb[s, s2, 1] += x0 * h1
                        Kb[s, s2, 2] += x1 * h0
                        Kb[s, s2, 3] += x1 * h1
        for i in range(nd):
            f[dofs[e, i]] += fl[i]
        # upper half into the column band (the lower entry of a diagonal block is skipped)
        g = dofs[e, 0]
        contiguous = True
        for k in range(1, nd):
            contiguous = contiguous and dofs[e, k] == g + k
        if contiguous:
            for s in range(ns):
                # diagonal block: (2s, 2s), (2s, 2s + 1), (2s + 1, 2s + 1)
                c = g + 2 * s
                Kc[c, b] += Kb[s, s, 0]
                Kc[c + 1, b - 1] += Kb[s, s, 1]
                Kc[c + 1, b] += Kb[s, s, 3]
                for s2 in range(s + 1, ns):
                    c = g + 2 * s2
                    o = b + 2 * (s - s2)
                    Kc[c, o] += Kb[s, s2, 0]
                    Kc[c, o + 1] += Kb[s, s2, 2]
                    Kc[c + 1, o - 1] += Kb[s, s2, 1]
                    Kc[c + 1, o] += Kb[s, s2, 3]
        else:
            for s in range(ns):
                for i in range(2):
                    r = dofs[e, 2 * s + i]
                    for s2 in range(s, ns):
                        for k in range(i if s2 == s else 0, 2):
                            c = dofs[e, 2 * s2 + k]
                            v = Kb[s, s2, 2 * i + k]
                            if r <= c:
                                Kc[c, b + r - c] += v
                            else:
                                Kc[r, b + c - r] += v



@njit(cache=True)
def strain_energy_fused(u, dN, w, dofs, ops, consts, pr, chunk, R, Fb, ab, Jb, ew):
    """U = sum_e sum_q w_q W(F_eq) (J), plus the element pressure field's
    alpha/2 g^T M^-1 g per element (pr, :func:`pressure_arrays`); nan if det F <= 0
    somewhere. chunk .. ew: :func:`step_scratch` (the pressures work in ew's gk, pk, pf)."""
    ne = dofs.shape[0]
    last = ops.shape[0] - 1
    nk = pr[2].shape[0]
    nq = dN.shape[0]
    g, pk, pq = ew[1], ew[2], ew[3]
    total = 0.0
    for e0 in range(0, ne, chunk):
        e1 = min(ne, e0 + chunk)
        m = point_gradients(u, u, 0.0, dN, dofs, e0, e1, Fb, ab, Jb)
        if m < 0:
            return np.nan
        tape_batch(ops, consts, ab, Jb, R, m, 0)
        for p in range(m):
            total += w[p % nq] * R[last, 0, p]
        if nk > 0:
            for p0 in range(0, m, nq):
                total += element_pressures(pr, Jb, p0, nq, g, pk, pq)
    return total


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


