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

The end moment M (``loads.end_moment``, static scenes) adds the couple's potential
-t M_p theta(d) (:class:`reference_fem.couple.EndMoment`; M_p = M / width_factor, per
unit width in 2D): d the end face's first moment (:class:`~.fem.FaceFirstMoment`,
linear in the unknowns, d = d0 + G^T w), theta = atan2(-d_x, d_y). Its force
-t M_p G dtheta/dd enters the residual and its rank-2 tangent -t M_p G H G^T enters the
Newton solve exactly, by Sherman-Morrison-Woodbury on the factorisation of the forms'
tangent (two extra solves per iteration; :class:`~.fem.NonlinearSystem`): the couple is
not a form, so the assembled matrix keeps its sparsity pattern. 2D and 3D (the same
forms; in 3D d is in-plane, the face's first moment weighted by 1 / (h^3 w / 12)).

Supports: ``clamp`` fixes the whole left face x = 0 (every component, any
``supports.clamp``: a continuum has no separate slopes); ``pin`` fixes the model
geometry's pin (2D: the node at the centre of the left face; 3D: the line across the
width at mid-height; both need an even number of cells across the height); ``slide``
fixes u_x on the face and u_y at its centre; ``hinge`` (2D) keeps the face straight
through its fixed centre, u(0, Y) = Y a, by exact elimination
(:class:`~.fem.FaceHinge`: u = T w_r, the tangent T^T K T by MatPtAP, the residual
T^T R; any number of cells across). 3D with ``side_faces = "plane-strain"`` adds
u_z = 0 on both side faces.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import ufl

from contract.errors import SceneError
from contract.loads import end_traction, face_moment_weight
from contract.scene import Scene
from mechanics.laws import Law, get_law

from . import fem as backend
from .models import ContinuumModel, get_model
from ..couple import EndMoment
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
    moment: float | None = None           # N m (per unit width in 2D): the end moment M_p
    moment_weight: float = 1.0            # 1 / int Y^2 dA over the end face (1/m^3 in 2D, 1/m^4 in 3D)
    hinge: backend.FaceHinge | None = None   # the hinge's elimination (supports.left = "hinge")

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
        """Unknowns the supports remove: the Dirichlet dofs, and the hinge's eliminated ones."""
        n = backend.fixed_dof_count(self.bcs, self.disc.comm)
        return n + (self.hinge.n_eliminated if self.hinge is not None else 0)

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
    """The Dirichlet conditions of the supports of :data:`contract.loads.SUPPORTS` on this
    discretisation (the hinge has none: :func:`hinge`)."""
    g, b, left = model.geometry, scene.beam, scene.supports.left
    check_support(left, g, settings)
    sides = disc.fix(g.sides(b), components=(2,)) if settings.side_faces == "plane-strain" else []
    if left == "clamp":
        return disc.fix(g.at_left(b), components=range(g.gdim)) + sides
    if left == "slide":
        return disc.fix(g.at_left(b), components=(0,)) + disc.fix(g.pin(b), components=(1,), on="points") + sides
    if left == "hinge":
        return sides
    return disc.fix(g.pin(b), components=range(g.gdim), on="points") + sides


def hinge(disc: backend.Discretisation, scene: Scene, settings: FemSettings, model: ContinuumModel):
    """The hinge's exact elimination (:class:`~.fem.FaceHinge`) for ``supports.left =
    "hinge"``, else None; the direct solver only (a SceneError naming fem.linear_solver)."""
    if scene.supports.left != "hinge":
        return None
    if settings.linear_solver != "direct":
        raise SceneError("fem.linear_solver: \"iterative\" with supports.left = \"hinge\" (the hinge is an "
                         "elimination of the face's unknowns, solved by LU); allowed: 'direct'")
    return backend.FaceHinge(disc, model.geometry.at_left(scene.beam))


def end_moment(scene: Scene, geometry) -> tuple[float | None, float]:
    """(M_p, weight): the scene's end moment per unit width in 2D (M / width_factor, N m)
    and 1 / int Y^2 dA of the end face (12 / h^3 per unit width; / w in 3D)."""
    b, M = scene.beam, scene.loads.end_moment
    weight = face_moment_weight(b.height) / (b.width if geometry.gdim == 3 else 1.0)
    return (None if M is None else M / geometry.width_factor(b)), weight


