"""Second-order forward derivatives in the two 2D invariants (a, J).

Every isotropic 2D energy here is a function of a = tr C = F:F and J = det F. A
:class:`Jet` carries a value and its first and second partial derivatives in (a, J),
elementwise over numpy arrays, so a material law is written once as an energy
expression and its stress and tangent follow exactly (forward-mode differentiation,
no finite differences).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Jet:
    """f and its partials: f_a, f_J, f_aa, f_aJ, f_JJ (arrays of one shape or scalars)."""

    v: np.ndarray
    a: np.ndarray
    J: np.ndarray
    aa: np.ndarray
    aJ: np.ndarray
    JJ: np.ndarray

    @staticmethod
    def variables(a, J) -> tuple["Jet", "Jet"]:
        z = np.zeros_like(a)
        one = np.ones_like(a)
        return Jet(a, one, z, z, z, z), Jet(J, z, one, z, z, z)

    @staticmethod
    def const(c, like: "Jet") -> "Jet":
        z = np.zeros_like(like.v)
        return Jet(z + c, z, z, z, z, z)

    def _lift(self, other) -> "Jet":
        return other if isinstance(other, Jet) else Jet.const(other, self)

    def __add__(self, o):
        o = self._lift(o)
        return Jet(self.v + o.v, self.a + o.a, self.J + o.J,
                   self.aa + o.aa, self.aJ + o.aJ, self.JJ + o.JJ)

    __radd__ = __add__

    def __neg__(self):
        return Jet(-self.v, -self.a, -self.J, -self.aa, -self.aJ, -self.JJ)

    def __sub__(self, o):
        return self + (-self._lift(o))

    def __rsub__(self, o):
        return self._lift(o) - self

    def __mul__(self, o):
        if not isinstance(o, Jet):
            return Jet(self.v * o, self.a * o, self.J * o, self.aa * o, self.aJ * o, self.JJ * o)
        return Jet(
            self.v * o.v,
            self.a * o.v + self.v * o.a,
            self.J * o.v + self.v * o.J,
            self.aa * o.v + 2 * self.a * o.a + self.v * o.aa,
            self.aJ * o.v + self.a * o.J + self.J * o.a + self.v * o.aJ,
            self.JJ * o.v + 2 * self.J * o.J + self.v * o.JJ,
        )

    __rmul__ = __mul__

    def __truediv__(self, o):
        if not isinstance(o, Jet):
            return self * (1.0 / o)
        return self * o ** -1

    def __rtruediv__(self, o):
        return self ** -1 * o

    def __pow__(self, p: float):
        if p == 1:
            return self
        if isinstance(p, int) and p >= 0:
            f = self.v ** p
            d1 = p * self.v ** (p - 1)
            d2 = p * (p - 1) * self.v ** (p - 2) if p >= 2 else np.zeros_like(self.v)
            return self.compose(f, d1, d2)
        return self.compose(self.v ** p, p * self.v ** (p - 1), p * (p - 1) * self.v ** (p - 2))

    def compose(self, f, df, d2f) -> "Jet":
        """g = phi(self), given phi, phi' and phi'' evaluated at self.v."""
        return Jet(
            f,
            df * self.a,
            df * self.J,
            d2f * self.a * self.a + df * self.aa,
            d2f * self.a * self.J + df * self.aJ,
            d2f * self.J * self.J + df * self.JJ,
        )
