"""The paper's numbers (Tables 2-4), read from ``studies/paper_data`` and returned in SI."""
from __future__ import annotations

import csv
from functools import lru_cache
from pathlib import Path

DATA = Path(__file__).with_name("paper_data")
PENALTY = 1000e6      # Pa, the paper's alpha
GRAVITY = 9.81        # m/s^2
CANTILEVER = {"length": 0.160, "height": 0.005, "width": 0.007}  # m
PENDULUM = {"length": 0.350, "height": 0.005, "width": 0.007}    # m
ELEMENT_COUNTS = {"HB2n-12": 160, "HB3n-12": 160, "HB2n-16": 640, "LB2n-12": 160}


def _rows(name: str):
    with open(DATA / name) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


@lru_cache(maxsize=None)
def materials() -> dict[str, dict[str, float]]:
    """{law: {constant (Pa) ..., 'density' (kg/m^3)}} from Table 2."""
    out = {}
    for r in _rows("materials.csv"):
        c = {k[:-4]: float(v) * 1e6 for k, v in r.items() if k.endswith("_MPa") and v}
        c["density"] = float(r["density_kg_m3"])
        out[r["law"]] = c
    return out


@lru_cache(maxsize=None)
def table3() -> dict[tuple[str, str], dict]:
    """{(source, law): {'elements', 'ux', 'uy' (m)}} from Table 3."""
    return {(r["source"], r["law"]): {"elements": int(r["elements"]),
                                      "ux": float(r["ux_mm"]) * 1e-3, "uy": float(r["uy_mm"]) * 1e-3}
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


def material_table(law: str, formulation: str, penalty: float = PENALTY) -> dict:
    """A scene's [material] table for one of the paper's laws."""
    t = {"law": law, "formulation": formulation, **materials()[law]}
    if formulation != "plane-stress":
        t["penalty"] = penalty
    return t


def cantilever_scene(law: str, formulation: str, element: str, elements: int,
                     quadrature=(3, 2), clamp: str = "face", penalty: float = PENALTY,
                     gravity: float = GRAVITY, name: str | None = None, **analysis) -> dict:
    """The paper's static cantilever as a scene dict (see ancf.scene)."""
    return {
        "name": name or f"cantilever-{law}-{formulation}-{element}-{elements}",
        "beam": dict(CANTILEVER),
        "material": material_table(law, formulation, penalty),
        "ancf": {"element": element, "elements": elements, "quadrature": list(quadrature)},
        "supports": {"left": "clamp", "clamp": clamp},
        "loads": {"gravity": [0.0, -gravity]},
        "analysis": {"kind": "static", **analysis},
    }
