"""The compiled time loop of the generalized-alpha family (generalized-alpha, Newmark)
and of the discrete-gradient scheme (:func:`step_dg`).

:func:`advance` integrates from the current time to the next output time in one numba
call: predictor, Newton iterations (fused assembly, banded LDL^T with envelope and
solve, convergence test), the update of velocities and accelerations, the landing on the
output time and the energy check. Python (:func:`mechanics.time_loop.integrate`) is entered
only at output times, when a step is rejected (Newton failure, a singular step matrix,
det F <= 0), when the energy limit is crossed, and every
:data:`mechanics.time_loop.STEPS_PER_CALL` steps
(progress, wall time, Ctrl-C). The step-control rules are those of
:mod:`mechanics.time_loop`: :func:`~mechanics.time_loop.next_step` and
:func:`~mechanics.time_loop.after_acceptance` are compiled here from that same source; a
rejected step is returned to the Python loop, which halves it (``after_rejection``) and
checks ``dt_min``, ``max_steps`` and ``wall_time`` there.

Laws and elements stay data: the compiled code sees the tabulated shape-function
gradients ``dN`` (nq, ns, 2) and weights ``w`` of the model, the element dofs, the law x
formulation energy traced into a tape (:mod:`ancf.core.tape`), the element pressure field's
arrays (:func:`ancf.kinematics.section.fields.pressure_arrays`, empty without one), the mass matrix, the
load and the fixed dofs; the element's assembly and energy are the element interface's
(:mod:`ancf.kinematics.kernels`, which chooses a continuum-based element's kernel or a
cable's from those data). A registered element or law runs with no new compiled code. The
integrator's coefficients (alpha_m, alpha_f, beta, gamma) come from the integrator class
as data.

The generalized-alpha family (Chung-Hulbert):

    M a_(n+1-alpha_m) + f_int(u_(n+1-alpha_f)) = f_ext,
    u_(n+1) = u_pred + beta h^2 (a_(n+1) - a_n),  u_pred = u_n + h v_n + h^2 a_n / 2,
    v_(n+1) = v_n + h ((1 - gamma) a_n + gamma a_(n+1)),

by Newton on u_(n+1) from the predictor a_(n+1) = a_n; in Arnold and Bruls's form (2007) the
forces are taken at the ends of the step, not at a configuration between them,

    M a_(n+1-alpha_m) + (1 - alpha_f) f_int(u_(n+1)) + alpha_f f_int(u_n) = f_ext,

a the pseudo-acceleration (``inewton[I_FORCES_AT_ENDS]``; f_int(u_n) is carried from step
to step). The step matrix is the same in both forms,
S = (1 - alpha_f) K + (1 - alpha_m) / (beta h^2) M (K at u_(n+1-alpha_f) or at u_(n+1)),
factorised by LDL^T without pivoting (:func:`ancf.core.bandsolve.col_ldlt`): S need not be positive definite at a Newton iterate (a
compressed beam with a stiff penalty, at the predictor), so only a (near) zero pivot
rejects the step.

Newton variants (``[analysis] newton``, :data:`NEWTON`):

- "full": tangent and factorisation at every iteration; stops on the residual
  |R|_2 <= rtol (|f_ext|_2 + |M a_n|_2) or on a correction max|du| <= utol max(|u|, h)
  (the Python loop's method, reproduced step for step);
- "chord" (default): the tangent at the predictor, factorised once per step and reused
  for the step's iterations (refreshed within the step if the residual contracts by less
  than ``KAPPA``). From the predictor the first correction is ~beta h^3 |da/dt|, so that
  Jacobian is as good as a fresh one: the same 2 iterations per step on the pendulum
  with one tangent, one factorisation and force-only residuals. Stops on the residual
  only;
- "modified": the factorisation is kept across iterations and steps (Exudyn's default),
  refreshed when there is none, when the step size changed, on a contraction worse than
  ``KAPPA`` or after ``MAX_MODIFIED`` iterations on one factorisation. Stops on the
  residual only.

- "linear": one solve per step with the tangent at the predictor and no convergence test
  (Exudyn's ``newton.active = False``), for runs whose step is small enough that one
  correction from the predictor is as accurate as the step; the new state's admissibility
  (det F > 0, a cable's fibre stretches > 0) is checked instead of its residual, and the
  energy guard applies as for every variant. ``newton_rtol`` does not apply. Not
  unconditionally stable: an unconverged step feeds the stiff modes, and on the pendulum
  it folds or gains energy at 10 ms steps and on fine meshes at 5 ms (measured by the
  peers' work-precision grid, reports/peers_work_precision.md).

With "chord", "modified" or "linear" a failed step is redone once from the predictor with full
Newton before it is rejected. A reused factorisation stops on the residual only: its
residual after a correction is (S_old - S) du, linear in du, so a correction test would
leave a residual that does not shrink with dt, and its work turns the energy drift from
O(dt^2) into O(dt) (measured; the residual stop keeps the Newmark drift ratio at 4.0 per
halving, tests/test_compiled_steps.py).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from mechanics import alpha_family, time_loop
from ..core.bandsolve import col_constrain, col_ldlt, col_ldlt_solve, col_matvec, col_matvec_split, same_component_only
from ..kinematics.model import refuse_discrete_gradient
from ..kinematics.section.dg_kernels import dg_scratch
from ..kinematics.kernels import element_admissible, element_assemble, element_assemble_dg, element_energy, element_work
from ..kinematics.section.kernels import INADMISSIBLE, NEWTON_FAILED, OK, SINGULAR, ENERGY_GROWTH, BUDGET, live_tape

NEWTON = ("chord", "full", "modified", "linear")
STATUS = {NEWTON_FAILED: "Newton failed", SINGULAR: "singular step matrix", INADMISSIBLE: "det F <= 0"}

KAPPA = 0.5                  # chord/modified: refactor when |R_k| > KAPPA |R_(k-1)|
# A reused factorisation stops on the residual, and also when the correction is below
# ROUNDOFF utol (1e-8) of the state: where round-off keeps the residual above its
# tolerance (fine meshes: 128 elements and more on the pendulum), and to spare the
# verifying residual of a step whose second correction is already that small. The
# residual it leaves, (S_old - S) du, is a hundred times below the correction test's;
# measured on the Newmark pendulum (8 x HB2n-12, dt 2 ms ... 0.125 ms) the energy drift
# is the same to 4 digits as with 1e-3 utol or with the residual test alone (ratio 4.0
# per halving), and it spares the verifying residual of 85 % of the steps.
ROUNDOFF = 1e-2
MAX_MODIFIED = 8             # modified: at most this many iterations on one factorisation per step

# The family's predictor and updates, as mechanics.alpha_family writes them for every
# stepper, compiled per entry (plain arithmetic, so they run on floats here)
_predict = njit(inline="always")(alpha_family.predict)
_update = njit(inline="always")(alpha_family.update)
_midpoint = njit(inline="always")(alpha_family.midpoint)

# Counters (an int64 array, cumulative over a run).
C_STEPS, C_ITERATIONS, C_RESIDUALS, C_TANGENTS, C_FACTORS, C_SOLVES, C_REJECTED, C_ENERGIES = range(8)
C_REJ_NEWTON, C_REJ_SINGULAR, C_REJ_INADMISSIBLE, C_INDEFINITE, C_FALLBACKS = range(8, 13)
COUNTER_NAMES = ("steps", "iterations", "residuals", "tangents", "factorisations", "solves", "rejected",
                 "energy_checks", "rejected_newton", "rejected_singular", "rejected_inadmissible",
                 "indefinite_factorisations", "full_newton_fallbacks")

# Integer Newton settings (``inewton``) and float ones (``fnewton``).
I_MAX_IT, I_MODIFIED, I_STOP, I_MAX_MODIFIED, I_ENERGY_EVERY, I_JAC_PER_STEP, I_SCHEME, I_MASS_SPLIT, I_LINEAR = range(9)
I_FORCES_AT_ENDS = 9                              # 1: Arnold-Bruls (forces at u_(n+1) and u_n)
ALPHA_FAMILY, DISCRETE_GRADIENT = 0, 1            # inewton[I_SCHEME]
STOP_RESIDUAL, STOP_BOTH = 0, 1
F_RTOL, F_UTOL, F_KAPPA, F_HBEAM, F_ELIMIT = range(5)

# the step-control rules of the one time loop, compiled from their one source
_next_step = njit(cache=True)(time_loop.next_step)
_after_acceptance = njit(cache=True)(time_loop.after_acceptance)


@njit(cache=True)
def _norm2_free(x, is_free):
    s = 0.0
    for i in range(x.shape[0]):
        if is_free[i]:
            s += x[i] * x[i]
    return math.sqrt(s)


@njit(cache=True)
def _mass(Mc, first, split, x, y):
    """y = M x (:func:`col_matvec`; :func:`col_matvec_split` if ``split``: M couples only
    dofs of the same component)."""
    if split:
        col_matvec_split(Mc, first, x, y)
    else:
        col_matvec(Mc, first, x, y)


@njit(cache=True)
def _residual(Mc, first, split, c, u, u_ref, base, f, f_ext, is_free, du, r, at_ref):
    """r = c M (u - u_ref) + base + f - f_ext on the free dofs (0 on the fixed ones);
    returns |r|_2. du: work. at_ref: u is u_ref (the predictor), M (u - u_ref) = 0 is not
    computed (the same r to the bit)."""
    if at_ref:
        for i in range(u.shape[0]):
            r[i] = (base[i] + f[i] - f_ext[i]) if is_free[i] else 0.0
        return _norm2_free(r, is_free)
    for i in range(u.shape[0]):
        du[i] = u[i] - u_ref[i]
    _mass(Mc, first, split, du, r)
    for i in range(u.shape[0]):
        r[i] = (c * r[i] + base[i] + f[i] - f_ext[i]) if is_free[i] else 0.0
    return _norm2_free(r, is_free)


@njit(cache=True)
def _factorise(S, k, Mc, c, fixed, first, wk, counters):
    """In place S <- k S + c M, constrained and factorised (:func:`col_ldlt`); returns
    its count (negative: singular)."""
    for j in range(S.shape[0]):
        for m in range(S.shape[1]):
            S[j, m] = k * S[j, m] + c * Mc[j, m]
    col_constrain(S, fixed)
    counters[C_FACTORS] += 1
    negative = col_ldlt(S, first, wk)
    if negative > 0:
        counters[C_INDEFINITE] += 1
    return negative


@njit(cache=True)
def _correct(S, first, r, du, u, counters):
    """u += du = -S^-1 r with S factorised; returns (max |u|, max |du|)."""
    for i in range(u.shape[0]):
        du[i] = -r[i]
    col_ldlt_solve(S, first, du)
    counters[C_SOLVES] += 1
    umax, dumax = 0.0, 0.0
    for i in range(u.shape[0]):
        u[i] += du[i]
        umax = max(umax, abs(u[i]))
        dumax = max(dumax, abs(du[i]))
    return umax, dumax


@njit(cache=True)
def _mix_forces(f, f_n, f_new, af):
    """Arnold-Bruls: f_new <- f = f(u_(n+1)), then f <- (1 - af) f + af f_n."""
    for i in range(f.shape[0]):
        f_new[i] = f[i]
        f[i] = (1.0 - af) * f[i] + af * f_n[i]


@njit(cache=True)
def step(dN, w, dofs, ops, consts, pr, Mc, first, f_ext, fixed, is_free, coef, inewton, fnewton,
         u_n, v_n, a_n, h, u, v, a, S, fstate, counters, wk, chunk, R, Fb, ab, Jb, ew, full):
    """One step u_n, v_n, a_n -> u, v, a of size h. S holds the current factorisation
    (modified Newton), fstate = [h of that factorisation, 1 if valid]; wk: work (7, n);
    chunk, R, Fb, ab, Jb, ew: :func:`ancf.kinematics.kernels.element_work`; full: full Newton whatever
    inewton says.
    Returns (status, iterations)."""
    am, af, beta, gamma = coef[0], coef[1], coef[2], coef[3]
    max_it, modified = inewton[I_MAX_IT], inewton[I_MODIFIED] != 0 and not full
    linear = inewton[I_LINEAR] != 0 and not full
    stop = STOP_BOTH if full else inewton[I_STOP]     # the fallback is the Python loop's Newton
    max_mod = inewton[I_MAX_MODIFIED]
    rtol, utol, kappa, hbeam = fnewton[F_RTOL], fnewton[F_UTOL], fnewton[F_KAPPA], fnewton[F_HBEAM]
    n = u.shape[0]
    u_pred, f, Ma_n, r, du = wk[0], wk[1], wk[2], wk[3], wk[4]
    # Arnold-Bruls: the forces at the ends of the step, (1 - af) f(u_(n+1)) + af f(u_n), with
    # f(u_n) in f_n (wk[7]); f(u_(n+1)) is left in wk[8] for the next step
    ends = inewton[I_FORCES_AT_ENDS] != 0
    f_n, f_new = wk[7], wk[8]
    af_at = 0.0 if ends else af                       # where the assembly evaluates
    bh2 = beta * h * h
    c = (1.0 - am) / bh2
    for i in range(n):
        u_pred[i] = _predict(u_n[i], v_n[i], a_n[i], h)
        u[i] = u_pred[i]
    split = inewton[I_MASS_SPLIT] != 0
    _mass(Mc, first, split, a_n, Ma_n)
    scale = _norm2_free(f_ext, is_free) + _norm2_free(Ma_n, is_free)
    tol = rtol * max(scale, 1e-30)
    if inewton[I_JAC_PER_STEP] != 0 or not (fstate[1] == 1.0 and abs(fstate[0] - h) <= 1e-9 * h):
        fstate[1] = 0.0                               # no factorisation for this step
    r_prev = 0.0
    since = 0                                         # iterations on the current factorisation
    it = 0
    while True:
        # residual M((1 - am) a + am a_n) + f(ue) - f_ext, with M a = c' M (u - u_pred) + M a_n
        refactor = (not modified) or fstate[1] == 0.0
        status = element_assemble(u, u_n, af_at, dN, w, dofs, ops, consts, pr, f, S, refactor, chunk, R, Fb, ab, Jb, ew)
        counters[C_RESIDUALS] += 1
        if refactor:
            counters[C_TANGENTS] += 1
        if status != OK:
            return status, it
        if ends:
            _mix_forces(f, f_n, f_new, af)
        rn = _residual(Mc, first, split, c, u, u_pred, Ma_n, f, f_ext, is_free, du, r, it == 0)
        if not rn < 1e300:
            return NEWTON_FAILED, it
        if rn <= tol:
            break
        if it == max_it:
            return NEWTON_FAILED, it
        rho = rn / r_prev if since > 0 else -1.0      # contraction of the last iteration (-1: none yet)
        if modified and not refactor and (since >= max_mod or rho > kappa):
            refactor = True                           # poor contraction: tangent at this iterate
            status = element_assemble(u, u_n, af_at, dN, w, dofs, ops, consts, pr, f, S, True, chunk, R, Fb, ab, Jb, ew)
            counters[C_TANGENTS] += 1
            if status != OK:
                return status, it
            if ends:
                _mix_forces(f, f_n, f_new, af)
        if refactor:
            # S = (1 - af) K + c M, constrained, factorised in place
            if _factorise(S, 1.0 - af, Mc, c, fixed, first, wk[5:7], counters) < 0:
                fstate[1] = 0.0
                return SINGULAR, it
            fstate[0], fstate[1] = h, 1.0
            since = 0
        r_prev = rn
        umax, dumax = _correct(S, first, r, du, u, counters)
        since += 1
        it += 1
        if linear:
            # one solve, no convergence test: the state's admissibility is checked (the
            # energy, as for every variant, by advance)
            status = element_admissible(u, dN, dofs, ops, pr, chunk, Fb, ab, Jb)
            if status != OK:
                return status, it
            break
        if dumax <= (utol if stop == STOP_BOTH else ROUNDOFF * utol) * max(umax, hbeam):
            break
    if ends and it > 0 and (linear or rn > tol):
        # stopped after a correction: f(u_(n+1)) for the next step at the final u
        status = element_assemble(u, u, 0.0, dN, w, dofs, ops, consts, pr, f_new, np.empty((0, 0)), False, chunk, R,
                                  Fb, ab, Jb, ew)
        counters[C_RESIDUALS] += 1
        if status != OK:
            return status, it
    for i in range(n):
        a[i], v[i] = _update(u[i], u_pred[i], v_n[i], a_n[i], h, beta, gamma)
    return OK, it



@njit(cache=True)
def step_dg(dN, w, dofs, ops, consts, pr, Mc, first, f_ext, fixed, is_free, inewton, fnewton, u_n, v_n, a_n, h,
            u, v, a, S, counters, wk, scratch):
    """One discrete-gradient step (:class:`ancf.solvers.integrators.DiscreteGradient`, its Python
    step compiled, the same iterations): Newton on
    R = M (2 (u - u_n) / h^2 - 2 v_n / h) + f_dg(u_n, u) - f_ext with the tangent
    K(u_m) / 2 + 2 M / h^2 at every iteration; stops on the residual
    |R| <= rtol (|f_ext| + |M a_n|) or on a correction below 1e-3 utol of the state (its
    Jacobian is not exact: a linear rate, so the tighter test), or, where the residual has
    stopped contracting (|R_k| > KAPPA |R_(k-1)|: its round-off floor, which a stiff
    near-rigid beam raises above the residual test), on the alpha family's correction test,
    utol of the state. Returns (status, iterations) with the Python step's count."""
    max_it = inewton[I_MAX_IT]
    rtol, utol, hbeam = fnewton[F_RTOL], fnewton[F_UTOL], fnewton[F_HBEAM]
    n = u.shape[0]
    f, Ma_n, r, du, Mv = wk[0], wk[1], wk[2], wk[3], wk[4]
    c = 2.0 / (h * h)
    for i in range(n):
        u[i] = u_n[i] + h * v_n[i] + 0.5 * h * h * a_n[i]
    split = inewton[I_MASS_SPLIT] != 0
    _mass(Mc, first, split, a_n, Ma_n)
    _mass(Mc, first, split, v_n, Mv)
    tol = rtol * max(_norm2_free(f_ext, is_free) + _norm2_free(Ma_n, is_free), 1e-30)
    for i in range(n):
        Mv[i] *= -2.0 / h                             # the residual's constant part, -2 M v_n / h
    it = 0
    r_prev = math.inf
    while True:
        status = element_assemble_dg(u_n, u, dN, w, dofs, ops, consts, pr, f, S, *scratch)
        counters[C_RESIDUALS] += 1
        counters[C_TANGENTS] += 1
        if status != OK:
            return status, it
        rn = _residual(Mc, first, split, c, u, u_n, Mv, f, f_ext, is_free, du, r, False)
        if not rn < 1e300:
            return NEWTON_FAILED, it
        if rn <= tol:
            it += 1
            break
        if it == max_it:
            return NEWTON_FAILED, it
        if _factorise(S, 0.5, Mc, c, fixed, first, wk[5:7], counters) < 0:
            return SINGULAR, it
        stalled = rn > KAPPA * r_prev
        r_prev = rn
        umax, dumax = _correct(S, first, r, du, u, counters)
        it += 1
        if dumax <= (utol if stalled else 1e-3 * utol) * max(umax, hbeam):
            break
    for i in range(n):
        a[i], v[i] = _midpoint(u_n[i], u[i], v_n[i], h)
    return OK, it


