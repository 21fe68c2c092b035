"""Who is cheaper at equal accuracy: our pendulum and Exudyn's ANCF cable pendulum on one
work-precision diagram, timed side by side in one run (``make bench-peers``, issue 10).

    .venv/bin/python -m studies.peers.work_precision [--scene pendulum|thick] [--counts 2 4 8 16 32 64]
        [--element HB2n-12 --element HB2n-16 --element HB2n-20xyp --element HB2n-40p --element HB2n-60p] [--import MODULE] [--rho-inf 0.5] [--repeats 5]
        [--out reports]

Grid: the element counts (2 to 64: at 1 % a run is a few elements, and the cable holds 1 % with
2 or 4, so the grid starts there for both sides), and the step ladder dt = 0.1 s / k for
k = 10, 20, 40, 80, 160, 320 (10 ms halving to 0.3125 ms: every step lands on the output
times 0.1 ... 0.5 s, as Exudyn's fixed step must). Each (solver, element, count, step) is one run: the median of
``--repeats`` warm runs (ours: ``wall_s`` of :func:`ancf.simulation.run_scene`, the solve
alone; Exudyn: ``SolveDynamic`` alone, see exudyn_pendulum.py), Exudyn's and ours in
turn for each point; the runs' times are kept for their spread. Neither side has an
energy guard (:data:`ENERGY_GUARD`): Exudyn's fixed-step run has none, so ours runs with
``energy_limit = inf``. Error: max over t = 0.1 ... 0.5 s of |r(t) - r_ref(t)| / L against
the converged continuum plane-stress pendulum (tests/gold/fem_pendulum.json), the
reference of the accuracy-cost diagram. Exudyn's cable is linear elastic (E = 6 C10) and
Euler-Bernoulli: its error has a floor set by its physics, not by its mesh or step; the
floors are read at the finest step of the finest mesh (:func:`floors`), not as the
smallest error over the grid.

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
machine's phase, the grid's two points need not); the table
``<out>/peers_work_precision.md`` and the figures ``.png`` (one per scene) are drawn from
those files alone (``--report-only`` redraws them; ``--rescore`` first recomputes
every error from the records' tip histories against the current references).
"""
from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")                 # one thread, before numpy loads

import argparse
import importlib
import itertools
import json
import statistics
import sys
import time
from pathlib import Path

from .anatomy import anatomy_lines, reach_lines, step_error_lines
from .compare import PEER_PYTHON, peer

ROOT = Path(__file__).resolve().parents[2]
STEPS_PER_OUTPUT = (10, 20, 40, 80, 160, 320)       # dt = 0.1 s / k
COUNTS = (2, 4, 8, 16, 32, 64)
ACCURACIES = (0.01, 0.003, 0.001)     # 0.3 % added after the thick scene's run: its floors lie between 1 % and 0.1 %
NAME = "peers-work-precision"
SCENE = "pendulum"          # the default scene
# scene -> cross-section height (m) and what its reference is
SCENES = {"pendulum": {"height": 0.005, "title": "the paper's slender pendulum, h = 5 mm (L / h = 70)",
                       "reference": "the converged continuum plane-stress Yeoh pendulum (tests/gold/fem_pendulum.json)"},
          "thick": {"height": 0.020, "title": "thick pendulum, h = 20 mm (L / h = 17.5)",
                    "reference": "the continuum plane-stress Yeoh pendulum with h = 20 mm "
                                 "(data/peers/thick-pendulum-reference.json, studies.peers.thick_reference: 8, 16 "
                                 "and 32 Q2 cells across; the tip moves by the same 0.14 mm at each halving, the point "
                                 "pin's logarithmic singularity, so the reference is the 16-cell run, a 1.25 mm pin as "
                                 "in the slender pendulum's gold, and its estimate is the time error plus one pin "
                                 "halving)"}}
