"""HB2n-20xyp: the example element HB2n-20xy (examples/cubic_slope.py: HB2n-16 with r_xy, a
cross-section field r_y cubic along the beam; 20 dof) with an element pressure {1, y}, which
carries the penalty (ancf/pressure.py). Issue 20, item 3: a cheap lock-free element for the
peers' work-precision diagram.

    .venv/bin/python -m studies card HB2n-20xyp --import examples.cubic_slope_pressure
    .venv/bin/python -m studies.peers.work_precision --import examples.cubic_slope_pressure --element HB2n-20xyp --out DIR

Why {1, y}: HB2n-20xy locks in penalised plane strain (reports/cards/HB2n-20xy.md: 8-11 %
plateau) because J = 1 is imposed at every quadrature point. Bending makes J - 1 linear
across the section, so the pressure must hold a y term (without it J - 1 is free to vary
across the section and the beam is 56 % too soft); any x term in it (constant curvature
change along an element) already stiffens it. Measured on the paper's cantilever (face
clamp, gravity, default rules), Yeoh, penalty 1e4 C10, error of the tip against the exactly
incompressible plane-strain continuum (tests/gold), at 16 / 32 / 64 / 160 elements:

    pressure                   16       32       64      160
    none (HB2n-20xy)          4.6 %    1.9 %   27 %     26 %     locks
    {1}, {1, x}                56 %     56 %   56 %     57 %     too soft
    {1, y}                    1.69 %   0.69 %  0.43 %   0.21 %   (320: 0.16 %, 640: 0.13 %)
    {1, x, y}                 1.73 %   0.70 %  0.43 %   0.21 %
    {1, x} x {1, y}           4.2 %    1.9 %   0.89 %   0.31 %
    {1, x, x^2} x {1, y}      4.3 %    1.9 %   0.89 %   0.31 %
    {1, x, y, xy, y^2} *       29 %     27 %   27 %     26 %     locks
    {1, x} x {1, y, y^2} *     29 %     28 %   27 %     26 %     locks
    (* y^2 needs 3 points across: rule [4, 3] in the penalised formulations)

Penalty sweep at 64 elements, k = 10 / 1e2 / 1e3 / 1e4 / 1e5 C10 (same reference): {1, y}
Yeoh 8.95 / 0.67 / 0.33 / 0.43 / 0.44 %, NH 12.6 / 0.96 / 0.38 / 0.52 / 0.53 %, MR 6.84 /
0.56 / 0.27 / 0.35 / 0.36 % (no growth: from 1e4 to 1e5 the tip moves 0.008-0.017 %, as the
continuum's own 1/k term says, 0.008-0.013 %; HB2n-20xy's moves 27-34 %); {1, x} x {1, y}
Yeoh 8.76 / 0.29 / 0.78 / 0.89 / 0.90 % (and 9.3 % at 8 elements, {1, y} 3.5 %). Mesh at
1e4 C10, NH 2.23 / 0.92 / 0.52 / 0.25 % (640: 0.16 %), MR 1.17 / 0.49 / 0.35 / 0.18 % (640:
0.12 %). Order about 1, as HB2n-20xy's in plane stress (the face clamp fixes r_yy, whose
field is linear along the element: HB2n-20xy's card, "What the clamp does"), down to the
quadratic section's plateau: 0.12-0.17 % in plane strain, 0.09 % in plane stress.

Plane stress: the pressure carries no penalty there, so the element is HB2n-20xy (bit for
bit; same rules, which resolve {1, y} with their two points across): cantilever 0.89 / 0.38
/ 0.25 / 0.13 % at 16 / 32 / 64 / 160 (Yeoh); slender pendulum (max error over 0.1 ... 0.5 s
/ L, dt 5 / 2.5 / 1.25 / 0.625 / 0.3125 ms): 8 elements 0.27 / 0.033 / 0.034 / 0.053 /
0.052 %, 16 elements 0.30 / 0.044 / 0.029 / 0.033 / 0.035 %.

Work-precision (studies.peers.work_precision, grid 8 ... 64 elements, the committed Exudyn
points reused, 2026-11-25, then the deciding points re-timed side by side, 3 rounds of 5):
slender pendulum 1 % and 0.3 %: HB2n-20xyp x 8, dt 5 ms, 0.0061 s against the cable x 8, dt
5 ms, 0.0065 s: 0.94 (HB2n-16 x 16 before: 1.14); 0.1 %: HB2n-20xyp x 8, dt 2.5 ms, 0.0076 s
against the cable x 16, dt 2.5 ms, 0.0150 s: 0.51. Thick pendulum (h = 20 mm): floor 0.21 %
(the quadratic section); 1 %: HB2n-12 stays cheapest (0.52; HB2n-20xyp x 8: 0.98); 0.3 %:
HB2n-20xyp x 8 at 0.0043 s, the cable never; 0.1 %: neither. With 4 elements in the grid the
cable holds 1 % on the slender pendulum (0.61-0.94 %, 0.0034 s) and HB2n-20xyp does not
(0.89-1.23 %); on the thick one the cable holds 1 % with 2 elements (0.43-0.80 %, 0.0013 s;
HB2n-20xyp x 2: 0.16-0.36 %, 0.0017 s) and HB2n-20xyp x 4 holds 0.3 % at 0.0024 s. At 1 % the
runs are 100 steps of a few elements, where the cost per step, not the element, decides.
"""
import examples.cubic_slope  # noqa: F401  (registers HB2n-20xy, whose basis and rules this element takes)
from ancf.elements import ELEMENTS, ElementSpec, register_element

if "HB2n-20xyp" not in ELEMENTS:
    _base = ELEMENTS["HB2n-20xy"]
    register_element(ElementSpec(
        name="HB2n-20xyp", basis=_base.basis, nodes=_base.nodes, kinds=_base.kinds,
        reference="harness example: HB2n-20xy (cubic r_y along the beam) with element pressure {1, y}",
        quadrature=_base.quadrature, pressure=("1", "y")))
