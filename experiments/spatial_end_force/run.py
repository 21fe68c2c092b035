"""The paper's cantilever in 3D (160 x 5 x 7 mm, the clamped face) under an end force instead
of its weight: the spatial ANCF elements against two 3D continuum codes.

The load: a dead traction, uniform on the free end face, of resultant (0, -F, 0) with
F = 0.03 N (contract.loads.end_traction, as the continuum's scene key ``loads.tip_force``
applies it), no gravity. F L^2 / EI = 1.84 for the neo-Hookean constants (E = 6 C10):
the tip drops by about 0.47 L, a large rotation as under the paper's weight, the
same force for every law.

    .venv/bin/python experiments/spatial_end_force/run.py continuum LAW [--backend B] [--levels N]
    .venv/bin/python experiments/spatial_end_force/run.py ancf LAW ELEMENT COUNTS [--grading G] [--penalty PA]

``continuum``: the scene on nested graded Q2/Q1 hexahedra (the 3D gold's sequence,
studies.verification.continuum_gold.cantilever.base_settings_3d: 16 x 1 x 1, 32 x 2 x 2,
64 x 4 x 4, exactly incompressible) and Richardson's value with its error estimate, by the
gold's own rule (reference_fem.convergence); one JSON line per backend and law in
continuum.jsonl. ``ancf``: the spatial element (a registered one or a trial of
experiments/spatial_cantilever/run.py's family) on equal or graded meshes, the paper's
penalty unless given, 10 load steps; one line per run in res.jsonl, with its error against
the DOLFINx value of its law, |u - u_ref| / |u_ref| over the tip's (ux, uy). Runs held are
skipped. summary.py prints the tables.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT / "experiments" / "spatial_cantilever"))

FORCE = 0.03   # N, downwards (-y)
# how a continuum run weighs the end face's nodes: DOLFINx integrates the traction on the
# facets; FElupe's Simpson weights, merged coordinates (fixed_face_weights)
FACE_WEIGHTS = {"dolfinx": "facets", "felupe": "simpson-merged"}


def scene(law: str, incompressibility: str = "mixed"):
    from contract import paper
    from contract.scene import scene_from_dict

    d = paper.cantilever_scene(law, "paper", fem={"model": "3d", "incompressibility": incompressibility},
                               load_steps=10, name=f"end-force-{law}-3d")
    d["loads"] = {"tip_force": [0.0, -FORCE]}
    return scene_from_dict(d)


def _lines(path: Path) -> list[dict]:
    return [json.loads(s) for s in path.read_text().splitlines()] if path.exists() else []


def fixed_face_weights(pts: np.ndarray, face: np.ndarray, gdim: int) -> np.ndarray:
    """reference_fem.felupe_backend.problem._face_weights with the face's node coordinates
    merged to 1e-9 of the section first: its np.unique of the raw coordinates keeps two
    copies of y = 0 (2e-19 apart) on the 64 x 4 x 4 mesh, the Simpson weights then pair the
    wrong nodes and the end force's resultant is 0.02417 N of 0.03 N."""
    from reference_fem.felupe_backend.problem import _simpson

    w = np.ones(len(face))
    for axis in range(1, gdim):
        x = pts[face, axis]
        tol = 1e-9 * np.ptp(x)
        c = np.unique(np.round(x / tol)) * tol
        w *= _simpson(c)[np.argmin(np.abs(x[:, None] - c[None, :]), axis=1)]
    return w


