"""Shared helpers of the pendulum studies (Figure 4, Figure 5, Table 4, stability, and the
dynamic halves of accuracy-cost and formulation).

- :func:`pendulum_case`: one ANCF pendulum run as a case, built on
  :func:`contract.paper.pendulum_scene` (the paper's pendulum) with the law, the
  simulated time, the output times and the hard-case changes (penalty, stiffness
  scale, integrator) applied to that scene;
- :func:`describe_dynamic`: the grid coordinates of a dynamic record;
- the converged-step rule of Table 4 (:data:`LADDER`, :func:`ladder`,
  :func:`converged_rung`), which ``studies.design.bench`` runs too;
- :func:`continuum_pendulum`: the converged continuum tip histories of
  ``tests/gold/fem_pendulum.json`` (``reference_fem``'s gold file), when it exists;
- :func:`tip_errors`: |r(t) - r_ref(t)| / L at the common output times.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from contract import paper

from ..engine.case import make_case

ROOT = Path(__file__).resolve().parents[2]
FEM_GOLD = ROOT / "tests" / "gold" / "fem_pendulum.json"
LENGTH = paper.PENDULUM["length"]
# The converged-step rule: the largest fixed dt of the ladder dt0, dt0/2, ... (down to
# dt_floor) whose tip positions at every output time are within tol (componentwise)
# of the dt/2 run, both converged.
LADDER = {"dt0": 8e-3, "tol": 1e-4, "dt_floor": 1e-4}


def ladder(dt0: float = LADDER["dt0"], dt_floor: float = LADDER["dt_floor"], last: float | None = None) -> list[float]:
    """dt0, dt0/2, ... while dt/2 >= dt_floor, cut at ``last``."""
    out = [dt0]
    while out[-1] / 2 >= dt_floor and (last is None or out[-1] / 2 >= last * (1 - 1e-9)):
        out.append(out[-1] / 2)
    return out


def converged_rung(rungs: list[dict], tol: float = LADDER["tol"]) -> tuple[dict | None, float | None]:
    """The rule on descriptions (:func:`describe_dynamic`) sorted by decreasing dt:
    (the converged rung, its tip difference to the dt/2 rung in m) or (None, None)."""
    for prev, half in zip(rungs, rungs[1:]):
        if prev["ok"] and half["ok"]:
            a = np.array([prev["tips"][t] for t in sorted(prev["tips"])])
            b = np.array([half["tips"][t] for t in sorted(half["tips"])])
            if a.shape == b.shape:
                diff = float(np.abs(a - b).max())
                if diff <= tol:
                    return prev, diff
    return None, None


def pendulum_dict(element: str, n: int, formulation: str, dt: float, rho_inf: float = 0.5,
                  law: str = paper.PENDULUM_LAW, t_end: float = paper.PENDULUM_T_END,
                  every: float = paper.OUTPUT_EVERY, integrator: str = "generalized-alpha",
                  penalty_factor: float | None = None, stiffness_scale: float = 1.0,
                  name: str | None = None) -> dict:
    """The paper's pendulum scene (:func:`contract.paper.pendulum_scene`) with these changes.

    ``penalty_factor``: penalty alpha = factor x C10 (formulations with a penalty);
    ``stiffness_scale``: every law constant (and the penalty) times this factor."""
    penalty = paper.PENALTY if penalty_factor is None else penalty_factor * paper.materials()[law]["C10"]
    return paper.pendulum_scene(
        law, formulation, float(dt), element, int(n), rho_inf=rho_inf, t_end=t_end, every=every,
        integrator=integrator, penalty=penalty, stiffness_scale=stiffness_scale,
        name=name or f"pendulum-{law}-{formulation}-{element}-{n}-dt{dt:g}-{integrator}-rho{rho_inf:g}-t{t_end:g}")


def pendulum_case(study: str, *args, options: dict | None = None, **kw):
    return make_case(study, "ancf", pendulum_dict(*args, **kw), options)


def describe_dynamic(rec: dict) -> dict:
    """Grid coordinates and results of an ANCF pendulum record."""
    s = rec["scene"]
    a, m = s["analysis"], s["material"]
    c10 = paper.materials()[m["law"]]["C10"]
    d = {"law": m["law"], "formulation": m["formulation"], "element": s["ancf"]["element"],
         "elements": s["ancf"]["elements"], "dt": a["dt"], "t_end": a["t_end"],
         "rho_inf": a.get("rho_inf", 0.5), "integrator": a.get("integrator", "generalized-alpha"),
         "penalty_factor": m["penalty"] / m["C10"] if "penalty" in m else None,
         "stiffness_scale": m["C10"] / c10, "status": rec.get("status"), "reason": rec.get("reason"),
         "ok": rec.get("status") == "converged" and bool(rec.get("tip_history")),
         "tips": {round(h["t"], 9): (h["x"], h["y"]) for h in rec.get("tip_history") or []},
         "steps": rec.get("steps"), "rejected": rec.get("rejected_steps"),
         "newton": rec.get("newton_iterations"), "ndof": rec.get("ndof"), "wall_s": rec.get("wall_s"),
         "timing": rec.get("timing")}
    from ..engine.report import verdict
    d["verdict"] = verdict(rec)
    return d


@dataclass
class ContinuumPendulum:
    law: str
    model: str                          # "plane-stress" | "plane-strain"
    tips: dict[float, tuple[float, float]]
    tolerance: dict[float, float]       # m, the gold file's per-value tolerance
    configurations: dict[float, tuple[list, list]]
    converged: bool
    wall_s: float | None
    ndof: int | None
    dt: float | None
    label: str
    error_estimate: float | None = None  # m, the gold's largest error estimate over t > 0


def continuum_pendulum(path: Path = FEM_GOLD) -> dict[tuple[str, str], ContinuumPendulum]:
    """{(law, model): converged continuum pendulum} from the gold file, {} without it."""
    path = Path(path)
    if not path.exists():
        return {}
    g = json.loads(path.read_text())
    out = {}
    for key, c in g.get("cases", {}).items():
        hist = c.get("tip_history") or []
        if c.get("status") != "converged" or not hist:
            continue
        law, model = key.split("/", 1)
        vals = {round(v["t"], 9): v.get("tolerance_m") for v in c.get("values") or []}
        base = (c.get("runs") or {}).get("base") or {}
        confs = c.get("configurations") or base.get("configurations") or []
        cells = c.get("fem") or {}
        out[(law, model)] = ContinuumPendulum(
            law, model, {round(h["t"], 9): (h["x"], h["y"]) for h in hist}, vals,
            {round(k["t"], 9): (k["x"], k["y"]) for k in confs}, bool(c.get("converged")),
            base.get("wall_s"), c.get("ndof"), c.get("dt", g.get("dt")),
            f"continuum {model} ({cells.get('cells_length', '?')} x {cells.get('cells_height', '?')} Q2, "
            f"dt {1e3 * (c.get('dt') or g.get('dt') or math.nan):g} ms)",
            max(c.get("error_estimate_m") or [math.nan]) if c.get("error_estimate_m") else None)
    return out


def tip_errors(tips: dict, ref: dict, skip_zero: bool = True) -> dict[float, float]:
    """{t: |r(t) - r_ref(t)| / L} at the output times both have (t = 0 left out)."""
    return {t: math.hypot(tips[t][0] - ref[t][0], tips[t][1] - ref[t][1]) / LENGTH
            for t in sorted(set(tips) & set(ref)) if not (skip_zero and t == 0)}


def gold_tips(prefix: str, d: dict, last_only: bool = False) -> dict:
    """Golden values of a converged run: tip x, y at every output time after t = 0
    (``last_only``: at the last output time only; tolerance 1e-6 |v| + 10 nm: Newton's accepted correction is below 1e-6 of the state,
    and the error after it is of its square)."""
    out = {}
    if not d["ok"]:
        return out
    last = max(d["tips"]) if d["tips"] else None
    for t, (x, y) in d["tips"].items():
        if t > 0 and (t == last or not last_only):
            for comp, v in (("x", x), ("y", y)):
                out[f"{prefix}/t{t:g}/{comp}"] = (v, 1e-6 * abs(v) + 1e-8)
    return out
