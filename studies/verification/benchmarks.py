"""Benchmarks whose answers no one here wrote: closed forms, published tables, another code.

A benchmark is data (:class:`Benchmark`): a scene per solver, the quantity read from the
record, the reference value and its kind (closed form, literature table, another code),
its source (citation with section, table or file), and a tolerance with its derivation,
fixed here before any run. Every built-in element runs each case it can (the cable
HC2n-8 the plane-stress ones), and both continuum codes where the continuum applies. The report lists every (case, solver) with
reference, tolerance, measured error and verdict; every miss names its cause, measured: from
the records where they carry it (a non-conforming element's failed patch test, an error that
grows with L/h), else by small runs around the case (the mesh doubled, the rule raised, the
penalty x 10: :data:`CAUSES`, each with its measurements, which
``experiments/benchmark_causes.py`` repeats); a miss never hidden.

The cases (the references in :mod:`studies.verification.closed_forms`):

1. ``tension``: homogeneous uniaxial tension of the paper's strip (L = 160 mm, h = 5 mm,
   w = 7 mm) to a large stretch, every law, in plane stress and in plane strain: the
   ``slide`` support (the end face held on x = 0, free along it), the end load as a
   uniform traction. The closed form is the incompressible stretch lambda(P). The state is
   in every element's space and in the continuum's, so only the solvers' stops separate
   them: tolerance 1e-6 on lambda - 1 (100 x Newton's 1e-8 of the load); the penalised
   plane strain of ANCF adds its own volumetric strain, J - 1 of about P / alpha: tolerance
   2 P lambda / (alpha (lambda - 1)) on lambda - 1 (twice that estimate). A non-conforming
   element (HB2n-12, HB3n-12: its patch test fails, :func:`ancf.checks.element.patch`) does not
   hold a homogeneous state exactly; its error is shown against the same tolerance.
2. ``shear``: simple shear at a material point (a beam cannot carry it): the ANCF
   material's first Piola-Kirchhoff P_12 at F = [[1, gamma], [0, 1]] against tau = 2 gamma
   (W1 + W2) (J = 1: the penalty and the isochoric split do nothing), every law and
   formulation: tolerance 1e-12 relative (both are explicit formulas; round-off).
3. ``elastica``: the slender limit. A cantilever (L = 350 mm, w = 7 mm, h = L / (L/h)),
   Neo-Hookean in plane stress, on the beam's clamp (``slide``: the end section held on
   x = 0, so it cannot turn, and free to contract; the face clamp, which also holds the
   section's shape, stiffens the first element, an error of order l_e / L that does not
   fall with h / L), under a transverse end load of alpha = P L^2 /
   (E I) (E = 3 mu, the small-strain modulus), 32 elements, against the inextensible
   elastica (Bisshopp and Drucker 1945). The beam departs from the elastica by its shear,
   its stretch and its material's nonlinearity, each of order (h / L)^2: shear 0.9 (h/L)^2
   (Timoshenko, kappa = 5/6), stretch alpha / 12 (h/L)^2, the law's cubic term alpha^2 / 4
   (h/L)^2 (strain amplitude alpha h / 2L); tolerance twice their sum on |u_tip - u_el| / L.
   The elastica itself is checked against Mattiasson's published table (the table's five
   decimals: half a unit of the fifth, 5e-6).
4. ``timoshenko``: the small-strain limit of a cantilever under a uniform load (the card's
   probe: L = 350 mm, L / h = 35, 70, 140, deflection 1e-4 L), on the beam's clamp
   (``slide``), against Euler-Bernoulli plus Timoshenko's shear (kappa = 5/6): tolerance
   2 (h/L)^2 on the relative tip deflection (plane-stress elasticity departs from the beam
   theory by terms of that relative order: Timoshenko & Goodier, Theory of Elasticity,
   the uniformly loaded beam).
5. ``bending``: pure bending at finite strain, every law, in plane strain against Rivlin's
   flexure (1949: exact for an incompressible block) and in plane stress against the same
   flexure of a plane-stress strip (a two-point problem across the thickness, solved to
   round-off: :func:`studies.verification.closed_forms.plane_stress_bending`). The strip (h = 5 mm) stands
   on its symmetry plane x = 0 (``slide``) under the end moment (:mod:`contract.loads`) of
   the exact solution at kappa h = 0.2 and 0.5 in plane stress, 0.2 and 0.3 in plane strain
   (Gent: 0.1, 0.2, below its lock). The case stops at kappa h = 0.3 because past about 0.35
   neither solver holds the flexure under this couple, for two causes found together
   (``experiments/bending_departure/REPORT.md``, every number there re-run by its scripts):
   the couple's traction is linear and symmetric in Y while Rivlin's end traction is not
   (-1.80 / +1.23 MPa on the inner / outer face at kappa h 0.39, the couple's -+1.42), so it
   leaves a self-equilibrated end zone, whose inner corner collapses as kappa h grows
   (DOLFINx Q2 at h / 4: det F 0.96 -> 0.10 from 0.30 to 0.40 while the interior stays
   Rivlin's to 1e-4): that collapsed zone is what the end rotation measured at 0.39 (1.8 to
   4.6 % off in the first runs, 1.45 / 0.32 % at h / 4 / h / 8 in these: near the threshold it
   depends on the mesh, the length and the path) and what stops ANCF (HB2n-40p x 16 fails
   from 0.33); and above 0.40-0.42 the
   exact flexure is an unstable state of the Q2 quadrilateral itself (Q2/Q1 mixed and
   penalty: 2 unstable directions at 0.42, a mode two cells long whatever the mesh), while
   P2/P1 triangles hold it stable to 0.50 and the real block is far from wrinkling (stretch
   0.544, kappa h 1.55) or creasing (about 0.65). Neither the end rotation crossing pi (the
   extra rotation is 0.0100 rad at kappa h 0.39 for every L from 2 h to 12 h) nor the load
   path is the cause. Loaded through a straight end face free to slide and to thin (the couple
   as a multiplier on the face's line: zero resultant, moment exactly M, a shear-free normal
   traction the block distributes), both solvers meet Rivlin to 1e-4 to 5e-4 up to kappa h =
   0.50 (Q2 only to 0.41); that couple is not yet a load of the scenes, so this case stops at
   0.3. The couple
   is applied as a conservative couple on the end face's rotation, not as Rivlin's end
   tractions: the two differ by a self-equilibrated load whose effect stays within about h
   of the end (Saint-Venant), so the strip is run at two lengths, 8 h and 16 h, and the
   curvature read as kappa = (theta(16 h) - theta(8 h)) / 8 h, where that end zone cancels.
   The exact section r(Y) is no polynomial, so no element holds it exactly: the tolerance
   is a requirement, 1e-3 relative on kappa, the accuracy class the lock-free elements are
   built for (0.1 % on the paper's cantilever); the penalised plane strain of ANCF adds its
   own softening of the bending stiffness by mu / alpha (E' = 4 mu (3 alpha + mu) /
   (3 alpha + 4 mu)): 2 mu / alpha more. The continuum codes run Q2 cells of h / 8 (and
   plane strain exactly incompressible, mixed): with h / 4 Gent's flexure near its lock is
   not resolved (1e-3 off at kappa h = 0.2, 6e-5 with h / 8), and at 10 load steps one code
   reached another equilibrium of the shorter strip (20 steps).
6. ``arc``: the slender limit under an end couple, Euler's circular arc of angle phi =
   M L / (E I) (E = 3 mu), on the slender cantilever of the elastica case (``slide``),
   neo-Hookean in plane stress, phi = 1 and 2 pi (a full roll-up), L / h = 25 to 200. The
   strip departs from the arc by its own finite-strain bending (the curvature at the couple
   and the mid-line's stretch, both of order (kappa h)^2), which the exact plane-stress
   pure bending gives: tolerance twice that departure (:func:`arc_departure`), plus the
   Newton floor 1e-6.
"""
from __future__ import annotations

