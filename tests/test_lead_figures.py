"""The lead figures a reader opens first (accuracy_cost.png, accuracy_cost_pendulum.png and
the peer report's work-precision figures) read as matplotlib objects, not pixels: at most
MAX_SERIES labelled series per axes, every legend outside every axes, and each figure's
fronts naming the tables' cheapest runs. Drawn from the committed records' tables
(accuracy_cost_points.csv, data/peers/peers-work-precision.jsonl) and from synthetic points
where the records cannot reach the limit."""
import csv
from pathlib import Path

import pytest

from studies.design import accuracy_cost as ac, accuracy_cost_figures as acf, accuracy_cost_points as acp
from studies.peers import precision_rules as rules, records
from studies.engine.report import MAX_SERIES, series

REPORTS = Path(__file__).resolve().parents[1] / "reports"
PEERS = REPORTS / "data" / "peers" / "peers-work-precision.jsonl"
GRID = ac.STUDY["grid"]


def problems(fig) -> list[str]:
    """What fails the look: an axes with more than MAX_SERIES labelled series, a legend that
    overlaps an axes (window extents after a draw: the axes' own area, not its labels)."""
    import matplotlib.pyplot as plt

    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    legends = [*fig.legends, *(ax.get_legend() for ax in fig.axes if ax.get_legend())]
    out = [f"axes {i}: {len(series(ax))} series > {MAX_SERIES}" for i, ax in enumerate(fig.axes)
           if len(series(ax)) > MAX_SERIES]
    out += [f"a legend over axes {i}" for leg in legends for i, ax in enumerate(fig.axes)
            if leg.get_window_extent(r).overlaps(ax.get_window_extent(r))]
    out += ["no legend"] if not legends else []
    plt.close(fig)
    return out


def static_points() -> list[dict]:
    """accuracy_cost_points.csv (every point of the static diagram) as :func:`acp.points` gives them."""
    def num(v, scale=1.0):
        return float(v) * scale if v not in ("", None) else None
    return [{"law": r["law"], "model": r["model"], "solver": r["solver"], "config": r["configuration"],
             "element": r["configuration"].split()[0] if r["solver"] == "ancf" else "continuum",
             "mesh": r["mesh"], "ndof": int(r["ndof"]) if r["ndof"] else None, "verdict": r["verdict"],
             "time": num(r["time (s)"]), "error": num(r["error (%)"], 0.01)}
            for r in csv.DictReader(open(REPORTS / "accuracy_cost_points.csv"))]


def tied_pendulum(k: int = 10) -> list[dict]:
    """k elements whose fronts all tie at every target (each within 1 % of the others' time):
    more leaders than a lead figure may colour."""
    return [{"formulation": "plane-stress", "element": f"E{i}", "n": n, "dt": dt, "law": "yeoh", "rho_inf": 0.5,
             "slenderness": 70.0, "verdict": "converged", "error": err, "time": t * (1 + 0.001 * i)}
            for i in range(k) for n, dt, err, t in ((4, 4e-3, 0.02, 0.001), (8, 2e-3, 0.002, 0.002),
                                                    (16, 1e-3, 0.0005, 0.004))]


@pytest.mark.skipif(not (REPORTS / "accuracy_cost_points.csv").exists(), reason="no committed reports")
def test_the_static_lead_figure_reads_and_its_fronts_name_the_tables_cheapest_runs():
    from studies.common.gold import MATCHING

    pts = static_points()
    models = [MATCHING[f] for f in GRID["formulations"]]
    assert problems(acf.lead_figure(GRID, pts, models)) == []
    for law in GRID["laws"]:
        for m in models:
            fr, _ = acf.static_fronts(GRID, pts, law, m)
            sel = [p for p in pts if p["law"] == law and p["model"] == m and p["solver"] == "ancf"]
            for a in GRID["accuracies"]:
                first = [p for f in fr.values() for p in f if p["settled"] <= a]
                best = acp.cheapest(acp.settled(sel, a), a)
                assert (min(first, key=lambda p: p["time"])["config"], min(p["time"] for p in first)) == \
                    (best["config"], best["time"]) if best else not first


def test_the_pendulum_lead_figure_colours_at_most_its_share_of_tied_leaders():
    pts = tied_pendulum()
    fr = acp.fronts(acp.with_settled(pts, acp.pendulum_finer(pts)))
    assert len(acp.leaders(fr, GRID["accuracies"], 100)) == 10          # every element ties at every target
    fig = acf.pendulum_lead_figure(GRID, pts)
    assert [len(series(ax)) for ax in fig.axes] == [MAX_SERIES - 1]     # 6 leaders and one grey family
    assert problems(fig) == []
    # the full cloud is the secondary figure: every element and count
    assert len(series(acf.pendulum_all_figure(GRID, pts).axes[0])) == 30


@pytest.mark.skipif(not PEERS.exists(), reason="no peer records")
def test_the_peer_lead_figures_read_and_their_fronts_name_the_tables_cheapest_runs():
    from studies.peers import precision_report as pr

    recs = records.read(PEERS)
    for scene in pr.scenes_of(recs):
        rs = [r for r in recs if r.get("scene", pr.SCENE) == scene]
        assert problems(pr.make_figure(rs, scene)) == []
        fr = pr.settled_fronts(rs)
        runs = {}                       # the report's cheapest, per element (its rule looks no further)
        for r in rs:
            runs.setdefault((r["solver"], r["element"]), []).append(r)
        for a in pr.ACCURACIES:
            for solver in ("ancf", "exudyn"):
                first = [p for k, f in fr.items() if k[0] == solver for p in f if p["settled"] <= a]
                each = [rules.cheapest(g, s, e, a) for (s, e), g in runs.items() if s == solver]
                best = min((b for b in each if b), key=lambda b: b["time_s"], default=None)
                assert (min(first, key=lambda p: p["time"])["run"] is best) if best else not first
