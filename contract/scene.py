"""Scene files (TOML, SI units): load, validate, and describe one simulation.

The contract both solvers read: the structure and types of a scene are checked here
(unknown or missing keys, wrong types, non-finite or non-positive sizes stop with a
:class:`SceneError` naming the field and the allowed values). The names a solver
resolves (element, law and its constants, formulation, integrator) are kept as
strings and checked by each solver's ``check`` against its own registries
(:func:`ancf.build.check`, :func:`reference_fem.simulation.check`), so this module imports no
solver. Each solver ignores the other's table (``[ancf]``, ``[fem]``).

Every key this module reads is declared once, in :data:`KEYS` (its table, what it
accepts, its unit, its default and for which analysis): the parser takes each table's
required and optional keys from there and the dataclasses their defaults, and the
documentation's scene reference is drawn from it (the ``[fem]`` table's keys are
``reference_fem.settings``'s).
"""
from __future__ import annotations

import hashlib
import json
import math
import re
import tomllib
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Collection, Mapping

from .errors import SceneError, UnknownName
from .loads import SUPPORTS as _SUPPORT_MEANINGS

SUPPORTS = tuple(_SUPPORT_MEANINGS)   # what each is: contract.loads.SUPPORTS
CLAMPS = ("face", "all")
ANALYSES = ("static", "dynamic")
NEWTON = ("chord", "full", "modified", "linear")   # the compiled time loop's Newton (ancf.solvers.compiled_steps)
# Sane ranges: a tolerance outside them answers a different question (1e10 "converges"
# at the first residual) or none (below round-off Newton never stops).
NEWTON_RTOL = (1e-15, 1e-3)
MAX_ITERATIONS = 1000
MAX_LOAD_STEPS = 10 ** 6
MAX_STEPS = 10 ** 7          # default bound of a dynamic run's accepted steps
MAX_GAUSS = 64               # Gauss points per direction (exact to degree 127)
MAX_NESTING = 32             # tables and arrays inside one another (a scene uses at most 3)
# The scene language's formulations and whether a scene in that formulation carries a
# penalty (material.penalty): the one statement both solvers and the paper's scenes read.
FORMULATIONS = {"paper": True, "plane-strain": True, "plane-stress": False}


# -- every key, declared once --------------------------------------------------------------
REQUIRED = "required"   # a key's default when the file must give it


@dataclass(frozen=True)
class Key:
    """One key of a scene file.

    ``table``: "" for the top level; ``accepts``: what the parser admits, as (kind,
    arguments): ("text",), ("name",) (a non-empty string; ("name", what): one a solver
    resolves against its registry of ``what``: law, formulation, element, integrator), ("table",),
    ("number",) (finite), ("positive",), ("positive int",), ("range", lo, hi) and
    ("int range", lo, hi) (inclusive), ("choice", allowed), ("vector",) ([x, y]),
    ("rule",) ([points along x, across the thickness], each in [1, MAX_GAUSS]),
    ("times",) (rising, within [0, t_end]), ("limit",) (positive, or "inf"); ``unit``: SI;
    ``default``: :data:`REQUIRED`, None (unset: the solver's rule applies) or the value;
    ``analysis``: "static" or "dynamic" for a key of one kind of analysis only."""

    table: str
    name: str
    accepts: tuple
    unit: str = ""
    default: Any = REQUIRED
    analysis: str = ""


