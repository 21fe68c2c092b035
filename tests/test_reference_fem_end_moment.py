"""The end moment (``loads.end_moment``, contract.loads) in the continuum reference: a
conservative couple -t M theta(d) on the end face's first moment d, in both backends
(DOLFINx: Sherman-Morrison-Woodbury on the LU; FElupe: the end face's dense block).

The strip: incompressible plane stress, neo-Hookean C10 = 0.5 MPa (E = 6 C10 = 3 mu),
h = 10 mm, w = 20 mm (w differs from 1 and from h, so that a slip in the per-unit-width
moment M / w or in the face weight 12 / h^3 shows), slenderness L / h as stated.

References, derived before the runs:

- **the linear limit**: a conservative couple bends an inextensible, unshearable beam into
  a circular arc, theta = M L / (E I) exactly (no geometric nonlinearity); the continuum
  adds (i) the material's and the thickness's nonlinearity, O((kappa h)^2) relative
  (kappa = theta / L), below 1e-6 for the small moments here, and (ii) the clamp's end
  effect: the clamped face cannot contract laterally (nu = 1/2), a constraint that can
  only stiffen (the compliance of a constrained subspace is smaller), local to about a
  height h, where it raises the bending stiffness at most to the plane-strain value
  E / (1 - nu^2) = 4/3 E: |theta / theta_lin - 1| <= (1 - (1 - nu^2)) h / L = h / (4 L)
  with theta below theta_lin. Being local to the clamp, it and its mesh error scale with
  h / L: halving h / L on the same cells per height halves the departure. On the ``slide``
  support (u_x = 0 on the face, u_y = 0 at its centre: a plane of symmetry) there is no
  end effect at the root, and linear pure bending (u_x = -kappa x y,
  u_y = kappa (x^2 + y^2 / 2) / 2) is in the Q2 space: theta = theta_lin to the
  nonlinearity (i) and Newton;
- **finite pure bending** (:func:`pure_bending`): the exact bending of the 2D plane-stress
  strip into a sector, x = r(Y) (sin kappa X, 1 - cos kappa X)-like with the fibres'
  stretches lambda_1 = kappa r, lambda_2 = r'; stationarity of int W(kappa r, r') dY gives
  d/dY (dW/dlambda_2) = kappa dW/dlambda_1 with dW/dlambda_2 = 0 on Y = +-h/2, and
  M = int dW/dlambda_1 r dY (a BVP solved by scipy's solve_bvp). The couple's theta is
  kappa L exactly there (the end face is radial and straight). For M = 2 pi E I / L it
  gives theta = 2 pi (1 + 0.1917 (kappa h)^2): the stretch departure, 0.30 % at L / h = 50.
  The FE's departure from it: at the loaded face the couple's traction is linear in Y
  and the exact one is not; the difference is self-equilibrated and even in Y to first
  order in kappa h, so it moves the face's first moment (odd in Y) only at second order:
  O((kappa h)^2 h / L); plus the mesh error (measured: 5e-5 relative between 4 and 8
  cells across at L / h = 50 on the slide).
"""
import math

import numpy as np
import pytest

from contract.scene import scene_from_dict

from .conftest import tiered

pytestmark = pytest.mark.dolfinx

C10 = 0.5e6                  # Pa
E = 6.0 * C10                # Pa, incompressible plane stress (E = 3 mu)
H, W = 0.01, 0.02            # m
EI = E * W * H ** 3 / 12.0   # N m^2, the full width
RTOL = 1e-10                 # Newton's, on the residual


def _scene(M: float, slender: float, cells_height: int = 4, left: str = "clamp", steps: int = 20,
           backend: str = "dolfinx", aspect: float = 2.0, max_iterations: int = 25, **fem):
    return scene_from_dict({
        "name": f"end-moment-{left}-{slender:g}", "beam": {"length": slender * H, "height": H, "width": W},
        "material": {"law": "neo-hookean", "formulation": "plane-stress", "density": 1000.0, "C10": C10},
        "supports": {"left": left}, "loads": {"end_moment": M},
        "analysis": {"kind": "static", "load_steps": steps, "newton_rtol": RTOL, "max_iterations": max_iterations},
        "fem": {"cells_height": cells_height, "aspect": aspect, "backend": backend, **fem}})