@njit(cache=True)
def energies(u, v, dN, w, dofs, ops, consts, pr, Mc, first, tmp, chunk, R, Fb, ab, Jb, ew):
    """(kinetic, strain) energy (J); the strain energy is nan if det F <= 0 somewhere
    (:func:`ancf.kinematics.kernels.element_energy`). tmp: work (n,); chunk .. ew:
    :func:`ancf.kinematics.kernels.element_work`."""
    col_matvec(Mc, first, v, tmp)
    return 0.5 * np.dot(v, tmp), element_energy(u, dN, w, dofs, ops, consts, pr, chunk, R, Fb, ab, Jb, ew)


@njit(cache=True)
def observed_energies(u, v, dN, w, dofs, ops, consts, pr, Mc, first):
    """:func:`energies` with its work arrays made here (an output's call: fewer arguments
    to pass cost less than the arrays to make)."""
    return energies(u, v, dN, w, dofs, ops, consts, pr, Mc, first, np.empty(u.shape[0]),
                    *element_work(ops, dN, pr))


@njit(cache=True)
def energy(u, v, dN, w, dofs, ops, consts, pr, Mc, first, f_ext, q_ref, tmp, chunk, R, Fb, ab, Jb, ew):
    """Kinetic + strain + the loads' potential (J), the potential -f_ext . (q_ref + u) as in
    ancf.solvers.integrators.Integrator.energies."""
    kin, strain = energies(u, v, dN, w, dofs, ops, consts, pr, Mc, first, tmp, chunk, R, Fb, ab, Jb, ew)
    return kin + strain - np.dot(f_ext, q_ref + u)


