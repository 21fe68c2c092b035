"""Benchmarks: tables of measured times (medians of warm runs in one process).

    python -m studies bench table3    # the twelve ANCF cells of the paper's Table 3
    python -m studies bench penalty   # static convergence over alpha = 10..1e5 C10
    python -m studies bench pendulum  # the paper's Table 4 grid, each case at its converged step
    python -m studies bench kernels   # us per element per force / tangent call (Chrono's form),
                                      # every element x law x formulation, and Exudyn's cable;
                                      # writes reports/kernels.csv and reports/kernels.md

Speed is measured here, never asserted in tests.
"""
from __future__ import annotations

import csv
import io
import itertools
import statistics
import sys
import time
from pathlib import Path

import numpy as np

from ancf.build import build_model, plan
from ancf.checks.element import runs
from ancf.kinematics.kernels import element_assemble, element_work
from ancf.elements import ELEMENTS
from ancf.kinematics.section.kernels import live_tape
from ancf.simulation import run_scene
from contract import paper
from contract.scene import FORMULATIONS, load_scene, scene_from_dict
from mechanics.laws import LAWS
from reference_fem.launch import scene_toml

from ..common.pendulum_cases import LADDER, converged_rung, describe_dynamic, ladder, pendulum_dict
from ..peers.compare import PEER_SCRIPT, peer_scene, pendulum_scene
from ..peers.venv import PEER_PYTHON, run_peer_script

# The setting that reproduces the paper's Table 3 (README, "Reproducing Table 3").
PAPER_SETTING = {"quadrature": (2, 2), "clamp": "all"}


def paper_cells() -> list[tuple[str, str]]:
    """(element, law) of the paper's Table 3 ANCF cells, in its order."""
    return [k for k in paper.table3() if k[0] != "ABAQUS"]


def _timed(scene, repeats: int):
    run_scene(scene)                                   # warm-up: caches, imports
    recs = [run_scene(scene)[0] for _ in range(repeats)]
    return recs[-1], statistics.median(r["wall_s"] for r in recs)


def table3(repeats: int = 5) -> float:
    print(f"Table 3 cells, `paper` formulation, quadrature {PAPER_SETTING['quadrature']}, "
          f"clamp '{PAPER_SETTING['clamp']}'; wall time = median of {repeats} warm runs, one process")
    print(f"{'element':8s} {'n':>4s} {'law':14s} {'ndof':>5s} {'steps':>5s} {'newton':>6s} "
          f"{'ux mm':>8s} {'paper':>8s} {'uy mm':>8s} {'paper':>8s} {'wall s':>7s}")
    total = 0.0
    for element, law in paper_cells():
        ref = paper.table3()[(element, law)]
        s = scene_from_dict(paper.cantilever_scene(law, "paper", element, ref["elements"], **PAPER_SETTING))
        rec, wall = _timed(s, repeats)
        total += wall
        tip = rec["tip"] or {"ux": float("nan"), "uy": float("nan")}
        print(f"{element:8s} {ref['elements']:4d} {law:14s} {rec['ndof']:5d} {rec['load_steps']:5d} "
              f"{rec['newton_iterations']:6d} {tip['ux'] * 1e3:8.2f} {ref['ux'] * 1e3:8.2f} "
              f"{tip['uy'] * 1e3:8.2f} {ref['uy'] * 1e3:8.2f} {wall:7.3f}")
    print(f"total wall time of the twelve cells: {total:.2f} s (target < 1 s)")
    return total