from ancf.build import build_material
from contract.errors import SceneError
from contract.scene import MaterialSpec

from .benchmark_rows import mattiasson_rows, rows
# STRIP, NEWTON_TOL and arc_departure too: experiments/benchmark_causes.py reads them here
from .benchmark_scenes import (NEWTON_TOL, STRIP, _solvers, arc_departure, arc_scene, bending_scene,  # noqa: F401
                               elastica_scene, shear_scene, tension_scene, timoshenko_scene)
from ..engine.case import make_case
from ..engine.solvers import Solver, register_solver
from ..engine.report import Section, Table

STUDY = {
    "name": "benchmarks",
    "title": "Benchmarks with outside references: closed forms, published tables",
    "grid": {
        "elements": {"registered": {}},     # every registered element
        "laws": ["neo-hookean", "mooney-rivlin", "yeoh", "gent"],
        "formulations": ["plane-stress", "plane-strain"],
        "codes": ["dolfinx", "felupe"],
        # the nominal stress of tension per law (Pa): stretches 1.7 to 2.1 (Gent: its limit)
        "tension_stress": {"neo-hookean": 3e6, "mooney-rivlin": 3e6, "yeoh": 3e6, "gent": 3e5},
        "tension_elements": 4,
        "penalty_factor": 1e4,          # alpha = this x C10 (mu / 2 for a law without C10)
        # shear strains within each law's domain (Gent's: gamma^2 < Jm = 0.1)
        "shear_gammas": {"neo-hookean": [0.5, 2.0], "mooney-rivlin": [0.5, 2.0], "yeoh": [0.5, 2.0],
                         "gent": [0.1, 0.3]},
        "elastica_alphas": [1.0, 5.0],
        "elastica_slenderness": [25.0, 50.0, 100.0, 200.0],
        "elastica_elements": 32,
        "timoshenko_slenderness": [35.0, 70.0, 140.0],
        "timoshenko_elements": 16,
        # pure bending: the curvature kappa h of the exact solution per formulation and law (Gent:
        # below its lock, kappa h = 0.32 in plane strain; plane strain to 0.3: see the module doc),
        # the two lengths in h, ANCF elements and the continuum's cells per h along (and across)
        "bending_curvatures": {
            "plane-stress": {"neo-hookean": [0.2, 0.5], "mooney-rivlin": [0.2, 0.5], "yeoh": [0.2, 0.5],
                             "gent": [0.1, 0.2]},
            "plane-strain": {"neo-hookean": [0.2, 0.3], "mooney-rivlin": [0.2, 0.3], "yeoh": [0.2, 0.3],
                             "gent": [0.1, 0.2]}},
        "bending_lengths": [8, 16],
        "bending_elements_per_h": 2,
        "bending_cells_per_h": 8,
        # the elastica under an end moment: the arc's angle phi = M L / (E I)
        "arc_angles": [1.0, 6.283185307179586],
        "arc_slenderness": [25.0, 50.0, 100.0, 200.0],
        "arc_elements": 32,
    },
    "tiny": {"elements": ["HB2n-16", "HB2n-12"], "laws": ["neo-hookean"], "codes": ["dolfinx"],
             "shear_gammas": {"neo-hookean": [0.5]}, "elastica_alphas": [1.0], "elastica_slenderness": [25.0, 50.0],
             "elastica_elements": 8, "timoshenko_slenderness": [35.0], "timoshenko_elements": 8,
             "bending_curvatures": {"plane-stress": {"neo-hookean": [0.5]}, "plane-strain": {}},
             "arc_angles": [6.283185307179586],
             "arc_slenderness": [50.0], "arc_elements": 8},
}


