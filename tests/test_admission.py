"""No traceback for any registered element: every element (the paper's, the pressure and
assumed-strain elements, the cable, and the examples' elements, registered from a user's
module) x formulation x law x support x load x analysis (static, or each integrator with
each Newton variant) goes through the scene check and one step, and ends in a SceneError
naming a field or in a record that passes the record schema's check
(:func:`contract.record_schema.problems`: a status, a reason where it failed, a finite tip
where it converged). The one rule of which integrators an element
refuses (:func:`ancf.admission.refused_integrators`) is what the check, the models, the
warm-up and the stability study ask.

The quick tier runs a covering of those seven dimensions in which every pair of values
meets (66 scenes: 46 stepped, 39 of them converged and 7 failed with their reason, 20
refused by name; stated budget: 5 s on one worker of this 2-core machine after ``ancf
warm``, measured by ``pytest --durations``: 2 to 3.5 s, most of it in the mechanisms that
fail); the full tier runs their whole product per element.
"""
from __future__ import annotations

import copy
import itertools
import random

import pytest

from ancf.admission import check, refused_integrators
from ancf.elements import BUILTIN, ELEMENTS, get_element
from ancf.core.formulations import FORMULATIONS
from ancf.solvers.integrators import INTEGRATORS
from ancf.simulation import run_scene
from contract import paper
from contract.errors import SceneError
from contract.record import sanitize
from contract.record_schema import problems
from contract.scene import NEWTON, SUPPORTS, keys_of, scene_from_dict
from mechanics.laws import LAWS

SUPPORT_VARIANTS = [("clamp", "face"), ("clamp", "all"), *((s, None) for s in SUPPORTS if s != "clamp")]
LOADS = tuple(k.name for k in keys_of("loads"))    # the scene's load keys
LOAD_VALUES = {"gravity": [0.0, -9.81], "tip_force": [0.0, -1e-3], "end_moment": 1e-5}   # N, N m
ANALYSES = ("static", *INTEGRATORS)
# a user's modules, each registering an element when imported (imported by the tests, not
# at collection: other files' parametrisations see the built-in elements alone)
USER_MODULES = ("examples.transversely_cubic", "examples.cubic_slope", "examples.sextic_section")


def user_elements() -> list[str]:
    """The names the user's modules register (importing them)."""
    import importlib

    for m in USER_MODULES:
        importlib.import_module(m)
    return [n for n in ELEMENTS if n not in BUILTIN]


def dimensions() -> dict[str, list]:
    """Each dimension's values, from the registries (nothing typed twice)."""
    user_elements()
    return {"element": list(ELEMENTS), "formulation": list(FORMULATIONS), "law": list(LAWS),
            "support": SUPPORT_VARIANTS, "load": list(LOADS), "analysis": list(ANALYSES), "newton": list(NEWTON)}


def scene_dict(element, formulation, law, support, load, analysis, newton) -> dict:
    """A two-element scene of the paper's cantilever (static: one load step) or pendulum
    (dynamic: one step of 1 ms), with the named law's constants, support and load."""
    if analysis == "static":
        d = paper.cantilever_scene("yeoh", formulation, element, 2, quadrature=None)
        # one load step of at most 3 iterations: a mechanism (a pin or a hinge under a static
        # load) still goes through the cuts and the descent to its failure, in a fraction
        # of the time 25 iterations take there
        d["analysis"].update(load_steps=1, max_iterations=3)
    else:
        d = paper.pendulum_scene("yeoh", formulation, 1e-3, element, 2, t_end=1e-3, integrator=analysis,
                                 newton=newton)
    d = copy.deepcopy(d)
    d["name"] = f"admission-{element}"
    kept = {k: d["material"][k] for k in ("density", "penalty", "formulation") if k in d["material"]}
    d["material"] = {**kept, "law": law, **_constants(law)}
    left, clamp = support
    d["supports"] = {"left": left, **({"clamp": clamp} if clamp else {})}
    d["loads"] = {load: LOAD_VALUES[load]}        # a new load key fails here until it has a value
    return d


def _constants(law: str) -> dict:
    """The law's constants: the paper's for its three laws, else the law's example."""
    try:
        m = paper.cantilever_scene(law, "plane-stress", "HB2n-12", 2)["material"]
    except (KeyError, ValueError):
        return dict(LAWS[law].example)
    return {k: m[k] for k in LAWS[law].constants}