def continuum(a) -> None:
    from dataclasses import replace

    if a.backend == "felupe":   # the end force's weights, fixed (see fixed_face_weights)
        import reference_fem.felupe_backend.problem as fp

        fp._face_weights = fixed_face_weights

    from reference_fem.convergence import refinement_study
    from studies.verification.continuum_gold.cantilever import base_settings_3d

    out = HERE / "continuum.jsonl"
    if any(r["law"] == a.law and r["backend"] == a.backend and r["levels_asked"] == a.levels
           and r.get("face_weights") == FACE_WEIGHTS[a.backend]
           and r.get("incompressibility", "mixed") == a.incompressibility for r in _lines(out)):
        return
    base = replace(base_settings_3d(a.incompressibility), backend=a.backend)
    t0 = time.perf_counter()
    study = refinement_study(scene(a.law, a.incompressibility), a.levels, base,
                             progress=lambda lv: print(lv["cells_length"], lv["tip"], f"{lv['wall_s']:.1f} s", flush=True))
    d = study.to_dict()
    rec = {"law": a.law, "backend": a.backend, "levels_asked": a.levels, "force_N": FORCE,
           "face_weights": FACE_WEIGHTS[a.backend], "incompressibility": a.incompressibility,
           "tip": d["extrapolated"], "error_estimate_m": d["error_estimate"], "order": d["order"],
           "levels": d["levels"], "seconds": time.perf_counter() - t0}
    with out.open("a") as f:
        f.write(json.dumps(rec) + "\n")
    print(json.dumps({k: rec[k] for k in ("law", "backend", "tip", "error_estimate_m", "order")}), flush=True)


def reference(law: str) -> dict:
    for r in _lines(HERE / "continuum.jsonl"):
        if (r["law"] == law and r["backend"] == "dolfinx" and r["tip"] is not None
                and r.get("incompressibility", "mixed") == "mixed"):
            return r
    raise SystemExit(f"no DOLFINx reference for {law}: run `run.py continuum {law}` first")


def ancf(a) -> None:
    from run import element   # experiments/spatial_cantilever/run.py

    from ancf.kinematics.spatial.beam import SpatialBeam
    from ancf.kinematics.spatial.statics import clamp_rows, end_face_load, solve_static
    from contract import paper
    from contract.loads import end_traction

    spec = element(a.element)
    points = spec.default_rule()
    ref = reference(a.law)
    c = {k: v for k, v in paper.materials()[a.law].items() if k != "density"}
    L, h, w = paper.CANTILEVER["length"], paper.CANTILEVER["height"], paper.CANTILEVER["width"]
    t = end_traction((0.0, -FORCE, 0.0), h, w)
    out = HERE / "res.jsonl"
    have = {(r["law"], r["element"], r["elements"], r["grading"], r["penalty"]) for r in _lines(out)}
    for n in (int(x) for x in a.counts.split(",")):
        if (a.law, a.element, n, a.grading, a.penalty) in have:
            continue
        b = SpatialBeam(spec, L, h, w, n, a.law, c, a.penalty, points, a.grading)
        t0 = time.perf_counter()
        res = solve_static(b, end_face_load(b, lambda y, z: np.tile(t, (y.size, 1))), clamp_rows(b), load_steps=10)
        tip = res.tip(b)
        g = ref["tip"]
        err = None if tip is None else float(np.hypot(tip["ux"] - g["ux"], tip["uy"] - g["uy"]) / np.hypot(g["ux"], g["uy"]))
        rec = {"law": a.law, "element": a.element, "elements": n, "grading": a.grading, "penalty": a.penalty,
               "points": points, "first_element_m": float(b.lengths[0]), "dof": b.dof, "status": res.status,
               "reason": res.reason, "tip": tip, "reference": g, "reference_error_estimate_m": ref["error_estimate_m"],
               "error": err, "newton_iterations": res.newton_iterations, "rejected_steps": res.rejected_steps,
               "seconds": time.perf_counter() - t0}
        with out.open("a") as f:
            f.write(json.dumps(rec) + "\n")
        print(json.dumps(rec), flush=True)


def main() -> None:
    from contract import paper

    a = argparse.ArgumentParser()
    sub = a.add_subparsers(dest="what", required=True)
    c = sub.add_parser("continuum")
    c.add_argument("law")
    c.add_argument("--backend", default="dolfinx", choices=["dolfinx", "felupe"])
    c.add_argument("--levels", type=int, default=3)
    c.add_argument("--incompressibility", default="mixed", choices=["mixed", "penalty"],
                   help="mixed: J = 1 exactly (the reference); penalty: the scene's alpha, as the ANCF runs")
    e = sub.add_parser("ancf")
    e.add_argument("law")
    e.add_argument("element")
    e.add_argument("counts")
    e.add_argument("--grading", type=float, default=1.0)
    e.add_argument("--penalty", type=float, default=paper.PENALTY)
    a = a.parse_args()
    (continuum if a.what == "continuum" else ancf)(a)


if __name__ == "__main__":
    main()
