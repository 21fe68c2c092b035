"""Scene files and records: bad input gets one clear message naming the field and the
allowed values (the contract checks structure and types, each solver the names it
resolves); records carry every documented key and never NaN."""
import copy
import json
import math
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from ancf.build import check
from contract.errors import SceneError
from contract.record import KEYS, sanitize, write_record
from contract.scene import load_scene, scene_from_dict

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "scenes" / "cantilever-yeoh.toml"
BASE = tomllib.loads(SCENE.read_text())


def mutated(path, value):
    d = copy.deepcopy(BASE)
    *head, last = path.split(".")
    t = d
    for k in head:
        t = t[k]
    if value is DELETE:
        del t[last]
    else:
        t[last] = value
    return d


DELETE = object()

BAD = [
    ("material.law", "ogden", r"material\.law: unknown value 'ogden'; allowed: 'gent', 'mooney-rivlin', 'neo-hookean', 'yeoh'"),
    ("material.formulation", "3d", r"material\.formulation: unknown value '3d'; allowed: 'paper', 'plane-strain', 'plane-stress'"),
    ("ancf.element", "HB9n-9", r"ancf\.element: unknown value 'HB9n-9'; allowed: .*'HB2n-12'"),
    ("material.C20", DELETE, r"material: missing key\(s\) \['C20'\]"),
    ("material.C01", 0.1e6, r"material: unknown key\(s\) \['C01'\]"),
    ("material.penalty", 1e9, r"material: unknown key\(s\) \['penalty'\]"),      # plane-stress has no penalty
    ("beam.length", -0.16, r"beam\.length: must be positive"),
    ("beam.height", 0, r"beam\.height: must be positive"),
    ("ancf.elements", 0, r"ancf\.elements: must be positive"),
    ("ancf.elements", 2.5, r"ancf\.elements: must be a positive integer"),
    ("ancf.quadrature", [3], r"ancf\.quadrature: must be \[points along x, points across the thickness\]"),
    ("supports.left", "roller", r"supports\.left: unknown value 'roller'; allowed: 'clamp', 'hinge', 'pin', 'slide'"),
    ("supports.clamp", "half", r"supports\.clamp: unknown value 'half'; allowed: 'all', 'face'"),
    ("loads.gravity", [0.0, -9.81, 0.0], r"loads\.gravity: must be a list of two numbers"),
    ("loads.wind", [1.0, 0.0], r"loads: unknown key\(s\) \['wind'\]; allowed: end_moment, gravity, tip_force"),
    ("analysis.kind", "modal", r"analysis\.kind: unknown value 'modal'; allowed: 'dynamic', 'static'"),
    ("analysis.load_steps", -3, r"analysis\.load_steps: must be positive"),
    ("colour", "red", r"scene: unknown key\(s\) \['colour'\]"),
]


@pytest.mark.parametrize("path,value,message", BAD, ids=[b[0] + "=" + repr(b[1])[:12] for b in BAD])
def test_bad_scene_names_the_field(path, value, message):
    with pytest.raises(SceneError, match=message):
        check(scene_from_dict(mutated(path, value)))


NAMES = [("material.law", "ogden"), ("material.formulation", "3d"), ("ancf.element", "HB9n-9"),
         ("material.C01", 0.1e6)]


@pytest.mark.parametrize("path,value", NAMES)
def test_the_contract_leaves_names_to_each_solver(path, value):
    """The contract knows no solver's registry: a name (or a law's constant) only a solver
    can judge passes the loader and is refused by both solvers' checks."""
    from reference_fem.simulation import check as check_fem
    scene = scene_from_dict(mutated(path, value))
    for solver_check in (check, check_fem):
        if path.startswith("ancf.") and solver_check is check_fem:
            continue                                   # the continuum ignores [ancf]
        with pytest.raises(SceneError, match=path.split(".")[0]):
            solver_check(scene)


def test_the_contract_imports_no_solver():
    code = "import sys, contract.scene, contract.record, contract.paper; print(sorted(m for m in sys.modules if m.split('.')[0] in ('ancf', 'reference_fem', 'studies')))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_penalty_is_required_where_it_belongs():
    d = mutated("material.formulation", "plane-strain")
    with pytest.raises(SceneError, match=r"material: missing key\(s\) \['penalty'\]"):
        check(scene_from_dict(d))
    d["material"]["penalty"] = 1e9
    assert check(scene_from_dict(d)).material.penalty == 1e9