# -- the material point: this study's own solver (registered at the end) -------------------------

def check_material_point(scene: dict) -> None:
    m = dict(scene.get("material") or {})
    try:
        spec = MaterialSpec(m.pop("law"), m.pop("formulation"), m.pop("density"), m, m.pop("penalty", None))
    except KeyError as e:
        raise SceneError(f"material.{e.args[0]}: required") from None
    build_material(spec)
    F = (scene.get("point") or {}).get("F")
    if not (isinstance(F, list) and len(F) == 2 and all(isinstance(r, list) and len(r) == 2 for r in F)):
        raise SceneError(f"point.F: a 2 x 2 deformation gradient, got {F!r}")


def run_material_point(scene: dict) -> dict:
    """The ANCF material at one deformation gradient: its energy density and first
    Piola-Kirchhoff stress (the record's ``point``). Its imports stay inside it: its text is
    the fingerprint of the material-point records (a lift would recompute them)."""
    import numpy as np

    from ancf.build import build_material
    from contract.record import new_record
    from contract.scene import MaterialSpec

    m = dict(scene["material"])
    spec = MaterialSpec(m.pop("law"), m.pop("formulation"), m.pop("density"), m, m.pop("penalty", None))
    W, P, _ = build_material(spec).evaluate(np.array(scene["point"]["F"], float), tangent=False)
    rec = new_record("ancf-material", scene)
    rec.update(status="converged", reason=None, point={"W": float(W), "P": np.asarray(P).tolist()})
    return rec


# -- cases and report -------------------------------------------------------------------------


