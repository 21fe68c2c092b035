"""Static equilibrium: Newton's method with adaptive load stepping.

The load path follows the one rule of :mod:`mechanics.load_path` (shared with the continuum
solver); :func:`increment_solver` is ANCF's attempt of one increment.
:func:`solve_static` runs the whole job:

1. if the formulation is not stress-free (``paper``), relax to the unloaded equilibrium
   along the homotopy f_int(u) = (1 - t) f_int(0), t: 0 -> 1;
2. load along f_int(u) = t Q_K, t: 0 -> 1, from the relaxed state;
3. check the converged state for stability (:mod:`ancf.solvers.stability`); if it
   is unstable, perturb along the unstable mode and re-solve, and say so.

An increment whose Newton fails (or meets an inadmissible state) is retried from the
last state with a line search, then (once the increment is small) by a shifted-Newton
energy descent, and only then cut by the load-path rule.

The Newton iterations run compiled (:mod:`ancf.solvers.compiled_statics`); :func:`newton_reference`
(the shared loop :func:`mechanics.newton.newton` on this system) is what they reproduce
and are tested against. The residual tolerance never
lies below the force's own round-off (:data:`ROUNDOFF_FLOOR`).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from mechanics.load_path import Attempt, PathCounts, PathFailure, follow
from mechanics.newton import newton as newton_loop
from mechanics.time_loop import StepFailure

from mechanics.end_rotation import continued

from . import compiled_statics
from ..kinematics.section.model import BeamModel, InadmissibleState
from .couple import Loading, as_loading
from .stability import check_stability


@dataclass
class NewtonResult:
    u: np.ndarray
    converged: bool
    iterations: int
    residuals: list[float]
    reason: str | None = None


def newton(model: BeamModel, u0: np.ndarray, target: Loading, atol: float,
           max_iterations: int, utol: float = 1e-9, line_search: bool = False) -> NewtonResult:
    """Solve f_int(u) = f_ext(u) (``target``, :class:`ancf.solvers.couple.Loading`) on the free dofs,
    starting at u0 (fixed dofs stay as in u0):
    :func:`newton_reference`'s iteration, compiled (:mod:`ancf.solvers.compiled_statics`). An attempt
    whose unpivoted LDL^T meets a zero pivot is redone by :func:`newton_reference`, whose
    pivoted LU decides whether the tangent is singular. A model the compiled loop cannot
    run (:attr:`ancf.kinematics.section.model.BeamModel.compiled`) goes to :func:`newton_reference` at once."""
    target = as_loading(target)
    if not model.compiled:
        return newton_reference(model, u0, target, atol, max_iterations, utol, line_search)
    outcome, u, its, residuals = model.static_kernel.newton(u0, target, atol, max_iterations, utol, line_search)
    if outcome == compiled_statics.CONVERGED:
        return NewtonResult(u, True, its, residuals)
    if outcome != compiled_statics.UNPIVOTED:
        return NewtonResult(u, False, its, residuals, compiled_statics.REASONS[outcome])
    return newton_reference(model, u0, target, atol, max_iterations, utol, line_search)


def newton_reference(model: BeamModel, u0: np.ndarray, target: Loading, atol: float,
                     max_iterations: int, utol: float = 1e-9, line_search: bool = False) -> NewtonResult:
    """Solve f_int(u) = f_ext(u) on the free dofs, starting at u0 (fixed dofs stay as in u0).

    Converged when the residual norm is at most ``atol`` (N), or when the last Newton
    correction is negligible, ||du||_inf <= utol max(||u||_inf, h) (the error after it
    is of order du^2). The residual has a round-off floor that can lie above any fixed
    force tolerance: about eps ||K|| ||u|| with a stiff penalty (measured 6e-10 N at
    alpha = 10 C10, 4e-6 N at 1e5 C10, 160 elements) and eps mu A / l_e from the
    cancellation in P = 2 W_a F + W_J cof F at small loads (1e-13 N measured, where the
    correction then stalls at 2e-10 of |u|).

    With ``line_search``, each step du is scaled by s from the slope
    g(s) = R(u + s du) . du (the potential's derivative along du; slopes, unlike
    energy differences, carry no cancellation): s = 1 if |g(1)| <= |g(0)| / 2, else a
    root of g by safeguarded regula falsi (at most 8 force evaluations).
    """
    system = _StaticSystem(model, u0, as_loading(target), utol, line_search)
    try:
        its, _ = newton_loop(system, 1.0, atol, max_iterations, system.small_correction, diverging=1e3)
        return NewtonResult(system.u, True, its, system.residuals)
    except InadmissibleState as e:
        return NewtonResult(system.u, False, len(system.residuals), system.residuals, f"inadmissible state ({e})")
    except StepFailure as e:
        # the compiled twin's words (compiled_statics.REASONS) for the same outcomes
        reason = "no convergence within max_iterations" if str(e).startswith("no convergence") else str(e)
        return NewtonResult(system.u, False, e.iterations, system.residuals, reason)


class _StaticSystem:
    """f_int(u) = f_ext(u) on the free dofs as a system of :func:`mechanics.newton.newton`
    (tolerance: ||R|| <= atol with r_ref = 1)."""

    def __init__(self, model: BeamModel, u0: np.ndarray, target: Loading, utol: float, line_search: bool):
        self.model, self.target, self.utol, self.line_search = model, target, utol, line_search
        self.free = np.ones(model.mesh.n_dof, bool)
        self.free[model.fixed] = False
        self.u = u0.copy()
        self.residuals: list[float] = []
        self.updates = 0

    def residual_norm(self) -> float:
        R, self.K = self.target.out_of_balance_and_tangent(self.model, self.u)
        self.R = np.where(self.free, R, 0.0)
        r = float(np.linalg.norm(self.R))
        self.residuals.append(r)
        return r

    def newton_update(self) -> float:
        try:
            du = self.K.constrain(self.model.fixed).solve(-self.R)
        except np.linalg.LinAlgError:
            raise ArithmeticError("singular tangent") from None
        if not np.all(np.isfinite(du)):
            raise ArithmeticError("singular tangent")
        if self.line_search:
            du = du * _line_search(self.model, self.u, du, self.target, self.R, self.free)
        self.u = self.u + du
        self.updates += 1
        self.du_max = float(np.abs(du).max())
        return self.du_max

    def small_correction(self, system, r: float, dw: float) -> bool:
        """From the second correction on: ||du||_inf <= utol max(||u||_inf, h); the
        residual after it is recorded (the confirming evaluation)."""
        if self.updates >= 2 and self.du_max <= self.utol * max(np.abs(self.u).max(), self.model.mesh.height):
            self.residuals.append(float(np.linalg.norm(
                np.where(self.free, self.target.out_of_balance(self.model, self.u), 0.0))))
            return True
        return False


def _line_search(model, u, du, target, R0, free) -> float:
    g0 = float(R0 @ du)
    if g0 >= 0:                      # not a descent direction (indefinite K): full step
        return 1.0

    def g(s):
        try:
            return float(np.where(free, target.out_of_balance(model, u + s * du), 0.0) @ du)
        except InadmissibleState:
            return np.inf
    g1 = g(1.0)
    if abs(g1) <= 0.5 * abs(g0):
        return 1.0
    lo, glo, hi, ghi = 0.0, g0, 1.0, g1
    if ghi < 0:                      # still descending at s = 1: take the full step
        return 1.0
    for _ in range(8):
        s = hi - ghi * (hi - lo) / (ghi - glo) if np.isfinite(ghi) else 0.5 * (lo + hi)
        s = min(max(s, lo + 0.1 * (hi - lo)), hi - 0.1 * (hi - lo))
        gs = g(s)
        if abs(gs) <= 0.5 * abs(g0):
            return s
        lo, glo, hi, ghi = (s, gs, hi, ghi) if gs < 0 else (lo, glo, s, gs)
    return lo if lo > 0 else 0.5 * hi


# The residual tolerance is at least this many times eps |f_int|_terms (the internal force
# assembled from the magnitudes of its terms, ancf.solvers.compiled_statics.StaticKernel.roundoff_floor,
# at the reference state): the residual's round-off. Measured on slender cantilevers
# (L/h 70 and 140, gravity scaled to the linear regime, where rtol |f_ext| is 1e-15 N):
# Newton's residual stalls at 0.2 (pivoted LU) to 1.1 (compiled loop) times that
# estimate, above rtol |f_ext|; 10 leaves a margin.
ROUNDOFF_FLOOR = 10.0

# The energy descent retries only increments at most this large (of the whole path);
# larger failing increments are cut first, which is cheaper.
DESCENT_BELOW = 1e-2


# An accepted increment may turn the end face by at most this much (rad): the face's
# rotation is continued from one equilibrium to the next (mechanics.end_rotation.continued), which
# is unambiguous below pi; a larger turn is cut like a failed increment.
MAX_TURN = 0.5 * np.pi


def increment_solver(model: BeamModel, target: Callable[[float], Loading], u0: np.ndarray,
                     atol: float, max_iterations: int, theta0: float = 0.0):
    """The ANCF attempt of one load increment for :func:`mechanics.load_path.follow`, and the
    state it keeps: from the last accepted u, Newton from a secant predictor; if it
    fails, Newton with a line search from u; if that fails on a small increment, the
    shifted-Newton energy descent. Returns (solve, state) with state["u"] the last
    accepted equilibrium and, with an end couple, state["theta"] its end face's rotation
    continued from ``theta0`` at u0."""
    state = {"u": u0, "du_prev": None, "theta": theta0}

    def solve(t0: float, t1: float) -> Attempt:
        u, prev, dt = state["u"], state["du_prev"], t1 - t0
        loading = as_loading(target(t1))
        guess = u if prev is None else u + prev[1] * (dt / prev[0])
        res = newton(model, guess, loading, atol, max_iterations)
        if not res.converged:        # retry from the last state with a line search
            retry = newton(model, u, loading, atol, max_iterations, line_search=True)
            retry.iterations += res.iterations
            res = retry
        if not res.converged and dt <= DESCENT_BELOW:
            # a small increment that still fails is not a step-size problem (e.g. an
            # indefinite tangent): descend the potential before cutting further
            retry = _descend(model, u, loading, atol, 4 * max_iterations)
            retry.iterations += res.iterations
            res = retry
        if res.converged and loading.face is not None:
            face = loading.face
            theta = continued(state["theta"], face.first_moment(u), face.first_moment(res.u))
            if abs(theta - state["theta"]) > MAX_TURN:
                return Attempt(False, res.iterations, f"the end face turned {abs(theta - state['theta']):.3g} rad "
                                                      f"in one increment (more than {MAX_TURN:.3g})")
            state["theta"] = theta
        if res.converged:
            state["du_prev"], state["u"] = (dt, res.u - u), res.u
        return Attempt(res.converged, res.iterations, res.reason)

    return solve, state


@dataclass
class StaticResult:
    u: np.ndarray | None
    status: str                    # "converged" | "failed"
    reason: str | None
    newton_iterations: int
    load_steps: int                # accepted increments (relaxation and loading)
    rejected_steps: int
    relax_steps: int
    stable: bool | None
    stability: str | None          # what the stability check found and did
    negative_eigenvalues: int | None = None   # of the final state's tangent (inertia count)
    cpu_s: float = 0.0
    wall_s: float = 0.0
    lowest_eigenvalue: float | None = None    # of the final state's Jacobi-scaled constrained tangent
    rotation: float | None = None             # of the end face (rad), continued, with an end couple


def solve_static(model: BeamModel, loads: Loading | np.ndarray, load_steps: int = 10,
                 rtol: float = 1e-8, max_iterations: int = 25, wall_time: float | None = None) -> StaticResult:
    """The equilibrium under ``loads`` (a :class:`ancf.solvers.couple.Loading`, or a dead load vector
    Q in N), reached along t: 0 -> 1 (see the module doc)."""
    wall0, cpu0 = time.perf_counter(), time.process_time()
    loads = as_loading(loads)
    deadline = None if wall_time is None else wall0 + wall_time
    free = np.ones(model.mesh.n_dof, bool)
    free[model.fixed] = False
    u = np.zeros(model.mesh.n_dof)
    counts = PathCounts()
    n_relax = 0
    f0 = np.where(free, model.internal_force(u), 0.0)
    f_ext = loads.force(u)
    scale = max(np.linalg.norm(f_ext[free]), np.linalg.norm(f0), 1e-30)
    # never below the force's round-off (small loads on a stiff section: rtol |f_ext|
    # can lie under it, and then only luck in the last digits converges)
    atol = max(rtol * scale, ROUNDOFF_FLOOR * model.roundoff_floor(u))

    theta = None if loads.face is None else loads.face.rotation(u)

    def finish(status, reason, u, verdict=None, stability=None):
        return StaticResult(u, status, reason, counts.newton_iterations, counts.accepted,
                            counts.rejected, n_relax, verdict and verdict.stable, stability,
                            verdict and verdict.negative, time.process_time() - cpu0,
                            time.perf_counter() - wall0, verdict and verdict.lowest, theta)

    phases = []
    if np.linalg.norm(f0) > atol:
        phases.append(("relax", lambda t: Loading(f0 * (1.0 - t)), 1))
    if np.linalg.norm(f_ext[free]) > 0:
        phases.append(("load", loads.scaled, load_steps))
    try:
        for phase, target, steps in phases:
            solve, state = increment_solver(model, target, u, atol, max_iterations, theta or 0.0)
            for _ in follow(solve, steps, counts, phase, deadline=deadline):
                n_relax += phase == "relax"
            u = state["u"]
            theta = None if loads.face is None else (loads.face.rotation(u) if phase == "relax" else state["theta"])
    except PathFailure as e:
        return finish("failed", e.reason, None)

    verdict = check_stability(model, u, loads)
    note = first = None if verdict.kind == "stable" else verdict.describe()
    tries = 0
    while verdict.kind == "unstable" and tries < 3:
        tries += 1
        u_new = _escape(model, u, verdict.mode, loads, atol, max_iterations, counts)
        if u_new is None:
            break
        if loads.face is not None:
            theta = continued(theta, loads.face.first_moment(u), loads.face.first_moment(u_new))
        u = u_new
        verdict = check_stability(model, u, loads)
        note = (f"Newton converged to an unstable equilibrium ({first}); perturbed along the "
                f"unstable mode and descended to {verdict.describe()} ({tries} time(s))")
    return finish("converged", None, u, verdict, note)


def relax(model: BeamModel, rtol: float = 1e-8, max_iterations: int = 25,
          wall_time: float | None = None) -> StaticResult:
    """The unloaded equilibrium of a formulation that is not stress-free.

    A pinned beam's relaxation is singular (rigid rotation about the pin), so the tip's
    y position is held while relaxing: in the uniform contraction of a straight beam it
    carries no reaction (checked: the reaction is returned in the result's reason when it
    is not negligible)."""
    m = model.mesh
    hold = m.dofs(m.n_nodes - 1, ["r"])[1:2]
    held = replace(model, fixed=np.union1d(model.fixed, hold))
    res = solve_static(held, np.zeros(m.n_dof), rtol=rtol, max_iterations=max_iterations, wall_time=wall_time)
    if res.u is not None:
        reaction = abs(held.internal_force(res.u)[hold[0]])
        scale = np.abs(held.internal_force(np.zeros(m.n_dof))).max()
        if reaction > 1e-6 * scale:
            res.status, res.reason = "failed", f"held dof carries a reaction {reaction:.3g} N"
    return res


def potential(model: BeamModel, u: np.ndarray, loads: Loading | np.ndarray, theta: float | None = None) -> float:
    """Total potential energy U(u) - Q_K . u - M theta (J); theta continued along the path
    where the caller has it (:meth:`ancf.solvers.couple.Loading.potential`)."""
    return model.strain_energy(u) + as_loading(loads).potential(u, theta)


def _escape(model, u, mode, f_ext: Loading, atol, max_iterations, counts: PathCounts) -> np.ndarray | None:
    """From u, move along +- the unstable mode and descend the potential energy to a
    minimum; keep the end state of lower energy (None if neither side converges).

    Plain Newton would return to the saddle it started next to. Energy differences near
    a saddle are below the round-off of the energy itself, so the search along the mode
    uses slopes g = (f_int - Q_K) . d, which are accurate: the step doubles (from
    1e-3 h up to the beam's length) while g < 0 and the sign change is bisected; then
    :func:`_descend` finishes.
    """
    mode = mode / max(np.abs(mode).max(), 1e-300)
    free = np.ones(model.mesh.n_dof, bool)
    free[model.fixed] = False

    def slope(v, d):
        return float(np.where(free, f_ext.out_of_balance(model, v), 0.0) @ d)

    best = None
    for sign in (1.0, -1.0):
        d = sign * mode
        lo, hi, a = 0.0, None, 1e-3 * model.mesh.height
        while a < model.mesh.length:
            try:
                g = slope(u + a * d, d)
            except InadmissibleState:
                hi = a
                break
            if g > 0 and lo > 0:
                hi = a
                break
            lo, a = a, 2 * a
        for _ in range(40 if hi is not None else 0):
            mid = 0.5 * (lo + hi)
            try:
                g = slope(u + mid * d, d)
            except InadmissibleState:
                g = 1.0
            lo, hi = (mid, hi) if g < 0 else (lo, mid)
        res = _descend(model, u + lo * d, f_ext, atol, 20 * max_iterations)
        counts.newton_iterations += res.iterations
        if res.converged:
            e = potential(model, res.u, f_ext, None if f_ext.face is None else
                          continued(0.0, f_ext.face.first_moment(u), f_ext.face.first_moment(res.u)))
            if best is None or e < best[0]:
                best = (e, res.u)
    return None if best is None else best[1]


def _descend(model, v, f_ext: Loading, atol, max_iterations) -> NewtonResult:
    """Shifted Newton descent to a minimum of the potential: (K + sigma |diag K|) du = -R
    with sigma raised (x 10 from 1e-12) until the matrix is positive definite, and lowered
    10x each iteration, and a backtracking line search whose decrease is measured from
    slopes as s/2 (g(0) + g(s)) (energy differences would drown in round-off). Converges
    from where plain Newton diverges, e.g. where the tangent is indefinite; near a minimum
    sigma falls to 0 and the convergence is Newton's again. Bounded: any sigma above
    ||D^-1/2 K D^-1/2||_inf gives a positive definite matrix, so at most ~20 raises are
    ever tried; the line search halves at most 27 times."""
    free = np.ones(model.mesh.n_dof, bool)
    free[model.fixed] = False

    def slope(w, d):
        return float(np.where(free, f_ext.out_of_balance(model, w), 0.0) @ d)

    sigma, residuals = 0.0, []
    try:
        for it in range(max_iterations):
            R, K = f_ext.out_of_balance_and_tangent(model, v)
            R = np.where(free, R, 0.0)
            residuals.append(float(np.linalg.norm(R)))
            if residuals[-1] <= atol:
                return NewtonResult(v, True, it, residuals)
            K = K.constrain(model.fixed)
            top = 2.0 * K.scaled_norm()           # positive definite for any shift above half of it
            sigma = sigma / 10 if sigma > 1e-12 else 0.0
            du = K.solve_shifted(-R, sigma)
            while du is None and sigma < top:
                sigma = min(max(10 * sigma, 1e-12), top)
                du = K.solve_shifted(-R, sigma)
            if du is None or not np.all(np.isfinite(du)):
                return NewtonResult(v, False, it, residuals, "descent: no positive definite shift "
                                                             "(non-finite tangent)")
            g0, step = float(R @ du), 1.0
            while step > 1e-8:
                try:
                    gs = slope(v + step * du, du)
                    if 0.5 * step * (g0 + gs) <= 1e-4 * step * g0:
                        break
                except InadmissibleState:
                    pass
                step *= 0.5
            v = v + step * du
            if sigma == 0.0 and np.abs(step * du).max() <= 1e-9 * max(np.abs(v).max(), model.mesh.height):
                return NewtonResult(v, True, it + 1, residuals)
    except InadmissibleState as e:
        return NewtonResult(v, False, len(residuals), residuals, f"inadmissible state ({e})")
    return NewtonResult(v, False, max_iterations, residuals, "descent did not converge")