@njit(cache=True)
def advance(dN, w, dofs, ops, consts, pr, Mc, first, f_ext, q_ref, fixed, coef, inewton, fnewton,
            u, v, a, tstate, t_out, dt, budget, offset, S, fstate, counters):
    """Integrate in place from tstate[0] with the next step tstate[1] towards t_out, by
    the rules of :mod:`mechanics.time_loop` (landing, growth back to dt). Returns

    - OK: landed on t_out;
    - BUDGET: ``budget`` steps taken without landing;
    - ENERGY_GROWTH: the total energy, checked every inewton[I_ENERGY_EVERY] accepted
      steps counted from ``offset`` (0: no check; not at the landing step, which Python
      checks with the output), is not <= fnewton[F_ELIMIT]; tstate[3] = that energy;
    - NEWTON_FAILED, SINGULAR, INADMISSIBLE: a rejected step; u, v, a and tstate[0] are
      at its start, tstate[1] is its size.

    tstate = [t, next step, accepted steps in this call, energy at a growth, largest
    energy checked in this call (-inf: none)]."""
    n = u.shape[0]
    is_free = np.ones(n, np.bool_)
    for k in fixed:
        is_free[k] = False
    wk = np.empty((9, n))
    chunk, R, Fb, ab, Jb, ew = element_work(ops, dN, pr)
    ends = inewton[I_FORCES_AT_ENDS] != 0 and inewton[I_SCHEME] != DISCRETE_GRADIENT
    if ends:
        # f(u_n) at this call's first state (Arnold-Bruls); then carried from step to step
        status = element_assemble(u, u, 0.0, dN, w, dofs, ops, consts, pr, wk[7], np.empty((0, 0)), False, chunk, R,
                                  Fb, ab, Jb, ew)
        if status != OK:
            tstate[2] = 0
            return status
    dg = inewton[I_SCHEME] == DISCRETE_GRADIENT
    scratch = dg_scratch(ops.shape[0] if dg else 1, dN, pr)   # (unused without dg: one op)
    un, vn, an = np.empty(n), np.empty(n), np.empty(n)
    every = inewton[I_ENERGY_EVERY]
    t, h = tstate[0], tstate[1]
    done = 0
    while True:
        if done >= budget:
            tstate[0], tstate[1], tstate[2] = t, h, done
            return BUDGET
        step_h, land = _next_step(t, h, t_out)
        un[:] = u
        vn[:] = v
        an[:] = a
        if dg:
            status, its = step_dg(dN, w, dofs, ops, consts, pr, Mc, first, f_ext, fixed, is_free, inewton, fnewton,
                                  un, vn, an, step_h, u, v, a, S, counters, wk, scratch)
        else:
            status, its = step(dN, w, dofs, ops, consts, pr, Mc, first, f_ext, fixed, is_free, coef, inewton, fnewton,
                               un, vn, an, step_h, u, v, a, S, fstate, counters, wk, chunk, R, Fb, ab, Jb, ew, False)
        counters[C_ITERATIONS] += its
        if status != OK and status != SINGULAR and inewton[I_MODIFIED] != 0 and not dg:
            # a reused factorisation failed (divergence, det F <= 0, no convergence):
            # redo the step from the predictor with full Newton before rejecting it
            counters[C_FALLBACKS] += 1
            status, its = step(dN, w, dofs, ops, consts, pr, Mc, first, f_ext, fixed, is_free, coef, inewton, fnewton,
                               un, vn, an, step_h, u, v, a, S, fstate, counters, wk, chunk, R, Fb, ab, Jb, ew, True)
            counters[C_ITERATIONS] += its
        if status != OK:
            u[:] = un
            v[:] = vn
            a[:] = an
            tstate[0], tstate[1], tstate[2] = t, step_h, done
            counters[C_REJECTED] += 1
            if status == NEWTON_FAILED:
                counters[C_REJ_NEWTON] += 1
            elif status == SINGULAR:
                counters[C_REJ_SINGULAR] += 1
            else:
                counters[C_REJ_INADMISSIBLE] += 1
            return status
        counters[C_STEPS] += 1
        done += 1
        if ends:
            wk[7, :] = wk[8]
        t = t_out if land else t + step_h
        h = _after_acceptance(h, step_h, 0.0, 0.0, dt, land)
        if every > 0 and not land and (offset + done) % every == 0:
            counters[C_ENERGIES] += 1
            E = energy(u, v, dN, w, dofs, ops, consts, pr, Mc, first, f_ext, q_ref, wk[5], chunk, R, Fb, ab, Jb, ew)
            if not E <= tstate[4]:
                tstate[4] = E          # (a NaN energy is kept: it is the peak that fails the run)
            if not E <= fnewton[F_ELIMIT]:
                tstate[0], tstate[1], tstate[2], tstate[3] = t, h, done, E
                return ENERGY_GROWTH
        if land:
            tstate[0], tstate[1], tstate[2] = t, h, done
            return OK


