"""The peer's own venv (``.venv-peers``, :file:`tools/setup_peers.sh`): where its Python is
and how a peer script of this directory runs in it; shared by the comparison
(:mod:`.compare`), the work-precision grid and the published-value checks
(:mod:`.exudyn_published`)."""
from __future__ import annotations

import json
import os
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PEER_PYTHON = ROOT / ".venv-peers" / "bin" / "python"


def parse_peer_output(stdout: str) -> dict:
    """The JSON object on the last non-empty line of the peer script's stdout."""
    lines = [ln for ln in stdout.splitlines() if ln.strip()]
    if not lines:
        raise RuntimeError("the peer script printed nothing")
    try:
        out = json.loads(lines[-1])
    except json.JSONDecodeError as e:
        raise RuntimeError(f"the peer script's last line is not JSON: {lines[-1][:200]!r}") from e
    if out.get("status") != "converged":
        raise RuntimeError(f"the peer run failed: {out.get('reason')}")
    return out


def run_peer_script(script: Path, args: list[str], python: Path = PEER_PYTHON, scene: str | None = None) -> dict:
    """Run a peer script of this directory with ``python`` (.venv-peers), in a scratch
    directory (nothing it might write lands in the repository) and without our venv's
    environment, and return the JSON on its last line (:func:`parse_peer_output`).
    ``scene``: a scene file's text, written to the scratch directory and given to the
    script as its first argument."""
    if not Path(python).exists():
        raise SystemExit(f"{python} not found: run `bash tools/setup_peers.sh` first")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV", "PYTHONHOME")}
    with tempfile.TemporaryDirectory(prefix="exudyn-peer-") as cwd:
        if scene is not None:
            (Path(cwd) / "scene.toml").write_text(scene)
            args = ["scene.toml", *args]
        p = subprocess.run([str(python), str(script), *args], cwd=cwd, env=env, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"peer script exited {p.returncode}:\n{p.stdout[-2000:]}\n{p.stderr[-2000:]}")
    return parse_peer_output(p.stdout)
