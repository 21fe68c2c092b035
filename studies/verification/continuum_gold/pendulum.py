"""The paper's flexible pendulum (Example 2) as a continuum: scenes, step and mesh
convergence, gold data for the ANCF comparison (no dolfinx imported at module level).

Study code, driven by ``python -m studies continuum gold --pendulum | pendulum | report
--pendulum`` (:mod:`studies.verification.continuum_gold`).

Pendulum: L = 350 mm, h = 5 mm, w = 7 mm, the paper's laws and densities (Table 2,
:mod:`contract.paper`), gravity (0, -9.81) m/s^2, pinned at the centre of
the left face, released from horizontal at rest, 0.5 s, output times 0, 0.1, ... 0.5 s.

Convergence check of a (mesh, dt): two more runs, one with dt / 2 and one with the
mesh refined once (every cell split in two per direction); the tip moves by
d_dt(t) and d_h(t) (Euclidean, m) at each output time. ``converged`` when both stay
below ``CRITERION_M`` (0.1 mm) at t = 0.1 ... 0.5 s.

Error estimate of the base run at time t (what the gold file stores):

    e(t) = 4/3 d_dt(t) + 2 d_h(t)

(second order in time: the base error is d_dt / (1 - 1/4); in space at least first
order is assumed, because the point pin is a singularity: factor 1 / (1 - 1/2)).
The per-value tolerance is ``TOLERANCE_FACTOR`` e(t), floored at ``TOLERANCE_FLOOR_M``.
"""
from __future__ import annotations

import json
import math
import time
from pathlib import Path

import numpy as np

from contract import paper

PIN_NOTE = ("The pin is the centre node of the left face: a point support, whose local field "
            "is logarithmically singular in a 2D continuum. Refining the mesh shrinks the "
            "support with the cells, and the tip moves by the same vector at each halving "
            "(measured on 2, 4 and 8 cells across: Yeoh 0.030 mm, Mooney-Rivlin 0.106 and "
            "0.121 mm at t = 0.3 s): change_refined_mesh_m is this pin-size sensitivity, not a "
            "beam discretisation error, and it does not vanish under refinement. The base "
            "mesh (cells 1.25 mm high) stands for a pin of about that size; the tolerance "
            "(2 x (4/3 d_dt + 2 d_h)) covers pin sizes between about 0.3 and 2.5 mm. "
            "Mooney-Rivlin (density 7200 kg/m^3, the largest pin reaction) exceeds the 0.1 mm "
            "criterion by this effect (converged: false); its time step is converged.")
FILE = "fem_pendulum.json"
LAWS = ("neo-hookean", "mooney-rivlin", "yeoh")
LENGTH = paper.PENDULUM["length"]
GRAVITY = paper.GRAVITY
T_END = paper.PENDULUM_T_END
CRITERION_M = 1e-4
TOLERANCE_FACTOR = 2.0
TOLERANCE_FLOOR_M = 5e-6
# The gold base: 4 cells across (140 x 4 Q2, cells 2.5 x 1.25 mm), dt = 1 ms,
# generalized-alpha rho_inf = 0.8 (the ANCF scene's); see reports/reference_fem.md.
GOLD_CELLS_HEIGHT = 4
GOLD_ASPECT = 2.0
GOLD_DT = 1e-3
GOLD_RHO_INF = 0.8


def pendulum_dict(law: str, model: str, dt: float = GOLD_DT, cells_height: int = GOLD_CELLS_HEIGHT,
                  aspect: float = GOLD_ASPECT, t_end: float = T_END, integrator: str = "generalized-alpha",
                  rho_inf: float = GOLD_RHO_INF, stiffness_scale: float = 1.0, output_times=None,
                  **analysis) -> dict:
    """The pendulum scene (as a TOML-like dict) for ``law`` in the continuum ``model``."""
    d = paper.pendulum_scene(law, model, dt, rho_inf=rho_inf, t_end=t_end, integrator=integrator,
                             stiffness_scale=stiffness_scale, name=f"pendulum-{law}-{model}-fem",
                             fem={"cells_height": cells_height, "aspect": aspect}, **analysis)
    if output_times is not None:
        d["analysis"]["output_times"] = list(output_times)
    return d


def energy_bound(law: str) -> float:
    """1e-3 m g L / 2 (J): the issue's bound on |E(t) - E(0)| for conservative settings."""
    return 1e-3 * paper.pendulum_mass(law) * GRAVITY * LENGTH / 2