@njit(cache=True)
def start(u, dN, w, dofs, ops, consts, pr, Mc, first, f_ext, fixed, a):
    """A run's initial accelerations in one call: a = M^-1 (f_ext - f_int(u)) on the free
    dofs, 0 on the fixed ones, with M constrained and factorised (:func:`col_ldlt`, M is
    positive definite: no pivoting needed, and the pivot test is relative to the
    diagonal, so small generalized masses lose nothing) at every run's start, as a peer
    computing initial accelerations does. Returns OK, INADMISSIBLE (det F <= 0) or
    SINGULAR."""
    n = u.shape[0]
    status = internal_force(u, dN, w, dofs, ops, consts, pr, a)
    if status != OK:
        return status
    for i in range(n):
        a[i] = f_ext[i] - a[i]
    for k in fixed:
        a[k] = 0.0
    C = Mc.copy()
    col_constrain(C, fixed)
    if col_ldlt(C, first, np.empty((2, n))) < 0:
        return SINGULAR
    col_ldlt_solve(C, first, a)
    return OK


@njit(cache=True)
def internal_force(u, dN, w, dofs, ops, consts, pr, f):
    """f = f_int(u) by the element's assembly (force only); returns its status."""
    chunk, R, Fb, ab, Jb, ew = element_work(ops, dN, pr)
    return element_assemble(u, u, 0.0, dN, w, dofs, ops, consts, pr, f, np.empty((0, 0)), False, chunk, R, Fb, ab, Jb, ew)