KEYS = (
    Key("", "name", ("name",)),
    Key("", "description", ("text",), default=None),
    Key("", "beam", ("table",)),
    Key("", "material", ("table",)),
    Key("", "ancf", ("table",), default=None),
    Key("", "supports", ("table",)),
    Key("", "loads", ("table",), default=None),
    Key("", "analysis", ("table",)),
    Key("", "fem", ("table",), default=None),
    Key("beam", "length", ("positive",), "m"),
    Key("beam", "height", ("positive",), "m"),
    Key("beam", "width", ("positive",), "m"),
    # and the law's constants by name (C10, mu, ...): which ones, the law says
    Key("material", "law", ("name", "law")),
    Key("material", "formulation", ("name", "formulation")),
    Key("material", "density", ("positive",), "kg/m^3"),
    Key("material", "penalty", ("positive",), "Pa", None),
    Key("ancf", "element", ("name", "element")),
    Key("ancf", "elements", ("positive int",)),
    Key("ancf", "quadrature", ("rule",), "", None),
    Key("supports", "left", ("choice", SUPPORTS)),
    Key("supports", "clamp", ("choice", CLAMPS), "", "face"),
    Key("loads", "gravity", ("vector",), "m/s^2", None),
    Key("loads", "tip_force", ("vector",), "N", None),
    Key("loads", "end_moment", ("number",), "N m", None, "static"),
    Key("analysis", "kind", ("choice", ANALYSES)),
    Key("analysis", "load_steps", ("int range", 1, MAX_LOAD_STEPS), "", 10, "static"),
    Key("analysis", "newton_rtol", ("range", *NEWTON_RTOL), "", 1e-8),
    Key("analysis", "max_iterations", ("int range", 1, MAX_ITERATIONS), "", 25),
    Key("analysis", "wall_time", ("positive",), "s", None),
    Key("analysis", "t_end", ("positive",), "s", REQUIRED, "dynamic"),
    Key("analysis", "dt", ("positive",), "s", REQUIRED, "dynamic"),
    Key("analysis", "dt_min", ("positive",), "s", None, "dynamic"),
    Key("analysis", "tolerance", ("positive",), "", None, "dynamic"),
    Key("analysis", "output_times", ("times",), "s", None, "dynamic"),
    Key("analysis", "integrator", ("name", "integrator"), "", "generalized-alpha", "dynamic"),
    Key("analysis", "rho_inf", ("range", 0.0, 1.0), "", 0.5, "dynamic"),
    Key("analysis", "energy_limit", ("limit",), "J", None, "dynamic"),
    Key("analysis", "max_steps", ("positive int",), "", None, "dynamic"),
    Key("analysis", "newton", ("choice", NEWTON), "", "chord", "dynamic"),
)


def keys_of(table: str, analysis: str | None = None) -> tuple[Key, ...]:
    """The keys of one table (of [analysis]: those of one kind of analysis)."""
    return tuple(k for k in KEYS if k.table == table
                 and (analysis is None or k.analysis in ("", analysis)))


def _required(table: str, analysis: str | None = None) -> set[str]:
    return {k.name for k in keys_of(table, analysis) if k.default is REQUIRED}


def _optional(table: str, analysis: str | None = None) -> set[str]:
    return {k.name for k in keys_of(table, analysis) if k.default is not REQUIRED}


def _default(table: str, name: str):
    return next(k.default for k in KEYS if k.table == table and k.name == name)


STATIC_KEYS = tuple(k.name for k in keys_of("analysis", "static"))
DYNAMIC_KEYS = tuple(k.name for k in keys_of("analysis", "dynamic"))


@dataclass(frozen=True)
class Beam:
    length: float  # m, along x
    height: float  # m, in plane (bending direction)
    width: float   # m, out of plane


@dataclass(frozen=True)
class MaterialSpec:
    law: str
    formulation: str
    density: float                       # kg/m^3
    constants: dict = field(hash=False)  # Pa, by name (C10, C01, C20, C30)
    penalty: float | None = None         # Pa


@dataclass(frozen=True)
class AncfSettings:
    element: str
    elements: int
    quadrature: tuple[int, int] | None = None  # Gauss points along x, across the thickness;
                                               # None: the element's default (ancf.checks.rank)


@dataclass(frozen=True)
class Supports:
    left: str
    clamp: str | None = None  # "face" | "all" when left = "clamp"


@dataclass(frozen=True)
class Loads:
    gravity: tuple[float, float] | None = None    # m/s^2
    tip_force: tuple[float, float] | None = None  # N
    end_moment: float | None = None               # N m, counter-clockwise (contract.loads)


