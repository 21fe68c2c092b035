"""Who is cheaper at equal accuracy: our pendulum and Exudyn's ANCF cable pendulum on one
work-precision diagram, timed side by side in one run (``make bench-peers``).

    .venv/bin/python -m studies peers work-precision [--scene pendulum|thick] [--counts 2 4 8 16 32 64]
        [--element HB2n-12 --element HB2n-16 --element HB2n-20xyp --element HB2n-20xypm --element HB2n-40p --element HB2n-60p
         --element HC2n-8] [--import MODULE] [--rho-inf 0.5] [--repeats 5]
        [--out reports]

Grid: the element counts (2 to 64: at 1 % a run is a few elements, and the cable holds 1 % with
2 or 4, so the grid starts there for both sides), and the step ladder dt = 0.1 s / k for
k = 10, 20, 40, 80, 160, 320 (10 ms halving to 0.3125 ms: every step lands on the output
times 0.1 ... 0.5 s, as Exudyn's fixed step must). The cable runs twice at each point, as
two "elements" (:data:`CABLE_SETTINGS`): ``ANCFCable2D``, modified Newton, and
``ANCFCable2D-linear``, one linear solve per step; its cheapest run at an accuracy is
taken over both. Ours runs three times (:data:`OUR_SETTINGS`): at its defaults, as
``<element> (rtol 1e-3)`` at the loosest Newton tolerance a scene accepts, and as
``<element> (linear)`` with one solve per step and no convergence test (the state's det F
still checked), as the cable's linear mode. Each (solver,
element, count, step) is one run: the median of
``--repeats`` warm runs (ours: ``wall_s`` of :func:`ancf.simulation.run_scene`, the solve
alone; Exudyn: ``SolveDynamic`` alone, see exudyn_pendulum.py), Exudyn's and ours in
turn for each point; the runs' times are kept for their spread. Neither side has an
energy guard (:data:`ENERGY_GUARD`): Exudyn's fixed-step run has none, so ours runs with
``energy_limit = inf``. Error: max over t = 0.1 ... 0.5 s of |r(t) - r_ref(t)| / L against
the converged continuum plane-stress pendulum (tests/gold/fem_pendulum.json), the
reference of the accuracy-cost diagram. Exudyn's cable is linear elastic (E = 6 C10) and
Euler-Bernoulli: its error has a floor set by its physics, not by its mesh or step; the
floors are read at the finest step of the finest mesh
(:func:`studies.peers.precision_report.floors`), not as the smallest error over the grid.

Scenes (:data:`SCENES`, ``--scene``): ``pendulum``, the paper's slender pendulum (h = 5 mm,
L / h = 70, small strains), and ``thick``, the same pendulum with h = 20 mm (L / h = 17.5),
where transverse shear and the cross-section's deformation matter and the cable's physics
differs from the continuum's; its reference is the DOLFINx plane-stress run of
:mod:`studies.peers.thick_reference` (reports/data/peers/thick-pendulum-reference.json).

Records go to ``<out>/data/peers/peers-work-precision.jsonl`` (one file, every record
keyed by its scene) as each point finishes (an interrupted run keeps them; a rerun skips
the points it has, ``--force`` redoes the chosen scene's);
after the grid, each accuracy's two cheapest points are timed again alternately in
``--rounds`` rounds (``peers-work-precision-rounds.jsonl``: a round's two medians share the
machine's phase, the grid's two points need not); where the rounds miss a row's target, :mod:`studies.peers.step_cost` measures why
(``peers-step-cost.json``: our run under each Newton a scene offers, and its step split into
its parts); the table
``<out>/peers_work_precision.md`` and the figures ``.png`` (two per scene: each element's front, and every run) are drawn from
those files alone by :mod:`studies.peers.precision_report` (``--report-only`` redraws
them; ``--rescore`` first recomputes every error from the records' tip histories against
the current references).
"""
from __future__ import annotations

import json
import math
import os
import statistics
import time
from pathlib import Path

from ancf.simulation import run_scene
from contract.scene import scene_from_dict

from ..common.pendulum_cases import LENGTH, continuum_pendulum, pendulum_dict, tip_errors
from . import thick_reference
from .compare import peer
from .precision_grid import ACCURACIES, CABLE_SETTINGS, ENERGY_GUARD, OUR_SETTINGS, SCENE, SCENES, our_element
from .precision_rules import cheapest, round_pair, round_ratios, rounds_of
from .records import points_path, read, rounds_path
from .thick_reference import pin_references

REACH = 2.0     # a pinned pendulum's tip stays within about L (1 + its stretch) of the pin: 2 L is out of it


def key(r: dict) -> tuple:
    return (r.get("scene", SCENE), r["solver"], r["element"], r["elements"], round(r["dt"], 12), r["rho_inf"])


