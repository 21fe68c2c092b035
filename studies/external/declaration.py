"""An external solver's declaration: one small TOML file that says how to run it and what
scenes it takes.

.. code-block:: toml

    [solver]
    name = "mysolver"                     # its records' solver name: letters, digits, - _ .
    version = "1.4.2"                     # your solver's version: a record is redone when it changes
    element = "MyCable"                   # its own element, if it ignores ancf.element (optional)
    command = ["mysolver", "run", "{scene}", "--json", "{out}"]   # or:
    # python = "mypackage.harness:run"    # a function scene dict -> record dict
    adapter = ["adapter.py"]              # files between the harness and your code (optional)
    wall_time = 120.0                     # s per run; past it the run is stopped: failed
    scene_format = "toml"                 # what {scene} is: "toml" or "json"

    [supports]                            # what the solver takes; any other scene is skipped
    analysis = ["static", "dynamic"]      # with the reason, never run
    integrators = ["generalized-alpha", "newmark"]
    laws = ["neo-hookean", "yeoh"]
    formulations = ["plane-stress"]
    supports = ["clamp", "pin"]
    loads = ["gravity", "tip_force"]

    [causes]                              # why it misses a benchmark kind, as you measured it
    Timoshenko = "Euler-Bernoulli: no shear deformation"

A key of ``[supports]`` left out takes every value. A solver with an element of its own
(``element``) runs it whatever ``ancf.element`` a case names: the harness gives it its
element's name there, and cases that differ only in the element run once. ``{scene}`` and ``{out}`` are replaced
by a scene file the harness writes and the record file the solver must write; paths in
``command`` that start with ``./`` or ``../``, and relative ``adapter`` paths, are relative
to the declaration's folder.
A bad declaration stops with one message naming the key and the allowed values.
"""
from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from contract.errors import SceneError
from contract.scene import ANALYSES, SUPPORTS, keys_of

LOADS = tuple(k.name for k in keys_of("loads"))    # the scene's load keys
SCENE_FORMATS = ("toml", "json")
FEATURES = ("analysis", "integrators", "laws", "formulations", "supports", "loads")
SOLVER_KEYS = ("name", "version", "element", "command", "python", "adapter", "wall_time", "scene_format")
NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.-]*$")


@dataclass(frozen=True)
class Declaration:
    name: str
    version: str
    path: Path                              # the declaration file
    command: tuple[str, ...] = ()
    python: str | None = None
    adapter: tuple[Path, ...] = ()
    wall_time: float = 300.0
    scene_format: str = "toml"
    # the solver's own element, where it ignores the scene's ancf.element (None: it runs the
    # element the scene names)
    element: str | None = None
    # feature -> the values taken (None: every value)
    supports: dict = field(default_factory=dict, hash=False)
    # a benchmark case kind (its first word: elastica, Timoshenko, ...) -> why the solver
    # misses it, as measured (the report says "cause not found" for a miss without one)
    causes: dict = field(default_factory=dict, hash=False)

    @property
    def text(self) -> dict:
        """The declaration as parsed (comments and layout do not count)."""
        return tomllib.loads(self.path.read_text(encoding="utf-8"))


def _fail(key: str, what: str) -> SceneError:
    return SceneError(f"{key}: {what}")


def _strings(value, key: str) -> tuple[str, ...]:
    if not (isinstance(value, list) and value and all(isinstance(v, str) and v for v in value)):
        raise _fail(key, f"a non-empty list of strings, got {value!r}")
    return tuple(value)


def _local(base: Path, item: str) -> str:
    """``item`` beside the declaration if it starts with ./ or ../ (symbolic links kept: a
    venv's python is one), else as it is."""
    import os

    return os.path.normpath(base / item) if item.startswith(("./", "../")) else item


