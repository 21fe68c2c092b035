"""The discrete-gradient scheme's assembly, compiled (:func:`assemble_dg`, stepped by
:func:`ancf.solvers.compiled_steps.step_dg`): the numpy version is
:meth:`ancf.kinematics.section.model.BeamModel.discrete_gradient_force_and_tangent`, which it is tested
against. It runs the tape at 13 (a, J) pairs per quadrature point and then the fused
kernel's element loop (:func:`ancf.kinematics.section.kernels.element_terms`), so a registered element or
law needs no new compiled code here either."""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .kernels import INADMISSIBLE, OK, element_terms, point_gradients, step_scratch
from ...core.tape import FASTMATH, tape_batch


@njit(cache=True)
def dg_scratch(n_ops, dN, pr):
    """Work arrays of :func:`assemble_dg`: (chunk, R (n_ops, 6, m) midpoint jets, Fb
    (m, 4) midpoint F, ab, Jb (m,), ew (:func:`ancf.kinematics.section.kernels.element_scratch`), F0 and F1
    (m, 4), a and J at the 12 line points (12 m,), their jets RL (n_ops, 3, 12 m), W (6, m)),
    m = chunk * nq."""
    chunk, R, Fb, ab, Jb, ew = step_scratch(n_ops, dN, pr)
    m = chunk * dN.shape[0]
    return (chunk, R, Fb, ab, Jb, ew, np.empty((m, 4)), np.empty((m, 4)), np.empty(12 * m), np.empty(12 * m),
            np.empty((n_ops, 3, 12 * m)), np.empty((6, m)))


# 3-point Gauss on [0, 1] for the discrete gradient's line integrals
GAUSS3_S = (0.5 - math.sqrt(0.15), 0.5, 0.5 + math.sqrt(0.15))
GAUSS3_W = (5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0)


@njit(cache=True, fastmath=FASTMATH)
def assemble_dg(u0, u1, dN, w, dofs, ops, consts, pr, f, Kc, chunk, R, Fb, ab, Jb, ew, F0, F1, aL, JL, RL, W):
    """The discrete-gradient force f_dg(u0, u1) into f and the tangent at the midpoint
    F_m = (F0 + F1) / 2 with the discrete-gradient W^_a, W^_J in its first-order terms
    (not yet halved) into Kc: :meth:`ancf.kinematics.section.model.BeamModel.discrete_gradient_force_and_tangent`
    compiled. The element pressure field pr (:func:`ancf.kinematics.section.fields.pressure_arrays`)
    takes its exact discrete gradient in :func:`ancf.kinematics.section.kernels.element_terms`: the pressure
    of the mean J (J0 + J1) / 2 in the force, that of det F_m in the tangent.
    W^_a = [int_0^1 W_a(a0 + s da, J0) + W_a(a0 + s da, J1) ds] / 2 and W^_J alike, by
    3-point Gauss in s; the second derivatives at (a_m, J_m). Returns OK or
    INADMISSIBLE (det F <= 0 at u0 or u1). Scratch: :func:`dg_scratch`."""
    ne = dofs.shape[0]
    last = ops.shape[0] - 1
    f[:] = 0.0
    Kc[:, :] = 0.0
    for e0 in range(0, ne, chunk):
        e1 = min(ne, e0 + chunk)
        m = point_gradients(u0, u0, 0.0, dN, dofs, e0, e1, F0, ab, Jb)
        if m < 0 or point_gradients(u1, u1, 0.0, dN, dofs, e0, e1, F1, aL, JL) < 0:
            return INADMISSIBLE
        for p in range(m):
            a0, J0 = ab[p], Jb[p]
            a1, J1 = aL[p], JL[p]
            for k in range(3):
                s = GAUSS3_S[k]
                aL[k * m + p], JL[k * m + p] = a0 + s * (a1 - a0), J0          # W_a along a at J0
                aL[(3 + k) * m + p], JL[(3 + k) * m + p] = a0 + s * (a1 - a0), J1
                aL[(6 + k) * m + p], JL[(6 + k) * m + p] = a0, J0 + s * (J1 - J0)   # W_J along J at a0
                aL[(9 + k) * m + p], JL[(9 + k) * m + p] = a1, J0 + s * (J1 - J0)
            for i in range(4):
                Fb[p, i] = 0.5 * (F0[p, i] + F1[p, i])
            ab[p] = 0.5 * (a0 + a1)
            Jb[p] = 0.5 * (J0 + J1)
        tape_batch(ops, consts, ab, Jb, R, m, 2)
        tape_batch(ops, consts, aL, JL, RL, 12 * m, 1)
        Wm, WL = R[last], RL[last]
        for p in range(m):
            wa, wj = 0.0, 0.0
            for k in range(3):
                wa += GAUSS3_W[k] * (WL[1, k * m + p] + WL[1, (3 + k) * m + p])
                wj += GAUSS3_W[k] * (WL[2, (6 + k) * m + p] + WL[2, (9 + k) * m + p])
            W[0, p] = Wm[0, p]
            W[1, p] = 0.5 * wa
            W[2, p] = 0.5 * wj
            W[3, p], W[4, p], W[5, p] = Wm[3, p], Wm[4, p], Wm[5, p]
        element_terms(Fb, W, Jb, e0, e1, dN, w, dofs, pr, f, Kc)
    return OK