# The same rule for both sides: Exudyn's fixed-step run has no energy check, so ours runs
# without its guard too (a run that gains energy shows it in its error, not by stopping).
ENERGY_GUARD = "none"
MIN_REPEATS = 5
ELEMENTS = ("HB2n-12", "HB2n-16", "HB2n-20xyp", "HB2n-40p", "HB2n-60p")   # the paper's two and the lock-free ones with a pressure field


def key(r: dict) -> tuple:
    return (r.get("scene", SCENE), r["solver"], r["element"], r["elements"], round(r["dt"], 12), r["rho_inf"])


def ours(element: str, n: int, dt: float, rho_inf: float, repeats: int, scene: str = SCENE) -> dict:
    from ancf.simulation import run_scene
    from contract.scene import scene_from_dict
    from ..pendulum_cases import pendulum_dict

    d = pendulum_dict(element, n, "plane-stress", dt, rho_inf=rho_inf)
    d["beam"]["height"] = SCENES[scene]["height"]
    d["analysis"]["energy_limit"] = "inf"      # no energy guard: Exudyn's run has none (ENERGY_GUARD)
    sc = scene_from_dict(d)
    recs = [run_scene(sc)[0] for _ in range(repeats + 1)][1:]     # one untimed warm-up
    last = recs[-1]
    ok = last["status"] == "converged"
    return {"status": last["status"], "reason": last.get("reason"), "energy_guard": ENERGY_GUARD,
            "time_s": statistics.median(r["wall_s"] for r in recs) if ok else None,
            "time_runs_s": [r["wall_s"] for r in recs] if ok else None,
            "cpu_s": statistics.median(r["cpu_s"] for r in recs) if ok else None,
            "ndof": last["ndof"], "newton_iterations": last.get("newton_iterations"),
            "tip_history": last.get("tip_history") if ok else None}


def exudyn(n: int, dt: float, rho_inf: float, repeats: int, python: Path, scene: str = SCENE) -> dict:
    try:
        p = peer(dt, rho_inf, repeats, python, elements=n, height=SCENES[scene]["height"])
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
    from ..pendulum_cases import LENGTH, continuum_pendulum
    from . import thick_reference

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
    from ..pendulum_cases import tip_errors

    ref = reference(scene)[0]
    if not tips or ref is None:
        return None
    e = tip_errors({round(h["t"], 9): (h["x"], h["y"]) for h in tips}, ref)
    return max(e.values()) if e else None


def read(path: Path) -> list[dict]:
    return [json.loads(ln) for ln in path.read_text().splitlines() if ln.strip()] if path.exists() else []


def run(a) -> list[dict]:
    path = a.out / "data" / "peers" / f"{NAME}.jsonl"
    path.parent.mkdir(parents=True, exist_ok=True)
    if a.force and path.exists():                  # redo this scene's points, keep the others'
        keep = [r for r in read(path) if r.get("scene", SCENE) != a.scene]
        path.write_text("".join(json.dumps(r) + "\n" for r in keep))
    have = {key(r) for r in read(path)}
    for n in a.counts:
        for k in a.steps_per_output:
            dt = 0.1 / k
            todo = [("exudyn", "ANCFCable2D")] + [("ancf", e) for e in a.element]
            for solver, element in todo:
                base = {"solver": solver, "scene": a.scene, "height": SCENES[a.scene]["height"], "element": element, "elements": n, "dt": dt,
                        "rho_inf": a.rho_inf,
                        "law": "yeoh", "formulation": "plane-stress" if solver == "ancf" else "linear cable"}
                if key(base) in have:
                    continue
                t0 = time.perf_counter()
                load0 = os.getloadavg()[0]
                res = (exudyn(n, dt, a.rho_inf, a.repeats, a.peer_python, a.scene) if solver == "exudyn"
                       else ours(element, n, dt, a.rho_inf, a.repeats, a.scene))
                rec = {**base, **res, "error": error(res.get("tip_history"), a.scene),
                       "reference_error": reference(a.scene)[1],
                       "error_by_pin_mm": errors_by_pin(res.get("tip_history"), a.scene), "repeats": a.repeats,
                       "host_load": [load0, os.getloadavg()[0]]}
                with path.open("a") as f:
                    f.write(json.dumps(rec) + "\n")
                e = rec["error"]
                print(f"{solver:7s} {element:12s} x{n:3d} dt {dt * 1e3:7.4f} ms  {rec['status']:9s} "
                      f"time {rec['time_s'] or float('nan'):8.4f} s  error {100 * e if e is not None else float('nan'):8.4f} %"
                      f"  ({time.perf_counter() - t0:.1f} s)", flush=True)
    return read(path)


