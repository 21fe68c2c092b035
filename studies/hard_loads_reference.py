"""The continuum refinement behind the hard-load sweep: every (formulation, law, load) of
hard-loads on the meshes of its ``reference_levels`` (cells halving), so that hard-loads
can judge ANCF against the continuum's Richardson value with its error estimate rather
than one mesh. No report of its own: hard-loads draws it. Heavy (the finest level of
every hard case), so ``make study-full`` runs it.
"""
from __future__ import annotations

from .engine.report import Section
from .hard_loads import reference_cases


def cases(grid: dict, tiny: bool) -> list:
    return reference_cases(grid, tiny)


def report(ctx) -> Section:
    n = len(ctx.records())
    failed = [r["scene"]["name"] for r in ctx.records() if r["status"] != "converged"]
    return Section(ctx.study.title, f"{n} continuum runs, the refinement levels of the hard-load sweep's references "
                                    "(drawn in its table)."
                   + (f" Failed: {', '.join(failed)}." if failed else ""))