def penalty(elements=(16, 160, 640), factors=(1e1, 1e2, 1e3, 1e4, 1e5)) -> bool:
    """Does every static solve converge for alpha = factor * C10, and how many load
    steps does it need? (default quadrature (3, 2), face clamp)"""
    print("Static cantilever under gravity over the penalty range; "
          "cells: accepted load steps (+rejected) / stable, or FAILED")
    ok = True
    for form, n in itertools.product(("paper", "plane-strain"), elements):
        print(f"\n{form}, {n} elements")
        print(f"{'element':8s} {'law':14s} " + " ".join(f"{f'a={f:.0e}C10':>16s}" for f in factors))
        for element, law in paper_cells():
            cells = []
            for f in factors:
                alpha = f * paper.materials()[law]["C10"]
                t0 = time.perf_counter()
                rec, _ = run_scene(scene_from_dict(paper.cantilever_scene(law, form, element, n, penalty=alpha)))
                dt = time.perf_counter() - t0
                if rec["status"] != "converged":
                    ok = False
                    cells.append("FAILED")
                else:
                    mark = {True: "", False: "!", None: "?"}[rec["stable"]]
                    cells.append(f"{rec['load_steps']}(+{rec['rejected_steps']}){mark} {dt:5.1f}s")
            print(f"{element:8s} {law:14s} " + " ".join(f"{c:>16s}" for c in cells))
            sys.stdout.flush()
    print("\n'!': converged to a state whose tangent is not positive definite (unstable or a "
          "zero-energy mode); '?': stability undetermined (lowest eigenvalue within round-off); "
          "see README.")
    return ok


def converged_step(element, n, formulation, rho_inf=0.5, dt0=LADDER["dt0"], tol=LADDER["tol"],
                   dt_floor=LADDER["dt_floor"]):
    """The converged step of Table 4's rule (:func:`studies.common.pendulum_cases.converged_rung`),
    running the ladder only as far as needed; returns (dt, difference in m)."""
    rungs = []
    for dt in ladder(dt0, dt_floor):
        rec = run_scene(scene_from_dict(pendulum_dict(element, n, formulation, dt, rho_inf)))[0]
        rungs.append(describe_dynamic(rec))
        rung, diff = converged_rung(rungs[-2:], tol)
        if rung is not None:
            return rung["dt"], diff
    return None, None


def pendulum(repeats: int = 5, rho_inf: float = 0.5, formulations=("plane-stress", "paper")) -> None:
    print(f"Table 4 grid: pendulum (Yeoh, 0.5 s), generalized-alpha rho_inf = {rho_inf}; each case "
          f"at its converged step (largest dt whose tip positions are within 0.1 mm of the dt/2 "
          f"run); wall time = median of {repeats} warm runs, one process, one thread; the "
          f"paper's CPU time on an i5-5200U for comparison")
    for form in formulations:
        print(f"\n{form}")
        print(f"{'element':8s} {'n':>3s} {'ndof':>5s} {'dt ms':>6s} {'steps':>6s} {'newton':>6s} "
              f"{'wall s':>7s} {'paper s':>8s} {'paper/ours':>10s}")
        cells = paper.table4()
        order = list(dict.fromkeys(el for el, _ in cells))
        for element, n in sorted(cells, key=lambda k: (order.index(k[0]), k[1])):
            dt, _ = converged_step(element, n, form, rho_inf)
            paper_s = paper.table4()[(element, n)]
            if dt is None:
                print(f"{element:8s} {n:3d}  no converged step above 0.1 ms")
                continue
            rec, wall = _timed(scene_from_dict(pendulum_dict(element, n, form, dt, rho_inf)), repeats)
            print(f"{element:8s} {n:3d} {rec['ndof']:5d} {dt * 1e3:6.3f} {rec['steps']:6d} "
                  f"{rec['newton_iterations']:6d} {wall:7.3f} {paper_s:8.1f} {paper_s / wall:10.0f}")
            sys.stdout.flush()


REPORTS = Path(__file__).resolve().parents[2] / "reports"
KERNEL_ELEMENTS = 32          # the pendulum's mesh (make bench-peers), 0.35 m
KERNEL_FIELDS = ("solver", "element", "law", "formulation", "elements", "points_per_element", "calls", "repeats",
                 "force_us_per_element", "tangent_us_per_element", "force_spread", "tangent_spread", "what")


def _kernel_material(law: str, form: str) -> dict:
    """The law's constants: the paper's for its three laws, the scene file's for another
    (``scenes/cantilever-<law>.toml``) with the paper's penalty where the formulation has one."""
    if law in paper.materials():
        return paper.material_table(law, form)
    m = dict(load_scene(REPORTS.parent / "scenes" / f"cantilever-{law}.toml").to_dict()["material"])
    m["formulation"] = form
    if FORMULATIONS[form]:
        m.setdefault("penalty", paper.PENALTY)
    return m


