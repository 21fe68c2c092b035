"""Kinematics as a registered family (:class:`Kinematics`, :data:`KINEMATICS`): each one package
that owns its model, supports, end face, what it admits and its checks' data.

Built in: :mod:`.section` ("continuum": the continuum-based planar section) and :mod:`.cable`
("cable": a centre line whose section is integrated fibre by fibre). Beside them, what every
kinematics' model shares (:mod:`.model`), the end face (:mod:`.face`) and the compiled
element interface that chooses a model's kernels from its data (:mod:`.kernels`).
"""
from __future__ import annotations

from ..core.spec import KINEMATICS  # noqa: F401
from .family import Kinematics, get_kinematics, register_kinematics  # noqa: F401
from . import section  # noqa: E402,F401  (the built-in kinematics register themselves,
from . import cable  # noqa: E402,F401   in the order the registry lists them)