def rounds_path(path: Path) -> Path:
    """The deciding points' re-timings, beside the points' records."""
    return path.with_name(f"{NAME}-rounds.jsonl")


def _pair(o: dict, p: dict) -> dict:
    """The (ours, cable's) points a rounds record re-times, as it stores them."""
    return {k: {"element": r["element"], "elements": r["elements"], "dt": r["dt"]} for k, r in (("ours", o), ("exudyn", p))}


def rounds_of(rounds: list[dict], scene: str, accuracy: float, o: dict, p: dict) -> dict | None:
    """The rounds record of ``scene`` and ``accuracy`` that re-timed exactly these two points."""
    pts = _pair(o, p)
    return next((r for r in rounds if r["scene"] == scene and r["accuracy"] == accuracy
                 and {k: r[k] for k in pts} == pts), None)


def _ratios(r: dict | None) -> list[float | None]:
    """Each round's ours / cable's (None where a side has no time)."""
    return [x["ours_s"] / x["exudyn_s"] if x["ours_s"] and x["exudyn_s"] else None for x in (r or {}).get("rounds", [])]


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
                pe = exudyn(p["elements"], p["dt"], a.rho_inf, a.repeats, a.peer_python, a.scene)
                ou = ours(o["element"], o["elements"], o["dt"], a.rho_inf, a.repeats, a.scene)
                rounds.append({"exudyn_s": pe["time_s"], "ours_s": ou["time_s"]})
            have = {"scene": a.scene, "accuracy": acc, **_pair(o, p), "repeats": a.repeats, "rounds": rounds,
                    "host_load": os.getloadavg()[0]}
            print(f"rounds {a.scene} {100 * acc:g} %: "
                  + ", ".join(f"{x:.2f}" if x is not None else "-" for x in _ratios(have)), flush=True)
        out.append(have)
    rp.write_text("".join(json.dumps(r) + "\n" for r in out))
    return out


def deciding_ratio(o: dict | None, p: dict | None, rr: dict | None) -> tuple:
    """(ratio, source) of a row with our and the cable's cheapest runs o, p and their rounds
    record rr: ours / cable's by the median of the rounds ('rounds') where they were
    re-timed, else by the grid's medians ('grid'); (None, None) without both runs."""
    if not (o and p):
        return None, None
    x = [r for r in _ratios(rr) if r is not None]
    return (statistics.median(x), "rounds") if x else (o["time_s"] / p["time_s"], "grid")


def rounds_text(r: dict | None) -> str:
    """'median (each round's ratio)' of a rounds record, or '-'."""
    rr = [x for x in _ratios(r) if x is not None]
    return f"{statistics.median(rr):.2f} ({', '.join(f'{x:.2f}' for x in rr)})" if rr else "-"


def errors_by_pin(tips: list[dict] | None, scene: str) -> dict[str, float] | None:
    """Thick scene: {pin size in mm: the error against the continuum with that pin}
    (:func:`studies.peers.thick_reference.pin_references`); None for other scenes."""
    from ..pendulum_cases import tip_errors
    from .thick_reference import pin_references

    if scene != "thick" or not tips:
        return None
    t = {round(h["t"], 9): (h["x"], h["y"]) for h in tips}
    return {f"{1e3 * pin:g}": max(tip_errors(t, ref).values()) for pin, ref in sorted(pin_references().items())}


