"""Stability of a static equilibrium: the lowest eigenvalue of the tangent decides.

:func:`check_stability` classifies an equilibrium as stable, unstable (a negative
eigenvalue: the static solver leaves it along the mode), singular (a zero-energy mode of
the quadrature rule) or undetermined (the lowest eigenvalue is within round-off of
zero: the tangent is too ill-conditioned to decide in double precision).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .model import BeamModel


@dataclass
class Stability:
    kind: str                 # "stable" | "unstable" | "singular" | "undetermined"
    lowest: float | None      # lowest eigenvalue of the Jacobi-scaled constrained tangent
    mode: np.ndarray | None   # its eigenvector (global dofs), when not stable

    @property
    def stable(self) -> bool | None:
        return {"stable": True, "unstable": False, "singular": False}.get(self.kind)

    def describe(self) -> str:
        if self.kind == "stable":
            return "stable"
        what = {"unstable": "tangent has a negative eigenvalue",
                "singular": "tangent singular: a zero-energy mode of the quadrature rule",
                "undetermined": "undetermined: the lowest eigenvalue is within round-off "
                                "(the tangent is too ill-conditioned to decide in double precision)",
                }[self.kind]
        if self.lowest is None:
            return "undetermined: the eigen solve for the lowest mode did not converge"
        return f"{what} (lowest scaled eigenvalue {self.lowest:.3g})"


# Eigenvalues of the unit-diagonal scaled tangent within this of zero are not resolved:
# their absolute error is ~c eps ||S|| (||S|| <= ~5). The softest genuine bending mode
# of the paper's cantilever falls with refinement to 5.7e-13 at 640 elements (resolved);
# with alpha = 1e5 C10 it falls to ~2e-16 (not resolved: "undetermined"). A structural
# zero-energy mode measured -4e-18. A Cholesky pivot above MIN_PIVOT settles stability
# without an eigen solve.
SINGULAR_TOL = 1e-14
MIN_PIVOT = 1e-10


def check_stability(model: BeamModel, u: np.ndarray) -> Stability:
    """Classify the equilibrium u by the lowest eigenpair (lambda, phi) of the
    Jacobi-scaled constrained tangent S: stable (lambda > SINGULAR_TOL), unstable (below
    -SINGULAR_TOL); in between, singular if phi is a zero-energy mode of the elastic
    quadrature rule (its strain variation B phi vanishes at the rule's points but not at
    a full rule's), else undetermined.

    Fast path: a banded Cholesky factorisation of S whose smallest pivot is not tiny
    (> MIN_PIVOT) proves S positive definite well above round-off (a plain Cholesky
    cannot tell singular from positive definite: round-off may leave a tiny positive
    pivot, as it did for HB2n-16's zero-energy mode)."""
    _, K = model.internal_force_and_tangent(u)
    K = K.constrain(model.fixed)
    c, _ = K.scaled_cholesky()
    if c is not None and (c[K.b] ** 2).min() > MIN_PIVOT:
        return Stability("stable", None, None)
    lowest, mode = _lowest_mode(K, model.fixed)
    if lowest is None:
        return Stability("undetermined", None, None)
    if lowest > SINGULAR_TOL:
        return Stability("stable", lowest, None)
    if lowest < -SINGULAR_TOL:
        return Stability("unstable", lowest, mode)
    return Stability("singular" if _is_quadrature_mode(model, mode) else "undetermined", lowest, mode)


def _is_quadrature_mode(model: BeamModel, mode: np.ndarray) -> bool:
    """Does the mode strain nothing at the elastic rule's points, while a rule exact for
    the element's polynomials sees it strain?"""
    from .quadrature import exact_for

    def strain(m: BeamModel) -> float:
        return float(np.abs(m.strain_variation(mode)).max())

    dx, dy = model.mesh.element.degree()
    full = BeamModel(model.mesh, model.material, exact_for(2 * dx, 2 * dy), model.fixed)
    return strain(model) <= 1e-6 * strain(full)


def _lowest_mode(K, fixed) -> tuple[float | None, np.ndarray | None]:
    """Lowest eigenpair of the Jacobi-scaled K by shift-invert Lanczos around a tiny
    negative shift (S + 1e-10 I stays factorisable when S is singular and separates the
    near-zero cluster), from a fixed start vector (deterministic) with bounded
    iterations; dense below 3000 unknowns if Lanczos does not converge; (None, None)
    if neither gives an answer."""
    from scipy.sparse import diags
    from scipy.sparse.linalg import ArpackError, ArpackNoConvergence, eigsh

    A = K.to_sparse()
    s = 1.0 / np.sqrt(np.abs(A.diagonal()))
    S = (diags(s) @ A @ diags(s)).tocsc()
    n = S.shape[0]
    v0 = np.cos(np.arange(n) * 0.7) + 1.0          # fixed, non-degenerate start vector
    try:
        vals, vecs = eigsh(S, k=1, sigma=-1e-10, which="LM", v0=v0, maxiter=300)
    except (ArpackNoConvergence, ArpackError, RuntimeError):
        if n > 3000:
            return None, None
        vals, vecs = np.linalg.eigh(S.toarray())
        vals, vecs = vals[:1], vecs[:, :1]
    mode = s * vecs[:, 0]
    mode[fixed] = 0.0
    return float(vals[0]), mode
