"""The [fem] table of a scene: validation and resolution (no dolfinx needed)."""
import json
import math
import re
import subprocess
import sys
from pathlib import Path

import pytest

from contract import paper
from contract.errors import SceneError
from contract.scene import scene_from_dict
from reference_fem.simulation import check_static
from reference_fem.settings import DEFAULT_ASPECT, DEFAULT_CELLS_HEIGHT, fem_settings
from studies.verification.continuum_gold.cantilever import cantilever

pytestmark = pytest.mark.dolfinx      # the continuum runs of this module are DOLFINx's

GOLD = Path(__file__).parent / "gold" / "fem_cantilever.json"


def _settings(model="plane-stress", fem=None, formulation=None):
    d = paper.cantilever_scene("neo-hookean", model, fem=fem)
    if formulation == "paper":
        d["material"]["formulation"] = "paper"
        d["material"]["penalty"] = 1e9
    return fem_settings(scene_from_dict(d))


def test_defaults_resolve_against_the_beam():
    s = _settings("plane-strain")
    assert (s.model, s.incompressibility, s.cell, s.degree) == ("plane-strain", "mixed", "quadrilateral", 2)
    assert s.cells_height == DEFAULT_CELLS_HEIGHT
    assert s.cells_length == round(0.160 / 0.005 * DEFAULT_CELLS_HEIGHT / DEFAULT_ASPECT)
    assert s.quadrature_degree == 4
    assert _settings("plane-stress").incompressibility == "exact"


def test_explicit_values_are_taken():
    s = _settings("plane-strain", {"cells_height": 3, "cells_length": 40, "cell": "triangle",
                                   "degree": 3, "quadrature_degree": 7, "incompressibility": "penalty"})
    assert (s.cells_height, s.cells_length, s.cell, s.degree, s.quadrature_degree,
            s.incompressibility) == (3, 40, "triangle", 3, 7, "penalty")
    assert _settings(fem={"cells_height": 4, "aspect": 4.0}).cells_length == 32
    assert _settings(fem={"model": "plane-stress"}, formulation="paper").model == "plane-stress"


@pytest.mark.parametrize("fem, field", [
    ({"cells_heigth": 2}, "fem: unknown key"),
    ({"cell": "hexahedron"}, "fem.cell"),
    ({"cells_height": 0}, "fem.cells_height"),
    ({"cells_height": 2.5}, "fem.cells_height"),
    ({"cells_length": True}, "fem.cells_length"),
    ({"aspect": -1.0}, "fem.aspect"),
    ({"aspect": 2.0, "cells_length": 10}, "fem.cells_length"),
    ({"degree": 0}, "fem.degree"),
    ({"quadrature_degree": "high"}, "fem.quadrature_degree"),
    ({"incompressibility": "penalty"}, "fem.incompressibility"),  # plane stress has none
    ({"model": "plane-strain"}, "fem.model"),                      # contradicts the scene
    ({"model": "axisymmetric"}, "fem.model"),
])
def test_bad_fem_tables_name_the_field(fem, field):
    with pytest.raises(SceneError, match=field.replace(".", r"\.")):
        _settings("plane-stress", fem)


def test_mixed_plane_strain_needs_degree_two():
    with pytest.raises(SceneError, match=r"fem\.degree"):
        _settings("plane-strain", {"degree": 1})
    with pytest.raises(SceneError, match=r"fem\.incompressibility.*allowed"):
        _settings("plane-strain", {"incompressibility": "exact"})


def test_paper_scenes_need_a_model():
    with pytest.raises(SceneError, match=r"fem\.model.*plane-strain.*plane-stress"):
        _settings(formulation="paper")
    with pytest.raises(SceneError, match=r"fem\.model"):
        _settings(fem={"model": "plane stress"}, formulation="paper")


def test_refinement_studies_refuse_dynamic_scenes():
    """`converge` is static only (the pendulum has `python -m studies continuum pendulum`)."""
    d = paper.cantilever_scene("yeoh", "plane-stress")
    d["analysis"] = {"kind": "dynamic", "t_end": 0.5, "dt": 1e-3}
    with pytest.raises(SceneError, match=r"analysis\.kind.*static only"):
        check_static(scene_from_dict(d))


def test_settings_and_run_modules_do_not_import_dolfinx():
    code = ("import sys, reference_fem.settings, reference_fem.simulation, reference_fem.dolfinx_backend.models, "
            "reference_fem.statics, reference_fem.convergence, reference_fem.stepper, "
            "studies.verification.continuum_gold.cantilever; "
            "print('dolfinx' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_gold_file_is_complete_and_consistent():
    """Readable without dolfinx: every law x model, finite values, a tolerance, and the
    Richardson value within the stated error of the finest level."""
    gold = json.loads(GOLD.read_text())
    # the gold command, under its name then (reference_fem) or now (studies continuum)
    assert gold["dolfinx"]
    assert re.fullmatch(r"python -m (reference_fem|studies continuum) gold --levels \d+", gold["generator"])
    for law in ("neo-hookean", "mooney-rivlin", "yeoh"):
        for variant in ("plane-strain", "plane-strain-penalty", "plane-stress"):
            case = gold["cases"][f"{law}/{variant}"]
            tip, fin, err = case["tip"], case["finest"], case["error_estimate_m"]
            assert all(math.isfinite(v) for v in (tip["ux"], tip["uy"], err))
            assert tip["uy"] < 0 and tip["ux"] < 0
            assert math.hypot(tip["ux"] - fin["ux"], tip["uy"] - fin["uy"]) <= err * (1 + 1e-9)
            assert case["tolerance"]["abs_m"] >= err
            assert case["order"] >= 1.0
            assert case["scene"]["material"]["law"] == law
            assert len(case["levels"]) >= 3 and all(lv["status"] == "converged" for lv in case["levels"])
