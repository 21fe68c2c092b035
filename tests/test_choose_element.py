"""The accuracy-cost study's cable and its choose-an-element table, without solver runs:
the cable's cells where it runs (plane stress) and why it is absent elsewhere, the
cheapest element per scene and accuracy, and the L / h down to which the cable stays within
an accuracy, read from its card's records as the card reads them."""
from types import SimpleNamespace

import pytest

from studies.design import accuracy_cost as ac, choose_element as ce

GRID = {"laws": ["yeoh"], "formulations": ["plane-strain", "plane-stress"], "elements": ["HB2n-16", "HC2n-8"],
        "accuracies": [0.01, 0.001]}


def pt(element, mesh, error, time, model="plane-stress", verdict="stable"):
    return {"law": "yeoh", "model": model, "solver": "ancf", "config": f"{element} qdef", "element": element,
            "quadrature": "default", "mesh": mesh, "ndof": 8 * mesh, "error": error, "time": time,
            "verdict": verdict, "slenderness": 32.0}


def pend(element, n, dt, error, time, formulation="plane-stress"):
    return {"formulation": formulation, "element": element, "n": n, "dt": dt, "law": "yeoh", "slenderness": 70.0,
            "verdict": "converged", "error": error, "time": time}


def test_the_cable_runs_plane_stress_only_and_the_tables_say_why():
    g = {**GRID, "quadratures": ["default"], "counts": [4], "clamp": "face", "timing": {"repeats": 1, "budget_s": 0.0},
         "continuum_levels": [],
         "pendulum": {"elements": ["HC2n-8"], "counts": [8], "formulations": ["plane-stress", "paper"],
                      "rho_inf": 0.5, "t_end": 0.5, "dt_last": 0.004, "timing": {"repeats": 1, "budget_s": 0.0}}}
    names = [c.name for c in ac.cases(g, True)]
    assert "cantilever-yeoh-plane-stress-HC2n-8-4-qdef-face" in names
    assert "cantilever-yeoh-plane-strain-HB2n-16-4-qdef-face" in names
    assert not any("plane-strain-HC2n-8" in n for n in names)
    dyn = [n for n in names if n.startswith("pendulum-")]            # the ladder 8, 4 ms; no `paper` cable
    assert dyn == ["pendulum-yeoh-plane-stress-HC2n-8-8-dt0.008-generalized-alpha-rho0.5-t0.5",
                   "pendulum-yeoh-plane-stress-HC2n-8-8-dt0.004-generalized-alpha-rho0.5-t0.5"]
    (why,) = ce.absent(g)
    assert why.startswith("HC2n-8 has no `plane-strain` cells: a cable integrates the law's incompressible uniaxial "
                          "energy over its section (free lateral faces), so plane stress alone")
    rules = {k: v for k, v in g.items() if k != "pendulum"}          # accuracy-cost-rules' grid has no pendulum
    assert not any(c.name.startswith("pendulum-") for c in ac.cases(rules, True))


