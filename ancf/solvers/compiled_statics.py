"""The compiled static Newton iteration: the step loop's kernels for statics.

:func:`newton` is :func:`ancf.solvers.statics.newton_reference` (the Python loop, kept as the
reference it is tested against) in one numba call: per iteration the fused assembly of
the force and the upper half of the tangent (:func:`ancf.kinematics.kernels.element_assemble`,
the step loop's), the constraint, a banded LDL^T without pivoting
(:func:`ancf.core.bandsolve.col_ldlt`) and its solve; the same tests in the same order
(non-finite residual, residual <= atol, divergence, correction <= utol) and the same
line search. Per iteration of 640 x HB2n-16 this is 1.6 ms (assembly 0.94, LDL^T 0.55,
solve 0.13) where the Python loop takes 3.1 ms (numpy gradients and the general band
tangent 1.9, LAPACK's pivoted band LU 1.1).

LDL^T without pivoting takes an indefinite tangent, but not one whose pivot vanishes
while the matrix does not (a symmetric indefinite matrix can need pivoting). Such an
iteration is not called singular here: the attempt returns ``UNPIVOTED`` and
:func:`ancf.solvers.statics.newton` redoes it with the Python loop, whose pivoted LU decides.

Laws and elements stay data, as in :mod:`ancf.solvers.compiled_steps`: the compiled code sees the
tabulated shape-function gradients, weights, element dofs, the law's tape and the element
pressure field's arrays (:func:`ancf.kinematics.section.fields.pressure_arrays`, empty without one),
and hands them to the element interface (:mod:`ancf.kinematics.kernels`), which chooses the
continuum's kernel or the cable's from them.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..core.bandsolve import col_constrain, col_ldlt, col_ldlt_solve
from .couple import add_couple
from ..kinematics.kernels import element_assemble, element_force_magnitude, element_work
from ..kinematics.section.kernels import OK, live_tape

# Outcomes of :func:`newton` (a converged attempt is CONVERGED).
CONVERGED, NON_FINITE, DIVERGING, NO_CONVERGENCE, UNPIVOTED, NOT_ADMISSIBLE = range(6)
REASONS = {NON_FINITE: "non-finite residual", DIVERGING: "diverging",
           NO_CONVERGENCE: "no convergence within max_iterations",
           NOT_ADMISSIBLE: "inadmissible state (det F <= 0 at a quadrature point)"}


@njit(cache=True)
def _residual(f, target, is_free, r):
    s = 0.0
    for i in range(f.shape[0]):
        r[i] = (f[i] - target[i]) if is_free[i] else 0.0
        s += r[i] * r[i]
    return math.sqrt(s)


@njit(cache=True)
def _assemble(u, dN, w, dofs, ops, consts, pr, couple, f, S, b, with_tangent, chunk, R, Fb, ab, Jb, ew):
    """f_int(u) minus the end couple's force (and the tangent of both, upper column band):
    :func:`ancf.kinematics.kernels.element_assemble` then :func:`ancf.solvers.couple.add_couple`."""
    status = element_assemble(u, u, 0.0, dN, w, dofs, ops, consts, pr, f, S, with_tangent, chunk, R, Fb, ab, Jb, ew)
    if status == OK:
        add_couple(u, couple[0], couple[1], couple[2], couple[3], f, S, b, with_tangent)
    return status


@njit(cache=True)
def _slope(s, u, du, ut, target, is_free, dN, w, dofs, ops, consts, pr, couple, b, f, S, chunk, R, Fb, ab, Jb,
           ew):
    """g(s) = R(u + s du) . du, the potential's slope along du (inf where det F <= 0)."""
    for i in range(u.shape[0]):
        ut[i] = u[i] + s * du[i]
    if _assemble(ut, dN, w, dofs, ops, consts, pr, couple, f, S, b, False, chunk, R, Fb, ab, Jb, ew) != OK:
        return math.inf
    g = 0.0
    for i in range(u.shape[0]):
        if is_free[i]:
            g += (f[i] - target[i]) * du[i]
    return g


@njit(cache=True)
def _line_search(u, du, r, target, is_free, dN, w, dofs, ops, consts, pr, couple, b, f, S, chunk, R, Fb, ab, Jb, ew,
                 ut):
    """The step factor of :func:`ancf.solvers.statics._line_search`, the same rule."""
    g0 = 0.0
    for i in range(u.shape[0]):
        g0 += r[i] * du[i]
    if g0 >= 0.0:                    # not a descent direction (indefinite K): full step
        return 1.0
    g1 = _slope(1.0, u, du, ut, target, is_free, dN, w, dofs, ops, consts, pr, couple, b, f, S, chunk, R, Fb, ab,
                Jb, ew)
    if abs(g1) <= 0.5 * abs(g0):
        return 1.0
    lo, glo, hi, ghi = 0.0, g0, 1.0, g1
    if ghi < 0.0:                    # still descending at s = 1: take the full step
        return 1.0
    for _ in range(8):
        if abs(ghi) < math.inf:
            s = hi - ghi * (hi - lo) / (ghi - glo)
        else:
            s = 0.5 * (lo + hi)
        s = min(max(s, lo + 0.1 * (hi - lo)), hi - 0.1 * (hi - lo))
        gs = _slope(s, u, du, ut, target, is_free, dN, w, dofs, ops, consts, pr, couple, b, f, S, chunk, R, Fb, ab,
                    Jb, ew)
        if abs(gs) <= 0.5 * abs(g0):
            return s
        if gs < 0.0:
            lo, glo = s, gs
        else:
            hi, ghi = s, gs
    return lo if lo > 0.0 else 0.5 * hi


