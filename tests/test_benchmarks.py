"""The benchmark suite (studies/verification/benchmarks.py and its benchmark_* modules): its closed
forms against published values, and a tiny subset of its cases run through both solvers (the full suite: make study)."""
import math

import pytest

from contract.scene import scene_from_dict
from studies.verification.closed_forms import (MATTIASSON_1981, elastica_end_moment, elastica_tip_load, nominal_stress,
                                  simple_shear_stress, uniaxial_stretch)

from .conftest import tiered


def test_the_elastica_closed_form_reproduces_mattiassons_table_to_its_last_digit():
    for alpha, (u, v) in MATTIASSON_1981.items():
        U, V, _ = elastica_tip_load(alpha)
        assert abs(U - u) <= 5e-6 and abs(V - v) <= 5e-6, alpha
    assert elastica_tip_load(1.0)[2] == pytest.approx(0.46135, abs=5e-6)      # the table's tip angle


def test_the_elastica_tends_to_the_linear_cantilever_and_the_arc_is_exact():
    u, v, th = elastica_tip_load(1e-3)
    assert v == pytest.approx(1e-3 / 3, rel=1e-3) and th == pytest.approx(1e-3 / 2, rel=1e-3)
    x, y = elastica_end_moment(math.pi / 2)
    assert x == pytest.approx(2 / math.pi) and y == pytest.approx(2 / math.pi)


@pytest.mark.parametrize("form", ["plane-stress", "plane-strain"])
def test_the_uniaxial_closed_form_inverts_its_stress_and_is_linear_at_small_strain(form):
    c = {"C10": 0.5e6}
    lam = uniaxial_stretch("neo-hookean", c, form, 2e6)
    assert nominal_stress("neo-hookean", c, form, lam) == pytest.approx(2e6, rel=1e-12)
    E = 3.0 * 1e6 if form == "plane-stress" else 4.0 * 1e6            # 3 mu, or 4 mu in plane strain
    assert uniaxial_stretch("neo-hookean", c, form, 1e-3 * E) - 1.0 == pytest.approx(1e-3, rel=2e-3)
    assert simple_shear_stress("mooney-rivlin", {"C10": 0.4e6, "C01": 0.1e6}, 0.5) == pytest.approx(0.5e6)


def _run(d: dict) -> dict:
    if "fem" in d:
        from reference_fem.simulation import run_scene
        return run_scene(scene_from_dict(d))
    from ancf.simulation import run_scene
    return run_scene(scene_from_dict(d))[0]


# DOLFINx's case in the full tier (about 3.5 s), FElupe's keeps the continuum in the quick one
@pytest.mark.dolfinx
@pytest.mark.parametrize("solver", tiered(["HB2n-16", "HB2n-40p", "dolfinx", "felupe"], lambda s: s == "dolfinx",
                                          "test_homogeneous_tension_is_the_closed_form_in_both_solvers"))
def test_homogeneous_tension_is_the_closed_form_in_both_solvers(solver):
    """The tiny subset of the tension benchmark: Yeoh in plane stress, the stretch of the
    closed form within the benchmark's tolerance (100 x Newton's)."""
    from studies.verification.benchmark_scenes import NEWTON_TOL, tension_reference, tension_scene
    from studies.verification.benchmarks import STUDY

    g = dict(STUDY["grid"])
    rec = _run(tension_scene(g, "yeoh", "plane-stress", solver))
    ref, _ = tension_reference(g, "yeoh", "plane-stress")
    assert rec["status"] == "converged"
    assert abs(rec["tip"]["ux"] / rec["scene"]["beam"]["length"] - ref) <= NEWTON_TOL * ref


def test_the_elastica_is_the_slender_limit_of_a_lock_free_element():
    """HB2n-40p at L/h = 50 and 100, alpha = 1: within the benchmark's tolerance, and the
    distance falls as (h/L)^2 (a ratio near 4 from 50 to 100)."""
    from studies.verification.benchmark_scenes import elastica_scene, elastica_tolerance
    from studies.verification.benchmarks import STUDY

    g = dict(STUDY["grid"])
    u, v, _ = elastica_tip_load(1.0)
    err = {}
    for ratio in (50.0, 100.0):
        rec = _run(elastica_scene(g, 1.0, ratio, "HB2n-40p"))
        L = rec["scene"]["beam"]["length"]
        err[ratio] = math.hypot(rec["tip"]["ux"] / L + u, rec["tip"]["uy"] / L + v)
        assert err[ratio] <= elastica_tolerance(1.0, ratio)
    assert 3.0 < err[50.0] / err[100.0] < 5.0


