"""A user's element found by the harness (README "At equal accuracy"): HB2n-20xy, HB2n-16
with the mixed slope r_xy added, so that the cross-section field r_y is cubic along the
beam like the centre line (r, r_x, r_y, r_xy, r_yy at two nodes).

Why: HB2n-16's r_y = dr/dy is linear in x within an element; with the shear strain held
near zero in a thin beam, the centre line's x^3 mode goes too, the curvature is constant
per element and a coarse mesh is too stiff in bending (8 elements: pendulum tip 2.0 % of L
off, natural frequencies +0.9 / +3.5 / +8 %). A cubic r_y removes that constraint.

    .venv/bin/python -m studies card HB2n-20xy --import examples.cubic_slope
    .venv/bin/python -m studies.peers.work_precision --import examples.cubic_slope --element HB2n-20xy

It declares no default quadrature: scenes get the rule exact for its basis.
"""
from ancf.elements import ELEMENTS, ElementSpec, register_element

if "HB2n-20xy" not in ELEMENTS:
    register_element(ElementSpec(
        name="HB2n-20xy",
        basis=("1", "x", "x^2", "x^3", "y", "x*y", "x^2*y", "x^3*y", "y^2", "x*y^2"),
        nodes=(0.0, 1.0), kinds=("r", "r_x", "r_y", "r_xy", "r_yy"),
        reference="harness example: HB2n-16 with r_xy (cubic r_y along the beam)"))
