"""Figure 4 reproduced: pendulum convergence (Yeoh) against the number of elements.

Each element (HB2n-12, HB3n-12, HB2n-16) at 4 ... 64 elements in the plane-stress and
the `paper` formulations, generalized-alpha at one fixed step (``dt``, fine enough to be
converged: the finest mesh of each element is run again at dt / 2 to show it). Error:
|r(t) - r_ref(t)| / L of the free-end centre line, at t_end (the paper's 0.5 s) and the
maximum over the output times 0.1 ... t_end, r_ref the converged continuum plane-stress
tip (``tests/gold/fem_pendulum.json``; the `paper` formulation is judged by it too,
labelled: the paper's ANCF is close to plane strain in statics). Without the gold file
the reference is the finest ANCF run (``reference`` grid key), labelled PROVISIONAL.
The self-convergence (each element against its own finest mesh) is shown beside it.
"""
from __future__ import annotations

from contract import paper

from ..common.pendulum_cases import (LENGTH, continuum_pendulum, describe_dynamic, gold_tips, pendulum_case,
                       tip_errors)
from ..engine.report import Section, Table, draw, element_color, figure, hollow_legend, legend_outside, marker


STUDY = {
    "name": "figure4",
    "title": "Figure 4: pendulum convergence against the number of elements",
    "grid": {
        # every element that runs both formulations, but one that locks
        "elements": {"registered": {"without": ["locking"], "running": ["plane-stress", "paper"]}},
        "counts": [4, 8, 16, 32, 64],
        "formulations": ["plane-stress", "paper"],
        # one fixed step for every mesh: 1 ms is the converged step of 32 x HB2n-12 (Table 4);
        # the finest mesh of each element runs again at dt / 2 (the step check)
        "dt": 0.0005,
        "rho_inf": 0.5,
        "t_end": 0.5,
        # the provisional reference while tests/gold/fem_pendulum.json is absent (run at dt / 2)
        "reference": {"element": "HB3n-12", "elements": 128},
    },
    "tiny": {
        "elements": ["HB2n-12", "HB3n-12"],
        "counts": [2, 4],
        "dt": 0.001,
        "t_end": 0.2,
        "reference": {"element": "HB3n-12", "elements": 8},
    },
}

CONVERGED_M = 1e-3   # "converged at n": within 1 mm of the element's finest mesh at every output time
CONTINUUM_MODEL = {"plane-stress": "plane-stress", "paper": "plane-stress", "plane-strain": "plane-strain"}


def _common(grid: dict) -> dict:
    return {"rho_inf": grid["rho_inf"], "t_end": grid["t_end"], "law": grid.get("law", paper.PENDULUM_LAW)}


def cases(grid: dict, tiny: bool) -> list:
    c, dt = _common(grid), grid["dt"]
    out = [pendulum_case("figure4", el, n, f, dt, **c)
           for f in grid["formulations"] for el in grid["elements"] for n in grid["counts"]]
    out += [pendulum_case("figure4", el, max(grid["counts"]), f, dt / 2, **c)      # the step check
            for f in grid["formulations"] for el in grid["elements"]]
    ref = grid["reference"]
    out += [pendulum_case("figure4", ref["element"], ref["elements"], f, dt / 2, **c) for f in grid["formulations"]]
    return out


def reference_for(ctx, formulation: str, descs: list[dict]) -> tuple[dict | None, str, bool]:
    """(tips {t: (x, y)}, label, provisional) of the reference of ``formulation``."""
    g = ctx.study.grid
    cont = continuum_pendulum().get((g.get("law", paper.PENDULUM_LAW), CONTINUUM_MODEL[formulation]))
    if cont and cont.tips:
        return cont.tips, cont.label + ("" if cont.converged else " (not converged to 0.1 mm)"), False
    ref = g["reference"]
    for d in descs:
        if (d["formulation"], d["element"], d["elements"], d["dt"]) == (formulation, ref["element"],
                                                                         ref["elements"], g["dt"] / 2) and d["ok"]:
            return d["tips"], (f"PROVISIONAL: finest ANCF `{formulation}` {ref['element']} x {ref['elements']}, "
                               f"dt {1e3 * g['dt'] / 2:g} ms (no continuum gold yet)"), True
    return None, "none", True


