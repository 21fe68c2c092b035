"""The rank tests of ancf.checks.rank and the default rules they choose: every declared default
passes both tests where it is declared; the next cheaper rule fails one; the u = 0
spurious-mode count agrees with the zero eigenvalues of the model's own tangent (the
independent route); a scene without a rule gets the default, a scene with a
rank-deficient one runs with a warning."""
from __future__ import annotations

import numpy as np
import pytest

from ancf.build import build_material
from ancf.elements import ELEMENTS, SLENDER, get_element
from ancf.core.mesh import Mesh
from ancf.kinematics.section.model import BeamModel
from ancf.core.quadrature import gauss
from ancf.checks.rank import ASPECTS, default_quadrature, rank_test, strain_test
from ancf.simulation import run_scene
from contract import paper
from contract.scene import MaterialSpec, scene_from_dict

from .conftest import LOCK_FREE

PAPER = ("LB2n-12", "HB2n-12", "HB3n-12", "HB2n-16")


@pytest.mark.parametrize("name", PAPER)
@pytest.mark.parametrize("penalised", [False, True])
def test_each_declared_default_passes_the_u0_test_where_it_is_declared(name, penalised):
    el = get_element(name)
    for aspect in ASPECTS:
        rule = default_quadrature(el, penalised, aspect)
        lin = rank_test(el, rule, aspect)
        assert lin["passes"], (rule, aspect, lin)


FINITE_STRAIN_ASPECTS = (1.0, 0.1, 0.05, 0.01)


def _strain_passes(name: str, penalised: bool, aspects) -> None:
    el = get_element(name)
    for aspect in aspects:
        rule = default_quadrature(el, penalised, aspect)
        if name != "LB2n-12" and not (penalised and aspect >= 0.1):
            assert strain_test(name, rule, aspect)["passes"], (rule, aspect)


@pytest.mark.parametrize("penalised", [False, True])
def test_the_declared_default_passes_the_finite_strain_test_where_it_is_hardest(penalised):
    """HB2n-12 at the smallest l_e / h of the sweep, where its rule is [3, 3]."""
    _strain_passes("HB2n-12", penalised, (0.01,))


@pytest.mark.slow(guard="test_the_declared_default_passes_the_finite_strain_test_where_it_is_hardest")
@pytest.mark.parametrize("name", PAPER)
@pytest.mark.parametrize("penalised", [False, True])
def test_each_declared_default_passes_the_finite_strain_test_where_it_is_declared(name, penalised):
    _strain_passes(name, penalised, FINITE_STRAIN_ASPECTS)


@pytest.mark.parametrize("name, rule, aspect, test", [
    ("LB2n-12", (2, 2), 1.0, "linear"),          # exact zero modes with 2 points along x
    ("HB2n-16", (2, 2), 1.0, "linear"),
    ("HB2n-16", (3, 2), 0.01, "linear"),         # x y^2: axial strain y^2 - h^2/12, zero at both points
    ("HB2n-12", (3, 2), 0.1, "strain"),          # the finite-strain family of x^2 + y^2
    ("HB3n-12", (3, 2), 0.05, "strain"),
    ("HB2n-16", (3, 2), 0.1, "linear"),
    ("HB3n-12", (5, 2), 0.05, "strain"),         # more points along x do not help
])
def test_the_cheaper_rules_fail(name, rule, aspect, test):
    if test == "linear":
        assert not rank_test(name, rule, aspect)["passes"]
    else:
        assert rank_test(name, rule, aspect)["passes"]          # invisible at u = 0 ...
        assert not strain_test(name, rule, aspect)["passes"]    # ... found at finite strain


