"""The record fingerprint: what a record depends on is the code its solver runs, with
comments and docstrings left out, and the packages that code uses, per continuum backend."""
import sys
import textwrap

import pytest

from studies.engine import fingerprint as fp
from studies.engine.solvers import SOLVERS, get_solver


@pytest.fixture
def probe(tmp_path, monkeypatch):
    """Two modules of a user's, outside the repository: ``fp_probe`` imports ``fp_dep``
    inside a function; ``write(name, text)`` rewrites one and forgets what was read."""
    monkeypatch.syspath_prepend(str(tmp_path))

    def write(name: str, text: str) -> dict:
        (tmp_path / f"{name}.py").write_text(textwrap.dedent(text))
        fp.clear_caches()
        return fp.fingerprint(("fp_probe",))

    write("fp_dep", "K = 2.0\n")
    yield write
    fp.clear_caches()
    for m in ("fp_probe", "fp_dep"):
        sys.modules.pop(m, None)


PROBE = '''
"""A module."""
import numpy as np


def f(x):
    """Twice x."""
    from fp_dep import K   # the factor
    return K * np.asarray(x)
'''


def test_comments_docstrings_and_wrapping_do_not_count_and_code_does(probe):
    base = probe("fp_probe", PROBE)
    assert probe("fp_probe", PROBE.replace('"""Twice x."""', '"""Twice x, as an array."""')
                 .replace("# the factor", "# K from the other module")) == base
    assert probe("fp_probe", PROBE.replace("return K * np.asarray(x)", "return (K\n            * np.asarray(x))")) == base
    assert probe("fp_probe", PROBE.replace("K * ", "K + "))["code"] != base["code"]


def test_a_module_imported_inside_a_function_counts(probe):
    base = probe("fp_probe", PROBE)
    assert probe("fp_dep", "K = 3.0\n")["code"] != base["code"]
    assert probe("fp_dep", "# a comment\nK = 2.0\n") == base


def test_the_packages_are_those_the_code_imports(probe):
    f = probe("fp_probe", PROBE)
    assert set(f["packages"]) == {"numpy", "python"}


def _modules(solver: str, scene: dict, options: dict | None = None, module: str | None = None) -> list[str]:
    return fp.modules(*get_solver(solver, module).entries(scene, options))


@pytest.mark.dolfinx
def test_each_backend_counts_its_own_code_and_packages():
    dolfinx, felupe = {"fem": {"backend": "dolfinx"}}, {"fem": {"backend": "felupe"}}
    md, mf = _modules("continuum", dolfinx), _modules("continuum", felupe)
    assert any(m.startswith("reference_fem.dolfinx_backend") for m in md)
    assert not any(m.startswith("reference_fem.felupe_backend") for m in md)
    assert any(m.startswith("reference_fem.felupe_backend") for m in mf)
    assert not any(m.startswith("reference_fem.dolfinx_backend") for m in mf)
    pd, pf = (SOLVERS["continuum"].fingerprint(s)["packages"] for s in (dolfinx, felupe))
    assert "fenics-dolfinx" in pd and "felupe" not in pd and "tensortrax" not in pd
    assert "felupe" in pf and "tensortrax" in pf and "fenics-dolfinx" not in pf
    # a study's own solver, registered by its module (imported here as a worker imports it)
    mms_d = _modules("mms", {"mms": {"code": "dolfinx"}}, module="studies.verification.manufactured")
    assert "reference_fem.dolfinx_backend.manufactured" in mms_d and "reference_fem.felupe_backend.manufactured" not in mms_d


def test_ancf_records_depend_on_no_continuum_code_and_no_report_code():
    for solver in ("ancf", "ancf-effects", "ancf-cold"):
        ms = _modules(solver, {})
        assert "ancf.simulation" in ms and "mechanics.laws.gent" in ms     # the laws' folder, found by name
        assert not any(m.startswith("reference_fem") for m in ms)
        # of the study engine, only the run function and the names it uses
        assert all(":" in m for m in ms if m.startswith("studies")), ms
        assert not any("report" in m for m in ms), ms
    pk = SOLVERS["ancf"].fingerprint({})["packages"]
    assert {"numpy", "numba", "scipy"} <= set(pk) and "fenics-dolfinx" not in pk


def test_no_record_depends_on_the_engine_that_keys_it():
    """Editing the fingerprint, the case or the catalog code recomputes nothing: no
    solver's fingerprint reaches them (a type in a signature runs nothing)."""
    engine = ("studies.engine.fingerprint", "studies.engine.case", "studies.engine.catalog", "studies.engine.report")
    for name in SOLVERS:
        for scene, options in (({}, {}), ({"fem": {"backend": "felupe"}}, {}), ({}, {"mpi_ranks": 2})):
            ms = _modules(name, scene, options)
            assert not [m for m in ms if m.split(":")[0] in engine], (name, options)


def test_no_record_depends_on_where_compiled_code_is_cached_or_on_the_command_lines():
    """The compiled-code cache's location (its own digest guards it), the console, the
    output writers and the warm-up cannot change a result: no solver's fingerprint reads
    them, so an edit there keeps every record."""
    for name in SOLVERS:
        for scene in ({}, {"fem": {"backend": "felupe"}}):
            ms = {m.split(":")[0] for m in _modules(name, scene)}
            assert not ms & set(fp.NOT_RESULTS), name
    assert "ancf.compiled_cache" in fp.NOT_RESULTS and "ancf.solvers.couple" in _modules("ancf", {})
