"""The work-precision bench's record files under ``<out>/data/peers/``, read and written in
one place (:mod:`studies.peers.work_precision` and :mod:`studies.peers.step_cost` write
them, :mod:`studies.peers.precision_report`, the audit and the accuracy-cost study read
them):

- ``peers-work-precision.jsonl``: one record per point of the grid (:func:`points_path`,
  :func:`read`);
- ``peers-work-precision-rounds.jsonl`` beside it: the deciding points' re-timings
  (:func:`rounds_path`);
- ``peers-step-cost.json``: the missed targets' measurements, a JSON list of every
  scene's (:func:`costs_path`, :func:`read_costs`, :func:`write_costs`).
"""
from __future__ import annotations

import json
from pathlib import Path

from .precision_grid import NAME

COSTS = f"{NAME.replace('work-precision', 'step-cost')}.json"     # peers-step-cost.json


def points_path(out: Path) -> Path:
    """The grid's records under the reports directory ``out``."""
    return Path(out) / "data" / "peers" / f"{NAME}.jsonl"


def read(path: Path) -> list[dict]:
    return [json.loads(ln) for ln in path.read_text().splitlines() if ln.strip()] if path.exists() else []


def rounds_path(path: Path) -> Path:
    """The deciding points' re-timings, beside the points' records."""
    return path.with_name(f"{NAME}-rounds.jsonl")


def costs_path(out: Path) -> Path:
    return Path(out) / "data" / "peers" / COSTS


def write_costs(path: Path, scene: str, new: list[dict]) -> list[dict]:
    """The record with ``scene``'s entries replaced by ``new``."""
    old = json.loads(path.read_text()) if path.exists() else []
    keep = [r for r in old if r["scene"] != scene] + new
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(keep, indent=1) + "\n")
    return keep


def read_costs(path: Path) -> list[dict]:
    return json.loads(Path(path).read_text()) if Path(path).exists() else []
