"""The registries are the only lists: an element registered once joins every study, card
and diagram its tags admit, and none that its tags keep out.

The element here is a copy of HB2n-12 under another name, registered in this process by
this module, which then stands where ``studies run --import`` puts a user's module. Each study's declared grid, and (full tier) the
cases it expands into, are searched for its name; the studies that reproduce the
paper take their elements by the tag "paper" and must not take it.
"""
from __future__ import annotations

import dataclasses

import pytest

from ancf.elements import ELEMENTS, TAGS, get_element, register_element, select

NAME = "HB2n-12-registered"
# studies that take every element running their formulations (the copy runs all three)
TAKING = {"accuracy-cost", "benchmarks", "dynamic-benchmarks", "figure2", "figure4", "formulation",
          "hard-loads", "pendulum-hinge", "stability-elements"}
# studies that take the paper's four (their tag), or no element of the registry
NOT_TAKING = {"accuracy-cost-rules", "table3", "sensitivity"}


def _names(value) -> set[str]:
    """Every string inside a scene (the element is one of them)."""
    if isinstance(value, dict):
        return set().union(*map(_names, value.values())) if value else set()
    if isinstance(value, (list, tuple)):
        return set().union(*map(_names, value)) if value else set()
    return {value} if isinstance(value, str) else set()


@pytest.fixture
def copied():
    from studies.engine import catalog

    spec = register_element(dataclasses.replace(get_element("HB2n-12"), name=NAME, tags=()))
    catalog.IMPORTED.append(ELEMENTS.origin[NAME])       # as `studies run --import` does
    try:
        yield spec
    finally:
        catalog.IMPORTED.remove(ELEMENTS.origin[NAME])
        del ELEMENTS[NAME]


def test_one_registration_puts_an_element_in_every_study_grid_its_tags_admit(copied):
    from studies.engine.catalog import load_catalog

    appears = {name for name, study in load_catalog().items() if NAME in _names(study.grid)}
    print("the registered element is in the grids of:", sorted(appears))
    assert TAKING <= appears, f"missing from {sorted(TAKING - appears)}"
    assert not appears & NOT_TAKING, f"in the paper's studies {sorted(appears & NOT_TAKING)}"


@pytest.mark.slow(guard="test_one_registration_puts_an_element_in_every_study_grid_its_tags_admit")
def test_and_in_their_cases(copied):
    """The same, read from the cases each study expands its grid into (5 s: full tier)."""
    from studies.engine.catalog import load_catalog

    appears = {name for name, study in load_catalog().items()
               if any(NAME in _names(case.scene) for case in study.cases())}
    print("the registered element appears in the cases of:", sorted(appears))
    assert TAKING <= appears, f"missing from {sorted(TAKING - appears)}"
    assert not appears & NOT_TAKING, f"in the paper's studies {sorted(appears & NOT_TAKING)}"


def test_an_element_a_card_imported_stays_out_of_the_studies():
    """A module imported for its cards (``studies card X --import M``, which rebuilds the
    reports afterwards) does not put its element into the studies' grids."""
    from studies.engine.catalog import load_catalog

    register_element(dataclasses.replace(get_element("HB2n-12"), name=NAME, tags=()))
    try:
        assert NAME in select()                  # registered: `studies card all` takes it
        assert not any(NAME in _names(s.grid) for s in load_catalog().values())
    finally:
        del ELEMENTS[NAME]


def test_its_cases_carry_the_module_a_worker_imports(copied):
    from contract import paper
    from studies.engine.case import make_case

    case = make_case("s", "ancf", paper.cantilever_scene("yeoh", "plane-stress", NAME, 4))
    assert case.options["imports"] == [ELEMENTS.origin[NAME]]


def test_the_card_and_the_peers_diagram_take_it_too(copied):
    from studies.peers.precision_grid import elements

    assert NAME in select()                    # studies card all
    assert NAME not in select("paper")         # studies card paper
    assert NAME in elements()                  # the work-precision diagram's default


def test_tags_keep_it_out_where_they_say():
    register_element(dataclasses.replace(get_element("HB2n-12"), name=NAME, tags=("locking",)))
    try:
        from studies.peers.precision_grid import elements

        assert NAME not in elements() and NAME not in select(without=["locking"])
        assert NAME in select("locking")
    finally:
        del ELEMENTS[NAME]


def test_an_unknown_tag_is_refused_with_the_allowed_ones():
    with pytest.raises(ValueError, match="unknown tags.*costly"):
        dataclasses.replace(get_element("HB2n-12"), name=NAME, tags=("papr",))
    with pytest.raises(ValueError, match="unknown element tag 'papr'"):
        select("papr")
    assert set(TAGS) == {"paper", "locking", "costly"}


def test_a_grid_selector_with_an_unknown_key_names_it():
    from studies.engine.catalog import registered

    with pytest.raises(ValueError, match=r"table3\.elements\.registered: unknown keys \['tag'\]"):
        registered({"elements": {"registered": {"tag": "paper"}}}, "table3")
    assert registered({"e": {"registered": {"tagged": "paper"}}}, "s") == {"e": select("paper")}


def test_a_study_leaves_an_element_out_only_with_its_reason():
    from studies.engine.catalog import registered

    got = registered({"registered": {"tagged": "paper", "except": {"HB3n-12": "not converged here"}}}, "s")
    assert got == [n for n in select("paper") if n != "HB3n-12"]
    for bad in ({"HB3n-12": ""}, {"HBx": "why"}, ["HB3n-12"]):
        with pytest.raises(ValueError, match=r"s\.registered\.except: \{element: why\}"):
            registered({"registered": {"except": bad}}, "s")