def set_up(scene: Scene, settings: FemSettings) -> Setup:
    """The scene's beam on the mesh ``settings`` describe, with the scene's loads."""
    model = get_model(settings.model, settings.incompressibility)
    g, b, m, loads = model.geometry, scene.beam, scene.material, scene.loads
    disc = backend.Discretisation(backend.beam_mesh(g, b, settings), settings.degree, model.has_pressure,
                                  settings.quadrature_degree)
    body = None if loads.gravity is None else m.density * g.vector(loads.gravity)
    traction = None if loads.tip_force is None else g.vector(end_traction(loads.tip_force, b.height, b.width))
    effects = ["elastic", *model.effects] + [k for k in ("gravity", "tip_force", "end_moment")
                                             if getattr(loads, k) is not None]
    moment, weight = end_moment(scene, g)
    return Setup(model, get_law(m.law), disc, dict(m.constants), supports(disc, scene, settings, model),
                 body, traction, g.at_right(b), m.penalty, g.width_factor(b), effects,
                 settings.linear_solver, moment, weight, hinge(disc, scene, settings, model))


@dataclass
class Problem:
    """The static problem: the nonlinear system of Pi and its load parameter."""
    setup: Setup
    system: backend.NonlinearSystem
    load: object                 # the load parameter t (a dolfinx Constant)
    couple: EndMoment | None = None   # the end moment's term

    end_moment_method = ("DOLFINx: G assembled over the end facets; the rank-2 tangent by "
                         "Sherman-Morrison-Woodbury on the forms' LU (two extra solves per iteration)")

    def rotation(self) -> float | None:
        """theta (rad) of the end face, continued along the load path (with an end moment)."""
        return None if self.couple is None else self.couple.rotation(self.system.x)

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

    def admissibility(self) -> dict:
        """{"det_F": min det F over the cells (not only the quadrature points), "at": where
        (reference point, m)} at the current state: <= 0 is an inverted cell, a state no
        continuum can take, which the discrete energy did not see (it is evaluated at the
        quadrature points only)."""
        d = self.setup.disc
        if not hasattr(self, "_detF"):
            self._detF = ufl.det(self.setup.gradient(d.u))
        v, x = d.cell_minimum(self._detF)
        return {"det_F": v, "at": [float(c) for c in x]}

    def diagnose(self, t1: float, iterations: int = 3) -> dict:
        """Why the increment from the current (accepted) state to load ``t1`` failed: a few
        Newton iterates toward t1, and at each the unstable directions of the tangent (from
        a stable accepted state, > 0 means the path meets a critical point there: Newton
        2-cycles across it) and where the correction peaks (reference point, m); the
        largest count and its place. The current state and load are restored."""
        saved = self.system.save()
        t0 = float(self.load.value)
        found, peak = 0, None
        try:
            self.set_load(t1)
            for _ in range(iterations):
                self.system.residual_norm()
                self.system.newton_update()
                n = self.system.unstable_directions()
                if n is None:                 # the eigen solve did not answer: nothing to count
                    break
                if peak is None or n > found:
                    found, peak = n, self.setup.disc.dof_point(self.system.last_increment())
                if n > 0:
                    # the correction from the indefinite iterate: it points at the critical
                    # mode (the first one is the load increment's global response)
                    self.system.residual_norm()
                    self.system.newton_update()
                    peak = self.setup.disc.dof_point(self.system.last_increment())
                    break
        except ArithmeticError:
            pass
        finally:
            self.system.restore(saved)
            self.set_load(t0)
        return {"unstable_directions": found,
                "correction_peak": None if peak is None else [float(c) for c in peak]}


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
    couple = None
    if s.moment is not None:
        couple = EndMoment(backend.FaceFirstMoment(d, s.traction_where, s.moment_weight, s.bcs), s.moment,
                           lambda: float(t.value))
    return Problem(s, system(s, residual, low_rank=couple), t, couple)


def system(s: Setup, residual, unknown=None, pressure_scale: str | None = "mu",
           low_rank=None) -> backend.NonlinearSystem:
    """The nonlinear system of ``residual`` with the set-up's supports (the hinge's
    elimination included) and linear solver; the iterative solver approximates the Schur
    complement by -mu M (``pressure_scale = "mu"``) or by PETSc's selfp (None).
    ``low_rank``: the end moment's term (:class:`reference_fem.couple.EndMoment`)."""
    return backend.NonlinearSystem(s.disc, residual, s.bcs, unknown=unknown, linear_solver=s.linear_solver,
                                   pressure_scale=s.mu if pressure_scale == "mu" else None,
                                   low_rank=low_rank, reduction=s.hinge)