@dataclass(frozen=True)
class Analysis:
    kind: str
    # static
    load_steps: int = _default("analysis", "load_steps")
    newton_rtol: float = _default("analysis", "newton_rtol")
    max_iterations: int = _default("analysis", "max_iterations")
    # dynamic
    t_end: float | None = None
    dt: float | None = None
    dt_min: float | None = None
    tolerance: float | None = None
    output_times: tuple[float, ...] | None = None
    integrator: str = _default("analysis", "integrator")
    rho_inf: float = _default("analysis", "rho_inf")
    energy_limit: float | None = None  # J; None: 1e-3 m |g| L / 2 (with gravity); inf: no check
    max_steps: int | None = None       # None: MAX_STEPS
    newton: str = _default("analysis", "newton")   # one of NEWTON: chord (measured fastest), full, modified, linear (one solve per step)
    # both
    wall_time: float | None = None     # s; a run still going then stops, status "failed"


@dataclass(frozen=True)
class Scene:
    name: str
    beam: Beam
    material: MaterialSpec
    ancf: AncfSettings | None
    supports: Supports
    loads: Loads
    analysis: Analysis
    fem: dict | None = field(default=None, hash=False)  # validated by reference_fem

    def to_dict(self) -> dict:
        """The scene in its file's shape (defaults filled in, unset keys left out), so
        that ``scene_from_dict(scene.to_dict())`` gives the same scene back."""
        d = asdict(self)
        material = d["material"]
        material.update(material.pop("constants"))
        analysis = {k: v for k, v in d["analysis"].items()
                    if k in (STATIC_KEYS if self.analysis.kind == "static" else DYNAMIC_KEYS)}
        d["analysis"] = analysis
        d["supports"] = {k: v for k, v in d["supports"].items() if v is not None}
        out = {k: v for k, v in d.items() if v is not None}
        out["material"] = {k: v for k, v in material.items() if v is not None}
        out["analysis"] = {k: v for k, v in analysis.items() if v is not None}
        out["loads"] = {k: v for k, v in d["loads"].items() if v is not None}
        if out.get("ancf"):
            out["ancf"] = {k: v for k, v in out["ancf"].items() if v is not None}
        if out["analysis"].get("energy_limit") == math.inf:
            out["analysis"]["energy_limit"] = "inf"       # JSON has no infinity; the loader takes "inf"
        return json.loads(json.dumps(out))  # tuples -> lists, plain JSON types

    def digest(self) -> str:
        """A stable hash of the scene's content (sha256 of its canonical JSON)."""
        return hashlib.sha256(json.dumps(self.to_dict(), sort_keys=True).encode()).hexdigest()


# ---------------------------------------------------------------------------------------
def load_scene(path: str | Path) -> Scene:
    path = Path(path)
    try:
        data = tomllib.loads(path.read_bytes().decode("utf-8"))
    except FileNotFoundError:
        raise SceneError(f"scene file not found: {path}") from None
    except IsADirectoryError:
        raise SceneError(f"{path}: is a directory, not a scene file") from None
    except PermissionError:
        raise SceneError(f"{path}: not readable (permission denied)") from None
    except OSError as e:
        raise SceneError(f"{path}: cannot be read ({e.strerror or e})") from None
    except UnicodeDecodeError as e:
        raise SceneError(f"{path}: not UTF-8 text (byte {e.start}); a scene file is TOML in UTF-8") from None
    except tomllib.TOMLDecodeError as e:
        raise SceneError(f"{path}: not valid TOML: {e}") from None
    except RecursionError:   # tomllib parses nested arrays / inline tables recursively
        raise SceneError(f"{path}: {_too_deep('arrays or inline tables nested hundreds of levels deep')}") from None
    return scene_from_dict(data)


def _too_deep(what: str) -> str:
    return (f"{what}; at most {MAX_NESTING} levels are allowed "
            f"(a scene's tables hold numbers, strings and short lists)")


