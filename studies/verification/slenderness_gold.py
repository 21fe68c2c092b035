"""The continuum references of the cards' slenderness sweep (:data:`studies.design.card.SLENDERNESS`):
the paper's cantilever at L / h = 140 ... 4 under the paper's load parameter, converged.

``python -m studies slenderness-gold`` writes ``tests/gold/fem_slenderness.json`` (DOLFINx,
plane stress, face clamp, Q2 quadrilaterals): for each law and L / h a refinement sequence
from cells of aspect 2 (L / h / 2 x 1 cells), halved in both directions (5 levels up to
L / h = 40, 4 beyond: the finest has 16 or 8 cells across h and at most 40 000 unknowns),
its observed order, Richardson value and error estimate (:func:`reference_fem.convergence.
refinement_study`, the same as the paper's cantilever gold). At L / h = 32 the scene is
the paper's, and its levels are the cantilever gold's to round-off. The cards read the file;
nothing here runs in a test.
"""
from __future__ import annotations

import json
import time
from pathlib import Path

from contract.scene import scene_from_dict
from reference_fem.convergence import refinement_study
from reference_fem.settings import FemSettings, default_quadrature_degree

from ..design.card_cases import LAWS, SLENDERNESS, slenderness_scene

ROOT = Path(__file__).resolve().parents[2]
GOLD = ROOT / "tests" / "gold" / "fem_slenderness.json"


def levels_for(ratio: float) -> int:
    return 5 if ratio <= 40 else 4


def gold_case(law: str, ratio: float, progress=None) -> dict:
    scene = scene_from_dict(slenderness_scene(law, ratio, fem={"model": "plane-stress"}))
    base = FemSettings("plane-stress", "exact", cells_length=max(1, round(ratio / 2)), cells_height=1,
                       cell="quadrilateral", degree=2, quadrature_degree=default_quadrature_degree(2))
    d = refinement_study(scene, levels_for(ratio), base, progress=progress).to_dict()
    return {"law": law, "slenderness": ratio, "tip": d["extrapolated"], "error_estimate_m": d["error_estimate"],
            "order": d["order"], "orders": d["orders"], "finest": d["levels"][-1]["tip"], "base_mesh": d["base"],
            "levels": d["levels"], "scene": d["scene"]}


def write_gold(path: Path = GOLD, laws=LAWS, ratios=SLENDERNESS["ratios"], log=print) -> Path:
    from reference_fem.dolfinx_backend.fem import VERSION      # dolfinx, which the runs need anyway

    cases = {}
    for law in laws:
        for ratio in ratios:
            t0 = time.perf_counter()
            c = gold_case(law, ratio)
            cases[f"{law}/Lh{ratio:g}"] = c
            rel = c["error_estimate_m"] / (c["tip"]["ux"] ** 2 + c["tip"]["uy"] ** 2) ** 0.5 if c["tip"] else None
            log(f"{law} L/h {ratio:g}: tip {c['tip']}, order {c['order']}, estimate {rel:.2e} relative "
                f"({time.perf_counter() - t0:.1f} s)")
    doc = {"description": "The paper's cantilever (L = 160 mm, w = 7 mm, face clamp, plane stress) at L / h = "
                          "140 ... 4 under the paper's load parameter (gravity 9.81 (32 / (L/h))^2 m/s^2): the "
                          "tip (free-end centre) in m, Richardson-extrapolated over uniform refinement "
                          "(reference_fem.convergence). Regenerate: python -m studies slenderness-gold",
           "generator": "python -m studies slenderness-gold", "dolfinx": VERSION, "units": "m",
           "comparison": "a tip agrees with the continuum to |u - u_ref| / |u_ref|; the reference's own error "
                         "is error_estimate_m", "cases": cases}
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".json.tmp")
    tmp.write_text(json.dumps(doc, indent=1) + "\n")
    tmp.replace(path)
    return path


def references(path: Path = GOLD) -> dict[tuple[str, float], dict]:
    """{(law, L/h): {"tip": (ux, uy), "error": relative error estimate}} from the gold file
    ({} without it)."""
    path = Path(path)
    if not path.exists():
        return {}
    out = {}
    for c in json.loads(path.read_text())["cases"].values():
        if c.get("tip"):
            tip = (c["tip"]["ux"], c["tip"]["uy"])
            out[(c["law"], float(c["slenderness"]))] = {
                "tip": tip, "error": c["error_estimate_m"] / (tip[0] ** 2 + tip[1] ** 2) ** 0.5}
    return out


def add_commands(sub) -> None:
    """The ``slenderness-gold`` command on the sub-parsers of ``python -m studies``."""
    p = sub.add_parser("slenderness-gold", help="the continuum references of the cards' slenderness sweep "
                                                "(DOLFINx): tests/gold/fem_slenderness.json")
    p.add_argument("--laws", nargs="*", default=list(LAWS))
    p.add_argument("--out", type=Path, default=GOLD)


def command(a) -> int:
    """The ``slenderness-gold`` command: :func:`write_gold`."""
    write_gold(a.out, tuple(a.laws))
    return 0

