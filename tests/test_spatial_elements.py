"""Contract tests of every registered spatial element (:mod:`ancf.kinematics.spatial`), each
property by a route of its own: the shape functions take their nodal values; a homogeneous
deformation is reproduced exactly and its internal force is the surface traction's (the
patch test, the force by a surface rule); a rigid motion strains nothing; the force is the
energy's gradient and the tangent the force's (Taylor tests); and the 3D density of a plane
strain is the planar solver's plane-strain density (:class:`ancf.core.material.Material`,
its own chain rule in the 2D invariants)."""
from __future__ import annotations

import numpy as np
import pytest

from ancf.kinematics.spatial import SPATIAL_ELEMENTS
from ancf.kinematics.spatial.beam import SpatialBeam
from ancf.kinematics.spatial.energy import stress
from ancf.kinematics.spatial.spec import SpatialSpec, kind_orders
from mechanics.laws import LAWS, get_law

from .conftest import tiered

L, H, W = 0.35, 0.005, 0.007          # m, the paper's pendulum section
ALPHA = 2.0e8                        # Pa, a penalty of the order of the suite's
LAW_CONSTANTS = {"neo-hookean": {"C10": 0.5e6}, "mooney-rivlin": {"C10": 0.4e6, "C01": 0.1e6},
                 "yeoh": {"C10": 545235.0, "C20": 61049.8, "C30": -802.537}}
ELEMENTS = list(SPATIAL_ELEMENTS)


def beam(name: str, law: str = "mooney-rivlin", elements: int = 2, grading: float = 1.0) -> SpatialBeam:
    return SpatialBeam(SPATIAL_ELEMENTS[name], L, H, W, elements, law, LAW_CONSTANTS[law], ALPHA, grading=grading)


def rotation(rng) -> np.ndarray:
    Q, R = np.linalg.qr(rng.standard_normal((3, 3)))
    Q = Q * np.sign(np.diag(R))
    return Q if np.linalg.det(Q) > 0 else -Q


