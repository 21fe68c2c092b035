"""The compiled assembly of an element with an assumed strain (:mod:`ancf.kinematics.section.assumed`, whose
numpy :class:`ancf.kinematics.section.assumed.AssumedStrain` these are tested against), inside
:func:`ancf.kinematics.section.kernels.assemble_fused` and :func:`ancf.kinematics.section.kernels.strain_energy_fused`:
:func:`assumed_invariants` takes (a, J) from C_bar at the rule's points, the law's tape
runs there, and :func:`assumed_terms` makes the element force and tangent."""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .fields import element_pressures
from ...core.tape import FASTMATH


@njit(cache=True, fastmath=FASTMATH)
def assumed_invariants(Fb, ab, Jb, m, T):
    """For the m points in Fb (elements of T.shape[2] points each, the rule's T.shape[1]
    first): a = tr C_bar and J = sqrt(det C_bar) at the rule's points, C_bar_c = sum_p
    T[c, r, p] C_c(x_p), into ab and Jb compacted (element by element, the rule's points
    only: the tape need not run at the sample points), and C_bar itself (xx, yy, xy) into
    Fb's columns 4 to 6 of the same compacted rows, for :func:`assumed_terms`
    (:func:`ancf.kinematics.section.kernels.step_scratch` makes Fb (m, 7) for such an element). Returns their
    number, or -1 if det C_bar <= 0 (or is not finite) at a point."""
    nr, npts = T.shape[1], T.shape[2]
    n = 0
    for base in range(0, m, npts):
        for r in range(nr):
            c0, c1, c2 = 0.0, 0.0, 0.0
            for p in range(npts):
                F00, F01, F10, F11 = Fb[base + p, 0], Fb[base + p, 1], Fb[base + p, 2], Fb[base + p, 3]
                c0 += T[0, r, p] * (F00 * F00 + F10 * F10)
                c1 += T[1, r, p] * (F01 * F01 + F11 * F11)
                c2 += T[2, r, p] * (F00 * F01 + F10 * F11)
            det = c0 * c1 - c2 * c2
            if not (det > 0.0 and det < 1e300):
                return -1
            ab[n] = c0 + c1
            Jb[n] = math.sqrt(det)
            Fb[n, 4], Fb[n, 5], Fb[n, 6] = c0, c1, c2
            n += 1
    return n


