"""The compiled kernels of a cable element (:mod:`ancf.cable`, whose numpy
:class:`ancf.cable.CableModel` methods ``*_numpy`` they are tested against), chosen by
:mod:`ancf.element_kernels` from the model's data.

A cable's data have the continuum's layout (:attr:`ancf.beam.ElementModel.fused`): at
each point p = (X_q, Y_j) of the rule (points along the centre line times points across
the section) dN[p, s, 0] = N_s'(X_q) and dN[p, s, 1] = Y_j N_s''(X_q), so that the two
vectors

    e = r_x(X_q) = (1, 0) + sum_s dN[p, s, 0] u_s,    g = Y_j r_xx(X_q) = sum_s dN[p, s, 1] u_s

take the places of F's two columns (Fb: e_x, g_x, e_y, g_y, as F00, F01, F10, F11), and w
the weights times l_e h w_b. The fibre at height Y (Euler-Bernoulli: it stays at
r + Y n, n the unit normal) has the stretch

    lambda = |e| - (e x g) / |e|^2        (= |r_x| - Y theta_X, theta_X = r_x x r_xx / |r_x|^2)

and the energy density W_u(lambda), the law's incompressible uniaxial energy, whose tape
(:func:`ancf.tape.trace_uniaxial`) gives W_u, W_u' and W_u'' at every point. Then, with
the derivatives of lambda in vec(e, g) (:func:`_stretch`),

    P = w W_u' dlambda,    A = w (W_u'' dlambda dlambda^T + W_u' d2lambda),

and the element force and tangent are B^T P and B^T A B with the continuum's B (the same
map from the element's dofs to vec(e, g) as to vec F).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .kernels import INADMISSIBLE, OK
from .tape import FASTMATH, tape_batch


@njit(cache=True, fastmath=FASTMATH)
def cable_points(u, u_n, alpha_f, dN, dofs, e0, e1, Fb, lam):
    """At the points of elements e0 .. e1 - 1 of the state ue = (1 - alpha_f) u + alpha_f u_n:
    e = r_x and g = Y r_xx into Fb (e_x, g_x, e_y, g_y) and the fibre stretch
    lambda = |e| - (e x g) / |e|^2 into lam. Returns the number of points, or -1 if a
    stretch is not > 0 (or not finite)."""
    nd = dofs.shape[1]
    nq, ns = dN.shape[0], dN.shape[1]
    c = 1.0 - alpha_f
    ue = np.empty(nd)
    m = 0
    for e in range(e0, e1):
        for k in range(nd):
            d = dofs[e, k]
            ue[k] = c * u[d] + alpha_f * u_n[d]
        for q in range(nq):
            ex, gx, ey, gy = 1.0, 0.0, 0.0, 0.0
            for s in range(ns):
                ux, uy = ue[2 * s], ue[2 * s + 1]
                a0, a1 = dN[q, s, 0], dN[q, s, 1]
                ex += a0 * ux
                gx += a1 * ux
                ey += a0 * uy
                gy += a1 * uy
            s2 = ex * ex + ey * ey
            if not (s2 > 0.0 and s2 < 1e300):       # (numba raises on a division by zero)
                return -1
            v = math.sqrt(s2) - (ex * gy - ey * gx) / s2
            if not (v > 0.0 and v < 1e300):
                return -1
            Fb[m, 0], Fb[m, 1], Fb[m, 2], Fb[m, 3] = ex, gx, ey, gy
            lam[m] = v
            m += 1
    return m


@njit(cache=True, fastmath=FASTMATH, inline="always")
def _stretch(ex, gx, ey, gy, dl, H, hessian):
    """dlambda (4,) and, if ``hessian``, d2lambda (4, 4) in vec(e, g) = (e_x, g_x, e_y, g_y),
    lambda = s - c p with s = |e|, c = e x g = e_x g_y - e_y g_x, p = 1 / s^2:
    dlambda = ds - p dc - c dp, d2lambda = d2s - p d2c - dc dp^T - dp dc^T - c d2p."""
    s2 = ex * ex + ey * ey
    s = math.sqrt(s2)
    p = 1.0 / s2
    c = ex * gy - ey * gx
    p2 = p * p
    dc0, dc1, dc2, dc3 = gy, -ey, -gx, ex
    dp0, dp2 = -2.0 * ex * p2, -2.0 * ey * p2
    dl[0] = ex / s - p * dc0 - c * dp0
    dl[1] = -p * dc1
    dl[2] = ey / s - p * dc2 - c * dp2
    dl[3] = -p * dc3
    if not hessian:
        return
    s3 = s * s2
    p3 = p2 * p
    dc = (dc0, dc1, dc2, dc3)
    dp = (dp0, 0.0, dp2, 0.0)
    for i in range(4):
        for k in range(4):
            H[i, k] = -(dc[i] * dp[k] + dp[i] * dc[k])
    H[0, 0] += ey * ey / s3 - c * (-2.0 * p2 + 8.0 * ex * ex * p3)
    H[2, 2] += ex * ex / s3 - c * (-2.0 * p2 + 8.0 * ey * ey * p3)
    x02 = -ex * ey / s3 - c * 8.0 * ex * ey * p3
    H[0, 2] += x02
    H[2, 0] += x02
    H[0, 3] -= p
    H[3, 0] -= p
    H[1, 2] += p
    H[2, 1] += p


@njit(cache=True, fastmath=FASTMATH)
def cable_terms(Fb, W, e0, e1, dN, w, dofs, f, Kc, with_tangent, fl, Ke):
    """Add the force and, if with_tangent, the upper half of the tangent of elements
    e0 .. e1 - 1 to f and Kc (column band), from (e, g) at their points (Fb, in
    :func:`cable_points`' order) and W (6, m): W_u and its derivatives in lambda in slots
    0, 1 and 3 (the tape's a slot). fl (nd,), Ke (nd, nd): work."""
    nd = dofs.shape[1]
    nq, ns = dN.shape[0], dN.shape[1]
    b = Kc.shape[1] - 1
    dl = np.empty(4)
    H = np.empty((4, 4))
    A = np.empty((4, 4))
    p = 0
    for e in range(e0, e1):
        fl[:] = 0.0
        if with_tangent:
            Ke[:, :] = 0.0
        for q in range(nq):
            ex, gx, ey, gy = Fb[p, 0], Fb[p, 1], Fb[p, 2], Fb[p, 3]
            W1, wq = W[1, p], w[q]
            _stretch(ex, gx, ey, gy, dl, H, with_tangent)
            P0, P1, P2, P3 = wq * W1 * dl[0], wq * W1 * dl[1], wq * W1 * dl[2], wq * W1 * dl[3]
            for s in range(ns):
                a0, a1 = dN[q, s, 0], dN[q, s, 1]
                fl[2 * s] += a0 * P0 + a1 * P1
                fl[2 * s + 1] += a0 * P2 + a1 * P3
            if with_tangent:
                W2 = W[3, p]
                for i in range(4):
                    for k in range(4):
                        A[i, k] = wq * (W2 * dl[i] * dl[k] + W1 * H[i, k])
                # K_(s i, t k) = sum_jl dN_s,j A_(2i+j, 2k+l) dN_t,l
                for s in range(ns):
                    a0, a1 = dN[q, s, 0], dN[q, s, 1]
                    for i in range(2):
                        t0 = a0 * A[2 * i, 0] + a1 * A[2 * i + 1, 0]
                        t1 = a0 * A[2 * i, 1] + a1 * A[2 * i + 1, 1]
                        t2 = a0 * A[2 * i, 2] + a1 * A[2 * i + 1, 2]
                        t3 = a0 * A[2 * i, 3] + a1 * A[2 * i + 1, 3]
                        r = 2 * s + i
                        for t in range(ns):
                            c0, c1 = dN[q, t, 0], dN[q, t, 1]
                            Ke[r, 2 * t] += t0 * c0 + t1 * c1
                            Ke[r, 2 * t + 1] += t2 * c0 + t3 * c1
            p += 1
        for i in range(nd):
            f[dofs[e, i]] += fl[i]
        if with_tangent:
            for i in range(nd):
                r = dofs[e, i]
                for k in range(nd):
                    c = dofs[e, k]
                    if r <= c:
                        Kc[c, b + r - c] += Ke[i, k]


@njit(cache=True, fastmath=FASTMATH)
def cable_assemble(u, u_n, alpha_f, dN, w, dofs, ops, consts, f, Kc, with_tangent, chunk, R, Fb, ab, Jb):
    """The cable's :func:`ancf.kernels.assemble_fused`: internal force at ue = (1 - alpha_f) u
    + alpha_f u_n into f and, if with_tangent, the upper half of the tangent into Kc, per
    chunk of elements: (e, g) and lambda at all points (:func:`cable_points`), the tape
    over them (lambda in the a slot; Jb unread), then the element terms
    (:func:`cable_terms`). Returns OK, or INADMISSIBLE if a fibre's stretch is not > 0."""
    ne, nd = dofs.shape[0], dofs.shape[1]
    f[:] = 0.0
    if with_tangent:
        Kc[:, :] = 0.0
    fl, Ke = np.empty(nd), np.empty((nd, nd))
    last = ops.shape[0] - 1
    for e0 in range(0, ne, chunk):
        e1 = min(ne, e0 + chunk)
        m = cable_points(u, u_n, alpha_f, dN, dofs, e0, e1, Fb, ab)
        if m < 0:
            return INADMISSIBLE
        tape_batch(ops, consts, ab, Jb, R, m, 2 if with_tangent else 1)
        cable_terms(Fb, R[last], e0, e1, dN, w, dofs, f, Kc, with_tangent, fl, Ke)
    return OK


@njit(cache=True)
def cable_energy(u, dN, w, dofs, ops, consts, chunk, R, Fb, ab, Jb):
    """U = sum_e sum_p w_p W_u(lambda_p) (J); nan if a fibre's stretch is not > 0."""
    ne, nq = dofs.shape[0], dN.shape[0]
    last = ops.shape[0] - 1
    total = 0.0
    for e0 in range(0, ne, chunk):
        e1 = min(ne, e0 + chunk)
        m = cable_points(u, u, 0.0, dN, dofs, e0, e1, Fb, ab)
        if m < 0:
            return np.nan
        tape_batch(ops, consts, ab, Jb, R, m, 0)
        for p in range(m):
            total += w[p % nq] * R[last, 0, p]
    return total


@njit(cache=True)
def cable_force_magnitude(u, dN, w, dofs, ops, consts, out, chunk, R, Fb, ab, Jb):
    """out (n,) <- the cable's internal force assembled from the magnitudes of its terms:
    sum |w dN_s,j| (|W_u'| + |W_u''|) |terms of dlambda_(2i+j)|. |W_u''| stands for the
    size of the terms inside W_u' (near lambda = 1 its terms, of the order of the modulus,
    cancel: 2 C10 (lambda - lambda^-2) for neo-Hookean, whose W_u'' = 6 C10 at 1). What the
    force's round-off is relative to. Returns OK, or INADMISSIBLE."""
    ne, nq, ns = dofs.shape[0], dN.shape[0], dN.shape[1]
    last = ops.shape[0] - 1
    out[:] = 0.0
    for e0 in range(0, ne, chunk):
        e1 = min(ne, e0 + chunk)
        m = cable_points(u, u, 0.0, dN, dofs, e0, e1, Fb, ab)
        if m < 0:
            return INADMISSIBLE
        tape_batch(ops, consts, ab, Jb, R, m, 2)
        p = 0
        for e in range(e0, e1):
            for q in range(nq):
                ex, gx, ey, gy = abs(Fb[p, 0]), abs(Fb[p, 1]), abs(Fb[p, 2]), abs(Fb[p, 3])
                s = math.sqrt(ex * ex + ey * ey)
                pp = 1.0 / (s * s)
                c = ex * gy + ey * gx
                a = abs(w[q]) * (abs(R[last, 1, p]) + abs(R[last, 3, p]))
                M0 = a * (ex / s + pp * gy + 2.0 * c * ex * pp * pp)
                M1 = a * pp * ey
                M2 = a * (ey / s + pp * gx + 2.0 * c * ey * pp * pp)
                M3 = a * pp * ex
                for t in range(ns):
                    g0, g1 = abs(dN[q, t, 0]), abs(dN[q, t, 1])
                    out[dofs[e, 2 * t]] += g0 * M0 + g1 * M1
                    out[dofs[e, 2 * t + 1]] += g0 * M2 + g1 * M3
                p += 1
    return OK
