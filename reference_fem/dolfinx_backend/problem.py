"""The continuum problem's set-up, shared by statics and dynamics: mesh, spaces, law,
model, supports and loads, from a scene and its [fem] settings.

:func:`set_up` builds a :class:`Setup`; :func:`static_problem` turns it into the
nonlinear system of the total potential

    Pi(u, phat) = int W(F, phat) dV - t * ( int rho g . u dV + int tbar . u dA )

(t the load parameter the static solver drives), and
:mod:`reference_fem.dolfinx_backend.dynamic_problem` into the residual of one time step. The model
(:mod:`reference_fem.dolfinx_backend.models`) gives W; gravity is the body force rho g, the tip force
the uniform dead traction tbar = F_tip / (h w) on the end face x = L (its resultant
over the full width is F_tip). Constants enter as dolfinx Constants.

Supports: ``clamp`` fixes the whole left face x = 0 (every component, any
``supports.clamp``: a continuum has no separate slopes); ``pin`` fixes the model
geometry's pin (2D: the node at the centre of the left face; 3D: the line across the
width at mid-height; both need an even number of cells across the height). 3D with
``side_faces = "plane-strain"`` adds u_z = 0 on both side faces.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import ufl

from contract.loads import end_traction
from contract.scene import Scene
from mechanics.laws import Law, get_law

from . import fem as backend
from .models import ContinuumModel, get_model
from ..geometry import check_support
from ..settings import FemSettings


@dataclass
class Setup:
    model: ContinuumModel
    law: Law
    disc: backend.Discretisation
    constants: dict                      # Pa, by name (floats)
    bcs: list
    body_force: np.ndarray | None = None  # N/m^3 (rho g), geometry's dimension
    traction: np.ndarray | None = None    # Pa, on the free end
    traction_where: object = None         # locator of the free end
    penalty: float | None = None          # Pa, for models with a penalty
    width: float = 1.0                    # factor from the problem's energies to the full beam's
    effects: list = field(default_factory=list)
    linear_solver: str = "direct"         # of the Newton increments (FemSettings.linear_solver)

    def __post_init__(self):
        d = self.disc
        self.mu = self.law.shear_modulus(self.constants)   # the pressure scale: p = mu phat
        self.c = {k: d.constant(self.constants[k]) for k in self.law.constants}
        self.mu_c = d.constant(self.mu)
        self.alpha = d.constant(self.penalty) if "penalty" in self.model.effects else None
        self.body = None if self.body_force is None else d.constant(self.body_force)
        self.tbar = None if self.traction is None else d.constant(self.traction)
        self.ds = None if self.traction is None else d.boundary_measure(self.traction_where)

    @property
    def n_fixed(self) -> int:
        return backend.fixed_dof_count(self.bcs, self.disc.comm)

    def gradient(self, u):
        return ufl.Identity(self.model.geometry.gdim) + ufl.grad(u)

    def energy(self, F, phat):
        """W (Pa) with the model's incompressibility terms."""
        return self.model.energy(self.law, self.c, F, phat, self.mu_c, self.alpha)

    def stress(self, u, phat):
        """P = dW/dF at u (and phat)."""
        F = ufl.variable(self.gradient(u))
        return ufl.diff(self.energy(F, phat), F)

    def external_work(self, u):
        """int rho g . u dV + int tbar . u dA (J per unit width in 2D), or None without loads."""
        terms = []
        if self.body is not None:
            terms.append(ufl.dot(self.body, u) * self.disc.dx)
        if self.tbar is not None:
            terms.append(ufl.dot(self.tbar, u) * self.ds)
        return sum(terms[1:], terms[0]) if terms else None

    def potentials(self, u) -> dict:
        """{effect: UFL form} of the dead loads' potentials for the full beam (J):
        -int rho g . (X + u) dV and -int tbar . (X + u) dA."""
        r = ufl.SpatialCoordinate(self.disc.mesh) + u
        out = {}
        if self.body is not None:
            out["gravity"] = -self.width * ufl.dot(self.body, r) * self.disc.dx
        if self.tbar is not None:
            out["tip_force"] = -self.width * ufl.dot(self.tbar, r) * self.ds
        return out


