"""The element report card rendered from its records only (:mod:`studies.design.card` makes them):
``<out>/cards/<element>.md`` and its figures beside it. Nothing here runs a solver."""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from .card_cases import beam_theory, cases, checks_path, element_imports, grid_for, slug
from ..common.pendulum_cases import FEM_GOLD, continuum_pendulum, describe_dynamic, tip_errors
from ..common.gold import MATCHING, gold_references, short
from ..engine.report import (FIGURE_DATA, element_color, figure, legend_outside, mm, target_handle, vec_error,
                             write_figure_data)
from ..engine.store import RecordStore, store_for

ROOT = Path(__file__).resolve().parents[2]
FEM_STATIC = ROOT / "tests" / "gold" / "fem_cantilever.json"


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


# A locking-free element's error at a fixed element count does not depend on L / h (beam
# theory scales out); the 2D continuum departs from Timoshenko's beam by O(h / L) near the
# clamp (under 0.5 % here). An error above 1 % that grows by more than this factor from
# the stoutest to the most slender beam is locking.
LOCKING_GROWTH = 1.5


def _contract_section(chk: dict) -> list[str]:
    lines = ["## 1. Contract checks (`ancf.checks`)", "",
             "| check | measured | bound | verdict |", "|---|---|---|---|"]
    add = lambda name, meas, bound, ok: lines.append(f"| {name} | {meas} | {bound} | {_yes(ok)} |")
    n, r, m = chk["nodality"], chk["reference_state"], chk["mass"]
    add("nodality: every basis function and gradient reproduced", f"{_f(n['error'])} (relative)", "1e-11", n["passes"])
    add("reference coordinates give F = I", _f(r["error"]), "1e-12", r["passes"])
    add("mass and gravity exact, M SPD", f"mass {_f(m['mass'])}, gravity {_f(m['gravity'])}, SPD {m['positive_definite']}",
        "1e-12", m["passes"])
    for form, t in chk["formulations"].items():
        eg, tg, rm = t["energy_gradient"], t["tangent_gradient"], t["rigid_motion"]
        add(f"`{form}` Yeoh: force = energy gradient (Taylor slope)", _f(eg["slope"]), "> 1.8", eg["passes"])
        add(f"`{form}` Yeoh: tangent = force gradient (slope; asymmetry)", f"{_f(tg['slope'])}; {_f(tg['asymmetry'])}",
            "> 1.8; 1e-10", tg["passes"])
        add(f"`{form}` Yeoh: rigid motion (energy, force rotation)", f"{_f(rm['energy'])}, {_f(rm['force'])}",
            "1e-9, 1e-8", rm["passes"])
    p = chk["patch"]
    add("patch test (constant stress, 3 elements), worst over l_e/h", _f(max(x["error"] for x in p)), "1e-6",
        all(x["passes"] for x in p))
    return lines + [""]


def _conformity_section(chk: dict, section: str = "r_y") -> list[str]:
    """``section``: the field whose jump the check reads besides r (a cable's: r_x, its
    section's normal)."""
    c = chk["conformity"]
    lines = ["## 3. Conformity across element faces", "",
             f"Bent state (circular arc, tip rotation 0.5 rad) on two elements: jump of r across the shared face "
             f"{_f(c['jump_r'])} h, jump of {section} {_f(c['jump_r_y'])}: "
             + ("**conforming**." if c["conforming"] else "**not conforming**: the trace on a face depends on the "
                "other node's coordinates."), "",
             "Patch test (Irons): the force of a homogeneous deformation against the constant stress times the "
             "boundary integrals of the shape functions, relative to max |f|. For a non-conforming element the "
             "interior faces' jump terms do not cancel; the inconsistency grows as l_e / h shrinks.", "",
             "| l_e / h | " + " | ".join(_f(x["aspect"]) for x in chk["patch"]) + " |",
             "|---|" + "---|" * len(chk["patch"]),
             "| error | " + " | ".join(_f(x["error"]) for x in chk["patch"]) + " |", ""]
    return lines


