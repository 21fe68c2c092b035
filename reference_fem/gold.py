"""Gold data: the paper's static cantilever, converged, for tests without dolfinx.

``python -m reference_fem gold`` writes ``tests/gold/fem_cantilever.json``: for each
law x continuum model (plane strain mixed = exactly incompressible, plane strain
penalty = the ANCF ``plane-strain`` energy with alpha = 1000 MPa, plane stress) the
refinement sequence, the observed order, the Richardson value and its error
estimate, with the scene, the base mesh and the DOLFINx version. Values in m.

How to compare (``tolerance`` of each case): a result u agrees with the continuum
if ||u - u_ref|| <= tolerance.abs_m + its own discretisation error, with u_ref the
Richardson value and tolerance.abs_m = 2 x the error estimate (the estimate is of
the finest mesh's error; the factor 2 covers its use for the extrapolated value).
``regression_rtol`` is how closely a fresh run of a stored level must reproduce it
(Newton tolerance and platform round-off).
"""
from __future__ import annotations

import json
from pathlib import Path

from contract import paper
from contract.scene import Scene, scene_from_dict

from .convergence import refinement_study
from .settings import FemSettings, default_quadrature_degree

FILE = "fem_cantilever.json"
LAWS = ("neo-hookean", "mooney-rivlin", "yeoh")
VARIANTS = {  # case suffix -> (scene formulation, [fem] incompressibility)
    "plane-strain": ("plane-strain", "mixed"),
    "plane-strain-penalty": ("plane-strain", "penalty"),
    "plane-stress": ("plane-stress", None),
}
REGRESSION_RTOL = 1e-6


def cantilever(law: str, model: str, incompressibility: str | None = None, fem: dict | None = None) -> Scene:
    """The paper's cantilever for ``law`` in the continuum ``model``."""
    fem = dict(fem or {})
    if incompressibility:
        fem["incompressibility"] = incompressibility
    return scene_from_dict(paper.cantilever_scene(law, model, fem=fem or None, load_steps=10,
                                                  name=f"fem-cantilever-{law}-{model}"))


def base_settings(model: str, incompressibility: str | None) -> FemSettings:
    """Level 0 of the gold sequences: 16 x 1 Q2 quadrilaterals (cells 10 mm x 5 mm)."""
    return FemSettings(model, incompressibility or "exact", cells_length=16, cells_height=1,
                       cell="quadrilateral", degree=2, quadrature_degree=default_quadrature_degree(2))


def gold_case(law: str, variant: str, levels: int, progress=None) -> dict:
    model, inc = VARIANTS[variant]
    scene = cantilever(law, model, incompressibility=inc if inc == "penalty" else None)
    study = refinement_study(scene, levels, base_settings(model, inc), progress=progress)
    d = study.to_dict()
    err = d["error_estimate"]
    return {
        "law": law, "continuum_model": model, "incompressibility": inc or "exact",
        "tip": d["extrapolated"], "error_estimate_m": err,
        "finest": d["levels"][-1]["tip"], "order": d["order"], "orders": d["orders"],
        "tolerance": {"abs_m": None if err is None else 2.0 * err},
        "regression_rtol": REGRESSION_RTOL,
        "base_mesh": d["base"], "levels": d["levels"], "scene": d["scene"],
    }


def write_gold(out_dir: Path, levels: int = 5, progress=None) -> Path:
    from .dolfinx_backend import VERSION

    cases = {}
    for law in LAWS:
        for variant in VARIANTS:
            key = f"{law}/{variant}"
            if progress:
                progress(f"-- {key}")
            cases[key] = gold_case(law, variant, levels,
                                   progress=None if not progress else
                                   (lambda lv: progress(f"   {lv['cells_length']} x {lv['cells_height']}: "
                                                        f"{lv['tip']} ({lv['wall_s']:.1f} s)")))
    doc = {
        "description": "Static cantilever of the paper (Table 3) as a 2D continuum: tip "
                       "(free-end centre point) displacement in m, Richardson-extrapolated "
                       "over uniform mesh refinement. Regenerate: python -m reference_fem gold",
        "generator": "python -m reference_fem gold --levels %d" % levels,
        "dolfinx": VERSION, "units": "m", "laws": list(LAWS), "variants": list(VARIANTS),
        "comparison": __doc__.split("How to compare")[1].strip(),
        "cases": cases,
    }
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / FILE
    tmp = path.with_suffix(".json.tmp")
    tmp.write_text(json.dumps(doc, indent=1) + "\n")
    tmp.replace(path)
    return path
