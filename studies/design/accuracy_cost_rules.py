"""Accuracy against cost, the fixed rules: the paper's four elements with the quadrature
rules [2, 2] (the paper's), [3, 2] and [5, 3] on the static cantilever, timed as the study
accuracy-cost times the defaults. Its records are drawn in accuracy-cost's diagram and
tables beside the defaults (:func:`studies.design.accuracy_cost_points.points`); it has no report of its
own. Heavy (a rule that misses modes takes thousands of Newton iterations at 640
elements), so ``make study-full`` runs it.
"""
from __future__ import annotations

from .accuracy_cost import cases as _cases
from ..engine.report import Section


STUDY = {
    "name": "accuracy-cost-rules",
    "title": "Accuracy against cost: the paper's elements with fixed quadrature rules",
    "needs": ["continuum"],
    "full": True,
    "grid": {
        "laws": ["neo-hookean", "mooney-rivlin", "yeoh"],
        "elements": {"registered": {"tagged": "paper"}},
        "formulations": ["plane-strain", "plane-stress"],
        "quadratures": [[2, 2], [3, 2], [5, 3]],
        "counts": [4, 8, 16, 32, 64, 160, 320, 640],
        "clamp": "face",
        "timing": {"repeats": 3, "budget_s": 2.0},
        "continuum_levels": [],
    },
    "tiny": {
        "laws": ["yeoh"],
        "elements": ["HB2n-12"],
        "quadratures": [[3, 2]],
        "counts": [4],
        "timing": {"repeats": 2, "budget_s": 0.5},
    },
}


def cases(grid: dict, tiny: bool) -> list:
    return _cases(grid, tiny, "accuracy-cost-rules")


def report(ctx) -> Section:
    n = len(ctx.records())
    return Section(ctx.study.title, f"{n} runs, drawn in the accuracy-cost diagram and its tables beside each "
                                    "element's default rule.")
