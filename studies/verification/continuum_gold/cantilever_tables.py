"""Tables for reports/reference_fem.md, from the gold file only (never a solver call).

``python -m studies continuum report [GOLD.json]`` prints markdown: the converged tips
against the paper's ABAQUS column, plane strain against plane stress, and the cost of
each reference at 1 % and 0.1 % tip accuracy (static error ||u - u_ref|| / ||u_ref||
over (ux, uy), u_ref the Richardson value).
"""
from __future__ import annotations

import json
import math
from pathlib import Path

from contract.paper import paper_tip

LABEL = {"plane-strain": "plane strain, mixed (exact)", "plane-strain-penalty":
         "plane strain, penalty 1000 MPa", "plane-stress": "plane stress (F33 = 1/J)"}


def _err(u, ref) -> float:
    return math.hypot(u["ux"] - ref["ux"], u["uy"] - ref["uy"]) / math.hypot(ref["ux"], ref["uy"])


def abaqus_table(cases: dict) -> list[str]:
    rows = ["| law | model | ux (mm) | uy (mm) | est. error (mm) | ABAQUS ux, uy (mm) "
            "| ux vs ABAQUS | uy vs ABAQUS |", "|---|---|---|---|---|---|---|---|"]
    for key, c in cases.items():
        law, variant = key.split("/")
        t, (ax, ay) = c["tip"], paper_tip("ABAQUS", law)
        rows.append(f"| {law} | {LABEL[variant]} | {t['ux'] * 1e3:.3f} | {t['uy'] * 1e3:.3f} "
                    f"| {c['error_estimate_m'] * 1e3:.1e} | {ax * 1e3:.2f}, {ay * 1e3:.2f} "
                    f"| {(t['ux'] - ax) / abs(ax) * 100:+.2f} % | {(t['uy'] - ay) / abs(ay) * 100:+.2f} % |")
    return rows


def strain_vs_stress_table(cases: dict) -> list[str]:
    rows = ["| law | plane stress ux, uy (mm) | plane strain ux, uy (mm) | distance / size of the plane stress tip "
            "| uy ratio strain/stress |", "|---|---|---|---|---|"]
    for law in sorted({k.split("/")[0] for k in cases}):
        s, e = cases[f"{law}/plane-stress"]["tip"], cases[f"{law}/plane-strain"]["tip"]
        rows.append(f"| {law} | {s['ux'] * 1e3:.2f}, {s['uy'] * 1e3:.2f} | {e['ux'] * 1e3:.2f}, "
                    f"{e['uy'] * 1e3:.2f} | {_err(e, s) * 100:.1f} % | {e['uy'] / s['uy']:.3f} |")
    return rows


def cost_table(cases: dict, accuracies=(1e-2, 1e-3)) -> list[str]:
    head = "| law | model | " + " | ".join(
        f"{a * 100:g} %: mesh, ndof, error, solve s (Newton its)" for a in accuracies) + " |"
    rows = [head, "|---|---|" + "---|" * len(accuracies)]
    for key, c in cases.items():
        law, variant = key.split("/")
        cells = []
        for acc in accuracies:
            ok = [lv for lv in c["levels"] if lv["tip"] and _err(lv["tip"], c["tip"]) <= acc]
            if not ok:
                cells.append("not reached")
                continue
            lv = ok[0]
            cells.append(f"{lv['cells_length']} x {lv['cells_height']}, {lv['ndof']}, "
                         f"{_err(lv['tip'], c['tip']) * 100:.3f} %, {lv['wall_s']:.2f} ({lv['newton_iterations']})")
        rows.append(f"| {law} | {LABEL[variant]} | " + " | ".join(cells) + " |")
    return rows


def levels_table(cases: dict) -> list[str]:
    rows = ["| case | " + " | ".join(f"{lv['cells_length']} x {lv['cells_height']}"
                                     for lv in next(iter(cases.values()))["levels"]) + " | orders |",
            "|---|" + "---|" * (len(next(iter(cases.values()))["levels"]) + 1)]
    for key, c in cases.items():
        rows.append(f"| {key} | " + " | ".join(f"{_err(lv['tip'], c['tip']) * 100:.4f} %"
                                               for lv in c["levels"])
                    + " | " + ", ".join(f"{p:.2f}" for p in c["orders"]) + " |")
    return rows


def render(gold_path: Path) -> str:
    gold = json.loads(Path(gold_path).read_text())
    cases = gold["cases"]
    parts = [f"Source: `{gold_path}` (DOLFINx {gold['dolfinx']}, `{gold['generator']}`).", "",
             "### Converged tip against the paper's ABAQUS column", "", *abaqus_table(cases), "",
             "### Plane strain against plane stress", "", *strain_vs_stress_table(cases), "",
             "### Error of each level (against the Richardson value) and observed orders", "",
             *levels_table(cases), "",
             "### Cost at 1 % and 0.1 % tip accuracy (Q2 quadrilaterals, solve wall time)", "",
             *cost_table(cases)]
    return "\n".join(parts) + "\n"
