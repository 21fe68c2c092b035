"""Two record directories side by side: which results changed, and by how much.

``python -m studies diff OLD NEW [--rtol R] [--atol A]`` matches the records of every
study by what the case *is* (its solver, scene and options), not by its id (an id
changes whenever a solver's source does), and compares what a record reports:

- status, reason class (the text before the first colon), stability verdict and the
  number of negative eigenvalues where recorded;
- the tip, the tip history and the energies (within ``rtol`` relative + ``atol`` m or J);
- counts (ndof, accepted steps).

Timings are never compared. A case present on one side only is listed. The output is one
line per difference, then a count per study; the exit status is 1 if anything differs.

A move that renames a solver or a study (``--rename OLD=NEW``, repeatable) pairs the old
records under the new names, so that the move can be shown to change no result.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

from .case import canonical


@dataclass
class Change:
    study: str
    case: str
    what: str

    def __str__(self) -> str:
        return f"{self.study}: {self.case}: {self.what}"


def _rounded(x):
    """Numbers to 12 significant digits, so that a 1-ulp change in a constant is the same case."""
    if isinstance(x, float):
        return float(f"{x:.12g}")
    if isinstance(x, dict):
        return {k: _rounded(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_rounded(v) for v in x]
    return x


def key_of(rec: dict, rename: dict | None = None) -> str:
    """What the case is: solver, scene and options (the id without source and versions).
    The scene's name is a label, left out; an ANCF scene that left its quadrature to the
    element's default counts with the rule that ran (the record's ``quadrature``), so a
    case that named [3, 2] matches one whose default was [3, 2]. The modules imported
    beside a case (``options.imports``) are how it was run, not what it is."""
    scene = {k: v for k, v in rec["scene"].items() if k != "name"}
    if "ancf" in scene and "quadrature" not in scene["ancf"] and rec.get("quadrature"):
        scene["ancf"] = {**scene["ancf"], "quadrature": rec["quadrature"]}
    case = rec.get("case") or {}
    options = {k: v for k, v in (case.get("options") or {}).items() if k != "imports"}
    solver = case.get("solver") or rec["solver"]          # the engine's solver (a record's label may be a backend's)
    solver = (rename or {}).get(solver, solver)
    return canonical(_rounded({"solver": solver, "scene": scene, "options": options}))


def read(path: Path, rename: dict | None = None) -> dict[str, dict]:
    out = {}
    if not path.exists():
        return out
    for line in path.read_text().splitlines():
        if line.strip():
            try:   # a torn or hand-edited line that is not a record is skipped, as the store does
                rec = json.loads(line)
                rec["scene"]["name"]
                out[key_of(rec, rename)] = rec
            except (json.JSONDecodeError, KeyError, TypeError, AttributeError, ValueError):
                continue
    return out


def _close(a, b, rtol: float, atol: float) -> bool:
    if a is None or b is None:
        return a is b
    return math.isclose(a, b, rel_tol=rtol, abs_tol=atol)


def _reason_class(r) -> str | None:
    return None if r is None else str(r).split(":")[0]


def compare(a: dict, b: dict, rtol: float, atol: float) -> list[str]:
    """What differs between two records of the same case."""
    out = []
    for k in ("status", "stable", "negative_eigenvalues", "ndof", "steps"):
        if a.get(k) != b.get(k) and not (k == "negative_eigenvalues" and (k not in a or k not in b)):
            out.append(f"{k} {a.get(k)!r} -> {b.get(k)!r}")
    if _reason_class(a.get("reason")) != _reason_class(b.get("reason")):
        out.append(f"reason {a.get('reason')!r} -> {b.get('reason')!r}")
    ta, tb = a.get("tip") or {}, b.get("tip") or {}
    for c in ("ux", "uy"):
        if not _close(ta.get(c), tb.get(c), rtol, atol):
            out.append(f"tip {c} {ta.get(c)!r} -> {tb.get(c)!r}")
    ha, hb = a.get("tip_history") or [], b.get("tip_history") or []
    if len(ha) != len(hb):
        out.append(f"tip_history length {len(ha)} -> {len(hb)}")
    else:
        worst = max((math.hypot(p["x"] - q["x"], p["y"] - q["y"]) for p, q in zip(ha, hb)), default=0.0)
        size = max((math.hypot(p["x"], p["y"]) for p in ha), default=0.0)
        if worst > rtol * size + atol:
            out.append(f"tip_history moved by up to {worst:.3g} m")
    ea, eb = a.get("energy") or [], b.get("energy") or []
    if len(ea) == len(eb):
        for p, q in zip(ea, eb):
            if not _close(p.get("total"), q.get("total"), rtol, atol):
                out.append(f"energy at t = {p.get('t')}: {p.get('total')!r} -> {q.get('total')!r}")
                break
    return out


def diff(old: Path, new: Path, rtol: float = 1e-6, atol: float = 1e-9,
         rename: dict | None = None) -> tuple[list[Change], dict]:
    """(the changes, {study: (matched, only old, only new, changed)}) over every study file;
    ``rename`` {old name: new name} of solvers and studies (a study's records file)."""
    rename = rename or {}
    changes, summary = [], {}
    olds = {rename.get(p.stem, p.stem): p for p in (Path(old) / "data").glob("*.jsonl")}
    names = sorted(set(olds) | {p.stem for p in (Path(new) / "data").glob("*.jsonl")})
    for study in names:
        a = read(olds[study], rename) if study in olds else {}
        b = read(Path(new) / "data" / f"{study}.jsonl")
        changed = 0
        for k in sorted(set(a) & set(b)):
            try:
                what = compare(a[k], b[k], rtol, atol)
            except (TypeError, AttributeError, KeyError, ValueError) as e:   # a field of the wrong type
                what = [f"cannot be compared (a malformed field: {type(e).__name__}: {e})"]
            if what:
                changed += 1
                changes.append(Change(study, a[k]["scene"]["name"], "; ".join(what)))
        for k in sorted(set(a) - set(b)):
            changes.append(Change(study, a[k]["scene"]["name"], "only in the old records"))
        for k in sorted(set(b) - set(a)):
            changes.append(Change(study, b[k]["scene"]["name"], "only in the new records"))
        summary[study] = (len(set(a) & set(b)), len(set(a) - set(b)), len(set(b) - set(a)), changed)
    return changes, summary
