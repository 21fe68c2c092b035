"""A law's card: a law of the shared table (mechanics.laws) run by both solvers.

For each law in the grid: the law itself (energy, constants, the shear modulus derived
from the energy) and the paper's cantilever with the law's example constants in plane
stress and in penalised plane strain, by the continuum (Q2, three levels, Richardson)
and by ANCF elements on a refinement sequence. A law's own effect is checked apart from
the elements' discretisation error: the tip of the law minus the tip of neo-Hookean with
the same small-strain stiffness (C10 = mu / 2), by each solver. The law's energy is one
function both solvers run (pointwise equal: tests/test_reference_fem_laws.py), so a
difference in the effect comes from the fields or the quadrature: each ANCF mesh runs
with its default rule and with the grid's richer rules, whose number of points across
the thickness is what a law of higher degree in the strain needs (Gent's extra energy
grows like (I1 - 3)^2 ~ y^4 across a bent section, which 2 Gauss points integrate to
5/9 of its value).
"""
from __future__ import annotations

from contract import paper
from contract.scene import FORMULATIONS
from mechanics.laws import get_law

from ..engine.case import make_case
from ..engine.report import Section, Table, mm, pct
from ..common.gold import continuum_references, is_continuum


STUDY = {
    "name": "law-card",
    "title": "Law cards: a law of the shared table run by both solvers",
    "full": True,
    "grid": {
        "laws": ["gent"],
        "elements": ["HB2n-12", "HB3n-12"],
        "counts": [16, 64],
        # the element's default rule, and 3 points across the thickness (Gent's (I1 - 3)^2 ~ y^4)
        "quadratures": ["default", [3, 3]],
        # continuum levels (cells along x, across): Richardson over the three
        "levels": [[32, 2], [64, 4], [128, 8]],
    },
    "tiny": {
        "elements": ["HB2n-12"],
        "counts": [8],
        "levels": [[8, 1], [16, 2], [32, 4]],
    },
}

VARIANTS = {"plane-stress": ("plane-stress", None), "plane-strain-penalty": ("plane-strain", "penalty")}
DENSITY = 2150.0      # kg/m^3, the paper's neo-Hookean rubber


def material(law: str, formulation: str) -> dict:
    """The law's example constants (the neo-Hookean twin: C10 = mu / 2 of ``twin``)."""
    if law.startswith("twin:"):
        c = {"C10": 0.5 * get_law(law[5:]).shear_modulus(get_law(law[5:]).example)}
        law = "neo-hookean"
    else:
        c = dict(get_law(law).example)
    t = {"law": law, "formulation": formulation, "density": DENSITY, **c}
    if FORMULATIONS[formulation]:
        t["penalty"] = paper.PENALTY
    return t


def _tag(law: str) -> str:
    return law.replace("twin:", "nh-twin-of-")


def _scene(law: str, formulation: str, name: str, **kw) -> dict:
    s = paper.cantilever_scene("neo-hookean", formulation, name=name, **kw)
    s["material"] = material(law, formulation)
    return s


def cases(grid: dict, tiny: bool) -> list:
    out = []
    for law in grid["laws"]:
        for who in (law, f"twin:{law}"):
            for v, (model, inc) in VARIANTS.items():
                for cl, ch in grid["levels"]:
                    fem = {"cells_length": cl, "cells_height": ch, "cell": "quadrilateral", "degree": 2,
                           "quadrature_degree": 4, **({"incompressibility": inc} if inc else {})}
                    out.append(make_case("law-card", "continuum", _scene(
                        who, model, f"law-card-{_tag(who)}-{v}-{cl}x{ch}", fem=fem, load_steps=10)))
                for el in grid["elements"]:
                    for n in grid["counts"]:
                        for q in grid["quadratures"]:
                            out.append(make_case("law-card", "ancf", _scene(
                                who, model, f"law-card-{_tag(who)}-{v}-{el}-{n}-{_rule(q)}", element=el,
                                elements=n, quadrature=None if q == "default" else tuple(q))))
    return out


def _rule(q) -> str:
    return "qdef" if q == "default" else f"q{q[0]}{q[1]}"


def _law_of(rec) -> str:
    name = rec["scene"]["name"]
    return ("twin:" + name.split("nh-twin-of-")[1].split("-plane")[0]) if "nh-twin-of-" in name \
        else rec["scene"]["material"]["law"]


