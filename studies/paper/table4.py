"""Table 4 reproduced: time of the pendulum (Yeoh, 0.5 s) per element type and count,
ours beside the paper's CPU time.

Each (element, count, formulation) runs over the step ladder of the converged-step rule
(:data:`studies.common.pendulum_cases.LADDER`: dt0 halving, down to ``dt_floor``), every rung a
timed case (serial warm runs: one warm-up, the median of up to ``repeats`` runs within
``budget_s``; the ``timing`` grid key). The report picks the converged step by the same
rule as ``studies.design.bench.converged_step`` (:func:`studies.common.pendulum_cases.converged_rung`): the
largest dt whose tip positions at all output times are within ``tol`` (0.1 mm,
componentwise) of the dt/2 run, both converged; and shows that rung's median wall time,
steps, Newton iterations and ndof beside the paper's CPU time
(``contract.paper.table4()``) and the ratio paper / ours. Different machines: the
paper's is an i5-5200U laptop.
"""
from __future__ import annotations

from contract import paper

from ..common.pendulum_cases import LADDER, converged_rung, describe_dynamic, gold_tips, ladder, pendulum_case
from ..engine.report import Section, Table, element_color, figure, legend_outside


STUDY = {
    "name": "table4",
    "title": "Table 4: pendulum time per element type and count",
    "grid": {
        "elements": {"registered": {"tagged": "paper", "without": ["locking"]}},   # the paper's, as its Table 4
        "counts": [4, 8, 16, 32],
        "formulations": ["plane-stress", "paper"],
        "rho_inf": 0.5,
        "t_end": 0.5,
        # the step ladder of studies.design.bench.converged_step (8 ms halving), cut at dt_last: every
        # rung is timed; the report picks the converged one (within 0.1 mm of the dt/2 rung)
        "dt_last": 0.00025,
        # serial warm timings: one warm-up run, then up to `repeats` runs within `budget_s`
        "timing": {"repeats": 3, "budget_s": 1.5},
    },
    "tiny": {
        "elements": ["HB2n-12"],
        "counts": [8],
        "formulations": ["plane-stress"],
        "dt_last": 0.0005,
        "timing": {"repeats": 1, "budget_s": 0.0},
    },
}

DT0, TOL = LADDER["dt0"], LADDER["tol"]
# the warm-up's time (the record's timing.warmup_s): milliseconds once the process has the compiled code,
# seconds where it loads it, so two significant digits at any size (a fixed .2f printed 0.00)
WARMUP_FORMAT = ".2g"


def cases(grid: dict, tiny: bool) -> list:
    opts = {"timing": dict(grid["timing"])}
    return [pendulum_case("table4", el, n, f, dt, rho_inf=grid["rho_inf"], t_end=grid["t_end"], options=opts)
            for f in grid["formulations"] for el in grid["elements"] for n in grid["counts"]
            for dt in ladder(grid.get("dt0", DT0), last=grid.get("dt_last"))]


def selected(ctx) -> list[dict]:
    """One row per (formulation, element, count): the converged rung or None."""
    g = ctx.study.grid
    descs = [describe_dynamic(r) for r in ctx.records()]
    out = []
    for f in g["formulations"]:
        for el in g["elements"]:
            for n in g["counts"]:
                rungs = sorted([d for d in descs if (d["formulation"], d["element"], d["elements"]) == (f, el, n)],
                               key=lambda d: -d["dt"])
                best, diff = converged_rung(rungs)
                out.append({"formulation": f, "element": el, "n": n, "rung": best, "diff": diff,
                            "rungs": rungs, "smallest": rungs[-1]["dt"] if rungs else None})
    return out


def _rows(sel: list[dict], ptab: dict) -> tuple[list[list], dict]:
    """The table's rows, one per (formulation, element, n) at its converged step, and the
    figure's points {(formulation, element): [(n, median wall s)]}."""
    rows, plot = [], {}
    for s in sel:
        r = s["rung"]
        med = (r["timing"] or {}).get("median_s") if r else None
        p = ptab.get((s["element"], s["n"]))
        rows.append([s["formulation"], s["element"], s["n"], r["ndof"] if r else None,
                     1e3 * r["dt"] if r else f"none >= {1e3 * s['smallest']:g}" if s["smallest"] else "no runs",
                     1e3 * s["diff"] if r else None, r["steps"] if r else None, r["newton"] if r else None,
                     med, (r["timing"] or {}).get("warmup_s") if r else None, p,
                     p / med if (p and med) else None, r["verdict"] if r else "failed"])
        if med:
            plot.setdefault((s["formulation"], s["element"]), []).append((s["n"], med))
    return rows, plot


