"""Static equilibrium of a spatial beam: the clamp, gravity, and Newton along a load path.

- The clamp (:func:`clamp_rows`) holds the first node's coordinates that describe the end
  face itself, every kind without an x derivative (r, r_y, r_z, r_yy, ...): the face's
  position field r(0, y, z) stays the reference one, as the continuum's clamped face; the
  slopes along the beam (r_x) stay free.
- Gravity (:func:`gravity_load`): the dead load of rho g on the volume, f_m = int rho g N_m dV.
- :func:`solve_static`: the load in ``load_steps`` equal increments, each by Newton on
  the free coordinates (the dense tangent), with a backtracking line search on the total
  potential E(q) - t f.q (a state outside the law's domain, det F <= 0 included, has no
  energy and is backed out of), to |residual| <= rtol t |f|, or until Newton's correction
  is below ``xtol`` of the beam's length: the residual's round-off (a stiff penalty's
  eps alpha h w, with terms of P of order mu that cancel) can lie above rtol |f| under
  gravity while the corrections fall quadratically to round-off (measured, 3333 x 4, the
  paper's cantilever at a tenth of its load: corrections 7e-4, 2e-7, 2e-11, 1e-14 m, the
  residual stalling at 5e-11 to 1e-10 N against rtol |f| = 4e-11 N). An increment that does
  not converge is halved, down to 1/64 of the first. It returns a status and a reason,
  never a state that did not converge.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

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
    load_steps: int

    def tip(self, beam: SpatialBeam) -> dict | None:
        """The displacement of the free end face's centre, r(L, 0, 0) - (L, 0, 0) (m)."""
        if self.q is None:
            return None
        k = len(beam.spec.kinds)
        r = self.q[(beam.nodes - 1) * k + beam.spec.kinds.index("r")]
        return {"ux": float(r[0] - beam.length), "uy": float(r[1]), "uz": float(r[2])}


def solve_static(beam: SpatialBeam, f_ext: np.ndarray, fixed: np.ndarray, load_steps: int = 10,
                 rtol: float = 1e-8, xtol: float = 1e-12, max_iterations: int = 40) -> StaticResult:
    """Equilibrium under ``f_ext`` with the dofs ``fixed`` held at the reference."""
    q = beam.reference().ravel()
    free = np.setdiff1d(np.arange(beam.dof), fixed)
    t, dt, iterations, steps = 0.0, 1.0 / load_steps, 0, 0
    scale = np.linalg.norm(f_ext) or 1.0

    def potential(x, load):
        e = beam.energy(x.reshape(-1, 3))
        return e - load * f_ext @ x if np.isfinite(e) else np.inf

    while t < 1.0 - 1e-12:
        target = min(1.0, t + dt)
        x, ok = q.copy(), False
        for _ in range(max_iterations):
            r = beam.force(x.reshape(-1, 3)) - target * f_ext
            if np.linalg.norm(r[free]) <= rtol * scale * target:
                ok = True
                break
            K = beam.tangent(x.reshape(-1, 3))[np.ix_(free, free)]
            dx = np.zeros_like(x)
            try:
                # scaled by the diagonal (the kinds' units differ: r in m, r_yy in 1/m)
                d = 1.0 / np.sqrt(np.abs(np.diag(K)))
                dx[free] = -d * np.linalg.solve(d[:, None] * K * d[None, :], d * r[free])
            except np.linalg.LinAlgError:
                break
            iterations += 1
            p0, s = potential(x, target), 1.0
            while s > 1e-4 and not potential(x + s * dx, target) <= p0 + 1e-4 * s * (r @ dx):
                s *= 0.5
            x = x + s * dx
            if s == 1.0 and np.abs(dx).max() <= xtol * beam.length:
                ok = True
                break
        if ok:
            q, t, steps = x, target, steps + 1
            continue
        dt *= 0.5
        if dt < 1.0 / (64 * load_steps):
            return StaticResult("failed", f"Newton did not converge at load {target:.4g} (increments cut to "
                                f"1/64 of 1/{load_steps})", None, iterations, steps)
    return StaticResult("converged", None, q.reshape(-1, 3), iterations, steps)
