"""The element card's cases and checks, as data: the grid of each part of the card, the
scenes of its probes (the slender probe, the slenderness sweep), the in-process checks and
their record. The card runs them (:mod:`studies.design.card`) and renders them
(:mod:`studies.design.card_report`); neither of those is imported here.
"""
from __future__ import annotations

import importlib
import json
import re
from functools import lru_cache
from pathlib import Path

import numpy as np

from ancf.checks.rank import ASPECTS
from contract import paper

from ..common.grid import DEFAULT, cantilever_case
from ..common.pendulum_cases import pendulum_dict
from ..engine import fingerprint as fp
from ..engine.case import Case, make_case

LAWS = ("neo-hookean", "mooney-rivlin", "yeoh")
GRID = {
    "laws": LAWS, "formulations": ("plane-stress", "plane-strain"),
    "counts": (4, 8, 16, 32, 64, 160, 320, 640),
    "timing": {"repeats": 3, "budget_s": 1.0},
    "locking": {"count": 64, "factors": (10.0, 1e2, 1e3, 1e4, 1e5, 1e6)},
    "pendulum": {"counts": (8, 16, 32, 64), "dt": 5e-4, "t_end": 0.5, "formulation": "plane-stress"},
    "slender": {"slenderness": (35.0, 70.0, 140.0), "counts": (4, 8, 16, 32)},
    "rules": ((2, 2), (3, 2), (3, 3), (5, 3)),
    "aspects": ASPECTS,                 # the rank tests' sweep, 35 .. 0.01
    "patch_aspects": (4.0, 1.0, 0.3, 0.1, 0.05),
}
TINY = {
    "laws": ("neo-hookean",), "formulations": ("plane-stress",), "counts": (4, 8, 16),
    "timing": {"repeats": 1, "budget_s": 0.2},
    "locking": {"count": 8, "factors": (10.0, 1e3)},
    "pendulum": {"counts": (4,), "dt": 1e-3, "t_end": 0.1, "formulation": "plane-stress"},
    "slender": {"slenderness": (35.0, 140.0), "counts": (8,)},
    "rules": ((3, 2), (3, 3)), "aspects": (1.0, 0.1), "patch_aspects": (1.0, 0.1),
}


def slug(element: str) -> str:
    """The element's name as a file stem."""
    return re.sub(r"[^A-Za-z0-9._-]+", "_", element)


def grid_for(tiny: bool) -> dict:
    return TINY if tiny else GRID


def import_modules(modules) -> None:
    for m in modules:
        importlib.import_module(m)


def element_imports(element: str) -> list[str]:
    """The module a fresh process imports to have ``element``: none for a built-in one,
    else the module that registered it (a case is what it runs: other modules imported
    beside it do not enter its cases)."""
    from ancf.elements import BUILTIN, ELEMENTS, get_element

    get_element(element)
    origin = ELEMENTS.origin.get(element, "__main__")
    if element in BUILTIN:
        return []
    if origin == "__main__":
        raise ValueError(f"card {element}: registered by a script; register it in an importable module "
                         "and name that with --import")
    return [origin]


def formulations_of(element: str, g: dict) -> list[str]:
    """The grid's formulations the element runs (a cable: plane stress alone)."""
    from ancf.checks.element import runs

    return [f for f in g["formulations"] if runs(element, f)]


