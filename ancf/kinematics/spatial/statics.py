"""Static equilibrium of a spatial beam: the supports, the loads, and Newton along a load path.

- The clamp (:func:`clamp_rows`) holds the first node's coordinates that describe the end
  face itself, every kind without an x derivative (r, r_y, r_z, r_yy, ...): the face's
  position field r(0, y, z) stays the reference one, as the continuum's clamped face; the
  slopes along the beam (r_x) stay free.
- Gravity (:func:`gravity_load`): the dead load of rho g on the volume, f_m = int rho g N_m dV;
  a dead traction on the free end face (:func:`end_face_load`), a torque about the axis by
  one (:func:`end_torque_load`, small twists), and the section's rotation about the axis at a
  node (:func:`section_rotation`); the free-warping support of torsion (:func:`free_warping_rows`);
  any section held as a rigid plate (:func:`face_rows`), turned (:func:`rotated_face`, a
  prescribed motion: :func:`solve_static`'s ``held``), and the plate's reaction
  (:func:`face_reaction`).
- :func:`solve_static`: the load along t: 0 -> 1 by the shared load-path rule
  (:func:`mechanics.load_path.follow`: adaptive increments, cut when one fails), each
  increment by the shared Newton loop (:func:`mechanics.newton.newton`) on the free
  coordinates (the banded tangent's LU, scaled by its diagonal: the kinds' units differ, r in
  m, r_yy in 1/m; :meth:`ancf.core.banded.Banded.solve`), from a secant predictor, with full
  steps. With an element pressure (the lock-free elements) the full steps are mixed: the
  residual is the penalty problem's (the condensed pressures lambda(q) = alpha M^-1 b(q) of
  q itself), but the tangent's geometric pressure term takes the iterate's own pressures,
  carried as unknowns and updated by their linearisation (lambda(q) + dlambda/dq dq,
  :meth:`.beam.SpatialBeam.linearised_pressures`; the secant predictor extrapolates them
  too). The equilibrium is the same, because the residual is; the tangent no longer holds
  the second-order terms of lambda(q), which alpha magnifies, and Newton converges as in a
  mixed (u, p) method (measured, HS2n-96p x 12 graded under the paper's end force: 41
  iterations against 123; Yeoh 42 against 273; NH under its weight 33 against 196). An
  increment whose full Newton fails is retried from the last equilibrium, first with full
  steps again, then with a backtracking line search (q's own pressures) on the
  total potential E(q) - t f.q (a state outside the law's domain, det F <= 0 included, has
  no energy and is backed out of). Full steps first, because a stiff penalty makes the
  energy a poor merit function: the linear step of a rotating beam stretches its fibres to
  second order, alpha times that is far above the load's work, and a line search that
  insists on descent crawls back to the constraint where Newton's full steps converge
  (measured, 3363p x 2, the paper's cantilever at a tenth of its load: 8 full steps to
  5e-9 of the load against more than 30 damped ones). An increment converges at
  |residual| <= max(rtol t |f|, floor), the floor the residual's round-off at the reference
  state (:func:`roundoff_floor`: the planar statics' ROUNDOFF_FLOOR eps |f_int|_terms, on the
  force assembled from the magnitudes of its terms, :meth:`.beam.SpatialBeam.force_magnitude`,
  plus the coordinates' representation eps |K| |q|), or when
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

from ...core.banded import Banded
from ...solvers.statics import ROUNDOFF_FLOOR
from .beam import SpatialBeam
from .spec import kind_orders


def clamp_rows(beam: SpatialBeam) -> np.ndarray:
    """The dof indices the clamp holds (see the module doc)."""
    return face_rows(beam, 0)


def face_rows(beam: SpatialBeam, node: int) -> np.ndarray:
    """The dof indices that describe the section at ``node`` itself, r(x_node, y, z): every
    kind without an x derivative (r, r_y, r_z, r_yy, ...); held, the face is a rigid plate's."""
    k = len(beam.spec.kinds)
    kinds = [m for m, kind in enumerate(beam.spec.kinds) if kind_orders(kind)[0] == 0]
    return np.array([3 * (node * k + m) + i for m in kinds for i in range(3)])