def scene_dict(element: str, n: int, dt: float, rho_inf: float, scene: str = SCENE) -> dict:
    """Our run of a point: the scene's plane-stress Yeoh pendulum on n elements, without
    the energy guard (Exudyn's run has none: :data:`ENERGY_GUARD`); ``element`` is a label
    of :func:`our_element` (an element, and the settings its suffix names)."""
    name, settings = our_element(element)
    d = pendulum_dict(name, n, "plane-stress", dt, rho_inf=rho_inf)
    d["beam"]["height"] = SCENES[scene]["height"]
    d["analysis"]["energy_limit"] = "inf"
    d["analysis"].update(settings)
    return d


def ours(element: str, n: int, dt: float, rho_inf: float, repeats: int, scene: str = SCENE) -> dict:
    sc = scene_from_dict(scene_dict(element, n, dt, rho_inf, scene))
    recs = [run_scene(sc)[0] for _ in range(repeats + 1)][1:]     # one untimed warm-up
    last = recs[-1]
    ok = last["status"] == "converged"
    return {"status": last["status"], "reason": last.get("reason"), "energy_guard": ENERGY_GUARD,
            "time_s": statistics.median(r["wall_s"] for r in recs) if ok else None,
            "time_runs_s": [r["wall_s"] for r in recs] if ok else None,
            "cpu_s": statistics.median(r["cpu_s"] for r in recs) if ok else None,
            "ndof": last["ndof"], "newton_iterations": last.get("newton_iterations"),
            "tip_history": last.get("tip_history") if ok else None}


def exudyn(n: int, dt: float, rho_inf: float, repeats: int, python: Path, scene: str = SCENE,
           element: str = "ANCFCable2D") -> dict:
    """The cable's run of a point; ``element``, a key of :data:`CABLE_SETTINGS`, names its Newton."""
    try:
        p = peer(scene_dict(element, n, dt, rho_inf, scene), repeats, python, newton=CABLE_SETTINGS[element])
    except RuntimeError as e:
        return {"status": "failed", "reason": str(e).splitlines()[0][:300], "time_s": None, "cpu_s": None,
                "tip_history": None}
    return {"status": "converged", "reason": None, "energy_guard": ENERGY_GUARD, "time_s": p["solve_median_s"],
            "time_runs_s": p["solve_s"], "cpu_s": p["solve_cpu_median_s"],
            "ndof": p["counters"].get("ODE2_coordinates"), "newton_iterations": p["counters"]["newtonSteps"],
            "tip_history": p["tip_history"], "exudyn": p["settings"]["exudyn"]}


def reference(scene: str = SCENE) -> tuple[dict | None, float | None]:
    """The scene's continuum reference: ({t: (x, y)} or None, its largest error estimate / L
    or None)."""
    if scene == "thick":
        tips = thick_reference.reference()
        est = thick_reference.error_estimate()
    else:
        c = continuum_pendulum().get(("yeoh", "plane-stress"))
        tips, est = (c.tips, c.error_estimate) if c else (None, None)
    return tips, (est / LENGTH if est is not None else None)


def error(tips: list[dict] | None, scene: str = SCENE) -> float | None:
    """max over the output times after 0 of |r - r_ref| / L against the scene's continuum
    plane-stress Yeoh pendulum; None without tips or reference."""
    ref = reference(scene)[0]
    if not tips or ref is None:
        return None
    e = tip_errors({round(h["t"], 9): (h["x"], h["y"]) for h in tips}, ref)
    return max(e.values()) if e else None


def run(a) -> list[dict]:
    path = points_path(a.out)
    path.parent.mkdir(parents=True, exist_ok=True)
    if a.force and path.exists():                  # redo this scene's points, keep the others'
        keep = [r for r in read(path) if r.get("scene", SCENE) != a.scene]
        path.write_text("".join(json.dumps(r) + "\n" for r in keep))
    have = {key(r) for r in read(path)}
    for n in a.counts:
        for k in a.steps_per_output:
            dt = 0.1 / k
            todo = ([("exudyn", e) for e in CABLE_SETTINGS]
                    + [("ancf", e + x) for e in a.element for x in OUR_SETTINGS])
            for solver, element in todo:
                base = {"solver": solver, "scene": a.scene, "height": SCENES[a.scene]["height"], "element": element, "elements": n, "dt": dt,
                        "rho_inf": a.rho_inf,
                        "law": "yeoh", "formulation": "plane-stress" if solver == "ancf" else "linear cable"}
                if key(base) in have:
                    continue
                t0 = time.perf_counter()
                load0 = os.getloadavg()[0]
                res = (exudyn(n, dt, a.rho_inf, a.repeats, a.peer_python, a.scene, element) if solver == "exudyn"
                       else ours(element, n, dt, a.rho_inf, a.repeats, a.scene))
                rec = score({**base, **res, "repeats": a.repeats, "host_load": [load0, os.getloadavg()[0]]})
                with path.open("a") as f:
                    f.write(json.dumps(rec) + "\n")
                e = rec["error"]
                print(f"{solver:7s} {element:12s} x{n:3d} dt {dt * 1e3:7.4f} ms  {rec['status']:9s} "
                      f"time {rec['time_s'] or float('nan'):8.4f} s  error {100 * e if e is not None else float('nan'):8.4f} %"
                      f"  ({time.perf_counter() - t0:.1f} s)", flush=True)
    return read(path)


