"""Reading records: what a record describes, and the continuum reference it is judged by.

:func:`describe` pulls the grid coordinates out of a record's scene (law, formulation,
element, count, quadrature, clamp; for the continuum its model variant and mesh), so
that reports need no side tables. :func:`continuum_references` turns the continuum
study's records into the converged value of each (law, variant): the Richardson value
of its last three converged levels (:func:`reference_fem.convergence.richardson`,
pure numpy). :data:`MATCHING` says which continuum variant an ANCF formulation is
judged by.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from contract.paper import paper_tip

from .grid import DEFAULT, rule

# ANCF formulation -> continuum variant of the same model (``paper`` has no continuum
# meaning; its energies are plane-strain-like, so plane strain with the penalty is shown).
MATCHING = {"plane-strain": "plane-strain-penalty", "plane-stress": "plane-stress",
            "paper": "plane-strain-penalty"}
VARIANT_LABEL = {"plane-strain": "plane strain, exact (mixed)",
                 "plane-strain-penalty": "plane strain, penalty 1000 MPa",
                 "plane-stress": "plane stress (F33 = 1/J)",
                 "3d": "3D beam, exact (mixed)"}
LAW_SHORT = {"neo-hookean": "NH", "mooney-rivlin": "MR", "yeoh": "Yeoh"}


def short(law: str) -> str:
    """A law's short name in table headers (its own name for a law without one)."""
    return LAW_SHORT.get(law, law)


def variant_of(scene: dict) -> str:
    """The continuum variant of a continuum scene (gold-file names)."""
    fem = scene.get("fem") or {}
    if fem.get("model") == "3d":
        return "3d"
    if scene["material"]["formulation"] == "plane-stress" or fem.get("model") == "plane-stress":
        return "plane-stress"
    return "plane-strain-penalty" if fem.get("incompressibility") == "penalty" else "plane-strain"


def describe(rec: dict) -> dict:
    s = rec["scene"]
    d = {"law": s["material"]["law"], "solver": rec["solver"], "status": rec.get("status"),
         "tip": rec.get("tip"), "stable": rec.get("stable"), "stability": rec.get("stability")}
    if rec["solver"] == "ancf":
        a = s["ancf"]
        d.update(formulation=s["material"]["formulation"], element=a["element"],
                 elements=a["elements"], quadrature=rule(a.get("quadrature", DEFAULT)),
                 rule_used=tuple(rec["quadrature"]) if rec.get("quadrature") else None,
                 clamp=s["supports"].get("clamp"))
    else:
        fem = s.get("fem") or {}
        cells = (fem.get("cells_length"), fem.get("cells_height"))
        d.update(variant=variant_of(s), cells=cells + ((fem.get("cells_width", 1),) if fem.get("model") == "3d" else ()))
    return d


@dataclass
class ContinuumReference:
    law: str
    variant: str
    tip: tuple[float, float] | None          # m, Richardson value
    error_estimate: float | None             # m
    order: float | None
    levels: list[dict] = field(default_factory=list)  # {cells, ndof, tip, status, wall_s}


def continuum_references(records: list[dict]) -> dict[tuple[str, str], ContinuumReference]:
    """{(law, variant): reference} from the continuum study's records."""
    from reference_fem.convergence import richardson

    groups: dict[tuple[str, str], list[dict]] = {}
    for r in records:
        d = describe(r)
        groups.setdefault((d["law"], d["variant"]), []).append(
            {"cells": d["cells"], "ndof": r.get("ndof"), "tip": r.get("tip"), "status": r.get("status"),
             "wall_s": r.get("wall_s"), "setup_s": r.get("setup_s")})
    out = {}
    for key, levels in groups.items():
        levels.sort(key=lambda lv: math.prod(lv["cells"]))
        tips = [(lv["tip"]["ux"], lv["tip"]["uy"]) for lv in levels
                if lv["status"] == "converged" and lv["tip"]]
        ref = richardson(*tips[-3:]) if len(tips) >= 3 else None
        out[key] = ContinuumReference(key[0], key[1], ref.value if ref else None,
                                      ref.error_estimate if ref else None,
                                      ref.order if ref else None, levels)
    return out


def gold_references(path) -> dict[tuple[str, str], tuple[float, float]]:
    """{(law, variant): (ux, uy)} from reference_fem's gold file (for the cross-check)."""
    import json
    g = json.loads(open(path).read())
    return {(c["law"], k.split("/", 1)[1]): (c["tip"]["ux"], c["tip"]["uy"])
            for k, c in g["cases"].items() if c.get("tip")}


GOLD_3D = Path(__file__).resolve().parents[2] / "tests" / "gold" / "fem_cantilever_3d.json"
GOLD_PENDULUM = Path(__file__).resolve().parents[2] / "tests" / "gold" / "fem_pendulum.json"
SOLID_LABEL = "3D beam (w = 7 mm)"


def solid_references(path=GOLD_3D) -> dict[str, tuple[float, float]]:
    """{law: (ux, uy)} of the converged 3D beam at the paper's width (the Richardson
    values of ``python -m studies continuum gold --3d``, tests/gold/fem_cantilever_3d.json,
    with the meshes and versions that made them), or {} without that file."""
    if not Path(path).exists():
        return {}
    return {law: tip for (law, variant), tip in gold_references(path).items() if variant == "3d"}


def abaqus(law: str) -> tuple[float, float] | None:
    return paper_tip("ABAQUS", law)


def stability_mark(d: dict) -> str:
    """"" for a stable (or unchecked) equilibrium, else " (singular)" / " (unstable)"."""
    if d.get("stable") is False:
        return " (singular)" if "singular" in str(d.get("stability")) else " (unstable)"
    return ""


def is_continuum(rec: dict) -> bool:
    """Was the record made by a continuum backend (its label, :data:`reference_fem.backends.BACKENDS`)?"""
    from reference_fem.backends import BACKENDS

    return rec.get("solver") in BACKENDS
