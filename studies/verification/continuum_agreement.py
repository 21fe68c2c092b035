"""Two continuum codes on the same truths: every continuum value the reports judge by,
computed by DOLFINx and by FElupe (``[fem] backend = "felupe"``, this study's cases).

- Table 3's continuum rows (plane strain exact, plane strain with the ANCF penalty, plane
  stress; the formulation table's continuum values are these same three): the Richardson
  values of DOLFINx (the ``continuum`` study's records: Q2 levels 16 x 1 ... 256 x 16)
  and of FElupe on its own mesh sequence (12 x 1 ... 96 x 8), so the two extrapolations
  share no mesh;
- the 3D beam at the paper's width (the formulation table's and width study's solid
  reference): DOLFINx's committed Richardson value (tests/gold/fem_cantilever_3d.json,
  graded 16 x 1 x 1 ... 64 x 4 x 4) against FElupe's on its own graded sequence
  (``solid_levels``, 12 x 1 x 1 ...);
- the hard loads (the ``hard-loads`` study's continuum runs, one mesh each, up to 1000 g
  and 200 N): the same scene on the same mesh by both codes, so the two discretisations
  are the same and the tips must agree to the Newton tolerance (:data:`SAME_MESH_RTOL`);
- the pendulum (the continuum pendulums of tests/gold/fem_pendulum.json, every law in plane
  stress and exactly incompressible plane strain, on 140 x 4 Q2 cells): FElupe's on its own
  mesh (``pendulum_aspect``: 112 x 4 cells) with its own estimate by the gold's rule
  (:func:`studies.verification.continuum_gold.pendulum.estimate_case`: runs at dt / 2 and on twice the cells,
  e(t) = 4/3 d_dt + 2 d_h), compared at t = 0.1 ... 0.5 s.

The check: two converged values differ by no more than the sum of their error
estimates (each the estimated error of its finest level, :mod:`reference_fem.convergence`,
so the bar is conservative for the extrapolated values); two same-mesh tips by no more
than SAME_MESH_RTOL of the tip. A disagreement beyond the bars, or a run that one code
finishes and the other does not, is printed as FAIL in the report and fails the
tiny-mode gold values.
"""
from __future__ import annotations

import json
import math

from reference_fem.backends import DEFAULT

from .continuum import scene as continuum_scene
from ..engine.case import make_case
from ..engine.report import Section, Table, mm
from .hard_loads import _scene as hard_scene
from .hard_loads import loads as hard_loads
from ..common.gold import GOLD_3D, GOLD_PENDULUM, VARIANT_LABEL, ContinuumReference, continuum_references, short


STUDY = {
    "name": "continuum-agreement",
    "title": "Continuum agreement: DOLFINx and FElupe on every continuum truth the reports use",
    "needs": ["continuum", "hard-loads"],
    "full": True,
    "grid": {
        "laws": ["neo-hookean", "mooney-rivlin", "yeoh"],
        "variants": ["plane-strain", "plane-strain-penalty", "plane-stress"],
        # FElupe's own sequence of Q2 meshes (no mesh shared with the continuum study's 16 x 1 ...):
        # cells along x, cells across; each level halves the cell size
        "levels": [[12, 1], [24, 2], [48, 4], [96, 8]],
        # the 3D beam (against the committed DOLFINx gold, 16 x 1 x 1 ... 64 x 4 x 4): FElupe's own
        # graded Q2/Q1 hexahedra, cells along x, across h, across w
        "solid_laws": ["neo-hookean", "mooney-rivlin", "yeoh"],
        "solid_levels": [[12, 1, 1], [24, 2, 2], [48, 4, 4]],
        # (the hard-load rows: the hard-loads study's continuum scenes, its grid)
        # the pendulum (against tests/gold/fem_pendulum.json, 140 x 4 cells): FElupe's own mesh,
        # cells_length = aspect x 4 (112 x 4), its own estimate from dt / 2 and 224 x 8
        "pendulum_laws": ["neo-hookean", "mooney-rivlin", "yeoh"],
        "pendulum_models": ["plane-stress", "plane-strain"],
        "pendulum_aspect": 2.5,
        "timeout_s": 1200.0,  # FElupe's 48 x 4 x 4 hexahedra and 224 x 8 plane-strain pendulum: minutes each
    },
    "tiny": {
        "laws": ["yeoh"],
        "levels": [[6, 1], [12, 2], [24, 4]],
        "solid_laws": [],
        "pendulum_laws": [],
    },
}

