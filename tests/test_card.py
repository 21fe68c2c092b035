"""The element report card, tiny grid, for a user's element registered from its own
module: the command runs the module in every worker, and the card states the checks'
verdicts and the runs' numbers from records."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SECTIONS = ["## 1. Contract checks", "## 2. Rank tests", "## 3. Conformity", "## 4. Static convergence",
            "## 5. Locking", "## 6. Pendulum", "## 7. Cost", "## 8. Stability"]


def _tree(folder: Path) -> dict:
    return {p: (p.stat().st_size, p.stat().st_mtime_ns) for p in folder.rglob("*") if p.is_file()}


@pytest.mark.slow(guard="test_a_committed_card_renders_again_from_its_records")
def test_a_user_elements_card_regenerates_from_its_records(tmp_path):
    reports = _tree(ROOT / "reports")
    cmd = [sys.executable, "-m", "studies", "card", "HB2n-20", "--import", "examples.transversely_cubic",
           "--tiny", "--out", str(tmp_path), "--no-progress", "--workers", "2"]
    run = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-3000:]
    card = (tmp_path / "cards" / "HB2n-20.md").read_text()
    for s in SECTIONS:
        assert s in card
    # the transversely cubic element conforms (its trace on x = const is its node's alone)
    # and passes every check; all its static runs converge to stable equilibria
    assert "Consistency checks: all pass; patch test: passes; conforming: True" in card
    recs = [json.loads(line) for line in (tmp_path / "data" / "card-HB2n-20.jsonl").read_text().splitlines()]
    assert recs and all(r["status"] == "converged" for r in recs)
    assert all(r["case"]["options"]["imports"] == ["examples.transversely_cubic"] for r in recs)
    static = [r for r in recs if r["scene"]["analysis"]["kind"] == "static"]
    assert f"stable: {len(static)}, unstable: 0" in card
    assert (tmp_path / "cards" / "HB2n-20-rank.png").exists() and (tmp_path / "cards" / "HB2n-20-cost.png").exists()
    # a second run reuses every record and renders the same card
    again = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0 and f"{len(recs)} reused, 0 computed" in again.stdout
    assert (tmp_path / "cards" / "HB2n-20.md").read_text() == card
    assert "### Shear locking" in card and "No shear locking" in card
    assert _tree(ROOT / "reports") == reports        # written with --out: reports/ untouched
    # records whose cases have changed since (another solver version: other case ids): the
    # audit's route refuses the card, the re-rendering after another card's runs passes it by
    from studies.design.card import recorded_cards
    data = tmp_path / "data" / "card-HB2n-20.jsonl"
    data.write_text("".join(json.dumps({**r, "case_id": "old-" + r["case_id"]}) + "\n" for r in recs))
    with pytest.raises(LookupError, match="card HB2n-20: no runs of it"):
        recorded_cards(tmp_path)
    stale = []
    assert recorded_cards(tmp_path, stale) == [] and stale == ["HB2n-20"]


def test_a_cards_cases_are_what_they_run_whatever_else_is_imported():
    """A built-in element's cases name no module (its records are reused whatever a
    command imports beside it); a user's element's name the module that registers it."""
    import importlib

    from studies.design.card import cases
    before = [c.id for c in cases("HB2n-12", tiny=True)]
    importlib.import_module("examples.transversely_cubic")
    importlib.import_module("examples.cubic_slope")
    after = cases("HB2n-12", tiny=True)
    assert [c.id for c in after] == before and not any("imports" in c.options for c in after)
    assert all(c.options["imports"] == ["examples.transversely_cubic"] for c in cases("HB2n-20", tiny=True))


def test_an_unknown_element_is_refused_with_the_list(tmp_path):
    run = subprocess.run([sys.executable, "-m", "studies", "card", "HB9n-99", "--tiny", "--out", str(tmp_path)],
                         cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert run.returncode == 2 and "HB2n-12" in run.stderr


def _probe(element: str, ratio: float, n: int) -> dict:
    from ancf.simulation import run_scene
    from contract.scene import scene_from_dict
    from studies.design.card import slender_scene

    d = slender_scene(element, ratio, n)
    rec, _ = run_scene(scene_from_dict(d))
    rec["case"] = {"name": d["name"]}
    return rec


def test_the_shear_locking_verdict_and_its_signature():
    """The card's verdict (error growth with L/h at fixed n) against a second route: a
    locking element's error is a function of l_e / h alone (equal at equal l_e / h), a
    locking-free one's of n alone; LB2n-12's error does not fall under refinement."""
    from studies.design.card_locking import shear_locking

    hb12 = [_probe("HB2n-12", r, n) for r, n in ((35, 8), (140, 8), (70, 16), (140, 32))]
    v = shear_locking(hb12)
    assert v["locks"]
    e = v["rows"]
    assert abs(e[16][70] - e[32][140]) < 0.01 * abs(e[32][140]) and abs(e[32][140]) > 0.05   # l_e/h = 0.3125
    hb16 = [_probe("HB2n-16", r, n) for r, n in ((35, 8), (140, 8), (35, 16))]
    v = shear_locking(hb16)
    assert not v["locks"] and v["converges"]
    assert abs(v["rows"][8][35] - v["rows"][8][140]) < 0.02 * abs(v["rows"][8][35])
    lb = shear_locking([_probe("LB2n-12", 35, n) for n in (16, 32)])
    assert not lb["converges"] and abs(lb["rows"][32][35] + 0.25) < 0.005     # 1 - (1 - nu^2), nu = 1/2


def _penalty_sweep(element: str, n: int) -> list:
    from ancf.simulation import run_scene
    from contract import paper
    from contract.scene import scene_from_dict

    c10, sweep = paper.materials()["neo-hookean"]["C10"], []
    for k in (1e3, 1e4, 1e5, 1e6):
        s = paper.cantilever_scene("neo-hookean", "plane-strain", element, n, quadrature=None, penalty=k * c10,
                                   name=f"penalty-{element}-{n}-{k:g}")
        r, _ = run_scene(scene_from_dict(s))
        assert r["status"] == "converged"
        sweep.append((k, (r["tip"]["ux"], r["tip"]["uy"])))
    return sweep


def test_the_volumetric_locking_verdict_on_elements_that_lock_and_that_do_not():
    """The card's rule (:func:`volumetric_locking`) on real penalty sweeps, NH plane strain,
    k = 1e3 .. 1e6 C10, against the incompressible continuum: the pressure element HB2n-40p
    is lock-free (its change per decade falls tenfold, as u + c / k: ratios 0.1 within 5 %),
    LB2n-12 is locked solid (the case whose error saturates at 99 % and so does not grow),
    HB3n-12 keeps stiffening (its change grows with k). Second route: refinement. The
    lock-free limit converges to the continuum (error falls at least 3x from n = 8 to 16:
    an order above 1.5 for a cubic element), LB2n-12's does not move (within 1 %)."""
    from studies.common.gold import gold_references
    from studies.design.card_locking import volumetric_locking, volumetric_verdict
    from studies.design.card_report import FEM_STATIC

    ref = gold_references(FEM_STATIC)[("neo-hookean", "plane-strain")]
    free = {n: volumetric_locking(_penalty_sweep("HB2n-40p", n), ref) for n in (8, 16)}
    solid = {n: volumetric_locking(_penalty_sweep("LB2n-12", n), ref) for n in (8, 16)}
    stiffening = volumetric_locking(_penalty_sweep("HB3n-12", 16), ref)
    for v in free.values():
        assert not v["locked"] and all(abs(r - 0.1) < 0.005 for r in v["ratios"])
    assert free[16]["limit_error"] < free[8]["limit_error"] / 3
    for v in solid.values():
        assert v["saturated"] and not v["stiffening"] and v["locked"]
    assert abs(solid[16]["limit_error"] - solid[8]["limit_error"]) < 0.01
    assert stiffening["stiffening"] and stiffening["locked"] and stiffening["ratios"][-1] > 1
    assert volumetric_verdict({"NH": free[16]}).startswith("No volumetric locking")
    assert volumetric_verdict({"NH": solid[16]}).startswith("**Volumetric locking**")
    said = volumetric_verdict({"NH": stiffening, "MR": free[16]})
    assert said.startswith("**Volumetric locking**") and "keeps stiffening" in said and "MR: the change falls" in said