def _face_vectors(beam: SpatialBeam, node: int) -> tuple[np.ndarray, np.ndarray]:
    """(the nodal vectors :func:`face_rows` holds, which of them is the centre's r)."""
    nodal = face_rows(beam, node)[::3] // 3
    return nodal, nodal == node * len(beam.spec.kinds) + beam.spec.kinds.index("r")


def rotated_face(beam: SpatialBeam, node: int, R: np.ndarray) -> np.ndarray:
    """The values of :func:`face_rows` (same order) of the reference section at ``node`` turned
    rigidly by the rotation matrix ``R`` about its centre (x_node, 0, 0): r stays, every other
    kind of the section's field is R times its reference value (r_y -> R e_y, r_z -> R e_z,
    r_yy, ... stay zero)."""
    ref = beam.reference()
    nodal, centre = _face_vectors(beam, node)
    values = ref[nodal] @ np.asarray(R, float).T
    values[centre] = ref[nodal[centre]]
    return values.ravel()


def face_reaction(beam: SpatialBeam, q: np.ndarray, f_ext: np.ndarray, node: int) -> dict:
    """The force and moment (about the section's centre r(x_node, 0, 0)) that the support
    holding :func:`face_rows` applies to the beam at equilibrium (N, N m): the generalised
    reactions f = f_int - f_ext at those rows, paired with a rigid virtual motion of the face
    (delta r = delta c + delta omega x (r - c): the kind r moves by delta c + delta omega x 0,
    every other kind q_k by delta omega x q_k), the continuum's sum of x x f over the face's
    nodes."""
    q = np.asarray(q).reshape(-1, 3)
    nodal, centre = _face_vectors(beam, node)
    f = (beam.force(q) - f_ext)[face_rows(beam, node)].reshape(-1, 3)
    arm = np.where(centre[:, None], 0.0, q[nodal])
    return {"force": f[centre].sum(axis=0), "moment": np.cross(arm, f).sum(axis=0)}


def free_warping_rows(beam: SpatialBeam) -> np.ndarray:
    """The dof indices of a support that holds the first node's section rigidly to first order
    and nothing more: its r, r_y and r_z (six rigid motions and the section's stretches and
    shears held), its higher section fields (r_yy, r_yz, ...) and slopes along the beam free,
    so that the face may warp and distort (Saint-Venant's free end, for torsion)."""
    held = [beam.spec.kinds.index(k) for k in ("r", "r_y", "r_z")]
    return np.array([3 * m + i for m in held for i in range(3)])


def gravity_load(beam: SpatialBeam, density: float, g=(0.0, -9.81, 0.0)) -> np.ndarray:
    """f (dof,) of the body force density * g (N), by the beam's own rule."""
    f = np.zeros((beam.n_global, 3))
    for e in range(beam.elements):
        N, _, w = beam.table(e)
        per = np.einsum("p,pm->m", w, N)
        np.add.at(f, beam.element_rows(e), np.outer(per, density * np.asarray(g, float)))
    return f.ravel()


def end_face_load(beam: SpatialBeam, traction, start: bool = False) -> np.ndarray:
    """f (dof,) of a dead traction on the free end face x = L (N), or with ``start`` on the face
    x = 0: f_m = int t(y, z) N_m dA, ``traction`` a function of the face's points y, z
    (arrays, m) giving t (npts, 3) in Pa, by the beam's rule across the section (exact for a
    traction of degree one on the squared basis's rule)."""
    gy, wy = np.polynomial.legendre.leggauss(beam.points[1])
    gz, wz = np.polynomial.legendre.leggauss(beam.points[2])
    Y, Z = (a.ravel() / 2.0 for a in np.meshgrid(gy, gz, indexing="ij"))
    wa = np.outer(wy, wz).ravel() / 4.0 * beam.height * beam.width
    e = 0 if start else beam.elements - 1
    N, _ = beam.spec.tabulate(np.full(Y.size, 0.0 if start else 1.0), Y, Z, beam.lengths[e], beam.height,
                              beam.width)
    t = np.asarray(traction(Y * beam.height, Z * beam.width), float).reshape(Y.size, 3)
    f = np.zeros((beam.n_global, 3))
    np.add.at(f, beam.element_rows(e), np.einsum("p,pm,pi->mi", wa, N, t))
    return f.ravel()


