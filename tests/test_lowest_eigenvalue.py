"""Every converged static record carries ``lowest_eigenvalue``, the lowest eigenvalue
of the Jacobi-scaled constrained tangent at its final state, stable states included (the
margin a reader checks the verdict by); checked against a dense symmetric eigen-solve."""
from __future__ import annotations

import numpy as np
import pytest

from ancf.build import build_model
from ancf.simulation import run_scene
from ancf.solvers.stability import SINGULAR_TOL
from contract import paper
from contract.scene import scene_from_dict

from .test_stability_inertia import scaled_dense


@pytest.mark.parametrize("element,count", [("HB2n-12", 6), ("HB3n-12", 6), ("HB2n-16", 24)])
def test_stable_record_carries_its_margin(element, count):
    """6 elements: the dense path of ancf.solvers.stability.lowest_eigenvalue; 24 x HB2n-16 (194
    unknowns): its shift-invert Lanczos."""
    d = paper.cantilever_scene("neo-hookean", "plane-stress", element, count, name="margin")
    rec, (model, res) = run_scene(scene_from_dict(d))
    assert rec["status"] == "converged" and rec["stable"] is True
    _, lam = scaled_dense(model, res.u)
    assert rec["lowest_eigenvalue"] > SINGULAR_TOL
    # against numpy's dense eigh: both ~ eps ||S|| (||S|| <= ~5)
    assert rec["lowest_eigenvalue"] == pytest.approx(lam[0], rel=1e-6, abs=1e-12)


def test_unstable_record_carries_its_negative_lowest():
    d = paper.cantilever_scene("yeoh", "paper", "HB2n-16", 32, quadrature=(2, 2), clamp="all", name="saddle")
    rec, (model, res) = run_scene(scene_from_dict(d))
    assert rec["status"] == "converged"
    assert rec["lowest_eigenvalue"] is not None
    _, lam = scaled_dense(model, res.u)
    assert rec["lowest_eigenvalue"] == pytest.approx(lam[0], rel=1e-3, abs=1e-12)