def rescore(path: Path) -> list[dict]:
    """Every record's error (and the reference's estimate) recomputed from its tip history
    against its scene's current reference; no solver runs (``--rescore``)."""
    recs = read(path)
    for r in recs:
        sc = r.get("scene", SCENE)
        r["error"] = error(r.get("tip_history"), sc)
        r["reference_error"] = reference(sc)[1]
        r["error_by_pin_mm"] = errors_by_pin(r.get("tip_history"), sc)
    path.write_text("".join(json.dumps(r) + "\n" for r in recs))
    return recs


def holds(r: dict, recs: list[dict], accuracy: float) -> bool:
    """Does run ``r`` reach ``accuracy``, and does every finer step of its mesh too? A
    coarse step's error can cancel the mesh's (numerical dissipation against stiffness):
    such a run is accurate by luck, and a finer step would lose it."""
    same = [q for q in recs if (q["solver"], q["element"], q["elements"]) == (r["solver"], r["element"], r["elements"])
            and q["dt"] <= r["dt"]]
    return all(q["error"] is not None and q["error"] <= accuracy for q in same)


def cheapest(recs: list[dict], solver: str, element: str | None, accuracy: float) -> dict | None:
    """The fastest run of ``solver`` (and ``element``) that :func:`holds` ``accuracy``."""
    ok = [r for r in recs if r["solver"] == solver and (element is None or r["element"] == element)
          and r["time_s"] and holds(r, recs, accuracy)]
    return min(ok, key=lambda r: r["time_s"]) if ok else None


def floors(recs: list[dict]) -> dict[tuple, dict]:
    """(solver, element) -> the run at the finest step of its finest mesh: its error is
    the model's accuracy floor read where step and mesh errors are smallest (not the
    smallest error over the grid, which a cancellation of the two can reach)."""
    out = {}
    for r in recs:
        if r["error"] is None:
            continue
        k = (r["solver"], r["element"])
        q = out.get(k)
        if q is None or (r["elements"], -r["dt"]) > (q["elements"], -q["dt"]):
            out[k] = r
    return out


def spread(r: dict) -> str:
    """'min-max' of the record's timed runs, or '-' (older records kept the median only)."""
    runs = r.get("time_runs_s")
    return f"{min(runs):.4f}-{max(runs):.4f}" if runs else "-"


def scenes_of(recs: list[dict]) -> list[str]:
    """The records' scenes, in :data:`SCENES` order (older records: the pendulum)."""
    have = {r.get("scene", SCENE) for r in recs}
    return [s for s in SCENES if s in have] + sorted(have - set(SCENES))


def figure_name(scene: str) -> str:
    return "peers_work_precision.png" if scene == SCENE else f"peers_work_precision_{scene}.png"


def report(recs: list[dict], out: Path, rounds: list[dict] = ()) -> str:
    """The tables (markdown, :func:`report_markdown`) and one figure per scene from the records."""
    text = report_markdown(recs, rounds)
    for scene in scenes_of(recs):
        figure([r for r in recs if r.get("scene", SCENE) == scene], out / figure_name(scene), scene)
    (out / "peers_work_precision.md").write_text(text)
    return text


def ratio_range(o: dict, p: dict) -> str:
    """'lo-hi' of ours / Exudyn's over their timed runs (slowest against fastest and back)."""
    a, b = o.get("time_runs_s"), p.get("time_runs_s")
    return f"{min(a) / max(b):.2f}-{max(a) / min(b):.2f}" if a and b else "-"


def load_text(recs: list[dict]) -> str:
    loads = [x for r in recs for x in (r["host_load"] if isinstance(r.get("host_load"), list)
                                        else [r["host_load"]] if r.get("host_load") is not None else [])]
    return (f"{min(loads):.2f} to {max(loads):.2f} (median {statistics.median(loads):.2f}; before and after each point)"
            if loads else "not recorded")


def ref_text(recs: list[dict]) -> str:
    e = {r.get("reference_error") for r in recs} - {None}
    return (f", its error estimate at most {100 * max(e):.3f} % of L" if e else ", its error estimate not recorded")


