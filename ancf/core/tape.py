"""A material's energy as a tape: traced once, evaluated per point by compiled code.

Laws and formulations are written with the arithmetic of :class:`ancf.core.jet.Jet`
(+, -, *, /, ** with a constant exponent, ``log``). Tracing runs that same code once on
:class:`Node` objects, which record each operation as an instruction
(opcode, operand, operand, constant). :func:`tape_batch` then replays the tape in
second-order jet arithmetic at every quadrature point inside numba, so a newly
registered law or formulation is compiled without new code. The numpy
:class:`~ancf.core.jet.Jet` stays the reference (contract test).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

# The compiled step loop's kernels (:func:`tape_batch`, the fused assembly and the band
# LDL^T of :mod:`ancf.kinematics.section.kernels`) let LLVM reassociate and contract floating-point
# operations, so that their inner products and point loops vectorise: 25 to 35 % less
# time per call here. No no-NaN / no-inf assumption: the admissibility tests (det F > 0
# and finite) stay exact. The last bits then depend on how LLVM compiled a function (code
# compiled in-process and loaded from numba's cache may differ at round-off).
FASTMATH = {"reassoc", "contract", "nsz", "arcp"}

# opcodes. VAR_STRETCH: the variable of a cable's tape (:func:`trace_uniaxial`), the fibre
# stretch lambda, carried in the first slot like a (the kernels read the tape's first
# instruction to tell a cable's tape from a continuum's: :mod:`ancf.kinematics.kernels`)
VAR_A, VAR_J, CONST, ADD, ADDC, MUL, MULC, POWC, LOG, VAR_STRETCH = range(10)


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

    def log(self):
        return self.tape.push(LOG, self.i)


def trace(material) -> tuple[np.ndarray, np.ndarray]:
    """The material's energy W(a, J) as (ops (n, 3) int64, consts (n,) float64)."""
    tape = Tape()
    a, J = tape.push(VAR_A), tape.push(VAR_J)
    I1, I2 = material.formulation.invariants(a, J)
    W = material.law.psi(I1, I2, material.constants)
    if material.formulation.penalised:
        W = W + 0.5 * material.penalty * (J - 1.0) ** 2
    W = W + 0.0          # the result is the last instruction
    ops = np.array([(op, x, y) for op, x, y, _ in tape.ops], dtype=np.int64)
    consts = np.array([c for *_, c in tape.ops], dtype=float)
    return ops, consts


def trace_uniaxial(material) -> tuple[np.ndarray, np.ndarray]:
    """The law's exact incompressible uniaxial energy W_u(lambda) = W(lambda, lambda^-1/2,
    lambda^-1/2) as a tape in the one variable lambda (VAR_STRETCH, its first instruction;
    replayed by :func:`tape_batch` with lambda in the a slot: R[-1] = (W_u, W_u', 0, W_u'',
    0, 0)): the law at I1 = lambda^2 + 2 / lambda, I2 = 2 lambda + lambda^-2 (free lateral
    faces: the lateral stretches lambda^-1/2 from incompressibility). These are the
    plane-stress formulation's invariants at F = diag(lambda, lambda^-1/2) (a = lambda^2 +
    1/lambda, J = lambda^1/2: I1 = a + J^-2, I2 = a J^-2 + J^2), written in lambda so that
    the replay needs no lambda^1/2 (a generic power, three pow() per point: measured, the
    cable's force kernel 0.82 -> 0.51 us per element); :meth:`ancf.kinematics.cable.model.CableModel.uniaxial_energy`
    takes the formulation's route in numpy jets and is the reference (tests/test_beam.py,
    round-off). The energy of a fibre of a cable's section (:mod:`ancf.kinematics.cable.model`); plane
    stress only."""
    if material.formulation.name != "plane-stress" or material.formulation.penalised:
        raise ValueError(f"material.formulation: {material.formulation.name!r}; a fibre's uniaxial energy "
                         "is the plane-stress one (free lateral faces): allowed: 'plane-stress'")
    tape = Tape()
    lam = tape.push(VAR_STRETCH)
    inv = lam ** -1
    I1 = lam ** 2 + 2.0 * inv
    I2 = 2.0 * lam + inv * inv
    W = material.law.psi(I1, I2, material.constants) + 0.0     # the result is the last instruction
    ops = np.array([(op, x, y) for op, x, y, _ in tape.ops], dtype=np.int64)
    consts = np.array([c for *_, c in tape.ops], dtype=float)
    return ops, consts


@njit(cache=True)
def evaluate(ops, consts, a, J):
    """W and its (a, J) partials, (6, ne, nq), at every point (a, J of shape (ne, nq)):
    the batched replay :func:`tape_batch` over all points at once (one interpreter of the
    tape; the numpy :class:`~ancf.core.jet.Jet` is its reference)."""
    ne, nq = a.shape
    m = ne * nq
    R = np.empty((ops.shape[0], 6, m))
    tape_batch(ops, consts, np.ascontiguousarray(a).reshape(m), np.ascontiguousarray(J).reshape(m), R, m, 2)
    return R[ops.shape[0] - 1].copy().reshape(6, ne, nq)