@pytest.mark.parametrize("name", PAPER)
@pytest.mark.parametrize("rule", [(1, 1), (2, 2), (3, 2), (2, 1)])
def test_the_spurious_count_matches_the_models_tangent(name, rule):
    """Zero eigenvalues of one free element's Jacobi-scaled tangent at u = 0 (plane stress,
    Neo-Hookean), with the rigid three taken away, against the strain-matrix count."""
    h = 0.005
    c = dict(paper.materials()["neo-hookean"])
    rho = c.pop("density")
    mat = build_material(MaterialSpec("neo-hookean", "plane-stress", rho, c, None))
    m = BeamModel(Mesh(get_element(name), 1, h, h, 0.007), mat, gauss(*rule), np.array([], dtype=int))
    K = m.internal_force_and_tangent(np.zeros(m.mesh.n_dof))[1].to_sparse().toarray()
    full = BeamModel(m.mesh, mat, gauss(6, 6), m.fixed).internal_force_and_tangent(np.zeros(m.mesh.n_dof))[1]
    s = 1.0 / np.sqrt(np.diag(full.to_sparse().toarray()))
    lam = np.linalg.eigvalsh(s[:, None] * (0.5 * (K + K.T)) * s)
    zeros = int(np.sum(np.abs(lam) < 1e-10 * lam[-1]))
    assert zeros - 3 == rank_test(name, rule, 1.0)["spurious"]


def test_a_scene_without_a_rule_gets_the_default_and_a_chosen_rank_deficient_rule_is_flagged():
    d = paper.cantilever_scene("mooney-rivlin", "plane-stress", "HB3n-12", 64, name="rank")
    del d["ancf"]["quadrature"]
    rec, _ = run_scene(scene_from_dict(d))
    assert rec["quadrature"] == [3, 2] and not rec.get("warnings")    # l_e/h = 0.5
    d["ancf"]["elements"] = 640                                           # l_e/h = 0.05
    assert run_scene(scene_from_dict(d))[0]["quadrature"] == [3, 3]
    d["ancf"]["elements"] = 64
    d["ancf"]["quadrature"] = [2, 1]
    rec, _ = run_scene(scene_from_dict(d))
    assert rec["quadrature"] == [2, 1]
    assert any("spurious zero-energy mode" in w for w in rec["warnings"])


def test_every_registered_element_has_a_default():
    for el in ELEMENTS.values():
        assert all(n >= 1 for n in default_quadrature(el, False, 1.0))



def test_at_the_slender_pendulums_two_elements_the_rule_below_fails_and_the_slender_one_passes():
    """HB2n-20xyp at l_e / h = 35: the quick part of the slender-rule test below."""
    el = get_element("HB2n-20xyp")
    slender, below = default_quadrature(el, False, SLENDER), default_quadrature(el, False, 0.999 * SLENDER)
    assert strain_test("HB2n-20xyp", slender, 35.0)["passes"] and rank_test(el, slender, 35.0)["passes"]
    assert strain_test("HB2n-20xyp", below, 35.0)["ratio"] < 0.2


@pytest.mark.slow(guard="test_at_the_slender_pendulums_two_elements_the_rule_below_fails_and_the_slender_one_passes")
@pytest.mark.parametrize("name", LOCK_FREE)
def test_the_slender_rule_sees_the_stretch_family_that_the_rule_below_it_misses(name):
    """The elements exact along the beam ([n, .] with n - 1 their degree along) declare more
    points along from l_e / h = 15 on. The rule below passes the finite-strain test up to 15
    and fails at 35 (the slender pendulum's 2 elements), its ratio halving as l_e / h doubles
    (a stretch family that tends to zero energy as the element gets slender); the slender
    rule passes both tests from 15 to 70 (the slender pendulum's single element)."""
    el = get_element(name)
    slender, below = default_quadrature(el, False, SLENDER), default_quadrature(el, False, 0.999 * SLENDER)
    assert slender[0] > below[0] and slender[1] == below[1] and default_quadrature(el, True, SLENDER) == slender
    for aspect in (SLENDER, 35.0, 70.0):
        assert rank_test(el, slender, aspect)["passes"] and strain_test(name, slender, aspect)["passes"], aspect
    assert rank_test(el, below, 0.999 * SLENDER)["passes"] and strain_test(name, below, 0.999 * SLENDER)["passes"]
    ratio = {a: strain_test(name, below, a)["ratio"] for a in (17.5, 35.0)}
    assert ratio[35.0] < 0.2 and ratio[17.5] / ratio[35.0] == pytest.approx(2.0, rel=0.1), ratio