def _rank_section(chk: dict, out: Path, name: str) -> list[str]:
    rules = list(chk["rank"][0]["rules"])
    lines = ["## 2. Rank tests (`ancf.rank`)", "",
             "Per rule: spurious zero-energy modes beyond the 3 rigid ones / mu_min (smallest energy ratio of a "
             "deformation mode under the rule against an exact rule) / finite-strain ratio (seen / true Green "
             "strain of the worst state, amplitude 0.2). Passing: 0 spurious, mu_min >= 0.1, ratio >= 0.3. The "
             "defaults are the rules the element declares for l_e / h (`ElementSpec.quadrature`), with their "
             "own tests; l_e / h = 35 and 17.5 are the slender pendulum's 2 and 4 elements.", "",
             "| l_e / h | default (plane stress) | default (penalised) | " + " | ".join(rules) + " |",
             "|---|---|---|" + "---|" * len(rules)]

    def cell(x):
        ok = x["spurious"] == 0 and x["mu_min"] >= 0.1 and (x["strain_ratio"] or 0) >= 0.3
        return f"{x['spurious']} / {_f(x['mu_min'], '.2f')} / {_f(x['strain_ratio'], '.2f')}" + ("" if ok else " ✗")

    for row in chk["rank"]:
        cells = [cell(row["rules"][r]) for r in rules]
        d, dt = row["default"], row.get("default_tests")
        ds = [f"{d[k]}" + (f": {cell(dt[k])}" if dt else "") for k in ("plane-stress", "penalised")]
        lines.append(f"| {_f(row['aspect'])} | {ds[0]} | {ds[1]} | " + " | ".join(cells) + " |")
    fig, ax = figure(1, 2, figsize=(9, 3.4))
    a = [row["aspect"] for row in chk["rank"]]
    for r in rules:
        ax[0].plot(a, [row["rules"][r]["mu_min"] for row in chk["rank"]], "o-", ms=3, label=r)
        ax[1].plot(a, [row["rules"][r]["strain_ratio"] or 0.0 for row in chk["rank"]], "o-", ms=3, label=r)
    for k, (t, lim) in enumerate((("mu_min (u = 0)", 0.1), ("finite-strain ratio", 0.3))):
        ax[k].axhline(lim, color="grey", ls=":")
        ax[k].set_xscale("log")
        ax[k].set_xlabel("l_e / h")
        ax[k].set_title(t, fontsize=9)
    legend_outside(fig, title="rule", title_fontsize=7)
    fig.savefig(out / f"{name}-rank.png", dpi=100, bbox_inches="tight")
    write_figure_data(fig, out / f"{name}-rank{FIGURE_DATA}")
    _close(fig)
    return lines + ["", f"![rank]({name}-rank.png)", ""]


def _close(fig):
    import matplotlib.pyplot as plt
    plt.close(fig)


