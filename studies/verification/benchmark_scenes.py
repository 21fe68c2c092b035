"""The benchmark suite's cases as data (:mod:`studies.verification.benchmarks` declares the
study, its module doc states each derivation): for each benchmark its scene, its reference
from the closed forms (:mod:`studies.verification.closed_forms`) and its tolerance: 1.
tension, 2. simple shear at a material point, 3. the elastica under a tip force, 4.
Timoshenko, 5. pure bending, 6. the elastica under an end moment; and the solvers that run a
formulation (:func:`_solvers`)."""
from __future__ import annotations

import math
from functools import lru_cache

from ancf.checks.element import runs
from contract import paper
from mechanics.laws import get_law

from .closed_forms import (elastica_end_moment, plane_stress_bending, plane_stress_curvature, rivlin_bending,
                           uniaxial_stretch)
from ..common.grid import fem_table
from ..design.card_cases import beam_theory, slender_scene


STRIP = {"length": 0.160, "height": 0.005, "width": 0.007}


SLENDER_BEAM = {"length": 0.350, "width": 0.007}


NEWTON_TOL = 1e-6                    # 100 x the Newton tolerance of the load (1e-8)


def constants(law: str) -> tuple[dict, float]:
    """(the law's constants, density): the paper's for its three laws, the example's for the others."""
    if law in paper.materials():
        c = dict(paper.materials()[law])
        return c, c.pop("density")
    return dict(get_law(law).example), paper.materials()["neo-hookean"]["density"]


def mu_of(law: str) -> float:
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
    d = slender_scene(element, ratio, grid["timoshenko_elements"])
    d["name"] = f"bench-timoshenko-Lh{ratio:g}-{element}-{grid['timoshenko_elements']}"
    d["supports"] = {"left": "slide"}
    return d


def timoshenko_reference(ratio: float) -> float:
    """The tip deflection (m) of the probe by Euler-Bernoulli + Timoshenko's shear."""
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
    L = SLENDER_BEAM["length"]
    h = L / ratio
    c, _ = constants("neo-hookean")
    M = phi * 3.0 * mu_of("neo-hookean") * h ** 3 / 12.0 / L          # per width
    k = plane_stress_curvature("neo-hookean", c, M, h)
    R = plane_stress_bending("neo-hookean", c, k, h)["lambda_mid"] / k   # the mid-line's radius
    x, y = elastica_end_moment(phi)
    return math.hypot(R * math.sin(k * L) / L - x, R * (1.0 - math.cos(k * L)) / L - y)


def _solvers(grid: dict, form: str) -> list[str]:
    """The elements that run ``form`` (a cable: plane stress alone) and the continuum codes."""
    return [*(el for el in grid["elements"] if runs(el, form)), *grid["codes"]]
