"""The kernel benchmark's table (studies.design.bench kernels): generated from its CSV rows, every
built-in element x law x formulation has a material, and one timed row is sane. Times are
printed by the benchmark, never asserted here."""
import csv
import io

from ancf.elements import ELEMENTS
from contract.scene import FORMULATIONS, scene_from_dict
from mechanics.laws import LAWS
from studies.design import bench
from studies.common.pendulum_cases import pendulum_dict


def test_every_element_law_and_formulation_has_a_material():
    for law in LAWS:
        for form in FORMULATIONS:
            d = pendulum_dict(sorted(ELEMENTS)[0], 2, form, 1e-3)
            d["material"] = bench._kernel_material(law, form)
            assert scene_from_dict(d).material.law == law


def test_table_is_generated_from_the_csv_rows():
    rows = [{"solver": "ours", "element": "HB2n-12", "law": "yeoh", "formulation": "paper", "elements": 32,
             "points_per_element": 6, "calls": 100, "repeats": 10, "force_us_per_element": 0.25,
             "tangent_us_per_element": 0.6, "force_spread": 0.05, "tangent_spread": 0.1, "what": "compiled"},
            {"solver": "Exudyn 1.13.6", "element": "ANCFCable2D", "law": "linear elastic",
             "formulation": "Euler-Bernoulli", "elements": 32, "points_per_element": "", "calls": 100,
             "repeats": 10, "force_us_per_element": 0.2, "tangent_us_per_element": 1.5, "force_spread": 0.1,
             "tangent_spread": 0.02, "what": "exudyn"}]
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=bench.KERNEL_FIELDS)
    w.writeheader()
    w.writerows(rows)
    md = bench.kernel_markdown(list(csv.DictReader(io.StringIO(buf.getvalue()))))
    assert "| HB2n-12 | yeoh | paper | compiled | 6 | 0.250 | 0.05 | 0.600 | 0.10 |" in md
    assert "## Exudyn 1.13.6" in md and "| ANCFCable2D | linear elastic | Euler-Bernoulli | exudyn |  | 0.200 |" in md


def test_one_kernel_row():
    rows = bench.kernel_rows(calls=2, repeats=2, elements=4, only=("HB2n-12", "yeoh", "plane-stress"))
    assert len(rows) == 1
    r = rows[0]
    assert r["elements"] == 4 and r["points_per_element"] == 6
    # times are measured, never compared here (a loaded machine reorders them)
    assert r["force_us_per_element"] > 0 and r["tangent_us_per_element"] > 0
    assert r["force_spread"] >= 0 and r["tangent_spread"] >= 0 and r["what"] == "compiled"