def _run(*args, **kw) -> dict:
    from reference_fem.simulation import run_scene

    rec = run_scene(_scene(*args, **kw))
    assert rec["status"] == "converged", rec["reason"]
    return rec


def _model(scene):
    from reference_fem.settings import fem_settings
    from reference_fem.simulation import backend

    return backend(scene.fem["backend"]).static_model(scene, fem_settings(scene))


# -- the exact finite pure bending of the plane-stress strip (module doc) --------------------------------
def pure_bending(k: float) -> tuple[float, float, float]:
    """Pure bending of the incompressible neo-Hookean plane-stress strip at k = kappa h:
    (M / (2 C10 h^2), N / (2 C10 h), r(0) / h), per unit width: the moment, the axial force
    (zero: a check) and the centre fibre's radius. W / (2 C10) = (l1^2 + l2^2 + l1^-2 l2^-2 - 3) / 2;
    the unknown is the radius's offset rho = r / h - 1 / k (of order h, well scaled for any k),
    so that l1 = 1 + k rho and M = int P1 rho (as int P1 = 0)."""
    from scipy.integrate import simpson, solve_bvp

    P1 = lambda l1, l2: l1 - l1 ** -3 * l2 ** -2      # dW/dl1 / (2 C10)
    P2 = lambda l1, l2: l2 - l1 ** -2 * l2 ** -3
    dP2_dl1 = lambda l1, l2: 2.0 * l1 ** -3 * l2 ** -3
    dP2_dl2 = lambda l1, l2: 1.0 + 3.0 * l1 ** -2 * l2 ** -4

    def ode(e, z):      # z = (rho, rho') at e = Y / h: d/de P2 = k P1
        rho, rp = z
        l1 = 1.0 + k * rho
        return np.vstack([rp, (k * P1(l1, rp) - dP2_dl1(l1, rp) * k * rp) / dP2_dl2(l1, rp)])

    def bc(za, zb):
        return np.array([P2(1.0 + k * za[0], za[1]), P2(1.0 + k * zb[0], zb[1])])

    e = np.linspace(-0.5, 0.5, 21)
    sol = solve_bvp(ode, bc, e, np.vstack([e, np.ones_like(e)]), tol=1e-10, max_nodes=100000)
    assert sol.success, sol.message
    ef = np.linspace(-0.5, 0.5, 4001)
    rho, rp = sol.sol(ef)
    p1 = P1(1.0 + k * rho, rp)
    return float(simpson(p1 * rho, x=ef)), float(simpson(p1, x=ef)), 1.0 / k + float(sol.sol(0.0)[0])


def pure_bending_rotation(M: float, slender: float) -> tuple[float, float]:
    """(theta = kappa L, r(0) / L) of the strip of slenderness L / h under the moment M
    (full width), from :func:`pure_bending`."""
    from scipy.optimize import brentq

    m = M / W / (2.0 * C10 * H ** 2)
    lin = M / EI * H                     # kappa h of the linear theory
    k = brentq(lambda k: pure_bending(k)[0] - m, 0.7 * lin, 1.3 * lin, xtol=1e-15)
    return k * slender, pure_bending(k)[2] / slender


def test_pure_bending_reference_has_the_linear_limit_and_no_axial_force():
    """At k = kappa h = 1e-3: M = E I kappa to 1e-5 (the next term is O(k^2) = 1e-6; the BVP's
    tolerance 1e-10). The axial force N = int P1 = (P2(h/2) - P2(-h/2)) / k vanishes to the
    BVP's tolerance on the boundary stresses: |N| <= 2e-10 / k (2 C10 h units)."""
    k = 1e-3
    m, n, r0 = pure_bending(k)
    assert m * 2.0 * C10 * H ** 2 == pytest.approx(E * H ** 3 / 12.0 * k / H, rel=1e-5)
    assert abs(n) <= 2e-10 / k and r0 == pytest.approx(1.0 / k, rel=1e-6)


