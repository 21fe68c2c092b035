"""The study list: every study module's declaration read into :class:`Study` objects.

A study is one module ``studies/<group>/<module>.py`` (grouped by what it is for: ``paper``,
``design``, ``verification``) that declares itself with a module-level
``STUDY = {"name": ..., "title": ..., "grid": {...}, "tiny": {...}, "needs": [...],
"full": False}``: a name, a grid (with the ``tiny`` overrides merged in tiny mode), the
studies whose records it reads (``needs``), whether it is heavy (``full``: left out of
``make study``), and beside it two functions:

- ``cases(grid: dict, tiny: bool) -> list[Case]``: the grid expanded into cases;
- ``report(ctx: studies.engine.report.Context) -> studies.engine.report.Section``: tables and
  figures from records only.

A grid names its elements by the registry, never by a list of names: a value
``{"registered": {"tagged": ..., "without": [...], "running": [...], "except": {element:
why}}}`` becomes, when the catalog loads, the built-in elements and those of a study run's
``--import`` modules (:data:`IMPORTED`) that those tags and formulations select
(:func:`ancf.elements.select`), but those ``except`` leaves out with its reason; a ``tiny``
grid may list a few names.

Optionally ``gold_values(ctx) -> {name: (value, tolerance)}`` for the tiny-mode
regression (tests/gold/studies_tiny.json), and ``audit(ctx) -> [problem]``: the study's
own consistency rules, run by ``python -m studies audit`` (:mod:`.audit`).

:func:`load_catalog` finds the declaring modules by a text scan of ``studies/`` (only they
are imported), in path order. A TOML file of study tables (``--catalog FILE``: one table per study naming
its ``module``, ``[NAME.tiny]`` overrides, ``[common]`` keys every table gets) replaces the
list for a test or a one-off run; the project's own studies are declared in their modules
only.
"""
from __future__ import annotations

import importlib
import tomllib
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from types import ModuleType

CASES_TOML = None    # the default catalog: the studies declared in their modules (no file)
META_KEYS = ("module", "title", "needs", "tiny", "full")
COMMON = "common"   # not a study: grid keys every study gets unless it sets its own
# a grid value {"registered": {"tagged": ..., "without": [...], "running": [...]}}: the
# studied elements those tags and formulations select (:func:`registered`)
REGISTERED = "registered"
SELECT_KEYS = ("tagged", "without", "running", "except")
# the modules a study run imported so that their elements join its studies (``studies run
# --import``); an element another module registered (a card's) stays out of the studies
IMPORTED: list[str] = []


def studied_elements() -> list[str]:
    """The elements the studies take: the built-in ones and those the modules of
    :data:`IMPORTED` registered, in the registry's order."""
    from ancf.elements import BUILTIN, ELEMENTS

    return [n for n in ELEMENTS if n in BUILTIN or ELEMENTS.origin.get(n) in IMPORTED]


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
        try:
            return self.module.cases(self.grid, self.tiny)
        except KeyError as e:   # a hand-edited catalog without a key the study's grid needs
            raise ValueError(f"study {self.name!r}: its grid needs the key {e}") from None


STUDIES_DIR = Path(__file__).resolve().parent.parent


def declared_studies(folder: Path = STUDIES_DIR) -> dict[str, dict]:
    """{name: table} of the study modules that declare ``STUDY = {...}`` (found by a
    text scan of studies/*.py; only those modules are imported), as catalog tables."""
    out = {}
    for f in sorted(folder.rglob("*.py"), key=lambda p: p.relative_to(folder).parts):
        if not any(line.startswith("STUDY = ") for line in f.read_text().splitlines()):
            continue
        module = ".".join(f.relative_to(folder).with_suffix("").parts)
        decl = dict(importlib.import_module(f"studies.{module}").STUDY)
        name = decl.pop("name")
        grid = decl.pop("grid", {})
        out[name] = {"module": module, **grid, **decl}
    return out


