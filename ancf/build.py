"""Scene -> objects: the one place where the names in a scene become elements, laws,
formulations, quadrature rules, supports and integrators. :func:`plan` checks a scene once
(:func:`ancf.admission.check`: its names against ancf's registries, and what each element
admits) and resolves it into a frozen :class:`Plan` (element, formulation, rule, estimate,
warnings); the builders take it."""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from contract.capacity import Estimate, check_capacity
from contract.scene import MaterialSpec, Scene

from .admission import check  # noqa: F401  (ancf.build.check: the name callers know)
from .integrators import INTEGRATORS
from .elements import get_element
from .formulations import get_formulation
from mechanics.laws import get_law
from .material import Material
from .mesh import Mesh, fixed_dofs
from .beam import BeamModel
from .elements import ElementSpec
from .formulations import Formulation
from .element_model import ElementModel
from .couple import Loading, end_face
from .quadrature import gauss
from .rank import default_quadrature, rule_warnings


# -- a scene resolved once ---------------------------------------------------------------

@dataclass(frozen=True)
class Plan:
    """A checked scene resolved once into what the solver's steps take: the element, the
    formulation, the elastic rule (the scene's, or the element's default at this mesh's
    l_e / h), the memory and time estimate and the warnings (capacity's, the chosen rule's).
    :func:`plan` makes it; every public function here takes a Plan or a scene (a scene is
    resolved on the spot), and a run (:func:`ancf.simulation.run_scene`, ``ancf run``)
    resolves its scene once and passes the plan on."""
    scene: Scene
    element: ElementSpec
    formulation: Formulation
    rule: tuple[int, int]
    aspect: float                       # l_e / h
    estimate: Estimate
    capacity_warnings: tuple[str, ...]

    @cached_property
    def rule_warnings(self) -> tuple[str, ...]:
        """The rank tests' verdict on a rule the scene chose (:func:`ancf.rank.rule_warnings`),
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


def resolve(scene: Scene | Plan) -> Plan:
    """A plan as it is, or a scene resolved (:func:`plan`)."""
    return scene if isinstance(scene, Plan) else plan(scene)


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


def estimate(scene: Scene | Plan) -> Estimate:
    """The run's unknowns, peak memory and time steps (:func:`_estimate`)."""
    return resolve(scene).estimate


def capacity(scene: Scene | Plan) -> list[str]:
    """Refuse a scene that cannot fit in this machine's memory (SceneError); warnings."""
    return list(resolve(scene).capacity_warnings)


def build_material(spec: MaterialSpec) -> Material:
    return Material(get_law(spec.law), get_formulation(spec.formulation),
                    dict(spec.constants), spec.penalty, spec.density)


def aspect(scene: Scene | Plan) -> float:
    """l_e / h of the scene's mesh."""
    return resolve(scene).aspect


def quadrature(scene: Scene | Plan) -> tuple[int, int]:
    """The elastic rule: the scene's, or the element's default for its formulation kind
    and l_e / h (:func:`ancf.rank.default_quadrature`)."""
    return resolve(scene).rule


def quadrature_warnings(scene: Scene | Plan) -> list[str]:
    """The rank tests' verdict on a rule the scene chose (:func:`ancf.rank.rule_warnings`)."""
    return list(resolve(scene).rule_warnings)


def build_model(scene: Scene | Plan) -> ElementModel:
    p = resolve(scene)
    scene, s = p.scene, p.scene.ancf
    mesh = Mesh(p.element, s.elements, scene.beam.length, scene.beam.height, scene.beam.width)
    return model_for(mesh, build_material(scene.material), gauss(*p.rule),
                     fixed_dofs(mesh, scene.supports.left, scene.supports.clamp))


def external_loads(model: ElementModel, scene: Scene | Plan) -> dict[str, np.ndarray]:
    """The dead load vectors Q (N) by effect: only the loads the scene names are built."""
    scene = scene.scene if isinstance(scene, Plan) else scene
    loads = {}
    if scene.loads.gravity is not None:
        loads["gravity"] = model.gravity_force(scene.loads.gravity)
    if scene.loads.tip_force is not None:
        loads["tip_force"] = model.tip_force(scene.loads.tip_force)
    return loads


def static_loading(model: ElementModel, loads: dict[str, np.ndarray], scene: Scene | Plan) -> Loading:
    """What a static solve balances (:class:`ancf.couple.Loading`): the sum of the dead
    load vectors and, if the scene names one, the end couple on the free end face."""
    scene = scene.scene if isinstance(scene, Plan) else scene
    Q = sum(loads.values(), np.zeros(model.mesh.n_dof))
    if scene.loads.end_moment is None:
        return Loading(Q)
    return Loading(Q, scene.loads.end_moment, end_face(model))


def build_integrator(scene: Scene | Plan, model: ElementModel, M, loads: dict):
    a = resolve(scene).scene.analysis
    return INTEGRATORS[a.integrator](model, M, loads, a.rho_inf, a.newton_rtol, a.max_iterations,
                                     newton=a.newton)


def model_for(mesh: Mesh, material: Material, rule, fixed: np.ndarray) -> ElementModel:
    """The model of the kinematics the mesh's element declares (``ElementSpec.kinematics``):
    :class:`ancf.cable.CableModel` for a cable, :class:`ancf.beam.BeamModel` otherwise."""
    if mesh.element.cable:
        from .cable import CableModel
        return CableModel(mesh, material, rule, fixed)
    return BeamModel(mesh, material, rule, fixed)