def test_strain_split_of_the_exact_bending_state():
    """ancf.checks.element.strain_split against closed form: pure bending of an incompressible
    plane-stress beam, u_x = -k x y, u_y = k x^2 / 2 + k y^2 / 4 (eps_xx = -k y,
    eps_yy = k y / 2, gamma = 0), set exactly in HB2n-16's nodal coordinates (its basis
    holds it): no shear energy and eps_yy / eps_xx = -1/2."""
    import numpy as np
    from ancf.checks.element import small_model, strain_split

    model = small_model("HB2n-16", "neo-hookean", "plane-stress", 3)
    m, k = model.mesh, 1e-4
    q = np.zeros((m.n_nodes, len(m.element.kinds), 2))
    x = np.linspace(0.0, m.length, m.n_nodes)
    kinds = m.element.kinds
    q[:, kinds.index("r")] = np.stack([0 * x, k * x ** 2 / 2], axis=1)
    q[:, kinds.index("r_x")] = np.stack([0 * x, k * x], axis=1)
    q[:, kinds.index("r_y")] = np.stack([-k * x, 0 * x], axis=1)
    q[:, kinds.index("r_yy")] = np.stack([0 * x, k / 2 + 0 * x], axis=1)
    s = strain_split(model, q.ravel())
    # the shape functions come from inverting the nodal-coordinate matrix: 2e-10 measured
    assert s["shear_share"] < 1e-20 and abs(s["eyy_exx"] + 0.5) < 1e-8


