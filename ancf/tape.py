"""A material's energy as a tape: traced once, evaluated per point by compiled code.

Laws and formulations are written with the arithmetic of :class:`ancf.jet.Jet`
(+, -, *, /, ** with a constant exponent). Tracing runs that same code once on
:class:`Node` objects, which record each operation as an instruction
(opcode, operand, operand, constant). :func:`evaluate` then replays the tape in
second-order jet arithmetic at every quadrature point inside numba, so a newly
registered law or formulation is compiled without new code. The numpy
:class:`~ancf.jet.Jet` stays the reference (contract test).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

# opcodes
VAR_A, VAR_J, CONST, ADD, ADDC, MUL, MULC, POWC = range(8)


class Tape:
    def __init__(self):
        self.ops: list[tuple[int, int, int, float]] = []

    def push(self, op, a=-1, b=-1, c=0.0) -> "Node":
        self.ops.append((op, a, b, float(c)))
        return Node(self, len(self.ops) - 1)


@dataclass(frozen=True)
class Node:
    tape: Tape
    i: int

    def __add__(self, o):
        if isinstance(o, Node):
            return self.tape.push(ADD, self.i, o.i)
        return self.tape.push(ADDC, self.i, c=o)

    __radd__ = __add__

    def __neg__(self):
        return self.tape.push(MULC, self.i, c=-1.0)

    def __sub__(self, o):
        return self + (-o)

    def __rsub__(self, o):
        return (-self) + o

    def __mul__(self, o):
        if isinstance(o, Node):
            return self.tape.push(MUL, self.i, o.i)
        return self.tape.push(MULC, self.i, c=o)

    __rmul__ = __mul__

    def __truediv__(self, o):
        if isinstance(o, Node):
            return self * o ** -1
        return self.tape.push(MULC, self.i, c=1.0 / o)

    def __rtruediv__(self, o):
        return self ** -1 * o

    def __pow__(self, p):
        if isinstance(p, Node):
            raise TypeError("only constant exponents can be traced")
        if p == 1:
            return self
        return self.tape.push(POWC, self.i, c=p)


def trace(material) -> tuple[np.ndarray, np.ndarray]:
    """The material's energy W(a, J) as (ops (n, 3) int64, consts (n,) float64)."""
    tape = Tape()
    a, J = tape.push(VAR_A), tape.push(VAR_J)
    I1, I2 = material.formulation.invariants(a, J)
    W = material.law.energy(I1, I2, material.constants)
    if material.formulation.penalised:
        W = W + 0.5 * material.penalty * (J - 1.0) ** 2
    W = W + 0.0          # the result is the last instruction
    ops = np.array([(op, x, y) for op, x, y, _ in tape.ops], dtype=np.int64)
    consts = np.array([c for *_, c in tape.ops], dtype=float)
    return ops, consts


@njit(cache=True)
def evaluate(ops, consts, a, J):
    """W and its (a, J) partials, (6, ne, nq), at every point; the tape's jet replay."""
    ne, nq = a.shape
    n = ops.shape[0]
    out = np.empty((6, ne, nq))
    R = np.zeros((n, 6))
    for e in range(ne):
        for q in range(nq):
            for k in range(n):
                op, x, y, c = ops[k, 0], ops[k, 1], ops[k, 2], consts[k]
                if op == VAR_A:
                    R[k, 0], R[k, 1], R[k, 2], R[k, 3], R[k, 4], R[k, 5] = a[e, q], 1.0, 0.0, 0.0, 0.0, 0.0
                elif op == VAR_J:
                    R[k, 0], R[k, 1], R[k, 2], R[k, 3], R[k, 4], R[k, 5] = J[e, q], 0.0, 1.0, 0.0, 0.0, 0.0
                elif op == CONST:
                    R[k, 0] = c
                    for m in range(1, 6):
                        R[k, m] = 0.0
                elif op == ADD:
                    for m in range(6):
                        R[k, m] = R[x, m] + R[y, m]
                elif op == ADDC:
                    for m in range(6):
                        R[k, m] = R[x, m]
                    R[k, 0] += c
                elif op == MULC:
                    for m in range(6):
                        R[k, m] = R[x, m] * c
                elif op == MUL:
                    x0, y0 = R[x, 0], R[y, 0]
                    R[k, 0] = x0 * y0
                    R[k, 1] = R[x, 1] * y0 + x0 * R[y, 1]
                    R[k, 2] = R[x, 2] * y0 + x0 * R[y, 2]
                    R[k, 3] = R[x, 3] * y0 + 2.0 * R[x, 1] * R[y, 1] + x0 * R[y, 3]
                    R[k, 4] = R[x, 4] * y0 + R[x, 1] * R[y, 2] + R[x, 2] * R[y, 1] + x0 * R[y, 4]
                    R[k, 5] = R[x, 5] * y0 + 2.0 * R[x, 2] * R[y, 2] + x0 * R[y, 5]
                else:  # POWC
                    v = R[x, 0]
                    if c == 2.0:
                        f, d1, d2 = v * v, 2.0 * v, 2.0
                    elif c == 3.0:
                        f, d1, d2 = v * v * v, 3.0 * v * v, 6.0 * v
                    else:
                        f = v ** c
                        d1 = c * f / v
                        d2 = c * (c - 1.0) * f / (v * v)
                    a1, a2 = R[x, 1], R[x, 2]
                    R[k, 0] = f
                    R[k, 1] = d1 * a1
                    R[k, 2] = d1 * a2
                    R[k, 3] = d2 * a1 * a1 + d1 * R[x, 3]
                    R[k, 4] = d2 * a1 * a2 + d1 * R[x, 4]
                    R[k, 5] = d2 * a2 * a2 + d1 * R[x, 5]
            for m in range(6):
                out[m, e, q] = R[n - 1, m]
    return out
