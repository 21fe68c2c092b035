"""Kinematics as a registered family (ancf.kinematics): the solver asks an element's kinematics,
never its name, so a kinematics registered beside the built-in ones runs with no line
elsewhere; and every registered kinematics gives the whole interface."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from ancf.build import plan
from ancf.elements import ELEMENTS, get_element, register_element
from ancf.kinematics import KINEMATICS, Kinematics, get_kinematics, register_kinematics
from ancf.kinematics.section import Section
from ancf.simulation import run_scene
from contract import paper
from contract.scene import scene_from_dict


@pytest.mark.parametrize("name", sorted(KINEMATICS))
def test_every_registered_kinematics_implements_the_interface(name):
    k = get_kinematics(name)
    assert isinstance(k, Kinematics) and k.name == name and k.summary
    assert not getattr(type(k), "__abstractmethods__", None)
    assert k.formulations is None or (k.formulations and k.formulations_why)
    users = [e for e in ELEMENTS.values() if e.kinematics == name]
    assert users, f"no registered element uses kinematics {name}"


@pytest.fixture
def copied_section():
    """A kinematics registered as a test would register a new one: the section's behaviour
    under another name, with an element of it (HB2n-12's data)."""
    class Copied(Section):
        name = "test-copied-section"
        summary = "the continuum-based section under another name (a test)"

    register_kinematics(Copied())
    spec = register_element(dataclasses.replace(get_element("HB2n-12"), name="HB2n-12-copied",
                                                kinematics="test-copied-section"))
    yield spec
    del ELEMENTS[spec.name]
    del KINEMATICS["test-copied-section"]


def _tip(element: str, **analysis) -> dict:
    d = paper.cantilever_scene("yeoh", "plane-stress", element, 4, quadrature=None, **analysis)
    rec, _ = run_scene(plan(scene_from_dict(d)))
    assert rec["status"] == "converged", rec.get("reason")
    return rec


def test_a_kinematics_registered_beside_the_built_in_ones_runs_with_no_line_elsewhere(copied_section):
    """The scene check, the plan (its default rule from the rank tests), the model, the
    supports, the compiled Newton and the record all follow the element's kinematics: the copy
    gives HB2n-12's answer to the bit."""
    assert copied_section.family.name == "test-copied-section"
    ours, theirs = _tip(copied_section.name), _tip("HB2n-12")
    assert ours["tip"] == theirs["tip"] and ours["quadrature"] == theirs["quadrature"]


def test_what_a_kinematics_refuses_is_asked_of_it_alone(copied_section, monkeypatch):
    """A kinematics that refuses plane strain refuses it for its elements, with its reason, in
    the scene check: no list of elements or names anywhere else learns it."""
    monkeypatch.setattr(type(copied_section.family), "formulations", ("plane-stress",))
    monkeypatch.setattr(type(copied_section.family), "formulations_why", "a test's reason")
    d = paper.cantilever_scene("yeoh", "plane-strain", copied_section.name, 4, quadrature=None)
    with pytest.raises(ValueError, match="material.formulation: 'plane-strain' cannot run element "
                                         "HB2n-12-copied .test-copied-section: a test's reason"):
        plan(scene_from_dict(d))
    assert np.isfinite(_tip(copied_section.name)["tip"]["uy"])        # plane stress still runs


def test_no_module_outside_a_kinematics_package_branches_on_its_name():
    """The solver, the checks, the studies and the continuum ask an element's kinematics for a
    property (its model, supports, formulations, section field, ...), never compare its name:
    an element's kinematics name compared (``spec.kinematics == ...``, ``family.name in ...``)
    or a property named for one kinematics (``spec.cable``) outside ``ancf/kinematics/<name>/``
    would be a branch a new kinematics must learn."""
    import re
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    names = "|".join(re.escape(n) for n in KINEMATICS)
    pattern = re.compile(rf"(\.kinematics|family\.name)\s*(==|!=|in\b|not in\b)|(?<=\w)\.({names})\b(?!\.|\s*import)")
    found = []
    for package in ("ancf", "studies", "reference_fem", "mechanics", "contract", "examples"):
        for path in sorted((root / package).rglob("*.py")):
            rel = path.relative_to(root).as_posix()
            if rel.startswith("ancf/kinematics/") and rel.split("/")[2] in KINEMATICS:
                continue
            found += [f"{rel}:{i}" for i, line in enumerate(path.read_text().splitlines(), 1)
                      if pattern.search(line.split("#")[0])]
    assert not found, found
