"""The tables of REPORT.md from continuum.jsonl and res.jsonl (mm where printed)."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent


def lines(name: str) -> list[dict]:
    p = HERE / name
    return [json.loads(s) for s in p.read_text().splitlines()] if p.exists() else []


def continuum_table() -> None:
    print("| law | backend | end face's weights | levels (cells) | finest uy (mm) | tip ux (mm) | tip uy (mm) | "
          "error estimate (mm) | order | s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in lines("continuum.jsonl"):
        cells = ", ".join(f"{lv['cells_length']}x{lv['cells_height']}x{lv['cells_width']}" for lv in r["levels"])
        t = r["tip"]
        head = (f"| {r['law']} | {r['backend']} | {r['face_weights']} | {cells} | "
                f"{1e3 * r['levels'][-1]['tip']['uy']:.3f} |")
        if t is None:
            print(f"{head} no Richardson value | | | | {r['seconds']:.0f} |")
            continue
        print(f"{head} {1e3 * t['ux']:.3f} | {1e3 * t['uy']:.3f} | "
              f"{1e3 * r['error_estimate_m']:.3f} | {r['order']:.2f} | {r['seconds']:.0f} |")


def agreement() -> None:
    by = {(r["law"], r["backend"]): r for r in lines("continuum.jsonl") if r["tip"] is not None}
    for (law, backend), r in sorted(by.items()):
        if backend == "dolfinx" or (law, "dolfinx") not in by:
            continue
        d, f = by[(law, "dolfinx")], r
        gap = np.hypot(d["tip"]["ux"] - f["tip"]["ux"], d["tip"]["uy"] - f["tip"]["uy"])
        bar = d["error_estimate_m"] + f["error_estimate_m"]
        print(f"{law}: DOLFINx and FElupe {1e3 * gap:.4f} mm apart, their error estimates' sum {1e3 * bar:.4f} mm")


def ancf_table() -> None:
    print("| element | law | elements | grading | first element (mm) | dof | tip ux (mm) | tip uy (mm) | error (%) | Newton | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in sorted(lines("res.jsonl"), key=lambda r: (r["element"], r["law"], r["grading"], r["elements"])):
        head = (f"| {r['element']} | {r['law']} | {r['elements']} | {r['grading']:g} | {1e3 * r['first_element_m']:.2f} | "
                f"{r['dof']} |")
        if r["status"] != "converged":
            print(f"{head} {r['status']}: {r['reason']} | | | {r['newton_iterations']} | {r['seconds']:.1f} |")
            continue
        t = r["tip"]
        print(f"{head} {1e3 * t['ux']:.3f} | {1e3 * t['uy']:.3f} | {100 * r['error']:.3f} | "
              f"{r['newton_iterations']} | {r['seconds']:.1f} |")


if __name__ == "__main__":
    continuum_table()
    print()
    agreement()
    print()
    ancf_table()
