"""2D formulations: which invariants a law sees, and whether a penalty is added.

A formulation maps the 2D invariants (a = tr C, J = det F) to the invariants (I1, I2)
the law is written in, and says whether the volumetric penalty alpha/2 (J - 1)^2 is
part of the energy.

- ``paper``: the paper's literal energies, with the 2 x 2 C: I1 = tr C, and I2 chosen so
  that C01 (I2 - 3) equals the paper's C01/2 ((tr C)^2 - tr(C^2) - 3), i.e.
  I2 = det C + 3/2. Not stress-free at F = I (see PAPER.md, numerical pitfalls).
- ``plane-strain``: 3D invariants with F33 = 1 (I1 = tr C + 1, I2 = tr C + J^2), made
  isochoric (I1bar = J^(-2/3) I1, I2bar = J^(-4/3) I2), plus the penalty (ABAQUS's
  form with D1 = 2 / alpha). Stress-free at F = I.
- ``plane-stress``: exactly incompressible with F33 = 1/J (I1 = tr C + J^-2,
  I2 = tr C J^-2 + J^2). No penalty.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from contract.registry import Registry
from contract.scene import FORMULATIONS as PENALISED


@dataclass(frozen=True)
class Formulation:
    name: str
    invariants: Callable  # (a: Jet, J: Jet) -> (I1: Jet, I2: Jet)
    stress_free: bool
    doc: str = ""

    @property
    def penalised(self) -> bool:
        """Is alpha/2 (J - 1)^2 part of the energy? The scene language says
        (:data:`contract.scene.FORMULATIONS`: the scene then carries material.penalty)."""
        return PENALISED[self.name]


def _paper(a, J):
    return a, J ** 2 + 1.5


def _plane_strain(a, J):
    return (a + 1.0) * J ** (-2.0 / 3.0), (a + J ** 2) * J ** (-4.0 / 3.0)


def _plane_stress(a, J):
    Jm2 = J ** -2
    return a + Jm2, a * Jm2 + J ** 2


FORMULATIONS: Registry[Formulation] = Registry("material.formulation", "formulation")
for _f in (Formulation("paper", _paper, stress_free=False,
                       doc="the paper's literal 2D energies plus alpha/2 (J - 1)^2"),
           Formulation("plane-strain", _plane_strain, stress_free=True,
                       doc="F33 = 1, isochoric invariants, plus alpha/2 (J - 1)^2"),
           Formulation("plane-stress", _plane_stress, stress_free=True,
                       doc="incompressible, F33 = 1/J, no penalty")):
    FORMULATIONS.register(_f.name, _f)
FORMULATIONS.freeze_builtin()


def get_formulation(name: str) -> Formulation:
    return FORMULATIONS.lookup(name)