# -- the couple's force and tangent ---------------------------------------------------------------------
class _Probe:
    """A backend's static model through one interface: the residual at (w, t), the
    couple's tangent applied to v, and the face's first moment by an independent route
    (DOLFINx: a UFL functional over the end facets; FElupe: the face's nodes with
    Simpson's rule coded here)."""

    def __init__(self, backend: str, scene):
        self.backend, self.model = backend, _model(scene)
        self.S = self.model.system
        b = scene.beam
        self.M = scene.loads.end_moment / b.width
        self.weight = 12.0 / b.height ** 3
        if backend == "dolfinx":
            import ufl

            from reference_fem.dolfinx_backend import fem

            d = self.model.setup.disc
            ds = d.boundary_measure(lambda x: np.abs(x[0] - b.length) < 1e-9)
            X = ufl.SpatialCoordinate(d.mesh)
            r = X + d.split(d.w)[0]
            self._d = [fem.Functional(r[i] * X[1] * ds) for i in range(2)]
            fixed = np.concatenate([bc.dof_indices()[0] for bc in self.S.bcs])
            self.free = np.ones(len(d.w.x.array), bool)
            self.free[fixed] = False
        else:
            pts = self.model.setup.mesh.points
            self.face = np.flatnonzero(np.abs(pts[:, 0] - b.length) < 1e-9)
            y = pts[self.face, 1]
            order = np.argsort(y)
            wts = np.zeros(len(y))
            for k in range(0, len(y) - 2, 2):          # [1, 4, 1] dy / 6 on each cell
                i = order[k:k + 3]
                wts[i] += np.array([1.0, 4.0, 1.0]) * (y[i[2]] - y[i[0]]) / 6.0
            self.wy = wts * y
            self.X = pts[self.face]
            self.free = ~self.S.fixed

    def set(self, w, t):
        self.S.restore(w)
        self.model.set_load(t)

    def residual(self, w, t) -> np.ndarray:
        self.set(w, t)
        if self.backend == "dolfinx":
            self.S.residual_norm()
            return self.S.residual()
        return self.S.residual(self.S.w)

    def couple_tangent(self, w, t, v) -> np.ndarray:
        self.set(w, t)
        if self.backend == "dolfinx":
            couple = self.model.couple
            _, C = couple.coefficients(self.S.x)
            U = np.array([g.array for g in couple.vectors])
            return U.T @ (C @ (U @ v))
        K1 = self.S.tangent(self.S.w)
        self.model.set_load(0.0)
        return (K1 - self.S.tangent(self.S.w)) @ v

    def potential(self, w, t) -> float:
        """-t M_p theta(d(w)) (per unit width) with d by the independent route."""
        from mechanics.end_rotation import face_rotation

        self.set(w, t)
        if self.backend == "dolfinx":
            d = self.weight * np.array([f() for f in self._d])
        else:
            u = self.S.w[:self.model.setup.fields[0].values.size].reshape(-1, 2)[self.face]
            d = self.weight * (self.wy @ (self.X + u))
        return -t * self.M * face_rotation(d)


