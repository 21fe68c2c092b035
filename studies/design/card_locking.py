"""The card's locking sections, from its records alone: volumetric locking as the penalty
grows (:func:`volumetric_locking`, :func:`volumetric_verdict`), shear locking of the slender
probe against beam theory (:func:`shear_locking`), the mechanism the probe's strains show
(:func:`mechanism`) and what the face clamp does to the order (:func:`clamp_orders`)."""
from __future__ import annotations

import math

from .card_cases import beam_theory
from .card_records import _f, _is_locking, _is_slender, _static
from ..common.gold import short
from ..engine.report import vec_error


# A locking-free element's error at a fixed element count does not depend on L / h (beam
# theory scales out); the 2D continuum departs from Timoshenko's beam by O(h / L) near the
# clamp (under 0.5 % here). An error above 1 % that grows by more than this factor from
# the stoutest to the most slender beam is locking.
LOCKING_GROWTH = 1.5


def _locking(recs, refs, not_run: str | None = None) -> list[str]:
    """The volumetric-locking sweep; ``not_run``: why the element has none (a cable)."""
    if not_run:
        return ["## 5. Locking", "", f"Volumetric locking: not run: {not_run}.", ""]
    rows = []
    for r, m, n in _static(recs):
        if not _is_locking(r):
            continue
        ref = refs.get((m["law"], "plane-strain"))
        k = m["penalty"] / m["C10"]
        ok = r["status"] == "converged" and r.get("tip") and ref
        rows.append((m["law"], k, n, vec_error(r["tip"], ref) if ok else None, r["status"],
                     (r["tip"]["ux"], r["tip"]["uy"]) if ok else None, ref))
    factors = sorted({x[1] for x in rows})
    lines = ["## 5. Locking: plane strain as the penalty grows", "",
             "Tip error against the exactly incompressible plane-strain continuum (mixed Q2/Q1), penalty "
             "alpha = k C10 (the paper's 1000 MPa is k = 1.05e3 for NH, 1.8e3 for Yeoh). As k grows the tip of a "
             "locking-free element tends to a limit as u + c / k does (its change per decade of k falls tenfold) "
             "near the incompressible continuum; a locking one keeps stiffening, or has stiffened far past it.", "",
             "| law | n | " + " | ".join(f"k = {k:g}" for k in factors) + " |",
             "|---|---|" + "---|" * len(factors)]
    verdicts = {}
    for law in dict.fromkeys(x[0] for x in rows):
        sel = sorted((x for x in rows if x[0] == law), key=lambda x: x[1])
        lines.append(f"| {short(law)} | {sel[0][2]} | " + " | ".join(
            (_f(100 * x[3], ".3g") + " %") if x[3] is not None else x[4] for x in sel) + " |")
        stiff = [(x[1], x[5]) for x in sel if x[1] >= VOLUMETRIC_FROM and x[5] is not None]
        if len(stiff) > 1:
            verdicts[short(law)] = volumetric_locking(stiff, sel[0][6])
    return lines + ["", volumetric_verdict(verdicts), ""] if verdicts else lines + [""]


# From the paper's penalty on (k = 1e3 C10), where compressibility no longer dominates. A
# lock-free tip follows u_inf + c / k: its change per decade of k falls tenfold; a change
# that falls by less than half (ratio above STILL_STIFFENING) is an element still locking.
# Changes under CHANGE_FLOOR of the tip are below the static solve's tolerance (1e-9
# relative Newton correction) and are not compared. A limit more than SATURATED off the
# incompressible continuum is a locked element that has stiffened as far as it can (a
# lock-free element's plane-strain tip at the card's 64 elements is within 1 %).
VOLUMETRIC_FROM, STILL_STIFFENING, CHANGE_FLOOR, SATURATED = 1e3, 0.5, 1e-7, 0.10


