"""The continuum problem: energy, loads and supports -> a nonlinear system.

Total potential per unit width (J/m):

    Pi(u, phat) = int W(F, phat) dA - t * ( int rho g . u dA + int tbar . u ds )

with t the load parameter (0..1) the static solver drives, W from
:mod:`reference_fem.energies`, gravity as the body force rho g and the tip force as
the uniform dead traction tbar = F_tip / (h w) on the end face x = L (its resultant
over the full width w is F_tip). Constants enter as dolfinx Constants, so the
compiled forms are shared by every set of material constants.

Supports (:func:`beam_supports`): ``clamp`` fixes the whole left face x = 0 (both
components, any ``supports.clamp``: a continuum has no separate slopes); ``pin``
fixes the one node at the centre of the left face (0, 0) (both components), which
needs an even number of cells across the height.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import ufl

from ancf.errors import SceneError
from ancf.scene import Scene

from . import dolfinx_backend as backend
from .energies import INCOMPRESSIBILITIES, get_law_ufl
from .settings import FemSettings


@dataclass
class Problem:
    disc: backend.Discretisation
    system: backend.NonlinearSystem
    load: object                 # the load parameter t (a dolfinx Constant)
    pressure_scale: float        # p = pressure_scale * phat (Pa)
    effects: list = field(default_factory=list)
    n_fixed: int = 0             # degrees of freedom fixed by the supports

    @property
    def n_free(self) -> int:
        """Unknowns of the solve (displacement + pressure, supports removed), as ancf's n_free."""
        return self.disc.ndof - self.n_fixed

    def set_load(self, t: float) -> None:
        self.load.value = t


def build_problem(disc: backend.Discretisation, law_name: str, constants: dict,
                  model: str, incompressibility: str, bcs, penalty: float | None = None,
                  body_force=None, traction=None, traction_where=None) -> Problem:
    """Assemble Pi for one law and continuum model on ``disc``; loads are optional:
    ``body_force`` (N/m^3, 2-vector) everywhere, ``traction`` (Pa, 2-vector) on the
    boundary where ``traction_where`` holds."""
    law = get_law_ufl(law_name)
    inc = INCOMPRESSIBILITIES[(model, incompressibility)]
    if inc.has_pressure != disc.pressure:
        raise ValueError("the discretisation's pressure field does not match the model")
    c = {k: disc.constant(constants[k]) for k in law.constants}
    mu_value = 2.0 * (constants.get("C10", 0.0) + constants.get("C01", 0.0))
    mu = disc.constant(mu_value)
    alpha = disc.constant(penalty) if incompressibility == "penalty" else None
    t = disc.constant(0.0)
    F = ufl.Identity(2) + ufl.grad(disc.u)
    W = inc.energy(law, c, F, disc.phat, mu, alpha)
    Pi = W * disc.dx
    effects = ["elastic"] + (["penalty"] if incompressibility == "penalty" else [])
    if body_force is not None:
        Pi = Pi - t * ufl.dot(disc.constant(np.asarray(body_force, float)), disc.u) * disc.dx
        effects.append("gravity")
    if traction is not None:
        ds = disc.boundary_measure(traction_where)
        Pi = Pi - t * ufl.dot(disc.constant(np.asarray(traction, float)), disc.u) * ds
        effects.append("tip_force")
    residual = ufl.derivative(Pi, disc.w, disc.test)
    system = backend.NonlinearSystem(disc, residual, bcs)
    return Problem(disc, system, t, mu_value, effects, backend.fixed_dof_count(bcs))


def beam_supports(disc: backend.Discretisation, scene: Scene, settings: FemSettings):
    tol = 1e-9 * scene.beam.length
    if scene.supports.left == "clamp":
        return disc.fix(lambda x: np.abs(x[0]) < tol)
    if settings.cells_height % 2:
        raise SceneError("fem.cells_height: supports.left = \"pin\" fixes the node at the "
                         "centre of the left face; needs an even number of cells across")
    return disc.fix(lambda x: (np.abs(x[0]) < tol) & (np.abs(x[1]) < tol), on="points")


def build_beam_problem(scene: Scene, settings: FemSettings) -> Problem:
    """The scene's beam as a 2D continuum on the mesh ``settings`` describe."""
    b, m, loads = scene.beam, scene.material, scene.loads
    mesh = backend.rectangle_mesh(b.length, b.height, settings.cells_length,
                                  settings.cells_height, settings.cell)
    disc = backend.Discretisation(mesh, settings.degree, settings.has_pressure,
                                  settings.quadrature_degree)
    body = None if loads.gravity is None else m.density * np.asarray(loads.gravity)
    traction = None if loads.tip_force is None else np.asarray(loads.tip_force) / (b.height * b.width)
    tol = 1e-9 * b.length
    return build_problem(
        disc, m.law, dict(m.constants), settings.model, settings.incompressibility,
        beam_supports(disc, scene, settings), penalty=m.penalty, body_force=body,
        traction=traction, traction_where=lambda x: np.abs(x[0] - b.length) < tol)
