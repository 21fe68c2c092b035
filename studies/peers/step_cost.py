"""Why a missed target is missed, measured (``make bench-peers``, after the rounds of
:mod:`studies.peers.work_precision`): for each row of a scene whose target (ours at most
:data:`studies.peers.anatomy.TARGET` of the cable's time) the rounds miss, two
measurements of our deciding run, into ``<out>/data/peers/peers-step-cost.json``:

1. **What exists.** The run under each Newton the compiled loop offers (``[analysis]
   newton`` = chord | full | modified, :data:`MODES`, at the loosest tolerance a scene
   accepts and at the default, and linear: one solve per step, no convergence test), timed in ``--rounds`` rounds beside the cable's deciding run
   (its run, then ours in each mode), each round's ratio of medians as the rounds of the
   grid: is there a cheaper step among the settings a scene has?
2. **What one step does.** The run's step split into its parts, each timed in a compiled
   loop of ``--calls`` calls at the run's final state (:func:`split`): the whole step
   (:func:`ancf.compiled_steps.step`), the force and tangent at the predictor, the
   factorisation and solve, and the residual after the correction that verifies the
   step. Where the run takes one iteration per step (its Newton counter equals its steps),
   its states are those of one linear solve per step, and the verifying residual is all a
   step with one linear solve and no convergence test (the peer's linear mode) would leave
   out: the record's estimate is the rounds' ratio with ``steps x`` that residual taken off
   our time (an estimate from a compiled loop's timing, beside the linear mode's run).

Nothing here changes a run's settings: the modes are scene settings with the same checks
(det F at every assembly, the energies at the outputs); the split reads the compiled
loop's own functions.

    .venv/bin/python -m studies.peers.work_precision ...     # runs it after the rounds
    .venv/bin/python -m studies.peers.step_cost [--scene pendulum] [--rounds 5] [--repeats 5] [--calls 20000]
"""
from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")                 # one thread, before numpy loads

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

import numpy as np

from .anatomy import TARGET, TARGET_ACCURACIES
from .compare import PEER_PYTHON
from .precision_grid import NAME, SCENE, SCENES, our_element
from .precision_report import cheapest, deciding_ratio, read, rounds_of, rounds_path

ROOT = Path(__file__).resolve().parents[2]
RECORD = f"{NAME.replace('work-precision', 'step-cost')}.json"     # peers-step-cost.json
# the compiled loop's Newtons (contract.scene.NEWTON) at the loosest tolerance a scene accepts,
# and the default: label -> [analysis] settings
MODES = {"chord, rtol 1e-3": {"newton": "chord", "newton_rtol": 1e-3},
         "full, rtol 1e-3": {"newton": "full", "newton_rtol": 1e-3},
         "modified, rtol 1e-3": {"newton": "modified", "newton_rtol": 1e-3},
         "chord, default rtol": {"newton": "chord"},
         "linear": {"newton": "linear"}}
PARTS = ("step", "force_and_tangent", "factorise_and_solve", "verifying_residual")


def record_path(out: Path) -> Path:
    return Path(out) / "data" / "peers" / RECORD


def _scene(element: str, n: int, dt: float, rho_inf: float, scene: str, settings: dict):
    from contract.scene import scene_from_dict

    from .work_precision import scene_dict

    d = scene_dict(our_element(element)[0], n, dt, rho_inf, scene)
    d["analysis"].update(settings)
    return scene_from_dict(d)


def run_mode(element: str, n: int, dt: float, rho_inf: float, repeats: int, scene: str, settings: dict) -> dict:
    """Our run of a point with these [analysis] settings: the median of ``repeats`` warm
    runs' solve times (one untimed warm-up), its Newton iterations and status."""
    from ancf.simulation import run_scene

    sc = _scene(element, n, dt, rho_inf, scene, settings)
    recs = [run_scene(sc)[0] for _ in range(repeats + 1)][1:]
    last = recs[-1]
    ok = last["status"] == "converged"
    return {"status": last["status"], "time_s": statistics.median(r["wall_s"] for r in recs) if ok else None,
            "newton_iterations": last.get("newton_iterations"), "steps": last.get("steps"),
            "tip_history": last.get("tip_history") if ok else None}


