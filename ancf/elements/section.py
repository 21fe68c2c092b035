"""The built-in elements of the continuum-based planar section (``kinematics = "continuum"``):
the paper's four and the harness's lock-free ones (their measurements: their cards)."""
from __future__ import annotations

from ..core.spec import SLENDER, ElementSpec, rules
from . import register_element

register_element(ElementSpec(
    "HB2n-12", ("1", "x", "y", "x*y", "x^2 + y^2", "x^3"), (0.0, 1.0), ("r", "r_x", "r_y"),
    "Zhao et al. 2021", rules((0.3, (3, 2)), (0.0, (3, 3)), penalised=((0.1, (3, 2)), (0.0, (3, 3)))), tags=("paper",)))
register_element(ElementSpec(
    "HB3n-12", ("1", "x", "y", "x*y", "x^2 + y^2", "x^2*y"), (0.0, 0.5, 1.0), ("r", "r_y"),
    "Zhao et al. 2021", rules((0.1, (3, 2)), (0.0, (3, 3))), tags=("paper",)))
register_element(ElementSpec(
    "HB2n-16", ("1", "x", "y", "x*y", "x^2", "y^2", "x*y^2", "x^3"), (0.0, 1.0),
    ("r", "r_x", "r_y", "r_yy"), "Patel & Shabana 2018",
    rules((0.3, (3, 2)), (0.0, (3, 3))), tags=("paper",)))
register_element(ElementSpec(
    "LB2n-12", ("1", "x", "y", "x*y", "x^2", "x^3"), (0.0, 1.0), ("r", "r_x", "r_y"),
    "Omar & Shabana 2001 (linear across the thickness)",
    rules((0.0, (3, 2))), tags=("paper", "locking")))
# Found with the harness: the cheap lock-free element, HB2n-16 with the mixed slope
# r_xy (so the cross-section field r_y is cubic along the beam like the centre line; HB2n-16's
# linear r_y makes a coarse mesh too stiff in bending: 8 elements, pendulum tip 2.0 % of L
# off) and an element pressure {1, y} that carries the penalty. Without the pressure (the
# example HB2n-20xy, examples/cubic_slope.py) it locks in penalised plane strain, 27 % at 64
# elements; bending makes J - 1 linear across the section, so the pressure needs y ({1} or
# {1, x}: 56 % too soft), and every richer space stiffens it ({1, x} x {1, y}: 1.9 % at 32;
# any y^2: 26-29 %, locked). Measured (paper's cantilever, face clamp, gravity, default rule,
# Yeoh, penalty 1e4 C10 against the exactly incompressible continuum): 1.69 / 0.69 / 0.43 /
# 0.21 % at 16 / 32 / 64 / 160 elements; from k = 1e4 to 1e5 its tip moves 0.008-0.017 %,
# the continuum's own 1/k term. Order about 1 (the face clamp fixes r_yy, linear along an
# element) to its quadratic section's plateau (plane stress 0.09 %, plane strain 0.13-0.17 %),
# so it meets no static target of the issue; on the slender pendulum it is the cheapest at
# 0.1 % (8 elements, dt 2.5 ms: 0.033 %; README "At equal accuracy"). In plane stress the
# pressure carries nothing and it is HB2n-20xy to the bit. The rules, from the rank tests:
# [4, 2] for l_e / h >= 1 (mu_min 0.37 at 1; [3, 2] fails at 10), [3, 3] below ([4, 2] fails
# at 0.5); both resolve the pressure's {1, y} (the exact rule is [4, 3]); [5, 2] from l_e / h
# = 15 (HB2n-40p's slender family: [4, 2] 0.36 at 15, 0.16 at 35; [5, 2] 0.87-0.89 from 15
# to 140; the slender pendulum hardly feels the rule, tests/test_example_along_rule.py).
register_element(ElementSpec(
    "HB2n-20xyp", ("1", "x", "x^2", "x^3", "y", "x*y", "x^2*y", "x^3*y", "y^2", "x*y^2"), (0.0, 1.0),
    ("r", "r_x", "r_y", "r_xy", "r_yy"),
    "this harness: HB2n-16 with r_xy (cubic r_y along the beam), element pressure {1, y}",
    rules((SLENDER, (5, 2)), (1.0, (4, 2)), (0.0, (3, 3))),
    pressure=("1", "y")))
# Found with the harness: HB2n-20xyp with an assumed membrane stretch, C_xx taken
# from 3 Gauss points along the beam at each row across and carried to the rule's points by
# quadratic Lagrange (ancf.kinematics.section.assumed). A cubic centre line in large rotation cannot keep its
# stretch at 1 at 4 points of an element and bends too stiffly (membrane locking); in small
# strain eps_xx is quadratic along x, so the 3 points see it exactly and the stiffness at
# u = 0 (the rank tests) is HB2n-20xyp's. Measured in the numpy prototype
# (tests/oracles/assumed_membrane.py) under [4, 2], slender pendulum, dt 2.5 ms: 2 / 4 elements 5.23
# / 0.447 % of L (HB2n-20xyp 7.25 / 1.18 %); with C_xy assumed as well 2.57 / 0.442 %, which changes
# the stiffness at u = 0 (not taken). The rules are HB2n-20xyp's ([4, 2] 0.31 at 15, 0.14
# at 35; [5, 2] 0.32-0.43 from 15 to 140: its 3 samples of C_xx bound what more points see).
register_element(ElementSpec(
    "HB2n-20xypm", ("1", "x", "x^2", "x^3", "y", "x*y", "x^2*y", "x^3*y", "y^2", "x*y^2"), (0.0, 1.0),
    ("r", "r_x", "r_y", "r_xy", "r_yy"),
    "this harness: HB2n-20xyp with an assumed membrane stretch C_xx (3 points along)",
    rules((SLENDER, (5, 2)), (1.0, (4, 2)), (0.0, (3, 3))),
    pressure=("1", "y"), assumed=("xx",)))