def retime(recs: list[dict], a, path: Path) -> list[dict]:
    """Each accuracy's two cheapest points of ``a.scene`` (ours and the cable's, from the
    grid's records) timed again alternately, ``a.rounds`` rounds of ``a.repeats`` runs
    each: the machine's speed drifts within a run, and a round's two medians share its
    phase where the grid's two points may not (measured 2026-11-26 at 0.1 %: 0.60 from the
    grid, rounds 0.53 / 0.33 / 0.53 / 0.33 / 0.32). Kept per (scene, accuracy) while its two
    points stay the cheapest; ``--force`` redoes them. Returns every scene's rounds."""
    rp = rounds_path(path)
    old = read(rp)
    mine = [r for r in recs if r.get("scene", SCENE) == a.scene]
    out = [r for r in old if r["scene"] != a.scene]
    for acc in ACCURACIES:
        o, p = cheapest(mine, "ancf", None, acc), cheapest(mine, "exudyn", None, acc)
        if not (o and p):
            continue
        have = rounds_of(old, a.scene, acc, o, p)
        if have is None or a.force:
            rounds = []
            for _ in range(a.rounds):
                pe = exudyn(p["elements"], p["dt"], a.rho_inf, a.repeats, a.peer_python, a.scene, p["element"])
                ou = ours(o["element"], o["elements"], o["dt"], a.rho_inf, a.repeats, a.scene)
                rounds.append({"exudyn_s": pe["time_s"], "ours_s": ou["time_s"]})
            have = {"scene": a.scene, "accuracy": acc, **round_pair(o, p), "repeats": a.repeats, "rounds": rounds,
                    "host_load": os.getloadavg()[0]}
            print(f"rounds {a.scene} {100 * acc:g} %: "
                  + ", ".join(f"{x:.2f}" if x is not None else "-" for x in round_ratios(have)), flush=True)
        out.append(have)
    rp.write_text("".join(json.dumps(r) + "\n" for r in out))
    return out


def errors_by_pin(tips: list[dict] | None, scene: str) -> dict[str, float] | None:
    """Thick scene: {pin size in mm: the error against the continuum with that pin}
    (:func:`studies.peers.thick_reference.pin_references`); None for other scenes."""
    if scene != "thick" or not tips:
        return None
    t = {round(h["t"], 9): (h["x"], h["y"]) for h in tips}
    return {f"{1e3 * pin:g}": max(tip_errors(t, ref).values()) for pin, ref in sorted(pin_references().items())}


def left(tips: list[dict] | None) -> float | None:
    """The tip's largest distance from the pin over the outputs, / L, where it is more than
    :data:`REACH` (or not finite): the run has left the pendulum whatever its solver says.
    None: it has not."""
    d = [math.hypot(h["x"], h["y"]) / LENGTH for h in tips or []]
    worst = max(d, key=lambda x: x if math.isfinite(x) else math.inf, default=None)
    return worst if worst is not None and not worst <= REACH else None


def score(r: dict) -> dict:
    """``r`` with its error against its scene's current reference, the reference's estimate
    and the errors by pin, from its tip history; a run whose tip :func:`left` the pendulum
    is "diverged" (Exudyn's linear-solve runs on fine meshes at 10 ms report success with
    tips 1e10 L away), with no error: it counts for no accuracy."""
    sc = r.get("scene", SCENE)
    tips = r.get("tip_history")
    out = left(tips)
    if out is not None:
        r.update(status="diverged", reason=f"the tip reached {out:.3g} L from the pin (its solver reported success)",
                 error=None, error_by_pin_mm=None)
    else:
        r.update(error=error(tips, sc), error_by_pin_mm=errors_by_pin(tips, sc))
    r["reference_error"] = reference(sc)[1]
    return r


def rescore(path: Path) -> list[dict]:
    """Every record :func:`score`-d again from its tip history against its scene's current
    reference; no solver runs (``--rescore``)."""
    recs = [score(r) for r in read(path)]
    path.write_text("".join(json.dumps(r) + "\n" for r in recs))
    return recs
