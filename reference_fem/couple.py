"""The end moment of a static scene (``loads.end_moment``, :mod:`contract.loads`) as a term
of a backend's Newton system, written once for both backends (no finite-element code here).

The couple's potential is -t M theta(d), with d the end face's first moment

    d = weight int_face (X + u) Y dA = d0 + G^T w,     weight = 1 / int_face Y^2 dA,

linear in the unknowns w (G = [g_x, g_y], g_i = weight int_face v_i Y dA, assembled by the
backend), theta = atan2(-d_x, d_y) and t the static load parameter. With (g, H) the
gradient and Hessian of theta at d (:func:`mechanics.end_rotation.rotation_derivatives`):

    residual  R += G c,       c = -t M g        (R = dPi/dw)
    tangent   K += G C G^T,   C = -t M H        (rank 2)

M is per unit width in the 2D problems (M / beam.width: the 2D energies are per unit
width) and the full moment in 3D. theta is continued (:func:`mechanics.end_rotation.continued`)
from one evaluation to the next (every Newton iterate): the system saves and restores
``branch`` (theta, d) with its state and resets it with the state, so a rotation past pi is
not folded back and a rejected load increment does not leave its branch behind.
"""
from __future__ import annotations

from typing import Callable

from mechanics.end_rotation import continued, face_rotation, rotation_derivatives


class EndMoment:
    """The couple -t M theta(d(w)) on a backend's first moment ``first_moment(x) -> d``
    (which has ``d0`` and ``vectors``, the columns of G in the backend's vector type) and
    load parameter ``load()`` (a callable returning t)."""

    def __init__(self, first_moment, moment: float, load: Callable[[], float]):
        self.first_moment, self.moment, self.load = first_moment, float(moment), load
        self.vectors = first_moment.vectors
        self.reset()

    def reset(self) -> None:
        """The branch of the reference state: theta(d0) = 0 for the symmetric face."""
        d0 = self.first_moment.d0
        self.branch = (face_rotation(d0), d0)

    def rotation(self, x) -> float:
        """theta (rad) at the state x, continued from the branch (which moves to x)."""
        d = self.first_moment(x)
        self.branch = (continued(*self.branch, d), d)
        return self.branch[0]

    def coefficients(self, x):
        """(c, C) at the state x: the residual's G c and the tangent's G C G^T."""
        self.rotation(x)
        g, H = rotation_derivatives(self.branch[1])
        tM = float(self.load()) * self.moment
        return -tM * g, -tM * H

    def potential(self, x) -> float:
        """-t M theta (J; per unit width in 2D) at the state x."""
        return -float(self.load()) * self.moment * self.rotation(x)


class Branches:
    """The couple's branch kept beside the states a Newton system saves (the last few,
    matched by identity of the saved array at restore)."""

    def __init__(self, couple: EndMoment | None, keep: int = 8):
        self.couple, self.keep, self.saved = couple, keep, []

    def save(self, state) -> None:
        if self.couple is not None:
            self.saved = [(state, self.couple.branch)] + self.saved[:self.keep - 1]

    def restore(self, state) -> None:
        for s, branch in self.saved:
            if s is state:
                self.couple.branch = branch
                return

    def reset(self) -> None:
        if self.couple is not None:
            self.couple.reset()