def cases(element: str, tiny: bool = False) -> list[Case]:
    """Parts 4 to 9 as cases (tiny: the CI grid). What an element cannot run is left out
    (a cable: plane strain, so the volumetric-locking sweep; the card says why); a cable's
    card adds the slenderness sweep (part 9)."""
    from ancf.elements import get_element

    g, study = grid_for(tiny), f"card-{element}"
    imports = element_imports(element)
    opts = {"imports": imports} if imports else {}
    out = []
    forms = formulations_of(element, g)
    for form in forms:
        for law in g["laws"]:
            for n in g["counts"]:
                timed = {**opts, "timing": dict(g["timing"])} if form == "plane-stress" else opts
                out.append(cantilever_case(study, law, form, element, n, DEFAULT, "face", timed or None))
    lk = g["locking"]
    for law in g["laws"] if "plane-strain" in formulations_of(element, GRID) else ():
        c10 = paper.materials()[law]["C10"]
        for k in lk["factors"]:
            s = paper.cantilever_scene(law, "plane-strain", element, lk["count"], quadrature=None,
                                       penalty=k * c10, name=f"cantilever-{law}-plane-strain-{element}-"
                                       f"{lk['count']}-qdef-face-penalty{k:g}C10")
            out.append(make_case(study, "ancf", s, opts or None))
    sl = g["slender"]
    for ratio in sl["slenderness"]:
        for n in sl["counts"]:
            out.append(make_case(study, "ancf", slender_scene(element, ratio, n), opts or None))
    pd = g["pendulum"]
    for n in pd["counts"]:
        out.append(make_case(study, "ancf", pendulum_dict(element, n, pd["formulation"], pd["dt"],
                                                          t_end=pd["t_end"]), opts or None))
    if not get_element(element).family.section_field:
        sw = SLENDERNESS_TINY if tiny else SLENDERNESS
        for law in g["laws"]:
            for ratio in sw["ratios"]:
                for n in sw["counts"]:
                    out.append(make_case(study, "ancf", slenderness_scene(law, ratio, element, n), opts or None))
    return out


# The shear-locking probe: the pendulum's beam (L = 350 mm, w = 7 mm) as a cantilever of
# height L / ratio, Neo-Hookean in plane stress (small-strain E = 3 mu, G = mu), under a
# uniform load that deflects the tip by 1e-4 L (linear regime).
SLENDER = {"length": 0.350, "width": 0.007, "law": "neo-hookean", "deflection": 1e-4}


def beam_theory(ratio: float) -> tuple[float, float]:
    """(gravity g in m/s^2, tip deflection in m) of the probe of slenderness L / h =
    ``ratio`` by Timoshenko's beam: q L^4 / (8 E I) + q L^2 / (2 kappa G A), kappa = 5/6."""
    L, w = SLENDER["length"], SLENDER["width"]
    h = L / ratio
    m = paper.materials()[SLENDER["law"]]
    mu = 2.0 * m["C10"]
    E, A, I = 3.0 * mu, h * w, w * h ** 3 / 12.0
    q = SLENDER["deflection"] * L * 8.0 * E * I / L ** 4      # the bending part alone: 1e-4 L
    return q / (m["density"] * A), q * L ** 4 / (8.0 * E * I) + q * L ** 2 / (2.0 * 5.0 / 6.0 * mu * A)


# The slenderness sweep (part 9, a cable's card): the paper's cantilever (L = 160 mm,
# w = 7 mm, face clamp, plane stress) made h = L / (L/h), its gravity scaled by (32 / (L/h))^2
# so that the load parameter q L^3 / EI is the paper's at every L/h (the same large
# deflection, about 0.7 L; the strains, and the section's kappa h, grow as h / L): where does
# a centre-line model stop being within 1 %, 0.3 %, 0.1 % of the converged continuum
# (tests/gold/fem_slenderness.json, :mod:`studies.verification.slenderness_gold`)?
SLENDERNESS = {"ratios": (140.0, 70.0, 40.0, 32.0, 24.0, 16.0, 12.0, 8.0, 6.0, 4.0), "counts": (32, 64),
               "targets": (0.01, 0.003, 0.001)}
SLENDERNESS_TINY = {"ratios": (32.0, 8.0), "counts": (32,), "targets": (0.01, 0.003, 0.001)}


def slenderness_scene(law: str, ratio: float, element: str | None = None, n: int | None = None,
                      fem: dict | None = None) -> dict:
    """The paper's cantilever at L / h = ``ratio`` under the paper's load parameter
    (:data:`SLENDERNESS`), for ANCF (``element``, ``n``) or the continuum (``fem``)."""
    L = paper.CANTILEVER["length"]
    g = paper.GRAVITY * (L / paper.CANTILEVER["height"] / ratio) ** 2
    d = paper.cantilever_scene(law, "plane-stress", element, n, quadrature=None, gravity=g, fem=fem,
                               name=f"slenderness-{law}-Lh{ratio:g}" + (f"-{element}-{n}" if element else "-fem"))
    d["beam"] = {"length": L, "height": L / ratio, "width": paper.CANTILEVER["width"]}
    if element is None:
        d.pop("ancf", None)
    return d


