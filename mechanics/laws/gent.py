"""Gent's law (Gent 1996): limited chain extensibility in one constant.

    psi = -mu Jm / 2 ln(1 - (I1 - 3) / Jm)

mu is the small-strain shear modulus (Pa), Jm the limit of I1 - 3 (the energy grows
without bound as I1 - 3 -> Jm); Jm -> infinity gives neo-Hookean with C10 = mu / 2.
Outside its domain (I1 - 3 >= Jm) the energy is not a number, which the solvers reject
as an inadmissible state like det F <= 0.
"""
from __future__ import annotations

from . import MATH, Law


def _gent(I1, I2, c, m=MATH):
    return -0.5 * c["mu"] * c["Jm"] * m.log(1.0 - (I1 - 3.0) / c["Jm"])


def _admissible(c):
    if not c["Jm"] > 0:
        return f"material.Jm: Gent's extensibility limit must be positive, got {c['Jm']!r}"
    return None


# Example constants: mu = 2 C10 of the paper's neo-Hookean rubber (the same small-strain
# stiffness) and a low limit Jm = 0.1, so that the stiffening shows in the paper's
# cantilever (natural rubber has Jm of about 100, where Gent equals neo-Hookean there).
LAW = Law("gent", ("mu", "Jm"), _gent, "-mu Jm / 2 ln(1 - (I1 - 3) / Jm)",
          admissible=_admissible, example={"mu": 1.906036e6, "Jm": 0.1})
