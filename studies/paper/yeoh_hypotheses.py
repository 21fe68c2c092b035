"""The last unexplained residual of Table 3: which slip reproduces the paper's Yeoh cells?

Our `paper` Yeoh cells sit +0.44 % / +0.16 % off the paper for all three higher-order
elements alike, while Neo-Hookean and Mooney-Rivlin match within 0.02 % in the same
setting (quadrature 2 x 2, clamp "all"). Each hypothesis is a change of constants or
load in the scene (the grid's ``hypotheses``: a name, what it changes, and the changed
[material] constants (Pa) and/or gravity (m/s^2)). An energy change that is a change of
constants is written as one: eq. 13's exponent typo C30 (tr C - 3)^2 is C20 -> C20 + C30,
C30 -> 0. A hypothesis that is not specific to Yeoh (``all_laws``) runs on the
Neo-Hookean and Mooney-Rivlin cells too: a slip that breaks them is rejected.

Verdict: "reproduces" when all six Yeoh values print as the paper's (two decimals, mm).
"""
from __future__ import annotations

from contract import paper

from ..engine.case import make_case
from ..common.gold import short
from ..engine.report import Section, Table, mm, pct, rel_dev, verdict as run_verdict


STUDY = {
    "name": "yeoh-hypotheses",
    "title": "Table 3's Yeoh cells: which slip reproduces them?",
    "full": True,
    "grid": {
        "elements": {"HB2n-12": 160, "HB3n-12": 160, "HB2n-16": 640},
        # name, what it changes, and the change: Yeoh constants (Pa), gravity (m/s^2), penalty (Pa);
        # all_laws: the change applies to every law, so NH and MR must still match
        "hypotheses": [{"name": "as-printed", "what": "Table 2 constants, eq. 13 with (tr C - 3)^3"},
                       {"name": "no-C30", "what": "C30 = 0", "constants": {"C30": 0.0}},
                       {"name": "C30-in-Pa", "what": "C30 read as -0.000802537 Pa", "constants": {"C30": -0.000802537}},
                       {"name": "C30-sign", "what": "C30 = +0.000802537 MPa", "constants": {"C30": 802.537}},
                       {"name": "eq13-typo",
                        "what": "C30 (tr C - 3)^2, i.e. C20 + C30 and no cubic term",
                        "constants": {"C20": 60247.263, "C30": 0.0}},
                       {"name": "rounded-4sf",
                        "what": "C10 0.5452, C20 0.06105, C30 -0.0008025 MPa",
                        "constants": {"C10": 545200.0, "C20": 61050.0, "C30": -802.5}},
                       {"name": "g-9.8", "what": "gravity 9.8 m/s^2", "gravity": 9.8, "all_laws": True},
                       {"name": "penalty-x2",
                        "what": "penalty alpha (J - 1)^2 without the 1/2: 2000 MPa",
                        "penalty": 2000000000.0,
                        "all_laws": True}],
    },
    "tiny": {
        "elements": {"HB2n-12": 8, "HB3n-12": 8, "HB2n-16": 16},
    },
}

LAWS = ("neo-hookean", "mooney-rivlin", "yeoh")


def _scene(law: str, element: str, n: int, h: dict) -> dict:
    s = paper.cantilever_scene(law, "paper", element, n, quadrature=(2, 2), clamp="all",
                               gravity=h.get("gravity", paper.GRAVITY),
                               name=f"cantilever-{law}-paper-{element}-{n}-q22-all-{h['name']}")
    if law == "yeoh":
        s["material"].update(h.get("constants", {}))
    if "penalty" in h:
        s["material"]["penalty"] = h["penalty"]
    return s


def cases(grid: dict, tiny: bool) -> list:
    out = []
    for h in grid["hypotheses"]:
        for el, n in grid["elements"].items():
            for law in (LAWS if h.get("all_laws") else ("yeoh",)):
                out.append(make_case("yeoh-hypotheses", "ancf", _scene(law, el, n, h)))
    return out


