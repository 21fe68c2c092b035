"""The study list: ``studies/cases.toml`` read into :class:`Study` objects.

A study is a name, a grid (its table of cases.toml, with the ``[NAME.tiny]`` overrides
merged in tiny mode, over the keys of the ``[common]`` table that every study shares),
the studies whose records it reads (``needs``), and a module
(``studies/<module>.py``) with two functions:

- ``cases(grid: dict, tiny: bool) -> list[Case]``: the grid expanded into cases;
- ``report(ctx: studies.engine.report.Context) -> studies.engine.report.Section``: tables and
  figures from records only.

Optionally ``gold_values(ctx) -> {name: (value, tolerance)}`` for the tiny-mode
regression (tests/gold/studies_tiny.json), and ``audit(ctx) -> [problem]``: the study's
own consistency rules, run by ``python -m studies audit`` (:mod:`.audit`).

The registry: a study is either a table of cases.toml naming its module, or one file
``studies/<module>.py`` that declares itself with a module-level ``STUDY = {"name": ...,
"title": ..., "grid": {...}, "tiny": {...}, "needs": [...], "full": False}`` beside its
``cases``, ``report`` (and optional ``gold_values``, ``audit``): :func:`load_catalog` finds
such files (a text scan, no import) and appends them after the cases.toml studies; ``list``,
``run``, ``report`` and ``audit`` see them like any other.
"""
from __future__ import annotations

import importlib
import tomllib
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from types import ModuleType

CASES_TOML = Path(__file__).resolve().parent.parent / "cases.toml"
META_KEYS = ("module", "title", "needs", "tiny", "full")
COMMON = "common"   # not a study: grid keys every study gets unless it sets its own


@dataclass(frozen=True)
class Study:
    name: str
    title: str
    module_name: str
    grid: dict
    needs: tuple[str, ...]
    tiny: bool
    full: bool = False      # heavy: left out of "all" (``make study``) unless tiny; run when named

    @property
    def in_all(self) -> bool:
        """Is this study part of ``run all``? Every study in tiny mode; outside it, not a
        ``full = true`` one (``make study-full`` names those)."""
        return self.tiny or not self.full

    @cached_property
    def module(self) -> ModuleType:
        return importlib.import_module(f"studies.{self.module_name}")

    def cases(self) -> list:
        return self.module.cases(self.grid, self.tiny)


STUDIES_DIR = CASES_TOML.parent


def declared_studies(folder: Path = STUDIES_DIR) -> dict[str, dict]:
    """{name: table} of the study modules that declare ``STUDY = {...}`` (found by a
    text scan of studies/*.py; only those modules are imported), as cases.toml tables."""
    out = {}
    for f in sorted(folder.glob("*.py")):
        if not any(line.startswith("STUDY = ") for line in f.read_text().splitlines()):
            continue
        decl = dict(importlib.import_module(f"studies.{f.stem}").STUDY)
        name = decl.pop("name")
        grid = decl.pop("grid", {})
        out[name] = {"module": f.stem, **grid, **decl}
    return out


def load_catalog(tiny: bool = False, path: Path = CASES_TOML) -> dict[str, Study]:
    """{name: Study}: the tables of ``path`` in their order, then (for the default
    cases.toml) the studies declared in their own module (:func:`declared_studies`)."""
    data = tomllib.loads(Path(path).read_text())
    common = data.pop(COMMON, {})
    # (a test's own case list stands alone)
    for name, t in (declared_studies().items() if Path(path) == CASES_TOML else ()):
        if name in data:
            raise ValueError(f"study {name!r}: declared both in {Path(path).name} and in studies/{t['module']}.py")
        data[name] = t
    out = {}
    for name, t in data.items():
        grid = {**common, **{k: v for k, v in t.items() if k not in META_KEYS}}
        if tiny:
            grid.update(t.get("tiny", {}))
        needs = tuple(t.get("needs", ()))
        out[name] = Study(name, t.get("title", name), t["module"], grid, needs, tiny, bool(t.get("full", False)))
    for s in out.values():
        unknown = [n for n in s.needs if n not in out]
        if unknown:
            raise ValueError(f"{CASES_TOML.name}: study {s.name!r} needs unknown {unknown}; "
                             f"studies: {', '.join(out)}")
    return out


def get_study(catalog: dict[str, Study], name: str) -> Study:
    try:
        return catalog[name]
    except KeyError:
        raise ValueError(f"study: unknown {name!r}; allowed: {', '.join(catalog)}, all") from None


def with_needs(catalog: dict[str, Study], names: list[str]) -> list[Study]:
    """The named studies preceded by the ones they need, each once, in file order."""
    want: set[str] = set()

    def add(n: str) -> None:
        if n not in want:
            want.add(n)
            for m in get_study(catalog, n).needs:
                add(m)

    for n in names:
        add(n)
    return [s for n, s in catalog.items() if n in want]