# -- the Python side -----------------------------------------------------------------------
def column_band(ab: np.ndarray, b: int) -> np.ndarray:
    """LAPACK general band ab (2 b + 1, n) of a symmetric matrix -> column band (n, b + 1)."""
    return np.ascontiguousarray(ab[: b + 1].T)


@dataclass
class Advanced:
    """What one :meth:`CompiledLoop.advance` call did."""
    outcome: str              # "landed", "budget", "energy-growth", "rejected"
    state: time_loop.State     # after the last accepted step (landed: at t_out)
    h: float                  # the next step; "rejected": the size of the rejected step
    steps: int                # accepted steps
    iterations: int           # Newton iterations, of rejected steps too
    energy: float = math.nan  # "energy-growth": the total energy found
    reason: str | None = None  # "rejected": why
    peak: float = -math.inf   # the largest total energy checked in the call (-inf: none)


class CompiledLoop:
    """The arrays and settings of :func:`advance` for one model and integrator."""

    def __init__(self, model, M, f_ext: np.ndarray, coefficients: dict, newton: str = "chord",
                 rtol: float = 1e-8, max_iterations: int = 25, utol: float = 1e-6,
                 discrete_gradient: bool = False, forces_at_ends: bool = False):
        """``discrete_gradient``: step by :func:`step_dg` (full Newton; ``newton`` and the
        coefficients do not apply), else by :func:`step` with ``newton``; ``forces_at_ends``:
        the Arnold-Bruls form of :func:`step` (the forces at u_(n+1) and u_n, not at
        u_(n+1-alpha_f))."""
        if newton not in NEWTON:
            raise ValueError(f"newton: {newton!r} is not one of {', '.join(NEWTON)}")
        if discrete_gradient:
            refuse_discrete_gradient(model)
        b = model.mesh.bandwidth
        self.n, self.b = model.mesh.n_dof, b
        dN, w, dofs, ops, consts, pr, first = model.fused
        ops, consts = live_tape(ops, consts)
        self.data = (dN, w, dofs, ops, consts, pr, column_band(M.ab, b), first, np.ascontiguousarray(f_ext, dtype=float),
                     np.ascontiguousarray(model.mesh.reference, dtype=float),
                     np.ascontiguousarray(model.fixed, dtype=np.int64))
        c = coefficients
        self.coef = np.array([c["alpha_m"], c["alpha_f"], c["beta"], c["gamma"]], dtype=float)
        self.newton = newton
        self.inewton = np.zeros(10, np.int64)
        self.inewton[I_MASS_SPLIT] = int(same_component_only(self.data[6]))
        self.inewton[I_SCHEME] = DISCRETE_GRADIENT if discrete_gradient else ALPHA_FAMILY
        self.inewton[I_MAX_IT] = max_iterations
        self.inewton[I_MODIFIED] = int(newton != "full")
        self.inewton[I_STOP] = STOP_BOTH if newton == "full" else STOP_RESIDUAL
        self.inewton[I_MAX_MODIFIED] = MAX_MODIFIED
        self.inewton[I_JAC_PER_STEP] = int(newton in ("chord", "linear"))
        self.inewton[I_LINEAR] = int(newton == "linear")
        self.inewton[I_FORCES_AT_ENDS] = int(forces_at_ends)
        self.fnewton = np.zeros(5)
        self.fnewton[F_RTOL], self.fnewton[F_UTOL] = rtol, utol
        self.fnewton[F_KAPPA], self.fnewton[F_HBEAM] = KAPPA, float(model.mesh.height)
        self.reset()

    def reset(self):
        """A new run: no factorisation kept, counters at zero."""
        self.S = np.zeros((self.n, self.b + 1))
        self.fstate = np.zeros(2)
        self.counters = np.zeros(len(COUNTER_NAMES), np.int64)

    @property
    def stats(self) -> dict:
        return dict(zip(COUNTER_NAMES, (int(x) for x in self.counters)))

    def initial_acceleration(self, u: np.ndarray) -> np.ndarray | None:
        """a0 from M a0 = f_ext - f_int(u) on the free dofs (:func:`start`); None if
        det F <= 0 at u or M is singular (the caller's Python route names why)."""
        a = np.empty(self.n)
        dN, w, dofs, ops, consts, pr, Mc, first, f_ext, _, fixed = self.data
        if start(np.ascontiguousarray(u, dtype=float), dN, w, dofs, ops, consts, pr, Mc, first, f_ext, fixed,
                 a) != OK:
            return None
        return a

    def energies(self, u: np.ndarray, v: np.ndarray) -> tuple[float, float]:
        """(kinetic, strain) energy (J) (:func:`energies`); strain nan if det F <= 0."""
        return observed_energies(np.ascontiguousarray(u, dtype=float), np.ascontiguousarray(v, dtype=float),
                                 *self.data[:8])

    def advance(self, s: time_loop.State, h: float, t_out: float, dt: float, budget: int, offset: int = 0,
                energy_every: int = 0, energy_max: float = math.inf) -> Advanced:
        """From state s with next step h towards t_out (:func:`advance`); s is not changed."""
        u, v, a = (np.array(x, dtype=float) for x in (s.u, s.v, s.a))
        tstate = np.array([s.t, h, 0.0, math.nan, -math.inf])
        self.inewton[I_ENERGY_EVERY] = energy_every
        self.fnewton[F_ELIMIT] = energy_max
        it0 = int(self.counters[C_ITERATIONS])
        status = advance(*self.data, self.coef, self.inewton, self.fnewton, u, v, a, tstate, float(t_out),
                         float(dt), int(budget), int(offset), self.S, self.fstate, self.counters)
        state = time_loop.State(float(tstate[0]), u, v, a)
        outcome = {OK: "landed", BUDGET: "budget", ENERGY_GROWTH: "energy-growth"}.get(status, "rejected")
        return Advanced(outcome, state, float(tstate[1]), int(tstate[2]), int(self.counters[C_ITERATIONS]) - it0,
                        float(tstate[3]), STATUS.get(status), float(tstate[4]))
