"""The record store: one JSON-lines file per study, ``<out>/data/<study>.jsonl``.

Each line is one record (a solver record plus ``case_id`` and ``case``), appended as
its case finishes and made durable at once (flush + fsync), so that a killed run keeps
every finished record. Reading skips a torn last line (a run killed mid-write) and keeps,
per case id, the line written last. :meth:`RecordStore.compact` rewrites the file
atomically with only the records of the current case list. :meth:`RecordStore.lock` is
the study's lock (``flock`` on ``<study>.lock`` beside the records, released by the
kernel however its holder ends): a second runner on the same study waits for the first,
says so on stderr, and then reuses its records.
"""
from __future__ import annotations

import fcntl
import json
import os
import sys
from contextlib import contextmanager
from pathlib import Path
from typing import Iterable, Iterator

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


    @property
    def lock_path(self) -> Path:
        return self.path.with_suffix(".lock")

    @contextmanager
    def lock(self, note=lambda msg: print(msg, file=sys.stderr, flush=True)) -> Iterator[None]:
        """Hold the study's lock for the block; wait (saying so through ``note``) while
        another process holds it. The file holds the holder's pid, for that message."""
        self.path.parent.mkdir(parents=True, exist_ok=True)
        fd = os.open(self.lock_path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                holder = os.pread(fd, 32, 0).decode(errors="replace").strip() or "?"
                note(f"studies: {self.path.stem}: another runner (pid {holder}) is computing these records; "
                     f"waiting for it to finish, then its records are reused")
                t0 = os.times().elapsed
                fcntl.flock(fd, fcntl.LOCK_EX)
                note(f"studies: {self.path.stem}: the other runner is done (waited "
                     f"{os.times().elapsed - t0:.1f} s); going on")
            os.ftruncate(fd, 0)
            os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
            yield
        finally:
            os.close(fd)   # releases the lock


def store_for(out_dir: str | Path, study: str) -> RecordStore:
    return RecordStore(Path(out_dir) / "data" / f"{study}.jsonl")
