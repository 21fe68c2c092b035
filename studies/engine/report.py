"""Reports from records only: Markdown tables with CSV beside them, PNG figures, and
``reports/README.md`` assembled from every study's :class:`Section`.

A study's ``report(ctx)`` gets a :class:`Context`: the records of its current cases
(and of the studies it needs), the output directory, and writers for tables and figures.
Nothing here calls a solver. SI in records; tables and figures print mm and MPa.
"""
from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Sequence

from .case import canonical
from .catalog import Study
from .store import store_for


@dataclass
class Table:
    """A table as header + rows; rendered to Markdown and CSV (the CSV keeps full
    precision: give raw numbers, and ``fmt`` per column for the Markdown)."""
    name: str                 # file stem: <out>/<name>.md and .csv
    header: Sequence[str]
    rows: list[Sequence]
    fmt: dict[int, str] = field(default_factory=dict)  # column index -> format spec

    def cell(self, j: int, v) -> str:
        if v is None or (isinstance(v, float) and not math.isfinite(v)):
            return "-"
        if isinstance(v, float):
            return format(v, self.fmt.get(j, ".4g"))
        return str(v)

    def markdown(self) -> str:
        lines = ["| " + " | ".join(self.header) + " |", "|" + "---|" * len(self.header)]
        lines += ["| " + " | ".join(self.cell(j, v) for j, v in enumerate(r)) + " |" for r in self.rows]
        return "\n".join(lines) + "\n"

    def write(self, out: Path) -> tuple[Path, Path]:
        md, cs = out / f"{self.name}.md", out / f"{self.name}.csv"
        md.write_text(self.markdown())
        with open(cs, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(self.header)
            w.writerows([["" if v is None else v for v in r] for r in self.rows])
        return md, cs


FIGURE_DATA = ".figure.csv"   # beside every <name>.png: what it draws, for the audit


def figure_data(fig) -> list[list]:
    """Every drawn point of ``fig`` as rows (panel, title, x label, y label, artist
    label, marker, filled, x, y): lines and scatter sets of every panel, so that a
    figure is audited by its data, not its pixels. ``filled`` is False for hollow
    markers (a run that is not stable, or warned)."""
    import matplotlib.colors as mcolors

    rows = []
    for i, ax in enumerate(fig.axes):
        head = [i, ax.get_title(), ax.get_xlabel(), ax.get_ylabel()]
        for ln in ax.get_lines():
            face = ln.get_markerfacecolor()
            filled = not (isinstance(face, str) and face == "none") and ln.get_fillstyle() != "none"
            for x, y in zip(ln.get_xdata(), ln.get_ydata()):
                rows.append(head + [ln.get_label(), str(ln.get_marker()), filled, _num(x), _num(y)])
        for col in ax.collections:
            offs = col.get_offsets()
            fc = col.get_facecolors()
            for k, (x, y) in enumerate(offs):
                f = fc[k % len(fc)] if len(fc) else None
                filled = f is not None and mcolors.to_rgba(f)[3] > 0
                rows.append(head + [col.get_label(), type(col).__name__, filled, _num(x), _num(y)])
    return rows


def _num(v):
    try:
        v = float(v)
    except (TypeError, ValueError):
        return str(v)
    return "" if not math.isfinite(v) else format(v, ".10g")


def write_figure_data(fig, path: Path) -> Path:
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["panel", "title", "x label", "y label", "label", "marker", "filled", "x", "y"])
        w.writerows(figure_data(fig))
    return path


@dataclass
class Section:
    """What a study contributes to reports/README.md."""
    title: str
    intro: str = ""
    items: list[tuple[str, str, str]] = field(default_factory=list)  # (kind, path, two lines)
    text: str = ""       # findings stated from the numbers

    def table(self, ctx: "Context", table: Table, caption: str) -> Table:
        md, cs = table.write(ctx.out)
        self.items.append(("table", md.name, caption))
        return table

    def figure(self, ctx: "Context", fig, name: str, caption: str) -> None:
        path = ctx.out / f"{name}.png"
        fig.savefig(path, dpi=110, bbox_inches="tight")
        write_figure_data(fig, ctx.out / f"{name}{FIGURE_DATA}")
        import matplotlib.pyplot as plt
        plt.close(fig)
        self.items.append(("figure", path.name, caption))