@pytest.mark.parametrize("backend", ["dolfinx", "felupe"])
def test_couple_force_is_its_potential_gradient_and_its_tangent_the_force_derivative(backend):
    """L / h = 10, 10 x 2 Q2 cells, at the equilibrium under M = E I / (2 L) (theta about
    0.5 rad) perturbed by a random field of 1e-6 m: the couple's force f = R(w, t) - R(w, 0)
    against central differences of the potential -t M theta(d(w)) (d by the independent
    route) along a random v, and the couple's tangent applied to v against central
    differences of f. With |dd| ~ 1e-4 per step the truncation is (dd)^2 ~ 1e-8 relative and
    the round-off 1e-16 / 1e-4 ~ 1e-12: tolerance 1e-6, relative. DOLFINx also checks its
    Sherman-Morrison-Woodbury solve: (A + U C U^T) x = b to 1e-8 relative (LU round-off
    times the condition number, ~1e-16 x 1e6)."""
    from reference_fem.statics import solve_static

    M = EI / (2.0 * 10 * H)
    p = _Probe(backend, _scene(M, 10, cells_height=2, steps=4, backend=backend))
    res = solve_static(p.S, p.model.set_load, 4, RTOL, 25)
    assert res.status == "converged"
    rng = np.random.default_rng(7)
    w0 = p.S.save()
    free = p.free                 # not the clamp's rows
    w = w0 + 1e-6 * rng.standard_normal(w0.size) * free
    v = 1e-6 * rng.standard_normal(w0.size) * free
    t = 1.0
    f = p.residual(w, t) - p.residual(w, 0.0)
    eps = 1.0
    dpi = (p.potential(w + eps * v, t) - p.potential(w - eps * v, t)) / (2 * eps)
    assert abs(f @ v - dpi) <= 1e-6 * abs(dpi), (f @ v, dpi)
    df = ((p.residual(w + eps * v, t) - p.residual(w + eps * v, 0.0))
          - (p.residual(w - eps * v, t) - p.residual(w - eps * v, 0.0))) / (2 * eps)
    Kv = p.couple_tangent(w, t, v)
    assert np.linalg.norm(Kv - df) <= 1e-6 * np.linalg.norm(df)
    if backend == "dolfinx":
        S = p.S
        b = rng.standard_normal(w0.size) * free
        p.set(w, t)
        S.residual_norm()
        x = S.tangent_solve(b)
        xv, Ax = S.b.duplicate(), S.b.duplicate()
        xv.array[:] = x
        S.A.mult(xv, Ax)
        total = Ax.array + p.couple_tangent(w, t, x)
        assert np.linalg.norm(total - b) <= 1e-8 * np.linalg.norm(b)


# -- Newton ------------------------------------------------------------------------------------------------
def _history(S, r_ref: float, iterations: int = 12) -> list[float]:
    """||R|| / r_ref of ``iterations`` Newton iterates of the current increment (fewer if it
    blows up): past convergence the residual sits on its round-off floor."""
    out = []
    for _ in range(iterations):
        out.append(S.residual_norm() / r_ref)
        if out[-1] > 1e6:
            break
        S.newton_update()
    return out


def _order(history: list[float]) -> float:
    """The convergence order p = log(r3 / r2) / log(r2 / r1) of the last three residuals
    above the round-off floor (1e3 x the smallest residual of the history)."""
    r = [x for x in history if x > 1e3 * min(history)]
    r1, r2, r3 = r[-3:]
    return math.log(r3 / r2) / math.log(r2 / r1)


@pytest.mark.parametrize("backend", ["dolfinx", "felupe"])
def test_newton_converges_quadratically_past_half_a_turn(backend, monkeypatch):
    """M = 2 pi E I / L, L / h = 20, 20 x 2 cells: the path to t = 0.45 (theta = 2.83 rad), then
    the increment to t = 0.5 (theta = 3.15 > pi). Exact Newton's order is 2 near the
    solution (pre-asymptotic estimates from three residuals can exceed it); an inexact
    tangent converges linearly, p = 1: the test asks p >= 1.8 (measured 3.2). Without the
    couple's rank-2 tangent (C = 0, everything else the same) the same increment does not
    converge within 12 iterations (it wanders: measured residuals 1e-2 to 9): the term is
    what Newton needs."""
    from reference_fem import couple
    from reference_fem.statics import reference_residual
    from mechanics.newton import newton

    def at_half_turn():
        model = _model(_scene(2 * math.pi * EI / (20 * H), 20, cells_height=2, backend=backend))
        S = model.system
        r_ref = reference_residual(S, model.set_load)
        for k in range(1, 10):
            model.set_load(k / 20)
            newton(S, r_ref, RTOL, 25)
        assert model.rotation() == pytest.approx(2.83, abs=0.01)
        return model, S, r_ref

    model, S, r_ref = at_half_turn()
    model.set_load(0.5)
    history = _history(S, r_ref)
    assert min(history) < 1e-10 and model.rotation() > math.pi, history
    assert _order(history) >= 1.8, history

    model, S, r_ref = at_half_turn()
    exact = couple.EndMoment.coefficients
    monkeypatch.setattr(couple.EndMoment, "coefficients", lambda self, x: (exact(self, x)[0], 0.0 * exact(self, x)[1]))
    model.set_load(0.5)
    history = _history(S, r_ref)
    assert min(history) > 1e-6, history


