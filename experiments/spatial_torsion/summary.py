"""The table of REPORT.md from res.jsonl (run.py's records), as markdown on stdout: each run's
torsion constant J (mm^4), off its section's bound and off Saint-Venant's exact J."""
from __future__ import annotations

import json
from pathlib import Path

HERE = Path(__file__).resolve().parent

rows = [json.loads(x) for x in (HERE / "res.jsonl").read_text().splitlines()]
print("| element | section degree | elements | dof | rule | support | penalty (Pa) | J (mm^4) | off the section's bound (%) | bound (mm^4) "
      "| off Saint-Venant (%) | Newton | s |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for r in sorted(rows, key=lambda r: (r["section_degree"], r["element"], r.get("support", "clamp"), -r["penalty"],
                                     r["elements"])):
    J = r["J"]
    cells = (f"{1e12 * J:.3f} | {100 * (J / r['J_section_bound'] - 1):+.4f}" if J else f"{r['status']}: {r['reason']} |")
    print(f"| {r['element']} | {r['section_degree']} | {r['elements']} | {r['dof']} | {tuple(r['points'])} | {r.get('support', 'clamp')} | {r['penalty']:.0e} | {cells} | "
          f"{1e12 * r['J_section_bound']:.3f} | " + (f"{100 * (J / r['J_saint_venant'] - 1):+.3f}" if J else "")
          + f" | {r['newton_iterations']} | {r['seconds']:.1f} |")
print()
print(f"Saint-Venant's J of the 5 x 7 mm section: {1e12 * rows[0]['J_saint_venant']:.3f} mm^4.")
