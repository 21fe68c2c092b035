"""Hostile input and hard loads: never a hang, never a traceback, never a file out of place.

Every case of the issue has a test here: the loops that hung (the energy descent on an
indefinite diagonal, a one-point rule, a huge load, 5e11 time steps, 10^7 cells), the
inputs that raised tracebacks (a list or table where a name is expected, a file that is
not UTF-8 text or not a file, output paths that cannot be written, Ctrl-C), the answers
that were not answers (a tolerance of 1e10, an unloaded scene, energy_limit = inf, dt
above t_end) and the files written in the wrong place (a scene name with separators).
A fuzz test (hypothesis, derandomized: the same examples every run) throws random TOML
documents, random values and random bytes at both solvers' loaders and runs small random
scenes: only a SceneError or a record with a status comes out, within a time bound.
"""
from __future__ import annotations

import copy
import json
import math
import os
import signal
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ancf.build import capacity as ancf_capacity
from ancf.build import check as ancf_check
from ancf.cli import main as ancf_main
from ancf.simulation import run_scene
from contract import paper
from contract.console import safe_name
from contract.errors import SceneError
from contract.record import sanitize
from contract.scene import load_scene, scene_from_dict

from .conftest import tiered

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "scenes" / "cantilever-yeoh.toml"
BASE = tomllib.loads(SCENE.read_text())


def fuzz(examples: int):
    return settings(derandomize=True, deadline=None, suppress_health_check=list(HealthCheck), database=None,
                    max_examples=examples)


def scene_with(**tables) -> dict:
    d = copy.deepcopy(BASE)
    for table, values in tables.items():
        if values is None:
            d.pop(table, None)
        else:
            d[table] = {**d.get(table, {}), **values}
    return d


def run(d: dict) -> dict:
    rec, _ = run_scene(scene_from_dict(d))
    return sanitize(rec)


# -- the hangs -------------------------------------------------------------------------------
def test_a_20_newton_tip_force_converges_where_the_descent_looped():
    """scenes/cantilever-yeoh.toml with a 20 N tip force instead of gravity used to loop in
    the energy descent (no shift made a matrix with a non-positive diagonal factorable).
    Now it converges from the default 10 load steps to the answer of 200 load steps."""
    d = scene_with(loads=None)
    d["loads"] = {"tip_force": [0.0, -20.0]}
    d["analysis"]["wall_time"] = 60.0          # a hang would end as "wall time", and fail here
    rec = run(d)
    assert rec["status"] == "converged", rec["reason"]
    d["analysis"]["load_steps"] = 200
    ref = run(d)
    assert rec["tip"]["ux"] == pytest.approx(ref["tip"]["ux"], rel=1e-6)
    assert rec["tip"]["uy"] == pytest.approx(ref["tip"]["uy"], rel=1e-6)


@pytest.mark.dolfinx
def test_the_20_newton_tip_force_agrees_with_the_continuum():
    """64 x HB2n-12 against the continuum's 64 x 4 Q2 (plane stress, the same scene):
    measured -155.65 / -191.34 mm against -155.60 / -191.38 mm; tolerance 0.2 % (the
    continuum's own mesh error at 64 x 4 is about 0.07 %, the ANCF mesh's similar)."""
    from reference_fem.simulation import run_scene as run_fem

    d = scene_with(loads=None, ancf={"elements": 64})
    d["loads"] = {"tip_force": [0.0, -20.0]}
    a, c = run(d), sanitize(run_fem(scene_from_dict(d)))
    assert a["status"] == c["status"] == "converged"
    err = math.hypot(a["tip"]["ux"] - c["tip"]["ux"], a["tip"]["uy"] - c["tip"]["uy"])
    assert err < 2e-3 * math.hypot(c["tip"]["ux"], c["tip"]["uy"]), (a["tip"], c["tip"])


@pytest.mark.parametrize("change", [
    {"ancf": {"quadrature": [1, 1]}},                       # zero-energy modes everywhere
    {"loads": {"gravity": [0.0, -9.81e4]}},                 # 10^4 g
])
def test_loads_that_looped_end_with_a_status_in_bounded_time(change):
    d = scene_with(**change)
    d["analysis"]["wall_time"] = 120.0         # the bound: a loop would end as "wall time"
    rec = run(d)
    assert rec["status"] in ("converged", "failed")
    assert rec["status"] == "converged" or rec["reason"]
    assert not str(rec["reason"]).startswith("wall time"), rec["reason"]


