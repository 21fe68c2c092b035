"""The paper's numbers and scenes: the one home used by studies, tests and reference_fem.

Guo et al. (2021): Tables 2-4 are read from ``contract/paper_data`` (the paper's MPa and
mm) and returned in SI; the two examples are built here as scene dicts
(:mod:`contract.scene` format):

- :func:`cantilever_scene`: Example 1, the static cantilever (L = 160 mm, h = 5 mm,
  w = 7 mm) clamped at x = 0 under its own weight;
- :func:`pendulum_scene`: Example 2, the flexible pendulum (L = 350 mm, same section)
  pinned at x = 0 and released from horizontal at rest, output every 0.1 s.

A scene may carry an ``[ancf]`` table (element, count, quadrature) and a ``[fem]`` table
(the continuum's discretisation); each solver reads its own.
"""
from __future__ import annotations

import csv
from decimal import Decimal
from functools import lru_cache
from pathlib import Path

from .scene import FORMULATIONS

DATA = Path(__file__).with_name("paper_data")
PENALTY = 1000e6      # Pa, the paper's alpha (section 3.1)
GRAVITY = 9.81        # m/s^2
CANTILEVER = {"length": 0.160, "height": 0.005, "width": 0.007}  # m
PENDULUM = {"length": 0.350, "height": 0.005, "width": 0.007}    # m
PENDULUM_T_END = 0.5  # s
PENDULUM_LAW = "yeoh"  # the law of the paper's pendulum (Figures 4, 5, Table 4)
OUTPUT_EVERY = 0.1    # s, the paper's output times 0, 0.1, ..., t_end


def _rows(name: str):
    with open(DATA / name) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def _si(text: str, scale: int) -> float:
    """A decimal of the paper's table in SI, rounded once (-0.000802537 MPa is exactly
    -802.537 Pa, not the -802.5369999999999 of a float product)."""
    return float(Decimal(text) * scale)


@lru_cache(maxsize=None)
def materials() -> dict[str, dict[str, float]]:
    """{law: {constant (Pa) ..., 'density' (kg/m^3)}} from Table 2."""
    out = {}
    for r in _rows("materials.csv"):
        c = {k[:-4]: _si(v, 10 ** 6) for k, v in r.items() if k.endswith("_MPa") and v}
        c["density"] = float(r["density_kg_m3"])
        out[r["law"]] = c
    return out


@lru_cache(maxsize=None)
def table3() -> dict[tuple[str, str], dict]:
    """{(source, law): {'elements', 'ux', 'uy' (m)}} from Table 3; source is an element
    name or "ABAQUS"."""
    return {(r["source"], r["law"]): {"elements": int(r["elements"]),
                                      "ux": _si(r["ux_mm"], 1) / 1000, "uy": _si(r["uy_mm"], 1) / 1000}
            for r in _rows("table3_static_tip_mm.csv")}


@lru_cache(maxsize=None)
def table4() -> dict[tuple[str, int], float]:
    """{(element, elements): CPU seconds} from Table 4."""
    out = {}
    for r in _rows("table4_pendulum_cpu_s.csv"):
        for el, v in r.items():
            if el != "elements":
                out[(el, int(r["elements"]))] = float(v)
    return out


def element_count(element: str) -> int:
    """The number of elements the paper's Table 3 uses for ``element``."""
    counts = {src: c["elements"] for (src, _), c in table3().items() if src != "ABAQUS"}
    try:
        return counts[element]
    except KeyError:
        raise ValueError(f"element {element!r} is not in the paper's Table 3; "
                         f"its elements: {', '.join(sorted(counts))}") from None


def paper_tip(source: str, law: str) -> tuple[float, float] | None:
    """(ux, uy) in m of the paper's Table 3 (source: an element name or "ABAQUS")."""
    t = table3().get((source, law))
    return (t["ux"], t["uy"]) if t else None


def material_table(law: str, formulation: str, penalty: float = PENALTY) -> dict:
    """A scene's [material] table for one of the paper's laws (the penalty only where
    the formulation has one)."""
    t = {"law": law, "formulation": formulation, **materials()[law]}
    if FORMULATIONS[formulation]:
        t["penalty"] = penalty
    return t


def _ancf(element, elements, quadrature) -> dict:
    t = {"element": element, "elements": int(elements)}
    if quadrature is not None:
        t["quadrature"] = [int(q) for q in quadrature]
    return t


def cantilever_scene(law: str, formulation: str, element: str | None = None, elements: int | None = None,
                     quadrature=(3, 2), clamp: str = "face", penalty: float = PENALTY,
                     gravity: float = GRAVITY, fem: dict | None = None, name: str | None = None,
                     **analysis) -> dict:
    """Example 1 as a scene dict: the ANCF mesh when ``element`` is given, the
    continuum's [fem] table when ``fem`` is; ``analysis`` keys go to [analysis]."""
    d = {
        "name": name or f"cantilever-{law}-{formulation}" + (f"-{element}-{elements}" if element else ""),
        "beam": dict(CANTILEVER),
        "material": material_table(law, formulation, penalty),
        "supports": {"left": "clamp", "clamp": clamp},
        "loads": {"gravity": [0.0, -gravity]},
        "analysis": {"kind": "static", **analysis},
    }
    if element is not None:
        d["ancf"] = _ancf(element, elements, quadrature)
    if fem is not None:
        d["fem"] = dict(fem)
    return d


def output_times(t_end: float, every: float = OUTPUT_EVERY) -> list[float]:
    """0, every, 2 every, ... up to t_end (t_end included)."""
    n = int(round(t_end / every))
    ts = [round(every * i, 10) for i in range(n + 1) if every * i <= t_end + 1e-12]
    if ts[-1] < t_end - 1e-12:
        ts.append(t_end)
    return ts


def pendulum_scene(law: str, formulation: str, dt: float, element: str | None = None,
                   elements: int | None = None, rho_inf: float = 0.5, t_end: float = PENDULUM_T_END,
                   every: float = OUTPUT_EVERY, integrator: str = "generalized-alpha",
                   penalty: float = PENALTY, stiffness_scale: float = 1.0, quadrature=None,
                   fem: dict | None = None, name: str | None = None, **analysis) -> dict:
    """Example 2 as a scene dict (see :func:`cantilever_scene` for ``element`` and
    ``fem``). ``stiffness_scale`` multiplies every law constant and the penalty."""
    material = material_table(law, formulation, penalty)
    for k in material:
        if k.startswith("C") or k == "penalty":
            material[k] *= stiffness_scale
    d = {
        "name": name or f"pendulum-{law}-{formulation}" + (f"-{element}-{elements}" if element else ""),
        "beam": dict(PENDULUM),
        "material": material,
        "supports": {"left": "pin"},
        "loads": {"gravity": [0.0, -GRAVITY]},
        "analysis": {"kind": "dynamic", "t_end": float(t_end), "dt": float(dt),
                     "output_times": output_times(t_end, every), "integrator": integrator,
                     "rho_inf": float(rho_inf), **analysis},
    }
    if element is not None:
        d["ancf"] = _ancf(element, elements, quadrature)
    if fem is not None:
        d["fem"] = dict(fem)
    return d


def pendulum_mass(law: str) -> float:
    """m = rho L h w of the pendulum (kg)."""
    b = PENDULUM
    return materials()[law]["density"] * b["length"] * b["height"] * b["width"]