def _per_call(f, calls: int, repeats: int) -> list[float]:
    for _ in range(10):                                  # warm-up
        f()
    out = []
    for _ in range(repeats):
        t0 = time.thread_time()
        for _ in range(calls):
            f()
        out.append((time.thread_time() - t0) / calls)
    return out


def kernel_rows(calls: int = 100, repeats: int = 10, elements: int = KERNEL_ELEMENTS,
                only: tuple[str, str, str] | None = None) -> list[dict]:
    """Chrono's ANCF benchmark form for our compiled kernel (:func:`ancf.kinematics.kernels.element_assemble`,
    the step loop's): microseconds per element per internal-force call and per tangent
    call (force and tangent in one pass: the step loop never needs the tangent alone),
    for every registered element x law x formulation, on the pendulum's mesh at a
    deformed state (u = 1e-4 m x a fixed random vector, alpha_f = 0); warm-up, then
    ``repeats`` x ``calls`` calls in thread CPU time, the median over the repeats;
    spread = (max - min) / median. ``only``: one (element, law, formulation)."""
    rows = []
    combos = [only] if only else [c for c in itertools.product(sorted(ELEMENTS), sorted(LAWS), FORMULATIONS)
                                  if runs(c[0], c[2])]            # a cable: plane stress alone
    for element, law, form in combos:
        d = pendulum_dict(element, elements, form, 1e-3, 0.5)
        d["material"] = _kernel_material(law, form)
        model = build_model(plan(scene_from_dict(d)))
        n = model.mesh.n_dof
        u = 1e-4 * np.random.default_rng(0).standard_normal(n)
        times = {}
        dN, w, dofs, ops, consts, pr, _ = model.fused
        ops, consts = live_tape(ops, consts)
        f, K = np.empty(n), np.empty((n, model.mesh.bandwidth + 1))
        scratch = element_work(ops, dN, pr)
        for name, tangent in (("force", False), ("tangent", True)):
            def call():
                return element_assemble(u, u, 0.0, dN, w, dofs, ops, consts, pr, f, K, tangent, *scratch)
            if call() != 0:
                raise RuntimeError(f"{element} {law} {form}: det F <= 0 at the benchmark state")
            times[name] = _per_call(call, calls, repeats)
        ne = model.mesh.n_elements
        row = {"solver": "ours", "element": element, "law": law, "formulation": form, "elements": ne,
               "points_per_element": len(model.rule.weight), "calls": calls, "repeats": repeats, "what": "compiled"}
        for name, ts in times.items():
            med = statistics.median(ts)
            row[f"{name}_us_per_element"] = round(med * 1e6 / ne, 4)
            row[f"{name}_spread"] = round((max(ts) - min(ts)) / med, 3)
        rows.append(row)
    return rows


def exudyn_kernel_row(elements: int = KERNEL_ELEMENTS) -> dict | None:
    """Exudyn's cable in the same form (:func:`studies.peers.exudyn_pendulum.kernel_times`, on
    the compared pendulum with ``elements`` cables), or None when .venv-peers is missing."""
    if not PEER_PYTHON.exists():
        return None
    d = pendulum_scene(1e-3, 0.8)
    d["ancf"]["elements"] = elements
    out = run_peer_script(PEER_SCRIPT, ["--kernels"], PEER_PYTHON, scene_toml(peer_scene(d)))
    row = {"solver": f"Exudyn {out['exudyn']}", "element": "ANCFCable2D", "law": "linear elastic",
           "formulation": "Euler-Bernoulli", "elements": out["elements"], "points_per_element": "",
           "calls": out["calls"], "repeats": out["repeats"],
           "what": "exudyn"}
    for name in ("force", "tangent"):
        ts = out[name]["us_per_call"]
        med = statistics.median(ts)
        row[f"{name}_us_per_element"] = round(out[name]["us_per_element"], 4)
        row[f"{name}_spread"] = round((max(ts) - min(ts)) / med, 3)
    return row


