"""Stability of a static equilibrium: the inertia of the tangent decides.

:func:`check_stability` classifies an equilibrium as stable, unstable (negative
eigenvalues, counted by Sylvester's law of inertia; the static solver leaves it along
the lowest mode), singular (a zero-energy mode of the quadrature rule) or undetermined
(the lowest eigenvalue is within round-off of zero: the tangent is too ill-conditioned
to decide in double precision).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..kinematics.section.model import BeamModel


@dataclass
class Stability:
    kind: str                 # "stable" | "unstable" | "singular" | "undetermined"
    lowest: float | None      # lowest eigenvalue of the Jacobi-scaled constrained tangent
    mode: np.ndarray | None   # its eigenvector (global dofs), when not stable
    negative: int | None = None   # eigenvalues below -SINGULAR_TOL (Sylvester's law of inertia)

    @property
    def stable(self) -> bool | None:
        return {"stable": True, "unstable": False, "singular": False}.get(self.kind)

    def describe(self) -> str:
        if self.kind == "stable":
            return "stable"
        n = self.negative or 0
        what = {"unstable": f"tangent has {n} negative eigenvalue{'s' if n != 1 else ''}",
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
# zero-energy mode measured -4e-18.
SINGULAR_TOL = 1e-14
# An LDL^T without pivoting is exact in exact arithmetic whenever it exists; in floating
# point a tiny pivot can let the factors grow and the count go wrong. The count is
# trusted when no pivot is below PIVOT_TRUST (S has a unit diagonal), or when the factors
# did not grow: diag(|L| |D| |L|^T) <= GROWTH_TRUST, so that the backward error stays
# within a few times that of a positive definite S (a tiny pivot alone, as in a nearly
# singular but definite S, does not spoil the count). Otherwise LAPACK's bisection
# (dsbevx; O(n^2 b), about 2 s at 5000 unknowns) counts.
PIVOT_TRUST = 1e-6
GROWTH_TRUST = 10.0


def below(K, shift: float) -> int:
    """How many eigenvalues of the Jacobi-scaled K lie below ``shift``: Sylvester's law
    of inertia on a banded LDL^T of S - shift I, or LAPACK's banded bisection when a
    tiny pivot made the factors grow."""
    neg, small, growth = K.scaled_inertia(shift)
    if small >= PIVOT_TRUST or growth <= GROWTH_TRUST:
        return neg
    from scipy.linalg import eigvals_banded
    upper, _ = K.scaled_upper()
    return int(len(eigvals_banded(upper, lower=False, select="v", select_range=(-np.inf, shift),
                                  check_finite=False)))


def check_stability(model: BeamModel, u: np.ndarray, loads=None) -> Stability:
    """Classify the equilibrium u by the inertia of the Jacobi-scaled constrained tangent
    S (a congruence of K: the same signs of eigenvalues): unstable when eigenvalues lie
    below -SINGULAR_TOL (their number is the record's ``negative_eigenvalues``); stable
    when none lies below +SINGULAR_TOL; in between (an eigenvalue within round-off of
    zero), singular if the lowest mode is a zero-energy mode of the elastic quadrature
    rule (its strain variation vanishes at the rule's points but not at a full rule's),
    else undetermined. Counting by inertia cannot miss a negative eigenvalue, as an
    eigen solver asked for the eigenvalue nearest a shift can; the lowest eigenpair (the
    mode the static solver escapes along) is computed only when the state is not stable;
    a stable state carries its lowest eigenvalue alone (its margin above SINGULAR_TOL).
    ``loads`` (:class:`ancf.solvers.couple.Loading`): an end couple's load stiffness joins the
    tangent (the Hessian of the total potential); dead loads add none."""
    if loads is not None and loads.has_couple:
        _, K = loads.out_of_balance_and_tangent(model, u)
    else:
        _, K = model.internal_force_and_tangent(u)
    K = K.constrain(model.fixed)
    negative = below(K, -SINGULAR_TOL)
    if negative == 0 and below(K, SINGULAR_TOL) == 0:
        return Stability("stable", lowest_eigenvalue(K), None, 0)
    lowest, mode = lowest_mode(K, model.fixed, negative)
    if lowest is None:
        return Stability("undetermined", None, None, negative)
    if negative:
        return Stability("unstable", lowest, mode, negative)
    return Stability("singular" if _is_quadrature_mode(model, mode) else "undetermined", lowest, mode, 0)


def lowest_eigenvalue(K) -> float | None:
    """The lowest eigenvalue of the Jacobi-scaled constrained K of a state with no
    eigenvalue below SINGULAR_TOL (a stable one): shift-invert Lanczos at 0 (ARPACK on a
    sparse LU of the band, O(n b^2): the eigenvalue nearest 0 is then the lowest),
    absolute error ~ eps ||S|| as LAPACK's banded bisection (dsbevx), which costs
    O(n^2 b) (2.2 s of the 2.3 s of a 640 x HB2n-16 cell, measured). Small systems: a
    dense solve. None if it gives no finite value."""
    import scipy.sparse as sps
    from scipy.sparse.linalg import ArpackError, eigsh

    upper, _ = K.scaled_upper()
    b, n = upper.shape[0] - 1, upper.shape[1]
    bands = [upper[b - off, off:] for off in range(1, b + 1) if off < n]
    S = sps.diags([upper[b]] + bands + bands, [0] + [o for o in range(1, len(bands) + 1)]
                  + [-o for o in range(1, len(bands) + 1)], format="csc")
    try:
        if n <= 64:
            lam = np.linalg.eigvalsh(S.toarray())[:1]
        else:
            lam = eigsh(S, k=1, sigma=0.0, which="LM", v0=np.ones(n), return_eigenvectors=False)
    except (np.linalg.LinAlgError, ValueError, RuntimeError, ArpackError):
        return None
    return float(lam[0]) if len(lam) and np.isfinite(lam[0]) else None


def _is_quadrature_mode(model: BeamModel, mode: np.ndarray) -> bool:
    """Does the mode strain nothing at the elastic rule's points, while a rule exact for
    the element's polynomials sees it strain?"""

    def strain(m: BeamModel) -> float:
        return float(np.abs(m.strain_variation(mode)).max())

    full = replace(model, rule=model.full_rule)
    return strain(model) <= 1e-6 * strain(full)


def lowest_mode(K, fixed, negative: int) -> tuple[float | None, np.ndarray | None]:
    """The lowest eigenpair of the Jacobi-scaled K: the lowest eigenvalue bracketed by
    bisection on inertia counts (lo with no eigenvalue below, hi with one), then inverse
    iteration with the banded Cholesky factor of S - lo I (positive definite: lo lies
    below every eigenvalue); the mode in global dofs (fixed dofs zero). (None, None) if
    S - lo I cannot be factorised or the iteration gives no finite value."""
    from scipy.linalg import cho_solve_banded, cholesky_banded

    norm = K.scaled_norm()
    lo, hi = (-1.01 * norm, -SINGULAR_TOL) if negative else (-SINGULAR_TOL, SINGULAR_TOL)
    for _ in range(200):
        if hi - lo <= 1e-3 * abs(hi) + 1e-3 * SINGULAR_TOL:
            break
        mid = 0.5 * (lo + hi)
        if below(K, mid) > 0:
            hi = mid
        else:
            lo = mid
    upper, s = K.scaled_upper()
    # below lo by a margin above round-off (S - lo I may be singular to working precision
    # when the lowest eigenvalue is itself at round-off level); widened if it still fails
    margin, c = 1e-3 * (hi - lo) + 10 * SINGULAR_TOL, None
    for _ in range(4):
        shifted = upper.copy()
        shifted[K.b] -= lo - margin
        try:
            c = cholesky_banded(shifted, lower=False, check_finite=False)
            break
        except np.linalg.LinAlgError:
            margin *= 100.0
    if c is None:
        return None, None
    x = np.cos(np.arange(K.n) * 0.7) + 1.0          # fixed, non-degenerate start vector
    lam = None
    for _ in range(100):
        y = cho_solve_banded((c, False), x, check_finite=False)
        y /= np.linalg.norm(y)
        new = float(y @ (s * K.matvec(s * y)))          # the Rayleigh quotient of S
        x = y
        # the Rayleigh quotient carries an error ~ eps ||S||: settle at 1e-10 relative,
        # or at 0.1 SINGULAR_TOL absolute near zero (a zero-mode cluster)
        if lam is not None and abs(new - lam) <= max(1e-10 * abs(new), 0.1 * SINGULAR_TOL):
            lam = new
            break
        lam = new
    if lam is None or not np.isfinite(lam):
        return None, None
    mode = s * x
    mode[fixed] = 0.0
    return lam, mode

