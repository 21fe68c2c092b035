"""The generalized-alpha family of both solvers: coefficients, predictor and update.

Chung and Hulbert's method solves

    M a_(n+1-alpha_m) + f_int(u_(n+1-alpha_f)) = Q,  x_(n+1-alpha) = (1 - alpha) x_(n+1) + alpha x_n,

with Newmark's relations between u, v and a (beta, gamma). Written once here and used by
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


# the methods of the family, by the name scenes give them
METHODS = {"generalized-alpha": generalized_alpha, "newmark": newmark}


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
