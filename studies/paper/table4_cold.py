"""Table 4's first run after installing: the pendulum in a fresh Python process with an
empty numba cache (solver ``ancf-cold``: a new NUMBA_CACHE_DIR), so that the compiled
loops are compiled, as a user's first run would compile them without the set-up's
``ancf warm``. Each element's case runs twice in turn (the ``timing`` option's warm-up
and one timed run, both cold), serially after any pool; the record keeps the whole
process's wall time, the part from the first import on, and the solve alone.

A study declared in its own file (the registry, :mod:`studies.engine.catalog`); heavy
(each run compiles for about two minutes), so ``make study-full`` runs it.
"""
from __future__ import annotations

from ..engine.case import make_case
from ..engine.report import Section, Table
from ..common.pendulum_cases import describe_dynamic, pendulum_dict

STUDY = {
    "name": "table4-cold",
    "title": "Table 4's first run after installing: compiling included",
    "grid": {"elements": {"registered": {"tagged": "paper", "without": ["locking"]}}, "count": 32, "formulation": "plane-stress",
             "dt": 1e-3, "rho_inf": 0.5, "t_end": 0.5},
    "tiny": {"elements": []},
    "full": True,
}

COLD = "ancf-cold"


def cases(grid: dict, tiny: bool) -> list:
    return [make_case("table4-cold", COLD, pendulum_dict(el, grid["count"], grid["formulation"], grid["dt"],
                                                   rho_inf=grid["rho_inf"], t_end=grid["t_end"]),
                      {"timing": {"repeats": 1, "budget_s": 0.0}})
            for el in grid["elements"]]


def report(ctx) -> Section:
    sec = Section(ctx.study.title,
                  "The pendulum of Table 4 in a fresh Python process with an empty numba cache: what a first run "
                  "costs when nothing is compiled yet (the set-up's `ancf warm` compiles once per clone, so a "
                  "user's first `ancf run` loads the compiled code instead).")
    rows = []
    for r in sorted(ctx.records(), key=lambda r: r["scene"]["ancf"]["element"]):
        t, d = r.get("timing") or {}, describe_dynamic(r)
        rows.append([d["element"], d["elements"], d["formulation"], 1e3 * d["dt"], d["status"],
                     t.get("warmup_s"), t.get("median_s"), (r.get("cold") or {}).get("import_build_solve_s"),
                     r.get("wall_s")])
    sec.table(ctx, Table("table4_cold", ["element", "n", "formulation", "dt (ms)", "status",
                                         "first cold process s", "second cold process s",
                                         "of which imports + compile + build + solve s", "solve s"], rows,
                         {3: "g", 5: ".1f", 6: ".1f", 7: ".1f", 8: ".3f"}),
              "The first run after installing: the pendulum in a fresh Python process with an empty numba "
              "cache (a new NUMBA_CACHE_DIR), so the compiled loops are compiled, run twice in turn after the "
              "study's pool has finished; the whole process's wall time, the part from the first import on "
              "(of the second run), and the solve alone.")
    return sec
