"""The record schema as an interface: what any solver's record must hold, checked key by key.

A record (:mod:`contract.record`) is one JSON object per run. :func:`problems` lists what
is wrong with one, each problem naming its key (``tip.ux: a number or null, got 'abc'``);
an empty list is a record the harness can use. The rules are those of
``docs/reference/record.md``:

- every key of :data:`contract.record.KEYS` is present (a value may be null);
- ``schema`` is ``ancf-harness/record/N`` with this harness's N (:data:`VERSION`);
- ``status`` is ``converged`` or ``failed``; a failed record says why (``reason``);
- a converged record has a finite tip ``{ux, uy}`` (m; ``rotation`` in rad where the scene
  has an end moment);
- counts are non-negative integers, times non-negative numbers, ``stable`` a boolean,
  ``effects`` a list of names, ``scene`` an object;
- no NaN or infinity anywhere (JSON has none; a record that needs one writes null).

Keys beyond these are the solver's own and are kept as they are.

**Version policy.** N changes only when a key of :data:`contract.record.KEYS` is removed,
renamed or changes its meaning or unit; a new key, or a new value of ``effects``, keeps N.
A checker accepts records of its own N only.
"""
from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from .record import KEYS, SCHEMA

NAME, _, _VERSION = SCHEMA.rpartition("/")
VERSION = int(_VERSION)
STATUSES = ("converged", "failed")
COUNTS = ("ndof", "newton_iterations", "load_steps", "rejected_steps")
TIMES = ("cpu_s", "wall_s", "setup_s")


def _number(x: Any) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def _non_finite(x: Any, path: str) -> list[str]:
    if isinstance(x, float) and not math.isfinite(x):
        return [f"{path}: {x!r} (a record holds no NaN or infinity; write null)"]
    if isinstance(x, dict):
        return [p for k, v in x.items() for p in _non_finite(v, f"{path}.{k}" if path else str(k))]
    if isinstance(x, list):
        return [p for i, v in enumerate(x) for p in _non_finite(v, f"{path}[{i}]")]
    return []


def problems(rec: Any) -> list[str]:
    """What is wrong with ``rec`` (a parsed record), each naming its key; [] if nothing."""
    if not isinstance(rec, dict):
        return [f"record: a JSON object, got {type(rec).__name__}"]
    out = [f"{k}: missing (every record has it; null where there is nothing to say)" for k in KEYS if k not in rec]
    out += _non_finite(rec, "")
    schema = rec.get("schema")
    if "schema" in rec and schema != SCHEMA:
        out.append(f"schema: {SCHEMA!r} (this harness reads version {VERSION} only), got {schema!r}")
    status = rec.get("status")
    if "status" in rec and status not in STATUSES:
        out.append(f"status: one of {', '.join(repr(s) for s in STATUSES)}, got {status!r}")
    reason = rec.get("reason")
    if reason is not None and not isinstance(reason, str):
        out.append(f"reason: a string or null, got {reason!r}")
    if status == "failed" and not reason:
        out.append("reason: a failed record says why (a non-empty string)")
    tip = rec.get("tip")
    if tip is not None:
        if not isinstance(tip, dict):
            out.append(f"tip: an object {{ux, uy}} or null, got {tip!r}")
        else:
            for k in ("ux", "uy"):
                if k not in tip:
                    out.append(f"tip.{k}: missing")
            for k, v in tip.items():
                if v is not None and not _number(v):
                    out.append(f"tip.{k}: a number (m, or rad for rotation) or null, got {v!r}")
    if status == "converged" and (not isinstance(tip, dict) or not all(_number(tip.get(k)) for k in ("ux", "uy"))):
        out.append("tip: a converged record has finite tip.ux and tip.uy")
    for k in COUNTS:
        v = rec.get(k)
        if v is not None and not (isinstance(v, int) and not isinstance(v, bool) and v >= 0):
            out.append(f"{k}: a non-negative integer or null, got {v!r}")
    for k in TIMES:
        v = rec.get(k)
        if v is not None and not (_number(v) and v >= 0):
            out.append(f"{k}: a non-negative number of seconds or null, got {v!r}")
    stable = rec.get("stable")
    if stable is not None and not isinstance(stable, bool):
        out.append(f"stable: true, false or null, got {stable!r}")
    effects = rec.get("effects")
    if effects is not None and not (isinstance(effects, list) and all(isinstance(e, str) for e in effects)):
        out.append(f"effects: a list of names or null, got {effects!r}")
    if "scene" in rec and not isinstance(rec["scene"], dict):
        out.append(f"scene: the scene as an object, got {type(rec['scene']).__name__}")
    return out


def _refuse_constant(name: str):
    raise ValueError(f"{name} is not JSON (a record holds no NaN or infinity; write null)")


def read(path: str | Path) -> tuple[dict | None, list[str]]:
    """(the record, its problems) of a JSON file; the record is None where the file is
    not a JSON object (its problem says why)."""
    try:
        rec = json.loads(Path(path).read_text(encoding="utf-8"), parse_constant=_refuse_constant)
    except FileNotFoundError:
        return None, [f"record: no file {path}"]
    except (ValueError, UnicodeDecodeError) as e:
        return None, [f"record: not JSON ({e})"]
    found = problems(rec)
    return (rec if isinstance(rec, dict) else None), found