def test_choose_names_the_cheapest_element_and_the_cables_slenderness_limit():
    from studies.design.card_cable import _crossing

    pts = [pt("HC2n-8", 8, 0.004, 0.002), pt("HC2n-8", 16, 0.004, 0.004),          # the cable: 0.4 % floor
           pt("HB2n-16", 16, 0.005, 0.01), pt("HB2n-16", 32, 0.0006, 0.02), pt("HB2n-16", 64, 0.0005, 0.04),
           pt("HB2n-16", 16, 0.003, 0.01, "plane-strain-penalty")]
    pendulum = [pend("HC2n-8", 4, 5e-3, 0.003, 0.001), pend("HC2n-8", 4, 2.5e-3, 0.0004, 0.002),
                pend("HC2n-8", 8, 5e-3, 0.003, 0.002), pend("HC2n-8", 8, 2.5e-3, 0.0004, 0.004),
                pend("HB2n-16", 16, 5e-3, 0.002, 0.03), pend("HB2n-16", 16, 2.5e-3, 0.0002, 0.05),
                pend("HB2n-12", 16, 1e-3, 0.008, 0.08, "paper")]
    sweep = [(140.0, 0.0004), (70.0, 0.0008), (32.0, 0.004), (16.0, 0.02), (8.0, 0.09)]
    rows = ce.choose_rows(GRID, pts, pendulum, {("HC2n-8", "yeoh"): sweep})
    by = {(r[0], r[1]): r for r in rows}
    strain1 = by[("cantilever, Yeoh, `plane-strain`", "1 %")]
    assert strain1[2:] == ["HB2n-16 qdef x 16", 0.01, pytest.approx(0.3), "", "32", "HC2n-8: - (plane stress only)"]
    stress1 = by[("cantilever, Yeoh, `plane-stress`", "1 %")]
    assert stress1[2:4] == ["HC2n-8 qdef x 8", 0.002] and stress1[6] == "32"
    # the card's own crossing: 1 % between L/h 32 (0.4 %) and 16 (2 %), log-log
    assert stress1[7] == f"HC2n-8: {_crossing(sweep, 0.01)}" == "HC2n-8: 21.6"
    stress01 = by[("cantilever, Yeoh, `plane-stress`", "0.1 %")]
    assert stress01[2] == "HB2n-16 qdef x 32" and stress01[7] == "HC2n-8: 62.8"
    p1, p01 = by[("pendulum, `plane-stress`", "1 %")], by[("pendulum, `plane-stress`", "0.1 %")]
    assert p1[2:4] == ["HC2n-8 x 4, dt 5 ms", 0.001] and p1[6] == "70"
    assert p01[2] == "HC2n-8 x 4, dt 2.5 ms"           # 4 x 5 ms is 0.3 % off: not within 0.1 %
    assert by[("pendulum, `paper`", "1 %")][2:] == ["HB2n-12 x 16, dt 1 ms", 0.08, pytest.approx(0.8), "", "70",
                                                    "HC2n-8: - (plane stress only)"]
    assert ce.choose_rows(GRID, pts, [], {})[2][7] == "HC2n-8: no card records"
    # within it at every L / h of the sweep, or beyond it already at the most slender
    assert ce.choose_rows(GRID, pts, [], {("HC2n-8", "yeoh"): [(140.0, 0.02), (32.0, 0.05)]})[2][7] == "HC2n-8: < 140"
    assert ce.choose_rows(GRID, pts, [], {("HC2n-8", "yeoh"): [(16.0, 1e-4), (4.0, 5e-4)]})[2][7] == "HC2n-8: > 4"


def test_the_cables_slenderness_is_read_from_its_card_records_as_the_card_reads_them():
    """The sweep's records (the card's case names and scenes), the finest mesh's tip at each
    L / h against the slenderness gold; a failed run and other elements' records are passed by."""
    from studies.verification.slenderness_gold import GOLD, references

    refs = references(GOLD)
    if not refs:
        pytest.skip("no tests/gold/fem_slenderness.json")
    asked = []

    def record_for(case, name):
        asked.append(name)
        s = case.scene
        ratio = round(s["beam"]["length"] / s["beam"]["height"], 6)
        ux, uy = refs[(s["material"]["law"], ratio)]["tip"]
        n = s["ancf"]["elements"]
        k = 1.0 + (0.5 if n == 32 else 1.0) * 0.01 * 32.0 / ratio        # 64 elements: 1 % x 32 / (L/h)
        if ratio == 140.0 and n == 64:
            return {"status": "failed", "scene": s, "tip": None}
        return {"status": "converged", "scene": s, "tip": {"ux": k * ux, "uy": k * uy}}
    ctx = SimpleNamespace(study=SimpleNamespace(grid={"elements": ["HB2n-16", "HC2n-8"]}), tiny=True,
                          record_for=record_for)
    sw = ce.cable_slenderness(ctx)
    assert set(asked) == {"card-HC2n-8"}
    assert sorted(sw) == [("HC2n-8", law) for law in ("mooney-rivlin", "neo-hookean", "yeoh")]
    got = dict(sw[("HC2n-8", "yeoh")])
    assert got[32.0] == pytest.approx(0.01) and got[8.0] == pytest.approx(0.04)
    assert got[140.0] == pytest.approx(0.5 * 0.01 * 32 / 140)      # its 64-element run failed: the 32's
