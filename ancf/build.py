"""Scene -> objects: the one place where the names in a scene become elements, laws,
formulations, quadrature rules and supports."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .elements import get_element
from .errors import SceneError
from .formulations import get_formulation
from .laws import get_law
from .material import Material
from .mesh import Mesh, fixed_dofs
from .model import BeamModel
from .quadrature import gauss
from .scene import MaterialSpec, Scene


def build_material(spec: MaterialSpec) -> Material:
    return Material(get_law(spec.law), get_formulation(spec.formulation),
                    dict(spec.constants), spec.penalty, spec.density)


def build_model(scene: Scene) -> BeamModel:
    if scene.ancf is None:
        raise SceneError("ancf: the scene has no [ancf] table (element, elements)")
    s = scene.ancf
    mesh = Mesh(get_element(s.element), s.elements, scene.beam.length,
                scene.beam.height, scene.beam.width)
    return BeamModel(mesh, build_material(scene.material), gauss(*s.quadrature),
                     fixed_dofs(mesh, scene.supports.left, scene.supports.clamp))


def external_force(model: BeamModel, scene: Scene) -> np.ndarray:
    """The dead external load vector Q_K (N): only the loads the scene names are built."""
    f = np.zeros(model.mesh.n_dof)
    if scene.loads.gravity is not None:
        f += model.gravity_force(scene.loads.gravity)
    if scene.loads.tip_force is not None:
        f += model.tip_force(scene.loads.tip_force)
    return f