def volumetric_locking(sweep: list[tuple[float, tuple[float, float]]], ref: tuple[float, float]) -> dict:
    """The volumetric-locking rule on one law's sweep [(k, (ux, uy)) for k >= VOLUMETRIC_FROM,
    ascending] against the incompressible continuum's tip ``ref``: {"changes": the tip's change
    per step of k over |ref|, "ratios": each change over the one before, "limit_error": the
    stiffest tip's error against ref, "stiffening": a change above CHANGE_FLOOR that fell by
    less than STILL_STIFFENING x, "saturated": limit_error > SATURATED, "locked": either,
    "span": (k first, k last)}."""
    scale = math.hypot(*ref)
    tips = [t for _, t in sweep]
    changes = [math.hypot(b[0] - a[0], b[1] - a[1]) / scale for a, b in zip(tips, tips[1:])]
    ratios = [b / a if a > 0 else math.inf for a, b in zip(changes, changes[1:])]
    stiffening = any(r > STILL_STIFFENING and c > CHANGE_FLOOR for r, c in zip(ratios, changes[1:]))
    limit_error = vec_error({"ux": tips[-1][0], "uy": tips[-1][1]}, ref)
    saturated = limit_error > SATURATED
    return {"changes": changes, "ratios": ratios, "limit_error": limit_error, "stiffening": stiffening,
            "saturated": saturated, "locked": stiffening or saturated, "span": (sweep[0][0], sweep[-1][0])}


def volumetric_verdict(verdicts: dict[str, dict]) -> str:
    """The card's sentence from {law: :func:`volumetric_locking`}; every number it states is in the table
    or follows from its tips."""
    def changes(v):
        return ", ".join(f"{100 * c:.2g} %" for c in v["changes"])

    k0, k1 = next(iter(verdicts.values()))["span"]
    locked = {law: v for law, v in verdicts.items() if v["locked"]}
    if not locked:
        per = "; ".join(f"{law} {changes(v)}" for law, v in verdicts.items())
        return (f"No volumetric locking: from k = {k0:g} to {k1:g} the tip's change per decade of k falls about "
                f"tenfold, as u + c / k does ({per}, of |u_ref|), to a limit within "
                f"{100 * max(v['limit_error'] for v in verdicts.values()):.2g} % of the incompressible continuum.")
    parts = []
    for law, v in locked.items():
        why = []
        if v["stiffening"]:
            why.append(f"its tip keeps stiffening (change per decade of k {changes(v)} of |u_ref|: it falls by less "
                       f"than {1 / STILL_STIFFENING:g}x, or grows)")
        if v["saturated"]:
            why.append(f"at k = {k1:g} it is {100 * v['limit_error']:.3g} % off the incompressible continuum (more "
                       f"than {100 * SATURATED:g} %: locked as stiff as it gets)")
        parts.append(f"{law}: " + " and ".join(why))
    free = [law for law in verdicts if law not in locked]
    return ("**Volumetric locking** from the paper's penalty on: " + "; ".join(parts) + "."
            + (f" {', '.join(free)}: the change falls tenfold per decade." if free else "")
            + " The element cannot keep J = 1 at every point without stiffening.")


def shear_locking(recs) -> dict:
    """The slender-beam probe from its records: {"rows": {n: {L/h: signed error against
    beam theory (fraction)}}, "growth": {n: |error| of the most slender / of the stoutest},
    "locks": any n whose error exceeds 1 % and grows more than LOCKING_GROWTH with L/h,
    "order": log2 of the stoutest beam's error ratio over the last doubling of n (None
    without two counts), "converges": False if that error stays above 1 % and does not
    shrink (order < 0.2)}."""
    rows: dict[int, dict[float, float]] = {}
    for r in recs:
        if not _is_slender(r) or r["status"] != "converged" or not r.get("tip"):
            continue
        b = r["scene"]["beam"]
        ratio = round(b["length"] / b["height"], 6)
        exact = beam_theory(ratio)[1]
        rows.setdefault(r["scene"]["ancf"]["elements"], {})[ratio] = (-r["tip"]["uy"] - exact) / exact
    rows = dict(sorted(rows.items()))
    growth = {n: abs(e[max(e)]) / abs(e[min(e)]) if e[min(e)] else math.inf for n, e in rows.items() if len(e) > 1}
    locks = any(abs(rows[n][max(rows[n])]) > 0.01 and g > LOCKING_GROWTH for n, g in growth.items())
    stout = [(n, e[min(e)]) for n, e in rows.items()]
    order = None
    if len(stout) > 1 and stout[-1][1] and stout[-2][1]:
        (n1, e1), (n2, e2) = stout[-2], stout[-1]
        order = math.log(abs(e1) / abs(e2)) / math.log(n2 / n1)
    converges = not (order is not None and abs(stout[-1][1]) > 0.01 and order < 0.2)
    return {"rows": rows, "growth": growth, "locks": locks, "order": order, "converges": converges}


