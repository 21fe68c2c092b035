"""The paper's three laws, polynomials in the invariants (constants in Pa)."""
from __future__ import annotations

from . import Law


def _neo_hookean(I1, I2, c, m=None):
    return c["C10"] * (I1 - 3.0)


def _mooney_rivlin(I1, I2, c, m=None):
    return c["C10"] * (I1 - 3.0) + c["C01"] * (I2 - 3.0)


def _yeoh(I1, I2, c, m=None):
    d = I1 - 3.0
    return c["C10"] * d + c["C20"] * d ** 2 + c["C30"] * d ** 3


LAWS = (
    Law("neo-hookean", ("C10",), _neo_hookean, "C10 (I1 - 3)"),
    Law("mooney-rivlin", ("C10", "C01"), _mooney_rivlin, "C10 (I1 - 3) + C01 (I2 - 3)"),
    Law("yeoh", ("C10", "C20", "C30"), _yeoh, "sum_i Ci0 (I1 - 3)^i, i = 1..3"),
)
