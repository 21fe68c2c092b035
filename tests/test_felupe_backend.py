"""The FElupe backend ([fem] backend = "felupe"): the same problem as the DOLFINx backend
on a second code. On the same mesh, degree and quadrature the two discretisations are the
same, so the tips agree to the Newton tolerance: checked against the committed DOLFINx
levels of tests/gold (no dolfinx needed), in every model FElupe offers, for every law."""
import dataclasses
import json
import math
from pathlib import Path

import pytest

from .conftest import tiered

from contract.errors import SceneError
from contract.scene import load_scene, scene_from_dict
from reference_fem.settings import FemSettings, fem_settings
from reference_fem.simulation import run_scene
from studies.verification.continuum_gold.cantilever import VARIANTS, base_settings, cantilever

pytest.importorskip("felupe")

GOLD = Path(__file__).parent / "gold"
CASES = json.loads((GOLD / "fem_cantilever.json").read_text())["cases"]
CASES_3D = json.loads((GOLD / "fem_cantilever_3d.json").read_text())["cases"]
# Newton stops at ||R|| <= 1e-8 ||R_ref|| (analysis.newton_rtol default): a tip error of that
# order relative; measured differences 1e-12 .. 1e-8 relative (Mooney-Rivlin plane stress).
RTOL = 1e-6


def _felupe(settings: FemSettings) -> FemSettings:
    return dataclasses.replace(settings, backend="felupe")


def _close(tip, ref, rtol=RTOL):
    return math.hypot(tip["ux"] - ref["ux"], tip["uy"] - ref["uy"]) <= rtol * math.hypot(ref["ux"], ref["uy"])


@pytest.mark.parametrize("key", tiered(sorted(CASES), lambda k: not k.startswith("yeoh"), "test_same_mesh_same_tip_as_dolfinx_gold_2d"))
def test_same_mesh_same_tip_as_dolfinx_gold_2d(key):
    """16 x 1 Q2 (Q2/Q1) cells: FElupe's tip equals DOLFINx's committed level 0."""
    law, variant = key.split("/")
    model, inc = VARIANTS[variant]
    scene = cantilever(law, model, incompressibility=inc if inc == "penalty" else None)
    rec = run_scene(scene, _felupe(base_settings(model, inc)))
    level = CASES[key]["levels"][0]
    assert rec["status"] == "converged", rec["reason"]
    assert rec["ndof"] == level["ndof"]
    assert rec["fem"]["backend"] == "felupe" and rec["felupe"] and "dolfinx" not in rec
    assert rec["continuum_model"] == model and rec["incompressibility"] == (inc or "exact")
    assert _close(rec["tip"], level["tip"]), (rec["tip"], level["tip"])


@pytest.mark.slow(guard="test_same_mesh_same_tip_as_dolfinx_gold_2d")
@pytest.mark.parametrize("inc", ["mixed", "penalty"])
def test_same_mesh_same_tip_as_dolfinx_gold_3d(inc):
    """The real beam, 16 x 1 x 1 graded Q2/Q1 hexahedra (Yeoh): DOLFINx's committed
    level 0 (mixed); penalty alpha = 1000 MPa within 0.1 % of it (a different model: the
    penalty's compliance)."""
    case = CASES_3D["yeoh/3d"]
    scene = scene_from_dict(case["scene"])
    base = FemSettings(**{**case["base_mesh"], "incompressibility": inc, "backend": "felupe"})
    rec = run_scene(scene, base)
    assert rec["status"] == "converged", rec["reason"]
    ref = case["levels"][0]
    assert rec["ndof"] == ref["ndof"] and rec["mpi_ranks"] == 1
    assert abs(rec["tip_uz"]) < 1e-12
    assert _close(rec["tip"], ref["tip"], RTOL if inc == "mixed" else 1e-3), (rec["tip"], ref["tip"])


def test_a_law_from_the_table_needs_no_backend_code():
    """Gent (one file in mechanics/laws/) on FElupe: converges, and stiffer than
    neo-Hookean of the same mu (the locking stretch), as on DOLFINx (scenes/cantilever-gent.toml)."""
    gent = load_scene("scenes/cantilever-gent.toml")
    s = _felupe(base_settings("plane-stress", None))
    rec = run_scene(gent, s)
    nh = run_scene(cantilever("neo-hookean", "plane-stress"), s)
    assert rec["status"] == "converged", rec["reason"]
    assert abs(rec["tip"]["ux"]) < abs(nh["tip"]["ux"])


# the mixed plane strain in the full tier (about 4 s), plane stress stays quick
@pytest.mark.dolfinx
@pytest.mark.parametrize("model, inc", tiered([("plane-strain", "mixed"), ("plane-stress", None)],
                                              lambda model, inc: inc == "mixed", "test_tip_force_as_dolfinx"))
def test_tip_force_as_dolfinx(model, inc):
    """The tip traction (consistent nodal forces: Simpson on the end face) with gravity:
    the same tip as DOLFINx on the same mesh."""
    d = cantilever("mooney-rivlin", model).to_dict()
    d["loads"] = {"gravity": [0.0, -9.81], "tip_force": [0.05, -0.02]}
    scene = scene_from_dict(d)
    s = dataclasses.replace(base_settings(model, inc), cells_height=2)
    a = run_scene(scene, s)
    b = run_scene(scene, _felupe(s))
    assert a["status"] == b["status"] == "converged", (a["reason"], b["reason"])
    assert b["effects"] == a["effects"] and b["ndof"] == a["ndof"]
    assert _close(b["tip"], a["tip"]), (b["tip"], a["tip"])