def _shear_locking(recs) -> list[str]:
    res = shear_locking(recs)
    if not res["rows"]:
        return []
    ratios = sorted({k for v in res["rows"].values() for k in v})
    lines = ["### Shear locking: slender beams against beam theory", "",
             "A cantilever of the pendulum's length (350 mm) and height L / (L/h), Neo-Hookean plane stress, default "
             "quadrature, under a uniform load that bends its tip by 1e-4 L (linear regime), against Timoshenko's "
             "beam (E = 3 mu, G = mu, kappa = 5/6). Error (ours - beam) / beam of the tip deflection. A locking-free "
             "element's error at a fixed element count n does not depend on L/h ('growth': |error| of the most "
             "slender over the stoutest beam); a locked coarse mesh can be equally stiff at every L/h (saturated), "
             "so the verdict takes every n.", "",
             "| n | " + " | ".join(f"L/h = {r:g}" for r in ratios) + " | growth |",
             "|---|" + "---|" * (len(ratios) + 1)]
    for n, errs in res["rows"].items():
        lines.append(f"| {n} | " + " | ".join(_f(100 * errs[r], "+.3g") + " %" if r in errs else "-" for r in ratios)
                     + f" | {_f(res['growth'].get(n), '.3g')} |")
    verdict = (f"**Shear locking**: the error exceeds 1 % and grows more than {LOCKING_GROWTH:g}x with L/h."
               if res["locks"] else f"No shear locking: the error grows at most {LOCKING_GROWTH:g}x with L/h "
               "(or stays under 1 %).")
    if res["order"] is not None:
        verdict += (f" At L/h = {ratios[0]:g} the error falls with order {res['order']:.2f} in n"
                    + ("." if res["converges"] else ": it **does not converge to beam theory** (a mesh-independent "
                       "error: with nu = 1/2, -25 % is the 1 - (1 - nu^2) of Poisson locking)."))
    return lines + ["", verdict, ""]


SPURIOUS_SHEAR = 10.0     # a shear share this many times Timoshenko's is spurious (shear locking)


CONTRACTION = (-0.75, -0.25)   # eps_yy / eps_xx outside this band (exact -1/2) is Poisson-type locking


def mechanism(row: dict) -> list[str]:
    """The mechanisms a slender-probe state shows (:func:`ancf.checks.element.strain_split`), by rule."""
    out = []
    if row["shear_share"] > SPURIOUS_SHEAR * row["beam_shear_share"]:
        out.append("shear locking")
    if row["eyy_exx"] > CONTRACTION[1]:
        out.append("Poisson locking in the plane (the height cannot contract)")
    elif row["eyy_exx"] < CONTRACTION[0]:
        out.append("Poisson locking out of the plane (eps_zz held at 0)")
    return out


