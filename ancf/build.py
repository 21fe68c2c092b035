"""Scene -> objects: the one place where the names in a scene become elements, laws,
formulations, quadrature rules, supports and integrators. :func:`plan` checks a scene's
names against ancf's registries once (:func:`check`) and resolves it into a frozen
:class:`Plan` (element, formulation, rule, estimate, warnings); the builders take it."""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from contract.capacity import Estimate, check_capacity
from contract.errors import SceneError
from contract.scene import MaterialSpec, Scene, check_names

from .elements import ELEMENTS, get_element
from .formulations import FORMULATIONS, get_formulation
from .integrators import INTEGRATORS
from mechanics.laws import LAWS, get_law
from .material import Material
from .mesh import Mesh, fixed_dofs
from .beam import BeamModel
from .elements import ElementSpec
from .formulations import Formulation
from .element_model import ElementModel
from .couple import Loading, end_face
from .quadrature import gauss
from .rank import default_quadrature, rule_warnings


def check(scene: Scene) -> Scene:
    """The scene's names against ancf's registries (one message naming the field and
    the allowed values); an ANCF run needs the [ancf] table."""
    if scene.ancf is None:
        raise SceneError("ancf: the scene has no [ancf] table (element, elements)")
    check_names(scene, laws=LAWS, formulations=FORMULATIONS, integrators=INTEGRATORS, elements=ELEMENTS)
    _check_kinematics(scene)
    _check_pressure_rule(scene)
    _check_aspect(scene)
    return scene


def _check_aspect(scene: Scene) -> None:
    """The element's basis must be determined by its nodal coordinates at this mesh's l_e and
    h (and at l_e / h, the rank tests' scaling): an element absurdly stout (l_e / h = 1e-7
    for HB2n-12 and HB3n-12) makes the nodal matrix singular in floating point."""
    s, el = scene.ancf, get_element(scene.ancf.element)
    le, h = scene.beam.length / s.elements, scene.beam.height
    try:
        el.dimensionless(le, h)
        el.dimensionless(le / h, 1.0)
    except ValueError:
        raise SceneError(f"beam.height: an element of l_e / h = {le / h:.3g} (beam.length / ancf.elements / "
                         f"beam.height) is singular for {el.name}: its nodal coordinates do not determine its "
                         "basis in floating point (fewer elements or a more slender beam)") from None


def _check_kinematics(scene: Scene) -> None:
    """What an element's kinematics cannot run: a cable (``ElementSpec.formulations``)
    integrates the law's uniaxial energy, with free lateral faces, so plane stress alone;
    and its fibre stretch is not quadratic in u, so it has no discrete gradient."""
    el = get_element(scene.ancf.element)
    allowed = el.formulations
    if allowed is not None and scene.material.formulation not in allowed:
        raise SceneError(f"material.formulation: {scene.material.formulation!r} cannot run element {el.name} "
                         f"({el.kinematics}: the section's fibres in uniaxial stress with free faces); "
                         f"allowed for it: {', '.join(repr(f) for f in allowed)}")
    a = scene.analysis
    if a.kind == "dynamic" and a.newton == "linear" and INTEGRATORS[a.integrator].compiled != "alpha-family":
        family = sorted(i for i, c in INTEGRATORS.items() if c.compiled == "alpha-family")
        raise SceneError(f"analysis.newton: 'linear' (one solve per step) is a step of the generalized-alpha "
                         f"family; integrator {a.integrator!r} runs full Newton: choose analysis.integrator from "
                         f"{', '.join(repr(i) for i in family)}, or another analysis.newton")
    if el.cable and scene.analysis.kind == "dynamic" and scene.analysis.integrator == "discrete-gradient":
        others = sorted(i for i in INTEGRATORS if i != "discrete-gradient")
        raise SceneError(f"analysis.integrator: 'discrete-gradient' cannot run element {el.name} (a cable's fibre "
                         f"stretch is not quadratic in u: no exact discrete gradient here); allowed for it: "
                         f"{', '.join(repr(i) for i in others)}")


def _check_pressure_rule(scene: Scene) -> None:
    """A rule the scene chose must resolve the element's pressure field where it carries
    the penalty (a tensor rule with more points than the field's degree in x and in y)."""
    s, el = scene.ancf, get_element(scene.ancf.element)
    if not (el.pressure and s.quadrature is not None and get_formulation(scene.material.formulation).penalised):
        return
    dx = max(p.degree()[0] for p in el.pressure_polys)
    dy = max(p.degree()[1] for p in el.pressure_polys)
    if s.quadrature[0] <= dx or s.quadrature[1] <= dy:
        raise SceneError(f"ancf.quadrature: {list(s.quadrature)} does not resolve the pressure field of "
                         f"{el.name} (degree {dx} in x, {dy} in y): at least [{dx + 1}, {dy + 1}] points; "
                         "or leave quadrature out for the element's default")


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