@pytest.mark.dolfinx
def test_a_failed_continuum_factorisation_does_not_poison_the_next_increment():
    """Neo-Hookean plane stress, 200 N at the tip, 64 x 4 Q2: the first increment's LU
    fails (PETSc reason -11) and PETSc kept the failed factorisation, so every smaller
    increment failed at once and the run ended "load increment below 1e-06 at t = 0".
    With a fresh LU after a failure it converges (ANCF 32 x HB2n-12: -157.99 / -496.30 mm)."""
    from reference_fem.simulation import run_scene as run_fem

    d = paper.cantilever_scene("neo-hookean", "plane-stress", name="nh-200N", fem={
        "cells_length": 64, "cells_height": 4, "cell": "quadrilateral", "degree": 2, "quadrature_degree": 4})
    d["loads"] = {"tip_force": [0.0, -200.0]}
    rec = sanitize(run_fem(scene_from_dict(d)))
    assert rec["status"] == "converged", rec["reason"]
    assert rec["rejected_steps"] > 0                 # the failure happened, and was recovered from
    assert rec["tip"]["uy"] == pytest.approx(-0.4963, rel=5e-3)


def test_steps_beyond_the_bound_are_refused_before_the_run():
    d = scene_with(analysis=None)
    d["supports"] = {"left": "pin"}
    d["analysis"] = {"kind": "dynamic", "t_end": 0.5, "dt": 1e-12}
    with pytest.raises(SceneError, match=r"analysis\.dt: t_end / dt = 5e\+11 steps exceeds analysis\.max_steps"):
        scene_from_dict(d)
    d["analysis"].update(t_end=0.02, dt=1e-3, max_steps=20, tolerance=1e-12)  # the controller needs more
    rec = run(d)
    assert rec["status"] == "failed" and rec["reason"].startswith("step limit: 20 accepted steps"), rec["reason"]


def test_a_wall_time_ends_a_run_with_a_reason():
    d = scene_with(ancf={"elements": 64}, analysis={"wall_time": 1e-3})
    rec = run(d)
    assert rec["status"] == "failed" and "wall time" in rec["reason"]


def test_ten_million_elements_are_refused_with_the_memory_they_would_need(capsys):
    d = scene_with(ancf={"elements": 10 ** 7})
    with pytest.raises(SceneError, match=r"ancf\.elements: too large for this machine: ancf would need about "
                                         r"[0-9.]+ GiB for 6e\+07 unknowns"):
        ancf_capacity(scene_from_dict(d))


def test_an_element_its_nodal_coordinates_cannot_determine_is_a_scene_error():
    """A beam 67 km high for 0.16 m of length (the full tier's fuzz found it): HB2n-12's
    nodal matrix is singular in floating point at l_e / h = 1.5e-7; the check names the
    field, it does not end in the element's ValueError (with the scene's own rule or the
    default, run or rank test alike)."""
    for ancf in ({}, {"quadrature": None}):
        d = scene_with(beam={"height": 67230.0}, ancf=ancf)
        d["ancf"] = {k: v for k, v in d["ancf"].items() if v is not None}
        with pytest.raises(SceneError, match=r"beam\.height: an element of l_e / h = 1\.49e-07 .* singular for HB2n-12"):
            ancf_capacity(scene_from_dict(d))
    with pytest.raises(SceneError, match=r"beam\.height"):
        run(scene_with(beam={"height": 67230.0}))


def test_a_large_run_is_warned_about():
    from contract.capacity import Estimate, check_capacity
    w = check_capacity(Estimate(2 * 10 ** 6, 1e9, 2 * 10 ** 6, "x"), "ancf", available=1.5e9)
    assert any("1e+06" in x or "2e+06 unknowns" in x for x in w) and any("time steps" in x for x in w)
    assert any("available" in x for x in w)