def scene_markdown(recs: list[dict], scene: str, rounds: list[dict] = ()) -> list[str]:
    """The section of one scene's records (``rounds``: its deciding points' re-timings,
    :func:`retime`)."""
    guards = {r.get("energy_guard", "the scene's energy limit") for r in recs if r["solver"] == "ancf"}
    runs = [len(r["time_runs_s"]) for r in recs if r.get("time_runs_s")]
    els = sorted({r["element"] for r in recs if r["solver"] == "ancf"})
    info = SCENES.get(scene, {"title": scene, "reference": "?"})
    lines = [f"## Scene `{scene}`: {info['title']}", "",
             f"Reference: {info['reference']}" + ref_text(recs) + f". Our elements: {', '.join(els)}"
             + " (all on the compiled step loop: the scenes are plane stress, where an element's pressure "
             "field carries no penalty).", "",
             "Energy guard: "
             + ("none on either side (Exudyn's run has none; ours runs with energy_limit = inf)"
                if guards == {"none"} else "NOT the same on both sides in these records (ours: "
                + ", ".join(sorted(guards)) + "; Exudyn: none): rerun with --force")
             + ". Timed runs per point: " + ((f"{min(runs)}" if min(runs) == max(runs) else f"{min(runs)} to {max(runs)}") if runs else "not recorded (older records)")
             + (f" (fewer than {MIN_REPEATS}: rerun with --repeats {MIN_REPEATS})" if not runs or min(runs) < MIN_REPEATS
                else "") + "; time = their median, spread = min-max. Load average (1 min) during the runs: "
             + load_text(recs) + ".",
             "",
             "| accuracy | cheapest ours | time (s) | error (%) | cheapest Exudyn cable | time (s) | error (%) | "
             "ours / Exudyn (medians) | range over runs | by rounds: median (each round) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    rows = []                          # (accuracy, ours, cable, ratio, source): the anatomy's rows
    for a in ACCURACIES:
        o, p = cheapest(recs, "ancf", None, a), cheapest(recs, "exudyn", None, a)
        fo = (f"{o['element']} x {o['elements']}, dt {o['dt'] * 1e3:g} ms | {o['time_s']:.4f} | "
              f"{100 * o['error']:.3f}") if o else "none | - | -"
        fp = (f"{p['elements']} elements, dt {p['dt'] * 1e3:g} ms | {p['time_s']:.4f} | "
              f"{100 * p['error']:.3f}") if p else "none | - | -"
        ratio = (f"{o['time_s'] / p['time_s']:.2f} | {ratio_range(o, p)}" if o and p
                 else "- (ours reaches it, the cable does not) | -" if o else "- | -")
        rr = rounds_of(rounds, scene, a, o, p) if o and p else None
        lines.append(f"| {100 * a:g} % | {fo} | {fp} | {ratio} | {rounds_text(rr)} |")
        rows.append((a, o, p, *deciding_ratio(o, p, rr)))
    if any(r.get("rounds") for r in rounds):
        n = sorted({len(r["rounds"]) for r in rounds})
        lines += ["", f"By rounds: the two points of a row timed again alternately after the grid ({'/'.join(map(str, n))} "
                  f"rounds of {'/'.join(map(str, sorted({r['repeats'] for r in rounds})))} runs, the cable's first), "
                  "each round's ratio of its two medians; the machine's speed drifts within a run, and a round's "
                  "two medians share its phase (data/peers/" + f"{NAME}-rounds.jsonl)."]
    lines += [""] + anatomy_lines(rows)
    lines += [""] + step_error_lines(recs)
    for text in reach_lines(recs, rows):
        lines += ["", text]
    fl = floors(recs)
    if fl:
        lines += ["", "Accuracy floors, read at the finest step of the finest mesh (the cable's: its physics, "
                  "linear elastic E = 6 C10, Euler-Bernoulli, no thickness deformation):", "",
                  "| solver | element | n | dt (ms) | error (%) |", "|---|---|---|---|---|"]
        for (solver, element), r in sorted(fl.items()):
            lines.append(f"| {solver} | {element} | {r['elements']} | {r['dt'] * 1e3:g} | {100 * r['error']:.4f} |")
    pins = sorted({k for r in fl.values() for k in (r.get("error_by_pin_mm") or {})}, key=float, reverse=True)
    if pins:
        lines += ["", "The floors against the same continuum with other pin sizes (the point pin is as large as its "
                  "cell, so the larger pins come from coarser meshes, 2 cells across at 10 mm; the reference's pin is 1.25 mm): the error of a beam pinned at its centreline depends on the "
                  "continuum pin it is held against, the gap between the codes much less:", "",
                  "| solver | element | " + " | ".join(f"pin {p} mm (%)" for p in pins) + " |",
                  "|---|---|" + "---|" * len(pins)]
        for (solver, element), r in sorted(fl.items()):
            e = r.get("error_by_pin_mm") or {}
            lines.append(f"| {solver} | {element} | "
                         + " | ".join(f"{100 * e[p]:.3f}" if p in e else "-" for p in pins) + " |")
    lines += ["", "| solver | element | n | dt (ms) | status | time (s) | spread (s) | error (%) |",
              "|---|---|---|---|---|---|---|---|"]
    for r in sorted(recs, key=lambda r: (r["solver"], r["element"], r["elements"], -r["dt"])):
        lines.append(f"| {r['solver']} | {r['element']} | {r['elements']} | {r['dt'] * 1e3:g} | {r['status']} | "
                     + (f"{r['time_s']:.4f}" if r["time_s"] else "-") + f" | {spread(r)} | "
                     + (f"{100 * r['error']:.4f}" if r["error"] is not None else "-") + " |")
    lines += ["", f"![work-precision, {scene}]({figure_name(scene)})", ""]
    return lines


def report_markdown(recs: list[dict], rounds: list[dict] = ()) -> str:
    """reports/peers_work_precision.md from the records alone (a plain function): one
    section per scene (``rounds``: the deciding points' re-timings, :func:`retime`)."""
    lines = ["# Work-precision: our pendulum against Exudyn's ANCF cable",
             "",
             "Generated by `python -m studies.peers.work_precision` (`make bench-peers`) from "
             f"`data/peers/{NAME}.jsonl`; do not edit; see the module's docstring for the method. Error: max over "
             "t = 0.1 ... 0.5 s of |r - r_ref| / L against the scene's converged continuum plane-stress Yeoh pendulum; "
             "time: median warm solve wall time, both solvers in one run (each point: Exudyn's runs, then ours), "
             "one thread. A run counts for an accuracy only if every finer step of its mesh reaches it too (no "
             "accuracy by cancellation of step and mesh errors). Ratios below 1: ours is cheaper.",
             ""]
    for scene in scenes_of(recs):
        lines += scene_markdown([r for r in recs if r.get("scene", SCENE) == scene], scene,
                                [r for r in rounds if r["scene"] == scene])
    return "\n".join(lines)


def figure(recs: list[dict], path: Path, scene: str = SCENE) -> None:
    """The work-precision figure of one scene's records (``path``, a .png) and the data it
    draws beside it (``<name>.figure.csv``, :func:`figure_csv`, which the audit compares)."""
    import matplotlib.pyplot as plt

    fig = make_figure(recs, scene)
    fig.savefig(path, dpi=150)
    path.with_name(path.stem + ".figure.csv").write_text(_csv(fig))
    plt.close(fig)


def _csv(fig) -> str:
    import csv
    import io

    from ..engine.report import figure_data

    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(["panel", "title", "x label", "y label", "label", "marker", "filled", "x", "y"])
    w.writerows(figure_data(fig))
    return buf.getvalue()


def figure_csv(recs: list[dict], scene: str = SCENE) -> str:
    """Every point the scene's figure draws, as the audit's figure data (CSV text)."""
    import matplotlib.pyplot as plt

    fig = make_figure([r for r in recs if r.get("scene", SCENE) == scene], scene)
    try:
        return _csv(fig)
    finally:
        plt.close(fig)


def make_figure(recs: list[dict], scene: str = SCENE):
    """The work-precision figure of one scene's records (a matplotlib Figure)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    els = list(dict.fromkeys(r["element"] for r in recs if r["solver"] == "ancf"))
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    markers = {"ANCFCable2D": "s", **{e: m for e, m in zip(els, itertools.cycle("o^vDpXh*P<>"))}}
    for solver, element in [("exudyn", "ANCFCable2D")] + [("ancf", e) for e in els]:
        for n in sorted({r["elements"] for r in recs if (r["solver"], r["element"]) == (solver, element)}):
            ser = sorted([r for r in recs if (r["solver"], r["element"], r["elements"]) == (solver, element, n)
                          and r["error"] is not None and r["time_s"]], key=lambda r: -r["dt"])
            if ser:
                ax.plot([r["time_s"] for r in ser], [r["error"] for r in ser], marker=markers[element], ms=3, lw=0.8,
                        ls="--" if solver == "exudyn" else "-",
                        label=f"{'Exudyn cable' if solver == 'exudyn' else 'ours ' + element} x {n}")
    for a in ACCURACIES:
        ax.axhline(a, color="grey", lw=0.6, ls=":")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.grid(True, alpha=0.3)
    ax.set_xlabel("solve wall time, median warm (s)")
    ax.set_ylabel("max over t of |r - r_ref| / L")
    h = SCENES.get(scene, {}).get("height")
    ax.set_title(f"{scene}" + (f" (h = {h * 1e3:g} mm)" if h else "") + ", Yeoh: ours (plane stress) vs Exudyn "
                 f"ANCF cable; step {1e3 * max(r['dt'] for r in recs):g} ms halving", fontsize=9)
    ax.legend(fontsize=5, ncol=3)
    fig.tight_layout()
    return fig


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m studies.peers.work_precision", description=__doc__.splitlines()[0])
    ap.add_argument("--scene", choices=sorted(SCENES), default=SCENE, help="pendulum (h = 5 mm, default) or thick "
                    "(h = 20 mm)")
    ap.add_argument("--counts", type=int, nargs="+", default=list(COUNTS))
    ap.add_argument("--element", action="append", help="our element (repeatable; default: ELEMENTS)")
    ap.add_argument("--rho-inf", type=float, default=0.5, help="generalized-alpha spectral radius (default 0.5, "
                    "Table 4's)")
    ap.add_argument("--steps-per-output", type=int, nargs="+", default=list(STEPS_PER_OUTPUT),
                    help="the step ladder: dt = 0.1 s / k for each k (default 10 20 40 80 160 320)")
    ap.add_argument("--repeats", type=int, default=MIN_REPEATS, help=f"timed warm runs per point (default {MIN_REPEATS})")
    ap.add_argument("--peer-python", type=Path, default=PEER_PYTHON)
    ap.add_argument("--out", type=Path, default=ROOT / "reports")
    ap.add_argument("--import", dest="imports", action="append", default=[],
                    help="a module that registers a user's element (repeatable)")
    ap.add_argument("--rounds", type=int, default=7, help="re-time each accuracy's two cheapest points "
                    "alternately in this many rounds after the grid (default %(default)s; 0: none)")
    ap.add_argument("--force", action="store_true", help="redo every point (and the rounds)")
    ap.add_argument("--report-only", action="store_true", help="redraw the table and figure from the records")
    ap.add_argument("--rescore", action="store_true", help="recompute every record's error from its tip history "
                    "against its scene's current reference (no solver runs), then redraw")
    a = ap.parse_args(argv)
    a.element = a.element or list(ELEMENTS)
    for m in a.imports:
        importlib.import_module(m)
    path = a.out / "data" / "peers" / f"{NAME}.jsonl"
    recs = rescore(path) if a.rescore else read(path) if a.report_only else run(a)
    busy = not (a.rescore or a.report_only) and a.rounds > 0
    rounds = retime(recs, a, path) if busy else read(rounds_path(path))
    print(report(recs, a.out, rounds))
    return 0


if __name__ == "__main__":
    sys.exit(main())
