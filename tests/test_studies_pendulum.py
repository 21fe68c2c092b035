"""The pendulum studies (Figure 4, Figure 5, Table 4, stability) in tiny mode: the step
rule of Table 4 against studies.design.bench.converged_step, errors against the continuum gold
recomputed here, the provisional reference without it, and the hard-case report's
honest failures and its bound."""
from __future__ import annotations

import csv
import json
import math
import shutil

import pytest

from contract import paper
from studies.common import pendulum_cases as pendulum
from studies.paper import figure4, table4
from studies.verification import dynamics_stability as stability
from studies.design.bench import converged_step
from studies.engine.catalog import load_catalog
from studies.engine.pipeline import build_reports, run_studies
from studies.engine.report import Context

PENDULUM = ["figure4", "figure5", "table4", "stability"]


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    out = tmp_path_factory.mktemp("studies-pendulum")
    run_studies(PENDULUM, out, tiny=True, executor="serial", progress=False, log=lambda *a: None)
    return out, load_catalog(tiny=True)


def ctx(out, catalog, name):
    return Context(catalog[name], out, catalog)


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


@pytest.mark.slow(guard="test_converged_rung_needs_both_runs_converged_and_the_tolerance")
def test_table4_picks_the_step_of_bench_converged_step(tiny):
    out, cat = tiny
    sel = table4.selected(ctx(out, cat, "table4"))
    assert sel
    for s in sel:
        dt, diff = converged_step(s["element"], s["n"], s["formulation"], cat["table4"].grid["rho_inf"])
        assert s["rung"] is not None and dt is not None
        assert s["rung"]["dt"] == pytest.approx(dt, rel=1e-12)
        assert s["diff"] == pytest.approx(diff, rel=1e-6, abs=1e-9)
        t = s["rung"]["timing"]
        assert t["serial"] and t["median_s"] > 0
    # the table shows the rung's median and the paper's time beside it
    tab = rows(out / "table4.csv")
    assert float(tab[0]["converged dt (ms)"]) == pytest.approx(1e3 * sel[0]["rung"]["dt"])
    assert float(tab[0]["wall s (median)"]) == pytest.approx(sel[0]["rung"]["timing"]["median_s"])


def test_converged_rung_needs_both_runs_converged_and_the_tolerance():
    def rung(dt, y, ok=True):
        return {"dt": dt, "ok": ok, "tips": {0.0: (0.35, 0.0), 0.5: (0.1, y)}}
    rungs = [rung(8e-3, 0.0), rung(4e-3, 5e-4), rung(2e-3, 5.5e-4, ok=False), rung(1e-3, 5.6e-4), rung(5e-4, 5.65e-4)]
    best, diff = table4.converged_rung(rungs, tol=1e-4)
    assert best["dt"] == 1e-3 and diff == pytest.approx(5e-6)
    assert table4.converged_rung(rungs[:3], tol=1e-4) == (None, None)
    assert table4.ladder(8e-3, 1e-4, 2.5e-4) == [8e-3, 4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4]


def test_figure4_errors_are_distances_to_the_continuum_gold(tiny):
    out, cat = tiny
    gold = json.loads(pendulum.FEM_GOLD.read_text()) if pendulum.FEM_GOLD.exists() else None
    if gold is None or "yeoh/plane-stress" not in gold["cases"]:
        pytest.skip("no continuum pendulum gold file")
    ref = {round(h["t"], 9): (h["x"], h["y"]) for h in gold["cases"]["yeoh/plane-stress"]["tip_history"]}
    t_end = cat["figure4"].grid["t_end"]
    tab = {(r["formulation"], r["element"], r["n"]): r for r in rows(out / "figure4_convergence.csv")}
    checked = 0
    for rec in ctx(out, cat, "figure4").records():
        s = rec["scene"]
        key = (s["material"]["formulation"], s["ancf"]["element"], str(s["ancf"]["elements"]))
        if s["analysis"]["dt"] != cat["figure4"].grid["dt"] or key not in tab:
            continue
        h = next(h for h in rec["tip_history"] if abs(h["t"] - t_end) < 1e-9)
        e = math.hypot(h["x"] - ref[round(t_end, 9)][0], h["y"] - ref[round(t_end, 9)][1]) / 0.350
        assert float(tab[key][f"error at {t_end:g} s (% L)"]) == pytest.approx(100 * e, rel=1e-9)
        checked += 1
    assert checked == len(tab)
    # more elements, smaller error (each element, plane stress)
    for el in cat["figure4"].grid["elements"]:
        errs = [float(tab[("plane-stress", el, str(n))][f"error at {t_end:g} s (% L)"])
                for n in cat["figure4"].grid["counts"]]
        assert errs == sorted(errs, reverse=True), (el, errs)