def table(rows: list[list]) -> Table:
    """Table 4 of :func:`_rows`' rows."""
    return Table("table4", ["formulation", "element", "n", "ndof", "converged dt (ms)", "tip change at dt/2 (mm)",
                            "steps", "Newton", "wall s (median)", "warm-up s (a two-element copy)", "paper CPU s",
                            "paper / ours", "verdict"], rows,
                 {4: "g", 5: ".4f", 8: ".3f", 9: WARMUP_FORMAT, 10: ".2f", 11: ".0f"})


def _ladder_table(ctx, sec: Section, sel: list[dict]) -> None:
    long = []
    for s in sel:
        for d in s["rungs"]:
            long.append([s["formulation"], s["element"], s["n"], 1e3 * d["dt"], d["status"], d["steps"],
                         d["rejected"], d["newton"], (d["timing"] or {}).get("median_s"),
                         "yes" if s["rung"] is d else "", d["verdict"]])
    t = Table("table4_ladder", ["formulation", "element", "n", "dt (ms)", "status", "steps", "rejected", "Newton",
                                "wall s (median)", "converged step", "verdict"], long, {3: "g", 8: ".4f"})
    t.write(ctx.out)
    sec.items.append(("link", t.name + ".md", "Every rung of the step ladder (status, steps, time)."))


def _figure(ctx, sec: Section, g: dict, plot: dict, ptab: dict) -> None:
    fig, ax = figure(1, 1, figsize=(5.5, 4.0))
    for (f, el), pts in plot.items():
        ax.plot([n for n, _ in pts], [m for _, m in pts], marker="o", ls="-" if f == "plane-stress" else "--",
                color=element_color(el), label=f"ours {el} `{f}`")
    for el in g["elements"]:
        pp = [(n, ptab[(el, n)]) for n in g["counts"] if (el, n) in ptab]
        ax.plot([n for n, _ in pp], [v for _, v in pp], marker="x", ls=":", color="grey", lw=0.8)
    ax.plot([], [], "x:", color="grey", label="paper (CPU s, i5-5200U)")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("number of elements")
    ax.set_ylabel("time for 0.5 s of motion (s)")
    ax.grid(True, which="both", alpha=0.3)
    legend_outside(fig)
    sec.figure(ctx, fig, "table4_times", "Our wall times (median of serial warm runs, at each converged step) and "
               "the paper's CPU times, against the number of elements, log scales: the gap is the ratio column.")


def report(ctx) -> Section:
    g = ctx.study.grid
    sel = selected(ctx)
    ptab = paper.table4()
    sec = Section(ctx.study.title,
                  f"Time of the pendulum ({paper.PENDULUM_LAW}, {g['t_end']:g} s; generalized-alpha, rho_inf = "
                  f"{g['rho_inf']}) per element and count, each at its converged step (largest dt of the ladder "
                  f"{DT0 * 1e3:g} ms, halving, whose tip positions are within {TOL * 1e3:g} mm of the dt/2 run); wall "
                  "time = median of serial warm runs in one process and one thread (compile time and warm-up apart; "
                  "the warm-up, shown beside it, runs a two-element copy of the case, which loads the compiled code "
                  "from the numba cache where the process has not loaded it yet and never compiles it; the first "
                  "run after installing, compiling included, is the study table4-cold). The paper's CPU time is "
                  "from an Intel i5-5200U laptop.")
    rows, plot = _rows(sel, ptab)
    sec.table(ctx, table(rows),
              "Table 4 beside the paper's: our median serial warm wall time of the pendulum at each case's converged "
              "step, with the steps, Newton iterations and ndof of that run, and the ratio of the paper's CPU time to "
              "ours.")
    _ladder_table(ctx, sec, sel)
    if plot:
        _figure(ctx, sec, g, plot, ptab)
    ratios = [r[11] for r in rows if r[11]]
    sec.text = (f"Paper / ours ranges from {min(ratios):.0f} to {max(ratios):.0f} over the {len(ratios)} timed cells "
                "(different machines and compilers; same physics, element and step rule)." if ratios else "")
    return sec


def gold_values(ctx) -> dict:
    out = {}
    for s in selected(ctx):
        if s["rung"]:
            d = s["rung"]
            out[f"table4/{s['formulation']}/{s['element']}/{s['n']}/converged_dt"] = (d["dt"], 1e-12)
            out.update(gold_tips(f"table4/{s['formulation']}/{s['element']}/{s['n']}", d))
    return out
