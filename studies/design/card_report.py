"""The element report card rendered from its records only (:mod:`studies.design.card` makes them):
``<out>/cards/<element>.md`` and its figures beside it. Nothing here runs a solver. The
locking sections are :mod:`studies.design.card_locking`'s, a cable's own parts
:mod:`studies.design.card_cable`'s; the records are read by :mod:`studies.design.card_records`."""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from ancf.elements import get_element

from .card_cable import (CABLE_NOT_RUN, _cable_contract_lines, _cable_rank_lines, _cable_shear_lines, _section_lines,
                         _sweep)
from .card_cases import checks_path, element_imports, grid_for, slug
from .card_locking import _locking, _mechanism_section, _shear_locking
from .card_records import _close, _f, _is_locking, _is_slender, _is_sweep, _records, _static, _yes
from ..common.pendulum_cases import FEM_GOLD, continuum_pendulum, describe_dynamic, tip_errors
from ..common.gold import MATCHING, gold_references, short
from ..engine.report import FIGURE_DATA, element_color, figure, legend_outside, mm, vec_error, write_figure_data
from ..engine.store import RecordStore

ROOT = Path(__file__).resolve().parents[2]
FEM_STATIC = ROOT / "tests" / "gold" / "fem_cantilever.json"


def _contract_section(chk: dict) -> list[str]:
    lines = ["## 1. Contract checks (`ancf.checks.element`)", "",
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
    lines = ["## 2. Rank tests (`ancf.checks.rank`)", "",
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
    if not get_element(element).family.section_field:                   # what a cable runs, and part 9
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