def _mechanism_section(chk: dict, recs) -> list[str]:
    rows = chk.get("slender_strains")
    if not rows:
        return []
    errs = shear_locking(recs)["rows"]
    lines = ["#### Which mechanism: the probe's strains", "",
             "The same states, split by `ancf.checks.element.strain_split`: the share of the energy in transverse shear "
             "against Timoshenko's 1.2 (h/L)^2 (more than "
             f"{SPURIOUS_SHEAR:g}x: spurious shear, **shear locking**), and the section's contraction eps_yy / eps_xx "
             "(exact -1/2; above " f"{CONTRACTION[1]:g}: the height cannot contract, **Poisson locking in the plane**, "
             f"E / (1 - nu^2); below {CONTRACTION[0]:g}: eps_zz is held at 0, **Poisson locking out of the plane**, "
             "the plane-strain stiffness; either is 4/3 too stiff at nu = 1/2, -25 %).", "",
             "| n | L/h | error | shear share (x Timoshenko) | eps_yy / eps_xx | mechanism |", "|---|---|---|---|---|---|"]
    found = set()
    for r in rows:
        e = errs.get(r["n"], {}).get(round(r["slenderness"], 6))
        m = mechanism(r)
        if e is not None and abs(e) > 0.01:
            found.update(m)
        lines.append(f"| {r['n']} | {r['slenderness']:g} | " + (_f(100 * e, "+.3g") + " %" if e is not None else "-")
                     + f" | {_f(r['shear_share'], '.2e')} ({_f(r['shear_share'] / r['beam_shear_share'], '.3g')}x) | "
                     f"{r['eyy_exx']:+.3f} | {', '.join(m) or 'none'} |")
    verdict = ("Where the error exceeds 1 %, the probe shows: **" + "; ".join(sorted(found)) + "**."
               if found else "Where the error exceeds 1 %, the probe shows no locking mechanism (or the error stays "
               "under 1 %).")
    return lines + ["", verdict, ""] + _clamp_lines(chk.get("clamp_probe"))


def clamp_orders(probe: dict) -> dict:
    """Observed orders over the probe's last doubling of n, clamped as scenes clamp and freed."""
    def order(errs):
        (n1, e1), (n2, e2) = list(zip(probe["counts"], errs))[-2:]
        return math.log(abs(e1) / abs(e2)) / math.log(n2 / n1) if e1 and e2 else None
    return {"face": order(probe["face"]), "freed": order(probe["freed_errors"])}


def _clamp_lines(probe) -> list[str]:
    if not probe or len(probe["counts"]) < 2 or None in probe["face"] + probe["freed_errors"]:
        return []
    o = clamp_orders(probe)
    freed = ", ".join(probe["freed"])
    lines = ["#### What the clamp does", "",
             f"The face clamp fixes {freed} at x = 0 besides r and r_y (the clamped face cannot contract, as in "
             f"the continuum). The most slender probe (L/h = {probe['slenderness']:g}) with it and with {freed} "
             "freed (in memory, for this check):", "",
             "| n | " + " | ".join(str(n) for n in probe["counts"]) + " | order |",
             "|---|" + "---|" * (len(probe["counts"]) + 1),
             "| face clamp | " + " | ".join(_f(100 * e, "+.3g") + " %" for e in probe["face"])
             + f" | {_f(o['face'], '.2f')} |",
             f"| {freed} freed | " + " | ".join(_f(100 * e, "+.3g") + " %" for e in probe["freed_errors"])
             + f" | {_f(o['freed'], '.2f')} |", ""]
    if o["face"] is not None and o["freed"] is not None and o["face"] < 1.5 <= o["freed"]:
        lines.append(f"**The clamp sets the order**: {o['face']:.2f} with it, {o['freed']:.2f} with {freed} freed. "
                     f"{freed} varies polynomially inside an element, so the contraction the clamped face may not "
                     "make is withheld over the whole first element (a zone l_e long, where the moment is largest; "
                     "in the continuum about h long): the error falls at first order until l_e is about h. The "
                     "constraint is the physical one, so scenes keep it.")
    else:
        lines.append(f"The clamp does not set the order here ({_f(o['face'], '.2f')} with it, "
                     f"{_f(o['freed'], '.2f')} freed).")
    return lines + [""]
