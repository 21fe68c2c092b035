"""HB2n-84p: HB2n-60p with a sextic section (README "An element for incompressible rubber",
issue 20), registered from outside the package.

Quintic Hermite along the beam (r, r_x, r_xx at each node), sextic across (r_y ... r_yyyyyy:
21 kinds, 84 dof), element pressure {1, x, x^2, x^3} x {1, y, y^2} plus y^3 (13 functions).
Why the section: in plane stress every element with a fixed section converges under
refinement to the beam whose section is that polynomial, not to the continuum; the distance
is set by the clamp's corner singularity and falls slowly with the degree across (Yeoh, 256
elements, quintic along: quartic section 0.0106 %, quintic 0.0079 %, sextic 0.0047 %; NH
0.0140 / 0.0100 / 0.0060 %, MR 0.0083 / 0.0061 / 0.0036 %). The sextic section is the first
whose plateau is below 0.01 % for all three laws. The pressure does not enter plane stress
(32 elements, Yeoh: 0.01824 % with every pressure below).

Why the pressure (measured; paper's cantilever, face clamp, gravity, default rule; Yeoh,
plane strain; "k = 1e4": penalty 1e4 C10 against the exactly incompressible continuum at
16 / 32 / 64 / 256 elements; "sweep": 64 elements, k = 1e3 / 1e4 / 1e5 C10, same reference;
"limit": the paper's penalty against the penalised continuum at 256 / 640 / 1280, signed,
+ softer). Under refinement the element tends to the beam whose section is constrained in
the pressure's span in y, whatever its span in x: {1, y, y^2} leaves that beam 0.03 % too
soft, and any odd term beyond y makes it too stiff (the full x-tensors hold their limit from
256 elements on); pressure terms with less than {1, .., x^3} along x reach the same limit,
only more slowly (they drift to it as l_e / h falls):

    pressure in y (x {1..x^3})  k = 1e4 (%)                 sweep (%)              limit (%)
    {1..y^4} (20; was here)     0.21 / 0.059 / 0.012 / 0.0018  0.088 / 0.012 / 0.021 ^  -0.011 / -0.011 / -0.011
    {1..y^3} (16)               0.21 / 0.059 / 0.012 / 0.0018  0.088 / 0.012 / 0.021 ^  -0.011 (256)
    {1..y^3} less x^3 y^3 (15)  0.18 / 0.028 / 0.0089 / 0.0021 0.11 / 0.0089 / 0.0010   -0.0093 (256)
    {1, y, y^2} (12)            0.17 / 0.014 / 0.034 / 0.043   0.13 / 0.034 / 0.024     +0.031 / +0.032
    {1, y} (8)                                                                          +0.035 (256)
    {1, y, y^3} (12)            0.20 / 0.054 / 0.0075 / 0.0049 0.093 / 0.0075 / 0.017 ^ -0.0061 / -0.0061 (NH -0.010)
    {1, y, y^5} (12)                                                                    -0.011 / -0.011
    {1, y, y^2, y^3, y^5} (20)                                                          -0.020 (256)
    {1, y, y^2} + {1, x} y^3    - / 0.026 / 0.0100 / -         - / 0.0100 / 0.0001      -0.0043 / -0.0097 (128: +0.0025)
    {1, y, y^2} + y^3 + y^5                                                             +0.0016 / -0.0069
    {1, y, y^2} + y^3 (13; now) 0.17 / 0.021 / 0.015 / 0.014   0.11 / 0.015 / 0.0055    +0.0030 / -0.0035 / -0.0083
    HB2n-60p, quartic section   0.17 / 0.025 / 0.0087 / 0.012  0.11 / 0.0087 / 0.0016   +0.0005 / +0.0005 / +0.0004

(^: grows from k = 1e4 to 1e5. At k = 1e4 the penalty itself leaves the continuum about
0.010 % softer than the incompressible one, Yeoh; NH 0.014 %, MR 0.008 % (the committed
continuum pair at the paper's penalty, scaled 1/k): the finer meshes' errors in that column
are mostly that. With that softness taken off, every space's own error at 64 elements is
the same from k = 1e3 to 1e5 within 0.0013 % (Yeoh: {1..y^4} -0.021 / -0.022 / -0.022 %,
this example's +0.0044 / +0.0042 / +0.0042 %, HB2n-60p -0.0022 / -0.0025 / -0.0025 %): none
locks in k; the growth marked ^ is a stiff element error that the penalty's softness hides
at 1e4 and no longer at 1e5. What tells the spaces apart is the sign and size of the limit.)

The example's pressure, all laws: 32 elements at k = 1e4 NH 0.024 / MR 0.016 / Yeoh
0.021 %; the sweep falls (NH 0.15 / 0.020 / 0.0069 %, MR 0.092 / 0.012 / 0.0040 %); limit
at 640 NH -0.0044 / MR -0.0027 / Yeoh -0.0035 %, and at k = 1e5 against the incompressible
continuum 0.0031 / 0.0020 / 0.0026 %. It is the only space measured that meets issue 20's
plane-strain targets on the card's grid (to 640 elements), but it has no plateau: past
l_e / h = 0.1 it drifts towards the {1, .., y^3} limit (1280 elements: Yeoh -0.0083 %, NH
-0.0102 %; bounded by that limit, Yeoh -0.011 %). No pressure space measured gives the
sextic section a plane-strain limit below 0.01 % in every law that holds under refinement;
HB2n-60p stays the plane-strain element, this one the plane-stress one.

Rules from the rank and finite-strain tests (:mod:`ancf.checks.rank`; the pressure does not enter
them): [6, 7] down to l_e/h = 0.05 (seen / true strain 0.34 to 0.54; [6, 6] fails
everywhere, 0.21 at l_e/h = 1), [6, 8] below (0.49; [6, 7] gives 0.25 at 0.025), and [8, 7]
from l_e/h = 15 (HB2n-40p's slender stretch family: [6, 7] 0.35 at 15, 0.15 at 35; [8, 7]
0.53-0.54 from 15 to 70).

    .venv/bin/python -m studies card HB2n-84p --import examples.sextic_section
"""
from ancf.elements import ELEMENTS, SLENDER, ElementSpec, register_element, rules


def _tensor(nx: int, ny: int) -> tuple[str, ...]:
    return tuple(f"x^{i}*y^{j}" for j in range(ny) for i in range(nx))


if "HB2n-84p" not in ELEMENTS:
    register_element(ElementSpec(
        name="HB2n-84p",
        basis=_tensor(6, 7),
        nodes=(0.0, 1.0),
        kinds=tuple(f"r{'_' if (a or b) else ''}{'x' * a}{'y' * b}" for b in range(7) for a in range(3)),
        reference="harness example: quintic Hermite along, sextic across, pressure {1..x^3} x {1, y, y^2} + y^3",
        quadrature=rules((SLENDER, (8, 7)), (0.05, (6, 7)), (0.0, (6, 8))),
        pressure=_tensor(4, 3) + ("x^0*y^3",)))