def check_nesting(data: Any, where: str = "scene", limit: int = MAX_NESTING) -> None:
    """Refuse values nested more than ``limit`` tables / arrays deep (a SceneError naming
    the first key path that goes too deep), without recursion: a document nested a few
    thousand levels would otherwise end in a RecursionError wherever it is next walked
    (repr in an error message, JSON, a hash)."""
    stack = [(data, where, 0)]
    while stack:
        value, path, depth = stack.pop()
        if isinstance(value, Mapping):
            children = ((f"{path}.{k}" if path else str(k), v) for k, v in value.items())
        elif isinstance(value, (list, tuple)):
            children = ((f"{path}[{i}]", v) for i, v in enumerate(value))
        else:
            continue
        if depth >= limit:
            shown = path if len(path) <= 80 else path[:60] + "..." + path[-17:]
            raise SceneError(f"{shown}: {_too_deep(f'more than {limit} levels of tables or arrays')}")
        stack.extend((v, p, depth + 1) for p, v in children if isinstance(v, (Mapping, list, tuple)))


def scene_from_dict(data: Mapping[str, Any]) -> Scene:
    if not isinstance(data, Mapping):
        raise SceneError(f"scene: must be a table of keys, got {type(data).__name__}")
    check_nesting(data, "")
    _keys("scene", data, required=_required(""), optional=_optional(""))
    name = data["name"]
    if not isinstance(name, str) or not name.strip():
        raise SceneError(f"name: must be a non-empty string, got {name!r}")
    if "description" in data and not isinstance(data["description"], str):
        raise SceneError(f"description: must be a string (free text), got {data['description']!r}")
    analysis = _analysis(_table(data, "analysis"))
    loads = _loads(_table(data, "loads")) if "loads" in data else Loads()
    if loads.end_moment is not None and analysis.kind != "static":
        raise SceneError("loads.end_moment: a static load only (the couple's rotation is followed along the "
                         "load path, contract.loads); allowed with analysis.kind = \"static\"")
    return Scene(
        name=name,
        beam=_beam(_table(data, "beam")),
        material=_material(_table(data, "material")),
        ancf=_ancf(_table(data, "ancf")) if "ancf" in data else None,
        supports=_supports(_table(data, "supports")),
        loads=loads,
        analysis=analysis,
        fem=dict(_table(data, "fem")) if "fem" in data else None,
    )


def _table(data, key) -> Mapping:
    t = data[key]
    if not isinstance(t, Mapping):
        raise SceneError(f"{key}: must be a table ([{key}])")
    return t


def _keys(where, table, required=frozenset(), optional=frozenset(), allowed: str | None = None):
    missing = sorted(set(required) - set(table))
    if missing:
        raise SceneError(f"{where}: missing key(s) {missing}")
    unknown = sorted(set(table) - set(required) - set(optional))
    if unknown:
        allowed = allowed or ", ".join(sorted(set(required) | set(optional)))
        raise SceneError(f"{where}: unknown key(s) {unknown}; allowed: {allowed}")


def _positive(field_, value, kind=float):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or (kind is int and not isinstance(value, int)):
        raise SceneError(f"{field_}: must be a positive {'integer' if kind is int else 'number'}, got {value!r}")
    if not value > 0 or value != value or value == float("inf"):
        raise SceneError(f"{field_}: must be positive and finite, got {value!r}")
    return kind(value)


def _number(field_, value):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or value != value or abs(value) == float("inf"):
        raise SceneError(f"{field_}: must be a finite number, got {value!r}")
    return float(value)


def _choice(field_, value, allowed):
    if value not in allowed:
        raise UnknownName(field_, value, allowed)
    return value


def _vector(field_, value):
    if not isinstance(value, list) or len(value) != 2:
        raise SceneError(f"{field_}: must be a list of two numbers [x, y], got {value!r}")
    return tuple(_number(f"{field_}[{i}]", v) for i, v in enumerate(value))


def _beam(t) -> Beam:
    _keys("beam", t, required=_required("beam"))
    return Beam(*(_positive(f"beam.{k}", t[k]) for k in ("length", "height", "width")))


# a law's constant: a name (C10, C01, mu, Jm, ...); which ones a law needs, and which
# values it admits, the law says (mechanics.laws), checked by check_names
CONSTANT = re.compile(r"[A-Za-z][A-Za-z0-9_]*")
MATERIAL_KEYS = tuple(k.name for k in keys_of("material"))