def test_pin_takes_no_clamp_option():
    d = mutated("supports.left", "pin")
    with pytest.raises(SceneError, match=r"supports\.clamp: only with left = \"clamp\""):
        scene_from_dict(d)


def test_defaults_are_filled_and_the_scene_round_trips():
    d = mutated("ancf.quadrature", DELETE)
    s = scene_from_dict(d)
    # no rule: the element's default, resolved by the solver (ancf.build.quadrature)
    assert s.ancf.quadrature is None and s.supports.clamp == "face"
    assert scene_from_dict(s.to_dict()) == s
    assert scene_from_dict(s.to_dict()).to_dict() == s.to_dict()
    assert "quadrature" not in s.to_dict()["ancf"]
    # the digest depends on content only: a chosen rule is a different scene
    assert s.digest() != scene_from_dict(BASE).digest()
    assert s.digest() != scene_from_dict(mutated("ancf.elements", 17)).digest()


def test_dynamic_scene_round_trips():
    d = mutated("analysis", {"kind": "dynamic", "t_end": 0.5, "dt": 1e-3, "output_times": [0.1, 0.5]})
    s = scene_from_dict(d)
    assert s.analysis.rho_inf == 0.5 and s.analysis.integrator == "generalized-alpha"
    assert scene_from_dict(s.to_dict()) == s


def _cli(*args, cwd=ROOT):
    return subprocess.run([sys.executable, "-m", "ancf", *args], capture_output=True, text=True, cwd=cwd)


def test_cli_bad_scene_one_message_no_traceback(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(SCENE.read_text().replace('law = "yeoh"', 'law = "yeo"'))
    p = _cli("run", str(bad))
    assert p.returncode == 2
    assert "Traceback" not in p.stderr
    assert p.stderr.strip().splitlines() == [
        "ancf: error: material.law: unknown value 'yeo'; allowed: 'gent', 'mooney-rivlin', 'neo-hookean', 'yeoh'"]
    missing = _cli("run", str(tmp_path / "nope.toml"))
    assert missing.returncode == 2 and "scene file not found" in missing.stderr


def test_cli_run_writes_a_complete_record(tmp_path):
    out = tmp_path / "rec.json"
    p = _cli("run", str(SCENE), "--json", str(out))
    assert p.returncode == 0, p.stderr
    assert "tip" in p.stdout and "newton" in p.stdout
    rec = json.loads(out.read_text())
    assert set(KEYS) <= set(rec)
    assert rec["solver"] == "ancf" and rec["status"] == "converged" and rec["reason"] is None
    assert rec["scene"] == load_scene(SCENE).to_dict()
    assert rec["tip"]["uy"] < -0.1 and rec["ndof"] > 0 and rec["stable"] is True
    assert rec["effects"] == ["elastic", "gravity"]
    assert all(rec[k] > 0 for k in ("cpu_s", "wall_s", "setup_s"))


def test_records_never_hold_nan(tmp_path):
    rec = {"status": "converged", "reason": None, "tip": {"ux": float("nan"), "uy": 1.0},
           "history": [1.0, float("inf")]}
    clean = sanitize(rec)
    assert clean["status"] == "failed" and "non-finite" in clean["reason"]
    assert clean["tip"]["ux"] is None and clean["history"][1] is None
    write_record(rec, tmp_path / "r.json")
    text = (tmp_path / "r.json").read_text()
    assert "NaN" not in text and "Infinity" not in text
    json.loads(text)


def test_the_solvers_are_siblings_and_mechanics_imports_neither():
    """Layout (issue 23): contract <- mechanics <- {ancf, reference_fem}; no import between
    the two solvers, none from mechanics or contract into them (read from the sources, every
    import statement, lazy ones inside functions included)."""
    import ast
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    forbidden = {"ancf": {"reference_fem", "studies"}, "reference_fem": {"ancf", "studies"},
                 "mechanics": {"ancf", "reference_fem", "studies"}, "contract": {"ancf", "reference_fem", "mechanics", "studies"}}
    bad = []
    for pkg, banned in forbidden.items():
        for f in (root / pkg).rglob("*.py"):
            for node in ast.walk(ast.parse(f.read_text())):
                names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
                    [node.module] if isinstance(node, ast.ImportFrom) and node.module and node.level == 0 else []
                bad += [f"{f.relative_to(root)}:{node.lineno} imports {n}" for n in names if n.split(".")[0] in banned]
    assert not bad, bad
