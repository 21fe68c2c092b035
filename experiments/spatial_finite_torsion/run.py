"""Finite torsion of the paper's bar in 3D (160 x 5 x 7 mm) between two rigid plates: the
spatial ANCF elements against the 3D continuum.

The case: the face x = 0 clamped, the face x = L turned rigidly about the bar's axis by
theta (up to half a turn) about its centre, which stays at (L, 0, 0); both faces are
rigid plates (no warping, no change of the section), the same boundary condition in
both solvers (a continuum's face nodes and the ANCF section's own field r(L, y, z) are
both the plate's rigid map). The quantities: the torque T and the axial force N that
the plate applies to the bar at x = L (its reaction: the continuum's residual summed
over the face's nodes, x x f about the centre; ANCF's generalised reactions paired with
the plate's rigid virtual motion, :func:`ancf.kinematics.spatial.statics.face_reaction`).
T is about mu J theta / L (J Saint-Venant's torsion constant, plus the restrained warping
near the plates); N is the Poynting effect, compressive, of second order in theta.

    .venv/bin/python experiments/spatial_finite_torsion/run.py level LAW --cells NX,NY,NZ [...] [--backend B] [--case C]
    .venv/bin/python experiments/spatial_finite_torsion/run.py ancf LAW ELEMENT COUNTS [--penalty PA] [--grading G] [--case C]

``level``: the continuum on Q2/Q1 hexahedra of the given cells (uniform along x: both ends
are plates), DOLFINx or FElupe, the plate's rotation in 10 equal increments
(reference_fem.statics.solve_static, its Newton and load-path rule), the reactions at every
fraction of ANGLES; one JSON line per mesh in levels.jsonl. ``ancf``: the element on equal
meshes or, with ``--grading G``, meshes graded from both plates to the middle (each element G
times as long as the one before it), the paper's penalty unless given, the same 10 increments; one line per run in
res.jsonl. summary.py computes the continuum's Richardson values from levels.jsonl and
prints the tables.
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT / "experiments" / "spatial_cantilever"))

# the plate's final rotation vector (rad) per case: half a turn about the axis; and a third
# of a turn about it with bending about both section axes (22.5 and 15 degrees)
CASES = {"twist": (math.pi, 0.0, 0.0), "twist-bend": (2 * math.pi / 3, math.pi / 8, math.pi / 12)}
ANGLES = (0.5, 1.0)                    # fractions of the rotation recorded
STEPS = 10
RTOL = 1e-9                            # the continuum's Newton tolerance, of its residual's scale


def rotation(case: str, frac: float) -> np.ndarray:
    """The plate's rotation matrix at ``frac`` of the case's rotation vector (Rodrigues)."""
    v = frac * np.asarray(CASES[case], float)
    a = float(np.linalg.norm(v))
    if a == 0.0:
        return np.eye(3)
    k = v / a
    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + math.sin(a) * K + (1.0 - math.cos(a)) * K @ K


def reactions(force, moment) -> dict:
    """The plate's reaction as recorded: T (the moment about x) and N (the axial force) with
    the whole vectors (N, N m)."""
    return {"T": float(moment[0]), "N": float(force[0]), "force": [float(v) for v in force],
            "moment": [float(v) for v in moment]}


def scene(law: str, incompressibility: str = "mixed"):
    from contract import paper
    from contract.scene import scene_from_dict

    d = paper.cantilever_scene(law, "paper", fem={"model": "3d", "incompressibility": incompressibility},
                               load_steps=STEPS, name=f"finite-torsion-{law}-3d")
    d["loads"] = {}
    return scene_from_dict(d)


def _lines(path: Path) -> list[dict]:
    return [json.loads(s) for s in path.read_text().splitlines()] if path.exists() else []


class Plate:
    """The rigid plate at x = L on a DOLFINx set-up: three Dirichlet conditions whose values
    are the plate's displacement R(theta)(X - c) + c - X, and the reaction it applies."""

    def __init__(self, s, beam):
        import dolfinx

        d, g = s.disc, s.model.geometry
        fdim = d.mesh.topology.dim - 1
        facets = dolfinx.mesh.locate_entities_boundary(d.mesh, fdim, g.at_right(beam))
        self.c = np.array([beam.length, 0.0, 0.0])
        self.funcs, self.bcs, self.dofs, self.X = [], [], [], []
        for i in range(3):
            sub = d.Wu.sub(i)
            V, _ = sub.collapse()
            w_dofs, v_dofs = dolfinx.fem.locate_dofs_topological((sub, V), fdim, facets)
            f = dolfinx.fem.Function(V)
            self.funcs.append(f)
            self.bcs.append(dolfinx.fem.dirichletbc(f, [w_dofs, v_dofs], sub))
            self.dofs.append(np.asarray(w_dofs))
            self.X.append(V.tabulate_dof_coordinates()[v_dofs])

    def set(self, R: np.ndarray) -> None:
        for i, f in enumerate(self.funcs):
            f.interpolate(lambda x, i=i: (R @ (x - self.c[:, None]))[i] + self.c[i] - x[i])

    def reaction(self, system, R: np.ndarray) -> dict:
        """Force and moment about the centre (N, N m) that the plate applies: the residual
        (no condition applied) at the plate's rows, x x f over its nodes."""
        import dolfinx.fem.petsc

        b = dolfinx.fem.petsc.assemble_vector(system.R)
        b.ghostUpdate()
        r = b.array
        force, moment = np.zeros(3), np.zeros(3)
        for i in range(3):
            f = np.zeros((len(self.dofs[i]), 3))
            f[:, i] = r[self.dofs[i]]
            force += f.sum(axis=0)
            moment += np.cross((self.X[i] - self.c) @ R.T, f).sum(axis=0)
        return {"force": force, "moment": moment}