def load_catalog(tiny: bool = False, path: Path | None = CASES_TOML) -> dict[str, Study]:
    """{name: Study}: the studies declared in their modules (:func:`declared_studies`), or
    the tables of the TOML file ``path`` in their order (a test's own case list)."""
    data = declared_studies() if path is None else _read(Path(path))
    common = data.pop(COMMON, {})
    out = {}
    for name, t in data.items():
        grid = {**common, **{k: v for k, v in t.items() if k not in META_KEYS}}
        if tiny:
            grid.update(t.get("tiny", {}))
        grid = registered(grid, name)
        needs = tuple(t.get("needs", ()))
        out[name] = Study(name, t.get("title", name), t["module"], grid, needs, tiny, bool(t.get("full", False)))
    for s in out.values():
        unknown = [n for n in s.needs if n not in out]
        if unknown:
            raise ValueError(f"{Path(path).name if path else 'studies'}: study {s.name!r} needs unknown {unknown}; "
                             f"studies: {', '.join(out)}")
    return out


def registered(value, where: str):
    """A grid with each ``{"registered": {...}}`` replaced by the names of the studied
    elements (:func:`studied_elements`) it selects (:func:`ancf.elements.select`: keys
    ``tagged``, ``without``, ``running``; ``except``: {element: why the study leaves it
    out}), read when the catalog loads: a study names its elements by their tags, never by
    a list of names."""
    if isinstance(value, dict) and set(value) == {REGISTERED}:
        from ancf.elements import ELEMENTS, select

        sel = dict(value[REGISTERED]) if isinstance(value[REGISTERED], dict) else value[REGISTERED]
        odd = sorted(set(sel) - set(SELECT_KEYS)) if isinstance(sel, dict) else [sel]
        if odd:
            raise ValueError(f"{where}.{REGISTERED}: unknown keys {odd}; allowed: {', '.join(SELECT_KEYS)}")
        # except: {element: why this study leaves it out} (a measured reason, never a list of members)
        left_out = sel.pop("except", {})
        if not (isinstance(left_out, dict) and all(n in ELEMENTS and isinstance(w, str) and w
                                                    for n, w in left_out.items())):
            raise ValueError(f"{where}.{REGISTERED}.except: {{element: why}} of registered elements, "
                             f"got {left_out!r}")
        try:
            studied = set(studied_elements())
            return [n for n in select(**sel) if n in studied and n not in left_out]
        except (TypeError, ValueError) as e:
            raise ValueError(f"{where}.{REGISTERED}: {e}") from None
    if isinstance(value, dict):
        return {k: registered(v, f"{where}.{k}") for k, v in value.items()}
    return value


def _read(path: Path) -> dict:
    """The catalog file as checked tables (a ValueError naming the file and the key
    for anything else: unreadable, not TOML, nested too deep, a study without a module)."""
    from contract.scene import check_nesting
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as e:
        raise ValueError(f"--catalog: cannot read {path} ({getattr(e, 'strerror', None) or e})") from None
    except tomllib.TOMLDecodeError as e:
        raise ValueError(f"--catalog: {path}: not valid TOML: {e}") from None
    except RecursionError:
        raise ValueError(f"--catalog: {path}: arrays or inline tables nested hundreds of levels deep") from None
    check_nesting(data, path.name)
    for name, t in data.items():
        if not isinstance(t, dict):
            raise ValueError(f"{path.name}: {name}: must be a table ([{name}]) of a study's grid")
        if name == COMMON:
            continue
        if not isinstance(t.get("module"), str) or not all(p.isidentifier() for p in t["module"].split(".")):
            raise ValueError(f"{path.name}: {name}.module: must name a module of studies/ "
                             f"(e.g. \"table3\"), got {t.get('module')!r}")
        for key, kind, what in (("title", str, "a string"), ("full", bool, "true or false"),
                                ("tiny", dict, "a table of grid overrides")):
            if key in t and not isinstance(t[key], kind):
                raise ValueError(f"{path.name}: {name}.{key}: must be {what}, got {t[key]!r}")
        needs = t.get("needs", [])
        if not isinstance(needs, list) or not all(isinstance(n, str) for n in needs):
            raise ValueError(f"{path.name}: {name}.needs: must be a list of study names, got {needs!r}")
    return data


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