def _contains(big, small) -> bool:
    """Whether ``small`` (a scene) is ``big`` with some defaulted keys left out."""
    if isinstance(small, dict):
        return isinstance(big, dict) and all(k in big and _contains(big[k], v) for k, v in small.items())
    return big == small


@dataclass
class Context:
    study: Study
    out: Path
    catalog: dict
    _index: dict = field(default_factory=dict, repr=False)

    def records(self, name: str | None = None) -> list[dict]:
        """The record of each current case of ``name`` (default: this study), in case
        order, each once (cases sharing a scene share a record); cases without a record
        are left out."""
        if name and name not in self.catalog:
            return []
        s = self.catalog[name] if name else self.study
        out, seen = [], set()
        for c in s.cases():
            r = self.record_for(c, s.name)
            if r is not None and id(r) not in seen:
                seen.add(id(r))
                out.append(r)
        return out

    def record_for(self, case, name: str | None = None) -> dict | None:
        """The record of ``case``: the one its id names, else (records computed with
        other solver sources, so other ids) the latest record of the same solver, scene
        name and options whose scene contains the case's scene (a solver echoes its
        scene with the defaults filled in). A report reads the records as they are and
        never runs a solver."""
        name = name or self.study.name
        if name not in self._index:
            recs = store_for(self.out, name).read()
            by_name: dict = {}
            for r in recs.values():
                c = r.get("case") or {}
                key = (c.get("solver"), (r.get("scene") or {}).get("name"), canonical(c.get("options") or {}))
                by_name.setdefault(key, []).append(r)
            self._index[name] = (recs, by_name)
        recs, by_name = self._index[name]
        if case.id in recs:
            return recs[case.id]
        scene = case.scene
        found = [r for r in by_name.get((case.solver, case.name, case.options_json), ())
                 if _contains(r["scene"], scene)]
        return found[-1] if found else None

    @property
    def tiny(self) -> bool:
        return self.study.tiny


def figure(nrows: int = 1, ncols: int = 1, **kw):
    """``plt.subplots`` on the Agg backend, with matplotlib's constrained layout unless told
    otherwise (titles, labels and tick labels of neighbouring axes kept apart, the axes
    reaching the figure's right edge, where :func:`legend_outside` puts the legend)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    kw.setdefault("layout", "constrained")
    return plt.subplots(nrows, ncols, **kw)


MARKERS = "os^xDv<>p*"
LINESTYLES = ("-", "--", ":", "-.")


def marker(element: str, elements) -> str:
    """The marker of ``element`` in figures: by its place in the grid's element list."""
    elements = list(elements)
    return MARKERS[elements.index(element) % len(MARKERS)] if element in elements else "."


def linestyle(element: str, elements) -> str:
    elements = list(elements)
    return LINESTYLES[elements.index(element) % len(LINESTYLES)] if element in elements else "-"


def mm(v: float | None) -> float | None:
    return None if v is None else v * 1e3


def pct(v: float | None) -> float | None:
    return None if v is None else v * 100.0


def rel_dev(value: float | None, ref: float | None) -> float | None:
    """(value - ref) / |ref| (a fraction), None when either is missing or ref = 0."""
    if value is None or ref is None or ref == 0:
        return None
    return (value - ref) / abs(ref)


VERDICTS = {
    "stable": "converged; the constrained tangent is positive definite (ancf.solvers.stability)",
    "converged": "converged; a dynamic run or a continuum run (no equilibrium tangent to test)",
    "warned": "converged, but the record carries a warning (e.g. a quadrature rule that nearly misses a mode)",
    "singular": "converged to a state whose tangent has a zero-energy mode of the quadrature rule",
    "indefinite": "converged to a saddle: the tangent has a negative eigenvalue (an unstable equilibrium)",
    "undetermined": "converged; the stability check could not decide (lowest eigenvalue within round-off)",
    "failed": "no converged result",
}
GOOD = ("stable", "converged")   # verdicts whose points count for "cheapest at accuracy a"