def run_case(d: dict, energy_every_step: bool = False) -> dict:
    """Run one scene dict; return its record (plain JSON types)."""
    from contract.record import sanitize
    from contract.scene import scene_from_dict

    from reference_fem.simulation import run_dynamic, run_scene
    from reference_fem.settings import fem_settings

    scene = scene_from_dict(d)
    if energy_every_step:
        return sanitize(run_dynamic(scene, fem_settings(scene), energy_every_step=True))
    return sanitize(run_scene(scene))


def _pool_map(dicts: list[dict], workers: int) -> list[dict]:
    if workers <= 1 or len(dicts) == 1:
        return [run_case(d) for d in dicts]
    import concurrent.futures as cf
    import multiprocessing as mp

    with cf.ProcessPoolExecutor(max_workers=workers, mp_context=mp.get_context("spawn")) as ex:
        return list(ex.map(run_case, dicts))


def tip_array(rec: dict) -> np.ndarray:
    """(n, 3) array of t, x, y from a record's tip_history."""
    return np.array([[h["t"], h["x"], h["y"]] for h in rec["tip_history"]])


def differences(base: dict, other: dict) -> list[float] | None:
    """|r_other(t) - r_base(t)| (m) at the base's output times, or None if either failed."""
    if base["status"] != "converged" or other["status"] != "converged":
        return None
    a, b = tip_array(base), tip_array(other)
    if a.shape != b.shape or not np.allclose(a[:, 0], b[:, 0]):
        return None
    return [float(x) for x in np.hypot(*(b[:, 1:] - a[:, 1:]).T)]


def _summary(rec: dict) -> dict:
    e = [x["total"] for x in rec["energy"]] if rec.get("energy") else []
    return {k: rec.get(k) for k in ("status", "reason", "ndof", "steps", "rejected_steps",
                                    "newton_iterations", "wall_s", "setup_s", "fem")} | {
        "tip_history": rec.get("tip_history"), "energy": rec.get("energy"),
        "energy_drift_J": max(abs(x - e[0]) for x in e) if e else None}


def convergence_case(law: str, model: str, dt: float = GOLD_DT, cells_height: int = GOLD_CELLS_HEIGHT,
                     aspect: float = GOLD_ASPECT, workers: int = 2, **kw) -> dict:
    """Base run, dt / 2 and one mesh refinement; differences, estimate, tolerances."""
    base, half, fine = convergence_scenes(law, model, dt, cells_height, aspect, **kw)
    return estimate_case(law, model, base, dt, *_pool_map([base, half, fine], workers))


def convergence_scenes(law: str, model: str, dt: float = GOLD_DT, cells_height: int = GOLD_CELLS_HEIGHT,
                       aspect: float = GOLD_ASPECT, **kw) -> tuple[dict, dict, dict]:
    """The three runs of a case: the base, dt / 2, and twice the cells in each direction."""
    return (pendulum_dict(law, model, dt, cells_height, aspect, **kw),
            pendulum_dict(law, model, dt / 2, cells_height, aspect, **kw),
            pendulum_dict(law, model, dt, 2 * cells_height, aspect, **kw))


def estimate_case(law: str, model: str, base: dict, dt: float, r_base: dict, r_half: dict, r_fine: dict) -> dict:
    """A case from the records of its three runs (:func:`convergence_scenes`): the base's
    tip history, the changes under dt / 2 and under refinement, the error estimate
    e(t) = 4/3 d_dt + 2 d_h, the tolerances and the convergence verdict."""
    d_dt, d_h = differences(r_base, r_half), differences(r_base, r_fine)
    case = {"law": law, "continuum_model": model, "incompressibility": r_base.get("incompressibility"),
            "scene": base, "dt": dt, "fem": r_base.get("fem"), "ndof": r_base.get("ndof"),
            "status": r_base["status"], "reason": r_base.get("reason"),
            "runs": {"base": _summary(r_base), "half_dt": _summary(r_half), "refined_mesh": _summary(r_fine)}}
    if d_dt is None or d_h is None:
        case.update(converged=False, tip_history=None, values=None)
        return case
    ts = [h["t"] for h in r_base["tip_history"]]
    est = [4.0 / 3.0 * a + 2.0 * b for a, b in zip(d_dt, d_h)]
    values = [{"t": h["t"], "x": h["x"], "y": h["y"],
               "tolerance_m": max(TOLERANCE_FACTOR * e, TOLERANCE_FLOOR_M)}
              for h, e in zip(r_base["tip_history"], est)]
    later = [i for i, t in enumerate(ts) if t > 0]
    case.update(
        tip_history=r_base["tip_history"], values=values,
        configurations=r_base.get("configurations"),
        change_half_dt_m=d_dt, change_refined_mesh_m=d_h, error_estimate_m=est,
        max_change_m=max(max(d_dt[i], d_h[i]) for i in later),
        converged=all(d_dt[i] < CRITERION_M and d_h[i] < CRITERION_M for i in later),
        energy_bound_J=energy_bound(law))
    return case


