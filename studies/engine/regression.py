"""Golden values of the tiny-mode studies: named values with per-value tolerances.

``tests/gold/studies_tiny.json`` holds {name: {"value", "tolerance"}} (SI), collected
from every study's ``gold_values(ctx)`` after a tiny run. :func:`compare` names each
mismatch with the difference; a value missing from either side is a mismatch too.
The file changes only through ``python -m studies gold --refresh``. Runs that end on an
equilibrium whose tangent is singular or indefinite (record ``stable`` false) give no
golden values: their tip is not fixed by the equations but by the solver's path.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

from .catalog import load_catalog

FILE = Path(__file__).resolve().parents[2] / "tests" / "gold" / "studies_tiny.json"


def collect(out: Path) -> dict[str, tuple[float, float]]:
    """{name: (value, tolerance)} from the records of a tiny run in ``out``."""
    from .report import Context

    catalog = load_catalog(tiny=True)
    values = {}
    for study in catalog.values():
        fn = getattr(study.module, "gold_values", None)
        if fn is not None:
            values.update(fn(Context(study, Path(out), catalog)))
    return values


def compare(values: dict[str, tuple[float, float]], gold: dict[str, dict]) -> list[str]:
    """Mismatches, one line each, naming the value and the difference."""
    problems = []
    for name, g in sorted(gold.items()):
        if name not in values:
            problems.append(f"{name}: missing (gold {g['value']!r})")
            continue
        v, d = values[name][0], values[name][0] - g["value"]
        if not (math.isfinite(v) and abs(d) <= g["tolerance"]):
            problems.append(f"{name}: got {v!r}, gold {g['value']!r}, difference {d:+.3e} "
                            f"exceeds tolerance {g['tolerance']:.1e}")
    for name in sorted(set(values) - set(gold)):
        problems.append(f"{name}: new value {values[name][0]!r}, not in the gold file "
                        "(refresh: python -m studies gold --refresh)")
    return problems


def load_gold(path: Path = FILE) -> dict[str, dict]:
    return json.loads(Path(path).read_text())["values"]


def _tiny_run(out: Path) -> None:
    from .pipeline import run_studies
    run_studies(["all"], Path(out), tiny=True, progress=False, log=lambda *a: None)


def check_gold(out: Path, path: Path = FILE) -> list[str]:
    _tiny_run(out)
    return compare(collect(out), load_gold(path))


def refresh_gold(out: Path, path: Path = FILE) -> Path:
    _tiny_run(out)
    values = collect(out)
    doc = {"description": "Named values of the tiny-mode studies (SI: m), each with its tolerance "
                          "(see each study's gold_values). Refresh only with: python -m studies gold --refresh",
           "values": {k: {"value": v, "tolerance": t} for k, (v, t) in sorted(values.items())}}
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(doc, indent=1) + "\n")
    return path