def both_ends(n: int, grading: float, length: float) -> np.ndarray:
    """The n + 1 cell boundaries along x of cells growing by ``grading`` from both ends to the
    middle (the ANCF beams' ``both_ends``)."""
    from ancf.kinematics.spatial.beam import graded_lengths

    x = np.concatenate([[0.0], np.cumsum(graded_lengths(n, grading, length, both_ends=True))])
    x[-1] = length                      # exactly: the plate's nodes are found at x = L
    return x


def continuum_level(law: str, incompressibility: str, settings, rtol: float = RTOL, case: str = "twist",
                    grading: float = 1.0) -> dict:
    from reference_fem.dolfinx_backend.problem import set_up, static_problem
    from reference_fem.statics import solve_static

    sc = scene(law, incompressibility)
    t0 = time.perf_counter()
    s = set_up(sc, settings)
    if grading != 1.0:
        # the uniform mesh's nodes moved along x, cell by cell, onto cells graded from both
        # plates (a map linear in each cell: the cells stay straight-sided boxes)
        x = s.disc.mesh.geometry.x
        n, L = settings.cells_length, sc.beam.length
        x[:, 0] = np.interp(x[:, 0], np.linspace(0.0, L, n + 1), both_ends(n, grading, L))
    plate = Plate(s, sc.beam)
    s.bcs = s.bcs + plate.bcs
    prob = static_problem(s)
    out = {}

    # the path in legs ending at each recorded angle, so that each is an accepted state
    done, res, iterations = 0.0, None, 0
    for frac in ANGLES:
        leg = lambda t, a=done, b=frac: plate.set(rotation(case, a + t * (b - a)))
        steps = max(1, round(STEPS * (frac - done)))
        res = solve_static(prob.system, leg, steps, rtol, 40)
        iterations += res.newton_iterations
        if res.status != "converged":
            break
        r = plate.reaction(prob.system, rotation(case, frac))
        out[str(frac)] = reactions(r["force"], r["moment"])
        done = frac
    return {"cells": [settings.cells_length, settings.cells_height, settings.cells_width],
            "ndof": s.disc.ndof, "status": res.status, "reason": res.reason, "newton_iterations": iterations,
            "reactions": out, "seconds": time.perf_counter() - t0}


