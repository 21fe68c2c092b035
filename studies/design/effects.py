"""Only the effects a scene calls for: which effects the records of each kind of scene
list, and what each effect costs when it is assembled, measured side by side.

A static scene assembles no mass matrix; a scene without a tip force builds no tip-force
vector; a formulation without a penalty has no penalty term. The cases here solve the
paper's static cantilever as it is and then, in the same process (solver
``ancf-effects``), time each effect's assembly: the whole static solve as is against the
same followed by the mass matrix (inertia assembled but unused), one internal force and
tangent (elastic law, plus the penalty term in `plane-strain`; `plane-stress` has none),
the mass matrix, the gravity and tip-force vectors. The two solves run alternately (15 pairs), each assembly alone 7 times, after a warm-up;
with their spread.

A study declared in its own file (the registry, :mod:`studies.engine.catalog`).
"""
from __future__ import annotations

from contract import paper

from ..engine.case import make_case
from ..engine.report import Section, Table

STUDY = {
    "name": "effects",
    "title": "Only the effects a scene calls for: what each effect costs",
    "grid": {"law": "neo-hookean", "element": "HB2n-12", "counts": [16, 160],
             "formulations": ["plane-strain", "plane-stress"], "tip_force": [0.0, -0.05]},
    "tiny": {"counts": [4]},
}

COST_KEYS = ("static_solve", "static_solve_with_mass_matrix", "tangent", "mass_matrix", "gravity", "tip_force")


def scene(g: dict, n: int, formulation: str, tip: bool) -> dict:
    d = paper.cantilever_scene(g["law"], formulation, g["element"], n,
                               name=f"effects-{formulation}-{g['element']}-{n}" + ("-tip" if tip else ""))
    if tip:
        d["loads"]["tip_force"] = list(g["tip_force"])
    return d


def cases(grid: dict, tiny: bool) -> list:
    # a timing option: run serially after any pool (never timed on a busy pool); one
    # warm-up run of the whole measurement, then the recorded one
    opts = {"timing": {"repeats": 1, "budget_s": 600.0}}
    return [make_case("effects", "ancf-effects", scene(grid, n, f, tip), opts)
            for f in grid["formulations"] for n in grid["counts"] for tip in (False, True)]


def kinds(ctx) -> list[list]:
    """[study, solver, kind, effects, records] of every study's records."""
    rows: dict = {}
    for name in ctx.catalog:
        for r in ctx.records(name):
            kind = ((r.get("scene") or {}).get("analysis") or {}).get("kind", "?")
            key = (name, r.get("solver"), kind, ", ".join(r.get("effects") or []) or "-")
            rows[key] = rows.get(key, 0) + 1
    return [list(k) + [v] for k, v in rows.items()]


def _ms(c: dict, key: str):
    x = c.get(key)
    return None if x is None else 1e3 * x["median_s"]


def _spread(c: dict, key: str):
    x = c.get(key)
    return None if x is None else f"{1e3 * x['min_s']:.3g}-{1e3 * x['max_s']:.3g}"


def report(ctx) -> Section:
    sec = Section(ctx.study.title,
                  "Every record lists the effects its solver assembled (record key effects); a scene gets only those it "
                  "calls for. Below: the effects per study and kind of scene, then what each effect costs when "
                  "assembled, measured side by side on the static cantilever (in one process after a warm-up: the solves "
                  "as 15 alternating pairs, each assembly alone as the median of 7; spread min-max; solver ancf-effects).")
    sec.table(ctx, Table("effects_by_kind", ["study", "solver", "kind", "effects", "records"], kinds(ctx)),
              "The effects the records of each study list, per solver and kind of scene.")
    rows, lines = [], []
    for r in ctx.records():
        c = r.get("effect_costs")
        sc = r["scene"]
        label = f"{sc['ancf']['element']} x {sc['ancf']['elements']} `{sc['material']['formulation']}`" + (
            " + tip force" if sc["loads"].get("tip_force") else "")
        if not c:
            rows.append([label, ", ".join(r.get("effects") or []), r["status"]] + [None] * 8)
            continue
        base, with_m = _ms(c, "static_solve"), _ms(c, "static_solve_with_mass_matrix")
        diff = _ms(c, "mass_matrix_paired_difference")
        rows.append([label, ", ".join(r.get("effects") or []), r["status"], base, _spread(c, "static_solve"), with_m,
                     diff, _spread(c, "mass_matrix_paired_difference"), _ms(c, "tangent"), _ms(c, "mass_matrix"),
                     _ms(c, "gravity"), _ms(c, "tip_force")])
        m = _ms(c, "mass_matrix")
        if base and m is not None:
            lines.append(f"- {label}: the mass matrix alone costs {m:.3g} ms, {100 * m / base:.1f} % of the static "
                         f"solve ({base:.3g} ms); side by side the difference is {diff:.3g} ms (median of paired runs, "
                         f"spread {_spread(c, 'mass_matrix_paired_difference')} ms).")
    sec.table(ctx, Table("effects_cost", ["scene", "effects (record)", "status", "static solve ms", "spread ms",
                                          "same + mass matrix ms", "paired difference ms", "its spread ms",
                                          "one tangent ms", "mass matrix ms", "gravity vector ms",
                                          "tip-force vector ms"], rows,
                         {3: ".3g", 5: ".3g", 6: "+.3g", 8: ".3g", 9: ".3g", 10: ".3g", 11: ".3g"}),
              "What each effect costs when assembled: the static solve as is against the same with the mass matrix "
              "assembled but unused (run alternately, 15 pairs; the paired difference's median and spread), and each "
              "assembly alone (one tangent: the elastic law, with the penalty term in "
              "`plane-strain` only). '-': an effect the scene does not call for.")
    sec.text = "\n".join(lines)
    return sec


def audit(ctx) -> list[str]:
    """Every record lists the effects it called for: a static record lists no inertia,
    a record without a tip force lists no tip force."""
    out = []
    for name in ctx.catalog:
        for r in ctx.records(name):
            eff = set(r.get("effects") or [])
            sc = r.get("scene") or {}
            kind = (sc.get("analysis") or {}).get("kind")
            if r.get("solver") == "ancf" and kind == "static" and "inertia" in eff:
                out.append(f"data/{name}.jsonl: static record {sc.get('name')} lists inertia")
            if "tip_force" in eff and not (sc.get("loads") or {}).get("tip_force"):
                out.append(f"data/{name}.jsonl: record {sc.get('name')} lists a tip force its scene has not")
    return out
