"""The element's own fields as the compiled kernels read them: the projected pressure field
(:class:`ancf.kinematics.section.pressure.ProjectedPenalty`) and the assumed strain's sampling
(:func:`ancf.kinematics.section.assumed.sampling`), made into arrays once per model (:func:`pressure_arrays`,
``pr``), and the element pressure at an element's points (:func:`element_pressures`),
shared by the assemblies (:mod:`ancf.kinematics.section.kernels`, :mod:`ancf.kinematics.section.assumed_kernels`) and the
statics' round-off floor (:mod:`ancf.solvers.compiled_statics`)."""
from __future__ import annotations

import numpy as np
from numba import njit

from ...core.tape import FASTMATH


def pressure_arrays(penalty, nq: int, T: np.ndarray | None = None) -> tuple:
    """The element's fields as the compiled kernels read them (``pr``), four arrays: the
    pressure field's q (nq, nk) basis at the points; qw (2, nq, nk), the basis times the
    weights wq and wl = wq L, pm = L L^T (Cholesky: the tangent's G^T pm G = (L^T G)^T
    (L^T G), L^T G = wl^T dJ/du); pm (nk, nk) = alpha M^-1, from a
    :class:`ancf.kinematics.section.pressure.ProjectedPenalty` (tabulated at the first nq' <= nq points: the
    rows of the sample points after them are zero); and the assumed strain's T (3, nq',
    nq) (:func:`ancf.kinematics.section.assumed.sampling`). With ``penalty`` None (no pressure field, or no
    penalty) nk = 0 and the kernels' pressure loops run zero times; with ``T`` None it is
    (3, 0, 0) and the points take their own C: one code path for every element.

    Four, not five: numba's dispatcher fingerprints a tuple of at most four arrays in C;
    with five it typed the arguments in Python at every call (about 1 ms per run of 2 x
    HB2n-12 on the thick pendulum, 1.2 -> 2.2 ms)."""
    if penalty is None:
        q, wq, pm, wl = np.zeros((nq, 0)), np.zeros((nq, 0)), np.zeros((0, 0)), np.zeros((nq, 0))
    else:
        pad = ((0, nq - penalty.q.shape[0]), (0, 0))
        q, wq, pm = np.pad(penalty.q, pad), np.pad(penalty.wq, pad), penalty.alpha * penalty.minv
        wl = wq @ np.linalg.cholesky(0.5 * (pm + pm.T))
    T = np.zeros((3, 0, 0)) if T is None else T
    return tuple(np.ascontiguousarray(x, dtype=float) for x in (q, np.stack([wq, wl]), pm, T))


@njit(cache=True, fastmath=FASTMATH)
def element_pressures(pr, Jb, p0, nq, g, pk, out):
    """The element pressure at the element's points p0 .. p0 + nq - 1 into out (nq,), from
    the J there (Jb): g = wq^T (J - 1), its coefficients pk = alpha M^-1 g
    (:class:`ancf.kinematics.section.pressure.ProjectedPenalty`). Returns the element's U_vol = g . pk / 2."""
    pq, pw, pm = pr[0], pr[1][0], pr[2]
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

