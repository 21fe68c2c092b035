"""The one migration of the records' fingerprints to the multiset of statements
(:mod:`studies.engine.fingerprint`, :mod:`contract.source`), recomputing nothing.

Run once, on the code whose records are committed (no solver code changed since they
were made): for every engine record under ``reports/data`` it takes the record's own case
(solver, scene, options), computes the case's id under the former scheme (each reached
module's whole normalised text, keyed by the module's name) and under the new one, and
re-keys the record from the old id to the new one only where the old id is the record's
own, so that only a record that is current for this code is carried over; a card's checks
record (``card-*-checks.json``) gets its ``source`` digest the same way. It prints, per
file, how many records it carried over and how many it left (stale, or not an engine
record), and changes nothing else in a line. Once it has run, the records carry the new ids
and a second run finds nothing to carry over (it says so per file).

    .venv/bin/python tools/migrations/fingerprint_v2.py [--dry-run]
"""
from __future__ import annotations

import ast
import hashlib
import json
import sys
from functools import lru_cache
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from contract.source import normalised  # noqa: E402
from studies.engine import case as case_mod  # noqa: E402
from studies.engine import fingerprint as fp  # noqa: E402


def _v1_text(key: str) -> str:
    """The former scheme's text of one key: a whole module's normalised source, or a
    by-name definition's normalised statements joined by newlines."""
    module, _, name = key.partition(":")
    path = fp._path(module)
    if not name:
        return normalised(path.read_text(encoding="utf-8"))
    defs = [fp._unannotated(s) for s in fp._tree(path).body if fp._binds(s, name)]
    return "\n".join(normalised(ast.unparse(s)) for s in defs)


_v2 = fp._fingerprint.__wrapped__


def _v1(entries, exclude, whole=False):
    r = fp._read(entries, exclude, whole)
    h = hashlib.sha256()
    for key in sorted(r.code):
        h.update(key.encode() + b"\0" + _v1_text(key).encode() + b"\0")
    return h.hexdigest(), tuple(fp.packages(r.third_party).items())


_CACHED = {_v1: lru_cache(maxsize=None)(_v1), _v2: lru_cache(maxsize=None)(_v2)}


def _use(scheme) -> None:
    fp._fingerprint = _CACHED[scheme]


def _ids(solver: str, scene_json: str, options_json: str) -> tuple[str, str]:
    _use(_v1)
    old = case_mod._fresh_id(solver, scene_json, options_json)
    _use(_v2)
    new = case_mod._fresh_id(solver, scene_json, options_json)
    return old, new


def _cases() -> list:
    """Every case of every study (the full ones too) and of every recorded card."""
    from studies.design.card import recorded_cards
    from studies.design.card_cases import cases as card_cases
    from studies.engine.catalog import load_catalog

    out = []
    for study in load_catalog().values():
        out += study.cases()
    for element, tiny in recorded_cards(ROOT / "reports", stale=[]):
        out += card_cases(element, tiny)
    return out


def main(dry_run: bool) -> int:
    from studies.design import card_cases

    renamed = {}
    _use(_v1)                                   # the cases as the committed records know them
    for c in _cases():
        old, new = _ids(c.solver, c.scene_json, c.options_json)
        if old != c.id:
            raise SystemExit(f"case {c.name}: the engine's id {c.id} is not the former scheme's {old}")
        renamed[old] = new
    print(f"{len(renamed)} cases")
    data = ROOT / "reports" / "data"
    for path in sorted(data.glob("*.jsonl")):
        lines = path.read_text().splitlines(keepends=True)
        out, carried, left = [], 0, 0
        for line in lines:
            try:
                old = json.loads(line)["case_id"]
            except (json.JSONDecodeError, KeyError, TypeError):
                old = None
            if old in renamed:
                line = line.replace(old, renamed[old])
                carried += 1
            else:
                left += 1
            out.append(line)
        print(f"{path.name}: {carried} carried over, {left} left")
        if not dry_run:
            path.write_text("".join(out))
    for path in sorted(data.glob("card-*-checks.json")):
        text = path.read_text()
        _use(_v1)
        old = card_cases.checks_source()
        _use(_v2)
        new = card_cases.checks_source()
        ok = json.loads(text).get("source") == old
        print(f"{path.name}: {'carried over' if ok else 'left (stale)'}")
        if ok and not dry_run:
            path.write_text(text.replace(old, new))
    return 0


if __name__ == "__main__":
    sys.exit(main("--dry-run" in sys.argv[1:]))