BACKEND = "felupe"
# Same mesh, same elements, same quadrature: the two codes' discrete problems are the same,
# so their tips differ by the Newton tolerance (||R|| <= 1e-8 ||R_ref||): measured 1e-12 to
# 1e-8 relative on the committed gold meshes (tests/test_felupe_backend.py, the same bound).
SAME_MESH_RTOL = 1e-6
# cells along x of the coarsest graded 3D mesh (its progression 8^(1/11): last cell 8 x the first)
SOLID_BASE = 12


def _on_felupe(d: dict) -> dict:
    """A scene dict moved to FElupe, named apart from its DOLFINx twin."""
    d["fem"]["backend"] = BACKEND
    d["name"] += f"-{BACKEND}"
    return d


def scene(law: str, variant: str, cells: tuple[int, int]) -> dict:
    """The continuum study's scene on FElupe."""
    return _on_felupe(continuum_scene(law, variant, cells))


def solid_scene(law: str, cells) -> dict:
    """The 3D beam of the committed DOLFINx gold (its scene: the paper's cantilever at the
    paper's width, clamped face, own weight) on FElupe: ``cells`` (along x, across h,
    across w) Q2/Q1 hexahedra, graded along x as the gold's meshes: at 12 cells the last
    cell is 8 times the first, and a mesh of nx cells splits each of those into nx / 12
    (the progression's (nx / 12)-th root, so that the levels nest)."""
    g = json.loads(GOLD_3D.read_text())["cases"][f"{law}/3d"]
    d = json.loads(json.dumps(g["scene"]))
    nx, ny, nz = (int(c) for c in cells)
    d["fem"] = {**g["base_mesh"], "cells_length": nx, "cells_height": ny, "cells_width": nz,
                "progression": (8.0 ** (1.0 / (SOLID_BASE - 1))) ** (SOLID_BASE / nx)}
    d["name"] = f"solid-{law}-3d-{nx}x{ny}x{nz}"
    return _on_felupe(d)


def hard_load_scenes(hard: dict) -> list[tuple[str, str, dict, dict]]:
    """[(law, load label, DOLFINx scene, FElupe scene)] of the hard-loads study's continuum
    runs (the label names the formulation where the study has several)."""
    out = []
    forms = list(hard["formulations"])
    for form in forms:
        for law in hard["laws"]:
            for label, _, load in hard_loads(hard, law):
                d = hard_scene(hard, law, form, label, load, None)
                tag = f"{label} ({form})" if len(forms) > 1 else label
                out.append((law, tag, d, _on_felupe(json.loads(json.dumps(d)))))
    return out


def pendulum_scenes(law: str, model: str, aspect: float) -> tuple[dict, dict, dict]:
    """FElupe's three runs of a pendulum case (base, dt / 2, twice the cells), named apart."""
    from studies.verification.continuum_gold.pendulum import convergence_scenes

    out = []
    for d in convergence_scenes(law, model, aspect=aspect):
        d["name"] += f"-ch{d['fem']['cells_height']}-dt{d['analysis']['dt'] * 1e3:g}ms"
        out.append(_on_felupe(d))
    return tuple(out)


def cases(grid: dict, tiny: bool) -> list:
    from ..engine.catalog import load_catalog

    out = [make_case("continuum-agreement", "continuum", scene(law, v, tuple(lv)))
           for law in grid["laws"] for v in grid["variants"] for lv in grid["levels"]]
    out += [make_case("continuum-agreement", "continuum", solid_scene(law, lv))
            for law in grid["solid_laws"] for lv in grid["solid_levels"]]
    hard = load_catalog(tiny=tiny)["hard-loads"].grid
    out += [make_case("continuum-agreement", "continuum", f) for _, _, _, f in hard_load_scenes(hard)]
    out += [make_case("continuum-agreement", "continuum", d) for law in grid["pendulum_laws"]
            for model in grid["pendulum_models"] for d in pendulum_scenes(law, model, grid["pendulum_aspect"])]
    return out


