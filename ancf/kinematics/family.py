"""What a kinematics is: the interface every family of ANCF elements gives the solver.

A kinematics (the continuum-based planar section, the cable; a spatial beam later) says how
an element's nodal coordinates become strains, and everything that follows from it: the
model that integrates the law, the dofs a support fixes, the end face a couple turns, which
formulations and integrators it admits, and the data its contract checks and rank tests
read. The solver and the checks ask the element's kinematics
(:attr:`ancf.core.spec.ElementSpec.family`), never the kinematics' name. A kinematics is one
package under :mod:`ancf.kinematics` and one :func:`register_kinematics`; its elements are
data (:mod:`ancf.elements`).
"""
from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np

from ..core.spec import KINEMATICS, ElementSpec


class Kinematics(ABC):
    """The interface (see the module doc). A subclass sets :attr:`name`, :attr:`summary`, the
    data of its checks (:attr:`section_field` ... :attr:`patch_test`) and, if it refuses
    some, :attr:`formulations`, and implements every abstract method."""
    name: str = ""
    summary: str = ""
    # the formulations its elements run (None: every registered one), and why only those
    formulations: tuple[str, ...] | None = None
    formulations_why: str = ""
    # the data its contract checks read (:mod:`ancf.checks.element`): do positions vary across
    # the section (N(x, y))? its point data at rest; which column of the point data the
    # section's slope is (the conformity check's jump); is a mirrored state admissible? its
    # patch test: "stress" (a constant F on a free patch) or "uniaxial" (a constant fibre stretch)
    section_field: bool = True
    reference_gradient: np.ndarray = np.eye(2)
    section_slope: int = 1
    mirror_admissible: bool = False
    patch_test: str = "stress"

    # -- the spec and what a scene may ask of it -------------------------------------
    def check(self, spec: ElementSpec) -> None:
        """ValueError naming the element if the spec does not fit this kinematics."""

    def refused_integrators(self, spec: ElementSpec) -> dict[str, str]:
        """{integrator: why the element cannot run it} (the one rule, asked by the scene
        check, the models, the warm-up and the studies: :mod:`ancf.admission`)."""
        return {}

    def runs(self, formulation: str) -> bool:
        """Can its elements run the formulation?"""
        return self.formulations is None or formulation in self.formulations

    # -- the model, the supports, the end face ---------------------------------------
    @abstractmethod
    def model(self, mesh, material, rule, fixed: np.ndarray):
        """The model (:class:`ancf.kinematics.model.ElementModel`) of a mesh of its elements."""

    @abstractmethod
    def fixed_dofs(self, mesh, left: str, clamp: str | None) -> np.ndarray:
        """The dofs a support at x = 0 fixes (:data:`contract.loads.SUPPORTS`)."""

    @abstractmethod
    def end_face(self, model):
        """The free end face's first moment d = d0 + A u[rows]
        (:class:`ancf.kinematics.face.EndFace`), which the end couple turns."""

    @abstractmethod
    def section_points(self, model, u: np.ndarray, xi: np.ndarray, eta: np.ndarray) -> np.ndarray:
        """Deformed positions (ne, len(xi), 2) of the points (xi, eta) of every element (drawn
        by :mod:`ancf.output`)."""

    # -- what the contract checks and the rank tests read ------------------------------
    @abstractmethod
    def point_data(self, spec: ElementSpec, xi, eta, length: float, height: float) -> np.ndarray:
        """(npts, n_shape, 2): the two vectors each point's strain is made of, per shape
        function (a continuum's grad N; a cable's (N', Y N''))."""

    @abstractmethod
    def exact_degree(self, spec: ElementSpec) -> tuple[int, int]:
        """The degrees (along, across) a rule must integrate exactly for the small-strain
        stiffness (:func:`ancf.checks.rank.exact_rule`)."""

    @abstractmethod
    def small_strain(self, dN: np.ndarray) -> np.ndarray:
        """B (nq, 3, ns, 2): [eps_xx; eps_yy; 2 eps_xy] at the points of ``dN`` per nodal
        displacement (the rank test's rows)."""

    @abstractmethod
    def finite_strain(self, q: np.ndarray, dN: np.ndarray, T=None) -> np.ndarray:
        """The strain measure the finite-strain rank test compares (npts, k) at displacements
        q (ns, 2); T an assumed strain's sampling (:func:`ancf.kinematics.section.assumed.sampling`)."""

    def __repr__(self) -> str:
        return f"<kinematics {self.name}>"


def register_kinematics(k: Kinematics) -> Kinematics:
    """Add a kinematics to :data:`ancf.core.spec.KINEMATICS` (an element names it)."""
    return KINEMATICS.register(k.name, k)


def get_kinematics(name: str) -> Kinematics:
    return KINEMATICS.lookup(name)