def report(ctx) -> Section:
    g = ctx.study.grid
    recs = ctx.records()
    sec = Section(ctx.study.title,
                  "Each law of the shared table (mechanics/laws/) on the paper's cantilever with its example "
                  "constants, by the continuum (Q2, Richardson over " + ", ".join(f"{a} x {b}" for a, b in g["levels"])
                  + ") and by ANCF (default rule, face clamp), in plane stress and in plane strain with the "
                  "paper's penalty. 'law effect' is the tip of the law minus the tip of its neo-Hookean twin "
                  "(C10 = mu / 2, the same small-strain stiffness) by the same solver and mesh.")
    for law in g["laws"]:
        L = get_law(law)
        c = dict(L.example)
        rows_law = [[law, L.doc, ", ".join(f"{k} = {v:g}" for k, v in c.items()), L.shear_modulus(c) / 1e6]]
        sec.table(ctx, Table(f"law_{law}", ["law", "energy", "example constants (SI)", "mu derived (MPa)"],
                             rows_law, {3: ".6g"}),
                  f"The {law} law as registered; mu = 2 (psi_1 + psi_2) at rest, derived from the energy.")
        rows, effects = [], []
        for v in VARIANTS:
            def fem_ref(who):
                refs = continuum_references([r for r in recs if is_continuum(r) and _law_of(r) == who
                                             and f"-{v}-" in r["scene"]["name"]])
                return next(iter(refs.values()), None)
            ref, twin = fem_ref(law), fem_ref(f"twin:{law}")
            if ref and ref.tip:
                rows.append([v, "continuum (Richardson)", mm(ref.tip[0]), mm(ref.tip[1]), None, None])
            for el in g["elements"]:
                for n in g["counts"]:
                    for q in g["quadratures"]:
                        def tip(who):
                            name = f"law-card-{_tag(who)}-{v}-{el}-{n}-{_rule(q)}"
                            r = next((r for r in recs if r["scene"]["name"] == name), None)
                            return ((r["tip"]["ux"], r["tip"]["uy"]) if r and r.get("status") == "converged"
                                    and r.get("tip") else None)
                        t, tt = tip(law), tip(f"twin:{law}")
                        dev = ([(t[k] - ref.tip[k]) / abs(ref.tip[k]) for k in (0, 1)] if t and ref and ref.tip
                               else [None, None])
                        label = f"{el} x {n}, {'default rule' if q == 'default' else f'{q[0]} x {q[1]} points'}"
                        rows.append([v, label, mm(t[0]) if t else None, mm(t[1]) if t else None,
                                     pct(dev[0]), pct(dev[1])])
                        if t and tt and ref and ref.tip and twin and twin.tip:
                            fe = [ref.tip[k] - twin.tip[k] for k in (0, 1)]
                            ae = [t[k] - tt[k] for k in (0, 1)]
                            effects.append([v, label, mm(fe[0]), mm(fe[1]), mm(ae[0]), mm(ae[1]),
                                            pct((ae[0] - fe[0]) / abs(fe[0])) if fe[0] else None, _rule(q)])
        sec.table(ctx, Table(f"law_{law}_cantilever", ["model", "solver", "ux (mm)", "uy (mm)",
                                                       "ux vs continuum (%)", "uy vs continuum (%)"], rows,
                             {2: ".3f", 3: ".3f", 4: "+.3f", 5: "+.3f"}),
                  f"The cantilever in the {law} law: each ANCF mesh against the converged continuum.")
        sec.table(ctx, Table(f"law_{law}_effect", ["model", "ANCF mesh", "continuum effect ux (mm)",
                                                   "continuum effect uy (mm)", "ANCF effect ux (mm)",
                                                   "ANCF effect uy (mm)", "ux effect, ANCF vs continuum (%)"],
                             [e[:7] for e in effects], {2: "+.4f", 3: "+.4f", 4: "+.4f", 5: "+.4f", 6: "+.2f"}),
                  f"The {law} law's own effect (tip minus its neo-Hookean twin's): the two solvers run the "
                  "same energy, so they must see the same effect; the last column is its relative difference.")
        for q in g["quadratures"]:
            d = [abs(e[6]) for e in effects if e[7] == _rule(q) and e[6] is not None]
            what = "the default rule" if q == "default" else f"{q[0]} x {q[1]} points"
            sec.text += (f"- {law}, {what}: the law's effect on ux by ANCF differs from the continuum's by "
                         f"{min(d):.2f} to {max(d):.2f} % of the effect over the meshes shown.\n" if d else
                         f"- {law}, {what}: no complete pair of runs to compare.\n")
    return sec