@pytest.mark.parametrize("fem, field", [
    ({"cells_length": 10 ** 7}, r"fem\.cells_length / cells_height / degree: too large"),
    ({"degree": 20}, r"fem\.degree: must be an integer in \[1, 8\]"),
])
def test_continuum_sizes_that_ran_until_killed_are_refused(fem, field):
    from reference_fem.simulation import capacity, check
    scene = scene_from_dict(scene_with(fem=fem))
    with pytest.raises(SceneError, match=field):
        capacity(scene, check(scene))


# -- tracebacks where one line is promised -------------------------------------------------------
@pytest.mark.parametrize("table, key, value", [
    ("material", "law", ["yeoh"]), ("ancf", "element", {"name": "HB2n-12"}),
    ("material", "formulation", 3), ("analysis", "integrator", ["newmark"]), ("supports", "left", ["clamp"]),
    ("analysis", "kind", {"static": True}), ("fem", "cell", ["triangle"]), ("fem", "model", {"a": 1}),
])
def test_a_list_or_table_where_a_name_belongs_is_one_scene_error(table, key, value):
    from reference_fem.simulation import check as fem_check
    d = scene_with(**{table: {key: value}})
    if key == "integrator":
        d["analysis"] = {"kind": "dynamic", "t_end": 0.1, "dt": 1e-2, "integrator": value}
    with pytest.raises(SceneError, match=f"{table}.{key}"):
        s = scene_from_dict(d)
        ancf_check(s)
        fem_check(s)


