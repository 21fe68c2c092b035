"""What clamp and quadrature do to the `paper` cells of Table 3.

The paper leaves both open. Every element x law at the paper's counts, in the `paper`
formulation, for each clamp ("face": r, r_y (, r_yy) fixed; "all": r_x fixed too) and
each elastic quadrature (points along x, across the thickness). A run that fails
(no convergence, singular tangent) is shown as such, with its reason in the CSV.
"""
from __future__ import annotations


from ..common.grid import cantilever_case, count_for
from ..common.gold import short, describe, paper_tip, stability_mark
from ..engine.report import Section, Table, mm, pct, vec_error, verdict


STUDY = {
    "name": "sensitivity",
    "title": "Table 3, `paper` cells: clamp and quadrature",
    "full": True,
    "grid": {
        "laws": ["neo-hookean", "mooney-rivlin", "yeoh"],
        "elements": {"registered": {"tagged": "paper"}},
        "counts": "paper",
        "clamps": ["face", "all"],
        "quadratures": [[2, 2], [3, 2], [5, 3], [3, 3]],
    },
    "tiny": {
        "counts": {"HB2n-12": 8, "HB3n-12": 8, "HB2n-16": 16, "LB2n-12": 8},
        "quadratures": [[2, 2], [3, 3]],
    },
}


def settings(grid: dict) -> list[tuple[str, tuple[int, int]]]:
    return [(c, tuple(q)) for c in grid["clamps"] for q in grid["quadratures"]]


def cases(grid: dict, tiny: bool) -> list:
    return [cantilever_case("sensitivity", law, "paper", el, count_for(grid, el), q, clamp)
            for el in grid["elements"] for law in grid["laws"] for clamp, q in settings(grid)]


def _label(clamp: str, q) -> str:
    return f"{clamp} ({q[0]},{q[1]})"


def report(ctx) -> Section:
    g = ctx.study.grid
    recs = ctx.records()
    by = {}
    for r in recs:
        d = describe(r)
        by[(d["element"], d["law"], d["clamp"], d["quadrature"])] = (d, r)
    sec = Section(ctx.study.title,
                  "The `paper` formulation at the paper's element counts under every clamp x quadrature "
                  "choice; Table 3 uses clamp \"all\" with quadrature (2, 2).")
    cols = settings(g)
    hdr = ["element", "law"] + [_label(c, q) for c, q in cols]
    rows, long = [], []
    for el in g["elements"]:
        for law in g["laws"]:
            ref = paper_tip(el, law)
            row = [el, short(law)]
            for clamp, q in cols:
                d, r = by.get((el, law, clamp, q), (None, None))
                if d is None:
                    row.append("not run")
                    continue
                ok = d["status"] == "converged" and d["tip"]
                err = vec_error(d["tip"], ref) if ok else None
                row.append(f"{pct(err):.2f}{stability_mark(d)}" if ok and err is not None else d["status"])
                long.append([el, law, clamp, f"{q[0]}x{q[1]}", count_for(g, el), d["status"] + stability_mark(d),
                             mm(d["tip"]["ux"]) if ok else None, mm(d["tip"]["uy"]) if ok else None,
                             mm(ref[0]) if ref else None, mm(ref[1]) if ref else None, pct(err),
                             r.get("reason") or r.get("stability") or "", verdict(r)])
            rows.append(row)
    sec.table(ctx, Table("sensitivity", hdr, rows, {j: ".2f" for j in range(2, len(hdr))}),
              "Distance of each `paper` cell from the paper's own cell, |u - u_paper| / |u_paper| (%), per clamp "
              "and quadrature (points along x, across the thickness); a word where the run failed, (singular) / (unstable) "
              "where Newton converged to an equilibrium whose tangent is singular or indefinite.")
    t = Table("sensitivity_values", ["element", "law", "clamp", "quadrature", "n", "status", "ux (mm)", "uy (mm)",
                                     "paper ux (mm)", "paper uy (mm)", "distance (%)", "reason or stability",
                                     "verdict"], long,
              {6: ".2f", 7: ".2f", 8: ".2f", 9: ".2f", 10: ".2f"})
    t.write(ctx.out)
    sec.items.append(("link", t.name + ".md", "Every run's tip, status and failure reason."))
    sec.text = _findings(long, g.get("low_order", ()))
    return sec


def _findings(long: list, low_order) -> str:
    lines = []
    failed = [r for r in long if not r[5].startswith("converged")]
    for r in failed:
        lines.append(f"- {r[0]} {short(r[1])}, clamp {r[2]}, quadrature {r[3]} at {r[4]} elements: "
                     f"{r[5]} ({r[11]}).")
    odd = [r for r in long if r[5].startswith("converged (") and r[0] not in low_order]
    for r in odd:
        lines.append(f"- {r[0]} {short(r[1])}, clamp {r[2]}, quadrature {r[3]}: converged to an equilibrium that is "
                     f"not stable ({r[11]}).")
    ho = [r for r in long if r[0] not in low_order and r[10] is not None]
    worst: dict = {}      # (clamp, quadrature) -> {element: largest distance}: per element, so that one
    for r in ho:          # element's locking is named, not spread over the others as "within"
        per = worst.setdefault((r[2], r[3]), {})
        per[r[0]] = max(per.get(r[0], 0.0), r[10])
    for key, per in sorted(worst.items(), key=lambda kv: max(kv[1].values())):
        lines.append(f"- clamp {key[0]}, quadrature {key[1]}, largest distance from the paper's cells: "
                     + ", ".join(f"{el} {d:.2f} %" for el, d in per.items()) + ".")
    return "\n".join(lines)


def gold_values(ctx) -> dict:
    out = {}
    for r in ctx.records():
        d = describe(r)
        if d["status"] == "converged" and d["stable"] is not False and d["element"] not in ctx.study.grid.get("low_order", ()):
            q = d["quadrature"]
            for comp in ("ux", "uy"):
                v = d["tip"][comp]
                out[f"sensitivity/{d['element']}/{short(d['law'])}/{d['clamp']}/q{q[0]}{q[1]}/{comp}"] = (
                    v, 1e-6 * abs(v) + 1e-9)
    return out