def slender_scene(element: str, ratio: float, n: int) -> dict:
    g, _ = beam_theory(ratio)
    d = paper.cantilever_scene(SLENDER["law"], "plane-stress", element, n, quadrature=None, gravity=g,
                               name=f"slender-{element}-{n}-Lh{ratio:g}")
    d["beam"] = {"length": SLENDER["length"], "height": SLENDER["length"] / ratio, "width": SLENDER["width"]}
    return d


def measure_checks(element: str, tiny: bool = False) -> dict:
    """Parts 1 to 3, measured here (numbers in SI or as ratios)."""
    from ancf.checks import element as checks
    from ancf.elements import get_element
    from ancf.checks.rank import default_quadrature, rank_test, strain_test

    g, spec, rng = grid_for(tiny), get_element(element), np.random.default_rng(20211206)
    forms = {}
    for form in ("paper", "plane-strain", "plane-stress"):
        if not checks.runs(spec, form):
            continue                                # a cable: plane stress alone (the card says why)
        model = checks.small_model(element, "yeoh", form)
        forms[form] = {"energy_gradient": checks.energy_gradient(model, rng),
                       "tangent_gradient": checks.tangent_gradient(model, rng),
                       "rigid_motion": checks.rigid_motion(model, rng)}

    @lru_cache(maxsize=None)
    def tests(r, a):
        """One rule's two tests at l_e / h = a, run once: a declared default is mostly one of
        the grid's rules, and the same rule in both default columns."""
        lin = rank_test(spec, r, a)
        fs = strain_test(element, r, a) if lin["spurious"] == 0 else None
        return {**lin, "strain_ratio": fs["ratio"] if fs else None}

    rank = []
    for a in g["aspects"]:
        row = {"aspect": a, "default": {"plane-stress": list(default_quadrature(spec, False, a)),
                                        "penalised": list(default_quadrature(spec, True, a))}, "rules": {}}
        for r in g["rules"]:
            row["rules"][f"{r[0]}x{r[1]}"] = tests(r, a)
        row["default_tests"] = {k: tests(tuple(r), a) for k, r in row["default"].items()}
        rank.append(row)
    patch = [{"aspect": a, **checks.patch(spec, length=a * 0.005 * 3)} for a in g["patch_aspects"]]
    return {"element": element, "definition": repr(spec),
            "nodality": checks.nodality(spec), "reference_state": checks.reference_state(spec),
            "mass": checks.mass(spec), "formulations": forms, "patch": patch,
            "conformity": checks.conformity(spec), "rank": rank, "slender_strains": slender_strains(element, g),
            "clamp_probe": clamp_probe(element, g), "section": section_model(element, g), "tiny": tiny}


SECTION_CURVATURES = (0.1, 0.2, 0.3, 0.5)       # kappa h of a cable's section-model table


def section_model(element: str, g: dict) -> list[dict] | None:
    """A cable's section model (None for other elements): its bending moment at N = 0 per
    law and kappa h (:func:`ancf.kinematics.cable.model.section_moment`, the element's own rule across and 64
    points), with the thickness change d eta / dY = lambda^-1/2 instead of eta = Y, and the
    exact plane-stress pure bending (:func:`studies.verification.closed_forms.plane_stress_bending`), each
    as M / (EI kappa), EI = 3 mu h^3 / 12 per width."""
    from ancf.kinematics.cable.model import section_moment
    from ancf.checks.element import law_constants, paper_material
    from ancf.elements import get_element
    from ancf.checks.rank import default_quadrature
    from mechanics.laws import get_law
    from ..verification.closed_forms import plane_stress_bending

    spec = get_element(element)
    if spec.family.section_field:
        return None
    h = paper.CANTILEVER["height"]
    across = default_quadrature(spec, False, 1.0)[1]
    rows = []
    for law in g["laws"]:
        c = dict(law_constants(law))
        c.pop("density")
        mat = paper_material(law, "plane-stress")
        EI = 3.0 * get_law(law).shear_modulus(c) * h ** 3 / 12.0
        for kh in SECTION_CURVATURES[:2] if g is TINY else SECTION_CURVATURES:
            k = kh / h
            M = lambda **kw: section_moment(mat, k, h, **kw)["moment_per_width"] / (EI * k)
            rows.append({"law": law, "kappa_h": kh, "cable": M(), "rule": M(points=across),
                         "thickness_change": M(thickness_change=True),
                         "exact": plane_stress_bending(law, c, k, h)["moment_per_width"] / (EI * k)})
    return rows


