"""The built-in cable (``kinematics = "cable"``): HC2n-8."""
from __future__ import annotations

from ..core.spec import ElementSpec, rules
from . import register_element

# Found with the harness, looking for the cheapest element at every accuracy: the planar ANCF
# cable (r and r_x at two nodes, cubic Hermite along: Gerstmayr & Irschik 2008's centre
# line, Exudyn's ObjectANCFCable2D's dofs) whose section integrates the law's exact
# incompressible uniaxial energy fibre by fibre (ancf.kinematics.cable.model), instead of a linear
# EA eps^2 / 2 + EI kappa^2 / 2. H: its section law is the hyperelastic one (beside the
# linear cable of the peers' runs); C: a cable (centre line only, Euler-Bernoulli, no
# section coordinates, so the B of the continuum-based elements' names does not fit);
# 2n, 8: two nodes, 8 dof. Its rule: points along x points across the section. Along: the
# small strain u_x' (quadratic) needs 3 points ([2, .]: one spurious mode; [3, 1] two, the
# bending unseen at y = 0); [3, 2] and up are exact at u = 0 (mu_min 1). Across: the section's
# energy int W_u(s - y kappa) dy by Gauss, against 64 points at kappa h = 0.1 / 0.3 / 0.5
# (neo-Hookean; Yeoh and Mooney-Rivlin alike): 2 points 8.9e-4 / 7.9e-3 / 2.1e-2 of M, as large
# as the section model's own error 0.225 (kappa h)^2 (tests/test_cable.py); 3 points 8.6e-7 /
# 6.8e-5 / 5.0e-4, under 1 % of it to kappa h = 0.3, 2 % at 0.5: [3, 3]. The finite-strain
# test finds, with 3 or 4 points along, the membrane stretch between the points unseen at slender elements
# (seen/true 0.33 / 0.19 / 0.09 at l_e / h = 10 / 17.5 / 35; [5, 3] 0.93); seeing it is the
# cubic cable's membrane locking: on the paper's cantilever (NH, plane stress) [3, 3] is off the
# continuum by 4.7 / 0.39 / 0.044 / 0.033 % at 2 / 4 / 8 / 32 elements, [5, 3] by 6.1 / 0.79 /
# 0.055 / 0.033 %; on the pendulum (Yeoh) 2.4 / 0.46 / 0.081 % at 2 / 4 / 8 elements against 6.7 /
# 0.90 / 0.091 %, no unstable equilibrium either way: [3, 3] at every l_e / h.
register_element(ElementSpec(
    "HC2n-8", ("1", "x", "x^2", "x^3"), (0.0, 1.0), ("r", "r_x"),
    "this harness: ANCF cable (cubic Hermite centre line), section integrated with the law's incompressible "
    "uniaxial energy", rules((0.0, (3, 3))), kinematics="cable"))
