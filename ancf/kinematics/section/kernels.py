"""Compiled hot loops (numba), generic over elements and laws.

:func:`assemble_force_tangent` takes what the numpy side tabulates once (shape-function
gradients at the quadrature points, weights, element dofs, the band layout) and what it
evaluates per call (deformation gradients and the law's (a, J) derivatives from
:class:`ancf.core.jet.Jet`), and does the chain rule to P and A, the element integrals
B^T P and B^T A B and the scatter into the force vector and the band storage, in one
pass. A newly registered element or law goes through it without new code.

The chain rule from (a, J) to P and A has three twins: :meth:`ancf.core.material.Material.evaluate`
(numpy, the reference), :func:`assemble_force_tangent` (band storage, for the Python
solvers) and :func:`element_terms` (column storage, inside :func:`assemble_fused` of the
compiled steps and statics). tests/test_beam.py holds both compiled ones equal to the
reference to round-off for every element, law and formulation.

The band linear algebra these assemblies feed (products, LDL^T, its solve, the inertia
count) is :mod:`ancf.core.bandsolve`.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .assumed_kernels import assumed_invariants, assumed_terms
from .fields import element_pressures
from ...core.tape import FASTMATH, tape_batch


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


# -- the fused step kernels of the compiled time loop (:mod:`ancf.solvers.compiled_steps`) ---------------
# Status codes of the compiled loop (the fused assembly returns OK or INADMISSIBLE).
OK, NEWTON_FAILED, SINGULAR, INADMISSIBLE, ENERGY_GROWTH, BUDGET = range(6)


def live_tape(ops: np.ndarray, consts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The energy tape (:func:`ancf.core.tape.trace`) without the instructions its result does
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
    6, m) tape jets, Fb (m, 4) deformation gradients (m, 7 with an assumed strain: C_bar
    in columns 4 to 6, :func:`ancf.kinematics.section.assumed_kernels.assumed_invariants`), ab, Jb (m,)
    invariants, ew the element work of :func:`element_scratch`), m = chunk * nq; dN (nq,
    ns, 2) the shape gradients, pr the element's fields
    (:func:`ancf.kinematics.section.fields.pressure_arrays`)."""
    nq = dN.shape[0]
    chunk = max(1, 192 // nq)
    m = chunk * nq
    nf = 7 if pr[3].shape[1] > 0 else 4
    return chunk, np.empty((n_ops, 6, m)), np.empty((m, nf)), np.empty(m), np.empty(m), element_scratch(dN, pr)


@njit(cache=True)
def element_scratch(dN, pr):
    """The work arrays of :func:`element_forces`, made once per loop rather than at every
    assembly: (fl (nd,), gk, pk (nk,), pf (nq,)). :func:`element_terms` (the tangent) and
    :func:`point_gradients` keep making theirs: made inside a kernel, the compiler knows
    they alias nothing (measured with theirs passed in as well: the 32 x HB2n-12 tangent
    33 -> 39 us; with point_gradients' ue passed in, the 32 x HB2n-12 pendulum 2 to 3 %
    slower, at the edge of the machine's noise)."""
    nq, ns = dN.shape[0], dN.shape[1]
    nd, nk = 2 * ns, pr[2].shape[0]
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
    tangent by 2 x 2 node blocks, and one scatter per element. pr: the element's fields
    (:func:`ancf.kinematics.section.fields.pressure_arrays`; empty without them); chunk, R, Fb, ab, Jb,
    ew: :func:`step_scratch` for these dN and pr. An element with an assumed strain (pr's
    T, :mod:`ancf.kinematics.section.assumed`) takes (a, J) from C_bar at the rule's points
    (:mod:`ancf.kinematics.section.assumed_kernels`: :func:`assumed_invariants`, :func:`assumed_terms`).
    Returns OK, or INADMISSIBLE if det F (det C_bar) <= 0 (or is not finite) at a point."""
    ne = dofs.shape[0]
    f[:] = 0.0
    if with_tangent:
        Kc[:, :] = 0.0
    for e0 in range(0, ne, chunk):
        e1 = min(ne, e0 + chunk)
        m = point_gradients(u, u_n, alpha_f, dN, dofs, e0, e1, Fb, ab, Jb)
        if m >= 0 and pr[3].shape[1] > 0:
            m = assumed_invariants(Fb, ab, Jb, m, pr[3])     # the rule's points only, from here
        if m < 0:
            return INADMISSIBLE
        tape_batch(ops, consts, ab, Jb, R, m, 2 if with_tangent else 1)
        if pr[3].shape[1] > 0:
            assumed_terms(Fb, R[ops.shape[0] - 1], Jb, e0, e1, dN, w, dofs, pr, f, Kc, with_tangent)
        elif with_tangent:
            element_terms(Fb, R[ops.shape[0] - 1], Jb, e0, e1, dN, w, dofs, pr, f, Kc)
        else:
            element_forces(Fb, R[ops.shape[0] - 1], Jb, e0, e1, dN, w, dofs, pr, f, ew)
    return OK


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
    nk = pr[2].shape[0]
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

    The element pressure field pr (:func:`ancf.kinematics.section.fields.pressure_arrays`, nk
    functions; nothing to do if nk = 0), :class:`ancf.kinematics.section.pressure.ProjectedPenalty` compiled: its force
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
    wl = pr[1][1]
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
    """U = sum_e sum_q w_q W(F_eq) (J), plus the element pressure field's alpha/2 g^T M^-1 g
    per element (pr, :func:`ancf.kinematics.section.fields.pressure_arrays`; with an assumed strain W
    at C_bar, the sample points weighing zero); nan if det F (det C_bar) <= 0 somewhere.
    chunk .. ew: :func:`step_scratch` (the pressures work in ew's gk, pk, pf)."""
    ne = dofs.shape[0]
    last = ops.shape[0] - 1
    nk = pr[2].shape[0]
    nq, nr = dN.shape[0], pr[3].shape[1]
    nw = nr if nr > 0 else nq                  # points per element that carry energy
    g, pk, pq = ew[1], ew[2], ew[3]
    total = 0.0
    for e0 in range(0, ne, chunk):
        e1 = min(ne, e0 + chunk)
        m = point_gradients(u, u, 0.0, dN, dofs, e0, e1, Fb, ab, Jb)
        if m >= 0 and nr > 0:
            m = assumed_invariants(Fb, ab, Jb, m, pr[3])     # the rule's points only, from here
        if m < 0:
            return np.nan
        tape_batch(ops, consts, ab, Jb, R, m, 0)
        for p in range(m):
            total += w[p % nw] * R[last, 0, p]
        if nk > 0:
            for p0 in range(0, m, nw):
                total += element_pressures(pr, Jb, p0, nw, g, pk, pq)
    return total


@njit(cache=True)
def force_magnitude_fused(u, dN, w, dofs, ops, consts, pr, out):
    """out (n,) <- the internal force assembled from the magnitudes of its terms,
    sum |w dN_s,j| (|2 W_a F_ij| + (|W_J| + |p|) |(cof F)_ij|), p the element pressure
    field's value at the point (pr, :func:`ancf.kinematics.section.fields.pressure_arrays`; 0 without one):
    what the force's round-off is relative to. An element with an assumed strain is
    measured by its rule's points' own F and (a, J), not C_bar's (its sample points weigh
    zero): terms of the same size, which is all a floor needs. Returns OK, or INADMISSIBLE
    if det F <= 0 somewhere."""
    ne = dofs.shape[0]
    nq, ns = dN.shape[0], dN.shape[1]
    chunk, R, Fb, ab, Jb, ew = step_scratch(ops.shape[0], dN, pr)
    W = R[ops.shape[0] - 1]
    nk = pr[2].shape[0]
    g, pk, pp = ew[1], ew[2], ew[3]          # the pressures' work (element_scratch)
    pp[:] = 0.0                              # p = 0 without a pressure field
    out[:] = 0.0
    for e0 in range(0, ne, chunk):
        e1 = min(ne, e0 + chunk)
        m = point_gradients(u, u, 0.0, dN, dofs, e0, e1, Fb, ab, Jb)
        if m < 0:
            return INADMISSIBLE
        tape_batch(ops, consts, ab, Jb, R, m, 1)
        p = 0
        for e in range(e0, e1):
            if nk > 0:
                element_pressures(pr, Jb, p, nq, g, pk, pp)
            for q in range(nq):
                a2, aj, wq = abs(2.0 * W[1, p]), abs(W[2, p]) + abs(pp[q]), w[q]
                M0 = wq * (a2 * abs(Fb[p, 0]) + aj * abs(Fb[p, 3]))
                M1 = wq * (a2 * abs(Fb[p, 1]) + aj * abs(Fb[p, 2]))
                M2 = wq * (a2 * abs(Fb[p, 2]) + aj * abs(Fb[p, 1]))
                M3 = wq * (a2 * abs(Fb[p, 3]) + aj * abs(Fb[p, 0]))
                for s in range(ns):
                    g0, g1 = abs(dN[q, s, 0]), abs(dN[q, s, 1])
                    out[dofs[e, 2 * s]] += g0 * M0 + g1 * M1
                    out[dofs[e, 2 * s + 1]] += g0 * M2 + g1 * M3
                p += 1
    return OK
