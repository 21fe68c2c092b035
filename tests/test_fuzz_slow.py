"""The fuzz of tests/test_hostile.py at a raised budget (``make test-slow``), and the three
command lines fed random files and arguments: only a one-line error (exit 2), a status
record, or argparse's usage (SystemExit 2) may come out; never a traceback.

Derandomized like the quick fuzz: the same examples on every run, so a failure here is
reproducible; the quick versions in tests/test_hostile.py guard the same properties in
``make test`` with fewer examples.
"""
from __future__ import annotations

import json
import tomllib

import pytest
from hypothesis import given
from hypothesis import strategies as st

from . import test_hostile as quick
from .test_hostile import KEYS, fuzz, small_scenes, values



@pytest.mark.slow(guard="test_hostile.py::test_fuzz_one_wrong_value")
@fuzz(4000)
@given(st.sampled_from([(t, k) for t, ks in KEYS.items() for k in ks]), values)
def test_fuzz_one_wrong_value_many(place, value):
    quick.test_fuzz_one_wrong_value.hypothesis.inner_test(place, value)


@fuzz(2000)
@given(st.dictionaries(st.sampled_from(KEYS[""]),
                       st.one_of(values, st.dictionaries(st.sampled_from(sum(KEYS.values(), [])), values,
                                                         max_size=8)), max_size=9))
@pytest.mark.slow(guard="test_hostile.py::test_fuzz_random_documents")
def test_fuzz_random_documents_many(d):
    quick._check_both(d)


# TOML text made of a real scene's lines with some of them replaced, duplicated or cut: closer
# to a user's mistakes than random bytes (those almost never parse)
_LINES = quick.SCENE.read_text().splitlines()
_snippets = st.sampled_from(["[", "]", "{", "}", "= ", "[[analysis]]", "[material]", "x = 1", "law = 3",
                             "elements = -1", "dt = 1e999", "name = [" * 50, "= \"", "inf", "nan",
                             "t_end = 1e-300", "kind = \"dynamic\"", "\x00", "\ufeff", "a.b.c = 1"])
mutated_scenes = st.lists(st.one_of(st.sampled_from(_LINES), _snippets, st.text(max_size=20)),
                          min_size=1, max_size=len(_LINES) + 5)


@pytest.mark.slow(guard="test_hostile.py::test_fuzz_random_documents")
@fuzz(1500)
@given(mutated_scenes)
def test_fuzz_mutated_scene_text(lines):
    text = "\n".join(lines)
    try:
        quick._check_both(tomllib.loads(text))
    except tomllib.TOMLDecodeError:
        pass


@pytest.mark.slow(guard="test_hostile.py::test_fuzz_random_bytes")
@fuzz(2000)
@given(st.binary(max_size=2000))
def test_fuzz_random_bytes_many(tmp_path_factory, data):
    quick.test_fuzz_random_bytes.hypothesis.inner_test(tmp_path_factory, data)


@pytest.mark.slow(guard="test_hostile.py::test_fuzz_small_random_runs_end_with_a_status")
@fuzz(150)
@given(small_scenes)
def test_fuzz_small_random_runs_many(p):
    quick.test_fuzz_small_random_runs_end_with_a_status.hypothesis.inner_test(p)


# -- the command lines -------------------------------------------------------------------------
def _main(module: str):
    if module == "ancf":
        from ancf.cli import main
    elif module == "reference_fem":
        from reference_fem.cli import main
    else:
        from studies.cli import main
    return main


def _call(module: str, argv: list[str], capsys) -> int:
    try:
        code = _main(module)(argv)
    except SystemExit as e:          # argparse: usage and one error line, exit 2
        code = e.code
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return code


tokens = st.sampled_from(["run", "list", "report", "diff", "card", "gold", "continuum", "converge", "elements", "laws",
                          "--json", "--vtk", "--import", "--catalog", "--out", "--levels", "--tiny", "--quiet",
                          "-1", "0", "nan", "", "/", "/proc/x", "/dev/null", "FILE", "DIR", "os", "no.such.module",
                          "examples.cubic_slope", "--workers", "--timeout", "--rtol"])


@fuzz(400)
@given(st.sampled_from(["ancf", "reference_fem", "studies"]), st.lists(st.one_of(tokens, st.text(max_size=8)),
                                                                        max_size=6),
       st.binary(max_size=300))
@pytest.mark.slow(guard="test_hostile.py::test_files_that_are_not_scenes_are_one_line")
def test_fuzz_command_lines(tmp_path_factory, capsys, module, argv, content):
    """Random arguments and a random file ("FILE") and folder ("DIR") where a path goes.
    Commands that would start real work on a valid input (a study run, a gold refresh, a
    pendulum or a mesh study) are left out: their inputs are the catalog and the scene,
    fuzzed above."""
    tmp = tmp_path_factory.mktemp("cli")
    (tmp / "f.toml").write_bytes(content)
    argv = [str(tmp / "f.toml") if a == "FILE" else str(tmp) if a == "DIR" else a for a in argv]
    if module == "studies" and (argv[:1] in (["run"], ["gold"], ["card"]) or
                                argv[:2] in (["continuum", "gold"], ["continuum", "pendulum"])) or \
            module == "reference_fem" and argv[:1] == ["converge"]:
        return
    if module == "studies" and argv[:1] == ["report"] and "--out" not in argv:
        return                          # would rebuild reports/ from its records
    code = _call(module, argv, capsys)
    assert code in (0, 1, 2), (module, argv, code)


@fuzz(300)
@given(st.lists(st.one_of(st.binary(max_size=80).map(lambda b: b.decode("latin-1")),
                          st.builds(json.dumps, st.dictionaries(st.sampled_from(["case_id", "status", "tip", "case"]),
                                                                values, max_size=4))), max_size=6))
@pytest.mark.slow(guard="test_hostile.py::test_studies_diff_of_garbage_records_is_one_line_or_a_table")
def test_fuzz_studies_diff_of_garbage_records(tmp_path_factory, capsys, lines):
    """``studies diff OLD NEW`` on record files with garbage lines."""
    old, new = tmp_path_factory.mktemp("old"), tmp_path_factory.mktemp("new")
    for d in (old, new):
        (d / "data").mkdir()
        (d / "data" / "table3.jsonl").write_text("\n".join(lines))
    assert _call("studies", ["diff", str(old), str(new)], capsys) in (0, 1, 2)
