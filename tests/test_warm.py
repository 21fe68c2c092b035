"""The compiled code a scene runs is loaded before its run and timed apart: after
:func:`ancf.warm.load` of a shipped scene, its run compiles (or loads) nothing more."""
import json
import subprocess
import sys
from pathlib import Path

from ancf.warm import tiny
from contract.scene import load_scene

ROOT = Path(__file__).resolve().parent.parent

PROBE = """
import json, sys
from ancf.build import plan
from ancf.simulation import run_scene
from ancf.warm import compiled_signatures, load, shipped
out = {}
for scene in shipped():
    load(plan(scene))
    before = compiled_signatures()
    run_scene(scene)
    out[scene.name] = [before, compiled_signatures()]
print(json.dumps(out))
"""


def test_after_the_load_a_shipped_scenes_run_compiles_nothing():
    p = subprocess.run([sys.executable, "-c", PROBE], cwd=ROOT, capture_output=True, text=True, timeout=900)
    assert p.returncode == 0, p.stderr[-2000:]
    counts = json.loads(p.stdout.strip().splitlines()[-1])
    assert len(counts) >= 8
    assert {k: v for k, v in counts.items() if v[0] != v[1]} == {}


def test_the_tiny_copy_keeps_what_selects_the_compiled_code():
    scene = load_scene(ROOT / "scenes" / "pendulum-yeoh-paper.toml")
    t = tiny(scene)
    assert t.ancf.elements == 2 and t.analysis.t_end == 2 * scene.analysis.dt and t.analysis.output_times is None
    for part in ("material", "supports", "loads", "beam"):
        assert getattr(t, part) == getattr(scene, part)
    assert (t.ancf.element, t.ancf.quadrature) == (scene.ancf.element, scene.ancf.quadrature)
    keep = ("kind", "dt", "integrator", "newton", "rho_inf", "newton_rtol", "max_iterations", "tolerance")
    assert all(getattr(t.analysis, k) == getattr(scene.analysis, k) for k in keep)
