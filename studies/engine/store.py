"""The record store: one JSON-lines file per study, ``<out>/data/<study>.jsonl``.

Each line is one record (a solver record plus ``case_id`` and ``case``), appended as
its case finishes and made durable at once (flush + fsync), so that a killed run keeps
every finished record. Reading skips a torn last line (a run killed mid-write) and keeps,
per case id, the line written last. :meth:`RecordStore.compact` rewrites the file
atomically with only the records of the current case list.
"""
from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Iterable

from contract.record import sanitize


class RecordStore:
    def __init__(self, path: str | Path):
        self.path = Path(path)
        self.skipped_lines = 0

    def read(self) -> dict[str, dict]:
        """{case id: latest record}; unreadable lines are counted in ``skipped_lines``."""
        out: dict[str, dict] = {}
        self.skipped_lines = 0
        if not self.path.exists():
            return out
        with open(self.path) as f:
            for line in f:
                if not line.strip():
                    continue
                try:
                    rec = json.loads(line)
                    out[rec["case_id"]] = rec
                except (json.JSONDecodeError, KeyError, TypeError):
                    self.skipped_lines += 1
        return out

    def append(self, rec: dict) -> dict:
        """Write one record (sanitised: no NaN, numpy made plain) durably; return it."""
        rec = sanitize(rec)
        line = json.dumps(rec, allow_nan=False, separators=(",", ":")) + "\n"
        self.path.parent.mkdir(parents=True, exist_ok=True)
        with open(self.path, "a") as f:
            # A torn line left by a killed writer must not swallow this record.
            if f.tell() > 0 and not self._ends_with_newline():
                f.write("\n")
            f.write(line)
            f.flush()
            os.fsync(f.fileno())
        return rec

    def _ends_with_newline(self) -> bool:
        with open(self.path, "rb") as f:
            f.seek(-1, os.SEEK_END)
            return f.read(1) == b"\n"

    def compact(self, keep: Iterable[str]) -> int:
        """Keep only the latest record of each id in ``keep`` (in that order); return
        how many lines were dropped."""
        keep = list(keep)
        recs = self.read()
        lines = sum(1 for _ in open(self.path)) if self.path.exists() else 0
        kept = [recs[i] for i in keep if i in recs]
        tmp = self.path.with_suffix(".jsonl.tmp")
        with open(tmp, "w") as f:
            for rec in kept:
                f.write(json.dumps(rec, allow_nan=False, separators=(",", ":")) + "\n")
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, self.path)
        return lines - len(kept)


def store_for(out_dir: str | Path, study: str) -> RecordStore:
    return RecordStore(Path(out_dir) / "data" / f"{study}.jsonl")
