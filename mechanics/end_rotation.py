"""The end face's rotation theta = atan2(-d_x, d_y) of its first moment d (what the end
moment is: :mod:`contract.loads`): its value, its continuation along a load path, and its
first and second derivatives in d, which every solver's couple needs."""
from __future__ import annotations

import math

import numpy as np


def face_rotation(d) -> float:
    """theta (rad) of a face whose first moment is d, in (-pi, pi]: atan2(-d_x, d_y)."""
    return math.atan2(-float(d[0]), float(d[1]))


def continued(theta_before: float, d_before, d) -> float:
    """theta at d, continued from (theta_before, d_before) by the turn from d_before to d
    (less than pi in magnitude): a rotation past pi is not folded back."""
    cross = float(d_before[0]) * float(d[1]) - float(d_before[1]) * float(d[0])
    dot = float(d_before[0]) * float(d[0]) + float(d_before[1]) * float(d[1])
    return theta_before + math.atan2(cross, dot)


def rotation_derivatives(d) -> tuple[np.ndarray, np.ndarray]:
    """(g, H): the gradient dtheta/dd (2,) and Hessian d2theta/dd2 (2, 2) of
    theta = atan2(-d_x, d_y), at d != 0: g = (-d_y, d_x) / |d|^2,
    H = [[2 d_x d_y, d_y^2 - d_x^2], [d_y^2 - d_x^2, -2 d_x d_y]] / |d|^4."""
    dx, dy = float(d[0]), float(d[1])
    r2 = dx * dx + dy * dy
    g = np.array([-dy, dx]) / r2
    H = np.array([[2 * dx * dy, dy * dy - dx * dx], [dy * dy - dx * dx, -2 * dx * dy]]) / (r2 * r2)
    return g, H
