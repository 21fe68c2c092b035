"""The continuum reference of the work-precision's second scene: the paper's pendulum
(Yeoh, plane stress, pinned at the centre of the left face, released from horizontal at
rest, 0.5 s) with a thick cross-section, h = 20 mm (L / h = 17.5), where transverse shear
and the cross-section's own deformation are no longer negligible and the cable's
Euler-Bernoulli, linear-elastic physics differs from the continuum's.

    .venv/bin/python -m studies peers thick-reference [--cells-height 8] [--dt 1e-3]
        [--reuse FILE ...]

The DOLFINx plane-stress model of ``reference_fem`` (the one that produced
tests/gold/fem_pendulum.json, see :mod:`studies.verification.continuum_gold.pendulum`: Q2 cells of aspect
2, generalized-alpha rho_inf = 0.8), run on three meshes, c, 2c and 4c cells across the
height at dt, and on the middle mesh at dt / 2. d_dt: the middle mesh's change when dt is
halved; d_h: the change from the middle to the finest mesh; r: the observed contraction
of the mesh changes, max_t d_h / max_t d_h' with d_h' the change from the coarsest to the
middle mesh (Richardson: r = 1/2 for first order, 1/4 for second).

- r < 0.8 (the mesh error contracts): the reference is the finest run, its error
  e(t) = 4/3 d_dt(t) + d_h(t) r / (1 - r).
- r >= 0.8 (it does not): the pin. The continuum's pin is the centre node of the left
  face, a point support, a logarithmic singularity in 2D: each halving of the cells
  halves the pin and moves the tip by the same vector, so the tip has no mesh limit; a
  pin has to be given a size. The reference is then the middle run, whose cells (and so
  pin) are 1.25 mm high at c = 8, the cell height of the slender pendulum's gold
  (tests/gold/fem_pendulum.json), and e(t) = 4/3 d_dt(t) + d_h(t): the time error plus
  the change of one halving of the pin (a pin between about half and twice that size).

The file also keeps runs on c / 4 and c / 2 cells across (pins of 10 and 5 mm at c = 8):
with the others, the pin-size sweep of :func:`pin_references`. It keeps every run, the
changes, r, which rule applied and e(t):
``reports/data/peers/thick-pendulum-reference.json``. ``--reuse`` takes runs (same
scene, cells and dt) from earlier files of this command instead of recomputing them.
"""
from __future__ import annotations

import json
import time
from pathlib import Path

from studies.verification.continuum_gold.pendulum import differences, pendulum_dict, run_case

ROOT = Path(__file__).resolve().parents[2]
HEIGHT = 0.020                                       # m
PATH = ROOT / "reports" / "data" / "peers" / "thick-pendulum-reference.json"
LAW, MODEL = "yeoh", "plane-stress"
T_END = 0.5                                          # s, the pendulum's
LENGTH = 0.350                                       # m


def scene(dt: float, cells_height: int, aspect: float = 2.0, rho_inf: float = 0.8) -> dict:
    d = pendulum_dict(LAW, MODEL, dt, cells_height, aspect, rho_inf=rho_inf)
    d["beam"]["height"] = HEIGHT
    d["name"] = f"pendulum-thick-h{HEIGHT * 1e3:g}mm-{LAW}-{MODEL}-fem"
    return d


def _key(run: dict) -> tuple[int, float]:
    return run["fem"]["cells_height"], round(T_END / run["steps"], 12)