def _kernels():
    """The compiled timing loops (compiled on first use, cached in memory)."""
    from numba import njit

    from ancf.compiled_steps import _correct, _factorise, _mass, _residual, step
    from ancf.element_kernels import element_assemble, element_work

    @njit
    def steps(N, dN, w, dofs, ops, consts, pr, Mc, first, f_ext, fixed, coef, inewton, fnewton, u_n, v_n, a_n, h,
              S, fstate, counters):
        n = u_n.shape[0]
        is_free = np.ones(n, np.bool_)
        for k in fixed:
            is_free[k] = False
        wk = np.empty((7, n))
        chunk, R, Fb, ab, Jb, ew = element_work(ops, dN, pr)
        u, v, a = np.empty(n), np.empty(n), np.empty(n)
        its = 0
        for _ in range(N):
            status, it = step(dN, w, dofs, ops, consts, pr, Mc, first, f_ext, fixed, is_free, coef, inewton,
                              fnewton, u_n, v_n, a_n, h, u, v, a, S, fstate, counters, wk, chunk, R, Fb, ab, Jb, ew,
                              False)
            its += it
        return its

    @njit
    def assemble(N, tangent, u, u_n, af, dN, w, dofs, ops, consts, pr, S):
        n = u.shape[0]
        f = np.empty(n)
        chunk, R, Fb, ab, Jb, ew = element_work(ops, dN, pr)
        for _ in range(N):
            element_assemble(u, u_n, af, dN, w, dofs, ops, consts, pr, f, S, tangent, chunk, R, Fb, ab, Jb, ew)

    @njit
    def factorise_and_solve(N, S, k, Mc, c, fixed, first, r, counters):
        n = r.shape[0]
        wk = np.empty((2, n))
        du, u = np.empty(n), np.zeros(n)
        for _ in range(N):
            T = S.copy()
            _factorise(T, k, Mc, c, fixed, first, wk, counters)
            _correct(T, first, r, du, u, counters)

    @njit
    def verify(N, u, u_n, u_pred, af, c, split, dN, w, dofs, ops, consts, pr, Mc, first, a_n, f_ext, fixed, S):
        n = u.shape[0]
        is_free = np.ones(n, np.bool_)
        for k in fixed:
            is_free[k] = False
        f, Ma_n, r, du = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
        chunk, R, Fb, ab, Jb, ew = element_work(ops, dN, pr)
        _mass(Mc, first, split, a_n, Ma_n)
        for _ in range(N):
            element_assemble(u, u_n, af, dN, w, dofs, ops, consts, pr, f, S, False, chunk, R, Fb, ab, Jb, ew)
            _residual(Mc, first, split, c, u, u_pred, Ma_n, f, f_ext, is_free, du, r, False)

    return steps, assemble, factorise_and_solve, verify


def split(element: str, n: int, dt: float, rho_inf: float, scene: str, settings: dict, calls: int = 20000,
          repeats: int = 5) -> dict:
    """One step of our run split into its parts (module doc), each the best of ``repeats``
    compiled loops of ``calls`` calls, in seconds per call: the step from the run's final
    state (``step``), the force and tangent there (``force_and_tangent``), the step
    matrix's factorisation and one solve (``factorise_and_solve``), and the force and
    residual at the corrected state (``verifying_residual``)."""
    from ancf.build import build_integrator, external_loads, resolve
    from ancf.compiled_steps import I_MASS_SPLIT
    from mechanics import alpha_family

    from ancf.simulation import run_scene

    p = resolve(_scene(element, n, dt, rho_inf, scene, settings))
    rec, (model, res) = run_scene(p)
    M = model.mass_matrix()
    integ = build_integrator(p, model, M, external_loads(model, p))
    loop = integ._loop
    dN, w, dofs, ops, consts, pr, Mc, first, f_ext, _, fixed = loop.data
    s = res.final
    u_n, v_n, a_n = (np.ascontiguousarray(x, dtype=float) for x in (s.u, s.v, s.a))
    am, af, beta, gamma = (float(x) for x in loop.coef)
    c = (1.0 - am) / (beta * dt * dt)
    u_pred = np.array([alpha_family.predict(u_n[i], v_n[i], a_n[i], dt) for i in range(len(u_n))])
    steps, assemble, fs, verify = _kernels()
    counters = np.zeros_like(loop.counters)

    def best(fn, *args) -> float:
        fn(10, *args)                                          # compile, warm
        out = []
        for _ in range(repeats):
            t0 = time.perf_counter()
            fn(calls, *args)
            out.append((time.perf_counter() - t0) / calls)
        return min(out)

    S = np.zeros_like(loop.S)
    t = {"step": best(steps, dN, w, dofs, ops, consts, pr, Mc, first, f_ext, fixed, loop.coef, loop.inewton,
                      loop.fnewton, u_n, v_n, a_n, dt, S, np.zeros(2), counters),
         "force_and_tangent": best(assemble, True, u_pred, u_n, af, dN, w, dofs, ops, consts, pr, S)}
    K = np.zeros_like(loop.S)
    assemble(1, True, u_pred, u_n, af, dN, w, dofs, ops, consts, pr, K)
    r = np.ones(len(u_n)) * 1e-9
    t["factorise_and_solve"] = best(fs, K, 1.0 - af, Mc, c, fixed, first, r, counters)
    split_mass = bool(loop.inewton[I_MASS_SPLIT])
    t["verifying_residual"] = best(verify, u_pred, u_n, u_pred, af, c, split_mass, dN, w, dofs, ops, consts, pr, Mc,
                                   first, a_n, f_ext, fixed, S)
    return {"seconds_per_call": t, "calls": calls, "repeats": repeats, "ndof": int(len(u_n)),
            "run": {"steps": rec.get("steps"), "newton_iterations": rec.get("newton_iterations"),
                    "wall_s": rec.get("wall_s")}}