def run_one(values: tuple) -> str:
    """'refused: <field>' or the record's status; anything else raises (the test fails)."""
    d = scene_dict(*values)
    try:
        scene = scene_from_dict(d)
        before = copy.deepcopy(scene)
        assert check(scene) is scene and scene == before, "a check must return its scene untouched"
        rec, _ = run_scene(scene)
    except SceneError as e:
        field = str(e).split(":")[0]
        assert "." in field or field in ("ancf", "material", "analysis", "loads", "supports", "beam"), str(e)
        return f"refused: {field}"
    assert not problems(sanitize(rec)), f"{values}: {problems(sanitize(rec))}"   # a status, a reason if failed
    return rec["status"]


def covering(dims: dict[str, list], seed: int = 0) -> list[tuple]:
    """Rows in which every pair of values of two dimensions meets (greedy, seeded: the
    same rows every run)."""
    names = list(dims)
    todo = {(a, va, b, vb) for a, b in itertools.combinations(range(len(names)), 2)
            for va in range(len(dims[names[a]])) for vb in range(len(dims[names[b]]))}
    rng, rows = random.Random(seed), []
    while todo:
        a, va, b, vb = min(todo)
        best, gain = None, -1
        for _ in range(40):
            row = [rng.randrange(len(dims[n])) for n in names]
            row[a], row[b] = va, vb
            g = sum((i, row[i], j, row[j]) in todo for i, j in itertools.combinations(range(len(names)), 2))
            if g > gain:
                best, gain = row, g
        todo -= {(i, best[i], j, best[j]) for i, j in itertools.combinations(range(len(names)), 2)}
        rows.append(tuple(dims[n][k] for n, k in zip(names, best)))
    return rows


def test_every_pair_of_values_meets_in_a_scene_that_ends_without_a_traceback():
    dims = dimensions()
    rows = covering(dims)
    outcomes = {row: run_one(row) for row in rows}
    # the covering holds every registered element, the examples' among them
    assert {r[0] for r in rows} == set(ELEMENTS) and set(ELEMENTS) - set(BUILTIN)
    # and the rule is applied where it bites: an element that refuses an integrator is
    # refused by name for it, never run into a traceback
    for row, outcome in outcomes.items():
        element, analysis = get_element(row[0]), row[5]
        if analysis in refused_integrators(element) and not outcome.startswith("refused"):
            pytest.fail(f"{row}: {outcome}, not refused")


@pytest.mark.parametrize("element", ["HB2n-20xypm", "HC2n-8"])
def test_a_refused_integrator_is_named_with_the_allowed_ones(element):
    """The traceback that was: the discrete gradient on an assumed strain, or a cable."""
    d = scene_dict(element, "plane-stress", "yeoh", ("pin", None), "gravity", "discrete-gradient", "chord")
    with pytest.raises(SceneError) as e:
        check(scene_from_dict(d))
    msg = str(e.value)
    assert msg.startswith("analysis.integrator: 'discrete-gradient' cannot run element")
    assert "'generalized-alpha'" in msg and "'newmark'" in msg and "hht" not in msg


def test_the_rule_is_the_one_the_models_and_the_stability_study_ask():
    from ancf.kinematics.model import refuse_discrete_gradient
    from studies.verification.dynamics_stability import STUDY, offered

    user_elements()
    for name, el in ELEMENTS.items():
        refused = "discrete-gradient" in refused_integrators(el)
        assert offered(STUDY["grid"], {"element": name}, "discrete-gradient") is not refused
        assert offered(STUDY["grid"], {"element": name}, "arnold-bruls")

        class Model:
            class mesh:
                element = el
        if refused:
            with pytest.raises(ValueError, match=name):
                refuse_discrete_gradient(Model)
        else:
            refuse_discrete_gradient(Model)


@pytest.mark.slow(guard="test_every_pair_of_values_meets_in_a_scene_that_ends_without_a_traceback")
@pytest.mark.parametrize("element", [*sorted(BUILTIN), "a user's"])
def test_the_whole_product_ends_without_a_traceback(element):
    """Every combination, the Newton variants with the dynamic analyses only (a static run
    has one Newton)."""
    for row in product(user_elements() if element == "a user's" else [element]):
        run_one(row)


def product(elements: list[str]) -> list[tuple]:
    dims = dimensions()
    dims["element"] = elements
    rows = []
    for row in itertools.product(*dims.values()):
        if row[5] == "static" and row[6] != NEWTON[0]:
            continue
        rows.append(row)
    return rows