def felupe_level(law: str, incompressibility: str, settings, rtol: float = RTOL, case: str = "twist",
                 grading: float = 1.0) -> dict:
    """continuum_level on FElupe's hexahedra (the same Q2/Q1 mesh): the plate's nodes held,
    their values written into the unknowns at every load (the Newton system keeps held
    values as set), the reaction its residual at those nodes. With ``grading`` the mesh's
    points along x are both_ends' (the backend's one-end progression replaced)."""
    from dataclasses import replace

    import reference_fem.felupe_backend.problem as fp
    from reference_fem.felupe_backend.problem import Reduction, System, set_up
    from reference_fem.statics import solve_static

    if grading != 1.0:
        fp._graded = lambda n, length, q: both_ends(n, q, length)
        settings = replace(settings, progression=grading)
    sc = scene(law, incompressibility)
    t0 = time.perf_counter()
    s = set_up(sc, replace(settings, backend="felupe"))
    pts = s.mesh.points
    nodes = np.flatnonzero(s.settings.geometry.at_right(sc.beam)(pts.T))
    rows = (3 * nodes[:, None] + np.arange(3)).ravel()
    s.fixed[rows] = True
    s.reduction = Reduction(s.fixed)
    system = System(s)
    c = np.array([sc.beam.length, 0.0, 0.0])
    X = pts[nodes]

    def place(R: np.ndarray) -> None:
        system.w[rows] = ((X - c) @ R.T + c - X).ravel()

    import reference_fem.statics as statics

    own_scale, scales = statics.reference_residual, []

    def linear_scale(frac: float):
        """reference_fem.statics' residual scale (the residual at the leg's end with the rest
        at rest), or, where that is not a number (the plate's whole turn at once inverts the
        cells beside it), 20 times the residual at 5 % of the turn from rest: the same scale
        to first order, the residual of a prescribed motion being linear in it at rest."""
        def reference_residual(system_, set_load):
            r = own_scale(system_, set_load)
            if np.isfinite(r):
                return r
            saved = system_.save()
            system_.reset()
            place(rotation(case, 0.05 * frac))
            r = 20.0 * system_.residual_norm()
            system_.restore(saved)
            set_load(0.0)
            scales.append(frac)
            return r
        return reference_residual

    out, done, res, iterations = {}, 0.0, None, 0
    try:
        for frac in ANGLES:
            leg = lambda t, a=done, b=frac: place(rotation(case, a + t * (b - a)))
            statics.reference_residual = linear_scale(frac)
            res = solve_static(system, leg, max(1, round(STEPS * (frac - done))), rtol, 40)
            iterations += res.newton_iterations
            if res.status != "converged":
                break
            f = system.residual(system.w)[rows].reshape(-1, 3)
            arm = (X - c) @ rotation(case, frac).T
            out[str(frac)] = reactions(f.sum(axis=0), np.cross(arm, f).sum(axis=0))
            done = frac
    finally:
        statics.reference_residual = own_scale
    rec = {"cells": [settings.cells_length, settings.cells_height, settings.cells_width], "ndof": s.ndof,
           "status": res.status, "reason": res.reason, "newton_iterations": iterations, "reactions": out,
           "seconds": time.perf_counter() - t0}
    if scales:
        rec["residual_scale"] = "20 x the residual at 5 % of the turn, for the legs ending at " + ", ".join(map(str, scales))
    return rec


def settings_for(cells: tuple[int, int, int], incompressibility: str):
    from dataclasses import replace

    from studies.verification.continuum_gold.cantilever import base_settings_3d

    nx, ny, nz = cells
    return replace(base_settings_3d(incompressibility), progression=1.0, cells_length=nx, cells_height=ny,
                   cells_width=nz)


def _cells(text: str) -> tuple[int, int, int]:
    return tuple(int(v) for v in text.split(","))


def find_level(law: str, incompressibility: str, backend: str, case: str, cells, rtol: float = RTOL,
               grading: float = 1.0) -> dict:
    """The level's line of levels.jsonl, computed and appended if it is not there."""
    key = (law, incompressibility, backend, case, list(cells), rtol, grading)
    for r in _lines(HERE / "levels.jsonl"):
        if (r["law"], r["incompressibility"], r["backend"], r.get("case", "twist"), r["cells"], r["rtol"],
                r.get("grading", 1.0)) == key:
            return r
    if backend == "felupe":
        rec = felupe_level(law, incompressibility, settings_for(cells, incompressibility), rtol, case, grading)
    else:
        rec = continuum_level(law, incompressibility, settings_for(cells, incompressibility), rtol, case, grading)
    if rec["status"] == "converged" and not all(
            np.isfinite(v).all() for g in rec["reactions"].values() for v in (g["force"], g["moment"])):
        # reference_fem.statics scales Newton by the residual at full load with the rest at
        # rest; where that inverts the cells at the plate (FElupe, graded twist-bend) it is not
        # a number, which the statics take for an unloaded scene ("converged", no iteration)
        rec = {**rec, "status": "failed", "reason": "the reactions are not numbers: the residual scale at full "
               "load (the plate turned, the rest at rest) is not a number", "reactions": {}}
    lv = {"law": law, "backend": backend, "incompressibility": incompressibility, "rtol": rtol, "case": case,
          "grading": grading, **rec}
    with (HERE / "levels.jsonl").open("a") as f:
        f.write(json.dumps(lv) + "\n")
    print(json.dumps(lv), flush=True)
    return lv