def series(descs, formulation, element, dt) -> list[dict]:
    return sorted([d for d in descs if (d["formulation"], d["element"], d["dt"]) == (formulation, element, dt)],
                  key=lambda d: d["elements"])


def _element(g: dict, descs: list[dict], f: str, el: str, ref) -> dict:
    """One element's runs in one formulation: each run with its error against the reference
    and against the element's own finest mesh, the table rows, the smallest converged mesh,
    the step check's row and the summary line."""
    t_end = round(g["t_end"], 9)
    ser = series(descs, f, el, g["dt"])
    ok = [d for d in ser if d["ok"]]
    finest = ok[-1] if ok else None
    pts, rows = [], []
    for d in ser:
        e = tip_errors(d["tips"], ref) if (ref and d["ok"]) else {}
        s = tip_errors(d["tips"], finest["tips"]) if (finest and d["ok"] and d is not finest) else {}
        pts.append((d, e, s))
        rows.append([f, el, d["elements"], d["ndof"], d["status"],
                     100 * e[t_end] if t_end in e else None, 100 * max(e.values()) if e else None,
                     1e3 * LENGTH * max(e.values()) if e else None,
                     100 * max(s.values()) if s else None, d["steps"], d["newton"], d["verdict"]])
    good = [(d, e, s) for d, e, s in pts if e]
    conv = next((d["elements"] for d, _, s in pts
                 if d["ok"] and (d is finest or (s and max(s.values()) * LENGTH <= CONVERGED_M))), None)
    half = [d for d in descs if (d["formulation"], d["element"], d["elements"], d["dt"]) ==
            (f, el, max(g["counts"]), g["dt"] / 2) and d["ok"]]
    dstep = tip_errors(finest["tips"], half[0]["tips"]) if (half and finest and
                                                             finest["elements"] == max(g["counts"])) else {}
    summary = [f"{d['elements']}: {1e3 * LENGTH * max(e.values()):.2f}" for d, e, _ in good]
    line = (f"  - {el}, max tip error over t (mm) at n = " + ", ".join(summary)
            + (f"; within 1 mm of its own finest mesh from n = {conv}." if conv else ".")) if summary else None
    step = [f, el, max(g["counts"]), 1e3 * g["dt"], 1e3 * LENGTH * max(dstep.values()) if dstep else None, conv]
    return {"pts": pts, "good": good, "rows": rows, "line": line, "step": step}


ROWS = ("at t_end", "max over t", "vs own finest")     # the figure's rows, one measure each


def _draw_element(axes, g: dict, el: str, data: dict) -> None:
    """The element's error at t_end (top row), its maximum over t (middle) and its maximum
    against its own finest mesh (bottom), in the element's colour."""
    t_end = round(g["t_end"], 9)
    good = data["good"]
    if not good:
        return
    ns, vs = [d["elements"] for d, _, _ in good], [d["verdict"] for d, _, _ in good]
    style = dict(marker=marker(el, g["elements"]), color=element_color(el), lw=1.2)
    draw(axes[0], ns, [max(e[t_end], 1e-9) for _, e, _ in good], vs, el, **style)
    draw(axes[1], ns, [max(max(e.values()), 1e-9) for _, e, _ in good], vs, el, **style)
    selfc = [(d, s) for d, _, s in data["pts"] if s]
    if selfc:
        draw(axes[2], [d["elements"] for d, _ in selfc], [max(max(s.values()), 1e-9) for _, s in selfc],
             [d["verdict"] for d, _ in selfc], el, **style)


