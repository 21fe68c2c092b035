"""The continuum-agreement check (studies/verification/continuum_agreement.py) on made-up records:
two codes agree when their Richardson values are within the sum of their estimates."""
import pytest

from studies.verification.continuum_agreement import agreement, scene as felupe_scene
from studies.verification.continuum import scene as dolfinx_scene


def _records(make, tips):
    cells = [(12, 1), (24, 2), (48, 4)]
    return [{"scene": make("yeoh", "plane-stress", c), "status": "converged", "solver": "dolfinx",
             "tip": {"ux": ux, "uy": uy}} for c, (ux, uy) in zip(cells, tips)]


def _converging(limit, h0):
    """Tips limit + h0 / 4^k: order 2, Richardson exact, estimate sqrt(2) h0 (1/4 - 1/16) / (2^2 - 1) = sqrt(2) h0 / 16."""
    return [(limit[0] + h0 / 4 ** k, limit[1] + h0 / 4 ** k) for k in range(3)]


@pytest.mark.parametrize("shift, agree", [(0.0, True), (1e-5, True), (1e-3, False)])
def test_agreement_within_the_combined_bar(shift, agree):
    a = _records(dolfinx_scene, _converging((-0.066, -0.120), 1e-3))
    b = _records(felupe_scene, _converging((-0.066 + shift, -0.120), 1e-3))
    (row,) = agreement(a, b)
    assert row["variant"] == "plane-stress" and row["law"] == "yeoh"
    assert row["bar"] == pytest.approx(2 * 2 ** 0.5 * 1e-3 / 16)
    assert row["diff"] == pytest.approx(shift, abs=1e-12)
    assert row["agree"] is agree


def test_no_richardson_value_is_not_agreement():
    a = _records(dolfinx_scene, _converging((-0.066, -0.120), 1e-3))
    b = _records(felupe_scene, _converging((-0.066, -0.120), 1e-3))[:2]
    (row,) = agreement(a, b)
    assert row["agree"] is None


def test_felupe_scene_names_the_backend():
    s = felupe_scene("yeoh", "plane-strain-penalty", (12, 1))
    assert s["fem"]["backend"] == "felupe" and s["fem"]["incompressibility"] == "penalty"
