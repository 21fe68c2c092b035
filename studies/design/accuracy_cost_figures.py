"""The accuracy-cost study's figures, drawn from its points (:mod:`studies.design.accuracy_cost_points`):
the lead work-precision figures of the static cantilever and of the pendulum (each element's
front, the leaders coloured) and their full clouds of every run."""
from __future__ import annotations

from .accuracy_cost_points import fronts, leaders, pendulum_finer, static_finer, with_settled
from ..common.grid import DEFAULT
from ..common.pendulum_cases import LENGTH
from ..engine.report import (MAX_SERIES, draw, draw_front, draw_grey, draw_targets, element_color, figure,
                             hollow_legend, legend_outside, marker, target_handle)


STYLE = {(2, 2): ":", (3, 2): "-", (5, 3): "--", (3, 3): "-.", DEFAULT: "-"}


def draw_fronts(ax, fr: dict[str, list[dict]], colored: list[str], markers: list[str]) -> None:
    """The coloured elements' fronts, one series each, and the others' in one grey series."""
    draw_grey(ax, [([p["time"] for p in f], [p["settled"] for p in f]) for el, f in fr.items() if el not in colored])
    for el in colored:
        draw_front(ax, fr[el], el, error="settled", color=element_color(el), marker=marker(el, markers), zorder=3)


def _log_axes(ax) -> None:
    """Log scales, decades gridded, no minor ticks (several panels of minor log ticks cost
    a constrained layout most of its drawing time, and say little on these ranges)."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.grid(True, which="major", alpha=0.3)
    ax.minorticks_off()


def _panel(ax, g: dict, sel: list[dict]) -> None:
    """One law and model of the full cloud: a curve per configuration (ANCF element and
    rule) over its meshes, and the continuum's own levels in black."""
    for cfg in dict.fromkeys(p["config"] for p in sel):
        ser = [p for p in sel if p["config"] == cfg and p["error"] is not None and p["time"]]
        ser.sort(key=lambda p: p["ndof"] or 0)  # along the refinement
        if not ser:
            continue
        xs, ys, vs = [p["time"] for p in ser], [max(p["error"], 1e-7) for p in ser], [p["verdict"] for p in ser]
        if cfg.startswith("continuum"):
            draw(ax, xs, ys, vs, "continuum Q2 (levels)", color="k", marker="D", lw=2, ms=5)
            continue
        el, q = ser[0]["element"], ser[0]["quadrature"]
        draw(ax, xs, ys, vs, cfg, marker=marker(el, g["elements"]), ls=STYLE.get(q, "-"), lw=1, ms=3.5)
    draw_targets(ax, g["accuracies"])
    _log_axes(ax)


def _grid_of_panels(g: dict, models: list[str]):
    fig, axes = figure(len(models), len(g["laws"]), figsize=(3.9 * len(g["laws"]), 3.3 * len(models)),
                       squeeze=False, sharex=True, sharey=True, layout="constrained")
    for i, (f, m) in enumerate(zip(g["formulations"], models)):
        for j, law in enumerate(g["laws"]):
            ax = axes[i][j]
            ax.set_title(f"{law}: `{f}` vs continuum {m}", fontsize=8)
            if i == len(models) - 1:
                ax.set_xlabel("wall time, serial warm (s)")
    return fig, axes


def static_fronts(g: dict, pts: list[dict], law: str, model: str) -> tuple[dict, dict | None]:
    """({element: front}, the continuum's front) of one law and model (:func:`studies.design.accuracy_cost_points.fronts`)."""
    sel = [p for p in pts if p["law"] == law and p["model"] == model]
    fr = fronts(with_settled(sel, static_finer(sel)))
    return {el: f for el, f in fr.items() if el != "continuum"}, fr.get("continuum")


def lead_figure(g: dict, pts: list[dict], models: list[str]):
    """The lead work-precision figure of the static cantilever (a matplotlib Figure): per law
    and model, each element's front of settled errors (:func:`studies.design.accuracy_cost_points.fronts`), the leaders coloured
    (:func:`studies.design.accuracy_cost_points.leaders`), the others grey, the continuum's own front in black, the targets dotted."""
    fig, axes = _grid_of_panels(g, models)
    for i, m in enumerate(models):
        for j, law in enumerate(g["laws"]):
            ax = axes[i][j]
            fr, cont = static_fronts(g, pts, law, m)
            draw_fronts(ax, fr, [el for el in g["elements"] if el in leaders(fr, g["accuracies"])], g["elements"])
            if cont:
                draw_front(ax, cont, "continuum Q2 (levels)", error="settled", color="k", marker="D", ms=4, lw=1.8)
            draw_targets(ax, g["accuracies"])
            _log_axes(ax)
            if j == 0:
                ax.set_ylabel("settled |u - u_ref| / |u_ref|")
    legend_outside(fig, *_with_targets(fig, g["accuracies"], g["elements"]))
    return fig


