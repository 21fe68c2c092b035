"""studies.peers.compare without Exudyn: parsing the peer script's output and the table."""
import json
import statistics
from pathlib import Path

import pytest

from studies.peers import compare, precision_rules as rules, records, step_cost_report as scr

TIMES = (0.1, 0.2, 0.3, 0.4, 0.5)


def fake_peer(status="converged"):
    return {
        "status": status, "reason": None if status == "converged" else "SolveDynamic returned False",
        "settings": {"exudyn": "9.9", "elements": 32, "steps": 500, "spectralRadius": 0.8,
                     "linearSolver": "LinearSolverType.EigenSparse",
                     "newton": {"useModifiedNewton": True}},
        "counters": {"newtonSteps": 1500, "newtonJacobians": 40, "ODE2_coordinates": 132,
                     "algebraic_coordinates": 2},
        "repeats": 5, "build_s": [0.001] * 5, "solve_s": [0.1, 0.2, 0.1, 0.1, 0.1],
        "build_median_s": 0.001, "solve_median_s": 0.1, "solve_cpu_s": [0.1] * 5, "solve_cpu_median_s": 0.1,
        "tip_history": [{"t": t, "x": 0.3 - t, "y": -t} for t in TIMES],
    }


def fake_ours(wall=0.25):
    return {
        "element": "HB2n-12", "elements": 32, "formulation": "plane-stress", "law": "yeoh",
        "dt": 1e-3, "rho_inf": 0.8, "wall_s": [wall] * 5, "wall_median_s": wall, "cpu_s": [wall] * 5, "cpu_median_s": wall,
        "setup_median_s": 0.002, "first_run_s": 1.0, "steps": 500, "rejected_steps": 0,
        "newton_iterations": 1000, "ndof": 196,
        # t = 0 is ours only; the others are Exudyn's + (1 mm, -2 mm), off by round-off in t
        "tip_history": [{"t": 0.0, "x": 0.35, "y": 0.0}]
        + [{"t": t + 1e-13, "x": 0.3 - t + 1e-3, "y": -t - 2e-3} for t in TIMES],
    }


def test_parse_takes_the_last_json_line_after_exudyn_chatter():
    out = "Imported exudyn fast version without range checks\n" + json.dumps(fake_peer()) + "\n\n"
    assert compare.parse_peer_output(out)["solve_median_s"] == 0.1
    with pytest.raises(RuntimeError, match="not JSON"):
        compare.parse_peer_output(json.dumps(fake_peer()) + "\nsome warning")
    with pytest.raises(RuntimeError, match="failed"):
        compare.parse_peer_output(json.dumps(fake_peer("failed")))


def test_table_ratio_and_tip_differences():
    text = compare.format_table(fake_ours(0.04), fake_peer(), ((1.0, 1.0, 1.0), (1.5, 1.0, 1.0)))
    assert ("ratio ours / Exudyn: 0.40 wall, 0.40 CPU (ours 0.0400 s, Exudyn 0.1000 s CPU); by round (CPU) "
            "0.40, median 0.40; target: within 0.5x -> within target") in text
    assert "spread (min-max): ours 0.0400-0.0400 s wall" in text and "Exudyn 0.1000-0.2000 s wall" in text
    rows = [ln.split() for ln in text.splitlines() if ln.startswith(" 0.") and len(ln.split()) == 8]
    assert [float(r[0]) for r in rows] == list(TIMES)
    for r in rows:
        assert (float(r[5]), float(r[6]), float(r[7])) == pytest.approx((1.0, -2.0, 5 ** 0.5), abs=0.006)
    assert "linearSolver = LinearSolverType.EigenSparse" in text and "useModifiedNewton = True" in text
    assert "before 1.00 1.00 1.00, after 1.50 1.00 1.00" in text
    assert "NOT within target" in compare.format_table(fake_ours(0.06), fake_peer())     # HB2n-12: 0.5x


def test_missing_output_time_is_an_error():
    o = fake_ours()
    o["tip_history"] = o["tip_history"][:-1]
    with pytest.raises(RuntimeError, match="t = 0.5"):
        compare.tip_differences(o["tip_history"], fake_peer()["tip_history"])


# -- work-precision (studies.peers.work_precision), without Exudyn ----------------------------
def test_work_precision_error_is_zero_on_the_reference_and_the_report_picks_the_cheapest(tmp_path):
    from studies.common.pendulum_cases import continuum_pendulum
    from studies.peers import precision_report as pr, work_precision as wp

    ref = continuum_pendulum()[("yeoh", "plane-stress")]
    tips = [{"t": t, "x": x, "y": y} for t, (x, y) in sorted(ref.tips.items())]
    assert wp.error(tips) == 0.0
    moved = [{**h, "x": h["x"] + 0.0035} for h in tips]          # 3.5 mm = 1 % of L at every t > 0
    assert abs(wp.error(moved) - 0.01) < 1e-12

    def rec(solver, element, n, t, e):
        return {"solver": solver, "element": element, "elements": n, "dt": 1e-3, "rho_inf": 0.5,
                "status": "converged", "time_s": t, "error": e}
    recs = [rec("ancf", "HB2n-12", 8, 0.02, 0.02), rec("ancf", "HB2n-12", 32, 0.2, 0.005),
            rec("ancf", "HB2n-16", 32, 0.1, 0.009), rec("exudyn", "ANCFCable2D", 8, 0.01, 0.006)]
    assert rules.cheapest(recs, "ancf", None, 0.01)["element"] == "HB2n-16"
    assert rules.cheapest(recs, "exudyn", None, 0.001) is None
    text = pr.report(recs, tmp_path)
    assert "| 1 % | HB2n-16 x 32, dt 1 ms | 0.1000 | 0.900 | 8 elements, dt 1 ms | 0.0100 | 0.600 | 10.00 |" in text
    assert (tmp_path / "peers_work_precision.png").exists()


