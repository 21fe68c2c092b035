"""Second-order forward derivatives in the two 2D invariants (a, J).

Every isotropic 2D energy here is a function of a = tr C = F:F and J = det F. A
:class:`Jet` carries a value and its first and second partial derivatives in (a, J),
elementwise over numpy arrays, so a material law is written once as an energy
expression and its stress and tangent follow exactly (forward-mode differentiation,
no finite differences).

The six components are stacked in one array D (6, ...) = (f, f_a, f_J, f_aa, f_aJ, f_JJ),
so each operation is a few whole-array numpy calls (this sits in the time-stepping hot
loop).
"""
from __future__ import annotations

import numpy as np


class Jet:
    __slots__ = ("D",)

    def __init__(self, D: np.ndarray):
        self.D = D

    # the components, by name
    v = property(lambda self: self.D[0])
    a = property(lambda self: self.D[1])
    J = property(lambda self: self.D[2])
    aa = property(lambda self: self.D[3])
    aJ = property(lambda self: self.D[4])
    JJ = property(lambda self: self.D[5])

    @staticmethod
    def variables(a, J) -> tuple["Jet", "Jet"]:
        a, J = np.broadcast_arrays(np.asarray(a, float), np.asarray(J, float))
        Da = np.zeros((6,) + a.shape)
        DJ = np.zeros((6,) + a.shape)
        Da[0], Da[1] = a, 1.0
        DJ[0], DJ[2] = J, 1.0
        return Jet(Da), Jet(DJ)

    def __add__(self, o):
        if isinstance(o, Jet):
            return Jet(self.D + o.D)
        D = self.D.copy()
        D[0] += o
        return Jet(D)

    __radd__ = __add__

    def __neg__(self):
        return Jet(-self.D)

    def __sub__(self, o):
        return self + (-o)

    def __rsub__(self, o):
        return (-self) + o

    def __mul__(self, o):
        if not isinstance(o, Jet):
            return Jet(self.D * o)
        x, y = self.D, o.D
        D = x * y[0] + x[0] * y          # value counted twice, second derivatives lack cross terms
        D[0] -= x[0] * y[0]
        D[3] += 2.0 * x[1] * y[1]
        D[4] += x[1] * y[2] + x[2] * y[1]
        D[5] += 2.0 * x[2] * y[2]
        return Jet(D)

    __rmul__ = __mul__

    def __truediv__(self, o):
        if not isinstance(o, Jet):
            return Jet(self.D / o)
        return self * o ** -1

    def __rtruediv__(self, o):
        return self ** -1 * o

    def __pow__(self, p: float):
        if p == 1:
            return self
        x = self.D[0]
        if p == 2:
            return self.compose(x * x, 2.0 * x, 2.0 + 0.0 * x)
        xp2 = x ** (p - 2)
        return self.compose(xp2 * x * x, p * xp2 * x, p * (p - 1) * xp2)

    def log(self) -> "Jet":
        """log and its derivatives; not a number (value and derivatives) where x <= 0,
        so that a state outside a law's domain is rejected as inadmissible."""
        x = np.where(self.D[0] > 0.0, self.D[0], np.nan)
        with np.errstate(invalid="ignore"):
            return self.compose(np.log(x), 1.0 / x, -1.0 / (x * x))

    def compose(self, f, df, d2f) -> "Jet":
        """g = phi(self), given phi, phi' and phi'' evaluated at self.v."""
        x = self.D
        D = df * x
        D[0] = f
        D[3] += d2f * x[1] * x[1]
        D[4] += d2f * x[1] * x[2]
        D[5] += d2f * x[2] * x[2]
        return Jet(D)
