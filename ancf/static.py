"""Static equilibrium: Newton's method with adaptive load stepping.

The path is a generator (:func:`load_path`): it yields each accepted increment, so a
caller can watch, record or stop it. :func:`solve_static` runs the whole job:

1. if the formulation is not stress-free (``paper``), relax to the unloaded equilibrium
   along the homotopy f_int(u) = (1 - t) f_int(0), t: 0 -> 1;
2. load along f_int(u) = t Q_K, t: 0 -> 1, from the relaxed state;
3. check the converged state for stability (Cholesky of the constrained tangent); if it
   is unstable, perturb along the unstable mode and re-solve, and say so.

Increments are cut (x 1/2) when Newton fails or meets an inadmissible state, and grown
(x 1.5) after easy convergence; below ``min_step`` the run fails with a reason.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable, Iterator

import numpy as np

from .model import BeamModel, InadmissibleState


@dataclass
class NewtonResult:
    u: np.ndarray
    converged: bool
    iterations: int
    residuals: list[float]
    reason: str | None = None


def newton(model: BeamModel, u0: np.ndarray, target: np.ndarray, atol: float,
           max_iterations: int) -> NewtonResult:
    """Solve f_int(u) = target on the free dofs, starting at u0 (fixed dofs stay as in u0)."""
    free = np.ones(model.mesh.n_dof, bool)
    free[model.fixed] = False
    u = u0.copy()
    residuals: list[float] = []
    try:
        for it in range(max_iterations + 1):
            f, K = model.internal_force_and_tangent(u)
            R = np.where(free, f - target, 0.0)
            r = float(np.linalg.norm(R))
            residuals.append(r)
            if not np.isfinite(r):
                return NewtonResult(u, False, it, residuals, "non-finite residual")
            if r <= atol:
                return NewtonResult(u, True, it, residuals)
            if it == max_iterations:
                break
            if it >= 3 and r > 1e3 * residuals[0]:
                return NewtonResult(u, False, it, residuals, "diverging")
            du = K.constrain(model.fixed).solve(-R)
            if not np.all(np.isfinite(du)):
                return NewtonResult(u, False, it, residuals, "singular tangent")
            u = u + du
    except InadmissibleState as e:
        return NewtonResult(u, False, len(residuals), residuals, f"inadmissible state ({e})")
    return NewtonResult(u, False, max_iterations, residuals, "no convergence within max_iterations")


@dataclass
class Increment:
    phase: str          # "relax" | "load"
    t: float            # path parameter reached, 0..1
    u: np.ndarray
    iterations: int
    residuals: list[float]


@dataclass
class PathFailure(Exception):
    phase: str
    t: float
    reason: str


def load_path(model: BeamModel, target: Callable[[float], np.ndarray], u0: np.ndarray,
              phase: str, steps: int, atol: float, max_iterations: int,
              min_step: float = 1e-6, stats: dict | None = None) -> Iterator[Increment]:
    """Follow f_int(u) = target(t) from t = 0 (u0 in equilibrium) to t = 1."""
    stats = stats if stats is not None else {}
    stats.setdefault("rejected_steps", 0)
    t, dt, u, du_prev = 0.0, 1.0 / steps, u0, None
    while t < 1.0 - 1e-14:
        dt = min(dt, 1.0 - t)
        guess = u if du_prev is None else u + du_prev[1] * (dt / du_prev[0])
        res = newton(model, guess, target(t + dt), atol, max_iterations)
        if not res.converged and du_prev is not None:  # retry without the predictor
            retry = newton(model, u, target(t + dt), atol, max_iterations)
            retry.iterations += res.iterations
            res = retry
        stats["newton_iterations"] = stats.get("newton_iterations", 0) + res.iterations
        if not res.converged:
            stats["rejected_steps"] += 1
            dt *= 0.5
            if dt < min_step:
                raise PathFailure(phase, t, f"load increment below {min_step:g} at t = {t:.6g} "
                                            f"({phase}): {res.reason}")
            continue
        du_prev = (dt, res.u - u)
        t, u = t + dt, res.u
        stats["accepted"] = stats.get("accepted", 0) + 1
        yield Increment(phase, t, u, res.iterations, res.residuals)
        if res.iterations <= 4:
            dt *= 1.5


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
    increments: list[Increment] = field(default_factory=list)
    cpu_s: float = 0.0
    wall_s: float = 0.0


def solve_static(model: BeamModel, f_ext: np.ndarray, load_steps: int = 10,
                 rtol: float = 1e-8, max_iterations: int = 25,
                 keep_increments: bool = False) -> StaticResult:
    wall0, cpu0 = time.perf_counter(), time.process_time()
    free = np.ones(model.mesh.n_dof, bool)
    free[model.fixed] = False
    u = np.zeros(model.mesh.n_dof)
    stats: dict = {}
    increments: list[Increment] = []
    n_relax = 0
    f0 = np.where(free, model.internal_force(u), 0.0)
    scale = max(np.linalg.norm(f_ext[free]), np.linalg.norm(f0), 1e-30)
    atol = rtol * scale

    def finish(status, reason, u, stable=None, stability=None):
        return StaticResult(u, status, reason, stats.get("newton_iterations", 0),
                            stats.get("accepted", 0), stats.get("rejected_steps", 0), n_relax,
                            stable, stability, increments,
                            time.process_time() - cpu0, time.perf_counter() - wall0)

    phases = []
    if np.linalg.norm(f0) > atol:
        phases.append(("relax", lambda t: f0 * (1.0 - t), 1))
    if np.linalg.norm(f_ext[free]) > 0:
        phases.append(("load", lambda t: f_ext * t, load_steps))
    try:
        for phase, target, steps in phases:
            for inc in load_path(model, target, u, phase, steps, atol, max_iterations, stats=stats):
                n_relax += phase == "relax"
                if keep_increments:
                    increments.append(inc)
                u = inc.u
    except PathFailure as e:
        return finish("failed", e.reason, None)

    stable, note = check_stability(model, u)
    tries = 0
    while not stable and tries < 3:
        tries += 1
        mode = unstable_mode(model, u)
        amp = 1e-3 * model.mesh.length / max(np.abs(mode).max(), 1e-300)
        res = newton(model, u + amp * mode, f_ext, atol, max_iterations)
        stats["newton_iterations"] = stats.get("newton_iterations", 0) + res.iterations
        if res.converged:
            u = res.u
            stable, _ = check_stability(model, u)
        note = (f"Newton converged to an unstable equilibrium; perturbed along the unstable "
                f"mode and re-solved {tries} time(s): {'stable' if stable else 'still unstable'}")
    return finish("converged", None, u, stable, note)


def check_stability(model: BeamModel, u: np.ndarray) -> tuple[bool, str | None]:
    """Is the constrained tangent at u positive definite? (banded Cholesky)"""
    _, K = model.internal_force_and_tangent(u)
    ok = K.constrain(model.fixed).is_positive_definite()
    return ok, None if ok else "tangent not positive definite"


def unstable_mode(model: BeamModel, u: np.ndarray) -> np.ndarray:
    """Eigenvector of the lowest eigenvalue of the constrained tangent at u."""
    from scipy.sparse.linalg import eigsh

    _, K = model.internal_force_and_tangent(u)
    A = K.constrain(model.fixed).to_sparse()
    vals, vecs = eigsh(A, k=min(6, A.shape[0] - 2), sigma=0.0, which="LM")
    mode = vecs[:, int(np.argmin(vals))]
    mode[model.fixed] = 0.0
    return mode
