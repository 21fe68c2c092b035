"""The tables of REPORT.md from levels.jsonl and res.jsonl (run.py writes them).

    .venv/bin/python experiments/spatial_finite_torsion/summary.py
"""
from __future__ import annotations

import json
import math
from pathlib import Path

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
# on the 4 x 4 section (16, 32, 64 along) and extrapolated at its own order.
SECTION_SEQUENCE = [[32, 2, 2], [32, 4, 4], [32, 8, 8]]
LENGTH_SEQUENCE = [[16, 4, 4], [32, 4, 4], [64, 4, 4]]


def _level(law: str, inc: str, cells: list[int]) -> dict | None:
    for r in lines("levels.jsonl"):
        if ((r["law"], r["incompressibility"], r["backend"], r.get("case", "twist"), r["cells"], r["rtol"])
                == (law, inc, "dolfinx", "twist", cells, 1e-9)):
            return r
    return None


def _extrapolate(a: float, b: float, c: float) -> tuple[float, float, float] | None:
    """(c's limit, the tail (limit - c), order) of three levels of ratio 2 by
    reference_fem.convergence.richardson (no cap on the trusted order: see above); None
    unless the levels converge monotonically."""
    from reference_fem.convergence import richardson

    if (b - a) * (c - b) <= 0:
        return None
    r = richardson((a, 0.0), (b, 0.0), (c, 0.0), p_trusted=math.inf)
    return None if r.value is None else (r.value[0], r.value[0] - c, r.order)


def references() -> dict:
    """{(law, incompressibility, angle): {"T": (value, error estimate, section order), "N": ...}}:
    the section's Richardson value at 32 cells along plus the length's correction; the error
    estimate the sum of the two tails (each the size of what its extrapolation added)."""
    out = {}
    keys = {(r["law"], r["incompressibility"]) for r in lines("levels.jsonl")}
    for law, inc in sorted(keys):
        sec = [_level(law, inc, c) for c in SECTION_SEQUENCE]
        lng = [_level(law, inc, c) for c in LENGTH_SEQUENCE]
        if None in sec or None in lng:
            continue
        for frac in sec[0]["reactions"]:
            q = {}
            for k in ("T", "N"):
                s_ = _extrapolate(*(lv["reactions"][frac][k] for lv in sec))
                x_ = _extrapolate(*(lv["reactions"][frac][k] for lv in lng))
                if s_ is None or x_ is None:
                    q[k] = (None, None, None)
                    continue
                correction = x_[0] - lng[1]["reactions"][frac][k]      # from 32 cells along to the limit
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


if __name__ == "__main__":
    print(continuum_table(), end="\n\n")
    print(reference_table(), end="\n\n")
    print(ancf_table())
