"""The free end face a couple turns: its first moment, linear in the displacements."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechanics.end_rotation import face_rotation


@dataclass(frozen=True)
class EndFace:
    """d = d0 + A u[rows]: the first moment of the free end face (dimensionless, the face's
    direction and stretch in the plane); each kinematics makes its own
    (:meth:`ancf.kinematics.family.Kinematics.end_face`)."""
    rows: np.ndarray     # (m,) global dofs, int64
    A: np.ndarray        # (2, m)
    d0: np.ndarray       # (2,): d at u = 0 (the reference face: (0, 1))

    def first_moment(self, u: np.ndarray) -> np.ndarray:
        return self.d0 + self.A @ u[self.rows]

    def rotation(self, u: np.ndarray) -> float:
        """theta (rad) in (-pi, pi] at u; :func:`mechanics.end_rotation.continued` continues it."""
        return face_rotation(self.first_moment(u))