@njit(cache=True)
def newton(dN, w, dofs, ops, consts, pr, first, fixed, b, target, couple, u, atol, utol, hbeam, max_it, line_search,
           residuals):
    """Solve f_int(u) = target + the end couple's force on the free dofs from u (in place),
    with the line search of :func:`ancf.solvers.statics._line_search` if ``line_search``; b: the
    half-bandwidth; couple: (rows, A, d0, M) of :meth:`ancf.solvers.couple.Loading.compiled`.
    residuals (max_it + 2,) receives the residual norms. Returns (outcome, iterations,
    number of residuals)."""
    n = u.shape[0]
    is_free = np.ones(n, np.bool_)
    for k in fixed:
        is_free[k] = False
    S = np.empty((n, b + 1))
    f, r, du, ut = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    wk = np.empty((2, n))
    chunk, R, Fb, ab, Jb, ew = element_work(ops, dN, pr)
    nres = 0
    for it in range(max_it + 1):
        if _assemble(u, dN, w, dofs, ops, consts, pr, couple, f, S, b, True, chunk, R, Fb, ab, Jb, ew) != OK:
            return NOT_ADMISSIBLE, nres, nres
        rn = _residual(f, target, is_free, r)
        residuals[nres] = rn
        nres += 1
        if not rn < math.inf:
            return NON_FINITE, it, nres
        if rn <= atol:
            return CONVERGED, it, nres
        if it == max_it:
            break
        if it >= 3 and rn > 1e3 * residuals[0]:
            return DIVERGING, it, nres
        col_constrain(S, fixed)
        if col_ldlt(S, first, wk) < 0:
            return UNPIVOTED, it, nres
        for i in range(n):
            du[i] = -r[i]
        col_ldlt_solve(S, first, du)
        for i in range(n):
            if not abs(du[i]) < math.inf:
                return UNPIVOTED, it, nres
        if line_search:
            step = _line_search(u, du, r, target, is_free, dN, w, dofs, ops, consts, pr, couple, b, f, S, chunk, R,
                                Fb, ab, Jb, ew, ut)
            for i in range(n):
                du[i] *= step
        umax, dumax = 0.0, 0.0
        for i in range(n):
            u[i] += du[i]
            umax = max(umax, abs(u[i]))
            dumax = max(dumax, abs(du[i]))
        if it >= 1 and dumax <= utol * max(umax, hbeam):
            if _assemble(u, dN, w, dofs, ops, consts, pr, couple, f, S, b, False, chunk, R, Fb, ab, Jb, ew) != OK:
                return NOT_ADMISSIBLE, nres, nres
            residuals[nres] = _residual(f, target, is_free, r)
            return CONVERGED, it + 1, nres + 1
    return NO_CONVERGENCE, max_it, nres


# the round-off floor's force magnitudes (the element's, :mod:`ancf.kinematics.kernels`)
force_magnitude = element_force_magnitude


class StaticKernel:
    """The arrays :func:`newton` reads, for one model (built once per model)."""

    def __init__(self, model):
        dN, w, dofs, ops, consts, pr, first = model.fused
        self.data = (dN, w, dofs, *live_tape(ops, consts), pr, first,
                     np.ascontiguousarray(model.fixed, dtype=np.int64))
        self.hbeam = float(model.mesh.height)
        self.bandwidth = int(model.mesh.bandwidth)

    def newton(self, u0: np.ndarray, loading, atol: float, max_iterations: int,
               utol: float, line_search: bool = False) -> tuple[int, np.ndarray, int, list[float]]:
        """(outcome, u, iterations, residuals) from u0 (not changed), balancing ``loading``
        (:class:`ancf.solvers.couple.Loading`)."""
        u = np.array(u0, dtype=float)
        residuals = np.empty(max_iterations + 2)
        outcome, its, nres = newton(*self.data, self.bandwidth, np.ascontiguousarray(loading.Q, dtype=float),
                                    loading.compiled(), u, float(atol), float(utol), self.hbeam,
                                    int(max_iterations), bool(line_search), residuals)
        return int(outcome), u, int(its), [float(x) for x in residuals[:nres]]

    def roundoff_floor(self, u: np.ndarray) -> float:
        """eps ||sum of |terms| of f_int(u)||_2 over the free dofs (N): the size of the
        force's round-off; nan if det F <= 0 at u."""
        dN, w, dofs, ops, consts, pr, _, fixed = self.data
        out = np.empty(len(u))
        if force_magnitude(np.ascontiguousarray(u, dtype=float), dN, w, dofs, ops, consts, pr, out) != OK:
            return float("nan")
        out[fixed] = 0.0
        return float(np.finfo(float).eps * np.linalg.norm(out))