def level(a) -> None:
    """Each mesh of ``--cells NX,NY,NZ [...]`` into levels.jsonl (those there already kept)."""
    for cells in a.cells:
        find_level(a.law, a.incompressibility, a.backend, a.case, _cells(cells), a.rtol, a.grading)


def ancf_run(law: str, element: str, n: int, penalty: float, case: str = "twist", grading: float = 1.0) -> dict:
    from run import element as named   # experiments/spatial_cantilever/run.py

    from ancf.kinematics.spatial.beam import SpatialBeam
    from ancf.kinematics.spatial.statics import clamp_rows, face_reaction, face_rows, rotated_face, solve_static
    from contract import paper

    spec = named(element)
    c = {k: v for k, v in paper.materials()[law].items() if k != "density"}
    L, h, w = paper.CANTILEVER["length"], paper.CANTILEVER["height"], paper.CANTILEVER["width"]
    b = SpatialBeam(spec, L, h, w, n, law, c, penalty, spec.default_rule(), grading, both_ends=True)
    end = b.nodes - 1
    fixed = np.concatenate([clamp_rows(b), face_rows(b, end)])
    clamp = b.reference().ravel()[clamp_rows(b)]
    zero = np.zeros(b.dof)
    t0 = time.perf_counter()
    out, done, iterations, res = {}, 0.0, 0, None
    q_start = None
    for frac in ANGLES:
        held = lambda t, a=done, e=frac: np.concatenate([clamp, rotated_face(b, end, rotation(case, a + t * (e - a)))])
        res = solve_static(b, zero, fixed, load_steps=max(1, round(STEPS * (frac - done))), held=held,
                           start=q_start)
        iterations += res.newton_iterations
        if res.status != "converged":
            break
        r = face_reaction(b, res.q, zero, end)
        out[str(frac)] = reactions(r["force"], r["moment"])
        q_start, done = res.q, frac
    return {"law": law, "case": case, "element": element, "elements": n, "penalty": penalty, "grading": grading,
            "first_element_m": float(b.lengths[0]),
            "points": spec.default_rule(),
            "dof": b.dof, "status": res.status, "reason": res.reason, "newton_iterations": iterations,
            "reactions": out, "seconds": time.perf_counter() - t0}


def ancf(a) -> None:
    out = HERE / "res.jsonl"
    have = {(r["law"], r.get("case", "twist"), r["element"], r["elements"], r["penalty"], r.get("grading", 1.0))
            for r in _lines(out)}
    for n in (int(x) for x in a.counts.split(",")):
        if (a.law, a.case, a.element, n, a.penalty, a.grading) in have:
            continue
        rec = ancf_run(a.law, a.element, n, a.penalty, a.case, a.grading)
        with out.open("a") as f:
            f.write(json.dumps(rec) + "\n")
        print(json.dumps(rec), flush=True)


def main() -> None:
    from contract import paper

    a = argparse.ArgumentParser()
    sub = a.add_subparsers(dest="what", required=True)
    v = sub.add_parser("level")
    v.add_argument("law")
    v.add_argument("--cells", required=True, nargs="+", help="NX,NY,NZ per mesh, e.g. 32,2,2 32,4,4 32,8,8")
    v.add_argument("--rtol", type=float, default=RTOL)
    v.add_argument("--grading", type=float, default=1.0,
                   help="cells along growing by this ratio from both plates to the middle")
    e = sub.add_parser("ancf")
    e.add_argument("law")
    e.add_argument("element")
    e.add_argument("counts")
    e.add_argument("--penalty", type=float, default=paper.PENALTY)
    e.add_argument("--grading", type=float, default=1.0,
                   help="each element this times as long as the one before it, from both plates to the middle")
    for p in (v, e):
        p.add_argument("--case", default="twist", choices=list(CASES))
    for p in (v,):
        p.add_argument("--backend", default="dolfinx", choices=["dolfinx", "felupe"])
        p.add_argument("--incompressibility", default="mixed", choices=["mixed", "penalty"])
    a = a.parse_args()
    {"level": level, "ancf": ancf}[a.what](a)


if __name__ == "__main__":
    main()