def verdict(rec: dict) -> str:
    """The verdict of a run from its record (a key of :data:`VERDICTS`): failed, else
    singular / indefinite / undetermined from the static stability check, else warned
    (any warning in the record), else stable (a static ANCF state checked stable) or
    converged (nothing to check)."""
    if rec.get("status") != "converged":
        return "failed"
    st = rec.get("stable")
    text = str(rec.get("stability") or "")
    if st is False:
        if "singular" in text:
            return "singular"
        if text.startswith("undetermined"):
            return "undetermined"
        return "indefinite"
    if st is None and text.startswith("undetermined"):
        return "undetermined"
    if rec.get("warnings"):
        return "warned"
    return "stable" if st is True else "converged"


def hollow(v: str) -> bool:
    """Figures draw a point hollow unless its verdict is good."""
    return v not in GOOD


def draw(ax, xs, ys, verdicts, label, **kw) -> None:
    """A curve and its points: filled markers for good runs, hollow ones for the rest
    (not stable, or warned): the line carries the label, the points the verdicts."""
    mk, ms = kw.pop("marker", "o"), kw.pop("ms", 3.5)
    (line,) = ax.plot(xs, ys, label=label, **kw)
    good = [(x, y) for x, y, v in zip(xs, ys, verdicts) if not hollow(v)]
    bad = [(x, y) for x, y, v in zip(xs, ys, verdicts) if hollow(v)]
    if good:
        ax.plot(*zip(*good), ls="none", marker=mk, ms=ms, color=line.get_color(), label="_good")
    if bad:
        ax.plot(*zip(*bad), ls="none", marker=mk, ms=ms, color=line.get_color(), mfc="none", label="_hollow")


def hollow_legend(ax) -> None:
    """The legend with one entry for hollow points."""
    from matplotlib.lines import Line2D

    h, l = ax.get_legend_handles_labels()
    h.append(Line2D([], [], ls="none", marker="o", color="grey", mfc="none"))
    l.append("hollow: singular, indefinite, warned or undetermined")
    return h, l


# -- what a figure a reader opens first may draw (the lead figures; their full clouds are
# secondary figures beside them, with the same data in their .figure.csv)
MAX_SERIES = 8           # labelled series per axes
TARGETS = (0.01, 0.003, 0.001)   # the accuracy targets the work-precision figures mark
OTHERS = "other elements' fronts (grey)"


def series(ax) -> list[str]:
    """The labelled series an axes draws (lines and scatter sets whose label does not start
    with '_': matplotlib's mark for an artist the legend leaves out, which the figures use
    for markers, target lines and annotations of a labelled series)."""
    return [a.get_label() for a in [*ax.get_lines(), *ax.collections]
            if not str(a.get_label()).startswith("_")]


def legend_outside(fig, handles=None, labels=None, **kw):
    """One legend for the whole figure, right of its axes (outside every axes: saved with
    ``bbox_inches="tight"`` it widens the image instead of covering data); ``handles`` and
    ``labels`` default to every axes' labelled artists, each label once."""
    if handles is None:
        handles, labels, seen = [], [], set()
        for ax in fig.axes:
            for h, l in zip(*ax.get_legend_handles_labels()):
                if l not in seen:
                    seen.add(l)
                    handles.append(h)
                    labels.append(l)
    kw.setdefault("fontsize", 7)
    return fig.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.0, 1.0),
                      bbox_transform=fig.transFigure, **kw)


def element_color(element: str) -> str:
    """An element's colour, the same in every figure: its place among the built-in elements
    of the registry, in tab10 without its grey (grey is the lead figures' secondary lines);
    an element registered by another module gets the colour after theirs."""
    import matplotlib

    from ancf.elements import ELEMENTS

    names = [n for n in ELEMENTS.keys() if n in ELEMENTS.builtin]
    colors = [c for k, c in enumerate(matplotlib.colormaps["tab10"].colors) if k != 7]
    i = names.index(element) if element in names else len(names)
    return matplotlib.colors.to_hex(colors[i % len(colors)])


def front(points: list[dict], error: str = "error", time: str = "time") -> list[dict]:
    """The Pareto envelope of ``points`` (dicts with a time and an error; missing ones are
    passed by): sorted by time, each point whose error is below every cheaper point's, so
    that the first point of the front within an accuracy is the cheapest that reaches it."""
    out = []
    for p in sorted((p for p in points if p.get(error) is not None and p.get(time)),
                    key=lambda p: (p[time], p[error])):
        if not out or p[error] < out[-1][error]:
            out.append(p)
    return out