def supports(disc: backend.Discretisation, scene: Scene, settings: FemSettings, model: ContinuumModel):
    """The supports of :data:`contract.loads.SUPPORTS` on this discretisation."""
    g, b, left = model.geometry, scene.beam, scene.supports.left
    check_support(left, g, settings)
    sides = disc.fix(g.sides(b), components=(2,)) if settings.side_faces == "plane-strain" else []
    if left == "clamp":
        return disc.fix(g.at_left(b), components=range(g.gdim)) + sides
    if left == "slide":
        return disc.fix(g.at_left(b), components=(0,)) + disc.fix(g.pin(b), components=(1,), on="points") + sides
    return disc.fix(g.pin(b), components=range(g.gdim), on="points") + sides


def set_up(scene: Scene, settings: FemSettings) -> Setup:
    """The scene's beam on the mesh ``settings`` describe, with the scene's loads."""
    model = get_model(settings.model, settings.incompressibility)
    g, b, m, loads = model.geometry, scene.beam, scene.material, scene.loads
    disc = backend.Discretisation(backend.beam_mesh(g, b, settings), settings.degree, model.has_pressure,
                                  settings.quadrature_degree)
    body = None if loads.gravity is None else m.density * g.vector(loads.gravity)
    traction = None if loads.tip_force is None else g.vector(end_traction(loads.tip_force, b.height, b.width))
    effects = ["elastic", *model.effects] + [k for k in ("gravity", "tip_force") if getattr(loads, k) is not None]
    return Setup(model, get_law(m.law), disc, dict(m.constants), supports(disc, scene, settings, model),
                 body, traction, g.at_right(b), m.penalty, g.width_factor(b), effects,
                 settings.linear_solver)


@dataclass
class Problem:
    """The static problem: the nonlinear system of Pi and its load parameter."""
    setup: Setup
    system: backend.NonlinearSystem
    load: object                 # the load parameter t (a dolfinx Constant)

    @property
    def n_free(self) -> int:
        """Unknowns of the solve (displacement + pressure, supports removed), as ancf's n_free."""
        return self.setup.disc.ndof - self.setup.n_fixed

    def set_load(self, t: float) -> None:
        self.load.value = t

    # what the one static driver (reference_fem.simulation) reads of a backend's model
    @property
    def effects(self) -> list:
        return self.setup.effects

    @property
    def ranks(self) -> int:
        """MPI processes the solve runs on."""
        return self.setup.disc.comm.size

    def displacement(self, point) -> np.ndarray:
        """u (m) at a point of the reference configuration."""
        return self.setup.disc.point_displacement([point])[0]

    def write(self, path, fmt: str):
        """The mesh with its displacement (and pressure) as ``fmt`` ("vtk" | "xdmf")."""
        return self.setup.disc.write(path, fmt, scale=self.setup.mu)


def static_model(scene: Scene, settings: FemSettings) -> Problem:
    """The backend's static model of the scene (:func:`reference_fem.simulation.run_scene`)."""
    return static_problem(set_up(scene, settings))


def static_problem(s: Setup) -> Problem:
    d = s.disc
    t = d.constant(0.0)
    Pi = s.energy(s.gradient(d.u), d.phat) * d.dx
    work = s.external_work(d.u)
    if work is not None:
        Pi = Pi - t * work
    residual = ufl.derivative(Pi, d.w, d.test)
    return Problem(s, system(s, residual), t)


def system(s: Setup, residual, unknown=None, pressure_scale: str | None = "mu") -> backend.NonlinearSystem:
    """The nonlinear system of ``residual`` with the set-up's supports and linear solver;
    the iterative solver approximates the Schur complement by -mu M (``pressure_scale =
    "mu"``) or by PETSc's selfp (None)."""
    return backend.NonlinearSystem(s.disc, residual, s.bcs, unknown=unknown, linear_solver=s.linear_solver,
                                   pressure_scale=s.mu if pressure_scale == "mu" else None)
