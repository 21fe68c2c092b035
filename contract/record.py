"""Result records: one JSON object per run, the same schema for both solvers.

A record never carries NaN or infinity: :func:`finite_or_none` turns them into null,
and :func:`write_record` refuses to write a converged record that still holds one
(that would be a solver bug presented as a result).
"""
from __future__ import annotations

import json
import math
import os
import platform
from pathlib import Path
from typing import Any

SCHEMA = "ancf-harness/record/1"

# Keys every record has (values may be null); solvers add their own after these.
KEYS = ("schema", "solver", "status", "reason", "tip", "ndof", "newton_iterations",
        "load_steps", "rejected_steps", "stable", "cpu_s", "wall_s", "setup_s",
        "effects", "scene")


def new_record(solver: str, scene: dict) -> dict:
    rec = {k: None for k in KEYS}
    rec.update(schema=SCHEMA, solver=solver, status="failed", reason="not run", scene=scene,
               host={"python": platform.python_version(), "machine": platform.machine(),
                     "cpus": os.cpu_count()})
    return rec


def finite_or_none(x: Any) -> Any:
    """The same structure with every non-finite float replaced by None."""
    if isinstance(x, float):
        return x if math.isfinite(x) else None
    if isinstance(x, dict):
        return {k: finite_or_none(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [finite_or_none(v) for v in x]
    if hasattr(x, "tolist"):  # numpy scalars and arrays
        return finite_or_none(x.tolist())
    return x


def _has_non_finite(x: Any) -> bool:
    if isinstance(x, float):
        return not math.isfinite(x)
    if isinstance(x, dict):
        return any(_has_non_finite(v) for v in x.values())
    if isinstance(x, (list, tuple)):
        return any(_has_non_finite(v) for v in x)
    return False


def sanitize(rec: dict) -> dict:
    """A record fit to write: numpy values made plain, non-finite numbers nulled; a
    'converged' record that held a non-finite number becomes 'failed'."""
    plain = json.loads(json.dumps(rec, default=lambda o: o.tolist() if hasattr(o, "tolist") else str(o)))
    if _has_non_finite(plain) and plain.get("status") == "converged":
        plain["status"], plain["reason"] = "failed", "non-finite value in the result"
    return finite_or_none(plain)


def write_record(rec: dict, path: str | Path) -> None:
    """Write the record atomically (a temporary file beside it, then a rename; the
    temporary file never stays behind)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(path.suffix + ".tmp")
    try:
        tmp.write_text(json.dumps(sanitize(rec), indent=2, allow_nan=False) + "\n")
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