def draw_front(ax, pts: list[dict], label: str, error: str = "error", time: str = "time", **kw):
    """A front (:func:`front`) as the staircase of the smallest error each time buys: flat
    from each point to the next cheaper-and-better one, then down; markers at the runs."""
    xs, ys = [p[time] for p in pts], [p[error] for p in pts]
    kw = {"ms": 4, "lw": 1.4, **kw}
    (line,) = ax.plot(xs, ys, drawstyle="steps-post", label=label, **kw)
    return line


def draw_grey(ax, curves: list[tuple[list, list]], label: str = OTHERS, **kw):
    """Several curves as one grey series (joined by NaN breaks): the secondary lines of a lead
    figure, shown without one legend entry each; None when there are none."""
    xs, ys = [], []
    for x, y in curves:
        if len(x):
            xs += [*x, float("nan")]
            ys += [*y, float("nan")]
    if not xs:
        return None
    kw = {"color": "0.72", "lw": 0.8, "drawstyle": "steps-post", "zorder": 1, **kw}
    (line,) = ax.plot(xs, ys, label=label, **kw)
    return line


def draw_targets(ax, targets=TARGETS) -> None:
    """The accuracy targets as dotted horizontal lines (left out of the legend, which names
    them once: :func:`target_handle`)."""
    for a in targets:
        ax.axhline(a, color="grey", lw=0.7, ls=":", label=f"_target {a:g}")


def target_handle(targets=TARGETS):
    """A legend entry for the targets' dotted lines."""
    from matplotlib.lines import Line2D

    return Line2D([], [], color="grey", lw=0.7, ls=":"), "targets " + ", ".join(f"{100 * a:g}" for a in targets) + " %"


def vec_error(tip: dict | None, ref: tuple[float, float] | None) -> float | None:
    """|u - u_ref| / |u_ref| over (ux, uy)."""
    if not tip or ref is None:
        return None
    d = math.hypot(tip["ux"] - ref[0], tip["uy"] - ref[1])
    return d / math.hypot(*ref)


def write_readme(out: Path, sections: list[Section], tiny: bool, timings: dict[str, float] | None = None) -> Path:
    lines = ["# Results", "",
             "Generated by `python -m studies run all` from the records in `data/` (one JSON line per",
             "case; tables and figures read records only). Lengths in mm, stresses in MPa; records in SI.",
             "The beams: the paper's static cantilever (L = 160 mm, h = 5 mm, w = 7 mm, own weight) and its",
             "flexible pendulum (L = 350 mm, same section, pinned at one end, released from horizontal at rest).", ""]
    if tiny:
        lines += ["**Tiny mode** (CI): few elements and coarse meshes; the numbers are not results.", ""]
    for i, s in enumerate(sections, 1):
        lines += [f"## {i}. {s.title}", ""]
        if s.intro:
            lines += [s.intro, ""]
        for kind, path, caption in s.items:
            if kind == "figure":
                lines += [f"![{path}]({path})", "", caption, ""]
            elif kind == "link":
                lines += [f"{caption} ([{path}]({path}), CSV: [{path[:-3]}.csv]({path[:-3]}.csv))", ""]
            else:
                lines += [(out / path).read_text().rstrip(), "",
                          f"{caption} ([{path}]({path}), CSV: [{path[:-3]}.csv]({path[:-3]}.csv))", ""]
        if s.text:
            lines += [s.text, ""]
    cards = sorted((out / "cards").glob("*.md")) if (out / "cards").is_dir() else []
    if cards:   # written by `python -m studies card` (make study runs it after the studies)
        lines += ["## Element report cards", "",
                  "Every check the harness knows, run on one element (`python -m studies card NAME`): "
                  + ", ".join(f"[{c.stem}](cards/{c.name})" for c in cards) + ".", ""]
    if timings:
        lines += ["## Run times of the last run", "", "| study | s |", "|---|---|"]
        lines += [f"| {k} | {v:.1f} |" for k, v in timings.items()] + [""]
    path = out / "README.md"
    path.write_text("\n".join(lines))
    return path