def _scene(fem: dict, **over):
    d = cantilever("neo-hookean", "plane-stress").to_dict()
    d["fem"] = fem
    d.update(over)
    return scene_from_dict(d)


def test_backend_is_validated_and_named_only_when_not_default():
    with pytest.raises(SceneError, match=r"fem\.backend.*dolfinx.*felupe"):
        fem_settings(_scene({"backend": "abaqus"}))
    assert "backend" not in fem_settings(_scene({})).to_dict()
    assert fem_settings(_scene({"backend": "felupe"})).to_dict()["backend"] == "felupe"
    assert fem_settings(_scene({"backend": "felupe"})).refined(2).backend == "felupe"


@pytest.mark.parametrize("fem, field", [({"backend": "felupe", "cell": "triangle"}, "fem.cell"),
                                        ({"backend": "felupe", "degree": 3}, "fem.degree")])
def test_what_felupe_does_not_offer_is_a_clear_error(fem, field):
    with pytest.raises(SceneError, match=field.replace(".", r"\.")):
        run_scene(_scene(fem))


def test_dynamic_scenes_run_on_felupe():
    """A dynamic scene runs on FElupe through the one time loop (the pendulum against
    DOLFINx: tests/test_felupe_dynamics.py); the clamped cantilever released at rest
    under gravity starts falling freely."""
    d = cantilever("neo-hookean", "plane-stress").to_dict()
    d["analysis"] = {"kind": "dynamic", "t_end": 0.002, "dt": 0.001}
    d["fem"] = {"backend": "felupe", "cells_height": 2}
    rec = run_scene(scene_from_dict(d))
    assert rec["status"] == "converged", rec["reason"]
    assert rec["steps"] == 2 and rec["fem"]["backend"] == "felupe" and rec["felupe"]
    assert rec["pin"].startswith("clamp") and rec["effects"] == ["elastic", "gravity", "inertia"]
    assert rec["tip_history"][-1]["y"] == pytest.approx(-0.5 * 9.81 * 0.002 ** 2, rel=0.05)


@pytest.mark.parametrize("model, inc", [("plane-strain", "mixed"), ("plane-stress", None)])
def test_output_holds_the_solution(tmp_path, model, inc):
    """--output on FElupe writes the corner mesh with the displacement (and the pressure
    p = mu phat): the node at the tip carries the record's tip displacement."""
    import meshio
    import numpy as np

    scene = cantilever("neo-hookean", model, incompressibility=inc)
    settings = dataclasses.replace(_felupe(base_settings(model, inc)), cells_height=2)   # a corner at the tip
    rec = run_scene(scene, settings, output=tmp_path)
    assert rec["status"] == "converged", rec["reason"]
    out = meshio.read(rec["output"])
    assert Path(rec["output"]).suffix == ".vtu"
    tip = np.array([scene.beam.length, 0.0])
    k = int(np.argmin(np.linalg.norm(out.points[:, :2] - tip, axis=1)))
    assert np.allclose(out.point_data["displacement"][k], [rec["tip"]["ux"], rec["tip"]["uy"]], rtol=0, atol=1e-15)
    assert ("pressure" in out.point_data) == (model == "plane-strain")
    if model == "plane-strain":      # the pressure scale: |p| of order rho g L^2 / h at the root
        assert np.all(np.isfinite(out.point_data["pressure"])) and np.ptp(out.point_data["pressure"]) > 0


def _committed(name: str) -> dict:
    """The record of ``name`` in the committed continuum-agreement records (reports/data)."""
    path = Path(__file__).parent.parent / "reports" / "data" / "continuum-agreement.jsonl"
    recs = [json.loads(line) for line in path.read_text().splitlines() if line.strip()]
    return next(r for r in recs if r["scene"]["name"] == name)


@pytest.mark.slow(guard="test_same_mesh_same_tip_as_dolfinx_gold_2d")
def test_felupe_sequence_reproduces_its_committed_levels_and_richardson():
    """The CI-sized case of FElupe's own refinement (Yeoh, plane stress, 12 x 1 ... 96 x 8,
    about 3 s): every level reproduces the committed record of the continuum-agreement
    study (regression, the Newton tolerance); observed order >= 1 and the Richardson value
    of the first three levels predicts the fourth within its estimate (DOLFINx's own check,
    tests/test_reference_fem_cantilever.py); the Richardson value of the last three agrees
    with DOLFINx's committed one (tests/gold) within the two estimates."""
    from reference_fem.convergence import richardson
    from studies.verification.continuum_agreement import scene as felupe_scene

    tips = []
    for cells in ((12, 1), (24, 2), (48, 4), (96, 8)):
        d = felupe_scene("yeoh", "plane-stress", cells)
        rec = run_scene(scene_from_dict(d))
        stored = _committed(d["name"])
        assert rec["status"] == "converged", rec["reason"]
        assert _close(rec["tip"], stored["tip"]), (cells, rec["tip"], stored["tip"])
        tips.append((rec["tip"]["ux"], rec["tip"]["uy"]))
    first = richardson(*tips[:3])
    assert first.order >= 1.0
    assert math.hypot(tips[3][0] - first.value[0], tips[3][1] - first.value[1]) <= first.error_estimate
    own = richardson(*tips[1:])
    gold = CASES["yeoh/plane-stress"]
    dist = math.hypot(own.value[0] - gold["tip"]["ux"], own.value[1] - gold["tip"]["uy"])
    assert dist <= own.error_estimate + gold["error_estimate_m"], (dist, own.error_estimate, gold["error_estimate_m"])
