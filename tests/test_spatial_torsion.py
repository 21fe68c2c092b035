"""Small-twist torsion of the spatial elements (:mod:`ancf.kinematics.spatial`) against
Saint-Venant's (:mod:`studies.verification.torsion`), each side by a route of its own.

- The closed forms: the torsion constant's series against Timoshenko and Goodier's table, and
  the polynomial-warping bound (a least-squares Ritz minimum) against its closed form at
  degree two and three, never below the exact constant and falling to it.
- The elements: a bar on the free-warping support, loaded at its end by the traction of its
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
    f = end_face_load(b, lambda y, z: MU * rate * np.column_stack([0.0 * y, *shear(y, z)]))
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