# -- the linear limit and the full roll-up ---------------------------------------------------------------------
def test_small_moment_gives_the_linear_rotation():
    """theta_lin = M L / (E I) = 0.01 rad on 4 cells across (aspect 2): clamped at L / h = 20 and
    40, theta below theta_lin by at most h / (4 L) (the clamp's end effect, module doc) plus
    the mesh error of 4 cells across (measured at L / h = 20: -0.183, -0.112, -0.085 % on
    2, 4, 8 cells, Richardson -0.069 %: 0.043 %; allowed 0.1 %); the departure is local to
    the clamp, so it halves with h / L: the ratio of the two departures is 2 to O(h / L),
    allowed 1.8 to 2.2. On the slide (no end effect, linear pure bending in Q2) theta_lin
    to 1e-6 (the nonlinearity (kappa h)^2 = (0.01 h / L)^2 ~ 1e-7, and Newton)."""
    theta_lin = 0.01
    dep = {}
    for slender in (20, 40):
        M = theta_lin * EI / (slender * H)
        rec = _run(M, slender, steps=1)
        dep[slender] = rec["tip"]["rotation"] / theta_lin - 1.0
        assert -(1.0 / (4 * slender) + 1e-3) <= dep[slender] < 0.0, dep
    assert 1.8 <= dep[20] / dep[40] <= 2.2, dep
    rec = _run(theta_lin * EI / (20 * H), 20, left="slide", steps=1)
    assert rec["tip"]["rotation"] == pytest.approx(theta_lin, rel=1e-6)


# the slide's roll-up in the quick tier, the clamp's (about 3.5 s) in the full one
@pytest.mark.parametrize("left", tiered(["slide", "clamp"], lambda left: left == "clamp",
                                        "test_full_roll_up_goes_round_the_circle"))
def test_full_roll_up_goes_round_the_circle(left):
    """M = 2 pi E I / L, L / h = 50, 100 x 4 cells, 20 load steps: theta past pi and near
    2 pi, against finite pure bending (module doc: theta_pb = 6.3023, 2 pi (1 + 0.1917 (kappa
    h)^2), 0.30 % above 2 pi): within (kappa h)^2 h / L (the loaded face, 3.2e-4) + 1e-4 (the
    mesh: 2 x the measured 4-to-8-cells difference) = 4.2e-4, and for the clamp h / (4 L) more
    (its end effect, below). The tip closes the circle: it lies on the pure-bending arc of
    its own rotation through the fixed root centre, r0 (sin theta, 1 - cos theta) with the
    centre fibre's radius r0, within 1e-3 h + theta's tolerance times r0 (a face's
    end-effect displacement of (kappa h)^2 h / 10, and the arc's sensitivity to theta),
    and near the root: the exact arc's 0.30 % overshoot of 2 pi leaves it r0 (theta_pb - 2 pi)
    = 0.003 L past the root, allowed 0.01 L (a rotation folded back to theta - 2 pi = 0.02
    would pass this but not theta > pi)."""
    slender = 50
    L = slender * H
    M = 2 * math.pi * EI / L
    theta_pb, r0 = pure_bending_rotation(M, slender)
    assert theta_pb / (2 * math.pi) - 1 == pytest.approx(0.1917 * (2 * math.pi / slender) ** 2, rel=0.01)
    rec = _run(M, slender, left=left)
    theta = rec["tip"]["rotation"]
    kh = theta_pb / slender
    tol = kh ** 2 / slender + 1e-4 + (1.0 / (4 * slender) if left == "clamp" else 0.0)
    assert theta > math.pi
    assert abs(theta / theta_pb - 1) <= tol, (theta, theta_pb)
    if left == "clamp":
        assert theta < theta_pb
    tip = np.array([L + rec["tip"]["ux"], rec["tip"]["uy"]])
    arc = r0 * L * np.array([math.sin(theta), 1 - math.cos(theta)])
    assert np.linalg.norm(tip - arc) <= 1e-3 * H + tol * theta * r0 * L, (tip, arc)
    assert np.linalg.norm(tip) <= 0.01 * L