def write_pendulum_gold(out_dir: Path, models=("plane-stress", "plane-strain"), workers: int = 2,
                        progress=None) -> Path:
    from reference_fem.dolfinx_backend.fem import VERSION

    out_dir = Path(out_dir)
    path = out_dir / FILE
    cases = {}
    for model in models:
        for law in LAWS:
            t0 = time.perf_counter()
            case = convergence_case(law, model, workers=workers)
            cases[f"{law}/{model}"] = case
            if progress:
                progress(f"{law}/{model}: {case['status']}, converged {case['converged']}, "
                         f"max change {case.get('max_change_m', math.nan) * 1e3:.4f} mm "
                         f"({time.perf_counter() - t0:.0f} s)")
    doc = {
        "description": "The paper's flexible pendulum (Example 2) as a 2D continuum (Q2 "
                       "quadrilaterals; plane stress: F33 = 1/det F; plane strain: exactly "
                       "incompressible Taylor-Hood Q2/Q1), pinned at the centre of the left "
                       "face, released from horizontal at rest: position (m) of the free-end "
                       "centre point at t = 0, 0.1, ..., 0.5 s (pin at the origin, beam along "
                       "+x at t = 0). Regenerate: python -m studies continuum gold --pendulum",
        "generator": "python -m studies continuum gold --pendulum",
        "dolfinx": VERSION, "units": "m, s, J",
        "integrator": {"name": "generalized-alpha", "rho_inf": GOLD_RHO_INF},
        "mesh": {"cells_height": GOLD_CELLS_HEIGHT, "aspect": GOLD_ASPECT}, "dt": GOLD_DT,
        "criterion_m": CRITERION_M,
        "pin": PIN_NOTE,
        "comparison": __doc__.split("Error estimate")[1].strip(),
        "how_to_compare": "for each case and value: |r(t) - (x, y)| <= tolerance_m is "
                          "agreement with the continuum within its own error; the ANCF target "
                          "is |r(t) - (x, y)| <= 1 mm at t = 0.1 ... 0.5 s (plane stress).",
        "cases": cases,
    }
    out_dir.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".json.tmp")
    tmp.write_text(json.dumps(doc, indent=1) + "\n")
    tmp.replace(path)
    return path


def render(path: Path) -> str:
    """Markdown tables of the pendulum gold file (for reports/reference_fem.md)."""
    gold = json.loads(Path(path).read_text())
    out = [f"Gold file: generalized-alpha rho_inf = {gold['integrator']['rho_inf']}, dt = "
           f"{gold['dt'] * 1e3:g} ms, {gold['mesh']['cells_height']} Q2 cells across "
           f"(aspect {gold['mesh']['aspect']:g}); DOLFINx {gold['dolfinx']}.", ""]
    out.append("| case | t (s) | x (mm) | y (mm) | change dt/2 (mm) | change mesh/2 (mm) | tolerance (mm) |")
    out.append("|---|---|---|---|---|---|---|")
    for key, c in gold["cases"].items():
        if not c.get("values"):
            out.append(f"| {key} | - | failed: {c.get('reason')} | | | | |")
            continue
        for v, a, b in zip(c["values"], c["change_half_dt_m"], c["change_refined_mesh_m"]):
            if v["t"] == 0:
                continue
            out.append(f"| {key} | {v['t']:.1f} | {v['x'] * 1e3:.3f} | {v['y'] * 1e3:.3f} | "
                       f"{a * 1e3:.4f} | {b * 1e3:.4f} | {v['tolerance_m'] * 1e3:.4f} |")
    out += ["", "| case | run | cells | ndof | steps | Newton its | rejected | wall s | energy drift (J) | bound (J) |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for key, c in gold["cases"].items():
        for name, r in c["runs"].items():
            f = r.get("fem") or {}
            drift = r.get("energy_drift_J")
            out.append(f"| {key} | {name} | {f.get('cells_length')} x {f.get('cells_height')} | {r['ndof']} | "
                       f"{r['steps']} | {r['newton_iterations']} | {r['rejected_steps']} | "
                       f"{(r['wall_s'] or 0):.1f} | {'-' if drift is None else f'{drift:.2e}'} | "
                       f"{c.get('energy_bound_J') or 0:.2e} |")
    return "\n".join(out) + "\n"