def _convergence(recs, refs, out: Path | None = None, name: str = "") -> list[str]:
    """The table of observed orders and plateaus per law and formulation, and (with
    ``out``) the error against n, with the data it draws beside it as CSV."""
    series: dict = {}
    for r, m, n in _static(recs):
        if _is_locking(r) or _is_slender(r) or _is_sweep(r):
            continue
        ref = refs.get((m["law"], MATCHING[m["formulation"]]))
        ok = r["status"] == "converged" and r.get("tip")
        err = vec_error(r["tip"], ref) if ok and ref else None
        t = (r.get("timing") or {}).get("median_s")
        series.setdefault((m["law"], m["formulation"]), []).append((n, err, r.get("ndof"), t, r if ok else None))
    lines = ["## 4. Static convergence against the converged continuum", "",
             "Default quadrature at each mesh (recorded per run). Error: |u - u_ref| / |u_ref| over (ux, uy), "
             "u_ref the Richardson value of the matching continuum model. Observed orders, n: log2 of "
             "|u_n - u_2n| / |u_2n - u_4n| for each doubling triple (a negative order: the differences grow, the "
             "mesh sequence drifts). Plateau: the finest mesh's error, where discretisation has stopped and the "
             "beam model's own distance remains.", "",
             "| law | formulation | finest n | tip ux, uy (mm) | plateau | observed orders (n: p) | errors 4 ... finest |",
             "|---|---|---|---|---|---|---|"]
    for (law, form), ser in sorted(series.items()):
        ser.sort(key=lambda p: p[0])
        tips = {n: np.array([rec["tip"]["ux"], rec["tip"]["uy"]]) for n, _, _, _, rec in ser if rec}
        orders = []
        for n in (n for n in sorted(tips) if 2 * n in tips and 4 * n in tips):
            d1, d2 = np.linalg.norm(tips[n] - tips[2 * n]), np.linalg.norm(tips[2 * n] - tips[4 * n])
            orders.append(f"{n}: {math.log2(d1 / d2):.2f}" if d1 > 0 and d2 > 0 else f"{n}: -")
        last = next(((n, e, rec) for n, e, _, _, rec in reversed(ser) if rec), None)
        errs = ", ".join(_f(100 * e, ".2g") + " %" if e is not None else "failed" for _, e, _, _, _ in ser)
        tip = f"{mm(last[2]['tip']['ux']):.2f}, {mm(last[2]['tip']['uy']):.2f}" if last else "-"
        lines.append(f"| {short(law)} | {form} | {last[0] if last else '-'} | {tip} | "
                     f"{_f(100 * last[1], '.3f') + ' %' if last and last[1] is not None else '-'} | {', '.join(orders) or '-'} | {errs} |")
    if out is None or not series:
        return lines + [""]
    fig, ax = figure(1, 1, figsize=(6, 3.8))
    rows = ["law,formulation,elements,error"]
    for k, ((law, form), ser) in enumerate(sorted(series.items())):
        pts = [(n, e) for n, e, _, _, _ in ser if e]
        rows += [f"{law},{form},{n},{e:.6e}" for n, e in pts]
        if pts:
            ax.loglog(*zip(*pts), marker="os^"[k // 2 % 3], ls="-" if form == "plane-stress" else "--", ms=4,
                      label=f"{short(law)} {form}")
    ax.set_xlabel("elements n")
    ax.set_ylabel("|u - u_ref| / |u_ref| (tip)")
    ax.grid(True, which="both", alpha=0.3)
    legend_outside(fig)
    fig.savefig(out / f"{name}-error.png", dpi=100, bbox_inches="tight")
    _close(fig)
    (out / f"{name}-error.figure.csv").write_text("\n".join(rows) + "\n")
    return lines + ["", f"![error against n]({name}-error.png)", ""]


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
    """The mechanisms a slender-probe state shows (:func:`ancf.checks.strain_split`), by rule."""
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
             "The same states, split by `ancf.checks.strain_split`: the share of the energy in transverse shear "
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


def _pendulum(recs) -> list[str]:
    gold = continuum_pendulum(FEM_GOLD)
    lines = ["## 6. Pendulum against the continuum", ""]
    rows, failed = [], []
    for r in recs:
        if r["scene"]["analysis"]["kind"] != "dynamic":
            continue
        d = describe_dynamic(r)
        if not d["ok"]:
            failed.append(f"- n = {d['elements']}, dt = {d['dt'] * 1e3:g} ms: {d['status']}: "
                          f"{d['reason'] or 'no reason recorded'}")
        ref = gold.get((d["law"], d["formulation"]))
        errs = tip_errors(d["tips"], ref.tips) if ref and d["ok"] else {}
        rows.append(f"| {d['elements']} | {d['dt'] * 1e3:g} | {d['status']} | "
                    f"{_f(100 * max(errs.values()), '.3g') + ' %' if errs else '-'} | "
                    f"{_f(100 * errs[max(errs)], '.3g') + ' %' if errs else '-'} | {_f(d['wall_s'], '.3g')} |")
    if not gold:
        return lines + ["No continuum pendulum gold (tests/gold/fem_pendulum.json).", ""]
    return (lines + ["Yeoh, plane stress, generalized-alpha rho_inf 0.5. Error: |r(t) - r_ref(t)| / L over the "
                    "output times, against the continuum gold.", "",
                    "| n | dt (ms) | status | max error | error at t_end | wall (s) |", "|---|---|---|---|---|---|"] + rows + [""]
            + (["Runs without a result, with their records' reasons:", "", *failed, ""] if failed else []))


def _cost(element: str, law: str, out: Path, cards: Path, name: str) -> list[str]:
    """Work-precision of the plane-stress refinement of ``law``: this element and every
    other card whose records are in ``out``/data; the figure goes to ``cards``."""
    fig, axes = figure(1, 1, figsize=(5.5, 4))
    others = sorted(p.stem[len("card-"):] for p in (out / "data").glob("card-*.jsonl"))
    refs = gold_references(FEM_STATIC)
    drawn = []
    for other in others:
        recs = list(RecordStore(out / "data" / f"card-{other}.jsonl").read().values())
        pts = []
        for r, m, n in _static(recs):
            t = (r.get("timing") or {}).get("median_s")
            ref = refs.get((m["law"], "plane-stress"))
            if m["formulation"] == "plane-stress" and m["law"] == law and t and r["status"] == "converged" and ref:
                pts.append((t, vec_error(r["tip"], ref), n))
        if pts:
            pts.sort(key=lambda p: p[2])
            mine = other == slug(element)
            xs, ys = [p[0] for p in pts], [max(p[1], 1e-7) for p in pts]
            if mine:
                axes.plot(xs, ys, "o-", lw=2, ms=4, color=element_color(element), label=other, zorder=3)
            else:   # the other cards in one grey family: one legend entry, each curve named in the data
                axes.plot(xs, ys, ".--", lw=0.8, ms=3, color="0.65", label=f"_{other}", zorder=1)
            drawn.append(other)
    if len(drawn) > 1:
        axes.plot([], [], ".--", lw=0.8, ms=3, color="0.65", label="the other elements with a card")
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.grid(True, which="major", alpha=0.3)
    axes.set_xlabel("wall time, serial warm median (s)")
    axes.set_ylabel(f"|u - u_ref| / |u_ref| ({short(law)}, plane stress)")
    legend_outside(fig)
    fig.savefig(cards / f"{name}-cost.png", dpi=100, bbox_inches="tight")
    write_figure_data(fig, cards / f"{name}-cost{FIGURE_DATA}")
    _close(fig)
    return ["## 7. Cost", "", f"{short(law)}, plane stress, the static refinement: this element in colour, the other elements with a "
            f"card in this directory ({', '.join(o for o in drawn if o != slug(element)) or 'none yet'}) grey and "
            "dashed (each one's curve is in colour on its own card, and named in this figure's data).", "",
            f"![cost]({name}-cost.png)", ""]


def _stability(recs) -> list[str]:
    static = [r for r, _, _ in _static(recs)]
    verdicts = {"stable": sum(r.get("stable") is True for r in static),
                "unstable": sum(r.get("stable") is False for r in static),
                "undetermined": sum(r.get("stable") is None and r["status"] == "converged" for r in static),
                "not converged": sum(r["status"] != "converged" for r in static)}
    neg = max((r.get("negative_eigenvalues") or 0 for r in static), default=0)
    bad = [f"{r['case']['name']} ({r.get('negative_eigenvalues')} negative)" for r in static if r.get("stable") is False]
    failed = [f"{r['case']['name']}: {r.get('reason')}" for r in static if r["status"] != "converged"]
    return (["## 8. Stability of every equilibrium above (inertia of the constrained tangent)", "",
             ", ".join(f"{k}: {v}" for k, v in verdicts.items()) + f"; most negative eigenvalues: {neg}.", ""]
            + [f"- unstable: {b}" for b in bad] + [f"- not converged: {f}" for f in failed] + [""])


# -- a cable's card (ElementSpec.kinematics = "cable") -----------------------------------------------

CABLE_NOT_RUN = ("a cable integrates the law's incompressible uniaxial energy over its section (free lateral "
                 "faces), so plane stress alone: `paper` and `plane-strain` are refused for it (`ancf.build.check`), "
                 "and incompressibility is exact in its fibres, with no penalty to lock")


def _cable_contract_lines(chk: dict) -> list[str]:
    p = chk["patch"][0]
    return [f"The `paper` and `plane-strain` rows are not run: {CABLE_NOT_RUN}. The patch test of a cable is axial "
            f"(`ancf.checks.axial_patch`): a uniform stretch {_f(p.get('stretch'))} on a free cable must load only "
            "the end positions, with P h w, P = dW_u/dlambda (the uniaxial nominal stress); its closed form "
            "lambda(P) is the benchmarks' tension case and tests/test_cable.py's.", ""]


def _cable_rank_lines(chk: dict) -> list[str]:
    rows = {row["aspect"]: row for row in chk["rank"]}
    slender = [a for a in sorted(rows) if a >= 10]
    ratios = ", ".join(f"{_f(rows[a]['default_tests']['plane-stress']['strain_ratio'], '.2f')} at {a:g}"
                       for a in slender)
    return ["A cable's tests read its fibre strain: the small u_x' - y u_y'' at u = 0 and the finite lambda - 1 "
            "(`ancf.rank`). Its default keeps 3 points along where the finite-strain test fails"
            + (f" ({ratios})" if ratios else "") + ": the state it finds is the membrane stretch between the points "
            "along, and seeing it is the cubic cable's membrane locking (measured: [5, 3] sees it, 0.93, and puts "
            "the paper's cantilever 2 to 3 times further from the continuum at 2 to 8 elements, the pendulum too, "
            "with the same converged tip; HC2n-8's note in `ancf/elements.py`). 3 points across: part 1b.", ""]


def _section_lines(chk: dict) -> list[str]:
    rows = chk.get("section")
    if not rows:
        return []
    lines = ["## 1b. The section model: M(kappa) against the exact plane-stress bending", "",
             "The cable's bending moment per width at no axial force, M / (EI kappa) with EI = 3 mu h^3 / 12 (a linear "
             "EA eps^2 / 2 + EI kappa^2 / 2 would give 1 at every kappa): its section (fibres at eta = Y, each in "
             "uniaxial stress; 64 points across, and its default rule's), the same fibres with the thickness change "
             "d eta / dY = lambda^-1/2 (not in the element: it moves the fibres by an ODE per section), and the "
             "exact pure bending of a plane-stress strip (`studies.verification.closed_forms.plane_stress_bending`, with the "
             "radial stress no fibre model has). Coefficients: (value - 1) / (kappa h)^2; model error: "
             "(cable / exact - 1) / (kappa h)^2.", "",
             "| law | kappa h | cable | its rule | eta(Y) | exact | cable coeff. | exact coeff. | model error coeff. | "
             "eta = Y's share |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        kh2 = r["kappa_h"] ** 2
        err = (r["cable"] / r["exact"] - 1) / kh2
        share = (r["cable"] / r["thickness_change"] - 1) / kh2
        lines.append(f"| {short(r['law'])} | {r['kappa_h']:g} | {r['cable']:.6f} | {r['rule']:.6f} | "
                     f"{r['thickness_change']:.6f} | {r['exact']:.6f} | {(r['cable'] - 1) / kh2:+.4f} | "
                     f"{(r['exact'] - 1) / kh2:+.4f} | {err:+.4f} | {share:+.4f} |")
    first = {r["law"]: r for r in rows if r["kappa_h"] == rows[0]["kappa_h"]}
    errs = ", ".join(f"{short(l)} {(r['cable'] / r['exact'] - 1) / r['kappa_h'] ** 2:.3f}" for l, r in first.items())
    shares = ", ".join(f"{short(l)} {(r['cable'] / r['thickness_change'] - 1) / r['kappa_h'] ** 2:.3f}"
                       for l, r in first.items())
    return lines + ["", f"The cable's section bends too stiffly by about ({errs}) (kappa h)^2 of M (a model error, "
                    f"of the order of the strain squared, that no mesh removes); keeping eta = Y is ({shares}) "
                    "(kappa h)^2 of it, the rest is the radial stress of the curved strip. The element keeps "
                    "eta = Y.", ""]


def _cable_shear_lines(recs) -> list[str]:
    """What the slender probe's error is for a cable: the shear it does not have."""
    rows = shear_locking(recs)["rows"]
    if not rows:
        return []
    n = max(rows)
    cells = "; ".join(f"L/h = {r:g}: {100 * e:+.3g} % against {-100 * 1.2 / r ** 2 / (1 + 1.2 / r ** 2):+.3g} %"
                      for r, e in sorted(rows[n].items()))
    return [f"A cable has no shear: its error here is Timoshenko's shear term, -1.2 (h/L)^2 / (1 + 1.2 (h/L)^2) of "
            f"the deflection, at every n ({n} elements: {cells}), not locking.", ""]


def _sweep(recs, cards: Path, name: str, tiny: bool) -> list[str]:
    """Part 9: the cable's tip against the converged continuum as L / h falls."""
    from .card_cases import SLENDERNESS, SLENDERNESS_TINY
    from ..verification.slenderness_gold import GOLD, references

    grid = SLENDERNESS_TINY if tiny else SLENDERNESS
    refs = references(GOLD)
    tips: dict = {}
    for r, m, n in _static(recs):
        if not _is_sweep(r) or r["status"] != "converged" or not r.get("tip"):
            continue
        b = r["scene"]["beam"]
        tips.setdefault((m["law"], round(b["length"] / b["height"], 6)), {})[n] = r["tip"]
    lines = ["## 9. Slenderness: where the centre line stops being enough", "",
             "The paper's cantilever (L = 160 mm, w = 7 mm, face clamp, plane stress) at L / h = "
             + ", ".join(f"{x:g}" for x in grid["ratios"]) + ", its gravity scaled by (32 / (L/h))^2 so that the load "
             "parameter q L^3 / EI is the paper's at every L / h (the same large deflection; strains and kappa h "
             "grow as h / L), against the converged continuum (tests/gold/fem_slenderness.json: Q2 cells halved 4 "
             "or 5 times, Richardson value; `python -m studies slenderness-gold`). Error |u - u_ref| / |u_ref| of the "
             f"tip at {max(grid['counts'])} elements (converged: the change from {min(grid['counts'])} elements "
             "beside it), the reference's own error estimate last.", ""]
    if not refs:
        return lines + ["No continuum references (tests/gold/fem_slenderness.json).", ""]
    laws = sorted({law for law, _ in tips})
    ratios = sorted({ratio for _, ratio in tips}, reverse=True)
    lines += ["| L / h | " + " | ".join(f"{short(l)} error | {short(l)} change" for l in laws) + " | reference error |",
              "|---|" + "---|---|" * len(laws) + "---|"]
    series: dict = {law: [] for law in laws}
    for ratio in ratios:
        cells, ref_err = [], []
        for law in laws:
            by_n, ref = tips.get((law, ratio), {}), refs.get((law, float(ratio)))
            if not by_n or not ref:
                cells += ["-", "-"]
                continue
            hi, lo = by_n[max(by_n)], by_n[min(by_n)]
            err = vec_error(hi, ref["tip"])
            change = math.hypot(hi["ux"] - lo["ux"], hi["uy"] - lo["uy"]) / math.hypot(*ref["tip"])
            series[law].append((ratio, err))
            ref_err.append(ref["error"])
            cells += [_f(100 * err, ".3g") + " %", _f(100 * change, ".2g") + " %" if len(by_n) > 1 else "-"]
        lines.append(f"| {ratio:g} | " + " | ".join(cells) + f" | {_f(100 * max(ref_err), '.2g') + ' %' if ref_err else '-'} |")
    lines += ["", "Where the error first exceeds each target as L / h falls (log-log interpolation between the two "
              "ratios around the crossing; '> x': within the target down to the stoutest beam run; '< x': beyond it "
              "already at the most slender):", "",
              "| law | " + " | ".join(f"within {100 * t:g} % down to L / h" for t in grid["targets"]) + " |",
              "|---|" + "---|" * len(grid["targets"])]
    for law in laws:
        lines.append(f"| {short(law)} | " + " | ".join(_crossing(series[law], t) for t in grid["targets"]) + " |")
    fig, ax = figure(1, 1, figsize=(5.5, 3.8))
    for law in laws:
        pts = sorted(series[law])
        if pts:
            ax.loglog([p[0] for p in pts], [max(p[1], 1e-7) for p in pts], "o-", ms=4, label=short(law))
    for t in grid["targets"]:
        ax.axhline(t, color="grey", ls=":", lw=0.8)
    ax.set_xlabel("L / h")
    ax.set_ylabel("|u - u_ref| / |u_ref| (tip)")
    h, l = ax.get_legend_handles_labels()
    th, tl = target_handle(grid["targets"])
    legend_outside(fig, h + [th], l + [tl])
    fig.savefig(cards / f"{name}-slenderness.png", dpi=100, bbox_inches="tight")
    write_figure_data(fig, cards / f"{name}-slenderness{FIGURE_DATA}")
    _close(fig)
    return lines + ["", f"![slenderness]({name}-slenderness.png)", ""]


def _crossing(series, target: float) -> str:
    """The L / h at which the error, falling L / h, first exceeds ``target`` (log-log between
    the bracketing ratios), as a cell."""
    pts = sorted(series, reverse=True)                 # slender first
    if not pts:
        return "-"
    if pts[0][1] > target:
        return f"< {pts[0][0]:g}"
    for (r1, e1), (r2, e2) in zip(pts, pts[1:]):
        if e2 > target >= e1:
            if e1 <= 0:
                return f"{r2:g}"
            x = math.exp(math.log(r1) + (math.log(target) - math.log(e1)) * (math.log(r2) - math.log(r1))
                         / (math.log(e2) - math.log(e1)))
            return f"{x:.3g}"
    return f"> {pts[-1][0]:g}"


def render(element: str, out: Path, tiny: bool = False) -> Path:
    out = Path(out)
    cards = out / "cards"
    cards.mkdir(parents=True, exist_ok=True)
    name = slug(element)
    chk = json.loads(checks_path(out, element).read_text())
    recs = _records(element, out, tiny)
    imports = element_imports(element)
    refs = gold_references(FEM_STATIC)
    conv = _convergence(recs, refs, cards, name)
    laws = grid_for(tiny)["laws"]
    checks_ok = (chk["nodality"]["passes"] and chk["reference_state"]["passes"] and chk["mass"]["passes"]
                 and all(v["passes"] for t in chk["formulations"].values() for v in t.values()))
    head = [f"# Element report card: {element}", "",
            f"{chk['definition']}", "",
            f"Generated by `python -m studies card {element}"
            + (f" --import {' '.join(imports)}" if imports else "") + ("` (tiny grid)." if tiny else "`."),
            f"Consistency checks: {'all pass' if checks_ok else '**some fail**'}; patch test: "
            f"{'passes' if all(x['passes'] for x in chk['patch']) else '**fails** (see 3)'}; conforming: "
            f"{chk['conformity']['conforming']}. {len(recs)} solver runs.", ""]
    from ancf.elements import get_element
    if get_element(element).cable:                   # what a cable runs, and part 9
        text = (head + _contract_section(chk) + _cable_contract_lines(chk) + _section_lines(chk)
                + _rank_section(chk, cards, name) + _cable_rank_lines(chk) + _conformity_section(chk, "r_x") + conv
                + _locking(recs, refs, CABLE_NOT_RUN) + _shear_locking(recs) + _cable_shear_lines(recs) + _pendulum(recs)
                + _cost(element, "yeoh" if "yeoh" in laws else laws[0], out, cards, name) + _stability(recs)
                + _sweep(recs, cards, name, tiny))
    else:
        text = (head + _contract_section(chk) + _rank_section(chk, cards, name) + _conformity_section(chk) + conv
                + _locking(recs, refs) + _shear_locking(recs) + _mechanism_section(chk, recs) + _pendulum(recs) + _cost(element, "yeoh" if "yeoh" in laws else laws[0], out, cards, name) + _stability(recs))
    path = cards / f"{name}.md"
    path.write_text("\n".join(text) + "\n")
    return path