def _axes(axes, g: dict, f: str, label: str, first: bool) -> None:
    for i, ax in enumerate(axes):
        ax.set_xscale("log", base=2)
        ax.set_xticks(g["counts"], [str(n) for n in g["counts"]])
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
        if i == len(axes) - 1:
            ax.set_xlabel("number of elements")
        if first:
            ax.set_ylabel({0: f"|r - r_ref| / L at t = {g['t_end']:g} s", 1: "max over t of |r - r_ref| / L",
                           2: "max over t of |r - r_finest| / L"}[i], fontsize=8)
    axes[0].set_title(f"`{f}` vs {label}", fontsize=8)


def report(ctx) -> Section:
    g = ctx.study.grid
    descs = [describe_dynamic(r) for r in ctx.records()]
    sec = Section(ctx.study.title,
                  f"The pendulum ({g.get('law', paper.PENDULUM_LAW)}, {g['t_end']:g} s, generalized-alpha rho_inf = "
                  f"{g['rho_inf']}, dt = {1e3 * g['dt']:g} ms) at 4 to {max(g['counts'])} elements: tip error "
                  f"|r - r_ref| / L (L = {1e3 * LENGTH:g} mm) at t = {g['t_end']:g} s and the maximum over the output "
                  "times, against the converged continuum plane-stress tip; bottom row of the figure: each element against its own "
                  "finest mesh.")
    forms = g["formulations"]
    fig, axes = figure(len(ROWS), len(forms), figsize=(4.2 * len(forms), 2.6 * len(ROWS)), squeeze=False,
                       sharex=True, sharey="row", layout="constrained")
    rows, steprows, lines = [], [], []
    for j, f in enumerate(forms):
        ref, label, provisional = reference_for(ctx, f, descs)
        block = []
        for el in g["elements"]:
            data = _element(g, descs, f, el, ref)
            rows += data["rows"]
            _draw_element([axes[i][j] for i in range(len(ROWS))], g, el, data)
            block += [data["line"]] if data["line"] else []
            steprows.append(data["step"])
        _axes([axes[i][j] for i in range(len(ROWS))], g, f, label, j == 0)
        lines += [f"- `{f}` against {label}:"] + block
    legend_outside(fig, *hollow_legend(axes[0][0]))
    sec.figure(ctx, fig, "figure4_pendulum_convergence",
               "Tip error of the pendulum against the number of elements, one line per element: top at t_end, middle "
               "its maximum over the output times, bottom its maximum against the element's own finest mesh "
               "(self-convergence); the reference is named in each column's title (continuum plane stress, or "
               "PROVISIONAL finest ANCF while the continuum gold is absent).")
    sec.table(ctx, Table("figure4_convergence",
                         ["formulation", "element", "n", "ndof", "status", f"error at {g['t_end']:g} s (% L)",
                          "max error (% L)", "max error (mm)", "vs own finest, max (% L)", "steps", "Newton", "verdict"],
                         rows, {5: ".3f", 6: ".3f", 7: ".3f", 8: ".3f"}),
              "Every run of the figure: tip error against the reference (see the list below the tables) at t_end and "
              "its maximum over t = 0.1 ... t_end, and the self-convergence against the same element's finest mesh.")
    sec.table(ctx, Table("figure4_step", ["formulation", "element", "n", "dt (ms)", "tip change at dt/2, max (mm)",
                                          f"converged at n (within {1e3 * CONVERGED_M:g} mm of finest)"],
                         steprows, {3: "g", 4: ".4f"}),
              "The step check: the finest mesh of each element again at dt/2 (the largest tip change over the output "
              "times), and the smallest mesh whose tip stays within 1 mm of that element's finest mesh at every output "
              "time.")
    sec.text = "\n".join(lines)
    return sec


def gold_values(ctx) -> dict:
    out = {}
    for r in ctx.records():
        d = describe_dynamic(r)
        out.update(gold_tips(f"figure4/{d['formulation']}/{d['element']}/{d['elements']}/dt{d['dt']:g}", d))
    return out