def compute(dt: float, cells_height: int, aspect: float = 2.0, reuse: list[Path] = ()) -> dict:
    have = {}
    for f in reuse:
        for r in json.loads(Path(f).read_text())["runs"].values():
            f_ = r.get("fem") or {}
            if (r.get("status") == "converged" and f_.get("cells_length")     # aspect = L c_h / (c_l h)
                    and abs(LENGTH * f_["cells_height"] / (f_["cells_length"] * HEIGHT) - aspect) < 1e-9 * aspect):
                have[_key(r)] = r
    c = cells_height
    plan = {"coarse": (c, dt), "middle": (2 * c, dt), "middle_half_dt": (2 * c, dt / 2), "fine": (4 * c, dt),
            # the pin-size sweep (pin_references): coarser meshes, larger pins
            "pin_quarter": (max(c // 4, 1), dt), "pin_half": (max(c // 2, 1), dt)}
    runs = {}
    for name, (cells, step) in plan.items():
        t0 = time.perf_counter()
        r = have.get((cells, round(step, 12)))
        if r is None:
            r = run_case(scene(step, cells, aspect))
            r = {k: r.get(k) for k in ("status", "reason", "ndof", "steps", "newton_iterations", "wall_s", "fem",
                                       "tip_history")}
        runs[name] = r
        print(f"{name} ({cells} across, dt {step:g}): {r['status']} ndof {r.get('ndof')} "
              f"({time.perf_counter() - t0:.0f} s)", flush=True)
    fine = runs["fine"]
    d_dt = differences(runs["middle"], runs["middle_half_dt"])
    d_h = differences(runs["middle"], fine)
    d_h0 = differences(runs["coarse"], runs["middle"])
    out = {"description": __doc__.split("\n\n")[0].replace("\n", " "),
           "generator": "python -m studies peers thick-reference", "units": "m, s",
           "law": LAW, "continuum_model": MODEL, "height_m": HEIGHT, "dt": dt,
           "mesh": {"cells_height": 4 * c, "aspect": aspect}, "scene": scene(dt, 4 * c, aspect),
           "status": fine["status"], "runs": runs}
    if d_dt is None or d_h is None or d_h0 is None:
        return out | {"status": "failed", "reason": "a convergence run failed", "tip_history": None}
    r = max(d_h) / max(d_h0) if max(d_h0) > 0 else 0.0
    if r < 0.8:
        ref, rule = "fine", "Richardson: the mesh error contracts; reference = finest mesh"
        est = [4.0 / 3.0 * a + b * r / (1 - r) for a, b in zip(d_dt, d_h)]
    else:
        ref = "middle"
        rule = (f"the mesh changes do not contract (r = {r:.3f}): the point pin's logarithmic singularity; "
                f"reference = middle mesh (pin {1e3 * HEIGHT / (2 * c):g} mm), estimate = time error + one pin halving")
        est = [4.0 / 3.0 * a + b for a, b in zip(d_dt, d_h)]
    out["mesh"]["cells_height"] = runs[ref]["fem"]["cells_height"]
    out["scene"] = scene(dt, runs[ref]["fem"]["cells_height"], aspect)
    return out | {"status": runs[ref]["status"], "reference_run": ref, "rule": rule,
                  "tip_history": runs[ref]["tip_history"], "change_half_dt_m": d_dt, "change_refined_mesh_m": d_h,
                  "change_coarse_to_middle_m": d_h0, "contraction": r, "error_estimate_m": est,
                  "max_error_estimate_m": max(est)}


def reference(path: Path = PATH) -> dict[float, tuple[float, float]] | None:
    """{t: (x, y)} of the thick pendulum's continuum reference, None without it."""
    if not Path(path).exists():
        return None
    g = json.loads(Path(path).read_text())
    if g.get("status") != "converged" or not g.get("tip_history"):
        return None
    return {round(h["t"], 9): (h["x"], h["y"]) for h in g["tip_history"]}


def pin_references(path: Path = PATH) -> dict[float, dict[float, tuple[float, float]]]:
    """{pin size (m, the cell height): {t: (x, y)}} of every run at the reference's dt: the
    same continuum with pins from h / 2 down (the point pin's size is its cell's)."""
    if not Path(path).exists():
        return {}
    g = json.loads(Path(path).read_text())
    return {HEIGHT / r["fem"]["cells_height"]: {round(h["t"], 9): (h["x"], h["y"]) for h in r["tip_history"]}
            for r in g["runs"].values()
            if r.get("status") == "converged" and abs(T_END / r["steps"] - g["dt"]) < 1e-12 and r.get("tip_history")}


def error_estimate(path: Path = PATH) -> float | None:
    """The reference's largest error estimate (m), None without it."""
    if not Path(path).exists():
        return None
    return json.loads(Path(path).read_text()).get("max_error_estimate_m")