def measure(recs: list[dict], rounds: list[dict], scene: str, a) -> list[dict]:
    """The rows of ``scene`` whose target the rounds miss, measured (module doc)."""
    from .work_precision import exudyn

    mine = [r for r in recs if r.get("scene", SCENE) == scene]
    out = []
    for acc in TARGET_ACCURACIES:
        o, p = cheapest(mine, "ancf", None, acc), cheapest(mine, "exudyn", None, acc)
        if not (o and p):
            continue
        rr = rounds_of(rounds, scene, acc, o, p)
        ratio, source = deciding_ratio(o, p, rr)
        if ratio <= TARGET:
            continue
        settings = our_element(o["element"])[1]
        rows = []
        for _ in range(a.rounds):
            pe = exudyn(p["elements"], p["dt"], a.rho_inf, a.repeats, a.peer_python, scene, p["element"])
            row = {"exudyn_s": pe["time_s"], "modes": {}}
            for label, st in MODES.items():
                m = run_mode(o["element"], o["elements"], o["dt"], a.rho_inf, a.repeats, scene, st)
                row["modes"][label] = {k: m[k] for k in ("status", "time_s", "newton_iterations", "steps")}
            rows.append(row)
        sp = split(o["element"], o["elements"], o["dt"], a.rho_inf, scene, settings, a.calls)
        rec = {"scene": scene, "accuracy": acc, "ours": {"element": o["element"], "elements": o["elements"],
                                                         "dt": o["dt"], "settings": settings},
               "exudyn": {"element": p["element"], "elements": p["elements"], "dt": p["dt"]},
               "deciding_ratio": ratio, "source": source, "repeats": a.repeats, "rounds": rows, "split": sp}
        out.append(rec)
        print(f"step cost {scene} {100 * acc:g} %: " + "; ".join(
            f"{k} {statistics.median(x['modes'][k]['time_s'] / x['exudyn_s'] for x in rows):.3f}" for k in MODES)
            + "; split (us): " + ", ".join(f"{k} {1e6 * v:.2f}" for k, v in sp["seconds_per_call"].items()), flush=True)
    return out


def write(path: Path, scene: str, new: list[dict]) -> list[dict]:
    """The record with ``scene``'s entries replaced by ``new``."""
    old = json.loads(path.read_text()) if path.exists() else []
    keep = [r for r in old if r["scene"] != scene] + new
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(keep, indent=1) + "\n")
    return keep


def read_record(path: Path) -> list[dict]:
    return json.loads(Path(path).read_text()) if Path(path).exists() else []


def mode_ratios(rec: dict) -> dict[str, float | None]:
    """{mode: the rounds' median of ours in that mode / the cable's}."""
    out = {}
    for k in MODES:
        x = [r["modes"][k]["time_s"] / r["exudyn_s"] for r in rec["rounds"]
             if r["exudyn_s"] and (r["modes"].get(k) or {}).get("time_s")]
        out[k] = statistics.median(x) if x else None
    return out


def linear_estimate(rec: dict) -> float | None:
    """The rounds' median of (ours - steps x the verifying residual) / the cable's, with
    ours in the deciding run's own mode; None unless the run takes one iteration per step."""
    sp = rec["split"]
    run = sp["run"]
    if not run["steps"] or run["newton_iterations"] != run["steps"]:
        return None
    mode = next((k for k, st in MODES.items() if st == {"newton": "chord", **rec["ours"]["settings"]}), None)
    if mode is None:
        return None
    saved = run["steps"] * sp["seconds_per_call"]["verifying_residual"]
    x = [(r["modes"][mode]["time_s"] - saved) / r["exudyn_s"] for r in rec["rounds"]
         if r["exudyn_s"] and r["modes"][mode].get("time_s")]
    return statistics.median(x) if x else None


