"""Figure 5 reproduced: pendulum configurations at t = 0.0, 0.1, ..., 0.5 s, one figure
per law, the higher-order elements (32 elements each) against the continuum model.

Plane-stress and `paper` formulations as the two panels of each law's figure; the
centre lines come from the records' ``configurations``. The continuum (from
``tests/gold/fem_pendulum.json``, plane stress) is drawn as its configurations where the
gold file has them, else as its tip positions only. A table gives the tip distance to
the continuum at each output time.
"""
from __future__ import annotations

from ..common.pendulum_cases import LENGTH, continuum_pendulum, describe_dynamic, gold_tips, pendulum_case, tip_errors
from ..common.gold import short
from ..engine.report import Section, Table, figure, legend_outside, linestyle


STUDY = {
    "name": "figure5",
    "title": "Figure 5: pendulum configurations at t = 0, 0.1, ..., 0.5 s",
    "grid": {
        "laws": ["neo-hookean", "mooney-rivlin", "yeoh"],
        "elements": {"registered": {"tagged": "paper", "without": ["locking"]}},   # the paper's, as its Figure 5
        "elements_count": 32,
        "formulations": ["plane-stress", "paper"],
        "dt": 0.0005,
        "rho_inf": 0.5,
        "t_end": 0.5,
    },
    "tiny": {
        "laws": ["neo-hookean", "yeoh"],
        "elements": ["HB3n-12"],
        "elements_count": 4,
        "dt": 0.001,
        "t_end": 0.2,
    },
}

CONTINUUM_MODEL = {"plane-stress": "plane-stress", "paper": "plane-stress", "plane-strain": "plane-strain"}


def cases(grid: dict, tiny: bool) -> list:
    return [pendulum_case("figure5", el, grid["elements_count"], f, grid["dt"], rho_inf=grid["rho_inf"],
                          t_end=grid["t_end"], law=law)
            for law in grid["laws"] for f in grid["formulations"] for el in grid["elements"]]


def report(ctx) -> Section:
    import matplotlib.cm as cm

    g = ctx.study.grid
    descs = [describe_dynamic(r) for r in ctx.records()]
    confs = {r["case_id"]: r.get("configurations") or [] for r in ctx.records()}
    recs = ctx.records()
    cont = continuum_pendulum()
    sec = Section(ctx.study.title,
                  f"Centre lines of the pendulum at t = 0, 0.1, ..., {g['t_end']:g} s for each law, "
                  f"{g['elements_count']} elements of each higher-order element (generalized-alpha rho_inf = "
                  f"{g['rho_inf']}, dt = {1e3 * g['dt']:g} ms), against the converged continuum plane-stress model.")
    rows = []
    forms = g["formulations"]
    for law in g["laws"]:
        fig, axes = figure(1, len(forms), figsize=(5.0 * len(forms), 3.2), squeeze=False, sharey=True)
        for j, f in enumerate(forms):
            ax = axes[0][j]
            c = cont.get((law, CONTINUUM_MODEL[f]))
            ts = sorted({t for d in descs if d["law"] == law for t in d["tips"]})
            colours = {t: cm.viridis(0.85 * i / max(len(ts) - 1, 1)) for i, t in enumerate(ts)}
            for el in g["elements"]:
                for r, d in zip(recs, descs):
                    if (d["law"], d["formulation"], d["element"]) != (law, f, el) or not d["ok"]:
                        continue
                    for k in confs[r["case_id"]]:
                        t = round(k["t"], 9)
                        ax.plot([1e3 * x for x in k["x"]], [1e3 * y for y in k["y"]], ls=linestyle(el, g["elements"]),
                                lw=1.1, color=colours.get(t, "k"), label=f"{el}" if t == ts[-1] else None)
                    e = tip_errors(d["tips"], c.tips) if c else {}
                    rows.append([short(law), f, el, d["elements"], d["status"]]
                                + [1e3 * LENGTH * e[t] if t in e else None for t in ts if t > 0]
                                + [1e3 * LENGTH * max(e.values()) if e else None, d["verdict"]])
            if c:
                for t, (xs, ys) in c.configurations.items():
                    ax.plot([1e3 * x for x in xs], [1e3 * y for y in ys], color="k", lw=0.6, alpha=0.6)
                ax.plot([1e3 * c.tips[t][0] for t in ts if t in c.tips], [1e3 * c.tips[t][1] for t in ts if t in c.tips],
                        "r*", ms=8, zorder=5, label=f"{c.label}" + ("" if c.configurations else ": tip"))
            ax.plot([0], [0], "ko", ms=4)
            if j == 0:
                for t in ts:
                    ax.plot([], [], color=colours[t], lw=2, label=f"t = {t:g} s")
            ax.set_aspect("equal")
            ax.grid(True, alpha=0.3)
            ax.set_xlabel("x (mm)")
            if j == 0:
                ax.set_ylabel("y (mm)")
            ax.set_title(f"{law}, `{f}`" + (" (vs continuum plane stress)" if f == "paper" else ""), fontsize=9)
        legend_outside(fig)
        sec.figure(ctx, fig, f"figure5_{law}",
                   f"{law}: pendulum centre lines at t = 0 ... {g['t_end']:g} s (colour: time, line style: element; "
                   f"left `{forms[0]}`{', right `' + forms[1] + '`' if len(forms) > 1 else ''}); red stars: the "
                   "converged continuum plane-stress tip" + (" and lines its configurations." if any(
                       c.configurations for c in cont.values()) else " (the gold file has no configurations)."))
    ts = sorted({t for d in descs for t in d["tips"] if t > 0})
    sec.table(ctx, Table("figure5_tip_distance", ["law", "formulation", "element", "n", "status"]
                         + [f"t = {t:g} s (mm)" for t in ts] + ["max (mm)", "verdict"], rows,
                         {5 + i: ".2f" for i in range(len(ts) + 1)}),
              "Distance of each ANCF tip from the converged continuum plane-stress tip at each output time, in mm "
              "('-' where the continuum gold has no case for the law or is absent).")
    missing = [law for law in g["laws"] if (law, "plane-stress") not in cont]
    if missing:
        sec.text = ("No converged continuum pendulum (tests/gold/fem_pendulum.json) for: " + ", ".join(missing)
                    + "; those figures show the ANCF configurations only.")
    return sec


def gold_values(ctx) -> dict:
    out = {}
    for r in ctx.records():
        d = describe_dynamic(r)
        out.update(gold_tips(f"figure5/{short(d['law'])}/{d['formulation']}/{d['element']}/{d['elements']}", d))
    return out
