"""The FElupe install (tools/setup.sh): pinned pure-Python packages next to Debian's
numpy/scipy, never shadowing them; the ANCF core runs without felupe or dolfinx."""
import re
import subprocess
import sys
from importlib.metadata import version
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DEBIAN = "/usr/lib/python3/dist-packages/"


@pytest.mark.debian
@pytest.mark.parametrize("name", ["numpy", "scipy"])
def test_numpy_and_scipy_are_debians(name):
    """pip must never install numpy/scipy into the venv (dolfinx is built against Debian's)."""
    module = __import__(name)
    assert module.__file__.startswith(DEBIAN), module.__file__


def test_felupe_pins_are_installed():
    pins = re.search(r'felupe_pins="([^"]+)"', (ROOT / "tools" / "setup.sh").read_text()).group(1).split()
    assert {p.split("==")[0] for p in pins} == {"felupe", "tensortrax"}
    for pin in pins:
        name, wanted = pin.split("==")
        assert version(name) == wanted, f"{name} {version(name)} installed, {wanted} pinned"
    assert "--no-deps $felupe_pins" in (ROOT / "tools" / "setup.sh").read_text()


BLOCK = """
import sys
class Block:
    def find_spec(self, name, path=None, target=None):
        if name.split('.')[0] in ('felupe', 'tensortrax', 'dolfinx', 'ufl', 'basix'):
            raise ImportError('blocked: ' + name)
sys.meta_path.insert(0, Block())
"""


def test_ancf_core_runs_without_felupe_or_dolfinx():
    """ANCF's static cantilever (a coarse one) with felupe and dolfinx unimportable."""
    code = BLOCK + """
from contract import paper
from contract.scene import scene_from_dict
import ancf.simulation as sim
rec, _ = sim.run_scene(scene_from_dict(paper.cantilever_scene('neo-hookean', 'plane-stress', 'HB2n-12', 4)))
assert rec['status'] == 'converged', rec['reason']
assert 'felupe' not in sys.modules and 'dolfinx' not in sys.modules
print(rec['tip'])
"""
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-2000:]
