"""The compiled kernels of a cable element (:mod:`ancf.kinematics.cable.model`, whose numpy
:class:`ancf.kinematics.cable.model.CableModel` methods ``*_numpy`` they are tested against), chosen by
:mod:`ancf.kinematics.kernels` from the model's data.

A cable's data (:attr:`ancf.kinematics.cable.model.CableModel.fused`) have the continuum's types with their
own meaning: dN (nx, ns, 2) holds N_s' and N_s'' at the points along the centre line, w
(nx,) their weights times l_e, and the element's fields pr hold its section rule,
pr[0] = (ny, 2): the heights Y_j (m) and their weights times h w_b (m^2)
(:func:`section_fields`). At a point X along, with e = r_x and k = r_xx (the two columns
of a "gradient" G = [e | k], Fb's rows e_x, k_x, e_y, k_y as F00, F01, F10, F11),

    s = |e|,  kappa = (e x k) / s^2,  lambda_j = s - Y_j kappa

(Euler-Bernoulli, eta = Y: the fibre at Y stays at r + Y n), and the section's resultants
of the law's uniaxial energy W_u (its tape, :func:`ancf.core.tape.trace_uniaxial`, at every
(X, Y_j))

    n0 = sum_j w_j W_u'(lambda_j),   n1 = sum_j w_j W_u' Y_j,
    d0 = sum_j w_j W_u'',  d1 = sum_j w_j W_u'' Y_j,  d2 = sum_j w_j W_u'' Y_j^2

(n0 the axial force, n1 minus the moment) give the stress and tangent in vec G,

    P = n0 ds - n1 dkappa,
    A = d0 ds ds^T - d1 (ds dkappa^T + dkappa ds^T) + d2 dkappa dkappa^T + n0 d2s - n1 d2kappa,

and the element force and tangent are B^T P and B^T A B with the continuum's B (the same
map from the element's dofs to vec G as to vec F). Once per point along, not per fibre:
the section costs a tape replay per fibre and five sums.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..section.kernels import INADMISSIBLE, OK, element_scratch
from ...core.tape import FASTMATH, tape_batch


def section_fields(Y: np.ndarray, weights: np.ndarray, nx: int) -> tuple:
    """A cable's element fields (``pr``, the types of :func:`ancf.kinematics.section.fields.pressure_arrays`):
    its section rule (ny, 2) = (Y_j, weights), and empty arrays (no pressure field, no
    assumed strain)."""
    sec = np.ascontiguousarray(np.stack([np.asarray(Y, float), np.asarray(weights, float)], axis=1))
    return sec, np.zeros((2, nx, 0)), np.zeros((0, 0)), np.zeros((3, 0, 0))


@njit(cache=True)
def cable_scratch(n_ops, dN, pr):
    """The work arrays of the cable's loops, :func:`ancf.kinematics.section.kernels.step_scratch`'s types: chunk
    (elements per pass, about 192 fibres), R (n_ops, 6, m) tape jets, Fb (m, 4) G at the
    points along (their first chunk nx rows), ab (m,) the fibres' stretches, Jb (m,) (the
    tape's J, unread), ew (:func:`ancf.kinematics.section.kernels.element_scratch`); m = chunk nx ny."""
    nx, ny = dN.shape[0], pr[0].shape[0]
    chunk = max(1, 192 // (nx * ny))
    m = chunk * nx * ny
    return chunk, np.empty((n_ops, 6, m)), np.empty((m, 4)), np.empty(m), np.empty(m), element_scratch(dN, pr)


@njit(cache=True, fastmath=FASTMATH)
def cable_points(u, u_n, alpha_f, dN, dofs, sec, e0, e1, Fb, lam):
    """For elements e0 .. e1 - 1 of ue = (1 - alpha_f) u + alpha_f u_n: G = [r_x | r_xx] at the
    points along into Fb (e_x, k_x, e_y, k_y) and the fibres' stretches lambda = |e| - Y kappa
    into lam (point along, then fibre). Returns the number of fibres, or -1 if |r_x| = 0 or a
    stretch is not > 0 (or not finite)."""
    nd = dofs.shape[1]
    nx, ns, ny = dN.shape[0], dN.shape[1], sec.shape[0]
    c = 1.0 - alpha_f
    ue = np.empty(nd)
    q = 0
    m = 0
    for e in range(e0, e1):
        for k in range(nd):
            d = dofs[e, k]
            ue[k] = c * u[d] + alpha_f * u_n[d]
        for x in range(nx):
            ex, kx, ey, ky = 1.0, 0.0, 0.0, 0.0
            for s in range(ns):
                ux, uy = ue[2 * s], ue[2 * s + 1]
                a0, a1 = dN[x, s, 0], dN[x, s, 1]
                ex += a0 * ux
                kx += a1 * ux
                ey += a0 * uy
                ky += a1 * uy
            s2 = ex * ex + ey * ey
            if not (s2 > 0.0 and s2 < 1e300):       # (numba raises on a division by zero)
                return -1
            st = math.sqrt(s2)
            kappa = (ex * ky - ey * kx) / s2
            Fb[q, 0], Fb[q, 1], Fb[q, 2], Fb[q, 3] = ex, kx, ey, ky
            q += 1
            for j in range(ny):
                v = st - sec[j, 0] * kappa
                if not (v > 0.0 and v < 1e300):
                    return -1
                lam[m] = v
                m += 1
    return m


@njit(cache=True, fastmath=FASTMATH, inline="always")
def _centre_line(ex, kx, ey, ky, ds, dk, H2s, H2k, hessian):
    """ds, dkappa (4,) and, if ``hessian``, d2s, d2kappa (4, 4) in vec G = (e_x, k_x, e_y, k_y):
    s = |e|, kappa = c p, c = e x k = e_x k_y - e_y k_x, p = 1 / s^2,
    dkappa = p dc + c dp, d2kappa = p d2c + dc dp^T + dp dc^T + c d2p."""
    s2 = ex * ex + ey * ey
    s = math.sqrt(s2)
    p = 1.0 / s2
    c = ex * ky - ey * kx
    p2 = p * p
    dc0, dc1, dc2, dc3 = ky, -ey, -kx, ex
    dp0, dp2 = -2.0 * ex * p2, -2.0 * ey * p2
    ds[0], ds[1], ds[2], ds[3] = ex / s, 0.0, ey / s, 0.0
    dk[0] = p * dc0 + c * dp0
    dk[1] = p * dc1
    dk[2] = p * dc2 + c * dp2
    dk[3] = p * dc3
    if not hessian:
        return
    s3 = s * s2
    p3 = p2 * p
    dc = (dc0, dc1, dc2, dc3)
    dp = (dp0, 0.0, dp2, 0.0)
    for i in range(4):
        for k in range(4):
            H2s[i, k] = 0.0
            H2k[i, k] = dc[i] * dp[k] + dp[i] * dc[k]
    H2s[0, 0], H2s[2, 2] = ey * ey / s3, ex * ex / s3
    H2s[0, 2] = H2s[2, 0] = -ex * ey / s3
    H2k[0, 0] += c * (-2.0 * p2 + 8.0 * ex * ex * p3)
    H2k[2, 2] += c * (-2.0 * p2 + 8.0 * ey * ey * p3)
    x02 = c * 8.0 * ex * ey * p3
    H2k[0, 2] += x02
    H2k[2, 0] += x02
    H2k[0, 3] += p
    H2k[3, 0] += p
    H2k[1, 2] -= p
    H2k[2, 1] -= p


@njit(cache=True, fastmath=FASTMATH)
def cable_terms(Fb, W, e0, e1, dN, w, dofs, sec, f, Kc, with_tangent, fl, Ke):
    """Add the force and, if with_tangent, the upper half of the tangent of elements
    e0 .. e1 - 1 to f and Kc (column band), from G at their points along (Fb, in
    :func:`cable_points`' order) and W (6, fibres): W_u and its derivatives in lambda in
    slots 0, 1 and 3 (the tape's a slot). fl (nd,), Ke (nd, nd): work."""
    nd = dofs.shape[1]
    nx, ns, ny = dN.shape[0], dN.shape[1], sec.shape[0]
    b = Kc.shape[1] - 1
    ds, dk = np.empty(4), np.empty(4)
    H2s, H2k, A = np.empty((4, 4)), np.empty((4, 4)), np.empty((4, 4))
    q = 0
    p = 0
    for e in range(e0, e1):
        fl[:] = 0.0
        if with_tangent:
            Ke[:, :] = 0.0
        for x in range(nx):
            n0, n1, d0, d1, d2 = 0.0, 0.0, 0.0, 0.0, 0.0
            for j in range(ny):
                Y, wj = sec[j, 0], sec[j, 1]
                a1 = wj * W[1, p]
                n0 += a1
                n1 += a1 * Y
                if with_tangent:
                    a2 = wj * W[3, p]
                    d0 += a2
                    d1 += a2 * Y
                    d2 += a2 * Y * Y
                p += 1
            wx = w[x]
            _centre_line(Fb[q, 0], Fb[q, 1], Fb[q, 2], Fb[q, 3], ds, dk, H2s, H2k, with_tangent)
            q += 1
            n0, n1 = wx * n0, wx * n1
            P0, P1, P2, P3 = (n0 * ds[0] - n1 * dk[0], n0 * ds[1] - n1 * dk[1],
                              n0 * ds[2] - n1 * dk[2], n0 * ds[3] - n1 * dk[3])
            for s in range(ns):
                a0, a1 = dN[x, s, 0], dN[x, s, 1]
                fl[2 * s] += a0 * P0 + a1 * P1
                fl[2 * s + 1] += a0 * P2 + a1 * P3
            if not with_tangent:
                continue
            d0, d1, d2 = wx * d0, wx * d1, wx * d2
            for i in range(4):
                si, ki = ds[i], dk[i]
                for k in range(4):
                    sk, kk = ds[k], dk[k]
                    A[i, k] = (d0 * si * sk - d1 * (si * kk + ki * sk) + d2 * ki * kk
                               + n0 * H2s[i, k] - n1 * H2k[i, k])
            # K_(s i, t k) = sum_jl dN_s,j A_(2i+j, 2k+l) dN_t,l
            for s in range(ns):
                a0, a1 = dN[x, s, 0], dN[x, s, 1]
                for i in range(2):
                    t0 = a0 * A[2 * i, 0] + a1 * A[2 * i + 1, 0]
                    t1 = a0 * A[2 * i, 1] + a1 * A[2 * i + 1, 1]
                    t2 = a0 * A[2 * i, 2] + a1 * A[2 * i + 1, 2]
                    t3 = a0 * A[2 * i, 3] + a1 * A[2 * i + 1, 3]
                    r = 2 * s + i
                    for t in range(ns):
                        c0, c1 = dN[x, t, 0], dN[x, t, 1]
                        Ke[r, 2 * t] += t0 * c0 + t1 * c1
                        Ke[r, 2 * t + 1] += t2 * c0 + t3 * c1
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
def cable_assemble(u, u_n, alpha_f, dN, w, dofs, ops, consts, pr, f, Kc, with_tangent, chunk, R, Fb, ab, Jb, ew):
    """The cable's :func:`ancf.kinematics.section.kernels.assemble_fused`: internal force at ue = (1 - alpha_f) u
    + alpha_f u_n into f and, if with_tangent, the upper half of the tangent into Kc, per
    chunk of elements: G and the fibres' stretches (:func:`cable_points`), the tape over the
    fibres (lambda in the a slot; Jb unread), then the element terms from the section's
    resultants (:func:`cable_terms`). chunk .. ew: :func:`cable_scratch`. Returns OK, or
    INADMISSIBLE if a fibre's stretch is not > 0."""
    ne, nd = dofs.shape[0], dofs.shape[1]
    sec = pr[0]
    f[:] = 0.0
    if with_tangent:
        Kc[:, :] = 0.0
    fl, Ke = ew[0], np.empty((nd, nd))
    last = ops.shape[0] - 1
    for e0 in range(0, ne, chunk):
        e1 = min(ne, e0 + chunk)
        m = cable_points(u, u_n, alpha_f, dN, dofs, sec, e0, e1, Fb, ab)
        if m < 0:
            return INADMISSIBLE
        tape_batch(ops, consts, ab, Jb, R, m, 2 if with_tangent else 1)
        cable_terms(Fb, R[last], e0, e1, dN, w, dofs, sec, f, Kc, with_tangent, fl, Ke)
    return OK


@njit(cache=True)
def cable_energy(u, dN, w, dofs, ops, consts, pr, chunk, R, Fb, ab, Jb):
    """U = sum_e sum_x w_x sum_j w_j W_u(lambda_xj) (J); nan if a fibre's stretch is not > 0."""
    ne, nx = dofs.shape[0], dN.shape[0]
    sec = pr[0]
    ny = sec.shape[0]
    last = ops.shape[0] - 1
    total = 0.0
    for e0 in range(0, ne, chunk):
        e1 = min(ne, e0 + chunk)
        m = cable_points(u, u, 0.0, dN, dofs, sec, e0, e1, Fb, ab)
        if m < 0:
            return np.nan
        tape_batch(ops, consts, ab, Jb, R, m, 0)
        for p in range(m):
            total += w[(p // ny) % nx] * sec[p % ny, 1] * R[last, 0, p]
    return total


@njit(cache=True)
def cable_force_magnitude(u, dN, w, dofs, ops, consts, pr, out, chunk, R, Fb, ab, Jb):
    """out (n,) <- the cable's internal force assembled from the magnitudes of its terms:
    sum |w_x dN_s,j| sum_j |w_j| (|W_u'| + |W_u''|) (|ds| + |Y_j| |terms of dkappa|). |W_u''|
    stands for the size of the terms inside W_u' (near lambda = 1 they cancel: 2 C10
    (lambda - lambda^-2) for neo-Hookean, whose W_u'' = 6 C10 at 1). What the force's
    round-off is relative to. Returns OK, or INADMISSIBLE."""
    ne, nx, ns = dofs.shape[0], dN.shape[0], dN.shape[1]
    sec = pr[0]
    ny = sec.shape[0]
    last = ops.shape[0] - 1
    out[:] = 0.0
    for e0 in range(0, ne, chunk):
        e1 = min(ne, e0 + chunk)
        m = cable_points(u, u, 0.0, dN, dofs, sec, e0, e1, Fb, ab)
        if m < 0:
            return INADMISSIBLE
        tape_batch(ops, consts, ab, Jb, R, m, 2)
        p = 0
        q = 0
        for e in range(e0, e1):
            for x in range(nx):
                ex, kx, ey, ky = abs(Fb[q, 0]), abs(Fb[q, 1]), abs(Fb[q, 2]), abs(Fb[q, 3])
                q += 1
                s = math.sqrt(ex * ex + ey * ey)
                pp = 1.0 / (s * s)
                c = ex * ky + ey * kx
                a0, a1 = 0.0, 0.0
                for j in range(ny):
                    t = abs(sec[j, 1]) * (abs(R[last, 1, p]) + abs(R[last, 3, p]))
                    a0 += t
                    a1 += t * abs(sec[j, 0])
                    p += 1
                a0, a1 = abs(w[x]) * a0, abs(w[x]) * a1
                M0 = a0 * ex / s + a1 * (pp * ky + 2.0 * c * ex * pp * pp)
                M1 = a1 * pp * ey
                M2 = a0 * ey / s + a1 * (pp * kx + 2.0 * c * ey * pp * pp)
                M3 = a1 * pp * ex
                for t in range(ns):
                    g0, g1 = abs(dN[x, t, 0]), abs(dN[x, t, 1])
                    out[dofs[e, 2 * t]] += g0 * M0 + g1 * M1
                    out[dofs[e, 2 * t + 1]] += g0 * M2 + g1 * M3
    return OK
