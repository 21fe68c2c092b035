"""The table of REPORT.md from res.jsonl (run.py's records), as markdown on stdout."""
from __future__ import annotations

import json
from pathlib import Path

HERE = Path(__file__).resolve().parent

rows = [json.loads(x) for x in (HERE / "res.jsonl").read_text().splitlines()]
print("| element | law | elements | dof | penalty (Pa) | tip ux (mm) | tip uy (mm) | |r - r_gold| / L | Newton "
      "(most per increment) | s |")
print("|---|---|---|---|---|---|---|---|---|---|")
for r in sorted(rows, key=lambda r: (r["element"], r["law"], r["penalty"], r["elements"], r.get("iterations", 100))):
    t = r["tip"]
    print(f"| {r['element']} | {r['law']} | {r['elements']} | {r['dof']} | {r['penalty']:.0e} | "
          + (f"{1e3 * t['ux']:.3f} | {1e3 * t['uy']:.3f} | {r['error_over_L']:.4f}" if t else f"{r['status']}: {r['reason']} | | ")
          + f" | {r['newton_iterations']} ({r.get('iterations', 100)}) | {r['seconds']:.1f} |")
print()
for law, r in sorted({r["law"]: r for r in rows}.items()):
    g = r["gold"]
    print(f"The continuum's gold, {law}: ux {1e3 * g['ux']:.3f} mm, uy {1e3 * g['uy']:.3f} mm "
          f"(error estimate {1e3 * r['gold_error_estimate_m']:.3f} mm).")