def end_torque_load(beam: SpatialBeam, torque: float) -> np.ndarray:
    """f (dof,) of a torque about the beam's axis on the free end face, as the dead traction
    t = (torque / I_p) (0, -z, y) (the circular bar's shear stress; any traction with this
    resultant twists the beam alike away from the end, Saint-Venant's principle), I_p the
    section's polar moment h w (h^2 + w^2) / 12. A dead traction: for small twists only (it
    does not turn with the face)."""
    ip = beam.height * beam.width * (beam.height ** 2 + beam.width ** 2) / 12.0
    return end_face_load(beam, lambda y, z: (torque / ip) * np.column_stack([0.0 * y, -z, y]))


def section_rotation(beam: SpatialBeam, q: np.ndarray, node: int) -> float:
    """The section's rotation about x at a node (rad): the angle of the rotation nearest the
    in-plane part of (r_y, r_z), atan2(a_zy - a_yz, a_yy + a_zz) with a = [r_y r_z] in (y, z)."""
    k = len(beam.spec.kinds)
    ry, rz = (np.asarray(q).reshape(-1, 3)[node * k + beam.spec.kinds.index(n)] for n in ("r_y", "r_z"))
    return float(np.arctan2(ry[2] - rz[1], ry[1] + rz[2]))


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
    coordinates under the load ``f``, full steps or (``line_search``) damped ones. With an
    element pressure and full steps, the pressures ``lam`` are unknowns of their own (the
    mixed form, see the module doc); damped steps take q's own (lam None)."""

    def __init__(self, beam: SpatialBeam, free: np.ndarray, q: np.ndarray, f: np.ndarray, line_search: bool,
                 lam: np.ndarray | None = None):
        self.beam, self.free, self.q, self.f, self.line_search = beam, free, q.copy(), f, line_search
        self.fixed = np.setdiff1d(np.arange(beam.dof), free)
        self.lam = None if line_search else lam

    def potential(self, q: np.ndarray) -> float:
        e = self.beam.energy(q.reshape(-1, 3))
        return e - self.f @ q if np.isfinite(e) else np.inf

    def residual_norm(self) -> float:
        self.r = self.beam.force(self.q.reshape(-1, 3)) - self.f
        return float(np.linalg.norm(self.r[self.free]))

    def newton_update(self) -> float:
        K = self.beam.tangent_banded(self.q.reshape(-1, 3), self.lam).constrain(self.fixed)
        try:
            r = self.r.copy()
            r[self.fixed] = 0.0
            dq = -_solve(K, r)
        except np.linalg.LinAlgError:       # not an ArithmeticError: the shared loop would let it through
            raise ArithmeticError("singular tangent") from None
        s = 1.0
        if self.line_search:
            p0, slope = self.potential(self.q), self.r @ dq
            while s > 1e-4 and not self.potential(self.q + s * dq) <= p0 + 1e-4 * s * slope:
                s *= 0.5
        if self.lam is not None:
            self.lam = self.beam.linearised_pressures(self.q.reshape(-1, 3), dq)
        self.q = self.q + s * dq
        return float(np.abs(dq).max())          # Newton's correction, undamped


def _solve(K, r: np.ndarray) -> np.ndarray:
    """K^-1 r by the banded Cholesky factorisation of the Jacobi-scaled K where it is positive
    definite (a stable state's tangent: about a quarter of the LU's work), else by the scaled
    LU (:meth:`ancf.core.banded.Banded.solve`; LinAlgError if singular)."""
    x = K.solve_shifted(r, 0.0)
    return K.solve(r) if x is None else x


def _linear_response(beam: SpatialBeam, q0: np.ndarray, fixed: np.ndarray, motion: np.ndarray):
    """The linear response to the prescribed ``motion`` of ``fixed`` from the equilibrium q0,
    the free coordinates following: (dq (dof,) for the whole motion, |f_int| at the held rows
    (N), the supports' reactions to first order, the force scale of a motion's residual). (The
    held rows' own response, the free ones at rest, is no scale: a section turned against its
    neighbours at rest meets the penalty's stiffness, some 1e4 times the reactions of the beam
    that follows.) K dq by differences of the force along a small multiple of the motion."""
    eps = 1e-6 * beam.length / max(float(np.abs(motion).max()), 1e-300)
    f0 = beam.force(q0.reshape(-1, 3))
    dq = np.zeros(beam.dof)
    dq[fixed] = eps * motion
    df = beam.force((q0 + dq).reshape(-1, 3)) - f0
    df[fixed] = 0.0
    dq -= _solve(beam.tangent_banded(q0.reshape(-1, 3), beam.pressures(q0)).constrain(fixed), df)
    return dq / eps, float(np.linalg.norm((beam.force((q0 + dq).reshape(-1, 3)) - f0)[fixed])) / eps