def linear_refused(rec: dict, grid: list[dict]) -> list[dict] | None:
    """Where the linear mode's run of the deciding point is within the target but the grid's
    own run of it in that mode (``<element> (linear)``) does not count at the row's accuracy:
    the runs refining it (:func:`studies.peers.precision_report.finer`) that fail or miss
    it; None where it counts, or the grid has no such run."""
    from .precision_report import finer, holds

    o = rec["ours"]
    base, _ = our_element(o["element"])
    run = next((r for r in grid if r["solver"] == "ancf" and r["element"] == f"{base} (linear)"
                and r["elements"] == o["elements"] and r["dt"] == o["dt"]), None)
    if run is None or holds(run, grid, rec["accuracy"]):
        return None
    return [q for q in finer(run, grid) if q["error"] is None or q["error"] > rec["accuracy"]]


def lines(recs: list[dict], grid: list[dict] | None = None) -> list[str]:
    """The report's sentences and table of a scene's step-cost records (:func:`record_path`);
    ``grid``: the scene's work-precision records (to say whether the linear mode's run counts)."""
    out = []
    for rec in recs:
        o, p = rec["ours"], rec["exudyn"]
        ratios = mode_ratios(rec)
        sp = rec["split"]
        t = {k: 1e6 * v for k, v in sp["seconds_per_call"].items()}
        run = sp["run"]
        est = linear_estimate(rec)
        acc = f"{100 * rec['accuracy']:g} %"
        out += [f"Why the {acc} target is missed, measured (data/peers/{RECORD}, `python -m studies.peers.step_cost`): "
                f"our deciding run ({o['element']} x {o['elements']}, dt {o['dt'] * 1e3:g} ms) under each Newton the "
                f"compiled loop offers, timed in {len(rec['rounds'])} rounds of {rec['repeats']} runs beside the "
                f"cable's ({p['elements']} elements{', linear' if p['element'].endswith('-linear') else ''}, dt "
                f"{p['dt'] * 1e3:g} ms), the rounds' median of ours / the cable's:", "",
                "| `[analysis]` setting | ours / cable (rounds' median) | Newton iterations | steps |",
                "|---|---|---|---|"]
        for k in MODES:
            m = rec["rounds"][-1]["modes"].get(k) or {}
            out.append(f"| {k} | " + (f"{ratios[k]:.3f}" if ratios[k] is not None else "-")
                       + f" | {m.get('newton_iterations') or '-'} | {m.get('steps') or '-'} |")
        text = (f"One of its steps ({sp['ndof']} coordinates, at the run's final state; compiled loops of {sp['calls']} calls, "
                f"the best of {sp['repeats']}): the whole step {t['step']:.2f} us, of which the force and tangent at the "
                f"predictor {t['force_and_tangent']:.2f} us, the factorisation and solve {t['factorise_and_solve']:.2f} "
                f"us, and the force and residual that verify the corrected state {t['verifying_residual']:.2f} us "
                f"(the run: {run['wall_s'] * 1e6 / run['steps']:.2f} us per step over {run['steps']} steps).")
        if est is not None:
            text += (f" The run takes {run['newton_iterations']} Newton iterations in {run['steps']} steps: its "
                     "states are those of one linear solve per step already, and a step with one linear solve and no "
                     "convergence test (the cable's linear mode; ours, `newton = \"linear\"`, is the table's last row, "
                     f"run) leaves out only the verifying residual: with it taken off our time, the rounds' "
                     f"median would be {est:.3f} ({'<=' if est <= TARGET else '>'} {TARGET:g}; an estimate from the "
                     "timed parts, not a run).")
        lin = ratios.get("linear")
        refused = linear_refused(rec, grid or []) if lin is not None and lin <= TARGET else None
        if refused:
            worst = ", ".join(f"{q['elements']} elements at {q['dt'] * 1e3:g} ms "
                              + (f"{100 * q['error']:.2f} % off" if q["error"] is not None else
                                 f"{q['status']} ({q.get('reason') or 'no reason recorded'})")
                              for q in sorted(refused, key=lambda q: (q["elements"], -q["dt"])))
            text += (f" The linear mode's run meets the target in time ({lin:.3f}) but does not count at {acc}: the "
                     f"two-way rule asks the runs that refine it in the same setting to reach it too: {worst}. "
                     "What misses the target is the linear step's robustness on the finer meshes, not its cost.")
        out += ["", text, ""]
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m studies.peers.step_cost", description=__doc__.splitlines()[0])
    ap.add_argument("--scene", choices=sorted(SCENES), default=SCENE)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--calls", type=int, default=20000)
    ap.add_argument("--rho-inf", type=float, default=0.5)
    ap.add_argument("--peer-python", type=Path, default=PEER_PYTHON)
    ap.add_argument("--out", type=Path, default=ROOT / "reports")
    a = ap.parse_args(argv)
    path = a.out / "data" / "peers" / f"{NAME}.jsonl"
    recs, rounds = read(path), read(rounds_path(path))
    write(record_path(a.out), a.scene, measure(recs, rounds, a.scene, a))
    return 0


if __name__ == "__main__":
    sys.exit(main())
