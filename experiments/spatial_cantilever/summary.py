"""The table of REPORT.md from res.jsonl (run.py's records), as markdown on stdout. The error
is the harness's: |u - u_gold| / |u_gold| over the tip's (ux, uy)."""
from __future__ import annotations

import json
import math
from pathlib import Path

HERE = Path(__file__).resolve().parent

paper_length = 0.16          # m: the runs before graded meshes had equal elements over the paper's length
rows = [json.loads(x) for x in (HERE / "res.jsonl").read_text().splitlines()]
print("| element | law | elements | first element (mm) | dof | rule | penalty (Pa) | loop | tip ux (mm) | tip uy (mm) | error (%) | Newton "
      "iterations (cap per increment) | s |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
key = lambda r: (r["element"], r["law"], r["penalty"], r.get("grading", 1.0), r["elements"], r.get("loop", "damped"),
                 r.get("iterations", 100))
for r in sorted(rows, key=key):
    t, g = r["tip"], r["gold"]
    err = t and math.hypot(t["ux"] - g["ux"], t["uy"] - g["uy"]) / math.hypot(g["ux"], g["uy"])
    first = r.get("first_element_m", paper_length / r["elements"])
    print(f"| {r['element']} | {r['law']} | {r['elements']} | {1e3 * first:.3g} | {r['dof']} | {tuple(r['points'])} | {r['penalty']:.0e} | "
          f"{r.get('loop', 'damped')} | "
          + (f"{1e3 * t['ux']:.3f} | {1e3 * t['uy']:.3f} | {100 * err:.3f}" if t else f"{r['status']}: {r['reason']} | | ")
          + f" | {r['newton_iterations']} ({r.get('iterations', 100)}) | {r['seconds']:.1f} |")
print()
for law, r in sorted({r["law"]: r for r in rows}.items()):
    g = r["gold"]
    print(f"The continuum's gold, {law}: ux {1e3 * g['ux']:.3f} mm, uy {1e3 * g['uy']:.3f} mm "
          f"(error estimate {1e3 * r['gold_error_estimate_m']:.3f} mm).")
