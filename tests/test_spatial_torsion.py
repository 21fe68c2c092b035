"""Small-twist torsion of the spatial elements (:mod:`ancf.kinematics.spatial`) against
Saint-Venant's (:mod:`studies.verification.torsion`), each side by a route of its own.

- The closed forms: the torsion constant's series against Timoshenko and Goodier's table, and
  the polynomial-warping bound (a least-squares Ritz minimum) against its closed form at
  degree two and three, never below the exact constant and falling to it.
- The elements: a bar on the free-warping support, loaded at both ends by the traction of its
  section's own Saint-Venant state (the warping minimising the energy over the section's
  monomials: none for a linear section, psi = c y z for a quadratic one, closed forms both;
  HS2n-96p's adds y^3 z and y z^3), twists uniformly, its twist rate the torque over mu J
  with J the section's bound. Tolerance: the twist is
  1e-4 rad, so the state departs from the linear one by O(1e-8), and Newton stops at 1e-8
  of the load: 1e-6 of J leaves a hundredfold margin.
"""
from __future__ import annotations

import numpy as np
import pytest

from ancf.kinematics.spatial import SPATIAL_ELEMENTS
from ancf.kinematics.spatial.beam import SpatialBeam
from ancf.kinematics.spatial.statics import end_face_load, free_warping_rows, section_rotation, solve_static
from studies.verification import torsion

H, W, L = 0.005, 0.007, 0.08          # m: the paper's section, a bar 16 h long
MU = 1.0e6                            # Pa, neo-Hookean C10 = mu / 2


def test_the_series_is_timoshenko_and_goodiers_table():
    for ratio, k1 in torsion.TIMOSHENKO_GOODIER_TABLE.items():
        assert torsion.saint_venant_rectangle(1.0, ratio) / ratio == pytest.approx(k1, abs=5e-4), ratio
        assert torsion.saint_venant_rectangle(ratio, 1.0) == torsion.saint_venant_rectangle(1.0, ratio)
    assert torsion.saint_venant_rectangle(1.0, 1e6) / 1e6 == pytest.approx(1.0 / 3.0, rel=1e-5)


@pytest.mark.parametrize("h, w", [(5.0, 7.0), (1.0, 1.0), (1.0, 4.0)])
def test_the_polynomial_warping_bound_is_closed_at_degree_two_and_falls_to_saint_venant(h, w):
    exact = torsion.saint_venant_rectangle(h, w)
    bounds = [torsion.polynomial_warping(h, w, d) for d in range(13)]
    assert bounds[:2] == pytest.approx([torsion.polar_moment(h, w)] * 2, rel=1e-12)
    assert bounds[2:4] == pytest.approx([torsion.quadratic_warping(h, w)] * 2, rel=1e-12)
    assert all(b1 <= b0 * (1 + 1e-12) for b0, b1 in zip(bounds, bounds[1:]))
    assert min(bounds) >= exact * (1 - 1e-12)
    assert bounds[12] == pytest.approx(exact, rel=1e-4)
    # the odd-odd monomials alone carry the warping: a quadratic section with y^3 z and y z^3
    # added is as good as the complete quartic
    quadratic = [(a, c) for a in range(3) for c in range(3 - a)]
    assert torsion.warping_bound(h, w, quadratic + [(3, 1), (1, 3)]) == pytest.approx(bounds[4], rel=1e-12)


@pytest.mark.parametrize("name", list(SPATIAL_ELEMENTS))
def test_a_bar_under_its_sections_saint_venant_traction_twists_uniformly(name):
    spec = SPATIAL_ELEMENTS[name]
    b = SpatialBeam(spec, L, H, W, 2, "neo-hookean", {"C10": MU / 2}, 1e9)
    J, shear = torsion.warping_state(H, W, spec.section_monomials)
    if "r_yz" not in spec.kinds:            # the closed forms: no warping, or psi = c y z alone
        assert J == pytest.approx(torsion.polar_moment(H, W), rel=1e-12)
    elif not {"r_yyyz", "r_yzzz"} & set(spec.kinds):
        assert J == pytest.approx(torsion.quadratic_warping(H, W), rel=1e-12)
    rate = 1e-4 / L
    # the stress of the twist rate's Saint-Venant state in the section, mu rate (psi_y - z, psi_z + y)
    sv = lambda y, z: MU * rate * np.column_stack([0.0 * y, *shear(y, z)])
    # the state's traction on both faces (x = L and, opposite, x = 0): a self-equilibrated load,
    # so the support holds the rigid motion only and carries nothing (with the load at one end,
    # a section with cubic fields y^2 z, z^3 free at a support that holds r, r_y and r_z is
    # not in equilibrium there: those fields do work against the state's shear stress)
    f = end_face_load(b, sv) - end_face_load(b, sv, start=True)
    res = solve_static(b, f, free_warping_rows(b), load_steps=1)
    assert res.status == "converged", res.reason
    xs = b.node_positions()
    angles = np.array([section_rotation(b, res.q, n) for n in range(b.nodes)])
    assert np.allclose(angles, rate * xs, rtol=0.0, atol=1e-6 * rate * L)