# -- batched replay: the compiled step loop (:mod:`ancf.solvers.compiled_steps`) ---------------------------
@njit(inline="always")
def _unary(Rk, Rx, p, nc, f, d1, d2):
    """Chain rule of a unary op g(x) at point p: the jet of g(x) from x's jet (Rx) and
    g, g', g'' at x (f, d1, d2); nc components as in :func:`tape_batch`."""
    Rk[0, p] = f
    if nc > 1:
        a1, a2 = Rx[1, p], Rx[2, p]
        Rk[1, p] = d1 * a1
        Rk[2, p] = d1 * a2
        if nc > 3:
            Rk[3, p] = d2 * a1 * a1 + d1 * Rx[3, p]
            Rk[4, p] = d2 * a1 * a2 + d1 * Rx[4, p]
            Rk[5, p] = d2 * a2 * a2 + d1 * Rx[5, p]


@njit(cache=True, fastmath=FASTMATH)
def tape_batch(ops, consts, a, J, R, m, order):
    """Replay the energy tape at m points (a, J) = (F:F, det F) in jet arithmetic.
    R (n_ops, 6, >= m) is the scratch; afterwards R[-1, :, p] = (W, W_a, W_J, W_aa,
    W_aJ, W_JJ) at point p. Instructions outer, points inner: one branch per
    instruction and batch, and loops the compiler vectorises. order 0: W only;
    1: W and its first derivatives (the force); 2: all (the tangent)."""
    n = ops.shape[0]
    nc = 6 if order >= 2 else (3 if order == 1 else 1)
    for k in range(n):
        op, x, y, c = ops[k, 0], ops[k, 1], ops[k, 2], consts[k]
        Rk = R[k]
        if op == VAR_A or op == VAR_J or op == CONST or op == VAR_STRETCH:
            for d in range(nc):
                for p in range(m):
                    Rk[d, p] = 0.0
            if op != CONST:                      # the variable, and its unit partial (a cable's
                v, slot = (J, 2) if op == VAR_J else (a, 1)     # stretch: in a's slot)
                for p in range(m):
                    Rk[0, p] = v[p]
                if nc > 1:
                    for p in range(m):
                        Rk[slot, p] = 1.0
            else:
                for p in range(m):
                    Rk[0, p] = c
        elif op == ADD:
            Rx, Ry = R[x], R[y]
            for d in range(nc):
                for p in range(m):
                    Rk[d, p] = Rx[d, p] + Ry[d, p]
        elif op == ADDC:
            Rx = R[x]
            for d in range(nc):
                for p in range(m):
                    Rk[d, p] = Rx[d, p]
            for p in range(m):
                Rk[0, p] += c
        elif op == MULC:
            Rx = R[x]
            for d in range(nc):
                for p in range(m):
                    Rk[d, p] = Rx[d, p] * c
        elif op == MUL:
            Rx, Ry = R[x], R[y]
            for p in range(m):
                Rk[0, p] = Rx[0, p] * Ry[0, p]
            if nc > 1:
                for p in range(m):
                    x0, y0 = Rx[0, p], Ry[0, p]
                    Rk[1, p] = Rx[1, p] * y0 + x0 * Ry[1, p]
                    Rk[2, p] = Rx[2, p] * y0 + x0 * Ry[2, p]
            if nc > 3:
                for p in range(m):
                    x0, y0, x1, x2, y1, y2 = Rx[0, p], Ry[0, p], Rx[1, p], Rx[2, p], Ry[1, p], Ry[2, p]
                    Rk[3, p] = Rx[3, p] * y0 + 2.0 * x1 * y1 + x0 * Ry[3, p]
                    Rk[4, p] = Rx[4, p] * y0 + x1 * y2 + x2 * y1 + x0 * Ry[4, p]
                    Rk[5, p] = Rx[5, p] * y0 + 2.0 * x2 * y2 + x0 * Ry[5, p]
        elif op == LOG:   # outside the domain (v <= 0): NaN, rejected as inadmissible
            Rx = R[x]
            for p in range(m):
                v = Rx[0, p]
                if v > 0.0:
                    f, d1 = np.log(v), 1.0 / v
                else:
                    f, d1 = np.nan, np.nan
                _unary(Rk, Rx, p, nc, f, d1, -d1 * d1)
        else:  # POWC: v^c, with the common exponents without pow()
            Rx = R[x]
            for p in range(m):
                v = Rx[0, p]
                if c == 2.0:
                    f, d1, d2 = v * v, 2.0 * v, 2.0
                elif c == 3.0:
                    f, d1, d2 = v * v * v, 3.0 * v * v, 6.0 * v
                elif c == -1.0:
                    iv = 1.0 / v
                    f, d1, d2 = iv, -iv * iv, 2.0 * iv * iv * iv
                elif c == -2.0:
                    iv = 1.0 / v
                    f = iv * iv
                    d1, d2 = -2.0 * f * iv, 6.0 * f * iv * iv
                else:   # not f / v: v = 0 (I1 - 3 at rest) is a valid point
                    f = v ** c
                    d1 = c * v ** (c - 1.0)
                    d2 = c * (c - 1.0) * v ** (c - 2.0)
                _unary(Rk, Rx, p, nc, f, d1, d2)