@pytest.mark.parametrize("content, message", [
    (b'name = "caf\xe9"\n', "not UTF-8 text"),
    (bytes(range(256)) * 3, "not UTF-8 text"),
    (b"\x00\x01 = [[[", "not valid TOML"),
    (b"name = 5\n", "scene: missing key(s)"),
])
def test_files_that_are_not_scenes_are_one_line(tmp_path, capsys, content, message):
    f = tmp_path / "bad.toml"
    f.write_bytes(content)
    assert ancf_main(["run", str(f)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0] and "Traceback" not in err[0]


@pytest.mark.parametrize("text", [
    "name = " + "[" * 5000 + "]" * 5000,                   # arrays in arrays: tomllib recurses
    "name = " + "{a = " * 5000 + "1" + "}" * 5000,           # inline tables in inline tables
    "[" + ".".join(["a"] * 5000) + "]\nx = 1",              # a table header 5000 keys deep
    "name = " + "[" * 40 + "]" * 40,                         # parses, but deeper than a scene goes
])
@pytest.mark.parametrize("module", ["ancf", "reference_fem"])
def test_a_scene_nested_thousands_deep_is_one_line(tmp_path, capsys, text, module):
    f = tmp_path / "deep.toml"
    f.write_text(text + "\n")
    main = ancf_main if module == "ancf" else __import__("reference_fem.cli", fromlist=["main"]).main
    assert main(["run", str(f)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "at most 32 levels" in err[0] and "Traceback" not in err[0]


def test_a_deep_value_given_as_a_dict_is_refused_before_it_is_walked():
    deep: list = []
    for _ in range(100_000):     # far beyond Python's recursion limit
        deep = [deep]
    d = scene_with(analysis={"output_times": deep})
    with pytest.raises(SceneError, match=r"analysis\.output_times\[0\]\[0\].*more than 32 levels"):
        scene_from_dict(d)
    scene_from_dict(scene_with(analysis={"load_steps": 3}))   # a real scene (3 levels) passes


def test_a_folder_given_as_the_scene(tmp_path, capsys):
    assert ancf_main(["run", str(tmp_path)]) == 2
    assert "is a directory, not a scene file" in capsys.readouterr().err


@pytest.mark.parametrize("option, target, message", [
    ("--json", "{tmp}", "is a folder; give a file name"),
    ("--json", "{file}/x.json", "is a file, not a folder"),
    ("--json", "/proc/harness-test.json", "cannot write in /proc"),
    ("--vtk", "{file}", "is a file; give a folder"),
    ("--vtk", "/proc/harness-test", "cannot write in /proc/harness-test"),
])
def test_output_paths_are_checked_before_the_solve(tmp_path, capsys, monkeypatch, option, target, message):
    """Before the solve (the solver is replaced by one that refuses), no stray file left."""
    blocker = tmp_path / "a-file"
    blocker.write_text("x")
    scene = tmp_path / "long.toml"
    scene.write_text(SCENE.read_text().replace("elements = 16", "elements = 2000"))
    import ancf.simulation

    def refuse(*a, **k):
        raise AssertionError("the solve started before the output path was checked")
    monkeypatch.setattr(ancf.simulation, "run_scene", refuse)
    code = ancf_main(["run", str(scene), option, target.format(tmp=tmp_path, file=blocker)])
    assert code == 2
    assert message in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a-file", "long.toml"]


def _maps(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/maps").read_text()
    except OSError:
        return ""


@pytest.mark.parametrize("module", tiered(["ancf", "reference_fem"], lambda m: m == "reference_fem", "test_ctrl_c_is_one_line_and_exit_130"))
def test_ctrl_c_is_one_line_and_exit_130(tmp_path, module):
    # 1000 s of pendulum: about 45 s of compiled solve, so the interrupt lands mid-run
    # (100 s finished in 5.5 s, racing the signal, once the step loop was compiled).
    scene = tmp_path / "long.toml"
    d = SCENE.read_text().replace('kind = "static"', 'kind = "dynamic"\nt_end = 1000.0\ndt = 1e-3') \
        .replace("load_steps = 10     # initial number of increments; stepping stays adaptive", "") \
        .replace('left = "clamp"      # "clamp" | "pin"\nclamp = "face"      # "face" | "all"', 'left = "pin"')
    scene.write_text(d)
    # the child gets SIGINT's default disposition: under a shell's background job (`make
    # test &`) SIGINT is ignored, Python then installs no KeyboardInterrupt handler, and
    # the run would finish (exit 0) whatever the harness does
    p = subprocess.Popen([sys.executable, "-m", module, "run", str(scene), "--quiet"], cwd=ROOT,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    # the solver's heavy library loaded (numba's llvmlite; dolfinx: 1 to 15 s to import
    # here), then a few seconds into the run (it lasts about 45 s)
    library = "llvmlite" if module == "ancf" else "dolfinx"
    t0 = time.monotonic()
    while time.monotonic() - t0 < 60 and p.poll() is None and library not in _maps(p.pid):
        time.sleep(0.1)
    time.sleep(3 if module == "ancf" else 4)
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=60)
    assert p.returncode == 130, err[-2000:]
    assert err.strip().splitlines()[-1] == f"{module}: interrupted" and "Traceback" not in err


# -- wrong answers presented as answers ---------------------------------------------------------
@pytest.mark.parametrize("key, value, message", [
    ("newton_rtol", 1e10, r"analysis\.newton_rtol: must lie in \[1e-15, 0\.001\]"),
    ("newton_rtol", 1e-30, r"analysis\.newton_rtol: must lie in"),
    ("max_iterations", 10 ** 9, r"analysis\.max_iterations: must lie in \[1, 1000\]"),
    ("load_steps", 10 ** 9, r"analysis\.load_steps: must lie in"),
])
def test_tolerances_and_counts_have_sane_ranges(key, value, message):
    with pytest.raises(SceneError, match=message):
        scene_from_dict(scene_with(analysis={key: value}))


def test_an_unloaded_scene_is_the_reference_state_in_both_solvers():
    d = scene_with(loads=None)
    rec = run(d)
    assert rec["status"] == "converged" and rec["tip"] == {"ux": 0.0, "uy": 0.0}
    assert "no load" in rec["note"]


@pytest.mark.dolfinx
def test_an_unloaded_scene_is_the_reference_state_in_the_continuum():
    from reference_fem.simulation import run_scene as run_fem
    rec = sanitize(run_fem(scene_from_dict(scene_with(loads=None, fem={"cells_height": 2}))))
    assert rec["status"] == "converged" and rec["tip"] == {"ux": 0.0, "uy": 0.0}
    assert "no load" in rec["note"]


def test_energy_limit_inf_runs_finishes_and_its_record_re_runs():
    d = paper.pendulum_scene("yeoh", "plane-stress", 2e-3, "HB2n-12", 4, t_end=0.02, energy_limit=math.inf)
    rec = run(d)
    assert rec["status"] == "converged", rec["reason"]
    assert rec["energy_limit"] is None                       # no check
    again = scene_from_dict(rec["scene"])                    # the record's scene re-runs
    assert again.analysis.energy_limit == math.inf
    assert rec["scene"]["analysis"]["energy_limit"] == "inf"


@pytest.mark.parametrize("analysis, message", [
    ({"kind": "dynamic", "t_end": 0.1, "dt": 0.2}, r"analysis\.dt: must not exceed t_end"),
    ({"kind": "dynamic", "t_end": 0.1, "dt": 0.01, "dt_min": 0.02}, r"analysis\.dt_min: must not exceed dt"),
])
def test_steps_must_fit_the_run(analysis, message):
    d = scene_with(analysis=None)
    d["analysis"] = analysis
    with pytest.raises(SceneError, match=message):
        scene_from_dict(d)


def test_a_description_is_text():
    with pytest.raises(SceneError, match=r"description: must be a string"):
        scene_from_dict({**BASE, "description": 5})


# -- output in the right place ------------------------------------------------------------------
@pytest.mark.parametrize("name, expected", [("../../x", "x"), ("a/b", "a_b"), ("nul\x00byte", "nul_byte"),
                                            ("...", "scene"), ("ok-name_1.2", "ok-name_1.2")])
def test_file_names_from_scene_names_stay_in_their_folder(name, expected):
    assert safe_name(name) == expected


def test_vtk_files_of_a_hostile_name_land_inside_the_folder(tmp_path):
    scene = tmp_path / "s.toml"
    scene.write_text(SCENE.read_text().replace('name = "cantilever-yeoh"', 'name = "../../escape/x"'))
    out = tmp_path / "deep" / "vtk"
    assert ancf_main(["run", str(scene), "--vtk", str(out)]) == 0
    written = sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*") if p.is_file())
    assert written == ["deep/vtk/escape_x.pvd", "deep/vtk/escape_x_0000.vtu", "s.toml"]


def _read_vtu(path):
    """Points and the displacement point data of an ASCII .vtu (both solvers write ASCII
    XML; DOLFINx's version 2.2 files are beyond meshio 5.0, so the XML is read here)."""
    import xml.etree.ElementTree as ET
    piece = ET.parse(path).getroot().find("UnstructuredGrid/Piece")

    def array(node):
        return np.array(node.text.split(), float).reshape(-1, int(node.get("NumberOfComponents", 1)))
    pts = array(piece.find("Points/DataArray"))
    disp = next(array(a) for a in piece.iter("DataArray") if a.get("Name") == "displacement")
    return pts[:, :2], disp[:, :2]


def test_ancf_vtk_is_the_reference_geometry_with_the_displacement(tmp_path):
    """Read back with meshio: the points are the undeformed beam (x in [0, L], |y| <= h/2)
    and points + displacement at the free-end centre is the record's tip."""
    rec_path = tmp_path / "r.json"
    assert ancf_main(["run", str(SCENE), "--vtk", str(tmp_path), "--json", str(rec_path)]) == 0
    rec = json.loads(rec_path.read_text())
    import meshio
    m = meshio.read(tmp_path / "cantilever-yeoh_0000.vtu")            # a standard reader takes it
    assert m.points.shape[0] > 0 and "displacement" in m.point_data
    pts, disp = _read_vtu(tmp_path / "cantilever-yeoh_0000.vtu")
    L, h = rec["scene"]["beam"]["length"], rec["scene"]["beam"]["height"]
    assert pts[:, 0].min() == pytest.approx(0.0, abs=1e-12) and pts[:, 0].max() == pytest.approx(L)
    assert np.abs(pts[:, 1]).max() == pytest.approx(h / 2)
    tip = np.argmin(np.hypot(pts[:, 0] - L, pts[:, 1]))
    assert disp[tip] == pytest.approx([rec["tip"]["ux"], rec["tip"]["uy"]], rel=1e-6)


@pytest.mark.dolfinx
def test_continuum_vtk_is_the_reference_geometry_with_the_displacement(tmp_path):
    from reference_fem.cli import main as fem_main
    scene = tmp_path / "s.toml"
    scene.write_text(SCENE.read_text() + '\n[fem]\ncells_height = 2\n')
    rec_path = tmp_path / "r.json"
    assert fem_main(["run", str(scene), "--vtk", str(tmp_path / "vtk"), "--json", str(rec_path)]) == 0
    rec = json.loads(rec_path.read_text())
    vtu = sorted((tmp_path / "vtk").rglob("*.vtu"))
    pts, disp = _read_vtu(vtu[-1])
    L, h = rec["scene"]["beam"]["length"], rec["scene"]["beam"]["height"]
    assert pts[:, 0].max() == pytest.approx(L) and np.abs(pts[:, 1]).max() == pytest.approx(h / 2)
    tip = np.argmin(np.hypot(pts[:, 0] - L, pts[:, 1]))
    assert disp[tip] == pytest.approx([rec["tip"]["ux"], rec["tip"]["uy"]], rel=1e-6)


# -- fuzz ---------------------------------------------------------------------------------------
KEYS = {"": ["name", "description", "beam", "material", "ancf", "supports", "loads", "analysis", "fem"],
        "beam": ["length", "height", "width"],
        "material": ["law", "formulation", "density", "penalty", "C10", "C01", "C20", "C30", "C99"],
        "ancf": ["element", "elements", "quadrature"], "supports": ["left", "clamp"],
        "loads": ["gravity", "tip_force"], "fem": ["cells_height", "cells_length", "aspect", "cell", "degree",
                                                   "quadrature_degree", "incompressibility", "model"],
        "analysis": ["kind", "load_steps", "newton_rtol", "max_iterations", "t_end", "dt", "dt_min", "tolerance",
                     "output_times", "integrator", "rho_inf", "energy_limit", "max_steps", "wall_time"]}
scalars = st.one_of(st.none(), st.booleans(), st.integers(-10 ** 12, 10 ** 12), st.floats(allow_nan=True),
                    st.text(max_size=12), st.sampled_from(["yeoh", "paper", "HB2n-12", "clamp", "pin", "static",
                                                           "dynamic", "inf", "face", "newmark", "3d"]))
values = st.recursive(scalars, lambda inner: st.one_of(st.lists(inner, max_size=4),
                                                       st.dictionaries(st.text(max_size=6), inner, max_size=3)),
                      max_leaves=6)


def _check_both(scene_dict) -> None:
    """Only a SceneError may come out of loading and checking a scene, in both solvers."""
    from reference_fem.simulation import capacity as fem_capacity
    try:
        s = scene_from_dict(scene_dict)
    except SceneError:
        return
    for check in (lambda: ancf_capacity(s), lambda: fem_capacity(s)):
        try:
            check()
        except SceneError:
            pass


@fuzz(150)    # 4000 in make test-slow
@given(st.sampled_from([(t, k) for t, ks in KEYS.items() for k in ks]), values)
def test_fuzz_one_wrong_value(place, value):
    table, key = place
    d = copy.deepcopy(BASE)
    if table:
        d.setdefault(table, {})
        if not isinstance(d[table], dict):
            d[table] = {}
        d[table][key] = value
    else:
        d[key] = value
    _check_both(d)


@fuzz(60)     # 2000 in make test-slow, and 1500 of mutated scene text
@given(st.dictionaries(st.sampled_from(KEYS[""]),
                       st.one_of(values, st.dictionaries(st.sampled_from(sum(KEYS.values(), [])), values,
                                                         max_size=8)), max_size=9))
def test_fuzz_random_documents(d):
    _check_both(d)


@fuzz(80)     # 2000 in make test-slow
@given(st.binary(max_size=400))
def test_fuzz_random_bytes(tmp_path_factory, data):
    f = tmp_path_factory.mktemp("fuzz") / "x.toml"
    f.write_bytes(data)
    try:
        _check_both(tomllib.loads(data.decode("utf-8")))
    except (UnicodeDecodeError, tomllib.TOMLDecodeError):
        pass
    with pytest.raises(SceneError):   # random bytes are never a whole scene
        load_scene(f)


small_scenes = st.fixed_dictionaries({
    "element": st.sampled_from(["LB2n-12", "HB2n-12", "HB3n-12", "HB2n-16"]),
    "elements": st.integers(1, 6), "law": st.sampled_from(["neo-hookean", "mooney-rivlin", "yeoh"]),
    "formulation": st.sampled_from(["paper", "plane-strain", "plane-stress"]),
    "quadrature": st.tuples(st.integers(1, 4), st.integers(1, 3)),
    "left": st.sampled_from(["clamp", "pin"]), "gravity": st.floats(-1e4, 1e4),
    "tip": st.floats(-1e3, 1e3), "dynamic": st.booleans(), "steps": st.integers(1, 20),
    "dt": st.sampled_from([1e-4, 1e-3, 5e-3]),
    "integrator": st.sampled_from(["generalized-alpha", "newmark", "discrete-gradient"]),
})


@fuzz(5)      # 150 in make test-full (tests/test_fuzz_slow.py)
@given(small_scenes)
def test_fuzz_small_random_runs_end_with_a_status(p):
    """Random small scenes run to a record with a status (never an exception, never NaN),
    bounded by the scene's wall time; a pinned static scene is singular (rigid
    rotation) and must fail with a reason, not hang."""
    d = paper.cantilever_scene(p["law"], p["formulation"], p["element"], p["elements"], quadrature=p["quadrature"],
                               load_steps=p["steps"], wall_time=20.0)
    d["supports"] = {"left": p["left"]} if p["left"] == "pin" else d["supports"]
    d["loads"] = {"gravity": [0.0, p["gravity"]], "tip_force": [0.0, p["tip"]]}
    if p["dynamic"]:
        d["analysis"] = {"kind": "dynamic", "t_end": 0.01, "dt": p["dt"], "integrator": p["integrator"],
                         "wall_time": 20.0}
    try:
        rec = run(d)
    except SceneError:
        return
    assert rec["status"] in ("converged", "failed")
    assert rec["status"] == "failed" and rec["reason"] or rec["status"] == "converged"
    json.dumps(rec, allow_nan=False)


# -- the study runner's command line on a bad catalog ---------------------------------------------
@pytest.mark.parametrize("content, message", [
    (None, "cannot read"),                                              # no such file
    (b"\xff", "cannot read"),
    (b"[x\n", "not valid TOML"),
    (b"name = " + b"[" * 5000 + b"]" * 5000, "nested hundreds of levels deep"),
    (b"[" + b".".join([b"a"] * 200) + b"]\nx = 1", "more than 32 levels"),
    (b"x = 5\n", "x: must be a table"),
    (b"[x]\ntitle = 't'\n", "x.module: must name a module"),
    (b"[x]\nmodule = '../etc'\n", "x.module: must name a module"),
    (b"[x]\nmodule = 'paper.table3'\nneeds = 5\n", "x.needs: must be a list"),
    (b"[x]\nmodule = 'paper.table3'\nneeds = ['y']\n", "needs unknown"),
    (b"[x]\nmodule = 'paper.table3'\ntiny = 3\n", "x.tiny: must be a table"),
    (b"[x]\nmodule = 'paper.table3'\n", "its grid needs the key 'formulations'"),
])
def test_a_bad_catalog_is_one_line(tmp_path, capsys, content, message):
    from studies.cli import main as studies_main
    f = tmp_path / "cases.toml"
    if content is not None:
        f.write_bytes(content)
    assert studies_main(["list", "--catalog", str(f)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0], err


def test_studies_diff_of_garbage_records_is_one_line_or_a_table(tmp_path, capsys):
    """The quick guard of the diff fuzz: torn, non-JSON and ill-typed record lines are
    skipped or named; no traceback."""
    from studies.cli import main

    lines = ["{", "null", '{"case_id": 3, "status": [], "tip": "x"}', '{"scene": {"name": 1}}', "\x00\xff",
             json.dumps({"case_id": "a", "case": {}, "status": "converged", "tip": {"ux": "1"}})]
    for d in ("old", "new"):
        (tmp_path / d / "data").mkdir(parents=True)
        (tmp_path / d / "data" / "table3.jsonl").write_text("\n".join(lines))
    code = main(["diff", str(tmp_path / "old"), str(tmp_path / "new")])
    assert code in (0, 1, 2) and "Traceback" not in capsys.readouterr().err