def _backend(rec: dict) -> str:
    return (rec["scene"].get("fem") or {}).get("backend", DEFAULT)


def _row(law: str, variant: str, ra: ContinuumReference, rb: ContinuumReference) -> dict:
    row = {"law": law, "variant": variant, "dolfinx": ra, "felupe": rb, "diff": None, "bar": None, "agree": None}
    if ra.tip and rb.tip and ra.error_estimate is not None and rb.error_estimate is not None:
        row["diff"] = math.hypot(ra.tip[0] - rb.tip[0], ra.tip[1] - rb.tip[1])
        row["bar"] = ra.error_estimate + rb.error_estimate
        row["agree"] = row["diff"] <= row["bar"]
    return row


def _kind(rec: dict) -> str:
    """Which truth a FElupe record belongs to: "pendulum", "solid" (3D), "hard" or "table3"."""
    s = rec["scene"]
    if s.get("analysis", {}).get("kind") == "dynamic":
        return "pendulum"
    if (s.get("fem") or {}).get("model") == "3d":
        return "solid"
    return "hard" if s["name"].startswith("hard-") else "table3"


def agreement(dolfinx_records: list[dict], felupe_records: list[dict]) -> list[dict]:
    """One row per (law, 2D variant) that both codes have: their Richardson tips (m), error
    estimates (m), the distance between the tips, the bar (sum of the estimates) and
    whether the tips agree within it (None without a Richardson value on either side)."""
    a = continuum_references([r for r in dolfinx_records if _backend(r) == "dolfinx"])
    b = continuum_references([r for r in felupe_records if _backend(r) == BACKEND and _kind(r) == "table3"])
    return [_row(key[0], key[1], a[key], b[key]) for key in b if key in a]


def solid_agreement(felupe_records: list[dict], gold=GOLD_3D) -> list[dict]:
    """Rows of the 3D beam: DOLFINx's committed Richardson value (the gold file: tip,
    error estimate, its levels) against FElupe's."""
    if not gold.exists():
        return []
    cases = json.loads(gold.read_text())["cases"]
    b = continuum_references([r for r in felupe_records if _backend(r) == BACKEND and _kind(r) == "solid"])
    rows = []
    for (law, variant), rb in b.items():
        c = cases.get(f"{law}/3d")
        if c is None:
            continue
        ra = ContinuumReference(law, variant, (c["tip"]["ux"], c["tip"]["uy"]) if c.get("tip") else None,
                                c.get("error_estimate_m"), c.get("order"),
                                [{**lv, "cells": tuple(lv[k] for k in ("cells_length", "cells_height", "cells_width"))}
                                 for lv in c["levels"]])
        rows.append(_row(law, variant, ra, rb))
    return rows


def hard_agreement(hard_records: list[dict], felupe_records: list[dict], hard: dict) -> list[dict]:
    """Rows of the hard loads, same scene and mesh on both codes: their tips, the distance,
    the bar SAME_MESH_RTOL |tip| and whether both finished and agree (False when only one
    converged: the two codes solve the same discrete problem)."""
    by_name = {r["scene"]["name"]: r for r in hard_records + felupe_records}
    rows = []
    for law, label, d, f in hard_load_scenes(hard):
        ra, rb = by_name.get(d["name"]), by_name.get(f["name"])
        if ra is None or rb is None:
            continue
        row = {"law": law, "load": label, "dolfinx": ra, "felupe": rb, "diff": None, "bar": None,
               "agree": None}
        ok_a, ok_b = ra.get("status") == "converged", rb.get("status") == "converged"
        if ok_a and ok_b:
            ta, tb = ra["tip"], rb["tip"]
            row["diff"] = math.hypot(ta["ux"] - tb["ux"], ta["uy"] - tb["uy"])
            row["bar"] = SAME_MESH_RTOL * math.hypot(ta["ux"], ta["uy"])
            row["agree"] = row["diff"] <= row["bar"]
        elif ok_a != ok_b:
            row["agree"] = False
        rows.append(row)
    return rows