def slender_strains(element: str, g: dict) -> list[dict]:
    """The slender probe's mechanism: its states solved here (small meshes, the linear
    regime) and split by :func:`ancf.checks.element.strain_split`, with Timoshenko's shear share
    1.2 (h / L)^2 beside each."""
    from ancf.checks.element import strain_split
    from ancf.simulation import run_scene
    from contract.scene import scene_from_dict

    from ancf.elements import get_element

    rows = []
    if not get_element(element).family.section_field:       # no section field to split: its strain is its fibres' alone
        return rows
    for ratio in g["slender"]["slenderness"]:
        for n in g["slender"]["counts"]:
            rec, (model, res) = run_scene(scene_from_dict(slender_scene(element, ratio, n)))
            if rec["status"] != "converged":
                continue
            rows.append({"slenderness": ratio, "n": n, **strain_split(model, res.u),
                         "beam_shear_share": 1.2 / ratio ** 2 / (1.0 + 1.2 / ratio ** 2)})
    return rows


def checks_source() -> str:
    """The fingerprint of what :func:`measure_checks` runs (its code, normalised, and the
    packages it uses): a checks record is measured again when it changes."""
    f = fp.fingerprint((fp.entry(measure_checks),))
    return fp.digest(f)


def checks_path(out: Path, element: str) -> Path:
    return Path(out) / "data" / f"card-{slug(element)}-checks.json"


def _current_checks(element: str, out: Path, tiny: bool) -> dict | None:
    """The stored checks record if it was measured for today's element definition and code."""
    from ancf.elements import get_element

    path = checks_path(out, element)
    if not path.exists():
        return None
    rec = json.loads(path.read_text())
    same = (rec.get("definition"), rec.get("source"), rec.get("tiny")) == (
        repr(get_element(element)), checks_source(), tiny)
    return rec if same else None


def checks_current(element: str, out: Path, tiny: bool = False) -> bool:
    """Is the element's stored checks record of today's definition and code?"""
    return _current_checks(element, out, tiny) is not None


def checks_record(element: str, out: Path, tiny: bool = False, force: bool = False) -> dict:
    """The stored parts 1 to 3, measured again when missing, forced, or when the element's
    definition or ancf's sources changed."""
    path = checks_path(out, element)
    if not force and (rec := _current_checks(element, out, tiny)) is not None:
        return rec
    rec = measure_checks(element, tiny)
    rec = {"element": rec.pop("element"), "definition": rec.pop("definition"), "source": checks_source(), **rec}
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(rec, indent=1, default=_plain))
    tmp.replace(path)
    return rec


def _plain(o):
    if isinstance(o, (np.floating, np.integer)):
        return o.item()
    if isinstance(o, np.bool_):
        return bool(o)
    raise TypeError(type(o))


def clamp_probe(element: str, g: dict) -> dict | None:
    """For an element whose face clamp fixes more than r and r_y (r_yy, ...: the clamped
    face cannot contract, as in the continuum): the most slender probe's error against
    beam theory on the probe's meshes, clamped as scenes clamp it and with only r and r_y
    fixed (in memory), so the card can say what the clamp does to the order. None for
    other elements."""
    from dataclasses import replace

    from ancf.build import build_model, external_loads, plan
    from ancf.elements import KINDS, get_element
    from ancf.solvers.statics import solve_static
    from contract.scene import scene_from_dict

    spec = get_element(element)
    extra = [k for k in spec.kinds if KINDS[k][0] == 0 and KINDS[k][1] >= 2]
    if not extra:
        return None
    ratio = max(g["slender"]["slenderness"])
    exact = beam_theory(ratio)[1]
    out = {"slenderness": ratio, "freed": extra, "counts": list(g["slender"]["counts"]), "face": [], "freed_errors": []}
    for n in g["slender"]["counts"]:
        p = plan(scene_from_dict(slender_scene(element, ratio, n)))
        model = build_model(p)
        f = sum(external_loads(model, p).values())
        freed = replace(model, fixed=model.mesh.dofs(0, ("r", "r_y")))
        for key, m in (("face", model), ("freed_errors", freed)):
            res = solve_static(m, f)
            out[key].append((-float(m.tip_displacement(res.u)[1]) - exact) / exact
                            if res.status == "converged" else None)
    return out