@pytest.mark.dolfinx
# the continuum's two runs (about 8 s each) in the full tier, the element's in the quick one
@pytest.mark.parametrize("solver, form, x", tiered([("HB2n-40p", "plane-stress", 0.5), ("dolfinx", "plane-strain", 0.2),
                                                    ("felupe", "plane-stress", 0.2)],
                                                   lambda solver, form, x: solver in ("dolfinx", "felupe"),
                                                   "test_pure_bending_is_rivlins_flexure_in_both_solvers"))
def test_pure_bending_is_rivlins_flexure_in_both_solvers(solver, form, x):
    """The tiny subset of the bending benchmark: the curvature from two lengths (8 h and 16 h,
    the couple's end zone cancelling) within the benchmark's tolerance of the exact flexure
    (Rivlin's in plane strain, the plane-stress two-point problem otherwise)."""
    from studies.verification.benchmark_scenes import bending_reference, bending_scene, bending_tolerance
    from studies.verification.benchmarks import STUDY

    g = dict(STUDY["grid"])
    theta = [_run(bending_scene(g, "neo-hookean", form, x, n, solver))["tip"]["rotation"] for n in (8, 16)]
    kappa = (theta[1] - theta[0]) / (8 * 0.005)
    ref = bending_reference("neo-hookean", form, x)["kappa"]
    assert ref == pytest.approx(x / 0.005, rel=1e-12)
    assert abs(kappa / ref - 1) <= bending_tolerance(g, "neo-hookean", form, solver)[0]


def test_a_lock_free_element_rolls_up_on_the_exact_bendings_arc():
    """HB2n-40p, a full roll-up (phi = 2 pi) at L/h = 50: the tip within the arc benchmark's
    tolerance (twice the exact plane-stress bending's own departure from Euler's arc)."""
    from studies.verification.benchmark_scenes import NEWTON_TOL, arc_departure, arc_scene
    from studies.verification.benchmarks import STUDY
    from studies.verification.closed_forms import elastica_end_moment

    g = dict(STUDY["grid"])
    g["arc_elements"] = 16
    phi = 2 * math.pi
    rec = _run(arc_scene(g, phi, 50.0, "HB2n-40p"))
    L = rec["scene"]["beam"]["length"]
    x, y = elastica_end_moment(phi)
    err = math.hypot(1 + rec["tip"]["ux"] / L - x, rec["tip"]["uy"] / L - y)
    assert err <= 2 * arc_departure(phi, 50.0) + NEWTON_TOL
    assert rec["tip"]["rotation"] > 2 * math.pi              # continued past pi, softer than the arc


REPORTS = __import__("pathlib").Path(__file__).resolve().parents[1] / "reports"


@pytest.mark.skipif(not (REPORTS / "benchmarks.csv").is_file(), reason="no committed benchmark report")
def test_every_benchmark_miss_names_its_cause():
    """Every FAIL of the committed benchmark report carries a cause (its note), and a bending or
    arc miss of an ANCF element has its measured one in ``CAUSES`` (a miss that appears after a
    change of the solver, or a cause taken out of the table, fails here); the report's summary
    names no miss without a cause."""
    import csv

    from studies.verification.benchmark_causes import CAUSES, cause_of
    from studies.verification.benchmark_rows import _is_cable

    with open(REPORTS / "benchmarks.csv") as fh:
        fails = [r for r in csv.DictReader(fh) if r["verdict"] == "FAIL"]
    assert fails
    for r in fails:
        assert r["note"].strip(), (r["case"], r["solver"])
        words = r["case"].split()
        if words[0] in ("bending", "arc") and not _is_cable(r["solver"]):
            law, form = (words[1], words[2]) if words[0] == "bending" else ("neo-hookean", "plane-stress")
            cause = cause_of(words[0], r["solver"], law, form)
            assert cause and cause in r["note"], (r["case"], r["solver"])
    assert "no cause named" not in (REPORTS / "README.md").read_text()
    assert all(v.strip() and "no cause named" not in v for v in CAUSES.values())