def test_work_precision_keeps_finished_points_and_skips_them_on_a_rerun(tmp_path, monkeypatch):
    from types import SimpleNamespace
    from studies.peers import precision_report as pr, work_precision as wp

    calls = []

    def fake(*args):
        calls.append(args)
        return {"status": "converged", "reason": None, "time_s": 0.01, "cpu_s": 0.01, "tip_history": None}
    monkeypatch.setattr(wp, "ours", lambda element, n, dt, rho, rep, scene: fake("ancf", element, n, dt, scene))
    monkeypatch.setattr(wp, "exudyn", lambda n, dt, rho, rep, py, scene, element: fake("exudyn", element, n, dt,
                                                                                       scene))
    a = SimpleNamespace(out=tmp_path, force=False, counts=[4, 8], steps_per_output=[20], element=["HB2n-12"],
                        rho_inf=0.5, repeats=1, peer_python=None, scene="pendulum")
    # each point: the cable with Newton and with one linear solve per step, then ours at its
    # defaults, at the loosest Newton tolerance and with one linear solve per step
    assert len(wp.run(a)) == 10 and len(calls) == 10
    assert [c[1] for c in calls[:5]] == ["ANCFCable2D", "ANCFCable2D-linear", "HB2n-12", "HB2n-12 (rtol 1e-3)",
                                         "HB2n-12 (linear)"]
    assert len(wp.run(a)) == 10 and len(calls) == 10          # nothing recomputed
    a.force = True
    assert len(wp.run(a)) == 10 and len(calls) == 20
    # a second scene: same points, its own records, keyed by scene; --force redoes only its own
    a.scene = "thick"
    recs = wp.run(a)
    assert len(recs) == 20 and len(calls) == 30 and {r["scene"] for r in recs} == {"pendulum", "thick"}
    assert {r["height"] for r in recs if r["scene"] == "thick"} == {0.020} and calls[-1][-1] == "thick"
    assert len(wp.run(a)) == 20 and len(calls) == 40 and pr.scenes_of(wp.run(a)) == ["pendulum", "thick"]


def test_our_settings_label_the_element_and_reach_the_scene():
    """'HB2n-20xyp (rtol 1e-3)' runs HB2n-20xyp with newton_rtol = 1e-3; the bare name runs
    the defaults; the scene built from either is valid."""
    from contract.scene import scene_from_dict
    from studies.peers import work_precision as wp
    from studies.peers.precision_grid import our_element

    assert our_element("HB2n-20xyp (rtol 1e-3)") == ("HB2n-20xyp", {"newton_rtol": 1e-3})
    assert our_element("HB2n-20xyp") == ("HB2n-20xyp", {})
    assert our_element("HC2n-8 (linear)") == ("HC2n-8", {"newton": "linear"})
    assert scene_from_dict(wp.scene_dict("HC2n-8 (linear)", 4, 0.005, 0.5, "pendulum")).analysis.newton == "linear"
    loose = scene_from_dict(wp.scene_dict("HB2n-20xyp (rtol 1e-3)", 4, 0.01, 0.5, "thick"))
    plain = scene_from_dict(wp.scene_dict("HB2n-20xyp", 4, 0.01, 0.5, "thick"))
    assert loose.analysis.newton_rtol == 1e-3 and plain.analysis.newton_rtol == 1e-8
    assert loose.ancf.element == plain.ancf.element == "HB2n-20xyp"


def test_the_cables_cheapest_run_is_taken_over_both_its_newtons_and_named():
    """A linear-solve cable run that reaches the accuracy for less time is the cable's
    cheapest, and the tables say which of its two settings it is."""
    from studies.peers import anatomy, precision_report as pr

    def rec(solver, element, n, t, e):
        return {"scene": "pendulum", "solver": solver, "element": element, "elements": n, "dt": 1e-2,
                "rho_inf": 0.5, "status": "converged", "time_s": t, "time_runs_s": [t], "error": e,
                "newton_iterations": 50}
    recs = [rec("ancf", "HB2n-16", 8, 0.01, 0.005), rec("exudyn", "ANCFCable2D", 4, 0.02, 0.004),
            rec("exudyn", "ANCFCable2D-linear", 4, 0.008, 0.006)]
    assert rules.cheapest(recs, "exudyn", None, 0.01)["element"] == "ANCFCable2D-linear"
    assert rules.cheapest(recs, "exudyn", None, 0.005)["element"] == "ANCFCable2D"       # linear misses 0.5 %
    text = pr.report_markdown(recs)
    assert "| 1 % | HB2n-16 x 8, dt 10 ms | 0.0100 | 0.500 | 4 elements, linear, dt 10 ms | 0.0080 | 0.600 | 1.25 |" in text
    assert "| | cable: cable x 4, linear, dt 10 ms | 50 | 50 | 1.00 |" in text
    assert anatomy.factors(recs[2])["per_step"] == 1.0


