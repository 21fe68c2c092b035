"""A user's element found by the harness (README "At equal accuracy"): HB2n-20xy, HB2n-16
with the mixed slope r_xy added, so that the cross-section field r_y is cubic along the
beam like the centre line (r, r_x, r_y, r_xy, r_yy at two nodes).

Why: HB2n-16's r_y = dr/dy is linear in x within an element; with the shear strain held
near zero in a thin beam, the centre line's x^3 mode goes too, the curvature is constant
per element and a coarse mesh is too stiff in bending (8 elements: pendulum tip 2.0 % of L
off, natural frequencies +0.9 / +3.5 / +8 %). A cubic r_y removes that constraint.

    .venv/bin/python -m studies card HB2n-20xy --import examples.cubic_slope
    .venv/bin/python -m studies peers work-precision --import examples.cubic_slope --element HB2n-20xy

Default rules, chosen by the rank tests of ancf.checks.rank (eigenvalue test at u = 0 and the
finite-strain test, as for the package's elements): [4, 2] for l_e / h >= 1 (mu_min 0.37 at
l_e / h = 1, 0.99 at 10; [3, 2] fails at 10 with 0.04), [3, 3] below ([4, 2] fails at
0.5 with 0.05; [3, 3] passes 0.9 ... 0.01 with >= 0.80), and [5, 2] from l_e / h = 15
(HB2n-20xyp's: [4, 2] sees 0.16 of a stretch family at 35, [5, 2] 0.88), in every
formulation. The exact rule would be [4, 3].
"""
from ancf.elements import ELEMENTS, SLENDER, ElementSpec, register_element, rules

if "HB2n-20xy" not in ELEMENTS:
    register_element(ElementSpec(
        name="HB2n-20xy",
        basis=("1", "x", "x^2", "x^3", "y", "x*y", "x^2*y", "x^3*y", "y^2", "x*y^2"),
        nodes=(0.0, 1.0), kinds=("r", "r_x", "r_y", "r_xy", "r_yy"),
        reference="harness example: HB2n-16 with r_xy (cubic r_y along the beam)",
        quadrature=rules((SLENDER, (5, 2)), (1.0, (4, 2)), (0.0, (3, 3)))))
