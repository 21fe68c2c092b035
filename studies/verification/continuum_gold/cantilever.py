"""Gold data: the paper's static cantilever, converged, for tests without dolfinx.

``python -m studies continuum gold`` writes ``tests/gold/fem_cantilever.json``: for each
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

from reference_fem.convergence import refinement_study
from reference_fem.settings import FemSettings, default_quadrature_degree

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
    from reference_fem.dolfinx_backend.fem import VERSION

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
                       "over uniform mesh refinement. Regenerate: python -m studies continuum gold",
        "generator": "python -m studies continuum gold --levels %d" % levels,
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


# -- the real beam in 3D ---------------------------------------------------------------
FILE_3D = "fem_cantilever_3d.json"
# Level 0 of the 3D sequences: 16 x 1 x 1 Q2/Q1 hexahedra, graded along x toward the clamp
# (cell-to-cell factor 8^(1/15): the last cell 8 times the first; each refined level takes
# the square root, so the levels stay nested). Uniform meshes are not monotone in 3D:
# refining along x and across the section move the tip in opposite directions, because
# the clamped face's edges are singular (README, "The real beam in 3D").
PROGRESSION_3D = 8.0 ** (1.0 / 15.0)


def base_settings_3d(incompressibility: str = "mixed", cell: str = "hexahedron") -> FemSettings:
    return FemSettings("3d", incompressibility, cells_length=16, cells_height=1, cell=cell, degree=2,
                       quadrature_degree=default_quadrature_degree(2), cells_width=1,
                       progression=PROGRESSION_3D)


def cantilever_3d(law: str, incompressibility: str = "mixed") -> Scene:
    """The paper's cantilever (160 x 5 x 7 mm) as the 3D solid, clamped face."""
    return scene_from_dict(paper.cantilever_scene(law, "paper", fem={"model": "3d",
                                                                     "incompressibility": incompressibility},
                                                  load_steps=10, name=f"fem-cantilever-{law}-3d"))


def gold_case_3d(law: str, levels: int, progress=None) -> dict:
    scene = cantilever_3d(law)
    study = refinement_study(scene, levels, base_settings_3d(), progress=progress)
    d = study.to_dict()
    err = d["error_estimate"]
    return {
        "law": law, "continuum_model": "3d", "incompressibility": "mixed",
        "tip": d["extrapolated"], "error_estimate_m": err, "p_trusted": d.get("p_trusted"),
        "finest": d["levels"][-1]["tip"], "order": d["order"], "orders": d["orders"],
        "tolerance": {"abs_m": None if err is None else 2.0 * err},
        "regression_rtol": REGRESSION_RTOL,
        "base_mesh": d["base"], "levels": d["levels"], "scene": d["scene"],
    }


def write_gold_3d(out_dir: Path, levels: int = 3, laws=LAWS, progress=None) -> Path:
    """tests/gold/fem_cantilever_3d.json: the three laws, Richardson over ``levels``
    graded levels (16 x 1 x 1 ... ). Cases already in the file for other laws are kept."""
    from reference_fem.dolfinx_backend.fem import VERSION

    out_dir = Path(out_dir)
    path = out_dir / FILE_3D
    cases = json.loads(path.read_text())["cases"] if path.exists() else {}   # read on every rank
    for law in laws:
        if progress:
            progress(f"-- {law}/3d")
        cases[f"{law}/3d"] = gold_case_3d(
            law, levels, progress=None if not progress else
            (lambda lv: progress(f"   {lv['cells_length']} x {lv['cells_height']} x {lv['cells_width']}: "
                                 f"{lv['tip']} ({lv['wall_s']:.1f} s, {lv['mpi_ranks']} ranks)")))
    doc = {
        "description": "Static cantilever of the paper (Table 3) as the real 3D beam (160 x 5 x 7 mm, "
                       "clamped face, gravity), exactly incompressible (Q2/Q1 hexahedra): tip (centre "
                       "of the free end face) displacement in m, Richardson-extrapolated over graded "
                       "nested meshes. Regenerate: python -m studies continuum gold --3d",
        "generator": "python -m studies continuum gold --3d --levels %d" % levels,
        "dolfinx": VERSION, "units": "m", "laws": sorted(k.split("/")[0] for k in cases),
        "comparison": __doc__.split("How to compare")[1].strip()
        + " In 3D the error estimate caps the order at 1 (the clamp's singular edges).",
        "cases": cases,
    }
    from mpi4py import MPI

    if MPI.COMM_WORLD.rank == 0:   # under mpiexec every rank has the same numbers; one writes
        out_dir.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(".json.tmp")
        tmp.write_text(json.dumps(doc, indent=1) + "\n")
        tmp.replace(path)
    return path