def test_work_precision_report_has_a_section_per_scene_with_its_ratios():
    from studies.peers import precision_report as pr

    def rec(scene, solver, n, dt, e, runs):
        return {"scene": scene, "solver": solver, "element": "ANCFCable2D" if solver == "exudyn" else "HB2n-16",
                "elements": n, "dt": dt, "rho_inf": 0.5, "status": "converged", "time_s": sorted(runs)[len(runs) // 2],
                "time_runs_s": runs, "error": e, "energy_guard": "none", "host_load": [1.0, 1.5]}
    five = [0.01] * 5
    recs = [rec("pendulum", "exudyn", 8, 1e-3, 0.0005, [0.02] * 5), rec("pendulum", "ancf", 8, 1e-3, 0.0005, five),
            rec("thick", "exudyn", 8, 1e-3, 0.004, [0.02] * 5), rec("thick", "ancf", 8, 1e-3, 0.0005, five)]
    text = pr.report_markdown(recs)
    pend, thick = text.split("## Scene `pendulum`")[1].split("## Scene `thick`")
    assert "| 0.1 % | HB2n-16 x 8, dt 1 ms | 0.0100 | 0.050 | 8 elements, dt 1 ms | 0.0200 | 0.050 | 0.50 | 0.50-0.50 |" in pend
    # the cable's 0.4 % floor: it reaches 1 % but not 0.1 %
    assert "| 1 % | HB2n-16 x 8, dt 1 ms | 0.0100 | 0.050 | 8 elements, dt 1 ms | 0.0200 | 0.400 | 0.50 |" in thick
    assert "| 0.1 % | HB2n-16 x 8, dt 1 ms | 0.0100 | 0.050 | none | - | - | - (ours reaches it, the cable does not) | - |" in thick
    assert "| exudyn | ANCFCable2D | 8 | 1 | 0.4000 |" in thick and "1.00 to 1.50" in thick
    assert "Our elements: HB2n-16 (all on the compiled step loop" in thick and "h = 20 mm" in thick


def test_work_precision_retimes_the_deciding_points_in_alternating_rounds(tmp_path, monkeypatch):
    """After the grid, each accuracy's cheapest pair is timed again, the cable's runs then
    ours in each round; the table shows the median of the rounds' ratios beside the grid's
    ratio; a rerun keeps the rounds while the pair stays the cheapest, --force redoes them."""
    from types import SimpleNamespace
    from studies.peers import precision_report as pr, work_precision as wp

    calls = []
    times = iter([0.02, 0.01, 0.02, 0.004, 0.04, 0.01] * 10)     # cable, ours, cable, ours, ...

    def fake(solver, *args):
        calls.append(solver)
        return {"time_s": next(times)}
    monkeypatch.setattr(wp, "ours", lambda element, n, dt, rho, rep, scene: fake("ancf"))
    monkeypatch.setattr(wp, "exudyn", lambda n, dt, rho, rep, py, scene, element: fake("exudyn"))

    def rec(solver, element, n, t, e):
        return {"scene": "pendulum", "solver": solver, "element": element, "elements": n, "dt": 1e-3,
                "rho_inf": 0.5, "status": "converged", "time_s": t, "time_runs_s": [t], "error": e}
    recs = [rec("ancf", "HB2n-16", 8, 0.01, 0.0005), rec("exudyn", "ANCFCable2D", 8, 0.03, 0.0005)]
    path = records.points_path(tmp_path)
    path.parent.mkdir(parents=True)
    a = SimpleNamespace(scene="pendulum", rounds=3, repeats=5, rho_inf=0.5, peer_python=None, force=False)
    rounds = wp.retime(recs, a, path)
    assert calls == ["exudyn", "ancf"] * 9                    # 3 accuracies x 3 rounds, alternating
    assert [len(r["rounds"]) for r in rounds] == [3, 3, 3]
    text = pr.report_markdown(recs, records.read(records.rounds_path(path)))
    assert "| 0.1 % | HB2n-16 x 8, dt 1 ms | 0.0100 | 0.050 | 8 elements, dt 1 ms | 0.0300 | 0.050 | 0.33 | " \
           "0.33-0.33 | 0.25 (0.50, 0.20, 0.25) |" in text
    assert wp.retime(recs, a, path) == rounds and len(calls) == 18      # kept: the same cheapest pair
    a.force = True
    wp.retime(recs, a, path)
    assert len(calls) == 36
    cheaper = recs + [rec("ancf", "HB2n-12", 8, 0.005, 0.0005)]       # another pair: its rounds are missing
    assert "| 0.1 % | HB2n-12 x 8" in pr.report_markdown(cheaper, rounds) and "| 0.33-0.33 | - |" not in text
    assert pr.report_markdown(cheaper, rounds).count("| - |") >= 3


def test_work_precision_does_not_count_accuracy_by_cancellation():
    from studies.peers import precision_report as pr

    def rec(dt, e, t):
        return {"solver": "exudyn", "element": "ANCFCable2D", "elements": 8, "dt": dt, "rho_inf": 0.5,
                "status": "converged", "time_s": t, "error": e}
    recs = [rec(5e-3, 0.0005, 0.01), rec(2.5e-3, 0.0013, 0.02), rec(1.25e-3, 0.0009, 0.04)]
    # 5 ms reaches 0.1 % only by luck (the 2.5 ms step loses it); 1.25 ms is the first that holds
    assert rules.cheapest(recs, "exudyn", None, 0.001)["dt"] == 1.25e-3
    assert rules.cheapest(recs, "exudyn", None, 0.002)["dt"] == 5e-3


def test_the_fairness_rule_refuses_a_cancellation_by_mesh_or_by_step_on_both_sides():
    """Two-way: a run counts for an accuracy only if every finer step of its mesh and every
    finer mesh at its step reach it too (a failed or diverged one reaches nothing); the same
    rule for ours and the cable's. A settled run is kept."""
    from studies.peers import precision_report as pr

    def grid(solver, element, errors, t0=0.01):
        """errors: {(n, dt in ms): error or None (failed)}; time grows with n / dt."""
        return [{"solver": solver, "element": element, "elements": n, "dt": ms * 1e-3, "rho_inf": 0.5,
                 "status": "converged" if e is not None else "failed", "time_s": t0 * n / ms if e is not None else None,
                 "error": e} for (n, ms), e in errors.items()]
    for solver, element in (("exudyn", "ANCFCable2D-linear"), ("ancf", "HC2n-8 (rtol 1e-3)")):
        # 4 x 10 ms reaches 1 % by a mesh error that cancels the step's: 8 and 16 elements at
        # 10 ms are 1.35 % off (the cable point); its finer steps alone would keep it
        by_mesh = grid(solver, element, {(4, 10): 0.0100, (4, 5): 0.005, (4, 2.5): 0.009,
                                         (8, 10): 0.0135, (16, 10): 0.0135, (8, 5): 0.004, (16, 5): 0.003,
                                         (8, 2.5): 0.001, (16, 2.5): 0.001})
        me = next(r for r in by_mesh if (r["elements"], r["dt"]) == (4, 1e-2))
        assert [(q["elements"], q["dt"]) for q in rules.finer(me, by_mesh)] == [(4, 1e-2), (4, 5e-3), (4, 2.5e-3),
                                                                             (8, 1e-2), (16, 1e-2)]
        assert not rules.holds(me, by_mesh, 0.01)
        best = rules.cheapest(by_mesh, solver, None, 0.01)            # the settled one: 4 x 5 ms
        assert (best["elements"], best["dt"]) == (4, 5e-3) and rules.holds(best, by_mesh, 0.01)
        # 8 x 5 ms reaches 0.3 % while its finer step on the same mesh does not
        by_step = grid(solver, element, {(8, 5): 0.002, (8, 2.5): 0.004, (16, 5): 0.002, (16, 2.5): 0.001})
        assert not rules.holds(by_step[0], by_step, 0.003) and rules.holds(by_step[0], by_step, 0.005)
        assert (rules.cheapest(by_step, solver, None, 0.003)["elements"], rules.cheapest(by_step, solver, None, 0.003)["dt"]) \
            == (16, 5e-3)
        # a finer mesh at the same step that failed refuses it too
        failed = grid(solver, element, {(4, 10): 0.005, (4, 5): 0.004, (8, 10): None, (8, 5): 0.003})
        assert not rules.holds(failed[0], failed, 0.01)
        assert rules.cheapest(failed, solver, None, 0.01)["dt"] == 5e-3
        # another element's or setting's runs are not its refinements
        other = grid(solver, element + "x", {(8, 10): 0.05})
        assert rules.holds(best, by_mesh + other, 0.01)


def test_the_thick_floors_set_our_cable_beside_the_shear_deformable_elements():
    from studies.peers import precision_report as pr

    def rec(solver, element, e):
        return {"solver": solver, "element": element, "elements": 64, "dt": 3.125e-4, "error": e}
    fl = pr.floors([rec("ancf", "HC2n-8", 0.0045), rec("ancf", "HC2n-8 (rtol 1e-3)", 0.0046),
                    rec("ancf", "HB2n-20xyp", 0.0027), rec("ancf", "HB2n-12", 0.032),
                    rec("exudyn", "ANCFCable2D", 0.00464), rec("exudyn", "ANCFCable2D-linear", 0.00464)])
    assert pr.floors_by_section(fl) == (
        "The floors by section model: our cable HC2n-8 0.450 % (a centre line, Euler-Bernoulli, the law's exact "
        "uniaxial energy), against 0.270 % (HB2n-20xyp) to 3.200 % (HB2n-12) for our shear-deformable elements (a "
        "section field: shear and the section's thickness change), and 0.464 % for Exudyn's linear elastic cable.")
    assert pr.floors_by_section({k: v for k, v in fl.items() if k[1] != "HC2n-8"}) == ""


def test_work_precision_floors_are_read_at_fine_steps_and_the_rules_are_stated():
    from studies.peers import precision_report as pr

    def rec(n, dt, e, guard="none", runs=None):
        return {"solver": "exudyn", "element": "ANCFCable2D", "elements": n, "dt": dt, "rho_inf": 0.5,
                "status": "converged", "time_s": 0.01, "error": e, "energy_guard": guard, "time_runs_s": runs}
    # 16 x 2.5 ms cancels to 0.039 %; the finest mesh at its finest step says 0.09 %
    recs = [rec(16, 2.5e-3, 0.00039), rec(16, 1.25e-3, 0.0008), rec(32, 2.5e-3, 0.0007),
            rec(32, 1.25e-3, 0.0009, runs=[0.01, 0.012, 0.011, 0.01, 0.013])]
    f = pr.floors(recs)[("exudyn", "ANCFCable2D")]
    assert (f["elements"], f["dt"], f["error"]) == (32, 1.25e-3, 0.0009)
    ours = {**rec(32, 1.25e-3, 0.001, runs=[0.02] * 5), "solver": "ancf", "element": "HB2n-12"}
    text = pr.report_markdown(recs + [ours])
    assert "| exudyn | ANCFCable2D | 32 | 1.25 | 0.0900 |" in text
    assert "Energy guard: none on either side" in text
    assert "| exudyn | ANCFCable2D | 32 | 1.25 | converged | 0.0100 | 0.0100-0.0130 | 0.0900 |" in text
    old = {**ours, "energy_guard": None}
    old.pop("energy_guard")
    assert "NOT the same on both sides" in pr.report_markdown(recs + [old])


def test_peers_report_is_generated_from_the_record():
    o16 = {**fake_ours(0.07), "element": "HB2n-16"}
    md = compare.peers_markdown({"ours": [fake_ours(0.04), o16], "exudyn": fake_peer(),
                                 "load": [(1.0, 1.0, 1.0), (2.0, 1.0, 1.0)], "rounds": 1})
    assert "| 0.0400-0.0400 | 0.0400 | 0.0400-0.0400 | 0.40, 0.40 | 0.40 (0.40) | 0.5: met |" in md
    assert "| 0.70, 0.70 | 0.70 (0.70) | 0.8: met |" in md
    assert "load average (1 min) 1.00 before, 2.00 after" in md
    assert "| HB2n-12 | 0.10 | 1.00 | -2.00 | 2.24 |" in md


def test_the_verdict_takes_each_rounds_ratio_when_the_machine_changes_speed():
    """Two rounds, the machine twice as fast in the second: our runs 0.05 s then 0.025 s.
    If Exudyn's switch falls inside its second round (0.1 s, then two of five at 0.05 s),
    the pooled medians say 0.375 and the rounds 0.5 and 0.25 (the second round mixes
    phases); with its runs 0.1 s then 0.05 s, the rounds say 0.5 and 0.5, the ratio in
    each phase."""
    ours = [0.05] * 5 + [0.025] * 5
    peer = [0.1] * 5 + [0.1, 0.1, 0.1, 0.05, 0.05]
    assert statistics.median(ours) / statistics.median(peer) == pytest.approx(0.375)
    assert compare.round_ratios(ours, peer, 2) == pytest.approx([0.5, 0.25])   # the second round mixes phases
    even = [0.1] * 5 + [0.05] * 5
    assert compare.round_ratios(ours, even, 2) == pytest.approx([0.5, 0.5])
    o = {**fake_ours(), "cpu_s": ours, "wall_s": ours, "cpu_median_s": statistics.median(ours),
         "wall_median_s": statistics.median(ours)}
    p = {**fake_peer(), "solve_cpu_s": even, "solve_s": even, "solve_cpu_median_s": statistics.median(even),
         "solve_median_s": statistics.median(even)}
    md = compare.peers_markdown({"ours": [o], "exudyn": p, "load": [(1.0,) * 3] * 2, "rounds": 2})
    assert "| 0.50 (0.50, 0.50) | 0.5: met |" in md
    with pytest.raises(ValueError, match="rounds"):
        compare.round_ratios(ours, peer[:9], 2)


@pytest.mark.slow(guard="test_audit.py::test_a_tampered_report_is_named_by_file_and_line")
def test_the_peer_reports_are_audited_against_their_records(tmp_path):
    """The audit's peer rule redraws peers.md and peers_work_precision.md from their
    records (their own plain functions) and names a tampered line."""
    import shutil

    from studies.engine.audit import AuditResult
    from studies.peers.audit import PEER_REPORTS, audit_peers

    reports = Path(__file__).resolve().parents[1] / "reports"
    copy = tmp_path / "reports"
    (copy / "data" / "peers").mkdir(parents=True)
    for name, (record, _) in PEER_REPORTS.items():
        shutil.copy(reports / name, copy / name)
        shutil.copy(reports / "data" / "peers" / record, copy / "data" / "peers" / record)
    rounds = reports / "data" / "peers" / "peers-work-precision-rounds.jsonl"    # the rounds column's records
    shutil.copy(rounds, copy / "data" / "peers" / rounds.name)
    published = reports / "data" / "peers" / "peers-published.json"     # peers.md's published-checks section
    shutil.copy(published, copy / "data" / "peers" / published.name)
    costs = reports / "data" / "peers" / "peers-step-cost.json"       # the missed targets' measurements
    if costs.exists():
        shutil.copy(costs, copy / "data" / "peers" / costs.name)
    figures = sorted(p.name for p in reports.glob("peers_work_precision*.figure.csv"))
    for name in figures:
        shutil.copy(reports / name, copy / name)
    res = AuditResult()
    covered = audit_peers(copy, res)
    assert res.ok, "\n".join(res.problems)
    assert sorted(res.checked) == sorted([*PEER_REPORTS, *figures]) and len(figures) == 4   # 2 scenes: lead, all
    assert {n[:-len(".figure.csv")] + ".png" for n in figures} <= covered
    wp = copy / "peers_work_precision.md"
    lines = wp.read_text().splitlines(keepends=True)
    i = next(i for i, ln in enumerate(lines) if ln.startswith("| 1 % |"))
    lines[i] = lines[i].replace(" | 0.", " | 9.", 1)
    wp.write_text("".join(lines))
    (copy / "data" / "peers" / PEER_REPORTS["peers.md"][0]).unlink()
    fig = copy / figures[0]
    rows = fig.read_text().splitlines(keepends=True)
    rows[1] = rows[1].replace(",True,", ",False,")       # a filled point drawn hollow
    fig.write_text("".join(rows))
    res = AuditResult()
    audit_peers(copy, res)
    assert [p.split(": ")[0] for p in res.problems] == [f"{copy / 'peers.md'}:1", f"{wp}:{i + 1}", f"{fig}:2"]


def test_work_precision_anatomy_splits_the_time_and_judges_the_target_by_the_deciding_ratio():
    """time = steps x iterations per step x time per iteration for each row's two runs; the
    target (ours <= 0.5 of the cable's time, at 1 %, 0.3 % and 0.1 %) is judged by the rounds'
    median where the pair was re-timed, else by the grid's medians; the coarsest step's error
    is read on each side's finest mesh with a result there."""
    from studies.peers import anatomy
    from studies.peers import precision_report as pr

    def rec(solver, n, dt, e, t, its):
        return {"scene": "pendulum", "solver": solver, "element": "ANCFCable2D" if solver == "exudyn" else "HB2n-16",
                "elements": n, "dt": dt, "rho_inf": 0.5, "status": "converged" if t else "failed", "time_s": t,
                "time_runs_s": [t] if t else None, "error": e, "newton_iterations": its}
    ours, cable = rec("ancf", 8, 5e-3, 0.0005, 0.012, 300), rec("exudyn", 4, 1e-2, 0.0005, 0.02, 450)
    f = anatomy.factors(ours)
    assert (f["steps"], f["iterations"], f["per_step"]) == (100, 300, 3.0)
    assert f["per_iteration_s"] == pytest.approx(4e-5) and f["per_step_s"] == pytest.approx(1.2e-4)
    failed = {**rec("exudyn", 8, 1e-2, None, None, None), "element": "ANCFCable2D-linear"}   # not the 4-cable's setting
    recs = [ours, cable, failed, rec("ancf", 8, 1e-2, 0.014, 0.006, 200)]
    text = pr.report_markdown(recs)
    assert "| 1 % | ours: HB2n-16 x 8, dt 5 ms | 100 | 300 | 3.00 | 40.0 | 120 | not met (0.600 > 0.5), by the grid's " \
           "medians |" in text
    assert "| | cable: cable x 4, dt 10 ms | 50 | 450 | 9.00 | 44.4 | 400 | |" in text
    assert "| 0.3 % | ours: HB2n-16 x 8, dt 5 ms | 100 | 300 | 3.00 | 40.0 | 120 | not met (0.600 > 0.5), by the " \
           "grid's medians |" in text
    assert anatomy.verdict(0.002, 0.6, ours, cable) == "-"                       # no target there
    assert "ours 1.40 % (8 elements); the cable's 0.05 % (4 elements)." in text     # the failed 8 x 10 ms is passed by
    rounds = [{"scene": "pendulum", "accuracy": 0.001, **rules.round_pair(ours, cable), "repeats": 5,
               "rounds": [{"exudyn_s": 0.02, "ours_s": 0.008}, {"exudyn_s": 0.02, "ours_s": 0.012},
                          {"exudyn_s": 0.02, "ours_s": 0.009}]}]
    assert "| 0.1 % | ours: HB2n-16 x 8, dt 5 ms | 100 | 300 | 3.00 | 40.0 | 120 | met (0.450 <= 0.5), by the rounds' " \
           "median |" in pr.report_markdown(recs, rounds)
    assert anatomy.verdict(0.001, None, None, cable) == "not met: no run of ours reaches it"
    assert anatomy.verdict(0.001, None, None, None) == "not met: no run of ours reaches it, nor of the cable"
    assert anatomy.verdict(0.01, None, ours, None) == "no run of the cable reaches it"


def test_work_precision_asks_whether_an_element_could_meet_a_missed_target():
    """Where the target is missed, half the cable's time is set against our cheapest run at
    each step at any error: no run within it -> no element as cheap per step meets it;
    runs within it only at a step whose own error (finest mesh) is above the accuracy ->
    only by cancellation; a step that allows the accuracy -> an element's question."""
    from studies.peers import anatomy

    def rec(solver, element, n, dt, e, t):
        return {"scene": "pendulum", "solver": solver, "element": element, "elements": n, "dt": dt,
                "rho_inf": 0.5, "status": "converged", "time_s": t, "time_runs_s": [t], "error": e,
                "newton_iterations": 100}
    cable = rec("exudyn", "ANCFCable2D", 4, 1e-2, 0.008, 0.004)
    coarse = [rec("ancf", "HB2n-12", 2, 1e-2, 0.2, 0.003), rec("ancf", "HB2n-12", 2, 5e-3, 0.2, 0.005),
              rec("ancf", "HB2n-16", 16, 1e-2, 0.014, 0.02), rec("ancf", "HB2n-16", 16, 5e-3, 0.002, 0.03)]
    best = coarse[3]                                    # ours at 1 %: 7.5 x the cable's time
    rows = [(0.01, best, cable, best["time_s"] / cable["time_s"], "grid")]
    (text,) = anatomy.reach_lines(coarse + [cable], rows)
    assert "0.5 of the cable's time is 2.00 ms (its grid median 4.00 ms)" in text
    assert "10 ms HB2n-12 x 2 3.0 ms (20.0 %), 5 ms HB2n-12 x 2 5.0 ms (20.0 %)" in text
    assert "None is within it (the cheapest, 0.75 of the cable's time)" in text
    cheap = [dict(r, time_s=r["time_s"] / 2) for r in coarse]      # 10 ms runs within it, 1.4 % step error there
    (text,) = anatomy.reach_lines(cheap + [cable], rows)
    assert "Only the runs at 10 ms are within it, and there our finest meshes are off by 1.40 %" in text
    assert "only through a mesh error that cancels the step's" in text
    fine = cheap + [rec("ancf", "HB2n-16", 32, 1e-2, 0.005, 0.05),  # the finest mesh at 10 ms: 0.5 % < 1 %
                    rec("ancf", "HB2n-60p", 2, 1e-2, 0.012, 0.03), rec("ancf", "HB2n-60p", 2, 5e-3, 0.007, 0.05)]
    cable2 = rec("exudyn", "ANCFCable2D", 2, 1e-2, 0.05, 0.002)
    (text,) = anatomy.reach_lines(fine + [cable, cable2], rows)
    assert ("Runs at 10 ms are within it, and at 10 ms the step allows 1 %: an element that reaches it there on 2 "
            "elements or fewer (the most within the time) would meet the target.") in text
    # how close anything comes on 2 elements at 10 ms, at any cost (not the 5 ms run, not the 4-element cable)
    assert ("On 2 elements or fewer at that step, the smallest error of any run, at any cost: ours 1.20 % "
            "(HB2n-60p x 2, 10 ms, 30.0 ms); the cable's 5.00 % (2 elements, 10 ms, 2.0 ms).") in text
    graze = [(0.01, fine[0], cable, 0.6, "rounds")]          # within the time by the grid, not by the rounds
    (text,) = anatomy.reach_lines(fine + [cable, cable2], graze)
    assert text.endswith("Our cheapest 1 % run is within it by the grid's medians (1.5 ms); the verdict above is the "
                         "rounds'.")
    met = [(0.01, best, cable, 0.4, "rounds"), (0.003, best, cable, 0.5, "grid"), (0.002, best, cable, 7.5, "grid"),
           (0.001, None, None, None, None)]
    assert anatomy.reach_lines(coarse + [cable], met) == []       # met, met at 0.5, no target at 0.2 %, no cable time


def test_a_run_whose_tip_leaves_the_pendulum_is_diverged_whatever_its_solver_says():
    """Exudyn's linear-solve runs on fine meshes at 10 ms report success with tips 1e10 L
    from the pin: such a run is scored "diverged", with no error, and counts for nothing."""
    from studies.peers import precision_report as pr, work_precision as wp
    from studies.common.pendulum_cases import LENGTH

    def rec(tips):
        return {"scene": "pendulum", "solver": "exudyn", "element": "ANCFCable2D-linear", "elements": 64,
                "dt": 1e-2, "rho_inf": 0.5, "status": "converged", "time_s": 0.001, "time_runs_s": [0.001],
                "tip_history": [{"t": 0.1 * k, "x": x, "y": y} for k, (x, y) in enumerate(tips, 1)]}
    sane = [(0.9 * LENGTH, -0.3 * LENGTH)] * 5
    assert wp.left([{"x": x, "y": y} for x, y in sane]) is None
    ok = wp.score(rec(sane))
    assert ok["status"] == "converged" and ok["error"] is not None and ok["error"] < 2
    for bad in ((1e9, 2e12), (float("nan"), 0.0), (2.1 * LENGTH, 0.0)):
        r = wp.score(rec(sane[:4] + [bad]))
        assert r["status"] == "diverged" and r["error"] is None and "from the pin" in r["reason"]
        assert rules.cheapest([r], "exudyn", None, 1.0) is None
    assert wp.score(rec(sane[:4] + [(1.9 * LENGTH, 0.0)]))["status"] == "converged"     # far off, but in reach


# -- Exudyn against its own published numbers (studies.peers.exudyn_published) --------------
def fake_published_peer(shift=0.0, fail=()):
    """The peer's output as if it gave every published value exactly, ``shift`` (m) added to
    each 'ux'; the runs named in ``fail`` failed."""
    from studies.peers import exudyn_published as ep

    runs = {}
    for c in ep.cases():
        if c["name"] in fail:
            runs[c["name"]] = {"status": "failed", "reason": "SolverError: SolveStatic terminated due to errors"}
            continue
        r = {"status": "converged", "newtonSteps": 6, "newtonJacobians": 6, "residual_N": 1e-3,
             "linearSolver": "LinearSolverType.EigenSparse", "relativeTolerance": c["static"]["relative_tolerance"],
             "absoluteTolerance": c["static"]["absolute_tolerance"], "numberOfLoadSteps": 1, "adaptiveStep": True}
        for k in c["checks"]:
            r[k["quantity"]] = k["published"] + (shift if k["quantity"] == "ux" else 0.0)
        runs[c["name"]] = r
    return {"status": "converged", "exudyn": "9.9", "numpy": "9.9", "module": "exudynCPPfast", "python": "3.11",
            "runs": runs}


def test_published_tolerances_are_derived_from_the_published_material():
    """The rows' 1e-9 m is three times the largest distance between two published runs of
    one mesh (3.4e-10 m, 4 elements, x: the file's two tables); the converged check adds the
    256 mesh's distance from the limit and half a 12th decimal; the mini example takes
    Exudyn's test-suite tolerance."""
    from studies.peers import exudyn_published as ep

    assert ep.rerun_spread() == pytest.approx(3.369e-10, rel=1e-3)
    assert ep.ROW_TOL == 1e-9 == pytest.approx(3 * ep.rerun_spread(), rel=0.02)
    assert ep.converged_tolerance() == pytest.approx(1e-9 + 7.48e-11 / 15 + 0.5e-12, rel=1e-3)
    assert ep.MINI_TOL == 3e-11
    cases = {c["name"]: c for c in ep.cases()}
    assert sorted(c["model"]["elements"] for n, c in cases.items() if n.startswith("cantilever-")
                  and not n.endswith("tight")) == [1, 2, 4, 8, 16, 32, 64, 128, 256]
    m = cases["cantilever-64"]["model"]
    assert m["EI"] == pytest.approx(2.07e11 * 0.1 ** 4 / 12) and m["tip_force"][1] == pytest.approx(-3 * m["EI"] / 4)
    assert m["support"] == "clamp" and m["gravity"] is None and cases["mini-cable2d"]["model"]["gravity"] == [0, -9.81]
    # every check names its source and says why its tolerance
    for c in cases.values():
        assert c["source"]["files"] and all(k["why"] and k["tolerance"] > 0 for k in c["checks"])


def test_published_checks_fail_beyond_their_tolerance_and_on_a_failed_run():
    from studies.peers import exudyn_published as ep

    ok = ep.evaluate(fake_published_peer())
    assert ok and all(k["agrees"] for k in ok) and len(ok) == 25
    off = ep.evaluate(fake_published_peer(shift=2e-9))         # every ux 2e-9 m off: the rows' 1e-9 m is exceeded
    bad = {(k["check"], k["quantity"]) for k in off if not k["agrees"]}
    assert ("table, 64 elements", "ux") in bad and ("mini example", "ux") in bad
    assert all(k["agrees"] for k in off if k["quantity"] != "ux")
    failed = ep.evaluate(fake_published_peer(fail=("cantilever-8",)))
    assert [(k["check"], k["peer"], k["agrees"]) for k in failed if k["run"] == "cantilever-8"] == [
        ("table, 8 elements", None, False)] * 2
    md = ep.published_markdown(ep.record(fake_published_peer(fail=("cantilever-8",))))
    assert "23 of 25 checks agree within their tolerance." in md
    assert "| table, 8 elements | ux | -0.5085092365729895 | failed | - | 1e-09 | DIFFERS |" in md
    assert "| cantilever-8 | 8 | failed: SolverError: SolveStatic terminated due to errors | | | | |" in md
    assert "main/pythonDev/Examples/ANCFcantileverTest.py:135-148" in md and "not in the installed wheel" in md


def test_peers_report_carries_the_published_section_from_its_record():
    from studies.peers import exudyn_published as ep

    rec = ep.record(fake_published_peer())
    base = {"ours": [fake_ours(0.04)], "exudyn": fake_peer(), "load": [(1.0,) * 3] * 2, "rounds": 1}
    md = compare.peers_markdown(base, rec)
    assert md.startswith(compare.peers_markdown(base).rstrip("\n"))
    assert "## Exudyn against its own published numbers" in md
    assert "| mini example | ux | -0.5013058140308901 | -0.5013058140308901 | 0.00e+00 | 3e-11 | agrees |" in md


def test_our_exudyn_set_up_gives_exudyns_published_numbers():
    """Runs Exudyn (in .venv-peers, the pinned version) on every published case, built by the
    pendulum's own set-up, and compares each value with its tolerance."""
    import re

    from studies.peers import exudyn_published as ep

    if not compare.PEER_PYTHON.exists():
        pytest.skip(f"SKIPPED, not run: {compare.PEER_PYTHON} does not exist (`bash tools/setup_peers.sh` makes it); "
                    "the checks against Exudyn's published numbers need Exudyn")
    peer = ep.run_peer()
    pinned = re.search(r"^EXUDYN_VERSION=(\S+)", (compare.ROOT / "tools" / "setup_peers.sh").read_text(), re.M)[1]
    assert peer["exudyn"] == pinned, f"the peer venv has exudyn {peer['exudyn']}, the pin is {pinned}: rerun setup_peers"
    rows = ep.evaluate(peer)
    bad = [f"{k['check']} {k['quantity']}: Exudyn {k['peer']!r}, published {k['published']!r}, "
           f"difference {k['difference']}, tolerance {k['tolerance']:g}" for k in rows if not k["agrees"]]
    assert not bad, "\n".join(bad)
    assert len(rows) == 25


def test_a_missed_target_is_measured_by_mode_and_by_the_parts_of_a_step(monkeypatch):
    """Where the rounds miss a row's target, our deciding run is timed under each Newton a
    scene offers beside the cable's run, and its step split into parts; the report draws
    the rounds' medians and, where the run takes one iteration per step, the estimate with
    the verifying residual taken off; a met row is not measured, and a record of another
    pair is not drawn."""
    from types import SimpleNamespace
    from studies.peers import precision_report as pr, step_cost as sc, work_precision as wp

    def rec(solver, element, n, dt, e, t):
        return {"scene": "pendulum", "solver": solver, "element": element, "elements": n, "dt": dt, "rho_inf": 0.5,
                "status": "converged", "time_s": t, "time_runs_s": [t], "error": e, "newton_iterations": 100}
    ours, cable = rec("ancf", "HC2n-8 (rtol 1e-3)", 4, 5e-3, 0.0005, 0.0010), rec("exudyn", "ANCFCable2D-linear", 4,
                                                                                   5e-3, 0.0005, 0.0018)
    recs = [ours, cable]
    times = {"chord, rtol 1e-3": 0.0010, "full, rtol 1e-3": 0.0012, "modified, rtol 1e-3": 0.0017,
             "chord, default rtol": 0.0017, "linear": 0.0011}
    monkeypatch.setattr(sc, "exudyn", lambda *args: {"time_s": 0.0018})
    monkeypatch.setattr(sc, "run_mode", lambda el, n, dt, rho, rep, scene, st: {
        "status": "converged", "time_s": times[next(k for k, v in sc.MODES.items() if v == st)],
        "newton_iterations": 100 if st.get("newton_rtol") else 361, "steps": 100})
    monkeypatch.setattr(sc, "split", lambda *args, **kw: {
        "seconds_per_call": {"step": 8e-6, "force_and_tangent": 4e-6, "factorise_and_solve": 0.8e-6,
                             "verifying_residual": 2.5e-6}, "calls": 100, "repeats": 2, "ndof": 20,
        "run": {"steps": 100, "newton_iterations": 100, "wall_s": 0.001}})
    a = SimpleNamespace(rounds=3, repeats=5, rho_inf=0.5, peer_python=None, calls=100)
    costs = sc.measure(recs, [], "pendulum", a)        # 1 %, 0.3 %, 0.1 %: 0.556 > 0.5 at each
    assert [c["accuracy"] for c in costs] == [0.01, 0.003, 0.001]
    c = costs[0]
    assert c["ours"]["settings"] == {"newton_rtol": 1e-3} and len(c["rounds"]) == 3
    assert scr.mode_ratios(c)["chord, rtol 1e-3"] == pytest.approx(0.0010 / 0.0018)
    assert scr.linear_estimate(c) == pytest.approx((0.0010 - 100 * 2.5e-6) / 0.0018)
    text = pr.report_markdown(recs, [], costs[:1])
    assert "| chord, rtol 1e-3 | 0.556 | 100 | 100 |" in text and "| modified, rtol 1e-3 | 0.944 | 100 | 100 |" in text
    assert "the rounds' median would be 0.417 (<= 0.5; an estimate from the timed parts, not a run)" in text
    assert "Why the 1 % target is missed" in text and "Why the 0.1 % target" not in text
    faster = [dict(ours, time_s=0.0008), cable]               # met by the grid's ratio: nothing measured
    assert sc.measure(faster, [], "pendulum", a) == []
    other = [rec("ancf", "HC2n-8 (rtol 1e-3)", 8, 5e-3, 0.0005, 0.0012), cable]
    assert "Why the 1 % target" not in pr.report_markdown(other, [], costs[:1])      # drawn for its own pair only
    two = dict(c, split={**c["split"], "run": {**c["split"]["run"], "newton_iterations": 142}})
    assert scr.linear_estimate(two) is None                    # not one iteration per step: no estimate
    # the linear mode's run within the target in time: said not to count where the grid's run of
    # it in that mode is refused by the two-way rule (a finer mesh at its step failed), with why
    lin = [rec("ancf", "HC2n-8 (linear)", n, 5e-3, 0.0005, 0.0008) for n in (4, 8, 16, 32)]
    lin.append(dict(rec("ancf", "HC2n-8 (linear)", 64, 5e-3, None, None), status="failed",
                    reason="step below dt_min: det F <= 0"))
    said = "\n".join(scr.lines(costs[:1], recs + lin))
    assert "The linear mode's run meets the target in time (0.611)" not in said     # 0.0011 / 0.0018 > 0.5
    cheap = dict(c, rounds=[{**r, "modes": {**r["modes"], "linear": {**r["modes"]["linear"], "time_s": 0.0008}}}
                            for r in c["rounds"]])
    said = "\n".join(scr.lines([cheap], recs + lin))
    assert "does not count at 1 %" in said and "64 elements at 5 ms failed (step below dt_min: det F <= 0)" in said
    assert "does not count" not in "\n".join(scr.lines([cheap], recs + lin[:-1]))     # every finer run reaches it


def test_one_place_builds_exudyn_models():
    """One way to run Exudyn: its nodes, objects, markers, loads and sensors are added in
    ``studies/peers/exudyn_model.py`` alone; the adapter (``exudyn_scene.py``), the peer
    benchmark's timed runs (``exudyn_pendulum.py``) and the published checks call it, and
    the timed runs take the scene our solver runs, with the declaration's element."""
    import re

    from contract.errors import SceneError

    peers = compare.ROOT / "studies" / "peers"
    adds = re.compile(r"\.Add(Node|Object|Marker|Load|Sensor)\(|itemInterface")
    builders = sorted(p.name for p in peers.glob("*.py") if adds.search(p.read_text()))
    assert builders == ["exudyn_model.py"]
    for script in ("exudyn_scene.py", "exudyn_pendulum.py", "exudyn_static.py"):
        assert "exudyn_model" in (peers / script).read_text(), script
    d = compare.pendulum_scene(2e-3, 0.8)
    p = compare.peer_scene(d)
    assert p["ancf"]["element"] == "ObjectANCFCable2D" and {**p, "ancf": d["ancf"]} == d
    with pytest.raises(SceneError, match="exudyn: .*loads 'end_moment'"):
        compare.peer_scene({**d, "loads": {**d["loads"], "end_moment": 1e-3}})


def test_the_timed_runs_and_the_adapter_run_the_same_model():
    """The pendulum as the peer benchmark times it (``exudyn_pendulum.py``, two warm runs)
    and as the external-solver adapter runs it (``exudyn_scene.py``, one run through the
    protocol) from the same scene: the same tip at every output time, to the last bit."""
    from studies.engine.solvers import SOLVERS
    from studies.engine.worker import execute
    from studies.engine.case import make_case
    from studies.external.protocol import register_external

    if not compare.PEER_PYTHON.exists():
        pytest.skip(f"SKIPPED, not run: {compare.PEER_PYTHON} does not exist (`bash tools/setup_peers.sh` makes it); "
                    "the two routes to Exudyn need Exudyn")
    d = compare.pendulum_scene(5e-3, 0.8)
    d["ancf"]["elements"] = 8
    timed = compare.peer(d, repeats=1)
    solver = register_external(compare.DECLARATION)
    try:
        rec = execute(make_case("peers-one-way", solver.name, compare.peer_scene(d)))
    finally:
        del SOLVERS[solver.name]
    assert rec["status"] == "converged", rec["reason"]
    by_t = {h["t"]: (h["x"], h["y"]) for h in rec["tip_history"]}
    assert [(h["t"], (h["x"], h["y"])) for h in timed["tip_history"]] == [(t, by_t[t]) for t in (0.1, 0.2, 0.3, 0.4, 0.5)]
