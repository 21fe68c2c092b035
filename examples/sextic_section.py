"""HB2n-84p: HB2n-60p with a sextic section (README "An element for incompressible rubber",
issue 20), registered from outside the package.

Quintic Hermite along the beam (r, r_x, r_xx at each node), sextic across (r_y ... r_yyyyyy:
21 kinds, 84 dof), element pressure two degrees below the displacement in each direction,
{1, x, x^2, x^3} x {1, y, ..., y^4}. Why: in plane stress every element with a fixed section
converges under refinement to the beam whose section is that polynomial, not to the
continuum; the distance is set by the clamp's corner singularity and falls slowly with the
degree across (Yeoh, 256 elements, quintic along: quartic section 0.0106 %, quintic 0.0079 %,
sextic 0.0047 %; NH 0.0140 / 0.0100 / 0.0060 %, MR 0.0083 / 0.0061 / 0.0036 %). The sextic
section is the first whose plateau is below 0.01 % for all three laws.

Rules from the rank and finite-strain tests (:mod:`ancf.rank`): [6, 7] down to l_e/h = 0.05
(seen / true strain 0.34 to 0.54; [6, 6] fails everywhere, 0.21 at l_e/h = 1), [6, 8] below
(0.49; [6, 7] gives 0.25 at 0.025).

    .venv/bin/python -m studies card HB2n-84p --import examples.sextic_section
"""
from ancf.elements import ELEMENTS, ElementSpec, register_element


def _tensor(nx: int, ny: int) -> tuple[str, ...]:
    return tuple(f"x^{i}*y^{j}" for j in range(ny) for i in range(nx))


if "HB2n-84p" not in ELEMENTS:
    register_element(ElementSpec(
        name="HB2n-84p",
        basis=_tensor(6, 7),
        nodes=(0.0, 1.0),
        kinds=tuple(f"r{'_' if (a or b) else ''}{'x' * a}{'y' * b}" for b in range(7) for a in range(3)),
        reference="harness example: quintic Hermite along, sextic across, pressure {1..x^3} x {1..y^4}",
        quadrature=((False, 0.05, (6, 7)), (False, 0.0, (6, 8)), (True, 0.05, (6, 7)), (True, 0.0, (6, 8))),
        pressure=_tensor(4, 5)))