def _name(field_, value) -> str:
    if not isinstance(value, str) or not value:
        raise SceneError(f"{field_}: must be a name (a non-empty string), got {value!r}")
    return value


def _material(t) -> MaterialSpec:
    _keys("material", t, required=_required("material"),
          optional={*_optional("material"), *(k for k in t if k not in MATERIAL_KEYS and CONSTANT.fullmatch(str(k)))},
          allowed="law, formulation, density, penalty and the law's constants (C10, C01, mu, ...)")
    constants = {k: _number(f"material.{k}", v) for k, v in t.items() if k not in MATERIAL_KEYS}
    return MaterialSpec(_name("material.law", t["law"]), _name("material.formulation", t["formulation"]),
                        _positive("material.density", t["density"]), constants,
                        _positive("material.penalty", t["penalty"]) if "penalty" in t else None)


def _ancf(t) -> AncfSettings:
    _keys("ancf", t, required=_required("ancf"), optional=_optional("ancf"))
    element = _name("ancf.element", t["element"])
    n = _positive("ancf.elements", t["elements"], int)
    if "quadrature" not in t:
        return AncfSettings(element, n, None)
    q = t["quadrature"]
    if not isinstance(q, list) or len(q) != 2:
        raise SceneError(f"ancf.quadrature: must be [points along x, points across the thickness], got {q!r}")
    q = tuple(_ranged(f"ancf.quadrature[{i}]", v, 1, MAX_GAUSS, int) for i, v in enumerate(q))
    return AncfSettings(element, n, q)


def _supports(t) -> Supports:
    _keys("supports", t, required=_required("supports"), optional=_optional("supports"))
    left = _choice("supports.left", t["left"], SUPPORTS)
    if left != "clamp":
        if "clamp" in t:
            raise SceneError("supports.clamp: only with left = \"clamp\"")
        return Supports(left)
    return Supports("clamp", _choice("supports.clamp", t.get("clamp", _default("supports", "clamp")), CLAMPS))


def _loads(t) -> Loads:
    _keys("loads", t, optional=_optional("loads"))
    return Loads(gravity=_vector("loads.gravity", t["gravity"]) if "gravity" in t else None,
                 tip_force=_vector("loads.tip_force", t["tip_force"]) if "tip_force" in t else None,
                 end_moment=_number("loads.end_moment", t["end_moment"]) if "end_moment" in t else None)


def _energy_limit(t):
    if "energy_limit" not in t:
        return None
    v = t["energy_limit"]
    if v == "inf":
        return math.inf
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not v > 0:
        raise SceneError(f"analysis.energy_limit: must be a positive number of J (inf: no check), got {v!r}")
    return float(v)


def _ranged(field_, value, lo, hi, kind=float):
    v = _positive(field_, value, kind)
    if not lo <= v <= hi:
        raise SceneError(f"{field_}: must lie in [{lo:g}, {hi:g}], got {value!r}")
    return v


def _common(t) -> dict:
    """The keys of both kinds of analysis."""
    d = Analysis.__dataclass_fields__
    return dict(
        newton_rtol=_ranged("analysis.newton_rtol", t.get("newton_rtol", d["newton_rtol"].default), *NEWTON_RTOL),
        max_iterations=_ranged("analysis.max_iterations", t.get("max_iterations", d["max_iterations"].default),
                               1, MAX_ITERATIONS, int),
        wall_time=_positive("analysis.wall_time", t["wall_time"]) if "wall_time" in t else None)


