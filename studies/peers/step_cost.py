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
   (:func:`ancf.solvers.compiled_steps.step`), the force and tangent at the predictor, the
   factorisation and solve, and the residual after the correction that verifies the
   step. Where the run takes one iteration per step (its Newton counter equals its steps),
   its states are those of one linear solve per step, and the verifying residual is all a
   step with one linear solve and no convergence test (the peer's linear mode) would leave
   out: the record's estimate is the rounds' ratio with ``steps x`` that residual taken off
   our time (an estimate from a compiled loop's timing, beside the linear mode's run).

Nothing here changes a run's settings: the modes are scene settings with the same checks
(det F at every assembly, the energies at the outputs); the split reads the compiled
loop's own functions.

    .venv/bin/python -m studies peers work-precision ...     # runs it after the rounds
    .venv/bin/python -m studies peers step-cost [--scene pendulum] [--rounds 5] [--repeats 5] [--calls 20000]
"""
from __future__ import annotations

import statistics
import time

import numpy as np
from numba import njit

from ancf.build import build_integrator, external_loads, plan
from ancf.solvers.compiled_steps import I_MASS_SPLIT, _correct, _factorise, _mass, _residual, step
from ancf.kinematics.kernels import element_assemble, element_work
from ancf.simulation import run_scene
from contract.scene import scene_from_dict
from mechanics import alpha_family

from .anatomy import TARGET, TARGET_ACCURACIES
from .precision_grid import MODES, SCENE, our_element
from .precision_rules import cheapest, deciding_ratio, rounds_of
from .work_precision import exudyn, scene_dict

PARTS = ("step", "force_and_tangent", "factorise_and_solve", "verifying_residual")


def _scene(element: str, n: int, dt: float, rho_inf: float, scene: str, settings: dict):
    d = scene_dict(our_element(element)[0], n, dt, rho_inf, scene)
    d["analysis"].update(settings)
    return scene_from_dict(d)


def run_mode(element: str, n: int, dt: float, rho_inf: float, repeats: int, scene: str, settings: dict) -> dict:
    """Our run of a point with these [analysis] settings: the median of ``repeats`` warm
    runs' solve times (one untimed warm-up), its Newton iterations and status."""
    sc = _scene(element, n, dt, rho_inf, scene, settings)
    recs = [run_scene(sc)[0] for _ in range(repeats + 1)][1:]
    last = recs[-1]
    ok = last["status"] == "converged"
    return {"status": last["status"], "time_s": statistics.median(r["wall_s"] for r in recs) if ok else None,
            "newton_iterations": last.get("newton_iterations"), "steps": last.get("steps"),
            "tip_history": last.get("tip_history") if ok else None}


def _kernels():
    """The compiled timing loops (compiled on first use, cached in memory)."""
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
    p = plan(_scene(element, n, dt, rho_inf, scene, settings))
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
