"""The tables of REPORT.md from continuum.jsonl and res.jsonl (mm where printed)."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
from contract.paper import PENALTY as PAPER_PENALTY   # the ANCF runs' default


def lines(name: str) -> list[dict]:
    p = HERE / name
    return [json.loads(s) for s in p.read_text().splitlines()] if p.exists() else []


def _incompressibility(r: dict) -> str:
    return r.get("incompressibility", "mixed")


def continuum_table() -> None:
    print("| law | backend | J | end face's weights | levels (cells) | finest uy (mm) | tip ux (mm) | tip uy (mm) | "
          "error estimate (mm) | order | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in lines("continuum.jsonl"):
        cells = ", ".join(f"{lv['cells_length']}x{lv['cells_height']}x{lv['cells_width']}" for lv in r["levels"])
        t = r["tip"]
        head = (f"| {r['law']} | {r['backend']} | {_incompressibility(r)} | {r['face_weights']} | {cells} | "
                f"{1e3 * r['levels'][-1]['tip']['uy']:.3f} |")
        if t is None:
            print(f"{head} no Richardson value | | | | {r['seconds']:.0f} |")
            continue
        print(f"{head} {1e3 * t['ux']:.3f} | {1e3 * t['uy']:.3f} | "
              f"{1e3 * r['error_estimate_m']:.3f} | {r['order']:.2f} | {r['seconds']:.0f} |")


def agreement() -> None:
    by = {(r["law"], r["backend"]): r for r in lines("continuum.jsonl")
          if r["tip"] is not None and _incompressibility(r) == "mixed"}
    for (law, backend), r in sorted(by.items()):
        if backend == "dolfinx" or (law, "dolfinx") not in by:
            continue
        d, f = by[(law, "dolfinx")], r
        gap = np.hypot(d["tip"]["ux"] - f["tip"]["ux"], d["tip"]["uy"] - f["tip"]["uy"])
        bar = d["error_estimate_m"] + f["error_estimate_m"]
        print(f"{law}: DOLFINx and FElupe {1e3 * gap:.4f} mm apart, their error estimates' sum {1e3 * bar:.4f} mm")


def _penalty_reference(law: str) -> dict | None:
    """DOLFINx's Richardson value of the penalty continuum (the paper's alpha, as the ANCF
    runs' default), or None."""
    for r in lines("continuum.jsonl"):
        if r["law"] == law and r["backend"] == "dolfinx" and r["tip"] is not None and _incompressibility(r) == "penalty":
            return r
    return None


def _error(t: dict, g: dict) -> float:
    return float(np.hypot(t["ux"] - g["ux"], t["uy"] - g["uy"]) / np.hypot(g["ux"], g["uy"]))


def ancf_table() -> None:
    """The ANCF runs at the paper's penalty; "error" against the exactly incompressible
    continuum, "error, penalty" against the continuum with the same penalty."""
    print("| element | law | elements | grading | first element (mm) | dof | tip ux (mm) | tip uy (mm) | error (%) | "
          "error, penalty (%) | Newton | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    rows = [r for r in lines("res.jsonl") if r["penalty"] == PAPER_PENALTY]
    for r in sorted(rows, key=lambda r: (r["element"], r["law"], r["grading"], r["elements"])):
        head = (f"| {r['element']} | {r['law']} | {r['elements']} | {r['grading']:g} | {1e3 * r['first_element_m']:.2f} | "
                f"{r['dof']} |")
        if r["status"] != "converged":
            print(f"{head} {r['status']}: {r['reason']} | | | | {r['newton_iterations']} | {r['seconds']:.1f} |")
            continue
        t, pen = r["tip"], _penalty_reference(r["law"])
        ep = "" if pen is None else f"{100 * _error(t, pen['tip']):.3f}"
        print(f"{head} {1e3 * t['ux']:.3f} | {1e3 * t['uy']:.3f} | {100 * r['error']:.3f} | {ep} | "
              f"{r['newton_iterations']} | {r['seconds']:.1f} |")


def penalty_sweep() -> None:
    """The same meshes at alpha 1e9, 1e10, 1e11 Pa; alpha -> infinity by the 1/alpha law
    from the two stiffest (u_inf = u_11 + (u_11 - u_10) / 9), against the exactly
    incompressible continuum."""
    by = {}
    for r in lines("res.jsonl"):
        if r["status"] == "converged":
            by.setdefault((r["element"], r["law"], r["grading"], r["elements"]), {})[r["penalty"]] = r
    print("| element | law | elements | grading | uy, alpha 1e9 (mm) | 1e10 | 1e11 | alpha -> inf (mm) | "
          "error at alpha -> inf (%) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for key, runs in sorted(by.items()):
        if not {1e9, 1e10, 1e11} <= set(runs):
            continue
        u = {a: runs[a]["tip"] for a in (1e9, 1e10, 1e11)}
        inf = {k: u[1e11][k] + (u[1e11][k] - u[1e10][k]) / 9.0 for k in ("ux", "uy")}
        err = _error(inf, runs[1e9]["reference"])
        print(f"| {key[0]} | {key[1]} | {key[3]} | {key[2]:g} | " + " | ".join(f"{1e3 * u[a]['uy']:.3f}" for a in (1e9, 1e10, 1e11))
              + f" | {1e3 * inf['uy']:.3f} | {100 * err:.3f} |")


if __name__ == "__main__":
    continuum_table()
    print()
    agreement()
    print()
    ancf_table()
    print()
    penalty_sweep()