def load_declaration(path: str | Path) -> Declaration:
    """The declaration in ``path``, checked (a SceneError names the key)."""
    path = Path(path).resolve()
    try:
        d = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise SceneError(f"declaration: no file {path}") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as e:
        raise SceneError(f"declaration: {path} is not TOML ({e})") from None
    for table in d:
        if table not in ("solver", "supports", "causes"):
            raise _fail(table, "unknown table; allowed: 'solver', 'supports', 'causes'")
    s = d.get("solver")
    if not isinstance(s, dict):
        raise _fail("solver", "the declaration has no [solver] table (name, version, command or python)")
    for k in s:
        if k not in SOLVER_KEYS:
            raise _fail(f"solver.{k}", f"unknown key; allowed: {', '.join(repr(x) for x in SOLVER_KEYS)}")
    name = s.get("name")
    if not (isinstance(name, str) and NAME.match(name)):
        raise _fail("solver.name", f"letters, digits and - _ . (the records' solver name), got {name!r}")
    version = s.get("version")
    if not (isinstance(version, str) and version):
        raise _fail("solver.version", f"the solver's version as a string (a record is redone when it changes), "
                                      f"got {version!r}")
    if ("command" in s) == ("python" in s):
        raise _fail("solver.command", "give exactly one of solver.command (a command line) and solver.python "
                                      "(module:function)")
    base = path.parent
    command: tuple[str, ...] = ()
    if "command" in s:
        command = tuple(_local(base, c) for c in _strings(s["command"], "solver.command"))
        if not any("{out}" in c for c in command):
            raise _fail("solver.command", "must contain {out}, the record file the solver writes")
        if not any("{scene}" in c for c in command):
            raise _fail("solver.command", "must contain {scene}, the scene file the solver reads")
    python = s.get("python")
    if python is not None and not (isinstance(python, str) and re.match(r"^[\w.]+:[\w]+$", python)):
        raise _fail("solver.python", f"'module:function' (a function scene dict -> record dict), got {python!r}")
    adapter = tuple(a if a.is_absolute() else (base / a).resolve()
                    for a in map(Path, _strings(s["adapter"], "solver.adapter"))) if "adapter" in s else ()
    for a in adapter:
        if not a.is_file():
            raise _fail("solver.adapter", f"no file {a}")
    wall = s.get("wall_time", Declaration.wall_time)
    if not (isinstance(wall, (int, float)) and not isinstance(wall, bool) and wall > 0):
        raise _fail("solver.wall_time", f"a positive number of seconds, got {wall!r}")
    fmt = s.get("scene_format", "toml")
    if fmt not in SCENE_FORMATS:
        raise _fail("solver.scene_format", f"one of {', '.join(repr(f) for f in SCENE_FORMATS)}, got {fmt!r}")
    element = s.get("element")
    if element is not None and not (isinstance(element, str) and element):
        raise _fail("solver.element", f"the name of the solver's own element, got {element!r}")
    causes = d.get("causes", {})
    if not (isinstance(causes, dict) and all(isinstance(v, str) and v for v in causes.values())):
        raise _fail("causes", f"a table of benchmark case kinds and why the solver misses them, got {causes!r}")
    return Declaration(name, version, path, command, python, adapter, float(wall), fmt, element,
                       _supports(d.get("supports", {})), causes)


def _allowed(feature: str) -> tuple[str, ...] | None:
    """The values a feature may name (None: any registered name, e.g. a user's law)."""
    return {"analysis": ANALYSES, "supports": SUPPORTS, "loads": LOADS}.get(feature)


def _supports(t) -> dict:
    if not isinstance(t, dict):
        raise _fail("supports", f"a table, got {t!r}")
    out = {}
    for k, v in t.items():
        if k not in FEATURES:
            raise _fail(f"supports.{k}", f"unknown key; allowed: {', '.join(repr(f) for f in FEATURES)}")
        values = _strings(v, f"supports.{k}")
        allowed = _allowed(k)
        for x in values:
            if allowed is not None and x not in allowed:
                raise _fail(f"supports.{k}", f"unknown value {x!r}; allowed: {', '.join(repr(a) for a in allowed)}")
        out[k] = frozenset(values)
    return out


def unsupported(decl: Declaration, scene: dict) -> str | None:
    """Why the solver does not take ``scene`` (a scene dict), or None if it does."""
    s = decl.supports
    material, loads = scene.get("material") or {}, scene.get("loads") or {}
    asked = {
        "analysis": [(scene.get("analysis") or {}).get("kind")],
        "integrators": [(scene.get("analysis") or {}).get("integrator", "generalized-alpha")]
        if (scene.get("analysis") or {}).get("kind") == "dynamic" else [],
        "laws": [material.get("law")],
        "formulations": [material.get("formulation")],
        "supports": [(scene.get("supports") or {}).get("left")],
        "loads": [k for k in LOADS if loads.get(k) is not None],
    }
    for feature, values in asked.items():
        taken = s.get(feature)
        for v in values:
            if taken is not None and v is not None and v not in taken:
                return (f"{decl.name} does not take {feature} {v!r} (its declaration's supports.{feature}: "
                        f"{', '.join(sorted(taken))})")
    return None
