"""A card's records as its sections read them (:mod:`studies.design.card_report`,
:mod:`studies.design.card_locking`, :mod:`studies.design.card_cable`): the element's
records in its cases' order, its runs by kind (static, the locking sweep, the slender
probe, the slenderness sweep), and the cells' formatting."""
from __future__ import annotations

import math
from pathlib import Path

from .card_cases import cases, slug
from ..engine.store import store_for


def _f(v, spec=".3g"):
    return "-" if v is None or (isinstance(v, float) and not math.isfinite(v)) else format(v, spec)


def _yes(ok) -> str:
    return "pass" if ok else "**fail**"


def _records(element: str, out: Path, tiny: bool) -> list[dict]:
    have = store_for(out, f"card-{slug(element)}").read()
    return [have[c.id] for c in cases(element, tiny) if c.id in have]


def _static(recs):
    for r in recs:
        s = r["scene"]
        if s["analysis"]["kind"] == "static":
            yield r, s["material"], s["ancf"]["elements"]


def _is_locking(r) -> bool:
    return "penalty" in r["case"]["name"]


def _is_slender(r) -> bool:
    return r["case"]["name"].startswith("slender-")


def _is_sweep(r) -> bool:
    """A run of the slenderness sweep (part 9, a cable's card)."""
    return r["case"]["name"].startswith("slenderness-")


def _close(fig):
    import matplotlib.pyplot as plt
    plt.close(fig)