@pytest.mark.parametrize("name", list(SPATIAL_ELEMENTS))
def test_the_end_torque_is_a_pure_torque(name):
    """The torque's nodal forces on the straight beam: no resultant (their sum over the
    position coordinates, whose shape functions sum to one) and the moment sum_m q_m x f_m
    (= int X x t dA, as r = sum_m N_m q_m) the torque about x, to round-off."""
    from ancf.kinematics.spatial.statics import end_torque_load

    b = SpatialBeam(SPATIAL_ELEMENTS[name], L, H, W, 2, "neo-hookean", {"C10": MU / 2}, 1e9, grading=0.5)
    T = 0.3
    f = end_torque_load(b, T).reshape(-1, 3)
    k = len(b.spec.kinds)
    r = b.spec.kinds.index("r")
    assert np.abs(f[r::k].sum(axis=0)).max() < 1e-12 * T / H
    moment = np.cross(b.reference(), f).sum(axis=0)
    assert np.allclose(moment, [T, 0.0, 0.0], rtol=0.0, atol=1e-12 * T)


def _twisted_between_plates(name: str, theta: float, shift: float = 0.0, steps: int = 1):
    """The bar clamped at x = 0, its face x = L a rigid plate turned by theta about the axis
    and moved by ``shift`` along it (a prescribed motion, ``held``), in ``steps`` increments."""
    from ancf.kinematics.spatial.statics import clamp_rows, face_rows, rotated_face

    b = SpatialBeam(SPATIAL_ELEMENTS[name], L, H, W, 2, "neo-hookean", {"C10": MU / 2}, 1e9)
    end = b.nodes - 1
    fixed = np.concatenate([clamp_rows(b), face_rows(b, end)])
    clamp = b.reference().ravel()[clamp_rows(b)]

    def held(t):
        c, s = np.cos(t * theta), np.sin(t * theta)
        face = rotated_face(b, end, np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])).reshape(-1, 3)
        face[0, 0] += t * shift                 # the kind r comes first
        return np.concatenate([clamp, face.ravel()])

    assert b.spec.kinds[0] == "r"
    res = solve_static(b, np.zeros(b.dof), fixed, load_steps=steps, held=held)
    assert res.status == "converged", res.reason
    return b, res


@pytest.mark.parametrize("name", ["3363p", "HS2n-96p"])
def test_the_plates_reaction_is_the_derivative_of_the_energy_and_balances_the_clamps(name):
    """Twisted by 0.3 rad between rigid plates (a finite twist: 0.01 shear strain at the
    section's corners, 2 elements): the plate's torque (face_reaction, the generalised
    reactions paired with its rigid virtual motion) is dE/dtheta of the equilibrium energy,
    its axial force dE/dL, both by central differences (steps of 1e-4 theta and 1e-6 L:
    truncation below 1e-7 relative; the equilibrium energy is stationary in the free
    coordinates, so Newton's tolerance leaves it accurate to about 1e-12): the torque to 1e-6;
    the axial force, Poynting's, is small (its differences are 4e-7 of the energy), to 1e-5.
    No load acts: the clamp's and the plate's reactions are equal and opposite, to the free
    coordinates' residual (Newton's 1e-8 of the reactions, whose forces are of order T / h),
    and the moment about x is the only one (the others vanish by symmetry; 1e-9 of the
    torque)."""
    from ancf.kinematics.spatial.statics import face_reaction

    theta, d_theta, d_shift = 0.3, 3e-5, 1e-6 * L
    b, res = _twisted_between_plates(name, theta)
    plate = face_reaction(b, res.q, np.zeros(b.dof), b.nodes - 1)
    clamp = face_reaction(b, res.q, np.zeros(b.dof), 0)
    T, N = plate["moment"][0], plate["force"][0]
    energy = lambda th, dx: b.energy(_twisted_between_plates(name, th, dx)[1].q)
    assert T == pytest.approx((energy(theta + d_theta, 0.0) - energy(theta - d_theta, 0.0)) / (2 * d_theta), rel=1e-6)
    assert N == pytest.approx((energy(theta, d_shift) - energy(theta, -d_shift)) / (2 * d_shift), rel=1e-5)
    arm = np.array([L, 0.0, 0.0])
    assert np.allclose(plate["force"] + clamp["force"], 0.0, rtol=0.0, atol=1e-8 * T / H)
    assert np.allclose(plate["moment"] + clamp["moment"] + np.cross(arm, plate["force"]), 0.0, rtol=0.0,
                       atol=1e-8 * T)
    assert np.abs(plate["moment"][1:]).max() < 1e-9 * T and np.abs(plate["force"][1:]).max() < 1e-9 * T / H


def test_between_plates_the_torque_is_linear_in_the_twist_and_the_poynting_force_quadratic():
    """At small twists the torque is odd in theta and the axial force (Poynting's) even, of
    order theta^2, and compressive: at theta and 2 theta (0.05 and 0.1 rad over 16 h, shear
    strains up to 5e-3 at the corners) T doubles and N quadruples, to the relative O(gamma^2)
    = 3e-5 of the next terms; the reactions' own accuracy (Newton's 1e-8 of the torque's
    forces) is 1e-5 of N at 0.1 rad: tolerance 1e-3."""
    from ancf.kinematics.spatial.statics import face_reaction

    out = []
    for theta in (0.05, 0.1):
        b, res = _twisted_between_plates("HS2n-96p", theta)
        r = face_reaction(b, res.q, np.zeros(b.dof), b.nodes - 1)
        out.append((r["moment"][0], r["force"][0]))
    (T1, N1), (T2, N2) = out
    assert T1 > 0 and N1 < 0
    assert T2 / T1 == pytest.approx(2.0, rel=1e-3)
    assert N2 / N1 == pytest.approx(4.0, rel=1e-3)
