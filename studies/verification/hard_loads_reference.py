"""The continuum refinement behind the hard-load sweep: every (formulation, law, load) of
hard-loads on the meshes of its ``reference_levels`` (cells halving), so that hard-loads
can judge ANCF against the continuum's Richardson value with its error estimate rather
than one mesh. No report of its own: hard-loads draws it. Heavy (the finest level of
every hard case), so ``make study-full`` runs it.
"""
from __future__ import annotations

from ..engine.report import Section
from .hard_loads import reference_cases


STUDY = {
    "name": "hard-loads-reference",
    "title": "Hard cases: the continuum's refinement behind the hard-load references",
    "full": True,
    "grid": {
        "laws": ["neo-hookean", "mooney-rivlin", "yeoh"],
        "formulations": ["plane-stress", "plane-strain"],
        "gravity_factors": [1.0, 10.0, 100.0, 1000.0],
        "tip_forces": [1.0, 20.0, 200.0],
        "end_moment_turns": [0.25, 0.5, 1.0],
        "continuum_cells": [64, 4],
        "reference_levels": [[32, 2], [64, 4], [128, 8]],
        "wall_time": 600.0,
        # the costly elements' hard loads (ANCF, hard-loads' count and wall_time), drawn in hard-loads' table
        "elements": {"registered": {"tagged": "costly"}},
    },
    "tiny": {
        "elements": [],
        "laws": ["yeoh"],
        "formulations": ["plane-stress"],
        "gravity_factors": [100.0],
        "tip_forces": [20.0],
        "continuum_cells": [16, 1],
        "reference_levels": [[8, 1], [16, 1], [32, 2]],
    },
}


def cases(grid: dict, tiny: bool) -> list:
    return reference_cases(grid, tiny)


def report(ctx) -> Section:
    recs = ctx.records()
    n = sum(r["solver"] != "ancf" for r in recs)
    failed = [r["scene"]["name"] for r in recs if r["status"] != "converged"]
    return Section(ctx.study.title, f"{n} continuum runs, the refinement levels of the hard-load sweep's references, "
                                    f"and {len(recs) - n} ANCF runs of the elements the sweep leaves to this study "
                                    "(all drawn in its table)."
                   + (f" Failed: {', '.join(failed)}." if failed else ""))
