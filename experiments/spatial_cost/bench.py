"""What 1 % and 0.1 % cost in 3D: the spatial ANCF elements beside the 3D continuum, timed
side by side in one process on the same machine.

    .venv/bin/python experiments/spatial_cost/bench.py [--case end-force|twist] [--repeats N] [--record FILE]
    .venv/bin/python experiments/spatial_cost/bench.py --table FILE

Two cases of the paper's 160 x 5 x 7 mm bar, neo-Hookean, each against its converged
continuum reference (the Richardson values of experiments/spatial_end_force, continuum.jsonl,
and experiments/spatial_finite_torsion, summary.py's references):

- ``end-force``: the clamped cantilever under a 0.03 N end force (the tip's |u - u_ref| / |u_ref|);
  the continuum on the 3D gold's graded Q2/Q1 meshes 16 x 1 x 1 and 32 x 2 x 2, the elements
  graded 1.25 from the clamp;
- ``twist``: the bar turned half a turn between rigid plates (the torque's error); the continuum
  on 32 cells along and 4, 5, 6 across, the elements graded 1.4 from both plates.

Each run is timed whole (the continuum's mesh, set-up and solve; the element's beam, load and
solve), warm (one untimed run of each kind first: compiled forms, tables), the median of
``--repeats`` runs where a run takes under a minute, one run otherwise. The table prints every
run with its error; the summary the cheapest run of each kind within 1 % and within 0.1 %
from which every finer run of its family stays within (a coarse mesh that crosses the
reference by chance does not count), and their ratio. The spatial elements run numpy (no
compiled kernel); the continuum runs DOLFINx on one process. ``--record FILE`` appends the
runs to FILE; ``--table FILE`` prints the tables of a recorded run without running.
"""
from __future__ import annotations

import argparse
import importlib.util
import json
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
EXP = HERE.parent


def _load(name: str, path: Path):
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod


# the trial-element parser first, under the name the other runners import it by
_load("run", EXP / "spatial_cantilever" / "run.py")
END_FORCE = _load("end_force_run", EXP / "spatial_end_force" / "run.py")
TORSION = _load("finite_torsion_run", EXP / "spatial_finite_torsion" / "run.py")
TORSION_SUMMARY = _load("finite_torsion_summary", EXP / "spatial_finite_torsion" / "summary.py")

LAW = "neo-hookean"
LONG = 60.0           # s: a run this long is timed once


def end_force_runs():
    """The warm-up runs and the timed ones, each (kind, label, run), run() -> (error, seconds)."""
    from ancf.kinematics.spatial.beam import SpatialBeam
    from ancf.kinematics.spatial.statics import clamp_rows, end_face_load, solve_static
    from contract import paper
    from contract.loads import end_traction
    from reference_fem.simulation import run_scene
    from studies.verification.continuum_gold.cantilever import base_settings_3d

    g = END_FORCE.reference(LAW)["tip"]
    u_ref = np.array([g["ux"], g["uy"]])
    sc = END_FORCE.scene(LAW)
    base = base_settings_3d("mixed")

    def continuum(k):
        def run():
            t0 = time.perf_counter()
            rec = run_scene(sc, base.refined(2 ** k))
            t = rec["tip"]
            return float(np.linalg.norm([t["ux"], t["uy"]] - u_ref) / np.linalg.norm(u_ref)), time.perf_counter() - t0
        s = base.refined(2 ** k)
        return ("continuum", f"DOLFINx {s.cells_length} x {s.cells_height} x {s.cells_width}", run)

    c = {k: v for k, v in paper.materials()[LAW].items() if k != "density"}
    L, h, w = paper.CANTILEVER["length"], paper.CANTILEVER["height"], paper.CANTILEVER["width"]
    traction = end_traction((0.0, -END_FORCE.FORCE, 0.0), h, w)

    def element(name, n):
        from run import element as named

        def run():
            t0 = time.perf_counter()
            b = SpatialBeam(named(name), L, h, w, n, LAW, c, paper.PENALTY, None, 1.25)
            res = solve_static(b, end_face_load(b, lambda y, z: np.tile(traction, (y.size, 1))), clamp_rows(b))
            tip = res.tip(b)
            return float(np.linalg.norm([tip["ux"], tip["uy"]] - u_ref) / np.linalg.norm(u_ref)), time.perf_counter() - t0
        return ("ANCF", f"{name} x {n}, graded 1.25", run)

    return ([continuum(0), element("HS2n-96p", 4)],
            [continuum(0), continuum(1), element("HS2n-96p", 4), element("HS2n-96p", 8), element("HS2n-96p", 12),
             element("HS2n-180p", 8), element("HS2n-180p", 12), element("HS2n-180p", 16),
             element("HS2n-216p", 12), element("HS2n-216p", 16)])