@pytest.mark.slow(guard="test_figure4_errors_are_distances_to_the_continuum_gold")
def test_without_the_continuum_gold_the_reference_is_the_finest_ancf_labelled_provisional(tiny, tmp_path, monkeypatch):
    out, cat = tiny
    assert pendulum.continuum_pendulum(tmp_path / "absent.json") == {}
    copy = tmp_path / "copy"
    shutil.copytree(out, copy)
    monkeypatch.setattr(figure4, "continuum_pendulum", lambda: {})
    build_reports(copy, tiny=True)
    text = (copy / "README.md").read_text()
    ref = cat["figure4"].grid["reference"]
    assert f"PROVISIONAL: finest ANCF `plane-stress` {ref['element']} x {ref['elements']}" in text
    tab = rows(copy / "figure4_convergence.csv")
    assert all(r["error at 0.2 s (% L)"] for r in tab if r["status"] == "converged")


def test_figure5_draws_every_law_from_the_records_configurations(tiny):
    out, cat = tiny
    g = cat["figure5"].grid
    for law in g["laws"]:
        assert (out / f"figure5_{law}.png").stat().st_size > 10_000
    for rec in ctx(out, cat, "figure5").records():
        assert rec["status"] == "converged"
        ts = [k["t"] for k in rec["configurations"]]
        assert ts == pytest.approx(paper.output_times(g["t_end"]))
        last = rec["configurations"][-1]
        assert (last["x"][-1], last["y"][-1]) == pytest.approx((rec["tip_history"][-1]["x"], rec["tip_history"][-1]["y"]),
                                                               abs=1e-12)


def test_stability_report_states_the_bound_first_and_shows_failures_honestly(tiny):
    out, cat = tiny
    page = (out / "stability.md").read_text()
    assert page.index("1e-3 m g L / 2") < page.index("| hard case |")
    rs = stability.rows_of(ctx(out, cat, "stability"))
    assert len(rs) == len(stability.hard_cases(cat["stability"].grid)) * len(cat["stability"].grid["integrators"])
    for x in rs:
        rec = x["d"]
        # the bound computed here from the scene is the limit ancf enforced in the run
        assert x["bound"] == pytest.approx(x["enforced"], rel=1e-12)
        if rec["status"] != "converged":
            assert x["verdict"] == "energy-growth (stopped)" or x["verdict"].startswith("failed")
    grown = [x for x in rs if x["verdict"] == "energy-growth (stopped)"]
    assert grown and all(x["integrator"] == "generalized-alpha" and x["group"] == "penalty" for x in grown)
    table = rows(out / "stability_runs.csv")
    assert sum(r["verdict"] == "energy-growth (stopped)" for r in table) == len(grown)
    assert all(r["status"] == "converged" for r in table if r["integrator"].startswith("discrete-gradient"))
    dg = [x for x in rs if x["integrator"] == "discrete-gradient"]
    # conserved to Newton's tolerance (README: about 1e-13 J), far inside the bound
    assert dg and all(x["drift"] <= 1e-6 * x["bound"] for x in dg)
    # the energy lost is shown as a number: never more than the largest change, and numerical
    # damping (rho_inf = 0) takes more than the conservative generalized-alpha (rho_inf = 1)
    for x in rs:
        if x["lost"] is not None:
            assert abs(x["lost"]) * x["bound"] / 1e-3 <= x["drift"] * (1 + 1e-9)
    ga = {x["label"]: x["lost"] for x in rs if x["integrator"] == "generalized-alpha"}
    assert ga["rho_inf = 0"] > max(ga["rho_inf = 1"], 0.0)
    assert "NaN" not in page and "nan" not in (out / "stability_runs.csv").read_text()


def test_the_pendulum_work_precision_points_are_table4_rungs_against_the_continuum(tiny):
    from studies.design.accuracy_cost_points import pendulum_points

    out, cat = tiny
    if not pendulum.FEM_GOLD.exists():
        pytest.skip("no continuum pendulum gold file")
    ref = {round(h["t"], 9): (h["x"], h["y"])
           for h in json.loads(pendulum.FEM_GOLD.read_text())["cases"]["yeoh/plane-stress"]["tip_history"]}
    pts = pendulum_points(ctx(out, cat, "accuracy-cost"))
    recs = ctx(out, cat, "table4").records()
    assert len(pts) == len(recs) > 0
    for p, r in zip(pts, recs):
        if r["status"] != "converged":
            assert p["error"] is None and p["time"] is None
            continue
        e = max(math.hypot(h["x"] - ref[round(h["t"], 9)][0], h["y"] - ref[round(h["t"], 9)][1])
                for h in r["tip_history"] if h["t"] > 0) / 0.350
        assert p["error"] == pytest.approx(e, rel=1e-12)
        assert p["time"] == r["timing"]["median_s"]
