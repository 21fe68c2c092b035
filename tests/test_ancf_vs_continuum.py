"""ANCF against the converged continuum (the FEniCSx gold values, committed; no
dolfinx needed): the static cantilever, each law, matching 2D models.

Where the two models differ by construction: the continuum clamp fixes the whole end
face, which stiffens the root by O(h/L) (measured by reference_fem on the small-load
cantilever: about 0.18 h/L in plane strain, 0.05 h/L in plane stress), while the ANCF
face clamp lets the section deform within the element's transverse polynomial.
Tolerances: 0.25 h/L (0.78 %) in plane strain, 0.1 h/L (0.31 %) in plane stress, on
|u - u_ref| / |u_ref| over (ux, uy). HB2n-16 is left out in plane strain: it still
locks at 640 elements (1.25 % for Yeoh; see test_static)."""
import json
from pathlib import Path

import numpy as np
import pytest

from .conftest import tiered

from ancf.simulation import run_scene
from contract.scene import scene_from_dict
from contract import paper

GOLD = json.loads((Path(__file__).parent / "gold" / "fem_cantilever.json").read_text())["cases"]
H_OVER_L = paper.CANTILEVER["height"] / paper.CANTILEVER["length"]
TOL = {"plane-stress": 0.1 * H_OVER_L, "plane-strain": 0.25 * H_OVER_L}
GOLD_KEY = {"plane-stress": "plane-stress", "plane-strain": "plane-strain-penalty"}
CASES = [(law, form, el, n) for law in ("neo-hookean", "mooney-rivlin", "yeoh")
         for form in ("plane-stress", "plane-strain")
         for el, n in (("HB2n-12", 160), ("HB3n-12", 160), ("HB2n-16", 640))
         if not (form == "plane-strain" and el == "HB2n-16")]


@pytest.mark.parametrize("law,form,element,n", tiered(CASES, lambda law, *rest: law != "yeoh",
                                                      "test_static_cantilever_matches_the_converged_continuum"))
def test_static_cantilever_matches_the_converged_continuum(law, form, element, n):
    gold = GOLD[f"{law}/{GOLD_KEY[form]}"]
    ref = np.array([gold["tip"]["ux"], gold["tip"]["uy"]])
    rec, _ = run_scene(scene_from_dict(paper.cantilever_scene(law, form, element, n)))
    assert rec["status"] == "converged"
    tip = np.array([rec["tip"]["ux"], rec["tip"]["uy"]])
    assert np.linalg.norm(tip - ref) / np.linalg.norm(ref) < TOL[form]


PENDULUM_GOLD = json.loads((Path(__file__).parent / "gold" / "fem_pendulum.json").read_text())["cases"]
# element counts at which each element's plane-stress pendulum has converged (tip
# changes with refinement well below 1 mm: HB3n-12 converges slowest in plane stress,
# 3.5 / 1.0 / 0.2 mm from the continuum at 64 / 128 / 256 elements for Yeoh)
CONVERGED_COUNT = {"HB2n-16": 64, "HB2n-12": 128, "HB3n-12": 256}


@pytest.mark.parametrize("law", tiered(["neo-hookean", "mooney-rivlin", "yeoh"], lambda law: law != "yeoh",
                                       "test_converged_pendulum_matches_the_continuum_within_1mm"))
@pytest.mark.parametrize("element", sorted(CONVERGED_COUNT))
def test_converged_pendulum_matches_the_continuum_within_1mm(law, element):
    """The issue's target: the converged ANCF plane-stress pendulum within 1 mm of the
    converged continuum plane-stress pendulum at every output time (measured at most
    0.41 mm; the continuum's own point-pin uncertainty for Mooney-Rivlin is 0.3 to
    0.7 mm, see the gold file)."""
    s = paper.pendulum_scene(law, "plane-stress", 1e-3, element, CONVERGED_COUNT[element])
    rec, _ = run_scene(scene_from_dict(s))
    assert rec["status"] == "converged", rec["reason"]
    ref = {round(v["t"], 9): (v["x"], v["y"]) for v in PENDULUM_GOLD[f"{law}/plane-stress"]["values"]}
    for h in rec["tip_history"]:
        x, y = ref[round(h["t"], 9)]
        assert np.hypot(h["x"] - x, h["y"] - y) < 1e-3, h


@pytest.mark.parametrize("element", ["HB2n-12", "HB3n-12"])
@pytest.mark.parametrize("n", [160, 320, 640])
def test_default_rules_keep_the_non_conforming_elements_within_half_a_percent(element, n):
    """Issue 8's bar: Mooney-Rivlin, plane stress, the element's default quadrature at
    l_e/h = 0.2, 0.1, 0.05 stays within 0.5 % of the converged continuum (measured: at most
    0.31 %, HB3n-12 at 640; with [3, 2] at 640 elements: 13 % for HB3n-12, 2.7 % for
    HB2n-12). Finer still, these non-conforming elements drift towards 0.5 % (README
    "Default quadrature")."""
    gold = GOLD["mooney-rivlin/plane-stress"]
    ref = np.array([gold["tip"]["ux"], gold["tip"]["uy"]])
    rec, _ = run_scene(scene_from_dict(paper.cantilever_scene("mooney-rivlin", "plane-stress", element, n,
                                                              quadrature=None)))
    assert rec["status"] == "converged" and rec["stable"] is True
    tip = np.array([rec["tip"]["ux"], rec["tip"]["uy"]])
    assert np.linalg.norm(tip - ref) / np.linalg.norm(ref) < 5e-3