def _analysis(t) -> Analysis:
    kind = _choice("analysis.kind", t.get("kind"), ANALYSES)
    if kind == "static":
        _keys("analysis", t, required=_required("analysis", "static"), optional=set(STATIC_KEYS))
        return Analysis(kind, load_steps=_ranged("analysis.load_steps", t.get("load_steps", Analysis.load_steps),
                                                 1, MAX_LOAD_STEPS, int), **_common(t))
    _keys("analysis", t, required=_required("analysis", "dynamic"), optional=set(DYNAMIC_KEYS))
    t_end = _positive("analysis.t_end", t["t_end"])
    dt = _positive("analysis.dt", t["dt"])
    if dt > t_end:
        raise SceneError(f"analysis.dt: must not exceed t_end = {t_end:g} s, got {dt!r}")
    dt_min = _positive("analysis.dt_min", t["dt_min"]) if "dt_min" in t else None
    if dt_min is not None and dt_min > dt:
        raise SceneError(f"analysis.dt_min: must not exceed dt = {dt:g} s, got {dt_min!r}")
    max_steps = _positive("analysis.max_steps", t["max_steps"], int) if "max_steps" in t else None
    if t_end / dt > (max_steps or MAX_STEPS) * (1 + 1e-9):
        raise SceneError(f"analysis.dt: t_end / dt = {t_end / dt:.3g} steps exceeds analysis.max_steps = "
                         f"{max_steps or MAX_STEPS:g}; raise max_steps to run it")
    rho_inf = _number("analysis.rho_inf", t.get("rho_inf", Analysis.rho_inf))
    if not 0.0 <= rho_inf <= 1.0:
        raise SceneError(f"analysis.rho_inf: must lie in [0, 1], got {rho_inf!r}")
    out = t.get("output_times")
    if out is not None:
        if not isinstance(out, list) or not out:
            raise SceneError("analysis.output_times: must be a non-empty list of times in s")
        out = tuple(_number(f"analysis.output_times[{i}]", v) for i, v in enumerate(out))
        if any(v < 0 or v > t_end for v in out) or list(out) != sorted(out):
            raise SceneError(f"analysis.output_times: must rise within [0, t_end = {t_end}]")
    return Analysis(
        kind, t_end=t_end, dt=dt, dt_min=dt_min,
        tolerance=_positive("analysis.tolerance", t["tolerance"]) if "tolerance" in t else None,
        output_times=out,
        integrator=_name("analysis.integrator", t.get("integrator", Analysis.integrator)),
        rho_inf=rho_inf, energy_limit=_energy_limit(t), max_steps=max_steps,
        newton=_newton(t), **_common(t))


def _newton(t) -> str:
    """analysis.newton; "linear" (one solve per step, no convergence test) has no tolerance to
    stop on and steps at fixed dt (an adaptive step runs full Newton)."""
    newton = _choice("analysis.newton", t.get("newton", Analysis.newton), NEWTON)
    if newton == "linear":
        for key, why in (("newton_rtol", "it has no convergence test"),
                         ("tolerance", "an adaptive step runs full Newton")):
            if key in t:
                raise SceneError(f"analysis.{key}: not used with analysis.newton = 'linear' ({why}); leave it out "
                                 f"or choose analysis.newton from {', '.join(repr(n) for n in NEWTON if n != 'linear')}")
    return newton


# ---------------------------------------------------------------------------------------
def check_names(scene: Scene, laws: Mapping, formulations: Collection[str],
                integrators: Collection[str], elements: Collection[str] | None = None) -> Scene:
    """Check the names a solver resolves against that solver's vocabulary: ``laws``
    {name: law} (a law has ``constants``, the names it needs, and ``check(constants)``,
    which raises a :class:`SceneError` for values it does not admit), ``formulations``
    (the names of :data:`FORMULATIONS` the solver implements), ``integrators`` (dynamic
    scenes), ``elements`` (the [ancf] table, if the solver reads it). Raises a
    :class:`SceneError` naming the field and the allowed values; returns the scene."""
    m = scene.material
    law = _choice("material.law", m.law, laws)
    form = _choice("material.formulation", m.formulation, [f for f in FORMULATIONS if f in formulations])
    need = set(laws[law].constants) | ({"penalty"} if FORMULATIONS[form] else set())
    have = set(m.constants) | ({"penalty"} if m.penalty is not None else set())
    _keys("material", dict.fromkeys(have | {"law", "formulation", "density"}),
          required=need | {"law", "formulation", "density"})
    laws[law].check(m.constants)
    if elements is not None and scene.ancf is not None:
        _choice("ancf.element", scene.ancf.element, elements)
    if scene.analysis.kind == "dynamic":
        _choice("analysis.integrator", scene.analysis.integrator, integrators)
    return scene
