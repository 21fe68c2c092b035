"""Static equilibrium of a spatial beam: the clamp, gravity, and Newton along a load path.

- The clamp (:func:`clamp_rows`) holds the first node's coordinates that describe the end
  face itself, every kind without an x derivative (r, r_y, r_z, r_yy, ...): the face's
  position field r(0, y, z) stays the reference one, as the continuum's clamped face; the
  slopes along the beam (r_x) stay free.
- Gravity (:func:`gravity_load`): the dead load of rho g on the volume, f_m = int rho g N_m dV.
- :func:`solve_static`: the load along t: 0 -> 1 by the shared load-path rule
  (:func:`mechanics.load_path.follow`: adaptive increments, cut when one fails), each
  increment by the shared Newton loop (:func:`mechanics.newton.newton`) on the free
  coordinates (the dense tangent, scaled by its diagonal: the kinds' units differ, r in m,
  r_yy in 1/m), from a secant predictor, with full steps; only an increment whose full
  Newton fails is retried from the last equilibrium with a backtracking line search on the
  total potential E(q) - t f.q (a state outside the law's domain, det F <= 0 included, has
  no energy and is backed out of). Full steps first, because a stiff penalty makes the
  energy a poor merit function: the linear step of a rotating beam stretches its fibres to
  second order, alpha times that is far above the load's work, and a line search that
  insists on descent crawls back to the constraint where Newton's full steps converge
  (measured, 3363p x 2, the paper's cantilever at a tenth of its load: 8 full steps to
  5e-9 of the load against more than 30 damped ones). An increment converges at
  |residual| <= max(rtol t |f|, ROUNDOFF_FLOOR eps |f_int|_terms) (the planar statics' floor,
  :data:`ancf.solvers.statics.ROUNDOFF_FLOOR`, on the force assembled from the magnitudes of
  its terms, :meth:`.beam.SpatialBeam.force_magnitude`, at the reference state), or when
  Newton's correction is below ``xtol`` of the beam's length: the residual's round-off (a stiff penalty's eps alpha h w, with terms of P of
  order mu that cancel) can lie above rtol |f| under gravity while the corrections fall
  quadratically to round-off (3333 x 4 at a tenth of the load: corrections 7e-4, 2e-7,
  2e-11, 1e-14 m, the residual stalling at 5e-11 to 1e-10 N against rtol |f| = 4e-11 N).
  It returns a status and a reason, never a state that did not converge.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechanics.load_path import Attempt, PathCounts, PathFailure, follow
from mechanics.newton import newton
from mechanics.time_loop import StepFailure

from ...solvers.statics import ROUNDOFF_FLOOR
from .beam import SpatialBeam
from .spec import kind_orders


def clamp_rows(beam: SpatialBeam) -> np.ndarray:
    """The dof indices the clamp holds (see the module doc)."""
    kinds = [m for m, k in enumerate(beam.spec.kinds) if kind_orders(k)[0] == 0]
    return np.array([3 * m + i for m in kinds for i in range(3)])


def gravity_load(beam: SpatialBeam, density: float, g=(0.0, -9.81, 0.0)) -> np.ndarray:
    """f (dof,) of the body force density * g (N), by the beam's own rule."""
    N, _, w = beam._table
    f = np.zeros((beam.n_global, 3))
    per = np.einsum("p,pm->m", w, N)
    for e in range(beam.elements):
        np.add.at(f, beam.element_rows(e), np.outer(per, density * np.asarray(g, float)))
    return f.ravel()


@dataclass
class StaticResult:
    status: str                 # "converged" or "failed"
    reason: str | None
    q: np.ndarray | None        # (n_global, 3) at the full load, None unless converged
    newton_iterations: int
    load_steps: int             # accepted increments
    rejected_steps: int = 0

    def tip(self, beam: SpatialBeam) -> dict | None:
        """The displacement of the free end face's centre, r(L, 0, 0) - (L, 0, 0) (m)."""
        if self.q is None:
            return None
        k = len(beam.spec.kinds)
        r = self.q[(beam.nodes - 1) * k + beam.spec.kinds.index("r")]
        return {"ux": float(r[0] - beam.length), "uy": float(r[1]), "uz": float(r[2])}