def _hypothesis(rec: dict) -> str:
    return rec["scene"]["name"].rsplit("-q22-all-", 1)[1]


def report(ctx) -> Section:
    g = ctx.study.grid
    by = {(_hypothesis(r), r["scene"]["material"]["law"], r["scene"]["ancf"]["element"]): r for r in ctx.records()}
    els = list(g["elements"])
    sec = Section(ctx.study.title,
                  "Each hypothesis is a change of the scene (constants, load) in the paper setting (`paper` "
                  "formulation, 2 x 2 points, clamp \"all\"; " + ", ".join(f"{e} x {n}" for e, n in g["elements"].items())
                  + "). Deviation = (ours - paper) / |paper|; \"=0.01\" counts the Yeoh values that print as the "
                  "paper's (mm, two decimals); NH/MR: the largest deviation the change causes on the twelve "
                  "Neo-Hookean and Mooney-Rivlin cells (which match within 0.02 % without it).")
    rows, found = [], []
    for h in g["hypotheses"]:
        devs, prints = [], 0
        for el in els:
            r, ref = by.get((h["name"], "yeoh", el)), paper.paper_tip(el, "yeoh")
            for k, comp in enumerate(("ux", "uy")):
                v = r["tip"][comp] if r and r["status"] == "converged" and r.get("tip") else None
                devs.append(rel_dev(v, ref[k]))
                prints += v is not None and round(mm(v), 2) == round(mm(ref[k]), 2)
        other = None
        if h.get("all_laws"):
            ds = [abs(rel_dev(by[(h["name"], law, el)]["tip"][c], paper.paper_tip(el, law)[k]))
                  for law in LAWS[:2] for el in els for k, c in enumerate(("ux", "uy"))
                  if (h["name"], law, el) in by and by[(h["name"], law, el)].get("tip")]
            other = max(ds) if ds else None
        worst = max((abs(d) for d in devs if d is not None), default=None)
        if any(d is None for d in devs):
            verdict = "not converged"
        elif prints == len(devs):
            verdict = "**reproduces**"
            found.append(h["name"])
        elif other is not None and other > 5e-4:
            verdict = f"rejected: breaks the NH/MR cells ({100 * other:.2f} %)"
        else:
            verdict = "rejected"
        rows.append([h["name"], h["what"]] + [pct(d) for d in devs] + [pct(worst), f"{prints}/{len(devs)}",
                                                                      pct(other), verdict,
                                                                      " / ".join(run_verdict(by[(h["name"], "yeoh", el)])
                                                                                 if (h["name"], "yeoh", el) in by else "not run"
                                                                                 for el in els)])
    hdr = ["hypothesis", "what it changes"] + [f"{e} {c} (%)" for e in els for c in ("ux", "uy")] + \
          ["max (%)", "=0.01", "NH/MR (%)", "verdict", "runs (" + " / ".join(els) + ")"]
    sec.table(ctx, Table("yeoh_hypotheses", hdr, rows, {**{j: "+.3f" for j in range(2, 2 + 2 * len(els))},
                                                         2 + 2 * len(els): ".3f", 4 + 2 * len(els): ".3f"}),
              "The paper's Yeoh cells of Table 3 under named hypotheses (`paper` setting).")
    sec.text = ("Reproduces all six Yeoh cells: " + (", ".join(found) if found else "none") + ". "
                "The paper's Table 2 lists C30 = -0.000802537 MPa; its Yeoh numbers are those of the law "
                "without the cubic term (or with C30 a thousand times smaller, which prints the same).")
    return sec


def gold_values(ctx) -> dict:
    out = {}
    for r in ctx.records():
        if r["status"] == "converged" and r.get("tip"):
            m = r["scene"]
            for c in ("ux", "uy"):
                v = r["tip"][c]
                out[f"yeoh-hypotheses/{_hypothesis(r)}/{short(m['material']['law'])}/{m['ancf']['element']}/{c}"] = \
                    (v, 1e-6 * abs(v) + 1e-9)
    return out