def pendulum_agreement(felupe_records: list[dict], grid: dict, gold=GOLD_PENDULUM) -> list[dict]:
    """Rows of the pendulum, one per (law, model): at every output time t > 0 the distance
    between DOLFINx's gold tip and FElupe's base run, and the bar e_DOLFINx(t) +
    e_FElupe(t); the row's worst time (largest distance / bar)."""
    from studies.verification.continuum_gold.pendulum import estimate_case

    if not gold.exists():
        return []
    cases = json.loads(gold.read_text())["cases"]
    by_name = {r["scene"]["name"]: r for r in felupe_records}
    rows = []
    for law in grid["pendulum_laws"]:
        for model in grid["pendulum_models"]:
            scenes = pendulum_scenes(law, model, grid["pendulum_aspect"])
            recs = [by_name.get(d["name"]) for d in scenes]
            g = cases.get(f"{law}/{model}")
            if g is None or any(r is None for r in recs):
                continue
            f = estimate_case(law, model, scenes[0], scenes[0]["analysis"]["dt"], *recs)
            row = {"law": law, "variant": model, "dolfinx": g, "felupe": f, "t": None, "diff": None,
                   "bar": None, "agree": None}
            if f.get("values") and g.get("values"):
                worst = None
                for a, b, ea, eb in zip(g["values"], f["values"], g["error_estimate_m"], f["error_estimate_m"]):
                    if a["t"] <= 0 or abs(a["t"] - b["t"]) > 1e-12:
                        continue
                    d, bar = math.hypot(a["x"] - b["x"], a["y"] - b["y"]), ea + eb
                    if worst is None or d / bar > worst[1] / worst[2]:
                        worst = (a["t"], d, bar)
                if worst:
                    row.update(t=worst[0], diff=worst[1], bar=worst[2], agree=worst[1] <= worst[2])
            elif f["status"] != "converged":
                row["agree"] = False
            rows.append(row)
    return rows


def _finest(ref) -> str | None:
    lv = [x for x in ref.levels if x["status"] == "converged"]
    return " x ".join(str(c) for c in lv[-1]["cells"]) if lv else None


def _richardson_table(ctx, name: str, rows: list[dict], caption: str, sec: Section) -> None:
    table = []
    for r in rows:
        a, b = r["dolfinx"], r["felupe"]
        table.append([short(r["law"]), VARIANT_LABEL[r["variant"]],
                      mm(a.tip[0]) if a.tip else None, mm(a.tip[1]) if a.tip else None, mm(a.error_estimate),
                      _finest(a), mm(b.tip[0]) if b.tip else None, mm(b.tip[1]) if b.tip else None,
                      mm(b.error_estimate), _finest(b), mm(r["diff"]), mm(r["bar"]), _yes(r["agree"])])
    sec.table(ctx, Table(name,
                         ["law", "model", "DOLFINx ux (mm)", "DOLFINx uy (mm)", "DOLFINx est. (mm)", "DOLFINx finest",
                          "FElupe ux (mm)", "FElupe uy (mm)", "FElupe est. (mm)", "FElupe finest",
                          "distance (mm)", "bar (mm)", "within bar"], table,
                         {2: ".4f", 3: ".4f", 4: ".1e", 6: ".4f", 7: ".4f", 8: ".1e", 10: ".1e", 11: ".1e"}),
              caption)


def _yes(agree) -> str | None:
    return None if agree is None else ("yes" if agree else "NO")


def _status(rec: dict) -> str:
    return "converged" if rec.get("status") == "converged" else f"{rec.get('status')}: {rec.get('reason')}"


