"""What the last full audit saw: the reports' inputs and outputs, so that an unchanged tree
is not rebuilt and audited again.

A full audit (:mod:`.audit`) rebuilds every report from the records and compares. When
it passes, :func:`write` stores a stamp (``<reports>/data/audit-stamp.json``) of

- the **inputs**: one digest of everything a report can read: the normalised code of
  every module of ``studies/`` and of all it imports (:mod:`.fingerprint`, whole
  modules), the versions of the packages that code uses (matplotlib draws the figures),
  and the bytes of every data file the reports read (``reports/data`` but this stamp,
  ``tests/gold``, ``contract/paper_data``, ``scenes``);
- the **outputs**: the sha256 of every report file (everything under ``<reports>`` but
  ``data/``).

:func:`current` is True when both are as stamped: the reports on disk are then what a
rebuild from these records with this code would write, as the full audit found, and
``studies run``, ``studies card`` and ``studies audit`` say so instead of rebuilding
(``studies audit --full`` rebuilds anyway). Any changed byte of an input or an output
makes it False, and the next audit is a full one.
"""
from __future__ import annotations

import hashlib
import json
from pathlib import Path

from . import fingerprint as fp

ROOT = Path(__file__).resolve().parents[2]
NAME = "audit-stamp.json"
DATA = ("tests/gold", "contract/paper_data", "scenes")
SKIPPED = (".lock", ".tmp", ".changed")


def _code() -> dict:
    modules = sorted(".".join(p.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__")
                     for p in (ROOT / "studies").rglob("*.py"))
    return fp.fingerprint(modules, whole=True)


def _hash_files(root: Path, files) -> dict[str, str]:
    out = {}
    for p in sorted(files):
        if p.is_file() and not p.name.endswith(SKIPPED) and p.name != NAME:
            out[str(p.relative_to(root))] = hashlib.sha256(p.read_bytes()).hexdigest()
    return out


def inputs(reports: Path) -> str:
    """One digest of the reports' inputs (see the module doc)."""
    reports = Path(reports)
    h = hashlib.sha256(json.dumps(_code(), sort_keys=True).encode())
    files = _hash_files(reports, (reports / "data").rglob("*"))
    for d in DATA:
        p = ROOT / d
        files.update({f"{d}/{k}" if p.is_dir() else d: v
                      for k, v in _hash_files(p if p.is_dir() else p.parent, p.rglob("*") if p.is_dir() else [p]).items()})
    h.update(json.dumps(files, sort_keys=True).encode())
    return h.hexdigest()


def outputs(reports: Path) -> dict[str, str]:
    """{report file: sha256} of every file under ``reports`` but ``data/``."""
    reports = Path(reports)
    return _hash_files(reports, (p for p in reports.rglob("*") if p.relative_to(reports).parts[0] != "data"))


def path(reports: Path) -> Path:
    return Path(reports) / "data" / NAME


def write(reports: Path) -> Path:
    """Stamp the reports as a passing full audit found them."""
    p = path(reports)
    p.write_text(json.dumps({"inputs": inputs(reports), "outputs": outputs(reports)}, indent=1, sort_keys=True) + "\n")
    return p


def current(reports: Path) -> bool:
    """Are the inputs and every report file as the last passing full audit stamped them?"""
    p = path(reports)
    if not p.exists():
        return False
    try:
        stamp = json.loads(p.read_text())
    except (OSError, json.JSONDecodeError):
        return False
    return stamp.get("inputs") == inputs(reports) and stamp.get("outputs") == outputs(reports)