def test_the_probe_names_the_mechanism():
    """The slender probe's strains name what its error is (studies.design.card_locking.mechanism):
    LB2n-12's section cannot contract (eps_yy / eps_xx = 0: Poisson locking in the plane,
    its -25 %); HB2n-12 at L/h = 140 on 8 elements carries 600 times Timoshenko's shear
    energy and holds eps_zz near 0 (-0.91): shear locking and Poisson locking out of the
    plane, whose -25 % is why its error saturates at LB2n-12's level; HB2n-16 shows
    neither (measured)."""
    from ancf.checks.element import strain_split
    from ancf.simulation import run_scene
    from contract.scene import scene_from_dict
    from studies.design.card import slender_scene
    from studies.design.card_locking import mechanism

    def row(element, ratio, n):
        rec, (model, res) = run_scene(scene_from_dict(slender_scene(element, ratio, n)))
        return {**strain_split(model, res.u), "beam_shear_share": 1.2 / ratio ** 2 / (1 + 1.2 / ratio ** 2)}

    assert mechanism(row("LB2n-12", 140, 8)) == ["Poisson locking in the plane (the height cannot contract)"]
    assert mechanism(row("HB2n-12", 140, 8)) == ["shear locking", "Poisson locking out of the plane (eps_zz held at 0)"]
    assert mechanism(row("HB2n-16", 140, 8)) == []


def test_the_clamp_sets_hb2n16s_order():
    """HB2n-16's first order on the slender probe is its clamp's (r_yy = 0 at the clamped
    face), not its interior's: with r_yy freed the same meshes converge at second order
    (measured 1.01 and 2.00); the card says so by rule."""
    from studies.design.card import clamp_probe
    from studies.design.card_locking import _clamp_lines, clamp_orders

    probe = clamp_probe("HB2n-16", {"slender": {"slenderness": (140.0,), "counts": (8, 16, 32)}})
    o = clamp_orders(probe)
    assert abs(o["face"] - 1.0) < 0.1 and abs(o["freed"] - 2.0) < 0.1
    assert any(line.startswith("**The clamp sets the order**") for line in _clamp_lines(probe))
    assert clamp_probe("HB2n-12", {"slender": {"slenderness": (140.0,), "counts": (8, 16)}}) is None


