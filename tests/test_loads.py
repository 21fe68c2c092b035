"""One end load and one set of supports for both solvers (contract.loads): the end load
is the uniform traction on the end face, ANCF's nodal forces its exact virtual work; a
support a solver cannot apply is one clear error naming it."""
import numpy as np
import pytest

from ancf.build import build_model, plan
from ancf.elements import ELEMENTS, KINDS
from contract import paper
from contract.errors import SceneError
from contract.scene import scene_from_dict


def _model(element: str, n: int = 2, left: str = "clamp"):
    d = paper.cantilever_scene("neo-hookean", "plane-stress", element, n, quadrature=None)
    d["supports"] = {"left": left} if left != "clamp" else d["supports"]
    return build_model(plan(scene_from_dict(d)))


def _rigid(model, v: np.ndarray, theta: float = 0.0) -> np.ndarray:
    """Nodal coordinates of a rigid translation v, or of a small rotation theta about (L, 0)."""
    m = model.mesh
    q = np.zeros(m.n_dof)
    for node, x in enumerate(m.node_x):
        for k, kind in enumerate(m.element.kinds):
            dx, dy = KINDS[kind]
            i = (node * m.n_kinds + k) * 2
            if theta == 0.0:
                q[i:i + 2] = v if kind == "r" else 0.0
            else:     # delta r(x, y) = theta e_z x (r - (L, 0)): (-theta y, theta (x - L)), its derivatives
                if (dx, dy) == (0, 0):
                    q[i:i + 2] = (0.0, theta * (x - m.length))
                elif (dx, dy) == (1, 0):
                    q[i:i + 2] = (0.0, theta)
                elif (dx, dy) == (0, 1):
                    q[i:i + 2] = (-theta, 0.0)
    return q


@pytest.mark.parametrize("element", sorted(ELEMENTS))
def test_the_end_load_has_the_force_as_resultant_and_no_moment_about_the_face_centre(element):
    model = _model(element)
    F = np.array([3.0, -7.0])
    f = model.tip_force(F)
    for v in (np.array([1.0, 0.0]), np.array([0.0, 1.0])):
        assert f @ _rigid(model, v) == pytest.approx(F @ v, rel=1e-12)
    assert abs(f @ _rigid(model, None, theta=1.0)) < 1e-12 * np.linalg.norm(F) * model.mesh.height


def test_a_section_richer_than_linear_takes_the_traction_on_its_higher_kinds():
    """HB2n-40p's r_yy and r_yyyy carry virtual work of a uniform traction (int y^2/2 over
    the face is not zero); a linear section (LB2n-12) takes the point load's forces."""
    m = _model("HB2n-40p")
    f = m.tip_force([0.0, -1.0])
    last = m.mesh.n_nodes - 1
    ryy = m.mesh.dofs(last, ("r_yy",))[1]
    h = m.mesh.height
    assert f[ryy] == pytest.approx(-h ** 2 / 24.0, rel=1e-12)       # -F * mean of y^2 / 2
    lb = _model("LB2n-12")
    point = np.zeros(lb.mesh.n_dof)
    point[lb.mesh.dofs(lb.mesh.n_nodes - 1, ("r",))[1]] = -1.0
    assert np.allclose(lb.tip_force([0.0, -1.0]), point, atol=1e-15)


def test_the_slide_support_holds_the_face_on_x0_and_its_centre_in_y():
    m = _model("HB2n-40p", left="slide")
    kinds = m.mesh.element.kinds
    face = [k for k in kinds if KINDS[k][0] == 0]
    want = sorted([m.mesh.dofs(0, face)[i] for i in range(0, 2 * len(face), 2)] + [m.mesh.dofs(0, ("r",))[1]])
    assert sorted(m.fixed.tolist()) == want


@pytest.mark.dolfinx
@pytest.mark.parametrize("fem, message", [
    ({"model": "3d"}, "supports.left: \"slide\" is not offered by the 3D continuum model"),
    ({"model": "plane-stress", "cells_height": 3}, "fem.cells_height: supports.left = \"slide\""),
])
def test_a_support_the_continuum_cannot_apply_is_one_error_naming_it(fem, message):
    from reference_fem.simulation import run_scene

    d = paper.cantilever_scene("neo-hookean", "plane-stress", fem=fem)
    d["supports"] = {"left": "slide"}
    with pytest.raises(SceneError, match=message.replace("(", r"\(").replace(")", r"\)")):
        run_scene(scene_from_dict(d))


def test_a_clamp_option_with_another_support_is_refused():
    d = paper.cantilever_scene("neo-hookean", "plane-stress", "HB2n-12", 4)
    d["supports"] = {"left": "slide", "clamp": "face"}
    with pytest.raises(SceneError, match="supports.clamp: only with left = \"clamp\""):
        scene_from_dict(d)