def report(ctx) -> Section:
    rows = agreement(ctx.records("continuum"), ctx.records())
    solid = solid_agreement(ctx.records())
    hard = hard_agreement(ctx.records("hard-loads"), ctx.records(), ctx.catalog["hard-loads"].grid)
    sec = Section(ctx.study.title,
                  "The continuum truths by two finite-element codes: DOLFINx (the `continuum` study, the "
                  "committed 3D gold, the `hard-loads` study) and FElupe (reference_fem's second backend). "
                  "Richardson values on different mesh sequences agree when their distance is within the sum "
                  "of the two error estimates; the hard loads run the same scene on the same mesh in both "
                  f"codes, so their tips must agree to the Newton tolerance ({SAME_MESH_RTOL:g} of the tip).")
    _richardson_table(ctx, "continuum_agreement", rows,
                      "Table 3's continuum values: Richardson tips of the two codes and their distance against the "
                      "combined error estimate (bar = DOLFINx's + FElupe's estimate).", sec)
    if solid:
        _richardson_table(ctx, "continuum_agreement_3d", solid,
                          "The 3D beam at the paper's width (7 mm; the formulation table's and the width study's "
                          "solid reference): DOLFINx's committed gold (graded hexahedra) against FElupe's own graded "
                          "sequence.", sec)
    if hard:
        table = []
        for r in hard:
            a, b = r["dolfinx"], r["felupe"]
            ta, tb = a.get("tip") or {}, b.get("tip") or {}
            table.append([short(r["law"]), r["load"], " x ".join(str(a["scene"]["fem"][k]) for k in
                                                                  ("cells_length", "cells_height")),
                          mm(ta.get("ux")), mm(ta.get("uy")), mm(tb.get("ux")), mm(tb.get("uy")),
                          None if a.get("status") == b.get("status") == "converged" else
                          f"DOLFINx {_status(a)}; FElupe {_status(b)}",
                          mm(r["diff"]), mm(r["bar"]), _yes(r["agree"])])
        sec.table(ctx, Table("continuum_agreement_hard_loads",
                             ["law", "load", "mesh", "DOLFINx ux (mm)", "DOLFINx uy (mm)", "FElupe ux (mm)",
                              "FElupe uy (mm)", "status", "distance (mm)", "bar (mm)", "within bar"], table,
                             {3: ".4f", 4: ".4f", 5: ".4f", 6: ".4f", 8: ".1e", 9: ".1e"}),
                  "The hard-load references (plane stress, one mesh): the same scene on the same mesh by both "
                  "codes.")
    pend = pendulum_agreement(ctx.records(), ctx.study.grid)
    if pend:
        table = []
        for r in pend:
            g, f = r["dolfinx"], r["felupe"]
            table.append([short(r["law"]), VARIANT_LABEL[r["variant"]],
                          " x ".join(str(g["fem"][k]) for k in ("cells_length", "cells_height")),
                          " x ".join(str(f["fem"][k]) for k in ("cells_length", "cells_height")) if f.get("fem") else None,
                          r["t"], mm(r["diff"]), mm(r["bar"]), _yes(r["agree"]),
                          mm(max(r["felupe"]["error_estimate_m"])) if f.get("error_estimate_m") else None])
        sec.table(ctx, Table("continuum_agreement_pendulum",
                             ["law", "model", "DOLFINx mesh", "FElupe mesh", "worst t (s)", "distance (mm)",
                              "bar (mm)", "within bar", "FElupe max est. (mm)"], table,
                             {4: ".1f", 5: ".4f", 6: ".4f", 8: ".4f"}),
                  "The pendulum (pinned, released from horizontal; dt 1 ms, generalized-alpha rho_inf 0.8): the "
                  "tip at t = 0.1 ... 0.5 s by DOLFINx (the gold) and by FElupe on its own mesh, each with its "
                  "estimate e(t) = 4/3 d_dt + 2 d_h (bar = the sum); the time of the largest distance / bar.")
    every = rows + solid + hard + pend
    label = [f"{short(r['law'])} {r.get('variant') or r.get('load')}" for r in every]
    bad = [n for n, r in zip(label, every) if r["agree"] is False]
    missing = [n for n, r in zip(label, every) if r["agree"] is None]
    verdict = "PASS" if every and not bad and not missing else "FAIL"
    sec.text = (f"Check: **{verdict}** ({len(every) - len(bad) - len(missing)} of {len(every)} within their bars"
                + (f"; beyond: {', '.join(bad)}" if bad else "")
                + (f"; not comparable: {', '.join(missing)}" if missing else "") + ").")
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