def test_a_card_names_why_a_pendulum_run_has_no_result():
    """A failed run is a row with '-' and a line with its record's reason."""
    from studies.design.card_report import _pendulum
    from studies.common.pendulum_cases import pendulum_dict

    scene = pendulum_dict("HB2n-16", 8, "plane-stress", 5e-4)
    rec = {"scene": scene, "status": "failed", "reason": "step below dt_min at t = 0 s: det F <= 0",
           "tip_history": None, "wall_s": 0.01}
    lines = _pendulum([rec])
    assert "| 8 | 0.5 | failed | - | - | 0.01 |" in lines
    assert "- n = 8, dt = 0.5 ms: failed: step below dt_min at t = 0 s: det F <= 0" in lines


@pytest.mark.records
def test_a_committed_card_renders_again_from_its_records(tmp_path):
    """The quick guard of the card runs: HB2n-12's committed card rendered again from
    the committed records alone (no solver run) is the committed card, line for line."""
    import shutil

    from studies.design.card_report import render
    (tmp_path / "data").mkdir()
    for f in (ROOT / "reports" / "data").glob("card-*"):
        shutil.copy(f, tmp_path / "data" / f.name)
    card = render("HB2n-12", tmp_path)
    assert card.read_text() == (ROOT / "reports" / "cards" / "HB2n-12.md").read_text()


@pytest.mark.slow(guard="test_a_committed_card_renders_again_from_its_records")
def test_the_cables_tiny_card_runs_what_applies_and_says_why_for_the_rest(tmp_path):
    """The full tier's tiny card: HC2n-8 on the tiny grid (about 8 s). It runs what applies to a
    cable and no plane strain (its records: plane stress only), says why it skips the rest,
    and has its section model (1b: M(kappa) leaving EI kappa, the model error against the
    exact plane-stress bending) and its slenderness sweep (9) against the continuum gold;
    every check passes and every equilibrium is stable."""
    cmd = [sys.executable, "-m", "studies", "card", "HC2n-8", "--tiny", "--out", str(tmp_path), "--no-progress",
           "--workers", "1"]
    run = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-3000:]
    card = (tmp_path / "cards" / "HC2n-8.md").read_text()
    for s in SECTIONS + ["## 1b. The section model", "## 9. Slenderness"]:
        assert s in card, s
    assert "Consistency checks: all pass; patch test: passes; conforming: True" in card
    assert "The `paper` and `plane-strain` rows are not run" in card and "Volumetric locking: not run" in card
    assert "| NH | 0.1 | 1.000333 |" in card and "+0.2250 |" in card           # 1 + (kappa h)^2 / 30; 0.225
    recs = [json.loads(line) for line in (tmp_path / "data" / "card-HC2n-8.jsonl").read_text().splitlines()]
    assert recs and all(r["status"] == "converged" for r in recs)
    assert {r["scene"]["material"]["formulation"] for r in recs} == {"plane-stress"}
    assert sum(r["case"]["name"].startswith("slenderness-") for r in recs) == 2
    static = [r for r in recs if r["scene"]["analysis"]["kind"] == "static"]
    assert f"stable: {len(static)}, unstable: 0" in card
    assert "| 32 | " in card.split("## 9.")[1] and "within 1 % down to L / h" in card


def test_card_all_is_every_registered_element_and_the_imported_modules_ones(tmp_path):
    """`studies card all` (the Makefile's CARDS) follows the registry: every built-in element
    and each element a --import module registers gets its card, with no list to extend
    (a dry run: nothing runs)."""
    from ancf.elements import ELEMENTS

    p = subprocess.run([sys.executable, "-m", "studies", "card", "all", "--import", "examples.cubic_slope",
                        "--tiny", "--out", str(tmp_path), "--dry-run"],
                       cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    carded = [line.split()[1].rstrip(":") for line in p.stdout.splitlines() if line.startswith("card ")]
    assert sorted(carded) == sorted([*ELEMENTS.builtin, "HB2n-20xy"]) and len(set(carded)) == len(carded)