# Found with the harness (README "An element for incompressible rubber"): HB2n-16
# made cubic along the beam in every cross-section mode and quartic across it (kinds r, r_y,
# ..., r_yyyy and their x-slopes: 10 kinds, 40 dof), with an element pressure linear in x and
# quadratic in y that carries the penalty (ancf.kinematics.section.pressure). Pressure spaces measured (paper's
# cantilever, Yeoh, plane strain at the paper's penalty against the penalised continuum, 32 /
# 64 / 160 / 320 / 640 elements): {1, x} x {1, y, y^2}: 0.018 / 0.034 / 0.0095 / 0.0024 /
# 0.0014 %; x {1, ..., y^3}: 0.010 / 0.015 / 0.022 / 0.038 / 0.042 % (locks as l_e / h
# falls); {1, x, y, xy}: 0.021 / 0.038 / 0.014 / 0.0069 / 0.0059 %; with x^2 in the pressure
# it locks (0.69 % at 32, penalty 1e4 C10); {1} or {1, x}: 57 % too soft (J - 1 free to vary
# across the section). The rules: [4, 5] is the exact rule of the basis and the cheapest
# without spurious modes; the finite-strain test wants [5, 5] below l_e / h = 1 (seen/true
# 0.18 at 0.3 with [4, 5], 0.47 with [5, 5] down to 0.1) and [5, 6] below 0.1 (0.40 at 0.05;
# every rule tried falls under 0.3 at l_e / h <= 0.025). Slender elements, l_e / h >= 15:
# [5, 5]. There the test finds a stretch of both directions that varies along the element
# like a quartic through the 4 points along, seen/true about 5 / (l_e / h) under [4, 5]
# (0.33 at 15, 0.28 at 17.5, 0.15 at 35); [5, 5] sees it (0.55-0.57 from 15 to 70). The same
# family and the same 15 for every element with a rule exact along (HB2n-20xyp, HB2n-60p).
register_element(ElementSpec(
    "HB2n-40p", tuple(f"x^{i}*y^{j}" for j in range(5) for i in range(4)), (0.0, 1.0),
    ("r", "r_x", "r_y", "r_xy", "r_yy", "r_xyy", "r_yyy", "r_xyyy", "r_yyyy", "r_xyyyy"),
    "this harness: cubic Hermite along, quartic across, element pressure {1, x} x {1, y, y^2}",
    rules((SLENDER, (5, 5)), (1.0, (4, 5)), (0.1, (5, 5)), (0.0, (5, 6))),
    pressure=("1", "x", "y", "x*y", "y^2", "x*y^2")))
# Found with the harness: HB2n-40p made quintic along the beam (Hermite: r, r_x,
# r_xx in every cross-section mode r, r_y, ..., r_yyyy: 15 kinds, 60 dof), quartic across,
# with an element pressure two degrees below the displacement in each direction, {1, x, x^2,
# x^3} x {1, y, y^2}. Measured on the paper's cantilever (face clamp, gravity, default rules)
# against the converged continuum: plane stress at 32 elements NH 0.028 / MR 0.017 / Yeoh
# 0.022 % (HB2n-40p: 0.087 / 0.054 / 0.069 %); exactly incompressible plane strain, penalty
# 1e4 C10, NH 0.21 / 0.027 / 0.014 % at 16 / 32 / 64. Pressure spaces: with HB2n-40p's
# {1, x} x {1, y, y^2} it stalls at 0.136 % (Yeoh, penalised plane strain, 16 and 32
# elements), with {1, x, x^2} x {1, y, y^2} at 0.068 %; {1, ..., x^4} x {1, y, y^2}: 0.42 /
# 0.11 / 0.016 %. The rules, from the rank tests: [6, 5] (exact for the basis) for
# l_e / h >= 1 (seen/true 0.39 at 1; [5, 5] fails there with 0.22, [6, 5] at 0.3 with 0.29),
# [6, 6] down to 0.05 (0.41; 0.21 at 0.025), [6, 7] below (>= 0.57 down to 0.01); [8, 5] from
# l_e / h = 15 (HB2n-40p's slender family: [6, 5] 0.33 at 15, 0.15 at 35; [7, 5] 0.21 at
# 35; [8, 5] 0.66 from 15 to 70).
register_element(ElementSpec(
    "HB2n-60p", tuple(f"x^{i}*y^{j}" for j in range(5) for i in range(6)), (0.0, 1.0),
    tuple(f"r{'_' if (a or b) else ''}{'x' * a}{'y' * b}" for b in range(5) for a in range(3)),
    "this harness: quintic Hermite along, quartic across, element pressure {1, .., x^3} x {1, y, y^2}",
    rules((SLENDER, (8, 5)), (1.0, (6, 5)), (0.05, (6, 6)), (0.0, (6, 7))),
    pressure=tuple(f"x^{i}*y^{j}" for j in range(3) for i in range(4)), tags=("costly",)))
