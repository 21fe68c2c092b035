"""The built-in HB2n-20xyp (ancf/elements/: the example HB2n-20xy, examples/cubic_slope.py,
with an element pressure {1, y}): the pressure cures HB2n-20xy's volumetric locking in
penalised plane strain and leaves plane stress as it was (issue 20, item 3)."""
import json
from pathlib import Path

import numpy as np
import pytest

from .conftest import tiered

import examples.cubic_slope  # noqa: F401  (registers HB2n-20xy, the element without the pressure)
from ancf.checks import element as checks
from ancf.elements import get_element
from ancf.simulation import run_scene
from contract import paper
from contract.scene import scene_from_dict

ELEMENT, BASE = "HB2n-20xyp", "HB2n-20xy"
GOLD = json.loads((Path(__file__).parent / "gold" / "fem_cantilever.json").read_text())["cases"]


def _tip(element: str, law: str, formulation: str, n: int, k: float | None = None) -> np.ndarray:
    """Tip (ux, uy) in m of the paper's cantilever (face clamp, gravity, default rule), with
    the penalty k C10 if given."""
    kw = {} if k is None else {"penalty": k * paper.materials()[law]["C10"]}
    d = paper.cantilever_scene(law, formulation, element, n, quadrature=None, **kw)
    d["ancf"].pop("quadrature", None)
    rec, _ = run_scene(scene_from_dict(d))
    assert rec["status"] == "converged", rec["reason"]
    return np.array([rec["tip"]["ux"], rec["tip"]["uy"]])


def _continuum_shift(law: str, k1: float, k2: float) -> float:
    """How far the continuum's tip moves, relative, when the penalty goes from k1 C10 to
    k2 C10: from the committed gold, the penalised (paper's penalty k_p) against the exactly
    incompressible tip, scaled as 1/k (the penalty's first-order effect)."""
    inc, pen = (np.array([GOLD[f"{law}/{v}"]["tip"][c] for c in ("ux", "uy")])
                for v in ("plane-strain", "plane-strain-penalty"))
    k_p = paper.PENALTY / paper.materials()[law]["C10"]
    return float(np.linalg.norm(pen - inc) / np.linalg.norm(inc)) * k_p * (1.0 / k1 - 1.0 / k2)


@pytest.mark.parametrize("law", tiered(["yeoh", "neo-hookean", "mooney-rivlin"], lambda law: law != "yeoh",
                                       "test_the_tip_moves_with_the_penalty_no_more_than_the_continuum_does"))
def test_the_tip_moves_with_the_penalty_no_more_than_the_continuum_does(law):
    """Lock-free: from k = 1e4 to 1e5 C10 the element's tip moves as the incompressible
    continuum's own 1/k term says (measured 1.0-1.3x it: Yeoh 0.013 / 0.010 % at 8 / 64
    elements against 0.0098 %), not with the penalty (HB2n-20xy: 3-4 % at 8, 27-34 % at
    64). 8 elements take the rule [4, 2] (l_e / h = 4), 64 take [3, 3] (0.5)."""
    bound = 2.0 * _continuum_shift(law, 1e4, 1e5)
    for n in (8, 64):
        moves = {}
        for el in (ELEMENT, BASE):
            a, b = _tip(el, law, "plane-strain", n, 1e4), _tip(el, law, "plane-strain", n, 1e5)
            moves[el] = np.linalg.norm(a - b) / np.linalg.norm(b)
        assert moves[ELEMENT] < bound < 0.01 < moves[BASE], (n, moves, bound)


def test_the_plane_strain_error_falls_with_refinement():
    """Yeoh, penalty 1e4 C10, against the exactly incompressible continuum: measured 1.7 /
    0.69 / 0.43 % at 16 / 32 / 64 elements (HB2n-20xy: 4.6 / 1.9 / 27 %, locked from 64 on,
    where the rule becomes [3, 3])."""
    ref = np.array([GOLD["yeoh/plane-strain"]["tip"][c] for c in ("ux", "uy")])
    errs = [np.linalg.norm(_tip(ELEMENT, "yeoh", "plane-strain", n, 1e4) - ref) / np.linalg.norm(ref)
            for n in (16, 32, 64)]
    assert errs[0] > errs[1] > errs[2] and errs[2] < 0.01
    base = np.linalg.norm(_tip(BASE, "yeoh", "plane-strain", 64, 1e4) - ref) / np.linalg.norm(ref)
    assert base > 10 * errs[2]


def test_plane_stress_is_the_base_element_and_the_rules_are_its_rules():
    """The pressure carries the penalty only: in plane stress the element is HB2n-20xy to
    the last bit (its rank-tested rules, tests/test_examples.py, resolve the pressure {1, y}:
    two points across)."""
    spec, base = get_element(ELEMENT), get_element(BASE)
    assert (spec.basis, spec.kinds, spec.quadrature) == (base.basis, base.kinds, base.quadrature)
    assert all(rule[1] >= 2 for _, _, rule in spec.quadrature)
    assert np.array_equal(_tip(ELEMENT, "yeoh", "plane-stress", 8), _tip(BASE, "yeoh", "plane-stress", 8))


def test_the_penalised_forms_pass_the_contract_checks():
    rng = np.random.default_rng(0)
    for form in ("plane-strain", "paper"):
        model = checks.small_model(ELEMENT, formulation=form)
        for check in (checks.energy_gradient, checks.tangent_gradient, checks.rigid_motion):
            assert check(model, rng)["passes"], (form, check.__name__)
    assert checks.patch(ELEMENT, formulation="plane-strain")["passes"]