class _Increment:
    """One increment's Newton system for :func:`mechanics.newton.newton`: q on the free
    coordinates under the load ``f``, full steps or (``line_search``) damped ones."""

    def __init__(self, beam: SpatialBeam, free: np.ndarray, q: np.ndarray, f: np.ndarray, line_search: bool):
        self.beam, self.free, self.q, self.f, self.line_search = beam, free, q.copy(), f, line_search

    def potential(self, q: np.ndarray) -> float:
        e = self.beam.energy(q.reshape(-1, 3))
        return e - self.f @ q if np.isfinite(e) else np.inf

    def residual_norm(self) -> float:
        self.r = self.beam.force(self.q.reshape(-1, 3)) - self.f
        return float(np.linalg.norm(self.r[self.free]))

    def newton_update(self) -> float:
        K = self.beam.tangent(self.q.reshape(-1, 3))[np.ix_(self.free, self.free)]
        d = 1.0 / np.sqrt(np.abs(np.diag(K)))
        dq = np.zeros_like(self.q)
        try:
            dq[self.free] = -d * np.linalg.solve(d[:, None] * K * d[None, :], d * self.r[self.free])
        except np.linalg.LinAlgError:       # not an ArithmeticError: the shared loop would let it through
            raise ArithmeticError("singular tangent") from None
        s = 1.0
        if self.line_search:
            p0, slope = self.potential(self.q), self.r @ dq
            while s > 1e-4 and not self.potential(self.q + s * dq) <= p0 + 1e-4 * s * slope:
                s *= 0.5
        self.q = self.q + s * dq
        return float(np.abs(dq).max())          # Newton's correction, undamped


def solve_static(beam: SpatialBeam, f_ext: np.ndarray, fixed: np.ndarray, load_steps: int = 10,
                 rtol: float = 1e-8, xtol: float = 1e-12, max_iterations: int = 40) -> StaticResult:
    """Equilibrium under ``f_ext`` with the dofs ``fixed`` held at the reference (see the
    module doc)."""
    free = np.setdiff1d(np.arange(beam.dof), fixed)
    scale = float(np.linalg.norm(f_ext)) or 1.0
    # never below the force's own round-off (the planar statics' rule and margin)
    floor = ROUNDOFF_FLOOR * np.finfo(float).eps * float(np.linalg.norm(beam.force_magnitude(beam.reference())[free]))
    state = {"q": beam.reference().ravel(), "dq": None}
    small = lambda system, r, dw: dw <= xtol * beam.length

    def attempt(t0: float, t1: float) -> Attempt:
        q, prev = state["q"], state["dq"]
        guess = q if prev is None else q + prev[1] * ((t1 - t0) / prev[0])
        spent, reason = 0, None
        for start, line_search in ((guess, False), (q, True)):
            system = _Increment(beam, free, start, t1 * f_ext, line_search)
            try:
                its, _ = newton(system, max(t1 * scale, floor / rtol), rtol, max_iterations, small)
            except StepFailure as e:
                spent, reason = spent + e.iterations, str(e)
                continue
            state["dq"], state["q"] = (t1 - t0, system.q - q), system.q
            return Attempt(True, spent + its)
        return Attempt(False, spent, reason)

    counts = PathCounts()
    try:
        for _ in follow(attempt, load_steps, counts, min_step=1.0 / (64 * load_steps)):
            pass
    except PathFailure as e:
        return StaticResult("failed", f"Newton did not converge: {e.reason}", None, counts.newton_iterations,
                            counts.accepted, counts.rejected)
    return StaticResult("converged", None, state["q"].reshape(-1, 3), counts.newton_iterations,
                        counts.accepted, counts.rejected)