def _with_targets(fig, targets, order=()) -> tuple[list, list]:
    """Every axes' labelled artists once (those named in ``order`` first, in its order) and
    the targets' entry."""
    hs, ls = [], []
    for ax in fig.axes:
        for h, l in zip(*ax.get_legend_handles_labels()):
            if l not in ls:
                hs.append(h)
                ls.append(l)
    rank = {l: i for i, l in enumerate(order)}
    pairs = sorted(zip(hs, ls), key=lambda hl: rank.get(hl[1], len(rank)))
    h, l = target_handle(targets)
    return [p[0] for p in pairs] + [h], [p[1] for p in pairs] + [l]


def all_figure(g: dict, pts: list[dict], models: list[str]):
    """The full cloud of the static cantilever: every configuration's curve over its meshes."""
    fig, axes = _grid_of_panels(g, models)
    for i, m in enumerate(models):
        for j, law in enumerate(g["laws"]):
            ax = axes[i][j]
            _panel(ax, g, [p for p in pts if p["law"] == law and p["model"] == m])
            if j == 0:
                ax.set_ylabel("|u - u_ref| / |u_ref|")
    h, l = _with_targets(fig, g["accuracies"])
    hh, ll = hollow_legend(axes[0][0])
    legend_outside(fig, h + hh[-1:], l + ll[-1:], ncol=2, fontsize=6)
    return fig


def _continuum_point(ax, cont) -> None:
    """The continuum gold's base run: its wall time and its own error estimate over L."""
    if cont and cont.wall_s and cont.error_estimate:
        ax.plot([cont.wall_s], [cont.error_estimate / LENGTH], "kD", ms=6,
                label="continuum (gold base run, own error estimate)")


def _pendulum_panels(pts: list[dict], laws: list[str]):
    forms = list(dict.fromkeys(p["formulation"] for p in pts))
    fig, axes = figure(1, len(forms), figsize=(4.6 * len(forms), 3.8), squeeze=False, sharex=True, sharey=True,
                       layout="constrained")
    for j, f in enumerate(forms):
        ax = axes[0][j]
        ax.set_xlabel("wall time, serial warm (s)")
        ax.set_title(f"pendulum ({', '.join(laws)}): ANCF `{f}` vs continuum plane stress", fontsize=8)
    return fig, axes[0], forms


def pendulum_lead_figure(g: dict, pts: list[dict], cont=None):
    """The lead work-precision figure of the pendulum (a matplotlib Figure): per formulation,
    each element's front of settled errors over its meshes and steps (:func:`studies.design.accuracy_cost_points.fronts`,
    :func:`settled_steps`' rule), the leaders coloured (:func:`studies.design.accuracy_cost_points.leaders`), the others grey, the
    continuum's own run, the targets dotted."""
    laws = sorted({p["law"] for p in pts})
    els = list(dict.fromkeys(p["element"] for p in pts))
    fig, axes, forms = _pendulum_panels(pts, laws)
    for ax, f in zip(axes, forms):
        sel = [p for p in pts if p["formulation"] == f]
        fr = fronts(with_settled(sel, pendulum_finer(sel)))
        draw_fronts(ax, fr, [el for el in els if el in leaders(fr, g["accuracies"], MAX_SERIES - 2)], els)
        _continuum_point(ax, cont)
        draw_targets(ax, g["accuracies"])
        _log_axes(ax)
    axes[0].set_ylabel("settled max over t of |r - r_ref| / L")
    legend_outside(fig, *_with_targets(fig, g["accuracies"], els))
    return fig


def pendulum_all_figure(g: dict, pts: list[dict], cont=None):
    """Every pendulum run: per formulation, a curve per element and count along the step
    ladder (the element's colour, a line style per count)."""
    laws = sorted({p["law"] for p in pts})
    els = list(dict.fromkeys(p["element"] for p in pts))
    counts = sorted({p["n"] for p in pts})
    fig, axes, forms = _pendulum_panels(pts, laws)
    for ax, f in zip(axes, forms):
        for el in els:
            for n in counts:
                ser = sorted([p for p in pts if (p["formulation"], p["element"], p["n"]) == (f, el, n)
                              and p["error"] is not None and p["time"]], key=lambda p: -p["dt"])
                if ser:
                    draw(ax, [p["time"] for p in ser], [max(p["error"], 1e-7) for p in ser],
                         [p["verdict"] for p in ser], f"{el} x {n}", marker=marker(el, els), lw=0.8, ms=3,
                         color=element_color(el), ls=("-", "--", ":", "-.")[counts.index(n) % 4])
        _continuum_point(ax, cont)
        draw_targets(ax, g["accuracies"])
        _log_axes(ax)
    axes[0].set_ylabel("max over t of |r - r_ref| / L")
    h, l = _with_targets(fig, g["accuracies"])
    hh, ll = hollow_legend(axes[0])
    legend_outside(fig, h + hh[-1:], l + ll[-1:], ncol=3, fontsize=6)
    return fig
