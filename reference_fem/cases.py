"""The paper's static cantilever (Table 3) as scenes, for the gold data and the report.

Constants: the paper's Table 2 (also /work/shared/paper-data/materials.csv), in Pa;
penalty alpha = 1000 MPa (section 3.1). Beam: L = 160 mm, h = 5 mm, w = 7 mm;
clamped left end; gravity (0, -9.81) m/s^2.
"""
from __future__ import annotations

from ancf.scene import Scene, scene_from_dict

MATERIALS = {  # Pa, kg/m^3
    "neo-hookean": {"C10": 0.953018e6, "density": 2150.0},
    "mooney-rivlin": {"C10": 0.8e6, "C01": 0.2e6, "density": 7200.0},
    "yeoh": {"C10": 0.545235e6, "C20": 0.0610498e6, "C30": -0.000802537e6, "density": 2150.0},
}
PENALTY = 1.0e9  # Pa
# The paper's ABAQUS column of Table 3 (m), for the report's comparison.
ABAQUS_TIP = {
    "neo-hookean": (-39.58e-3, -98.04e-3),
    "mooney-rivlin": (-95.07e-3, -135.85e-3),
    "yeoh": (-65.55e-3, -120.79e-3),
}


def cantilever_dict(law: str, model: str, fem: dict | None = None, gravity_scale: float = 1.0,
                    incompressibility: str | None = None) -> dict:
    """The scene (as a TOML-like dict) of the paper's cantilever for ``law`` in the
    continuum ``model`` ("plane-strain" | "plane-stress")."""
    material = {"law": law, "formulation": model, **MATERIALS[law]}
    if model == "plane-strain":
        material["penalty"] = PENALTY
    fem = dict(fem or {})
    if incompressibility:
        fem["incompressibility"] = incompressibility
    d = {
        "name": f"fem-cantilever-{law}-{model}",
        "beam": {"length": 0.160, "height": 0.005, "width": 0.007},
        "material": material,
        "supports": {"left": "clamp"},
        "loads": {"gravity": [0.0, -9.81 * gravity_scale]},
        "analysis": {"kind": "static", "load_steps": 10},
    }
    if fem:
        d["fem"] = fem
    return d


def cantilever(law: str, model: str, **kw) -> Scene:
    return scene_from_dict(cantilever_dict(law, model, **kw))