def roundoff_floor(beam: SpatialBeam, free: np.ndarray) -> float:
    """The residual's round-off over the ``free`` rows at the reference state (N), the
    tolerance's floor: the force's evaluation, ROUNDOFF_FLOOR eps |f_int|_terms (the planar
    statics' rule and margin), plus the coordinates' own representation, eps |K| |q| (a
    position held to eps |x| moves the force by K times that: on a short element at the far
    end of the beam, 1e-4 m long at x = 0.16 m with the penalty's stiffness, some 20 times the
    first term, below which Newton's residual cannot fall)."""
    q = beam.reference()
    eps = np.finfo(float).eps
    K = beam.tangent_banded(q)
    terms = ROUNDOFF_FLOOR * eps * float(np.linalg.norm(beam.force_magnitude(q)[free]))
    coordinates = eps * float(np.linalg.norm(Banded(np.abs(K.ab), K.b).matvec(np.abs(q.ravel()))[free]))
    return terms + coordinates


def solve_static(beam: SpatialBeam, f_ext: np.ndarray, fixed: np.ndarray, load_steps: int = 10,
                 rtol: float = 1e-8, xtol: float = 1e-12, max_iterations: int = 40,
                 held=None, start: np.ndarray | None = None) -> StaticResult:
    """Equilibrium under ``t f_ext`` with the dofs ``fixed`` held at the reference (see the
    module doc), or, with ``held`` (a function of the load parameter t giving the values of
    ``fixed``, in their order), moved along with the load: a prescribed motion (a support's
    rotation). Its force scale, for the residual's tolerance, is the larger of the load's
    and the prescribed motion's reactions to first order (:func:`_linear_response`), and the first
    increment starts from that linear response.
    ``start``: the state at t = 0 (an equilibrium there, e.g. the end of an earlier leg of a
    path; default the reference)."""
    fixed = np.asarray(fixed)
    free = np.setdiff1d(np.arange(beam.dof), fixed)
    q0 = (beam.reference() if start is None else np.asarray(start, float)).ravel()
    scale = float(np.linalg.norm(f_ext))
    state = {"q": q0, "lam": beam.pressures(q0), "dq": None}
    if held is not None:
        dq1, reaction = _linear_response(beam, q0, fixed, held(1.0) - q0[fixed])
        scale = max(scale, reaction)
        # the first increment's predictor: the motion's linear response (the free coordinates
        # beside a turned plate follow it, instead of starting at rest against it)
        lam0 = state["lam"]
        state["dq"] = (1.0, dq1, None if lam0 is None else beam.linearised_pressures(q0.reshape(-1, 3), dq1) - lam0)
    scale = scale or 1.0
    floor = roundoff_floor(beam, free)
    small = lambda system, r, dw: dw <= xtol * beam.length

    def attempt(t0: float, t1: float) -> Attempt:
        q, lam, prev = state["q"], state["lam"], state["dq"]
        guess, lam_guess = q, lam
        if prev is not None:          # the secant predictor, of the pressures too
            s = (t1 - t0) / prev[0]
            guess = q + prev[1] * s
            lam_guess = None if lam is None else lam + prev[2] * s
        spent, reason = 0, None
        for q_start, lam_start, line_search in ((guess, lam_guess, False), (q, lam, False), (q, lam, True)):
            if held is not None:
                q_start = q_start.copy()
                q_start[fixed] = held(t1)
            system = _Increment(beam, free, q_start, t1 * f_ext, line_search, lam_start)
            try:
                its, _ = newton(system, max(t1 * scale, floor / rtol), rtol, max_iterations, small)
            except StepFailure as e:
                spent, reason = spent + e.iterations, str(e)
                continue
            lam1 = beam.pressures(system.q.reshape(-1, 3))
            state["dq"] = (t1 - t0, system.q - q, None if lam is None else lam1 - lam)
            state["q"], state["lam"] = system.q, lam1
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