# -- the two codes, and 3D ------------------------------------------------------------------------------------------
def test_dolfinx_and_felupe_agree_on_the_same_mesh():
    """theta about 1 rad (M = E I / L), L / h = 20, 20 x 2 cells, both backends: the same
    discrete equations (Q2, quadrature exact to degree 4 in both, the couple's G exact in
    both), so the same answer to Newton's tolerance (rtol 1e-10 on the residual: ~1e-10 of
    the state, allowed 1e-8): theta and the tip. The records name each backend's method."""
    M = EI / (20 * H)
    a, b = (_run(M, 20, cells_height=2, steps=4, backend=k) for k in ("dolfinx", "felupe"))
    assert a["tip"]["rotation"] == pytest.approx(1.0, abs=0.01)
    assert b["tip"]["rotation"] == pytest.approx(a["tip"]["rotation"], rel=1e-8)
    for k in ("ux", "uy"):
        assert abs(a["tip"][k] - b["tip"][k]) <= 1e-8 * 20 * H
    assert "Sherman-Morrison-Woodbury" in a["end_moment"] and "dense block" in b["end_moment"]
    assert "end_moment" in a["effects"] and "end_moment" in b["effects"]


# DOLFINx's case in the full tier (about 5 s), FElupe's stays quick
@pytest.mark.parametrize("backend", tiered(["dolfinx", "felupe"], lambda b: b == "dolfinx",
                                           "test_3d_with_plane_strain_sides_is_the_2d_plane_strain_answer"))
def test_3d_with_plane_strain_sides_is_the_2d_plane_strain_answer(backend):
    """The 3D model's couple (weight 1 / (h^3 w / 12), the full moment) on 10 x 2 x 1 Q2/Q1
    hexahedra with u_z = 0 on the side faces holds the 2D plane-strain solution exactly (its
    z-independent extension satisfies the 3D equations), so it equals the 2D model's (M / w
    per unit width) to Newton's tolerance (allowed 1e-8, relative); theta about 0.5 rad."""
    from reference_fem.simulation import run_scene

    def scene(fem):
        return scene_from_dict({
            "name": "end-moment-3d", "beam": {"length": 10 * H, "height": H, "width": W},
            "material": {"law": "neo-hookean", "formulation": "plane-strain", "density": 1000.0, "C10": C10,
                         "penalty": 1e9},
            "supports": {"left": "clamp"}, "loads": {"end_moment": 0.5 * 4 * C10 * 2 * W * H ** 3 / 12 / (10 * H)},
            "analysis": {"kind": "static", "load_steps": 4, "newton_rtol": RTOL},
            "fem": {"cells_height": 2, "cells_length": 10, "backend": backend, **fem}})

    a = run_scene(scene({}))
    b = run_scene(scene({"model": "3d", "cells_width": 1, "side_faces": "plane-strain"}))
    assert a["status"] == b["status"] == "converged"
    assert a["tip"]["rotation"] == pytest.approx(0.5, abs=0.01)
    for k in ("rotation", "ux", "uy"):
        assert b["tip"][k] == pytest.approx(a["tip"][k], rel=1e-8)


def test_a_failed_path_whose_eigen_solve_does_not_answer_is_still_a_record(monkeypatch):
    """A failed static run is diagnosed (unstable directions along the failed increment); when
    the eigen solve gives no count (None), the record says "failed" with its reason instead of
    the run ending in a TypeError (it wrote no record before)."""
    from reference_fem.dolfinx_backend.fem import NonlinearSystem
    from reference_fem.simulation import run_scene

    monkeypatch.setattr(NonlinearSystem, "unstable_directions", lambda self: None)
    sc = _scene(2 * math.pi * EI / (4 * H), 4.0, cells_height=2, steps=1, max_iterations=1)
    rec = run_scene(sc)
    assert rec["status"] == "failed" and rec["reason"]
    assert rec["failure"]["unstable_directions"] == 0
