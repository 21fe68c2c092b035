"""Scene -> objects: the one place where the names in a scene become elements, laws,
formulations, quadrature rules, supports and integrators. :func:`plan` checks a scene once
(:func:`ancf.admission.check`: its names against ancf's registries, and what each element
admits) and resolves it into a frozen :class:`Plan` (element, formulation, rule, estimate,
warnings); :func:`build` turns the plan into the run (:class:`Run`)."""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from contract.capacity import Estimate, check_capacity
from contract.scene import MaterialSpec, Scene

from .admission import check  # noqa: F401  (ancf.build.check: the name callers know)
from .solvers.integrators import INTEGRATORS
from .elements import get_element
from .core.formulations import get_formulation
from mechanics.laws import get_law
from .core.material import Material
from .core.mesh import Mesh
from .core.spec import ElementSpec
from .core.formulations import Formulation
from .kinematics.model import ElementModel
from .solvers.couple import Loading
from .core.quadrature import gauss
from .checks.rank import default_quadrature, rule_warnings


# -- a scene resolved once ---------------------------------------------------------------

@dataclass(frozen=True)
class Plan:
    """A checked scene resolved once into what the solver's steps take: the element, the
    formulation, the elastic rule (the scene's, or the element's default at this mesh's
    l_e / h), the memory and time estimate and the warnings (capacity's, the chosen rule's).
    :func:`plan` makes it, once per run; :func:`build` turns it into the run, and nothing
    downstream takes a scene again."""
    scene: Scene
    element: ElementSpec
    formulation: Formulation
    rule: tuple[int, int]
    aspect: float                       # l_e / h
    estimate: Estimate
    capacity_warnings: tuple[str, ...]

    @cached_property
    def rule_warnings(self) -> tuple[str, ...]:
        """The rank tests' verdict on a rule the scene chose (:func:`ancf.checks.rank.rule_warnings`),
        run when first asked (a run's record), not by a check: they take half a second per
        element, rule and l_e / h."""
        if self.scene.ancf.quadrature is None:
            return ()
        return tuple(rule_warnings(self.element, self.rule, self.formulation.penalised, self.aspect))

    @property
    def warnings(self) -> list[str]:
        return [*self.capacity_warnings, *self.rule_warnings]


def plan(scene: Scene) -> Plan:
    """The scene checked (:func:`check`) and resolved (see :class:`Plan`); a SceneError names
    the field of a scene that cannot run or cannot fit in this machine's memory."""
    check(scene)
    s = scene.ancf
    el, form = get_element(s.element), get_formulation(scene.material.formulation)
    aspect = scene.beam.length / s.elements / scene.beam.height
    rule = tuple(s.quadrature) if s.quadrature is not None else default_quadrature(el, form.penalised, aspect)
    est = _estimate(scene, el, rule)
    return Plan(scene, el, form, rule, aspect, est, tuple(check_capacity(est, "ancf")))


def _estimate(scene: Scene, el: ElementSpec, rule: tuple[int, int]) -> Estimate:
    """Unknowns, peak memory and time steps of the scene's ANCF run, without building it.
    Memory (8-byte floats): the band matrices (tangent, mass, step matrix and the band LU
    workspace: (9 b + 4) n), some 30 vectors of n, the per-point arrays (F, the law's
    jets, stresses: 26 per point) and the gathered element displacements, and a dense
    eigen solve (3 n^2) below 3000 unknowns; n the unknowns, b the half-bandwidth."""
    s = scene.ancf
    nn, nk = len(el.nodes), len(el.kinds)
    nodes = s.elements * (nn - 1) + 1
    n = 2 * nk * nodes
    b = 2 * nk * nn - 1
    nq = math.prod(rule)
    words = (9 * b + 34) * n + s.elements * (26 * nq + 2 * el.dof) + (3 * n * n if n < 3000 else 0)
    a = scene.analysis
    steps = math.ceil(a.t_end / a.dt) if a.kind == "dynamic" else None
    return Estimate(n, 8.0 * words, steps, "ancf.elements")


def estimate(scene: Scene) -> Estimate:
    """The run's unknowns, peak memory and time steps (:func:`_estimate`), from its plan."""
    return plan(scene).estimate


def capacity(scene: Scene) -> list[str]:
    """Refuse a scene that cannot fit in this machine's memory (SceneError); warnings."""
    return list(plan(scene).capacity_warnings)


def build_material(spec: MaterialSpec) -> Material:
    return Material(get_law(spec.law), get_formulation(spec.formulation),
                    dict(spec.constants), spec.penalty, spec.density)


# -- the plan turned into the run --------------------------------------------------------

@dataclass
class Run:
    """What :func:`build` makes of a plan: the model, the dead load vectors by effect, the
    effects the run simulates, and what advances it: the static ``loading`` (a static scene;
    no mass matrix is made) or the mass matrix and the ``integrator`` (a dynamic one)."""
    plan: Plan
    model: ElementModel
    loads: dict[str, np.ndarray]
    effects: list[str]
    loading: Loading | None = None
    mass: object = None
    integrator: object = None


def build(p: Plan) -> Run:
    """The one step from a plan to the run: model, loads, and the static loading or the mass
    matrix and integrator (only what the scene calls for)."""
    model = build_model(p)
    loads = external_loads(model, p)
    effects = model.elastic_effects + list(loads)
    if p.scene.analysis.kind == "dynamic":
        M = model.mass_matrix()
        return Run(p, model, loads, effects + ["inertia"], mass=M, integrator=build_integrator(p, model, M, loads))
    loading = static_loading(model, loads, p)
    return Run(p, model, loads, effects + (["end_moment"] if loading.face is not None else []), loading=loading)


def build_model(p: Plan) -> ElementModel:
    scene, s = p.scene, p.scene.ancf
    mesh = Mesh(p.element, s.elements, scene.beam.length, scene.beam.height, scene.beam.width)
    return model_for(mesh, build_material(scene.material), gauss(*p.rule),
                     p.element.family.fixed_dofs(mesh, scene.supports.left, scene.supports.clamp))


def external_loads(model: ElementModel, p: Plan) -> dict[str, np.ndarray]:
    """The dead load vectors Q (N) by effect: only the loads the scene names are built."""
    loads, named = {}, p.scene.loads
    if named.gravity is not None:
        loads["gravity"] = model.gravity_force(named.gravity)
    if named.tip_force is not None:
        loads["tip_force"] = model.tip_force(named.tip_force)
    return loads


def static_loading(model: ElementModel, loads: dict[str, np.ndarray], p: Plan) -> Loading:
    """What a static solve balances (:class:`ancf.solvers.couple.Loading`): the sum of the dead
    load vectors and, if the scene names one, the end couple on the free end face."""
    Q = sum(loads.values(), np.zeros(model.mesh.n_dof))
    if p.scene.loads.end_moment is None:
        return Loading(Q)
    return Loading(Q, p.scene.loads.end_moment, model.mesh.element.family.end_face(model))


def build_integrator(p: Plan, model: ElementModel, M, loads: dict):
    a = p.scene.analysis
    return INTEGRATORS[a.integrator](model, M, loads, a.rho_inf, a.newton_rtol, a.max_iterations,
                                     newton=a.newton)


def model_for(mesh: Mesh, material: Material, rule, fixed: np.ndarray) -> ElementModel:
    """The model of the kinematics the mesh's element declares (``ElementSpec.kinematics``,
    :meth:`ancf.kinematics.family.Kinematics.model`)."""
    return mesh.element.family.model(mesh, material, rule, fixed)