def twist_runs():
    from contract import paper

    ref = TORSION_SUMMARY.references("twist")[(LAW, "mixed", "1.0")]["T"][0]

    def continuum(cells):
        def run():
            r = TORSION.continuum_level(LAW, "mixed", TORSION.settings_for(cells, "mixed"), TORSION.RTOL, "twist")
            return abs(r["reactions"]["1.0"]["T"] / ref - 1.0), r["seconds"]
        return ("continuum", f"DOLFINx {' x '.join(map(str, cells))}", run)

    def element(name, n, grading):
        def run():
            r = TORSION.ancf_run(LAW, name, n, paper.PENALTY, "twist", grading)
            return abs(r["reactions"]["1.0"]["T"] / ref - 1.0), r["seconds"]
        return ("ANCF", f"{name} x {n}, graded {grading:g}", run)

    return ([continuum((16, 1, 1)), element("HS2n-180p", 2, 1.0)],
            [continuum((32, 4, 4)), continuum((32, 5, 5)), continuum((32, 6, 6)),
             element("HS2n-180p", 8, 1.4), element("HS2n-180p", 12, 1.4), element("HS2n-180p", 16, 1.4),
             element("HS2n-216p", 16, 1.4)])


CASES = {"end-force": end_force_runs, "twist": twist_runs}


def bench(case: str, repeats: int) -> list[dict]:
    warm, runs = CASES[case]()
    for _, _, run in warm:              # compiled forms, tables, imports: untimed
        run()
    out = []
    for kind, label, run in runs:
        err, t = run()
        times = [t]
        if t < LONG:
            times += [run()[1] for _ in range(repeats - 1)]
        out.append({"case": case, "kind": kind, "run": label, "error": err,
                    "seconds": statistics.median(times), "repeats": len(times)})
        print(json.dumps(out[-1]), file=sys.stderr, flush=True)
    return out


def family(r: dict) -> str:
    """A run's refinement family: the continuum, or an element at its grading."""
    return "continuum" if r["kind"] == "continuum" else r["run"].split(" x ")[0] + r["run"].split(",")[-1]


def stays(r: dict, rows: list[dict], tol: float) -> bool:
    """``r`` is within ``tol``, and so is every finer run of its family (listed after it): a
    coarse run that crosses the reference by chance does not count."""
    same = [x for x in rows if x["case"] == r["case"] and family(x) == family(r)]
    return all(x["error"] <= tol for x in same[same.index(r):])


def table(rows: list[dict]) -> str:
    lines = ["| case | kind | run | error (%) | seconds (median) | runs |", "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['case']} | {r['kind']} | {r['run']} | {100 * r['error']:.3f} | {r['seconds']:.2f} | "
                     f"{r['repeats']} |")
    lines += ["", "| case | accuracy | cheapest continuum run (s) | cheapest ANCF run (s) | ANCF / continuum |",
              "|---|---|---|---|---|"]
    for case in dict.fromkeys(r["case"] for r in rows):
        for tol in (1e-2, 1e-3):
            best = {}
            for kind in ("continuum", "ANCF"):
                ok = [r for r in rows if r["case"] == case and r["kind"] == kind and stays(r, rows, tol)]
                best[kind] = min(ok, key=lambda r: r["seconds"]) if ok else None
            cells = [f"{b['run']} ({b['seconds']:.2f})" if b else "none of the runs" for b in best.values()]
            ratio = (f"1 / {best['continuum']['seconds'] / best['ANCF']['seconds']:.1f}"
                     if all(best.values()) else "")
            lines.append(f"| {case} | {100 * tol:g} % | {cells[0]} | {cells[1]} | {ratio} |")
    return "\n".join(lines)


def main() -> None:
    a = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    a.add_argument("--case", choices=list(CASES), action="append")
    a.add_argument("--repeats", type=int, default=3)
    a.add_argument("--record", help="append each run as a JSON line to this file")
    a.add_argument("--table", help="print the tables of the runs recorded in this file, and run nothing")
    args = a.parse_args()
    if args.table:
        print(table([json.loads(line) for line in open(args.table)]))
        return
    rows = []
    for case in args.case or list(CASES):
        rows += bench(case, args.repeats)
    if args.record:
        with open(args.record, "a") as f:
            for r in rows:
                f.write(json.dumps(r) + "\n")
    print(table(rows))


if __name__ == "__main__":
    main()
