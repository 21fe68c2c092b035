"""The five loops a user waits on, measured in a fresh clone: ``make loops``.

``python -m studies loops [--keep DIR]`` clones the committed tree (``git clone``) into a
new directory and there, in order:

1. **set-up**: ``make setup`` (the venv, the editable install, the compiled code: ``ancf
   warm``), timed;
2. **first run**: ``ancf run`` of every shipped ANCF scene, each in a fresh process with no
   thread variable set, timed as a whole process;
3. **tests**: ``make test`` (set-up, the quick tier, the mpi phase), the whole command timed
   and pytest's own time of each phase read from its summary line;
4. **verify**: ``python -m studies verify --sample 20 --seed 1`` of the committed records;
5. **cold study**: ``make study`` with ``reports/`` emptied (no records: everything
   computed; the loops record itself kept, the README quotes it), then **reused study**:
   ``make study`` again (every record reused).

The figures go to ``reports/data/loops.json`` (a record: the commit measured, the
machine, each figure); :func:`markdown` renders them into ``reports/loops.md``, which the
README quotes (:mod:`studies.engine.readme`: ``studies audit`` checks the quote, and that
``loops.md`` is the rendering of the record: :func:`record_problems`).
"""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

from .engine.readme import refresh

ROOT = Path(__file__).resolve().parents[1]
RECORD = ROOT / "reports" / "data" / "loops.json"
PAGE = ROOT / "reports" / "loops.md"
VERIFY_SAMPLE = 20


def _timed(cmd, cwd: Path, env=None) -> tuple[float, str]:
    t0 = time.perf_counter()
    p = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))} failed in {cwd} (exit {p.returncode}):\n"
                           f"{p.stdout[-3000:]}\n{p.stderr[-3000:]}")
    return dt, p.stdout + p.stderr


def _pytest_seconds(out: str) -> list[float]:
    """pytest's own time of each phase, from its summary lines ('... in 104.00s ...')."""
    return [float(m) for m in re.findall(r"(?:passed|failed|error|errors|deselected)[^\n]* in ([0-9.]+)s", out)]


def measure(clone: Path, log=print) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS",
                                                             "MKL_NUM_THREADS", "NUMBA_CACHE_DIR")}
    rec: dict = {"schema": "ancf-harness/loops/1", "date": time.strftime("%Y-%m-%d"),
                 "commit": subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=clone, capture_output=True,
                                          text=True).stdout.strip(),
                 "machine": {"cpus": os.cpu_count()}}
    log("set-up ...")
    rec["setup_s"], _ = _timed(["make", "setup"], clone, env)
    log("first runs ...")
    runs = {}
    for scene in sorted((clone / "scenes").glob("*.toml")):
        if "[ancf]" not in scene.read_text():
            continue
        runs[scene.name], _ = _timed([str(clone / ".venv" / "bin" / "ancf"), "run", str(scene), "--quiet"], clone, env)
    rec["first_run"] = {"scenes": runs, "max_s": max(runs.values())}
    log("tests ...")
    total, out = _timed(["make", "test"], clone, env)
    rec["tests"] = {"command_s": total, "pytest_s": _pytest_seconds(out)}
    log("verify ...")
    rec["verify"] = {"sample": VERIFY_SAMPLE}
    rec["verify"]["seconds"], _ = _timed([str(clone / ".venv" / "bin" / "python"), "-m", "studies", "verify",
                                          "--sample", str(VERIFY_SAMPLE), "--seed", "1"], clone, env)
    log("cold study ...")
    keep = {clone / "reports" / "loops.md", clone / "reports" / "data" / "loops.json"}   # not records
    for p in list((clone / "reports").rglob("*")):
        if p.is_file() and p not in keep:
            p.unlink()
    rec["study_cold_s"], _ = _timed(["make", "study"], clone, env)
    log("reused study ...")
    rec["study_reused_s"], _ = _timed(["make", "study"], clone, env)
    return rec


def _min_s(s: float) -> str:
    m, sec = divmod(round(s), 60)
    return f"{m} min {sec} s" if m else f"{sec} s"


def markdown(rec: dict) -> str:
    """The five figures as the README quotes them."""
    t = rec["tests"]
    scenes = rec["first_run"]["scenes"]
    return "\n".join([
        f"Measured by `make loops` in a fresh clone of {rec['commit']} on this project's "
        f"{rec['machine']['cpus']}-core machine (`reports/data/loops.json`):",
        "",
        "| loop | time |",
        "|---|---|",
        f"| set-up (venv, install, compiling the solver once) | {_min_s(rec['setup_s'])} |",
        f"| first `ancf run` of a shipped scene, whole process | {min(scenes.values()):.1f} to "
        f"{rec['first_run']['max_s']:.1f} s ({len(scenes)} scenes) |",
        f"| `make test`, pytest | {_min_s(sum(t['pytest_s']))} "
        f"({' + '.join(f'{x:.0f} s' for x in t['pytest_s'])}; the whole command {_min_s(t['command_s'])} "
        "once the set-up above is done) |",
        f"| `make study`, no records | {_min_s(rec['study_cold_s'])} |",
        f"| `make study`, every record reused | {_min_s(rec['study_reused_s'])} |",
        f"| `studies verify --sample {rec['verify']['sample']}` | {_min_s(rec['verify']['seconds'])} |",
        ""])


def record_problems(record: Path = RECORD, page: Path = PAGE) -> list[str]:
    """``loops.md`` against the rendering of the record (the audit's rule)."""
    if not record.exists():
        return []
    if not page.exists() or page.read_text() != markdown(json.loads(record.read_text())):
        return [f"{page}: not the rendering of {record.name} (make loops writes both)"]
    return []


def add_commands(sub) -> None:
    """The ``loops`` command on the sub-parsers of ``python -m studies`` (``make loops``)."""
    p = sub.add_parser("loops", help="the five loops a user waits on, measured in a fresh clone (make loops)")
    p.add_argument("--keep", type=Path, help="clone into this (new) directory and keep it")


def command(a) -> int:
    """The ``loops`` command: measure in a fresh clone, write the record and its page, refresh
    the README's quote."""
    clone = a.keep or Path(tempfile.mkdtemp(prefix="loops-")) / "clone"
    subprocess.run(["git", "clone", "--quiet", str(ROOT), str(clone)], check=True)
    try:
        rec = measure(clone, log=lambda s: print(s, flush=True))
    finally:
        if not a.keep:
            shutil.rmtree(clone.parent, ignore_errors=True)
    RECORD.write_text(json.dumps(rec, indent=1) + "\n")
    PAGE.write_text(markdown(rec))
    refresh()
    print(markdown(rec))
    return 0