KERNELS = {
    "compiled": "`ancf.kinematics.kernels.element_assemble`, the compiled step and static loops' kernel (force and "
                "tangent in one pass; `ancf.kinematics.section.kernels.assemble_fused` for a continuum-based element, "
                "`ancf.kinematics.cable.kernels.cable_assemble` for a cable)",
    "exudyn": "`MainSolverImplicitSecondOrder.ComputeODE2RHS` / `ComputeJacobianODE2RHS` called from "
              "Python: the whole system (the gravity loads and the Python call included) per element; "
              "Exudyn exposes no single element's force",
}


def kernel_markdown(rows: list[dict]) -> str:
    """reports/kernels.md from the rows of reports/kernels.csv (a plain function: records
    in, markdown out)."""
    lines = ["# Kernel times in Chrono's form", "",
             "Generated by `python -m studies bench kernels` (in `make bench`) from `kernels.csv`; "
             "do not edit. Microseconds per element per call, warm: 10 untimed calls, then "
             "repeats x calls timed calls, the median over the repeats (spread = (max - min) / median "
             "of the repeats), in the CPU time of the calling thread (`time.thread_time`: time the thread "
             "waits for a core on a loaded machine is not counted). Ours: on the pendulum's mesh at a "
             "deformed state; the tangent call computes the force too (the loops never need the "
             "tangent alone). "
             "Times depend on the machine and its load (measured on a shared 2-core machine); "
             "compare rows of one run.", ""]
    for solver in dict.fromkeys(r["solver"] for r in rows):
        sub = [r for r in rows if r["solver"] == solver]
        lines += [f"## {solver}", "", f"{sub[0]['elements']} elements, {sub[0]['repeats']} x {sub[0]['calls']} "
                  "calls. Kernel: " + "; ".join(f"{k}: {KERNELS.get(k, k)}" for k in dict.fromkeys(r["what"] for r in sub))
                  + ".", "",
                  "| element | law | formulation | kernel | points | force us/el | spread | force+tangent us/el | spread |",
                  "|---|---|---|---|---:|---:|---:|---:|---:|"]
        for r in sub:
            lines.append(f"| {r['element']} | {r['law']} | {r['formulation']} | {r['what']} | {r['points_per_element']} | "
                         f"{float(r['force_us_per_element']):.3f} | {float(r['force_spread']):.2f} | "
                         f"{float(r['tangent_us_per_element']):.3f} | {float(r['tangent_spread']):.2f} |")
        lines.append("")
    return "\n".join(lines)


def kernels(out: Path = REPORTS) -> list[dict]:
    rows = kernel_rows()
    peer = exudyn_kernel_row()
    if peer is not None:
        rows.append(peer)
    buf = io.StringIO()
    wr = csv.DictWriter(buf, fieldnames=KERNEL_FIELDS, lineterminator="\n")
    wr.writeheader()
    wr.writerows(rows)
    (out / "kernels.csv").write_text(buf.getvalue())
    with open(out / "kernels.csv") as fh:                 # the table from the file, as the audit reads it
        (out / "kernels.md").write_text(kernel_markdown(list(csv.DictReader(fh))))
    print((out / "kernels.md").read_text())
    return rows


def add_commands(sub) -> None:
    """The ``bench`` command on the sub-parsers of ``python -m studies`` (``make bench``,
    ``make bench-penalty``)."""
    p = sub.add_parser("bench", help="timings: the paper's Table 3 cells, the penalty sweep, the Table 4 grid, the "
                                     "compiled kernels (make bench)")
    p.add_argument("which", choices=("table3", "penalty", "pendulum", "kernels", "all"), nargs="?", default="table3")
    p.add_argument("--repeats", type=int, default=5)


def command(a) -> int:
    """The ``bench`` command: the benchmark ``a.which`` (module doc)."""
    if a.which in ("table3", "all"):
        table3(a.repeats)
    if a.which in ("pendulum", "all"):
        pendulum(a.repeats)
    if a.which in ("kernels", "all"):
        kernels()
    if a.which in ("penalty", "all"):
        return 0 if penalty() else 1
    return 0

