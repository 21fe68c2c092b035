import importlib.util
import json
from pathlib import Path
from typing import Callable

import numpy as np
import pytest

from ancf.checks.element import law_constants, paper_material
from contract import paper
from ancf.elements import ELEMENTS
from ancf.core.formulations import FORMULATIONS
from mechanics.laws import LAWS


material = paper_material   # the paper's constants of a law in a formulation
PAPER_LAWS = sorted(paper.materials())   # the laws the paper's tables have


def law_scene(law: str, formulation: str, *args, penalty: float = paper.PENALTY, **kw) -> dict:
    """The paper's cantilever scene in any registered law: the paper's constants for its
    three laws, the law's example constants (and the neo-Hookean density) otherwise."""
    s = paper.cantilever_scene("neo-hookean", formulation, *args, penalty=penalty, **kw)
    s["material"] = {"law": law, "formulation": formulation, **law_constants(law),
                     **({"penalty": penalty} if "penalty" in s["material"] else {})}
    s["name"] = s["name"].replace("neo-hookean", law)
    return s


@pytest.fixture
def rng():
    return np.random.default_rng(20211206)


ALL_ELEMENTS = sorted(ELEMENTS)
# the continuum-based elements (a cable, ElementSpec.kinematics = "cable", has no section
# coordinates: tests of the face clamp, r_y and the like are theirs; tests/test_cable.py is its)
CONTINUUM_ELEMENTS = sorted(n for n, e in ELEMENTS.items() if e.kinematics != "cable")


def contract_rule(element: str):
    """The rule contract tests run an element with: [3, 2] (cheap, the paper's), or the
    element's default where [3, 2] cannot resolve its pressure field or misses modes
    (HB2n-40p)."""
    return None if ELEMENTS[element].pressure else (3, 2)
ALL_LAWS = sorted(LAWS)
ALL_FORMULATIONS = sorted(FORMULATIONS)


# -- the two tiers -----------------------------------------------------------------------
# `make test` runs what is not marked slow; `make test-full` (which .ci/run runs too) runs
# the slow ones. A slow test guards a property that must keep a quick test in `make test`:
# it names that test, `@pytest.mark.slow(guard="test_name")` (a test of the same file, or
# "test_file.py::test_name"; a parametrized test's quick cases guard its slow ones by its
# own name). Collection fails on a slow test without a guard, or with one that is not a
# collected quick test.

def tiered(params, slow: Callable[..., bool], guard: str) -> list:
    """Parameter sets for parametrize, those for which ``slow(*values)`` holds marked slow
    with ``guard`` (the same test's quick cases, by its name)."""
    out = []
    for p in params:
        values = p if isinstance(p, tuple) else (p,)
        out.append(pytest.param(*values, marks=pytest.mark.slow(guard=guard)) if slow(*values) else p)
    return out


# the elements whose contract cases cost most (quartic sections, the sextic example)
HEAVY_ELEMENTS = ("HB2n-40p", "HB2n-60p", "HB2n-84p")
# the built-in elements free of volumetric and shear locking (their cards' locking sections;
# the stability-elements study runs the pendulum's hard cases with each)
LOCK_FREE = ("HB2n-20xyp", "HB2n-20xypm", "HB2n-40p", "HB2n-60p")


def _base(nodeid: str) -> str:
    return nodeid.split("[")[0]


def _guard_id(nodeid: str, guard: str) -> str:
    """The guard's node id: a bare test name is one of the slow test's own file."""
    want = guard if "::" in guard else f"{nodeid.split('::')[0]}::{guard}"
    return want if want.startswith("tests/") else f"tests/{want}"


@pytest.hookimpl(tryfirst=True)          # before -m deselects either tier
def pytest_collection_modifyitems(session, config, items):
    _route_skips(items)
    files = {i.nodeid.split("::")[0] for i in items}
    quick = {_base(i.nodeid) for i in items if i.get_closest_marker("slow") is None}
    bad = []
    for item in items:
        mark = item.get_closest_marker("slow")
        if mark is None:
            continue
        guard = mark.kwargs.get("guard")
        if not guard:
            bad.append(f"{item.nodeid}: marked slow without a guard (slow(guard=\"a quick test of the same property\"))")
            continue
        want = _guard_id(item.nodeid, guard)
        if want.split("::")[0] in files and _base(want) not in quick:
            bad.append(f"{item.nodeid}: its guard {guard!r} is not a quick test")
    if bad:
        raise pytest.UsageError("\n".join(bad))
    if config.getoption("--guards"):
        pairs = sorted({(_base(i.nodeid), _guard_id(i.nodeid, i.get_closest_marker("slow").kwargs["guard"]))
                        for i in items if i.get_closest_marker("slow") is not None})
        lines = [f"{slow}  <-  {guard}" for slow, guard in pairs]
        config.pluginmanager.get_plugin("terminalreporter").write_line(
            "the full tier's tests, each with the quick test that guards its property in make test:\n"
            + "\n".join(lines))
        config.hook.pytest_deselected(items=list(items))
        items[:] = []


def pytest_addoption(parser):
    parser.addoption("--guards", action="store_true",
                     help="list each slow test with the quick test that guards its property; run nothing")


# -- the routes: Debian's (everything) and a plain venv (docs/how-to/install-without-root.md) --
# A plain venv has no FEniCSx, PyPI's numpy, scipy and numba, and so none of the committed
# records' package versions: what needs them is skipped there, with the reason, never run
# and failed. `pytest -rs` lists them.
HAS_FENICSX = all(importlib.util.find_spec(m) is not None for m in ("dolfinx", "ufl"))
DEBIAN_NUMPY = Path(np.__file__).resolve().is_relative_to("/usr/lib/python3")
RECORDS = Path(__file__).resolve().parents[1] / "reports" / "data" / "table3.jsonl"


def _records_versions_differ() -> str | None:
    """Why the committed records cannot be reused here (their numpy, scipy, numba are not
    this interpreter's), or None."""
    import numba
    import scipy

    try:
        versions = json.loads(RECORDS.open().readline())["versions"]
    except (OSError, ValueError, KeyError):
        return "no committed records to compare with"
    here = {"numpy": np.__version__, "scipy": scipy.__version__, "numba": numba.__version__}
    differ = [f"{k} {versions.get(k)} there, {v} here" for k, v in here.items() if versions.get(k) != v]
    return ("the committed records were made with other packages (" + "; ".join(differ) + ")") if differ else None


def _names_dolfinx(item) -> bool:
    """A parametrized case that names the DOLFINx backend among its parameters."""
    spec = getattr(item, "callspec", None)
    return spec is not None and any(v == "dolfinx" for v in spec.params.values() if isinstance(v, str))


def _route_skips(items) -> None:
    no_fenicsx = pytest.mark.skip(reason="needs the FEniCSx stack (DOLFINx, UFL), not installed here: the "
                                         "Debian route or conda-forge (docs/how-to/install-without-root.md)")
    not_debian = pytest.mark.skip(reason="checks the Debian route's set-up; this interpreter's numpy is not Debian's")
    records_why = None
    for item in items:
        if not HAS_FENICSX and ("dolfinx" in item.keywords or _names_dolfinx(item)):
            item.add_marker(no_fenicsx)
        if not DEBIAN_NUMPY and "debian" in item.keywords:
            item.add_marker(not_debian)
        if "records" in item.keywords:
            records_why = records_why or _records_versions_differ() or ""
            if records_why:
                item.add_marker(pytest.mark.skip(reason=records_why))
