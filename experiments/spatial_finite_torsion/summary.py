"""The tables of REPORT.md from levels.jsonl and res.jsonl (run.py writes them).

    .venv/bin/python experiments/spatial_finite_torsion/summary.py
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent


def lines(name: str) -> list[dict]:
    p = HERE / name
    return [json.loads(s) for s in p.read_text().splitlines()] if p.exists() else []


def saint_venant_torque(law: str, theta: float) -> float:
    from contract import paper
    from mechanics.laws import get_law
    from studies.verification.torsion import saint_venant_rectangle

    c = {k: v for k, v in paper.materials()[law].items() if k != "density"}
    mu = get_law(law).shear_modulus(c)
    h, w, L = paper.CANTILEVER["height"], paper.CANTILEVER["width"], paper.CANTILEVER["length"]
    return mu * saint_venant_rectangle(h, w) * theta / L


# The reference: the section refined at 32 cells along (the section's error dominates the
# continuum's: levels.jsonl), Richardson's value of it at the observed order (the 2D
# Saint-Venant sequence of saint_venant_q2.py shows the Q2 section's order, 3.6 -> 3.7, so the
# 3D cap of 1 is not needed here), plus the length's correction from 32 cells on, measured
# on a coarser section and extrapolated at its own order. Pure twist: equal cells along, the
# length's sequence on the 4 x 4 section. Twist with bending: its plates' end zones bend (the
# corners of a clamped face), which equal cells resolve so slowly that their sequence is not
# monotone (16 -> 24 -> 32 -> 48 -> 64 cells on 2 x 2 move the axial force -0.34, +0.06,
# +0.27, +0.20 %): cells graded from both plates (1.1 at 32 along, its square and fourth roots
# at 64 and 128), the length's sequence on the 2 x 2 section. Each level: (cells, grading).
SEQUENCES = {
    "twist": ([([32, 2, 2], 1.0), ([32, 4, 4], 1.0), ([32, 8, 8], 1.0)],
              [([16, 4, 4], 1.0), ([32, 4, 4], 1.0), ([64, 4, 4], 1.0)]),
    "twist-bend": ([([32, 2, 2], 1.1), ([32, 4, 4], 1.1), ([32, 8, 8], 1.1)],
                   [([32, 2, 2], 1.1), ([64, 2, 2], 1.1 ** 0.5), ([128, 2, 2], 1.1 ** 0.25)]),
}
# the reaction's components per case: name -> (the record's key, index; None: a number)
COMPONENTS = {"twist": {"T": ("T", None), "N": ("N", None)},
              "twist-bend": {"N": ("force", 0), "Fy": ("force", 1), "Fz": ("force", 2), "T": ("moment", 0),
                             "My": ("moment", 1), "Mz": ("moment", 2)}}
# the twist-bend tables' columns (Fy, Fz enter the vectors' errors)
TB_SHOWN = ("N", "T", "My", "Mz")


def _level(law: str, inc: str, cells: list[int], case: str = "twist", grading: float = 1.0) -> dict | None:
    for r in lines("levels.jsonl"):
        if ((r["law"], r["incompressibility"], r["backend"], r.get("case", "twist"), r["cells"], r["rtol"])
                == (law, inc, "dolfinx", case, cells, 1e-9) and math.isclose(r.get("grading", 1.0), grading)
                and r["status"] == "converged"):
            return r
    return None


def component(reactions: dict, case: str, name: str) -> float:
    key, i = COMPONENTS[case][name]
    return reactions[key] if i is None else reactions[key][i]


def _extrapolate(a: float, b: float, c: float) -> tuple[float, float, float] | None:
    """(c's limit, the tail (limit - c), order) of three levels of ratio 2 by
    reference_fem.convergence.richardson (no cap on the trusted order: see above); None
    unless the levels converge monotonically."""
    from reference_fem.convergence import richardson

    if (b - a) * (c - b) <= 0:
        return None
    r = richardson((a, 0.0), (b, 0.0), (c, 0.0), p_trusted=math.inf)
    return None if r.value is None else (r.value[0], r.value[0] - c, r.order)


def references(case: str = "twist") -> dict:
    """{(law, incompressibility, angle): {component: (value, error estimate, section order)}}:
    the section's Richardson value at 32 cells along plus the length's correction; the error
    estimate the sum of the two tails (each the size of what its extrapolation added)."""
    out = {}
    section, length = SEQUENCES[case]
    keys = {(r["law"], r["incompressibility"]) for r in lines("levels.jsonl")}
    for law, inc in sorted(keys):
        sec = [_level(law, inc, c, case, g) for c, g in section]
        lng = [_level(law, inc, c, case, g) for c, g in length]
        if None in sec or None in lng:
            continue
        at32 = next(lv for (c, _), lv in zip(length, lng) if c[0] == 32)
        for frac in sec[0]["reactions"]:
            q = {}
            for k in COMPONENTS[case]:
                s_ = _extrapolate(*(component(lv["reactions"][frac], case, k) for lv in sec))
                x_ = _extrapolate(*(component(lv["reactions"][frac], case, k) for lv in lng))
                if s_ is None or x_ is None:
                    q[k] = (None, None, None)
                    continue
                # from the section sequence's length (32 cells along) to the limit
                correction = x_[0] - component(at32["reactions"][frac], case, k)
                q[k] = (s_[0] + correction, abs(s_[1]) + abs(x_[1]), s_[2])
            out[(law, inc, frac)] = q
    return out


def continuum_table() -> str:
    rows = ["| law | backend | J | cells (x, y, z) | Newton rtol | dof | T at pi / 2 (N mm) | T at pi (N mm) | "
            "N at pi / 2 (mN) | N at pi (mN) | Newton | s |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    seen = [(r["law"], r["incompressibility"], r) for r in lines("levels.jsonl") if r.get("case", "twist") == "twist"]
    for law, inc, lv in sorted(seen, key=lambda t: (t[0], t[1], t[2]["ndof"], t[2]["backend"])):
        g = lv["reactions"]
        if "1.0" not in g:
            rows.append(f"| {law} | {lv['backend']} | {inc} | {' x '.join(map(str, lv['cells']))} | "
                        f"{lv.get('rtol', 1e-9):.0e} | {lv['ndof']} | {lv['status']}: {lv['reason']} | | | | "
                        f"{lv['newton_iterations']} | {lv['seconds']:.0f} |")
            continue
        rows.append(f"| {law} | {lv['backend']} | {inc} | {' x '.join(map(str, lv['cells']))} | "
                    f"{lv.get('rtol', 1e-9):.0e} | {lv['ndof']} | "
                    f"{1e3 * g['0.5']['T']:.5f} | {1e3 * g['1.0']['T']:.5f} | {1e3 * g['0.5']['N']:.4f} | "
                    f"{1e3 * g['1.0']['N']:.4f} | {lv['newton_iterations']} | {lv['seconds']:.0f} |")
    return "\n".join(rows)


def ancf_table() -> str:
    ref = references()
    rows = ["| element | law | elements | grading | dof | penalty (Pa) | T at pi (N mm) | off the continuum (%) | "
            "T(pi) / T(pi / 2) | N at pi (mN) | off the continuum (%) | T over mu J theta / L | Newton | s |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in sorted((r for r in lines("res.jsonl") if r.get("case", "twist") == "twist"),
                    key=lambda r: (r["element"], r["law"], r["penalty"], r.get("grading", 1.0), r["elements"])):
        g = r["reactions"].get("1.0")
        head = (f"| {r['element']} | {r['law']} | {r['elements']} | {r.get('grading', 1.0):g} | {r['dof']} | "
                f"{r['penalty']:.0e} | ")
        if g is None:
            rows.append(head + f"{r['status']}: {r['reason']} | | | | | | {r['newton_iterations']} | {r['seconds']:.1f} |")
            continue
        c = ref.get((r["law"], "mixed", "1.0"))
        eT = "" if c is None or c["T"][0] is None else f"{100 * (g['T'] / c['T'][0] - 1):+.3f}"
        eN = "" if c is None or c["N"][0] is None else f"{100 * (g['N'] / c['N'][0] - 1):+.1f}"
        sv = g["T"] / saint_venant_torque(r["law"], math.pi)
        rows.append(head + f"{1e3 * g['T']:.5f} | {eT} | {g['T'] / r['reactions']['0.5']['T']:.4f} | "
                    f"{1e3 * g['N']:.4f} | {eN} | {sv:.4f} | "
                    f"{r['newton_iterations']} | {r['seconds']:.1f} |")
    return "\n".join(rows)


def reference_table() -> str:
    rows = ["| law | J | angle | T (N mm) | its error estimate | section order | N (mN) | its error estimate | section order |",
            "|---|---|---|---|---|---|---|---|---|"]
    for (law, inc, frac), q in sorted(references().items()):
        t, n = q["T"], q["N"]
        fmt = lambda v, s: "no value" if v is None else f"{s * v:.5f}"
        order = lambda v: "" if v is None else f"{v:.2f}"
        rows.append(f"| {law} | {inc} | {frac} pi | {fmt(t[0], 1e3)} | {fmt(t[1], 1e3)} | {order(t[2])} | "
                    f"{fmt(n[0], 1e3)} | {fmt(n[1], 1e3)} | {order(n[2])} |")
    return "\n".join(rows)


TB_UNITS = {"N": (1e3, "mN"), "Fy": (1e3, "mN"), "Fz": (1e3, "mN"), "T": (1e3, "N mm"), "My": (1e3, "N mm"),
            "Mz": (1e3, "N mm")}


def twist_bend_continuum_table() -> str:
    names = list(COMPONENTS["twist-bend"])
    rows = ["| law | backend | cells (x, y, z) | grading | dof | "
            + " | ".join(f"{k} ({TB_UNITS[k][1]})" for k in names) + " | Newton | s |",
            "|---|---|---|---|---|" + "---|" * len(names) + "---|---|"]
    seen = [r for r in lines("levels.jsonl") if r.get("case") == "twist-bend"]
    for lv in sorted(seen, key=lambda r: (r["law"], r.get("grading", 1.0) != 1.0, r["cells"][1], r["cells"][0],
                                          r["backend"])):
        g = lv["reactions"].get("1.0")
        head = (f"| {lv['law']} | {lv['backend']} | {' x '.join(map(str, lv['cells']))} | "
                f"{lv.get('grading', 1.0):.4g} | {lv['ndof']} | ")
        if g is None:
            rows.append(head + f"{lv['status']}: {lv['reason']} |" + " |" * (len(names) - 1)
                        + f" {lv['newton_iterations']} | {lv['seconds']:.0f} |")
            continue
        rows.append(head + " | ".join(f"{TB_UNITS[k][0] * component(g, 'twist-bend', k):.4f}" for k in names)
                    + f" | {lv['newton_iterations']} | {lv['seconds']:.0f} |")
    return "\n".join(rows)


def twist_bend_reference_table() -> str:
    names = list(COMPONENTS["twist-bend"])
    rows = ["| law | angle | " + " | ".join(f"{k} ({TB_UNITS[k][1]}) +- | order" for k in names) + " |",
            "|---|---|" + "---|---|" * len(names)]
    for (law, inc, frac), q in sorted(references("twist-bend").items()):
        cells = []
        for k in names:
            v, e, p = q[k]
            f = TB_UNITS[k][0]
            cells += ["no value", ""] if v is None else [f"{f * v:.4f} +- {f * e:.4f}", f"{p:.2f}"]
        rows.append(f"| {law} | {frac} | " + " | ".join(cells) + " |")
    return "\n".join(rows)


def twist_bend_ancf_table() -> str:
    ref = references("twist-bend")
    names = list(TB_SHOWN)
    rows = ["| element | law | elements | grading | dof | "
            + " | ".join(f"{k} ({TB_UNITS[k][1]}) | off (%)" for k in names)
            + " | force off (%) | moment off (%) | Newton | s |",
            "|---|---|---|---|---|" + "---|---|" * len(names) + "---|---|---|---|"]
    for r in sorted((r for r in lines("res.jsonl") if r.get("case") == "twist-bend"),
                    key=lambda r: (r["element"], r["law"], r.get("grading", 1.0), r["elements"])):
        g = r["reactions"].get("1.0")
        head = f"| {r['element']} | {r['law']} | {r['elements']} | {r.get('grading', 1.0):g} | {r['dof']} | "
        if g is None:
            rows.append(head + f"{r['status']}: {r['reason']} |" + " |" * (2 * len(names) + 1)
                        + f" {r['newton_iterations']} | {r['seconds']:.1f} |")
            continue
        c = ref.get((r["law"], "mixed", "1.0"))
        cells = []
        for k in names:
            v = component(g, "twist-bend", k)
            off = "" if c is None or c[k][0] is None else f"{100 * (v / c[k][0] - 1):+.3f}"
            cells += [f"{TB_UNITS[k][0] * v:.4f}", off]
        for vector, ks in (("force", ("N", "Fy", "Fz")), ("moment", ("T", "My", "Mz"))):
            if c is None or any(c[k][0] is None for k in ks):
                cells.append("")
                continue
            want = np.array([c[k][0] for k in ks])
            cells.append(f"{100 * np.linalg.norm(np.array(g[vector]) - want) / np.linalg.norm(want):.3f}")
        rows.append(head + " | ".join(cells) + f" | {r['newton_iterations']} | {r['seconds']:.1f} |")
    return "\n".join(rows)


if __name__ == "__main__":
    print(continuum_table(), end="\n\n")
    print(reference_table(), end="\n\n")
    print(ancf_table(), end="\n\n")
    print(twist_bend_continuum_table(), end="\n\n")
    print(twist_bend_reference_table(), end="\n\n")
    print(twist_bend_ancf_table())
