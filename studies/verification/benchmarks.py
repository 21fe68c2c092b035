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
   element (HB2n-12, HB3n-12: its patch test fails, :func:`ancf.checks.patch`) does not
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

import math
from dataclasses import dataclass
from functools import lru_cache

from contract import paper

from .closed_forms import (MATTIASSON_1981, MATTIASSON_1981_DIGITS, elastica_end_moment, elastica_tip_load,
                           plane_stress_bending, plane_stress_curvature, rivlin_bending, simple_shear_stress,
                           uniaxial_stretch)
from ..common.grid import fem_table
from ..engine.case import make_case
from ..engine.solvers import Solver, register_solver
from ..engine.report import Section, Table

STUDY = {
    "name": "benchmarks",
    "title": "Benchmarks with outside references: closed forms, published tables",
    "grid": {
        "elements": ["LB2n-12", "HB2n-12", "HB3n-12", "HB2n-16", "HB2n-20xyp", "HB2n-20xypm", "HB2n-40p",
                     "HB2n-60p", "HC2n-8"],
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

STRIP = {"length": 0.160, "height": 0.005, "width": 0.007}
SLENDER_BEAM = {"length": 0.350, "width": 0.007}
NEWTON_TOL = 1e-6                    # 100 x the Newton tolerance of the load (1e-8)


def constants(law: str) -> tuple[dict, float]:
    """(the law's constants, density): the paper's for its three laws, the example's for the others."""
    from mechanics.laws import get_law

    if law in paper.materials():
        c = dict(paper.materials()[law])
        return c, c.pop("density")
    return dict(get_law(law).example), paper.materials()["neo-hookean"]["density"]


def mu_of(law: str) -> float:
    from mechanics.laws import get_law

    return get_law(law).shear_modulus(constants(law)[0])


def penalty(grid: dict, law: str) -> float:
    c, _ = constants(law)
    return grid["penalty_factor"] * c.get("C10", mu_of(law) / 2)


# -- 1. tension ---------------------------------------------------------------------------

def tension_scene(grid: dict, law: str, form: str, solver: str) -> dict:
    c, rho = constants(law)
    P = grid["tension_stress"][law]
    F = P * STRIP["height"] * STRIP["width"]
    m = {"law": law, "formulation": form, "density": rho, **c}
    if form == "plane-strain":
        m["penalty"] = penalty(grid, law)
    d = {"name": f"bench-tension-{law}-{form}-{solver}", "beam": dict(STRIP), "material": m,
         "supports": {"left": "slide"}, "loads": {"tip_force": [F, 0.0]}, "analysis": {"kind": "static"}}
    if solver in grid["codes"]:
        d["fem"] = fem_table(solver, model=form, cells_length=8, cells_height=2)
    else:
        d["ancf"] = {"element": solver, "elements": grid["tension_elements"]}
    return d


def tension_reference(grid: dict, law: str, form: str) -> tuple[float, float]:
    """(lambda - 1 of the closed form, the tolerance on it relative: see the module doc)."""
    P = grid["tension_stress"][law]
    lam = uniaxial_stretch(law, constants(law)[0], form, P)
    return lam - 1.0, lam


# -- 2. simple shear at a material point --------------------------------------------------------

def shear_scene(grid: dict, law: str, form: str, gamma: float) -> dict:
    c, rho = constants(law)
    m = {"law": law, "formulation": form, "density": rho, **c}
    if form == "plane-strain":
        m["penalty"] = penalty(grid, law)
    return {"name": f"bench-shear-{law}-{form}-g{gamma:g}", "material": m,
            "analysis": {"kind": "material-point"}, "point": {"F": [[1.0, gamma], [0.0, 1.0]]}}


def check_material_point(scene: dict) -> None:
    from ancf.build import build_material
    from contract.errors import SceneError
    from contract.scene import MaterialSpec

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
    Piola-Kirchhoff stress (the record's ``point``)."""
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


# -- 3. the elastica ---------------------------------------------------------------------------

def elastica_scene(grid: dict, alpha: float, ratio: float, element: str) -> dict:
    L, w = SLENDER_BEAM["length"], SLENDER_BEAM["width"]
    h = L / ratio
    c, rho = constants("neo-hookean")
    E = 3.0 * mu_of("neo-hookean")
    P = alpha * E * w * h ** 3 / 12.0 / L ** 2
    n = grid["elastica_elements"]
    return {"name": f"bench-elastica-a{alpha:g}-Lh{ratio:g}-{element}-{n}",
            "beam": {"length": L, "height": h, "width": w},
            "material": {"law": "neo-hookean", "formulation": "plane-stress", "density": rho, **c},
            "ancf": {"element": element, "elements": n}, "supports": {"left": "slide"},
            "loads": {"tip_force": [0.0, -P]}, "analysis": {"kind": "static", "load_steps": 20}}


def elastica_tolerance(alpha: float, ratio: float) -> float:
    return 2.0 * (0.9 + alpha / 12.0 + alpha ** 2 / 4.0) / ratio ** 2


# -- 4. Timoshenko ----------------------------------------------------------------------------

def timoshenko_scene(grid: dict, ratio: float, element: str) -> dict:
    """The card's slender probe (:func:`studies.design.card.slender_scene`) on Timoshenko's
    clamp: the end section held from turning and free to deform (``slide``)."""
    from ..design.card_cases import slender_scene

    d = slender_scene(element, ratio, grid["timoshenko_elements"])
    d["name"] = f"bench-timoshenko-Lh{ratio:g}-{element}-{grid['timoshenko_elements']}"
    d["supports"] = {"left": "slide"}
    return d


def timoshenko_reference(ratio: float) -> float:
    """The tip deflection (m) of the probe by Euler-Bernoulli + Timoshenko's shear."""
    from ..design.card_cases import beam_theory

    return beam_theory(ratio)[1]


# -- 5. pure bending ---------------------------------------------------------------------------

BENDING_TOL = 1e-3      # relative on kappa: a requirement (see the module doc), not a round-off


def bending_scene(grid: dict, law: str, form: str, x: float, lengths: int, solver: str) -> dict:
    """The strip of h = 5 mm, w = 7 mm and ``lengths`` x h on the symmetry plane x = 0 (``slide``)
    under the end moment of the exact pure bending at kappa h = x."""
    c, rho = constants(law)
    h, w = STRIP["height"], STRIP["width"]
    m = {"law": law, "formulation": form, "density": rho, **c}
    if form == "plane-strain":
        m["penalty"] = penalty(grid, law)
    M = w * bending_reference(law, form, x)["moment_per_width"]
    d = {"name": f"bench-bending-{law}-{form}-kh{x:g}-L{lengths}h-{solver}",
         "beam": {"length": lengths * h, "height": h, "width": w}, "material": m,
         "supports": {"left": "slide"}, "loads": {"end_moment": M},
         "analysis": {"kind": "static", "load_steps": max(20, math.ceil(2 * x * lengths))}}
    if solver in grid["codes"]:
        n = grid["bending_cells_per_h"]
        d["fem"] = fem_table(solver, model=form, cells_length=n * lengths, cells_height=n)
    else:
        d["ancf"] = {"element": solver, "elements": grid["bending_elements_per_h"] * lengths}
    return d


def bending_reference(law: str, form: str, x: float) -> dict:
    """The exact pure bending at kappa h = x of the strip's section: Rivlin's flexure in plane
    strain, the plane-stress two-point problem otherwise (:mod:`studies.verification.closed_forms`)."""
    return dict(_bending_reference(law, form, float(x)))


@lru_cache(maxsize=None)
def _bending_reference(law: str, form: str, x: float) -> dict:
    # once per process: the plane-stress shooting takes a tenth of a second, and each of its
    # cases' scenes (every solver, every length) asks for it
    c, _ = constants(law)
    h = STRIP["height"]
    solve = rivlin_bending if form == "plane-strain" else plane_stress_bending
    return solve(law, c, x / h, h)


# The cause of each miss of the ANCF elements, measured by small runs around the case: the mesh
# doubled, the rule raised to 5 x 5 (and 8 x 8), the penalty x 10 (experiments/benchmark_causes.py
# re-runs every sweep quoted here). Keys (case kind, element, law, formulation), None for any;
# the most specific entry applies. Signed errors of kappa (bending) and end rotation / phi - 1
# (arc), as measured: "d" elements per h along; "[a, b]" the rule; "C10" the penalty alpha.
_SECTION_2 = ("the quadratic section's own miss of the exact flexure (what a 5 x 5 rule leaves, the same at "
              "twice the elements, as HB2n-20xyp's)")
CAUSES = {
    # HB2n-20xyp / -20xypm: [3, 3] (their default at l_e / h = 0.5), [5, 5], [8, 8] at 2 / 4 / 8 d: neo-Hookean
    # plane stress kappa h 0.2 -0.530 / -0.536 / -0.536 %, 0.5 -2.95 / -3.12 / -3.12 %; plane strain 0.3
    # -0.270 / -0.287 %, Mooney-Rivlin -0.49 / -0.51 %; HB2n-40p (quartic across) 0.000 / -0.003 / +0.024 %.
    # Gent: [3, 3] +0.19 % plane stress / +0.66 % plane strain at 0.2, [5, 5] -0.50 / -0.46 % at 2, 4, 8 d.
    ("bending", "HB2n-20xyp", None, None): "its section, quadratic across (y^2 and x y^2: the thickness stretch "
                                           "linear in y), misses the exact flexure, whose section is no polynomial "
                                           "(about the same with twice and four times the elements and a 5 x 5 or "
                                           "8 x 8 rule; Gent: its 3 points across leave kappa above the exact, "
                                           "5 x 5 points below it as for the other laws)",
    ("bending", "HB2n-20xypm", None, None): "its section, quadratic across (y^2 and x y^2: the thickness stretch "
                                            "linear in y), misses the exact flexure, whose section is no "
                                            "polynomial (about the same with twice and four times the elements "
                                            "and a 5 x 5 or 8 x 8 rule; Gent: its 3 points across leave kappa "
                                            "above the exact, 5 x 5 points below it as for the other laws)",
    # HB2n-40p / -60p: Gent plane strain at 0.2 +2.075 % at 2, 4, 8 d and with [5, 5] and [8, 8] (HB2n-40p); HB2n-40p
    # with y^3 and x y^3 added to its pressure (an element registered by the measuring script): Gent 0.1 / 0.2
    # +0.022 / +0.058 % (as is: +0.169 / +2.075 %), neo-Hookean 0.3 +0.021 % (+0.024 %).
    ("bending", "HB2n-40p", "gent", "plane-strain"): "its element pressure, quadratic in y, leaves J - 1 free in y^3, "
                                                     "which Gent near its lock sees (a pressure cubic in y removes "
                                                     "the miss; the same with twice the elements and a richer rule)",
    ("bending", "HB2n-60p", "gent", "plane-strain"): "its element pressure, quadratic in y, leaves J - 1 free in y^3, "
                                                     "which Gent near its lock sees (a pressure cubic in y removes "
                                                     "the miss)",
    # LB2n-12 plane stress: -24.94 / -24.93 / -24.92 % at 2 / 4 / 8 d (NH 0.2), [5, 5] -25.22 / -25.21 % at 2 / 4 d;
    # every law -23.7 to -26.4 % (Gent -16 to -24 %), the same at 2 and 4 d.
    ("bending", "LB2n-12", None, "plane-stress"): "Poisson locking: its section is linear across (r_y the same at "
                                                  "every y), so the thickness stretch cannot vary across and the "
                                                  "strip bends as one held from contracting, E / (1 - nu^2) = 4/3 E "
                                                  "at small strain (kappa 3/4 of the exact; about the same with twice "
                                                  "and four times the elements and a 5 x 5 rule)",
    # LB2n-12 plane strain: kappa / exact = 7.9e-3 / 7.9e-4 / 7.9e-5 at alpha = 1e3 / 1e4 / 1e5 C10 (NH 0.2; every
    # law alike), the same at 1 to 8 d and with [5, 5].
    ("bending", "LB2n-12", None, "plane-strain"): "volumetric locking: its linear section cannot bend at constant "
                                                  "volume, so the penalty carries the couple and kappa falls as "
                                                  "1 / alpha (10 x alpha: 10 x smaller; the same with 1 to 8 "
                                                  "elements per h and a 5 x 5 rule)",
    # LB2n-12 arc: end rotation / phi 0.7496-0.7503 (phi = 1) and 0.735-0.760 (2 pi) at 32 elements, 0.750 at 64
    # and 128, the same with [5, 5].
    ("arc", "LB2n-12", None, None): "Poisson locking of its linear section (as in its pure bending): the end turns "
                                    "about 3/4 of phi at every L/h, with 32, 64 or 128 elements and a 5 x 5 rule",
    # HB2n-12 arc, end rotation / phi at l_e / h = 0.78 / 1.6 / 3.1 / 6.3 (32 elements, L/h 25 to 200; phi = 1):
    # 0.997 / 0.987 / 0.955 / 0.883; with 64 elements 0.9995 / 0.9967 / 0.9871 / 0.9553 at L/h 25 / 50 / 100 /
    # 200 (l_e / h halved: the values of half that L/h at 32); with [5, 5] the same to 4 digits.
    ("arc", "HB2n-12", None, None): "locking set by l_e / h: its end turns short of phi by an amount that depends "
                                    "on l_e / h alone (the same at 64 elements as at 32 with half the L/h) and not "
                                    "on the rule (5 x 5 the same); its x^2 + y^2 mode ties the section's r_yy to "
                                    "the centre line's r_xx",
    # HB3n-12 arc: end rotation / phi 0.958 / 0.888 / 0.809 / 0.768 at l_e / h = 0.78 / 1.6 / 3.1 / 6.3 (phi = 1),
    # 0.9578 at 64 elements and L/h 50 (l_e / h 0.78), [5, 5] the same: toward LB2n-12's 3/4.
    ("arc", "HB3n-12", None, None): "locking set by l_e / h: its end turns short of phi by an amount that depends "
                                    "on l_e / h alone (the same at 64 elements as at 32 with half the L/h), not on "
                                    "the rule (5 x 5 the same), toward the linear section's 3/4 as l_e / h grows; "
                                    "its x^2 + y^2 mode ties the section's r_yy to the centre line's r_xx",
    # HB2n-16 arc (misses at L/h 100, 200): phi = 1, L/h 200: distance 6.4e-4 / 4.3e-5 / 3.7e-6 at 32 / 64 / 128
    # elements; L/h 100: 1.7e-4 / 1.5e-5; phi = 2 pi, L/h 200: 4.8e-2 / 3.4e-3 / 7.0e-5; [5, 5] the same at 32.
    ("arc", "HB2n-16", None, None): "discretisation at l_e / h of 3 and more: the distance falls 10 x and more with "
                                    "twice the elements and passes with four times; a 5 x 5 rule changes nothing",
    # HB2n-16 plane stress, [3, 2] (its default at l_e / h = 0.5) / [5, 5] at 2 d / [5, 5] at 4 d: NH 0.2 +0.22 /
    # -0.60 / -0.55 %, 0.5 +1.23 / -3.47 / -3.20 %; Mooney-Rivlin and Yeoh alike (HB2n-20xyp: -0.54, -3.12 %).
    ("bending", "HB2n-16", None, "plane-stress"): "its rule's 2 points across (its default at l_e / h = 0.5) soften "
                                                  "it past the exact by more than " + _SECTION_2,
    # Gent plane stress 0.1 / 0.2: [3, 2] +2.07 / +8.45 %, [3, 3] -0.10 / +0.14 %, [5, 5] -0.15 / -0.55 % (2 and 4 d).
    ("bending", "HB2n-16", "gent", "plane-stress"): "its rule's 2 points across do not see the outer fibres' "
                                                    "stiffening near Gent's lock (with 5 x 5 points it is left with "
                                                    + _SECTION_2 + ")",
    # HB2n-16 plane strain, [3, 2]: NH 0.2 +0.76 / +0.80 / +0.81 % at 2 / 4 / 8 d, +0.94 / +0.76 / +0.74 % at
    # alpha = 1e3 / 1e4 / 1e5 C10; 0.3 +1.64 %; [3, 3] or [5, 5]: -64 % (NH 0.2), -37 / -64 / -78 % at 1e3 / 1e4 /
    # 1e5 C10, the same at 4 and 8 d. Gent 0.1 / 0.2: [3, 2] +2.9 / +11.5 %, [5, 5] -47 / -60 %.
    ("bending", "HB2n-16", None, "plane-strain"): "its rule's 2 points across: with 3 or more points across its "
                                                  "section, which has no pressure field, locks (kappa far below the "
                                                  "exact, the further the higher the penalty); the 2 points relieve the "
                                                  "lock and leave it too soft, the same with twice and four times "
                                                  "the elements and at 10 x the penalty",
    ("bending", "HB2n-16", "gent", "plane-strain"): "its rule's 2 points across: with 3 or more points across its "
                                                    "section, which has no pressure field, locks; the 2 points "
                                                    "relieve the lock and do not see the outer fibres' stiffening "
                                                    "near Gent's lock (too soft, the same with twice the elements "
                                                    "and at 10 x the penalty)",
    # HB2n-12 plane stress, [3, 2] (default) / [5, 5] at 2 d / [5, 5] at 4 d: NH 0.5 +0.32 / -2.23 / -1.28 %;
    # Mooney-Rivlin 0.2 +0.13 / -0.42 / -0.19 %, 0.5 +1.18 / -1.99 / -1.00 %; Yeoh 0.2 +0.15 / -0.47 / -0.24 %,
    # 0.5 +1.17 / -2.25 / -1.34 %.
    ("bending", "HB2n-12", None, "plane-stress"): "discretisation of the non-conforming element at 2 elements per "
                                                  "h, which its rule's 2 points across turn into a softening: "
                                                  "fully integrated (5 x 5) its kappa is too small by an error that "
                                                  "about halves with twice the elements",
    # Gent 0.1 / 0.2: [3, 2] +1.90 / +8.20 %, [3, 3] -0.17 / +0.15 %, [5, 5] -0.21 / -0.48 % at 2 d, -0.09 / -0.31 %
    # at 4 d.
    ("bending", "HB2n-12", "gent", "plane-stress"): "its rule's 2 points across do not see the outer fibres' "
                                                    "stiffening near Gent's lock (fully integrated, 5 x 5, the error "
                                                    "is a tenth of it and falls with the mesh)",
    # HB2n-12 plane strain, [3, 2] at 2 d: NH 0.2 -2.75 % (alpha 1e4 C10), -7.40 % (1e5), +0.06 % (1e3); at 4 / 8 d
    # +0.44 / +0.76 %; NH 0.3 -8.3 % (1e4), -10.7 % (1e5), +0.31 % at 4 d; Mooney-Rivlin and Yeoh alike; [5, 5]:
    # -16 to -24 % at 2 d.
    ("bending", "HB2n-12", None, "plane-strain"): "partial volumetric locking at 2 elements per h: kappa too small "
                                                  "by an error that grows with the penalty (10 x alpha: about 3 x at "
                                                  "kappa h 0.2) and turns into a softening like HB2n-16's with twice "
                                                  "and four times the elements; fully integrated (5 x 5) it locks",
    # Gent 0.1 / 0.2: +2.50 / +8.08 % (1e4 C10), +0.75 / +1.89 % (1e5), +2.83 / +11.2 % at 4 d; [5, 5] -19 / -34 %.
    ("bending", "HB2n-12", "gent", "plane-strain"): "its rule's 2 points across do not see the outer fibres' "
                                                    "stiffening near Gent's lock (too soft, more so with twice the "
                                                    "elements), less its partial volumetric locking (10 x alpha: "
                                                    "kappa a third to a quarter as far off); fully integrated it "
                                                    "locks",
    # HB3n-12 plane stress, [3, 2] (default) / [5, 5] at 2 d / [5, 5] at 4 d: NH 0.2 -1.80 / -2.20 / -0.71 %, 0.5
    # -1.32 / -3.65 / -1.73 %; Mooney-Rivlin and Yeoh alike; [5, 5] at 8 d (NH 0.2) -0.30 %.
    ("bending", "HB3n-12", None, "plane-stress"): "discretisation of the non-conforming element at 2 elements per "
                                                  "h: fully integrated (5 x 5) its kappa is too small by an error "
                                                  "that falls about 2 to 3 x with twice the elements; its rule's 2 "
                                                  "points across soften it",
    # Gent 0.1 / 0.2: [3, 2] +0.13 / +6.52 %, [5, 5] -1.85 / -1.71 % at 2 d, -0.52 / -0.64 % at 4 d.
    ("bending", "HB3n-12", "gent", "plane-stress"): "discretisation of the non-conforming element at 2 elements per "
                                                    "h (fully integrated its kappa is too small by an error that "
                                                    "falls about 3 x with twice the elements) and its rule's 2 points "
                                                    "across, which do not see the outer fibres' stiffening near "
                                                    "Gent's lock",
    # HB3n-12 plane strain, [3, 2]: NH 0.2 +0.59 / +0.80 / +0.81 % at 2 / 4 / 8 d (HB2n-16: +0.76 / +0.80 / +0.81 %),
    # +0.96 / +0.59 / -1.10 % at alpha 1e3 / 1e4 / 1e5 C10; 0.3 +0.74 % (1e4), -5.5 % (1e5), +1.70 % at 4 d;
    # Mooney-Rivlin, Yeoh alike; [5, 5] -17 to -22 % at 2 d. Gent 0.1 / 0.2 +2.9 / +11.4 %, 1e5: +2.7 / +9.7 %.
    ("bending", "HB3n-12", None, "plane-strain"): "its rule's 2 points across, as HB2n-16's: fully integrated "
                                                  "(5 x 5) it locks; the 2 points relieve the lock and leave it too "
                                                  "soft (HB2n-16's softening with twice the elements), less a "
                                                  "partial lock that grows with the penalty (10 x alpha: kappa "
                                                  "below the exact)",
    ("bending", "HB3n-12", "gent", "plane-strain"): "its rule's 2 points across, as HB2n-16's: fully integrated "
                                                    "(5 x 5) it locks; the 2 points relieve the lock and do not see "
                                                    "the outer fibres' stiffening near Gent's lock (too soft, the "
                                                    "same with twice the elements and nearly so at 10 x the "
                                                    "penalty)",
}


def cause_of(kind: str, solver: str, law: str, form: str) -> str:
    """The measured cause of a miss of ``solver`` in a case of ``kind`` (:data:`CAUSES`), "" if none."""
    for key in ((kind, solver, law, form), (kind, solver, None, form), (kind, solver, law, None),
                (kind, solver, None, None)):
        if key in CAUSES:
            return CAUSES[key]
    return ""


def bending_tolerance(grid: dict, law: str, form: str, solver: str) -> tuple[float, str]:
    if form == "plane-strain" and solver not in grid["codes"]:
        alpha = penalty(grid, law)
        return BENDING_TOL + 2.0 * mu_of(law) / alpha, "1e-3 (the lock-free class) + 2 mu / alpha (the penalty)"
    return BENDING_TOL, "1e-3: the accuracy class of the lock-free elements (a requirement)"


# -- 6. the elastica under an end moment --------------------------------------------------------

def arc_scene(grid: dict, phi: float, ratio: float, element: str) -> dict:
    L, w = SLENDER_BEAM["length"], SLENDER_BEAM["width"]
    h = L / ratio
    c, rho = constants("neo-hookean")
    E = 3.0 * mu_of("neo-hookean")
    n = grid["arc_elements"]
    return {"name": f"bench-arc-phi{phi:.4g}-Lh{ratio:g}-{element}-{n}",
            "beam": {"length": L, "height": h, "width": w},
            "material": {"law": "neo-hookean", "formulation": "plane-stress", "density": rho, **c},
            "ancf": {"element": element, "elements": n}, "supports": {"left": "slide"},
            "loads": {"end_moment": phi * E * w * h ** 3 / 12.0 / L},
            "analysis": {"kind": "static", "load_steps": max(10, math.ceil(2 * phi))}}


@lru_cache(maxsize=None)
def arc_departure(phi: float, ratio: float) -> float:
    """|r_tip(exact pure bending) - r_tip(elastica)| / L: how far the plane-stress strip's own
    arc (its curvature and its mid-line's stretch, :func:`plane_stress_bending`) lies from
    Euler's inextensible one at the same couple; the beam's tip is read at r(L, 0)."""
    L, w = SLENDER_BEAM["length"], SLENDER_BEAM["width"]
    h = L / ratio
    c, _ = constants("neo-hookean")
    M = phi * 3.0 * mu_of("neo-hookean") * h ** 3 / 12.0 / L          # per width
    k = plane_stress_curvature("neo-hookean", c, M, h)
    R = plane_stress_bending("neo-hookean", c, k, h)["lambda_mid"] / k   # the mid-line's radius
    x, y = elastica_end_moment(phi)
    return math.hypot(R * math.sin(k * L) / L - x, R * (1.0 - math.cos(k * L)) / L - y)


# -- cases and report -------------------------------------------------------------------------

def _solvers(grid: dict, form: str) -> list[str]:
    """The elements that run ``form`` (a cable: plane stress alone) and the continuum codes."""
    from ancf.checks import runs

    return [*(el for el in grid["elements"] if runs(el, form)), *grid["codes"]]


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


@dataclass
class Row:
    case: str
    solver: str
    quantity: str
    reference: float | None
    kind: str
    source: str
    tolerance: float
    why: str
    value: float | None
    note: str = ""
    cause: str = ""     # why a miss misses (measured: :data:`CAUSES`, or from the records), "" if unknown

    @property
    def error(self) -> float | None:
        """|value - reference| relative to the reference (absolute where it is 0)."""
        if self.value is None or self.reference is None:
            return None
        return abs(self.value - self.reference) / (abs(self.reference) if self.reference else 1.0)

    @property
    def verdict(self) -> str:
        if self.value is None:
            return "no result"
        return "pass" if self.error <= self.tolerance else "FAIL"


OGDEN = "Ogden 1984, Non-linear elastic deformations, sec. 7.2.2"
SOURCES = {
    "tension": ("closed form", OGDEN),
    "shear": ("closed form", "Ogden 1984, sec. 5.3 (simple shear)"),
    "elastica": ("closed form", "Bisshopp & Drucker 1945, Q. Appl. Math. 3(3) 272-275 (elliptic integrals)"),
    "timoshenko": ("closed form", "Timoshenko & Gere 1972, Mechanics of Materials: q L^4 / 8 EI + q L^2 / 2 kappa G A"),
    "bending plane-strain": ("closed form", "Rivlin 1949, Proc. R. Soc. A 195, 463-473 (flexure); Ogden 1984, sec. 5.2"),
    "bending plane-stress": ("closed form (ODE)", "the same flexure for a plane-stress strip: a two-point problem "
                                                  "across the thickness, shot to round-off (closed_forms)"),
    "arc": ("closed form", "Euler's elastica under an end couple: x/L = sin(phi)/phi, y/L = (1 - cos phi)/phi"),
}
NONCONFORMING = ("HB2n-12", "HB3n-12")
# why a cable misses the finite-strain bending: a model error, not a discretisation one
CABLE_BENDING = ("a cable's fibres are in uniaxial stress (no radial stress, eta = Y): its M(kappa) lies above "
                 "the exact strip's by a model error of order (kappa h)^2 (0.225 (kappa h)^2 neo-Hookean and Yeoh, "
                 "0.245 Mooney-Rivlin: its card, 1b), so its kappa that much below")


def _is_cable(solver: str) -> bool:
    from ancf.elements import ELEMENTS

    return solver in ELEMENTS and ELEMENTS[solver].cable


def _solver_of(rec: dict) -> str:
    """The continuum backend that ran (the record's label), or the ANCF element."""
    return rec["solver"] if "fem" in rec["scene"] else rec["scene"]["ancf"]["element"]


def rows(ctx) -> list[Row]:
    g = ctx.study.grid
    out = []
    for r in ctx.records():
        s, name = r["scene"], r["scene"]["name"]
        ok = r.get("status") == "converged"
        if name.startswith("bench-tension-"):
            law, form = s["material"]["law"], s["material"]["formulation"]
            ref, lam = tension_reference(g, law, form)
            solver = _solver_of(r)
            tol, why = NEWTON_TOL, "state in the model's space: Newton's stop"
            if form == "plane-strain" and r["solver"] == "ancf":
                P = g["tension_stress"][law]
                tol = max(tol, 2.0 * P * lam / (s["material"]["penalty"] * (lam - 1.0)))
                why = "penalised: 2 P lambda / (alpha (lambda - 1))"
            note = "non-conforming: its patch test fails" if solver in NONCONFORMING else ""
            out.append(Row(f"tension {law} {form}", solver, "lambda - 1 = u_x(L) / L", ref, *SOURCES["tension"],
                           tol, why, r["tip"]["ux"] / s["beam"]["length"] if ok else None, note, note))
        elif name.startswith("bench-shear-"):
            law, form = s["material"]["law"], s["material"]["formulation"]
            gamma = s["point"]["F"][0][1]
            ref = simple_shear_stress(law, constants(law)[0], gamma)
            out.append(Row(f"shear {law} {form} gamma {gamma:g}", "ANCF material", "P_12 (Pa)", ref,
                           *SOURCES["shear"], 1e-12, "explicit formulas: round-off",
                           r["point"]["P"][0][1] if ok else None))
        elif name.startswith("bench-elastica-"):
            L, h = s["beam"]["length"], s["beam"]["height"]
            E = 3.0 * mu_of("neo-hookean")
            alpha = -s["loads"]["tip_force"][1] * L ** 2 / (E * s["beam"]["width"] * h ** 3 / 12.0)
            u, v, _ = elastica_tip_load(alpha)
            ratio = L / h
            val = None
            if ok:   # the tip's distance from the elastica's, over L; the reference is then 0 at scale 1
                val = math.hypot(r["tip"]["ux"] / L + u, r["tip"]["uy"] / L + v)
            out.append(Row(f"elastica alpha {alpha:.3g} L/h {ratio:g}", _solver_of(r), "|r_tip - r_elastica| / L",
                           0.0, *SOURCES["elastica"], elastica_tolerance(alpha, ratio),
                           "2 (0.9 + alpha/12 + alpha^2/4) (h/L)^2: shear, stretch, the law's cubic term",
                           val, f"elastica u/L {u:.6f}, v/L {v:.6f}"))
        elif name.startswith("bench-arc-"):
            L, h = s["beam"]["length"], s["beam"]["height"]
            E = 3.0 * mu_of("neo-hookean")
            phi = s["loads"]["end_moment"] * L / (E * s["beam"]["width"] * h ** 3 / 12.0)
            x, y = elastica_end_moment(phi)
            val = math.hypot(1.0 + r["tip"]["ux"] / L - x, r["tip"]["uy"] / L - y) if ok else None
            row = Row(f"arc phi {phi:.3g} L/h {L / h:g}", _solver_of(r), "|r_tip - r_arc| / L", 0.0,
                      *SOURCES["arc"], 2.0 * arc_departure(phi, L / h) + NEWTON_TOL,
                      "2 x the exact pure bending's own departure from the arc (its curvature and its mid-line's "
                      "stretch, plane stress) + 1e-6", val)
            if row.verdict == "FAIL":
                row.cause = cause_of("arc", row.solver, "neo-hookean", "plane-stress")
                row.note = _joined(f"its end turned {r['tip']['rotation'] / phi:.4f} phi", row.cause)
            out.append(row)
        elif name.startswith("bench-timoshenko-"):
            L, h = s["beam"]["length"], s["beam"]["height"]
            ref = timoshenko_reference(L / h)
            out.append(Row(f"Timoshenko L/h {L / h:g}", _solver_of(r), "tip deflection (m)", ref,
                           *SOURCES["timoshenko"], 2.0 * (h / L) ** 2,
                           "2 (h/L)^2: plane-stress elasticity departs from the beam by (h/L)^2",
                           -r["tip"]["uy"] if ok else None))
    return _beam_notes(out + bending_rows(ctx))


def bending_rows(ctx) -> list[Row]:
    """kappa = (theta(2 L) - theta(L)) / L of each pair of lengths (the end face's rotation:
    the couple's end zone, the same in both, cancels) against the exact pure bending's."""
    g = ctx.study.grid
    recs = {r["scene"]["name"]: r for r in ctx.records()}
    out = []
    for form in g["formulations"]:
        for law, curvatures in g["bending_curvatures"][form].items():
            if law not in g["laws"]:
                continue
            for x in curvatures:
                kappa = x / STRIP["height"]
                for solver in _solvers(g, form):
                    n1, n2 = g["bending_lengths"]
                    pair = [recs.get(bending_scene(g, law, form, x, n, solver)["name"]) for n in (n1, n2)]
                    val = None
                    if all(p is not None and p["status"] == "converged" for p in pair):
                        dL = (n2 - n1) * STRIP["height"]
                        val = (pair[1]["tip"]["rotation"] - pair[0]["tip"]["rotation"]) / dL
                    tol, why = bending_tolerance(g, law, form, solver)
                    row = Row(f"bending {law} {form} kappa h {x:g}", solver,
                              f"kappa = (theta({n2}h) - theta({n1}h)) / {n2 - n1}h (1/m)", kappa,
                              *SOURCES[f"bending {form}"], tol, why, val)
                    if _is_cable(solver):
                        row.note = row.cause = CABLE_BENDING
                    elif row.verdict == "FAIL":
                        row.cause = cause_of("bending", solver, law, form)
                        row.note = _joined(f"kappa {val / kappa:.4f} x the exact", row.cause)
                    out.append(row)
    return out


def _beam_notes(rows: list[Row]) -> list[Row]:
    """A missed beam case (elastica, Timoshenko) says why, from the element's own errors
    across the slendernesses of the same case: growing with L/h (shear locking: the
    element's bending stiffens as the beam thins), or not falling with h/L (an error of
    the element at this mesh that the slender limit does not remove)."""
    import re

    groups: dict = {}
    for r in rows:
        m = re.match(r"(elastica alpha \S+|Timoshenko) L/h (\S+)", r.case)
        if m and r.error is not None:
            groups.setdefault((m.group(1), r.solver), []).append((float(m.group(2)), r))
    for series in groups.values():
        series.sort(key=lambda x: x[0])
        first, last = series[0][1].error, series[-1][1].error
        for _, r in series:
            if r.verdict == "FAIL" and len(series) > 1:
                why = ("its error grows with L/h, so with l_e / h at this mesh: locking" if last > 1.25 * first
                       else "its error does not fall with h/L: the element's own at this mesh")
                r.note, r.cause = _joined(r.note, why), why
    return rows


def _joined(*parts: str) -> str:
    return "; ".join(p for p in parts if p)


def mattiasson_rows() -> list[list]:
    """The elastica's closed form against Mattiasson's published table."""
    half = 0.5 * 10.0 ** -MATTIASSON_1981_DIGITS
    out = []
    for alpha, (u_pub, v_pub) in sorted(MATTIASSON_1981.items()):
        u, v, _ = elastica_tip_load(alpha)
        err = max(abs(u - u_pub), abs(v - v_pub))
        out.append([alpha, u_pub, u, v_pub, v, err, half, "pass" if err <= half else "FAIL"])
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
