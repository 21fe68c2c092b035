"""A cable's card (``ElementSpec.kinematics = "cable"``), from its records alone: what a
cable does not run and why (:data:`CABLE_NOT_RUN`), its contract and rank lines, its section
model against the exact plane-stress bending, the shear it does not have, and part 9, the
slenderness below which its centre line stops being enough (:func:`_crossing`)."""
from __future__ import annotations

import math
from pathlib import Path

from .card_cases import SLENDERNESS, SLENDERNESS_TINY
from .card_locking import shear_locking
from .card_records import _close, _f, _is_sweep, _static
from ..common.gold import short
from ..engine.report import FIGURE_DATA, figure, legend_outside, target_handle, vec_error, write_figure_data
from ..verification.slenderness_gold import GOLD, references


CABLE_NOT_RUN = ("a cable integrates the law's incompressible uniaxial energy over its section (free lateral "
                 "faces), so plane stress alone: `paper` and `plane-strain` are refused for it (`ancf.build.check`), "
                 "and incompressibility is exact in its fibres, with no penalty to lock")


def _cable_contract_lines(chk: dict) -> list[str]:
    p = chk["patch"][0]
    return [f"The `paper` and `plane-strain` rows are not run: {CABLE_NOT_RUN}. The patch test of a cable is axial "
            f"(`ancf.checks.element.axial_patch`): a uniform stretch {_f(p.get('stretch'))} on a free cable must load only "
            "the end positions, with P h w, P = dW_u/dlambda (the uniaxial nominal stress); its closed form "
            "lambda(P) is the benchmarks' tension case and tests/test_cable.py's.", ""]


def _cable_rank_lines(chk: dict) -> list[str]:
    rows = {row["aspect"]: row for row in chk["rank"]}
    slender = [a for a in sorted(rows) if a >= 10]
    ratios = ", ".join(f"{_f(rows[a]['default_tests']['plane-stress']['strain_ratio'], '.2f')} at {a:g}"
                       for a in slender)
    return ["A cable's tests read its fibre strain: the small u_x' - y u_y'' at u = 0 and the finite lambda - 1 "
            "(`ancf.checks.rank`). Its default keeps 3 points along where the finite-strain test fails"
            + (f" ({ratios})" if ratios else "") + ": the state it finds is the membrane stretch between the points "
            "along, and seeing it is the cubic cable's membrane locking (measured: [5, 3] sees it, 0.93, and puts "
            "the paper's cantilever 2 to 3 times further from the continuum at 2 to 8 elements, the pendulum too, "
            "with the same converged tip; HC2n-8's note in `ancf/elements/`). 3 points across: part 1b.", ""]


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
