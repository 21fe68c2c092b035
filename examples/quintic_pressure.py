"""A candidate for the plane-stress target of issue 20 (README "An element for incompressible
rubber"): HB2n-60p, HB2n-40p made quintic along the beam (Hermite: r, r_x, r_xx at each
node; 15 kinds, 60 dof), quartic across, with an element pressure two degrees below the
displacement in each direction, {1, x, x^2, x^3} x {1, y, y^2} (HB2n-40p's rule).

Measured on the paper's cantilever (face clamp, gravity, default rules), against the
converged continuum: plane stress, 32 elements, NH 0.028 % / MR 0.017 % / Yeoh 0.022 %
(HB2n-40p: 0.087 / 0.054 / 0.069 %); exactly incompressible plane strain, penalty 1e4 C10,
NH: 0.21 / 0.027 / 0.014 % at 16 / 32 / 64. With HB2n-40p's pressure {1, x} x {1, y, y^2}
it stalls at 0.136 % (Yeoh, penalised plane strain, 16 and 32 elements); with
{1, x, x^2} x {1, y, y^2} at 0.068 %; {1, ..., x^4} x {1, y, y^2}: 0.42 / 0.11 / 0.016 %.

Not built in: its penalised solves run on the Python Newton loop (no compiled pressure
kernel yet), and the contract suite's Gent penalty sweep alone takes about 3 minutes.

    .venv/bin/python -m studies card HB2n-60p --import examples.quintic_pressure

Default rules from the rank tests of ancf.rank (u = 0 eigenvalue test and finite-strain
test): [6, 5] (exact for the basis) for l_e / h >= 1 (seen/true 0.39 at 1; [5, 5] fails
there with 0.22, [6, 5] at 0.3 with 0.29), [6, 6] down to 0.05 (0.41; 0.21 at 0.025),
[6, 7] below (>= 0.57 down to 0.01).
"""
from ancf.elements import ELEMENTS, ElementSpec, register_element

if "HB2n-60p" not in ELEMENTS:
    register_element(ElementSpec(
        name="HB2n-60p",
        basis=tuple(f"x^{i}*y^{j}" for j in range(5) for i in range(6)),
        nodes=(0.0, 1.0),
        kinds=tuple(f"r{'_' if (a or b) else ''}{'x' * a}{'y' * b}" for b in range(5) for a in range(3)),
        reference="harness example: quintic Hermite along, quartic across, pressure {1..x^3} x {1, y, y^2}",
        quadrature=((False, 1.0, (6, 5)), (False, 0.05, (6, 6)), (False, 0.0, (6, 7)),
                    (True, 1.0, (6, 5)), (True, 0.05, (6, 6)), (True, 0.0, (6, 7))),
        pressure=tuple(f"x^{i}*y^{j}" for j in range(3) for i in range(4))))
