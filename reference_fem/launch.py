"""Launching ``python -m reference_fem`` on several MPI ranks (no dolfinx here).

:func:`mpi_command` is the one place that knows how: ``srun -n N`` under Slurm
(``SLURM_JOB_ID`` set), else OpenMPI's ``mpiexec -n N`` with

- ``--oversubscribe``: more ranks than free cores is allowed (a 2-core machine, a busy
  one, or a test);
- ``--allow-run-as-root`` when running as root (CI containers; OpenMPI refuses otherwise);
- the environment the ranks need: ``PYTHONPATH`` (this checkout), one BLAS/OpenMP
  thread per rank (threaded BLAS under MPI oversubscribes the cores), and
  ``LD_LIBRARY_PATH`` if set (an OpenBLAS in place of Debian's reference BLAS, README);
- ``btl_vader_single_copy_mechanism none``: containers often forbid the cross-memory
  attach OpenMPI's shared-memory transport uses by default;
- ``mpi_yield_when_idle 1``: waiting ranks yield their core (a busy machine).

Every rank runs the same command; rank 0 writes the record (:mod:`reference_fem.cli`).
"""
from __future__ import annotations

import os
import shutil
import sys
from typing import Sequence

FORWARD = ("PYTHONPATH", "OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "LD_LIBRARY_PATH")


def environment(base: dict | None = None) -> dict:
    """The ranks' environment: ``base`` (default os.environ) with one thread per rank."""
    env = dict(os.environ if base is None else base)
    env.setdefault("OMP_NUM_THREADS", "1")
    env.setdefault("OPENBLAS_NUM_THREADS", "1")
    env.setdefault("OMPI_MCA_btl_vader_single_copy_mechanism", "none")
    # ranks waiting in a collective yield the core instead of spinning: with 2 ranks on a
    # 2-core machine where another process runs, spinning ranks starve each other
    env.setdefault("OMPI_MCA_mpi_yield_when_idle", "1")
    return env


def mpi_command(ranks: int, args: Sequence[str], python: str | None = None,
                env: dict | None = None) -> list[str]:
    """The command line running ``python -m reference_fem *args`` on ``ranks`` ranks."""
    python = python or sys.executable
    program = [python, "-m", "reference_fem", *args]
    env = environment(env)
    if env.get("SLURM_JOB_ID") and shutil.which("srun"):
        return ["srun", "-n", str(ranks), *program]
    mpiexec = shutil.which("mpiexec")
    if mpiexec is None:
        raise FileNotFoundError("mpiexec not found: install openmpi-bin (tools/setup.sh)")
    cmd = [mpiexec, "--oversubscribe"]
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    for name in FORWARD:
        if name in env:
            cmd += ["-x", name]
    return [*cmd, "-n", str(ranks), *program]


def scene_toml(d: dict, prefix: str = "") -> str:
    """A scene dict as a TOML file's text (what the ranks of a launch read): JSON
    scalars and arrays are TOML values; nested dicts become [tables]; None is left out."""
    import json

    lines, tables = [], []
    for k, v in d.items():
        if isinstance(v, dict):
            tables.append((k, v))
        elif v is not None:
            lines.append(f"{json.dumps(k)} = {json.dumps(v)}")
    out = "\n".join(lines) + "\n"
    for k, v in tables:
        out += f"\n[{prefix}{json.dumps(k)}]\n" + scene_toml(v, prefix=f"{prefix}{json.dumps(k)}.")
    return out


def run_launched(scene: dict, ranks: int, workdir, timeout_s: float | None = None) -> dict:
    """Run a scene dict under :func:`mpi_command` on ``ranks`` ranks; its record (rank 0's),
    or a failed record naming the launch's exit code and the end of its error output."""
    import json
    import subprocess
    from pathlib import Path

    from contract.record import new_record

    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    toml, out = workdir / "scene.toml", workdir / "record.json"
    toml.write_text(scene_toml(scene))
    out.unlink(missing_ok=True)
    env = environment()
    try:
        proc = subprocess.run(mpi_command(ranks, ["run", str(toml), "--json", str(out), "--quiet"], env=env),
                              env=env, capture_output=True, text=True, timeout=timeout_s)
        code, err = proc.returncode, proc.stderr
    except subprocess.TimeoutExpired:
        code, err = None, f"timeout: stopped after {timeout_s:g} s"
    if out.exists():
        return json.loads(out.read_text())
    rec = new_record((scene.get("fem") or {}).get("backend", "dolfinx"), scene)
    rec["reason"] = f"mpi launch on {ranks} ranks failed (exit {code}): {err.strip()[-1500:]}"
    return rec