def homogeneous(b: SpatialBeam, F0: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Nodal coordinates of r(X) = F0 X + c: each kind the matching derivative."""
    out = []
    for x in b.node_positions():
        for k in b.spec.kinds:
            d = kind_orders(k)
            out.append(F0 @ np.array([x, 0.0, 0.0]) + c if sum(d) == 0
                       else F0[:, d.index(1)] if sum(d) == 1 else np.zeros(3))
    return np.array(out)


@pytest.mark.parametrize("name", ELEMENTS)
def test_the_shape_functions_take_their_nodal_values(name):
    """d^k N_m at node n is 1 for m's own node and kind and 0 otherwise (physical units,
    an element 3 x its height long); the reference coordinates give r = X and F = I."""
    spec = SPATIAL_ELEMENTS[name]
    le = 3.0 * H
    for a, xi in enumerate(spec.nodes):
        for b_, k in enumerate(spec.kinds):
            dx, dy, dz = kind_orders(k)
            polys, C = spec.dimensionless(le, H, W)
            row = np.array([p(xi, 0.0, 0.0, (dx, dy, dz)) for p in polys]) @ C
            want = np.zeros(spec.n_shape)
            want[a * len(spec.kinds) + b_] = 1.0
            assert np.allclose(row, want, rtol=0.0, atol=1e-12), (xi, k)
    rng = np.random.default_rng(3)
    X = np.column_stack([rng.uniform(0, 1, 20), rng.uniform(-0.5, 0.5, 20), rng.uniform(-0.5, 0.5, 20)])
    N, dN = spec.tabulate(X[:, 0], X[:, 1], X[:, 2], le, H, W)
    q = np.concatenate([spec.reference_coordinates(xi * le) for xi in spec.nodes])
    assert np.allclose(N @ q, X * [le, H, W], rtol=0.0, atol=1e-15)
    assert np.allclose(np.einsum("mi,pmJ->piJ", q, dN), np.eye(3), rtol=0.0, atol=1e-12)


@pytest.mark.parametrize("name", ELEMENTS)
def test_a_homogeneous_deformation_is_exact_and_its_force_is_the_surface_tractions(name):
    """r = F0 X + c: F = F0 at every point, the energy W(F0) V with W from the law's psi
    on invariants taken by numpy, and the internal force the work-equivalent of the
    surface traction P0 n (a Gauss rule on the beam's six faces, exact for the
    polynomials). On a graded beam (three elements, each 0.6 times the one before it)."""
    rng = np.random.default_rng(7)
    b = beam(name, elements=3, grading=0.6)
    F0 = np.eye(3) + 0.15 * rng.standard_normal((3, 3))
    q = homogeneous(b, F0, rng.standard_normal(3) * 1e-3)
    for e in range(b.elements):
        assert np.allclose(b.gradients(q, e), F0, rtol=0.0, atol=1e-12)
    C = F0.T @ F0
    J = np.linalg.det(F0)
    I1, I2 = np.trace(C), 0.5 * (np.trace(C) ** 2 - np.trace(C @ C))
    law = get_law(b.law)
    W0 = law.psi(J ** (-2 / 3) * I1, J ** (-4 / 3) * I2, b.constants) + 0.5 * ALPHA * (J - 1.0) ** 2
    assert b.energy(q) == pytest.approx(W0 * L * H * W, rel=1e-12)

    _, P0, _ = stress(b.law, b.constants, ALPHA, F0[None], tangent=False)
    P0 = P0[0]
    g, wg = np.polynomial.legendre.leggauss(6)
    f = np.zeros((b.n_global, 3))
    # the end faces x = 0 (n = -e_x) and x = L (n = +e_x)
    for e, xi, sign in ((0, 0.0, -1.0), (b.elements - 1, 1.0, 1.0)):
        Y, Z = np.meshgrid(g / 2, g / 2, indexing="ij")
        N, _ = b.spec.tabulate(np.full(Y.size, xi), Y.ravel(), Z.ravel(), b.lengths[e], H, W)
        wa = np.outer(wg, wg).ravel() / 4 * H * W
        np.add.at(f, b.element_rows(e), np.einsum("p,pm,i->mi", wa, N, sign * P0[:, 0]))
    # the lateral faces of every element: y = +-h/2 (n = +-e_y), z = +-w/2 (n = +-e_z)
    for e in range(b.elements):
        X1, T = np.meshgrid((g + 1) / 2, g / 2, indexing="ij")
        wa = np.outer(wg / 2, wg / 2).ravel()
        for axis, size, other in ((1, W, H), (2, H, W)):
            for s in (-1.0, 1.0):
                pts = [X1.ravel(), None, None]
                pts[axis] = np.full(X1.size, s / 2)
                pts[3 - axis] = T.ravel()
                N, _ = b.spec.tabulate(*pts, b.lengths[e], H, W)
                np.add.at(f, b.element_rows(e), np.einsum("p,pm,i->mi", wa * b.lengths[e] * size, N, s * P0[:, axis]))
    scale = np.abs(P0).max() * H * W
    assert np.allclose(b.force(q).reshape(-1, 3), f, rtol=0.0, atol=1e-10 * scale)


@pytest.mark.parametrize("name", ELEMENTS)
def test_a_rigid_motion_strains_nothing(name):
    """Every nodal vector turned by one rotation and the positions moved: energy and force
    zero to round-off (the density is stress free at F = I and objective)."""
    rng = np.random.default_rng(11)
    b = beam(name, "yeoh")
    Q = rotation(rng)
    q = homogeneous(b, Q, rng.standard_normal(3))
    scale = 2.0 * b.constants["C10"] * H * W
    assert abs(b.energy(q)) < 1e-12 * scale * L
    assert np.abs(b.force(q)).max() < 1e-10 * scale


@pytest.mark.parametrize("law", list(LAW_CONSTANTS))
@pytest.mark.parametrize("name", ELEMENTS)
def test_the_force_is_the_energys_gradient_and_the_tangent_the_forces(name, law):
    """Taylor tests at a bent, stretched, twisted state: the remainders of the first-order
    expansions fall by 4 (within 1.25 %) at each halving of the step; the tangent is
    symmetric to round-off. The steps (2e-6 m per coordinate) are small enough that a
    tangent 1e-3 off in one term of d2I2/dF2 halves its remainder by 3 or less (tried), and
    large enough that round-off stays below 0.1 % of the remainders."""
    rng = np.random.default_rng(5)
    b = beam(name, law)
    q = b.reference() + 0.02 * rng.standard_normal((b.n_global, 3)) * np.array([L, H, W]).mean() / 10
    f, K = b.force(q), b.tangent(q)
    dq = rng.standard_normal(b.dof) * 2e-6
    r1, r2 = [], []
    for h in (1.0, 0.5, 0.25):
        qh = q + (h * dq).reshape(q.shape)
        r1.append(b.energy(qh) - b.energy(q) - h * f @ dq)
        r2.append(np.linalg.norm(b.force(qh) - f - h * K @ dq))
    for r in (r1, r2):
        ratios = np.array(r[:-1]) / np.array(r[1:])
        assert np.all(np.abs(ratios - 4.0) < 0.05), ratios
    assert np.abs(K - K.T).max() < 1e-12 * np.abs(K).max()


@pytest.mark.parametrize("name", ELEMENTS)
def test_the_banded_tangent_is_the_dense_one(name):
    """The band storage the statics solve holds the dense tangent's entries exactly, on a
    graded beam of three elements (its half-bandwidth: an element's dof span), and the
    band's solve is the Jacobi-scaled dense solve's to round-off (the kinds' scales differ by
    many decades, r_yyyz's in 1/m^3: an unscaled dense solve is the less accurate one), in the
    scaled unknowns, to a hundred times the scaled matrix's condition number times eps,
    compared on the straight beam's tangent (positive definite: a random state's tangent is
    indefinite, its conditioning unknown)."""
    rng = np.random.default_rng(7)
    b = beam(name, elements=3, grading=1.3)
    q = b.reference() + 1e-4 * rng.standard_normal((b.n_global, 3))
    K, B = b.tangent(q), b.tangent_banded(q)
    assert B.b == 3 * len(b.spec.kinds) * len(b.spec.nodes) - 1        # an element's dof span
    assert np.array_equal(B.to_sparse().toarray(), K)
    K, B = b.tangent(b.reference()), b.tangent_banded(b.reference())
    fixed = np.arange(3 * len(b.spec.kinds))
    free = np.setdiff1d(np.arange(b.dof), fixed)
    r = rng.standard_normal(b.dof)
    r[fixed] = 0.0
    x = B.constrain(fixed).solve(r)
    Kf = K[np.ix_(free, free)]
    d = 1.0 / np.sqrt(np.abs(np.diag(Kf)))          # the dense solve the statics took, Jacobi-scaled alike
    S = d[:, None] * Kf * d[None, :]
    ev = np.linalg.eigvalsh(S)
    assert ev[0] > 0.0
    y = d * np.linalg.solve(S, d * r[free])
    # in the scaled unknowns x / d, both solves' error is about cond(S) eps of |x / d|
    assert np.linalg.norm((x[free] - y) / d) <= 100 * ev[-1] / ev[0] * np.finfo(float).eps * np.linalg.norm(y / d)
    assert not x[fixed].any()


@pytest.mark.parametrize("name", ELEMENTS)
def test_the_sum_factorised_tangent_is_the_pointwise_one(name):
    """Every built-in element's shape functions split into along and section factors on its
    rule (:mod:`ancf.kinematics.spatial.product`), and the tangent by sum factorisation is
    the pointwise contraction's on a graded beam at a finite random strain (the law's part
    alone, alpha = 0, so that the penalty's larger terms hide nothing): the same sums of
    10^3 to 10^4 products in two orders, equal to a few hundred eps of the largest entry."""
    rng = np.random.default_rng(11)
    b = SpatialBeam(SPATIAL_ELEMENTS[name], L, H, W, 3, "mooney-rivlin", LAW_CONSTANTS["mooney-rivlin"], 0.0,
                    grading=1.3)
    assert b._product is not None
    q = b.reference() + 1e-4 * rng.standard_normal((b.n_global, 3))
    K, K0 = b.element_tangents(q), b.element_tangents(q, split=False)
    assert np.max(np.abs(K - K0)) <= 1e-13 * np.max(np.abs(K0))


def test_shape_functions_that_are_not_products_take_the_pointwise_tangent():
    """:func:`ancf.kinematics.spatial.product.factors` declines functions that do not split
    (random values on the grid: none is of rank one)."""
    from ancf.kinematics.spatial import product

    rng = np.random.default_rng(3)
    points = (3, 2, 2)
    N, dN = rng.standard_normal((2, 12, 5)), rng.standard_normal((2, 12, 5, 3))
    assert product.factors(N, dN, points, np.array([0.1, 0.2]), H, W) is None


@pytest.mark.parametrize("law", sorted(LAWS.builtin))
def test_a_plane_strain_is_the_planar_solvers_plane_strain(law):
    """F = [[F2, 0], [0, 1]]: the 3D density, stress and tangent equal the planar
    plane-strain formulation's (its chain rule in (tr C, det F), :mod:`ancf.core.material`),
    so the spatial elements evaluate the same law, not a law of their own."""
    from ancf.core.formulations import get_formulation
    from ancf.core.material import Material

    c = LAW_CONSTANTS.get(law) or dict(get_law(law).example)
    rng = np.random.default_rng(2)
    F2 = np.eye(2) + 0.04 * rng.standard_normal((6, 2, 2))     # inside Gent's example domain too
    F3 = np.zeros((6, 3, 3))
    F3[:, :2, :2], F3[:, 2, 2] = F2, 1.0
    W3, P3, A3 = stress(law, c, ALPHA, F3)
    W2, P2, A2 = Material(get_law(law), get_formulation("plane-strain"), c, ALPHA).evaluate(F2)
    assert np.all(np.isfinite(W2)) and np.allclose(W3, W2, rtol=1e-12)
    assert np.allclose(P3[:, :2, :2], P2, rtol=1e-10, atol=1e-9 * np.abs(P2).max())
    A3in = A3[:, :2, :2, :2, :2].reshape(-1, 4, 4)
    assert np.allclose(A3in, A2, rtol=1e-10, atol=1e-9 * np.abs(A2).max())


def test_a_spec_names_what_is_wrong():
    with pytest.raises(ValueError, match="unknown nodal coordinate kind 'r_zy'"):
        SpatialSpec("bad", ("1", "x"), (0.0, 1.0), ("r_zy",))
    with pytest.raises(ValueError, match="3 basis functions but 2 nodes x 1 kinds"):
        SpatialSpec("bad", ("1", "x", "y"), (0.0, 1.0), ("r",))
    with pytest.raises(ValueError, match="do not determine its basis"):
        SpatialSpec("bad", ("1", "y"), (0.0, 1.0), ("r",)).dimensionless(1.0, 0.1, 0.1)


def test_a_static_solve_balances_the_weight_and_its_moment_at_the_clamp():
    """The cantilever under its weight (3243 x 2, neo-Hookean, a mild penalty so that it
    bends: the tip drops by 0.31 of its length): converged, the clamp's reaction on the
    face coordinates (the internal force there) carries the whole weight rho g V, and its
    moment sum_m q_m x R_m is the moment of the weight about the origin in the deformed
    beam, int r x rho g dV by the beam's rule (translation and rotation invariance of the
    energy: two checks of the solve that no stiffness enters)."""
    from ancf.kinematics.spatial.beam import gauss_box
    from ancf.kinematics.spatial.statics import clamp_rows, gravity_load, solve_static

    rho, g = 1000.0, np.array([0.0, -9.81, 0.0])
    b = SpatialBeam(SPATIAL_ELEMENTS["3243"], 0.16, H, W, 2, "neo-hookean", {"C10": 0.2e6}, 2.0e6)
    f = gravity_load(b, rho, g)
    fixed = clamp_rows(b)
    res = solve_static(b, f, fixed, load_steps=2)
    assert res.status == "converged", res.reason
    tip = res.tip(b)
    assert tip["uy"] < -0.3 * b.length
    R = (b.force(res.q) - f).reshape(-1, 3)           # the reactions (zero off the clamp)
    free = np.setdiff1d(np.arange(b.dof), fixed)
    weight = rho * g * b.length * H * W
    assert np.abs(R.ravel()[free]).max() < 1e-8 * np.linalg.norm(weight)
    r_kind = b.spec.kinds.index("r")
    assert np.allclose(R[r_kind], -weight, rtol=0.0, atol=1e-8 * np.linalg.norm(weight))
    X, wq = gauss_box(b.points)
    N, _ = b.spec.tabulate(X[:, 0], X[:, 1], X[:, 2], b.le, H, W)
    moment = sum((wq * b.le * H * W) @ np.cross(N @ res.q[b.element_rows(e)], rho * g) for e in range(b.elements))
    reaction = sum(np.cross(res.q[m], R[m]) for m in range(len(b.spec.kinds)))
    assert np.allclose(reaction, -moment, rtol=0.0, atol=1e-8 * np.abs(moment).max())


PRESSURE_ELEMENTS = [n for n in ELEMENTS if SPATIAL_ELEMENTS[n].pressure]


@pytest.mark.parametrize("name", PRESSURE_ELEMENTS)
def test_the_mixed_iterates_pressures_are_the_projections_linearisation(name):
    """The statics' pressure unknowns: at lambda = q's own projection (:meth:`pressures`) the
    mixed tangent is the penalty's exactly, and the linearised pressures are the first-order
    Taylor expansion of the projection (remainders fall by 4, within 1.25 %, per halving of
    the step; the Taylor test's steps and bar)."""
    rng = np.random.default_rng(9)
    b = beam(name, "yeoh", elements=2, grading=1.3)
    q = b.reference() + 0.02 * rng.standard_normal((b.n_global, 3)) * np.array([L, H, W]).mean() / 10
    assert np.array_equal(b.tangent(q, b.pressures(q)), b.tangent(q))
    dq = rng.standard_normal(b.dof) * 2e-6
    lam = b.pressures(q)
    rem = [np.linalg.norm(b.pressures(q + (h * dq).reshape(q.shape)) - b.linearised_pressures(q, h * dq))
           for h in (1.0, 0.5, 0.25)]
    ratios = np.array(rem[:-1]) / np.array(rem[1:])
    assert np.all(np.abs(ratios - 4.0) < 0.05), ratios
    assert np.linalg.norm(b.linearised_pressures(q, 0.0 * dq) - lam) <= 1e-14 * np.linalg.norm(lam)


@pytest.mark.parametrize("name", ["3363p", "HS2n-72p"])
def test_the_mixed_newton_reaches_the_penalty_problems_equilibrium(name):
    """The statics' full steps with the pressures as unknowns, and the damped steps of the
    penalty problem alone (q's own pressures, the energy's line search): the same
    equilibrium of one increment, the paper's cantilever at a tenth of its weight (two
    graded elements, the paper's penalty), to Newton's tolerance (the tip within 1e-9 of
    its drop; the statics' stop: the force's round-off floor, or a correction below 1e-12 of
    the length)."""
    from mechanics.newton import newton
    from ancf.kinematics.spatial.statics import _Increment, clamp_rows, gravity_load
    from ancf.solvers.statics import ROUNDOFF_FLOOR
    from contract import paper

    c = {k: v for k, v in paper.materials()["neo-hookean"].items() if k != "density"}
    b = SpatialBeam(SPATIAL_ELEMENTS[name], 0.16, H, W, 2, "neo-hookean", c, paper.PENALTY, grading=1.25)
    f = 0.1 * gravity_load(b, paper.materials()["neo-hookean"]["density"])
    free = np.setdiff1d(np.arange(b.dof), clamp_rows(b))
    q0 = b.reference().ravel()
    floor = ROUNDOFF_FLOOR * np.finfo(float).eps * np.linalg.norm(b.force_magnitude(b.reference())[free])
    small = lambda system, r, dw: dw <= 1e-12 * b.length
    tips = {}
    for line_search in (False, True):
        system = _Increment(b, free, q0, f, line_search, b.pressures(q0))
        newton(system, max(np.linalg.norm(f), floor / 1e-10), 1e-10, 200, small)
        tips[line_search] = system.q.reshape(-1, 3)[(b.nodes - 1) * len(b.spec.kinds)] - (0.16, 0.0, 0.0)
    assert tips[False][1] < -1e-3
    assert np.abs(tips[False] - tips[True]).max() < 1e-9 * abs(tips[False][1]), tips


def test_the_residual_tolerance_respects_the_forces_roundoff():
    """The paper's cantilever (3333 x 4, alpha 1000 MPa) at a tenth of its weight: rtol |f|
    lies below the force's round-off, eps |f_int|_terms (:meth:`SpatialBeam.force_magnitude`,
    the penalty's alpha (|J| + 1) |cof F| in it). Newton's residuals at the converged state
    stall between 0.01 and ROUNDOFF_FLOOR times that estimate (the planar statics' bar;
    measured 0.55 to 0.85 times its 9.6e-11 N, rtol |f| 4.3e-11 N), so the floor neither
    accepts an unconverged state nor leaves the tolerance unreachable."""
    from ancf.kinematics.spatial.statics import _Increment, clamp_rows, gravity_load
    from ancf.solvers.statics import ROUNDOFF_FLOOR
    from contract import paper
    from mechanics.newton import newton
    from mechanics.time_loop import StepFailure

    m = paper.materials()["neo-hookean"]
    c = {k: v for k, v in m.items() if k != "density"}
    geo = paper.CANTILEVER
    b = SpatialBeam(SPATIAL_ELEMENTS["3333"], geo["length"], geo["height"], geo["width"], 4, "neo-hookean", c,
                    paper.PENALTY)
    f = 0.1 * gravity_load(b, m["density"], (0.0, -paper.GRAVITY, 0.0))
    free = np.setdiff1d(np.arange(b.dof), clamp_rows(b))
    floor = np.finfo(float).eps * np.linalg.norm(b.force_magnitude(b.reference())[free])
    assert 1e-8 * np.linalg.norm(f) < floor
    system = _Increment(b, free, b.reference().ravel(), f, line_search=False)
    with pytest.raises(StepFailure) as e:           # no stop: 10 full Newton steps
        newton(system, 1.0, 0.0, 10)
    tail = [system.residual_norm()]
    for _ in range(3):
        system.newton_update()
        tail.append(system.residual_norm())
    assert "no convergence" in str(e.value)
    assert 0.01 * floor < min(tail) and max(tail) < ROUNDOFF_FLOOR * floor, (tail, floor)


def test_the_tolerance_floor_holds_the_coordinates_representation():
    """On short elements far from the origin the residual's round-off is the coordinates':
    a position held to eps |x| moves the force by the penalty's stiffness times that. HS2n-72p
    x 12 graded 3 from both ends (0.22 mm elements at x = 0 and at x = 0.16 m) at a tenth of
    its weight: Newton's residuals at the converged state stall above the force evaluation's
    floor alone (ROUNDOFF_FLOOR eps |f_int|_terms, which the tolerance then could not reach;
    measured up to 5.6 times it) and below :func:`roundoff_floor`, which adds eps |K| |q|
    (measured 0.02 to 0.28 of it)."""
    from ancf.kinematics.spatial.statics import _Increment, clamp_rows, gravity_load, roundoff_floor
    from ancf.solvers.statics import ROUNDOFF_FLOOR
    from contract import paper
    from mechanics.newton import newton
    from mechanics.time_loop import StepFailure

    m = paper.materials()["neo-hookean"]
    c = {k: v for k, v in m.items() if k != "density"}
    geo = paper.CANTILEVER
    b = SpatialBeam(SPATIAL_ELEMENTS["HS2n-72p"], geo["length"], geo["height"], geo["width"], 12, "neo-hookean", c,
                    paper.PENALTY, grading=3.0, both_ends=True)
    f = 0.1 * gravity_load(b, m["density"], (0.0, -paper.GRAVITY, 0.0))
    free = np.setdiff1d(np.arange(b.dof), clamp_rows(b))
    terms = ROUNDOFF_FLOOR * np.finfo(float).eps * np.linalg.norm(b.force_magnitude(b.reference())[free])
    floor = roundoff_floor(b, free)
    system = _Increment(b, free, b.reference().ravel(), f, line_search=False)
    with pytest.raises(StepFailure):               # no stop: 12 full Newton steps
        newton(system, 1.0, 0.0, 12)
    tail = [system.residual_norm()]
    for _ in range(4):
        system.newton_update()
        tail.append(system.residual_norm())
    assert terms < max(tail) < floor and 0.01 * floor < max(tail), (tail, terms, floor)


# the sextic torsion modes' rule (4, 6, 6) takes seconds per rule: their cases run in the full tier
@pytest.mark.parametrize("name", tiered(ELEMENTS, lambda name: name in ("HS2n-132p", "HS2n-180p", "HS2n-216p"),
                                        "test_the_default_rule_is_the_cheapest_that_passes_the_rank_test"))
def test_the_default_rule_is_the_cheapest_that_passes_the_rank_test(name):
    """Each element's default rule passes the small-strain rank test (no zero-energy mode
    beyond the six rigid ones, no deformation mode seen below MU_MIN of its exact energy) at
    every l_e / h of the sweep, and each rule with one point fewer in one direction fails at
    one of them (the planar rules' contract, tests/test_rank.py, in 3D)."""
    from ancf.kinematics.spatial.rank import passes

    spec = SPATIAL_ELEMENTS[name]
    rule = spec.default_rule()
    assert passes(spec, rule)
    for a in range(3):
        cheaper = tuple(n - (i == a) for i, n in enumerate(rule))
        if min(cheaper) >= 1:
            assert not passes(spec, cheaper), cheaper