@njit(cache=True, fastmath=FASTMATH)
def assumed_terms(Fb, W, Jb, e0, e1, dN, w, dofs, pr, f, Kc, with_tangent):
    """Add the force and, if with_tangent, the upper half of the tangent of elements
    e0 .. e1 - 1 with an assumed strain to f and Kc: :class:`ancf.kinematics.section.assumed.AssumedStrain`
    compiled. Fb: F at each element's points (the rule's, then the sample points), and
    C_bar at the rule's points in its columns 4 to 6; W (6, .) the energy's (a, J)
    derivatives at (tr C_bar, sqrt(det C_bar)) and Jb the J_bar at the rule's points, rows
    compacted element by element (:func:`assumed_invariants`); the pressure field (pr,
    :func:`ancf.kinematics.section.fields.pressure_arrays`, with T = pr[3]) projects J_bar. The force
    from the point stresses S_p = sum_r w_r dW/dC_bar(r) T[., r, p] as P = dW/dF; the
    tangent a dense element matrix, its upper half by 2 x 2 node blocks. T's non-zeros
    are listed at each call (336 for HB2n-20xypm; not timed apart from the kernel)."""
    nd = dofs.shape[1]
    npts, ns = dN.shape[0], dN.shape[1]
    T, wl = pr[3], pr[1][1]
    nr, nk = T.shape[1], wl.shape[1]
    b = Kc.shape[1] - 1
    nz = np.zeros((3, nr), np.int64)  # T's non-zeros by row: C_bar_c(x_r) = sum_k tv[c, r, k] C_c(x_tp[c, r, k])
    tp = np.empty((3, nr, npts), np.int64)
    tv = np.empty((3, nr, npts))
    for c in range(3):
        for r in range(nr):
            for p in range(npts):
                if T[c, r, p] != 0.0:
                    tp[c, r, nz[c, r]], tv[c, r, nz[c, r]] = p, T[c, r, p]
                    nz[c, r] += 1
    dxT, dyT = np.empty((ns, npts)), np.empty((ns, npts))   # dN transposed, and the geometric
    k0T, k1T = np.empty((ns, npts)), np.empty((ns, npts))   # part's stress times dN
    for p in range(npts):
        for s in range(ns):
            dxT[s, p], dyT[s, p] = dN[p, s, 0], dN[p, s, 1]
    dC = np.empty((npts, 3, nd))      # dC_c(x_p)/du_e (for the tangent)
    Sp = np.empty((npts, 3))          # the point stresses sum_r w_r dW/dC_bar_c(r) T[c, r, p]
    g = np.empty((3, nd))             # dC_bar_c(x_r)/du_e
    h = np.empty((3, nd))
    fl = np.empty(nd)
    Ke = np.empty((nd, nd))
    geo = np.empty((ns, ns))
    gk, pk, pf = np.empty(nk), np.empty(nk), np.zeros(npts)
    Gl = np.empty((nk, nd))
    D = np.empty((3, 3))
    for e in range(e0, e1):
        base = (e - e0) * npts
        if with_tangent:
            for p in range(npts):
                F00, F01, F10, F11 = Fb[base + p, 0], Fb[base + p, 1], Fb[base + p, 2], Fb[base + p, 3]
                for s in range(ns):
                    gx, gy = dN[p, s, 0], dN[p, s, 1]
                    dC[p, 0, 2 * s], dC[p, 0, 2 * s + 1] = 2.0 * F00 * gx, 2.0 * F10 * gx
                    dC[p, 1, 2 * s], dC[p, 1, 2 * s + 1] = 2.0 * F01 * gy, 2.0 * F11 * gy
                    dC[p, 2, 2 * s], dC[p, 2, 2 * s + 1] = F00 * gy + F01 * gx, F10 * gy + F11 * gx
        if nk > 0:
            element_pressures(pr, Jb, (e - e0) * nr, nr, gk, pk, pf)
            Gl[:, :] = 0.0
        Sp[:, :] = 0.0
        if with_tangent:
            Ke[:, :] = 0.0
        for r in range(nr):
            q = (e - e0) * nr + r                                   # compacted (assumed_invariants)
            c0, c1, c2 = Fb[q, 4], Fb[q, 5], Fb[q, 6]               # C_bar there
            J = Jb[q]
            Wa, WJ = W[1, q], W[2, q] + pf[r]
            j0, j1, j2 = c1 / (2.0 * J), c0 / (2.0 * J), -c2 / J          # dJ_bar/dC_bar
            wr = w[r]
            s0, s1, s2 = wr * (Wa + WJ * j0), wr * (Wa + WJ * j1), wr * WJ * j2
            for k in range(nz[0, r]):
                Sp[tp[0, r, k], 0] += s0 * tv[0, r, k]
            for k in range(nz[1, r]):
                Sp[tp[1, r, k], 1] += s1 * tv[1, r, k]
            for k in range(nz[2, r]):
                Sp[tp[2, r, k], 2] += s2 * tv[2, r, k]
            if not with_tangent:
                continue
            for c in range(3):
                p, t = tp[c, r, 0], tv[c, r, 0]
                for d in range(nd):
                    g[c, d] = t * dC[p, c, d]
                for k in range(1, nz[c, r]):
                    p, t = tp[c, r, k], tv[c, r, k]
                    for d in range(nd):
                        g[c, d] += t * dC[p, c, d]
            # D = d2W/dC_bar2: W_aa da da + W_aJ (da dJ + dJ da) + W_JJ dJ dJ + W_J d2J,
            # d2J = H / (2 J) - det' det'^T / (4 J^3), det' = (c1, c0, -2 c2)
            Waa, WaJ, WJJ = W[3, q], W[4, q], W[5, q]
            da = (1.0, 1.0, 0.0)
            dj = (j0, j1, j2)
            dd = (c1, c0, -2.0 * c2)
            for c in range(3):
                for k in range(3):
                    D[c, k] = (Waa * da[c] * da[k] + WaJ * (da[c] * dj[k] + dj[c] * da[k]) + WJJ * dj[c] * dj[k]
                               - WJ * dd[c] * dd[k] / (4.0 * J * J * J))
            D[0, 1] += WJ / (2.0 * J)
            D[1, 0] += WJ / (2.0 * J)
            D[2, 2] -= WJ / J
            for c in range(3):
                for d in range(nd):
                    h[c, d] = wr * (D[c, 0] * g[0, d] + D[c, 1] * g[1, d] + D[c, 2] * g[2, d])
            for s in range(ns):                                   # the upper half, by node blocks
                a0, a1, b0, b1 = g[0, 2 * s], g[0, 2 * s + 1], g[1, 2 * s], g[1, 2 * s + 1]
                x0, x1 = g[2, 2 * s], g[2, 2 * s + 1]
                for t in range(s, ns):
                    p0, p1, q0, q1 = h[0, 2 * t], h[0, 2 * t + 1], h[1, 2 * t], h[1, 2 * t + 1]
                    y0, y1 = h[2, 2 * t], h[2, 2 * t + 1]
                    Ke[2 * s, 2 * t] += a0 * p0 + b0 * q0 + x0 * y0
                    Ke[2 * s, 2 * t + 1] += a0 * p1 + b0 * q1 + x0 * y1
                    Ke[2 * s + 1, 2 * t] += a1 * p0 + b1 * q0 + x1 * y0
                    Ke[2 * s + 1, 2 * t + 1] += a1 * p1 + b1 * q1 + x1 * y1
            if nk > 0:
                for k in range(nk):
                    c = wl[r, k]
                    for d in range(nd):
                        Gl[k, d] += c * (j0 * g[0, d] + j1 * g[1, d] + j2 * g[2, d])
        fl[:] = 0.0
        for p in range(npts):                                     # f = sum_p dN^T P(x_p)
            S0, S1, S2 = Sp[p, 0], Sp[p, 1], Sp[p, 2]
            if S0 == 0.0 and S1 == 0.0 and S2 == 0.0:
                continue
            F00, F01, F10, F11 = Fb[base + p, 0], Fb[base + p, 1], Fb[base + p, 2], Fb[base + p, 3]
            P00, P01 = 2.0 * S0 * F00 + S2 * F01, 2.0 * S1 * F01 + S2 * F00
            P10, P11 = 2.0 * S0 * F10 + S2 * F11, 2.0 * S1 * F11 + S2 * F10
            for s in range(ns):
                gx, gy = dN[p, s, 0], dN[p, s, 1]
                fl[2 * s] += gx * P00 + gy * P01
                fl[2 * s + 1] += gx * P10 + gy * P11
        for i in range(nd):
            f[dofs[e, i]] += fl[i]
        if not with_tangent:
            continue
        # geometric part: sum_p sum_c S_pc d2C_c(x_p)/du2, d2C/du_(s,i) du_(t,k) = delta_ik (...)
        for p in range(npts):
            sx, sy, sxy = 2.0 * Sp[p, 0], 2.0 * Sp[p, 1], Sp[p, 2]
            for s in range(ns):
                xs, ys = dxT[s, p], dyT[s, p]
                k0T[s, p] = sx * xs + sxy * ys
                k1T[s, p] = sy * ys + sxy * xs
        for s in range(ns):
            for t in range(s, ns):
                v = 0.0
                for p in range(npts):
                    v += k0T[s, p] * dxT[t, p] + k1T[s, p] * dyT[t, p]
                geo[s, t] = v
        for s in range(ns):
            for t in range(s, ns):
                Ke[2 * s, 2 * t] += geo[s, t]
                Ke[2 * s + 1, 2 * t + 1] += geo[s, t]
        for k in range(nk):
            for i in range(nd):
                x = Gl[k, i]
                for j in range(i, nd):
                    Ke[i, j] += x * Gl[k, j]
        for i in range(nd):                                       # Ke's upper half, into Kc's
            r = dofs[e, i]
            for j in range(i, nd):
                c = dofs[e, j]
                if r <= c:
                    Kc[c, b + r - c] += Ke[i, j]
                else:
                    Kc[r, b + c - r] += Ke[i, j]
