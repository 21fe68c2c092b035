"""Two continuum codes on the same truths: the Richardson values of DOLFINx (the
``continuum`` study's records: Q2 levels 16 x 1 ... 256 x 16) and of FElupe
(``[fem] backend = "felupe"``, this study's cases: its own mesh sequence, 12 x 1 ...
96 x 8 Q2 cells, so the two extrapolations share no mesh), for each law and 2D model of
Table 3's continuum rows (plane strain exact, plane strain with the ANCF penalty, plane
stress; the formulation table's continuum values are these same three).

The check: the two Richardson values differ by no more than the sum of their error
estimates (each the estimated error of its finest level, :mod:`reference_fem.convergence`,
so the bar is conservative for the extrapolated values). A disagreement beyond the bars
is printed as FAIL in the report and fails the tiny-mode gold values.
"""
from __future__ import annotations

import math

from .continuum import scene as continuum_scene
from .engine.case import make_case
from .engine.report import Section, Table, mm
from .reference import VARIANT_LABEL, continuum_references, short

BACKEND = "felupe"


def scene(law: str, variant: str, cells: tuple[int, int]) -> dict:
    """The continuum study's scene on FElupe."""
    d = continuum_scene(law, variant, cells)
    d["fem"]["backend"] = BACKEND
    d["name"] += f"-{BACKEND}"
    return d


def cases(grid: dict, tiny: bool) -> list:
    return [make_case("continuum-agreement", "fenicsx", scene(law, v, tuple(lv)))
            for law in grid["laws"] for v in grid["variants"] for lv in grid["levels"]]


def _backend(rec: dict) -> str:
    return (rec["scene"].get("fem") or {}).get("backend", "dolfinx")


def agreement(dolfinx_records: list[dict], felupe_records: list[dict]) -> list[dict]:
    """One row per (law, variant) that both codes have: their Richardson tips (m), error
    estimates (m), the distance between the tips, the bar (sum of the estimates) and
    whether the tips agree within it (None without a Richardson value on either side)."""
    a = continuum_references([r for r in dolfinx_records if _backend(r) == "dolfinx"])
    b = continuum_references([r for r in felupe_records if _backend(r) == BACKEND])
    rows = []
    for key in [k for k in b if k in a]:
        ra, rb = a[key], b[key]
        row = {"law": key[0], "variant": key[1], "dolfinx": ra, "felupe": rb,
               "diff": None, "bar": None, "agree": None}
        if ra.tip and rb.tip and ra.error_estimate is not None and rb.error_estimate is not None:
            row["diff"] = math.hypot(ra.tip[0] - rb.tip[0], ra.tip[1] - rb.tip[1])
            row["bar"] = ra.error_estimate + rb.error_estimate
            row["agree"] = row["diff"] <= row["bar"]
        rows.append(row)
    return rows


def _finest(ref) -> str | None:
    lv = [x for x in ref.levels if x["status"] == "converged"]
    return f"{lv[-1]['cells'][0]} x {lv[-1]['cells'][1]}" if lv else None


def report(ctx) -> Section:
    rows = agreement(ctx.records("continuum"), ctx.records())
    sec = Section(ctx.study.title,
                  "The continuum truths by two finite-element codes: DOLFINx (the `continuum` study) and "
                  "FElupe (reference_fem's second backend) on different mesh sequences, each Richardson-"
                  "extrapolated with its error estimate; they agree when their distance is within the sum "
                  "of the estimates.")
    table = []
    for r in rows:
        a, b = r["dolfinx"], r["felupe"]
        table.append([short(r["law"]), VARIANT_LABEL[r["variant"]],
                      mm(a.tip[0]) if a.tip else None, mm(a.tip[1]) if a.tip else None, mm(a.error_estimate),
                      _finest(a), mm(b.tip[0]) if b.tip else None, mm(b.tip[1]) if b.tip else None,
                      mm(b.error_estimate), _finest(b), mm(r["diff"]), mm(r["bar"]),
                      None if r["agree"] is None else ("yes" if r["agree"] else "NO")])
    sec.table(ctx, Table("continuum_agreement",
                         ["law", "model", "DOLFINx ux (mm)", "DOLFINx uy (mm)", "DOLFINx est. (mm)", "DOLFINx finest",
                          "FElupe ux (mm)", "FElupe uy (mm)", "FElupe est. (mm)", "FElupe finest",
                          "distance (mm)", "bar (mm)", "within bar"], table,
                         {2: ".4f", 3: ".4f", 4: ".1e", 6: ".4f", 7: ".4f", 8: ".1e", 10: ".1e", 11: ".1e"}),
              "Richardson tips of the two codes and their distance against the combined error estimate "
              "(bar = DOLFINx's + FElupe's estimate).")
    bad = [f"{short(r['law'])} {r['variant']}" for r in rows if r["agree"] is False]
    missing = [f"{short(r['law'])} {r['variant']}" for r in rows if r["agree"] is None]
    verdict = "PASS" if rows and not bad and not missing else "FAIL"
    sec.text = (f"Check: **{verdict}** ({len(rows) - len(bad) - len(missing)} of {len(rows)} within their bars"
                + (f"; beyond: {', '.join(bad)}" if bad else "")
                + (f"; no Richardson value: {', '.join(missing)}" if missing else "") + ").")
    return sec


def gold_values(ctx) -> dict:
    """FElupe's Richardson tips (m), to 1e-6 relative as the continuum study's; the
    agreement itself is the report's check (tests/test_studies_tiny.py reads it)."""
    out = {}
    for r in agreement(ctx.records("continuum"), ctx.records()):
        tip = r["felupe"].tip
        if tip:
            for name, v in zip(("ux", "uy"), tip):
                out[f"continuum-agreement/{short(r['law'])}/{r['variant']}/felupe/{name}"] = (v, 1e-6 * abs(v) + 1e-9)
    return out