def cases(grid: dict, tiny: bool) -> list:
    out = []
    for law in grid["laws"]:
        for form in grid["formulations"]:
            for solver in _solvers(grid, form):
                out.append(make_case("benchmarks", "continuum" if solver in grid["codes"] else "ancf",
                                     tension_scene(grid, law, form, solver)))
            for gamma in grid["shear_gammas"][law]:
                out.append(make_case("benchmarks", "ancf-material", shear_scene(grid, law, form, gamma)))
    for alpha in grid["elastica_alphas"]:
        for ratio in grid["elastica_slenderness"]:
            out += [make_case("benchmarks", "ancf", elastica_scene(grid, alpha, ratio, el)) for el in grid["elements"]]
    for ratio in grid["timoshenko_slenderness"]:
        out += [make_case("benchmarks", "ancf", timoshenko_scene(grid, ratio, el)) for el in grid["elements"]]
    for form in grid["formulations"]:
        for law, curvatures in grid["bending_curvatures"][form].items():
            if law not in grid["laws"]:
                continue
            for x in curvatures:
                for solver in _solvers(grid, form):
                    out += [make_case("benchmarks", "continuum" if solver in grid["codes"] else "ancf",
                                      bending_scene(grid, law, form, x, n, solver)) for n in grid["bending_lengths"]]
    for phi in grid["arc_angles"]:
        for ratio in grid["arc_slenderness"]:
            out += [make_case("benchmarks", "ancf", arc_scene(grid, phi, ratio, el)) for el in grid["elements"]]
    return out


def report(ctx) -> Section:
    rs = rows(ctx)
    sec = Section(ctx.study.title,
                  "Every case with its reference (kind and source), the tolerance fixed before the runs and why, "
                  "the measured value and error, and the verdict (`studies/verification/benchmarks.py` states each derivation).")
    sec.table(ctx, Table("benchmarks", ["case", "solver", "quantity", "reference", "kind", "source", "tolerance",
                                        "why", "value", "error", "verdict", "note"],
                         [[r.case, r.solver, r.quantity, r.reference, r.kind, r.source, r.tolerance, r.why, r.value,
                           r.error, r.verdict, r.note] for r in rs],
                         {3: ".8g", 6: ".2g", 8: ".8g", 9: ".2e"}),
              "The benchmark cases: error relative to the reference (elastica: the tip's distance from the "
              "elastica's tip over L).")
    sec.table(ctx, Table("benchmarks_mattiasson", ["alpha = P L^2 / EI", "u/L published", "u/L closed form",
                                                   "v/L published", "v/L closed form", "largest difference",
                                                   "tolerance (half a unit of the table's last digit)", "verdict"],
                         mattiasson_rows(), {2: ".8f", 4: ".8f", 5: ".1e", 6: ".0e"}),
              "The elastica's closed form against Mattiasson (1981), Int. J. Numer. Meth. Engng 17, 145-153, "
              "Table 1, as quoted with that citation by two open-source test suites (the paper itself was not "
              "read): a literature table.")
    n = len(rs)
    passed = sum(r.verdict == "pass" for r in rs)
    by_solver: dict = {}
    for r in rs:
        if r.verdict != "pass":
            kind = r.case.split()[0]
            why = r.cause or "no cause named"
            by_solver.setdefault(r.solver, {}).setdefault((kind, why), 0)
            by_solver[r.solver][(kind, why)] += 1
    lines = [f"- {passed} of {n} cases pass."]
    for solver, kinds in sorted(by_solver.items()):
        lines.append(f"- {solver} misses " + "; ".join(f"{k} {c} x ({why})" for (k, why), c in sorted(kinds.items())))
    passing = sorted({r.solver for r in rs} - set(by_solver))
    if passing:
        lines.append(f"- every case passes for: {', '.join(passing)}.")
    worst = sorted((r for r in rs if r.verdict == "pass" and r.error is not None and r.tolerance),
                   key=lambda r: -(r.error / r.tolerance))[:3]
    if worst:
        lines.append("- closest to their tolerance among the passing: "
                     + "; ".join(f"{r.case} {r.solver} {r.error:.2g} of {r.tolerance:.2g}" for r in worst) + ".")
    sec.text = "\n".join(lines)
    return sec


# the material point, this study's own solver (the engine imports this module to run its cases)
register_solver(Solver("ancf-material", run_material_point, check_material_point))
