"""Manufactured solutions for both continuum backends: the exact fields and their sources.

Code verification in the field's standard (Roy 2005; ASME V&V 10): on the unit square
(2D) or cube (3D) a smooth displacement u*(X) and, for the models with a pressure field,
a smooth scaled pressure phat*(X) (p* = mu phat*) are made the exact solution of

    Div P(u*, phat*) + b = 0,        dW/dphat (u*, phat*) = mu g,       u = u* on the boundary,

with W(F, phat) = psi(invariants of the model) [+ mu phat (J - 1)] [- (mu phat)^2 / (2 alpha)]
the backends' energy (:mod:`reference_fem.dolfinx_backend.models`,
:mod:`reference_fem.felupe_backend.problem`), built here a third time, in sympy, from the
shared law table (:mod:`mechanics.laws`, run on sympy symbols with ``m.log = sympy.log``):

- P = dW/dF and the tangent dP/dF, dP/dphat are differentiated symbolically in the
  entries of F and phat; the body force is their chain rule through the manufactured
  fields, b_i = -(dP_ij/dF_kl d^2u_k/dX_l dX_j + dP_ij/dphat dphat/dX_j), every factor
  exact (no expression in X is differentiated twice over the law);
- the constraint source g = J(u*) - 1 [- mu phat* / alpha]: the discrete constraint row
  int (dW/dphat - mu g) q dV = 0 then holds at the exact fields.

Models (:data:`MODELS`): ``plane-strain`` (F3 = diag(F, 1), isochoric invariants, mixed:
exactly incompressible with a Taylor-Hood pressure), ``plane-strain-penalty`` (the same
with the perturbed-Lagrangian penalty alpha), ``plane-stress`` (F3 = diag(F, 1/J),
displacement only), ``3d`` (full C, isochoric, mixed). The backends' solvers of these
problems and their L2 errors: :mod:`reference_fem.dolfinx_backend.manufactured`,
:mod:`reference_fem.felupe_backend.manufactured`; :func:`observed_orders` turns errors into orders.

Expected orders (Q2 displacement, Q1 pressure, smooth solution, exact boundary values):
3 for the L2 error of u, 2 for the L2 error of p (Taylor-Hood's a priori estimate with
the duality argument for u; Brezzi-Fortin).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from types import SimpleNamespace
from typing import Callable

import numpy as np

from contract.errors import UnknownName
from mechanics.laws import get_law


@dataclass(frozen=True)
class MmsModel:
    name: str
    dim: int
    has_pressure: bool
    penalty: bool
    invariants: str      # "isochoric" | "plane-stress"


MODELS = {m.name: m for m in (
    MmsModel("plane-strain", 2, True, False, "isochoric"),
    MmsModel("plane-strain-penalty", 2, True, True, "isochoric"),
    MmsModel("plane-stress", 2, False, False, "plane-stress"),
    MmsModel("3d", 3, True, False, "isochoric"),
)}

# the a priori L2 orders of Q2 (displacement) / Q1 (pressure) elements
EXPECTED_ORDER = {"u": 3.0, "p": 2.0}
AMPLITUDE = 0.1     # of the manufactured displacement (m on the unit domain): strains ~ 0.3


def get_model(name: str) -> MmsModel:
    try:
        return MODELS[name]
    except KeyError:
        raise UnknownName("mms.model", name, MODELS) from None


def exact_fields(dim: int, amplitude: float = AMPLITUDE):
    """Sympy symbols X and the manufactured u*(X) (list), phat*(X): smooth, not zero on
    the boundary, not divergence-free (the constraint source carries J - 1), J > 0."""
    import sympy as sp

    X = sp.symbols(f"X0:{dim}", real=True)
    a, pi = sp.Float(amplitude), sp.pi
    if dim == 2:
        x, y = X
        u = [a * sp.sin(pi * x) * sp.cos(pi * y / 2) + a * x * y / 2,
             a * sp.cos(pi * x / 2) * sp.sin(pi * y) - a * x ** 2 / 4]
        p = a * (sp.cos(pi * x) * sp.cos(pi * y) + x * y)
    else:
        x, y, z = X
        u = [a * sp.sin(pi * x) * sp.cos(pi * y / 2) * (1 + z / 2),
             a * sp.cos(pi * x / 2) * sp.sin(pi * y) - a * x * z / 2,
             a * sp.sin(pi * z) * (1 + x * y / 2)]
        p = a * (sp.cos(pi * x) * sp.cos(pi * y) * sp.cos(pi * z) + x * y * z)
    return X, u, p


def energy(law_name: str, constants: dict, model: MmsModel, F, phat=None, mu=None, alpha=None):
    """W(F, phat) of ``model`` as a sympy expression of the dim x dim matrix F."""
    import sympy as sp

    law = get_law(law_name)
    m = SimpleNamespace(log=sp.log)
    dim = F.shape[0]
    J = F.det()
    if model.invariants == "plane-stress":
        F3 = sp.diag(F, 1 / J)
    else:
        F3 = F if dim == 3 else sp.diag(F, 1)
    C = F3.T * F3
    I1 = C.trace()
    I2 = (I1 ** 2 - (C * C).trace()) / 2
    if model.invariants == "isochoric":
        I1, I2 = J ** sp.Rational(-2, 3) * I1, J ** sp.Rational(-4, 3) * I2
    W = law.psi(I1, I2, {k: sp.Float(v) for k, v in constants.items()}, m)
    if model.has_pressure:
        W = W + mu * phat * (J - 1)
        if model.penalty:
            W = W - (mu * phat) ** 2 / (2 * alpha)
    return W


def _vectorised(exprs, args) -> Callable:
    """numpy function of ``args`` returning np.array(exprs) broadcast to the arguments'
    shape (constant entries included), common subexpressions computed once."""
    import sympy as sp

    f = sp.lambdify(args, list(exprs), "numpy", cse=True)

    def call(*a):
        shape = np.broadcast(*a).shape if a else ()
        return np.stack([np.broadcast_to(np.asarray(v, float), shape) for v in f(*a)])
    return call


@dataclass
class Manufactured:
    """The manufactured problem in numbers: functions of X (an array (dim, ...)), each
    returning an array (components, ...)."""
    law: str
    constants: dict
    model: MmsModel
    mu: float                      # Pa, the pressure scale p = mu phat (the law's shear modulus)
    alpha: float | None            # Pa, the penalty (plane-strain-penalty)
    u: Callable                    # u*(X) -> (dim, ...)
    grad_u: Callable               # grad u*(X) -> (dim * dim, ...), row-major
    phat: Callable | None          # phat*(X) -> (1, ...)
    b: Callable                    # body force (N/m^3) -> (dim, ...)
    g: Callable | None             # constraint source (dimensionless) -> (1, ...)
    stress: Callable               # P(F (dim*dim, ...), phat (...)) -> (dim * dim, ...), Pa

    @property
    def dim(self) -> int:
        return self.model.dim


@lru_cache(maxsize=None)
def _build(law_name: str, constants_items: tuple, model_name: str, alpha: float | None, amplitude: float):
    import sympy as sp

    model = get_model(model_name)
    constants = dict(constants_items)
    law = get_law(law_name)
    law.check(constants)
    mu = law.shear_modulus(constants)
    if model.penalty and not (alpha and alpha > 0):
        raise ValueError(f"mms: the model {model_name!r} needs a positive penalty alpha, got {alpha!r}")
    dim = model.dim
    X, u, p = exact_fields(dim, amplitude)
    Fs = sp.Matrix(dim, dim, lambda i, j: sp.Symbol(f"F{i}{j}", real=True))
    ps = sp.Symbol("phat", real=True)
    W = energy(law_name, constants, model, Fs, ps, sp.Float(mu), sp.Float(alpha) if alpha else None)
    flat = list(Fs)                                              # row-major F entries
    P = [sp.diff(W, f) for f in flat]                            # P_ij = dW/dF_ij
    A = [[sp.diff(Pij, f) for f in flat] for Pij in P]           # dP_ij / dF_kl
    B = [sp.diff(Pij, ps) for Pij in P]                          # dP_ij / dphat
    grad = [sp.diff(u[k], X[l]) for k in range(dim) for l in range(dim)]
    # d F_kl / d X_j = d^2 u_k / dX_l dX_j, as (kl, j)
    dF = [[sp.diff(gkl, X[j]) for j in range(dim)] for gkl in grad]
    dp = [sp.diff(p, X[j]) for j in range(dim)] if model.has_pressure else None

    stress = _vectorised(P, flat + [ps])
    tangent = _vectorised([a for row in A for a in row], flat + [ps])
    dstress_dp = _vectorised(B, flat + [ps])
    u_f = _vectorised(u, X)
    grad_f = _vectorised(grad, X)
    p_f = _vectorised([p], X) if model.has_pressure else None
    dF_f = _vectorised([e for row in dF for e in row], X)
    dp_f = _vectorised(dp, X) if model.has_pressure else None

    def args(Xv):
        Fv = grad_f(*Xv) + np.eye(dim).reshape(-1, *([1] * (np.ndim(Xv) - 1)))
        pv = p_f(*Xv)[0] if p_f else np.zeros(np.shape(Xv)[1:])
        return Fv, pv

    def body(Xv):
        Xv = np.asarray(Xv, float)
        Fv, pv = args(Xv)
        shape = Xv.shape[1:]
        Av = tangent(*Fv, pv).reshape(dim, dim, dim, dim, *shape)      # (i, j, k, l, ...)
        H = dF_f(*Xv).reshape(dim, dim, dim, *shape)                   # (k, l, j, ...)
        out = -np.einsum("ijkl...,klj...->i...", Av, H)
        if dp_f is not None:
            Bv = dstress_dp(*Fv, pv).reshape(dim, dim, *shape)
            out = out - np.einsum("ij...,j...->i...", Bv, dp_f(*Xv))
        return out

    def source(Xv):
        Xv = np.asarray(Xv, float)
        Fv, pv = args(Xv)
        J = np.linalg.det(np.moveaxis(Fv.reshape(dim, dim, *Xv.shape[1:]), (0, 1), (-2, -1)))
        g = J - 1.0 - (mu * pv / alpha if model.penalty else 0.0)
        return g[None]

    return Manufactured(law_name, constants, model, mu, alpha if model.penalty else None,
                        lambda Xv: u_f(*np.asarray(Xv, float)),
                        lambda Xv: grad_f(*np.asarray(Xv, float)),
                        (lambda Xv: p_f(*np.asarray(Xv, float))) if p_f else None,
                        body, source if model.has_pressure else None,
                        lambda Fv, pv: stress(*np.asarray(Fv, float), np.asarray(pv, float)))


def manufactured(law_name: str, constants: dict, model: str, alpha: float | None = None,
                 amplitude: float = AMPLITUDE) -> Manufactured:
    """The manufactured problem of ``law_name`` (constants in Pa) in ``model`` (penalty
    ``alpha`` in Pa for plane-strain-penalty); cached per arguments."""
    return _build(law_name, tuple(sorted((k, float(v)) for k, v in constants.items())), model,
                  None if alpha is None else float(alpha), float(amplitude))


def observed_orders(cells: list[int], errors: list[float | None]) -> list[float | None]:
    """Observed orders log(e_(k-1) / e_k) / log(n_k / n_(k-1)) between successive levels
    of ``cells`` per side (h = 1/n); None where an error is missing or not positive."""
    out = []
    for (n0, e0), (n1, e1) in zip(zip(cells, errors), zip(cells[1:], errors[1:])):
        ok = e0 is not None and e1 is not None and e0 > 0 and e1 > 0
        out.append(math.log(e0 / e1) / math.log(n1 / n0) if ok else None)
    return out


def boundary(points: np.ndarray, tol: float = 1e-12) -> np.ndarray:
    """Mask of the points (n, dim) on the boundary of the unit square / cube."""
    return np.any((points < tol) | (points > 1.0 - tol), axis=1)


def newton_solve(system, scale: float, tol: float, max_iterations: int) -> tuple[str, str | None, int]:
    """(status, reason, iterations) of Newton on a backend's manufactured system
    (:func:`mechanics.newton.newton`, the one loop of the continuum: to ||R|| <= tol scale)."""
    from mechanics.newton import newton
    from mechanics.time_loop import StepFailure

    try:
        its, _ = newton(system, scale, tol, max_iterations)
    except StepFailure as e:
        return "failed", str(e), e.iterations
    return "converged", None, its
