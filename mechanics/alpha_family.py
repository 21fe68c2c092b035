"""The generalized-alpha family of both solvers: coefficients, predictor and update.

Chung and Hulbert's method (``generalized-alpha``) solves

    M a_(n+1-alpha_m) + f_int(u_(n+1-alpha_f)) = Q,  x_(n+1-alpha) = (1 - alpha) x_(n+1) + alpha x_n,

with Newmark's relations between u, v and a (beta, gamma). Arnold and Bruls's form
(``arnold-bruls``, the default of a scene) has the same coefficients and takes the
equations of motion at t_(n+1), M acc_(n+1) + f_int(u_(n+1)) = Q, with a the
pseudo-acceleration, (1 - alpha_m) a_(n+1) + alpha_m a_n = (1 - alpha_f) acc_(n+1) +
alpha_f acc_n; with M acc_k = Q - f_int(u_k) at both ends of the step that is

    M a_(n+1-alpha_m) + (1 - alpha_f) f_int(u_(n+1)) + alpha_f f_int(u_n) = Q:

the forces at configurations the body passes through (:data:`FORCES_AT_ENDS`), never at
the chord u_(n+1-alpha_f) between two rotated configurations, which is strained. Written once here and used by
ANCF's Python steppers (:mod:`ancf.solvers.integrators`), its compiled step
(:mod:`ancf.solvers.compiled_steps`, which compiles :func:`predict` and :func:`update` as they
are) and the continuum's stepper (:mod:`reference_fem.stepper`). The functions are
plain arithmetic, so they run on numpy arrays and, compiled by numba, on floats.
"""
from __future__ import annotations

from contract.errors import UnknownName


def generalized_alpha(rho_inf: float) -> dict:
    """alpha_m = (2 rho_inf - 1)/(rho_inf + 1), alpha_f = rho_inf/(rho_inf + 1),
    gamma = 1/2 - alpha_m + alpha_f, beta = (1 - alpha_m + alpha_f)^2 / 4: second order,
    high-frequency dissipation set by rho_inf (the spectral radius at infinity)."""
    am = (2 * rho_inf - 1) / (rho_inf + 1)
    af = rho_inf / (rho_inf + 1)
    return {"alpha_m": am, "alpha_f": af, "gamma": 0.5 - am + af, "beta": 0.25 * (1 - am + af) ** 2}


def newmark(rho_inf: float = 1.0) -> dict:
    """Newmark's average acceleration (gamma = 1/2, beta = 1/4, no alpha terms; rho_inf
    does not apply): energy-conserving for linear problems, no numerical dissipation."""
    return {"alpha_m": 0.0, "alpha_f": 0.0, "gamma": 0.5, "beta": 0.25}


def arnold_bruls(rho_inf: float) -> dict:
    """Chung and Hulbert's coefficients (:func:`generalized_alpha`); the steppers take the
    forces at the step's ends (:data:`FORCES_AT_ENDS`). Source: M. Arnold and O. Bruls
    (2007), Convergence of the generalized-alpha scheme for constrained mechanical
    systems, Multibody Syst. Dyn. 18, 185-202."""
    return generalized_alpha(rho_inf)


# the methods of the family, by the name scenes give them
METHODS = {"arnold-bruls": arnold_bruls, "generalized-alpha": generalized_alpha, "newmark": newmark}
# the methods whose step takes the forces at u_n and u_(n+1), weighted alpha_f and 1 - alpha_f
# (the multiplier of a constraint with them: each end's own), instead of at u_(n+1-alpha_f)
FORCES_AT_ENDS = frozenset({"arnold-bruls"})


def coefficients(method: str, rho_inf: float) -> dict:
    """{alpha_m, alpha_f, gamma, beta} of ``method`` at ``rho_inf``."""
    try:
        return METHODS[method](rho_inf)
    except KeyError:
        raise UnknownName("analysis.integrator", method, METHODS) from None


def predict(u, v, a, h):
    """The predictor a_(n+1) = a_n: u_pred = u_n + h v_n + h^2 a_n / 2."""
    return u + h * v + 0.5 * h * h * a


def update(u, u_pred, v, a, h, beta, gamma):
    """(a_(n+1), v_(n+1)) of the converged u_(n+1) by Newmark's relations:
    a_(n+1) = a_n + (u_(n+1) - u_pred) / (beta h^2), v_(n+1) = v_n + h ((1 - gamma) a_n + gamma a_(n+1))."""
    a_new = (u - u_pred) / (beta * h * h) + a
    return a_new, v + h * ((1.0 - gamma) * a + gamma * a_new)


def midpoint(u, u_new, v, h):
    """The step's midpoint relations (discrete gradient, trapezoidal rule):
    v_(n+1) = 2 (u_(n+1) - u_n) / h - v_n and a_(n+1) = (v_(n+1) - v_n) / h."""
    v_new = 2.0 / h * (u_new - u) - v
    return (v_new - v) / h, v_new
