"""Which element to choose (``reports/choose_element.md``, a table of the accuracy-cost
study): for each scene and accuracy the cheapest settled ANCF run and its ties
(:func:`choose_rows`), and the slenderness below which a cable stops being within the
accuracy, from its card's records (:func:`cable_slenderness`); why an element has no
cells where it refuses a formulation (:func:`absent`)."""
from __future__ import annotations

from ancf.checks.element import runs
from ancf.elements import get_element

from .accuracy_cost_points import TIE, _slenderness, all_pendulum_points, settled, settled_steps
from .card_cable import CABLE_NOT_RUN, _crossing
from .card_cases import cases as card_cases, slug
from ..common.gold import MATCHING, short
from ..engine.report import Section, Table, pct, vec_error
from ..verification.slenderness_gold import GOLD, references


def absent(grid: dict) -> list[str]:
    """Why the grid's elements that refuse one of its formulations have no cells there
    (a cable: plane stress alone), one sentence each."""
    out = []
    for el in grid["elements"]:
        miss = [f for f in grid["formulations"] if not runs(el, f)]
        if miss:
            why = CABLE_NOT_RUN if not get_element(el).family.section_field else f"it runs {', '.join(get_element(el).family.formulations)} only"
            out.append(f"{el} has no {' or '.join(f'`{f}`' for f in miss)} cells: {why}.")
    return out


def choose_element(ctx, sec: Section, pts: list[dict]) -> None:
    """For each scene (the static cantilever per law and 2D assumption, the pendulum per
    formulation) and accuracy: the cheapest element and mesh (its settled run: it and every
    finer one within the accuracy), the other elements within :data:`studies.design.accuracy_cost_points.TIE` of its time, the
    scene's L / h, and, from the grid's cables' card records (:func:`cable_slenderness`),
    the L / h down to which a cable stays within the accuracy (below it a shear-deformable
    section is needed; a cable refuses the formulations other than plane stress)."""
    g = ctx.study.grid
    rows = choose_rows(g, pts, all_pendulum_points(ctx), cable_slenderness(ctx))
    absent_text = "".join(" " + t for t in absent(g))
    sec.table(ctx, Table("choose_element", ["scene", "accuracy", "cheapest ANCF run", "time (s)", "error (%)",
                                            f"within {TIE:g} x its time", "scene L / h",
                                            "shear-deformable section needed below L / h (cable's card)"],
                         rows, {3: ".3g", 4: ".3f"}),
              "Which element to choose: for each scene and accuracy the cheapest ANCF run that reaches the accuracy "
              "and stays within it on every finer mesh (and, for the pendulum, every smaller step), with the other "
              f"elements whose cheapest such run is within {TIE:g} times its time (median serial warm wall time; "
              "timings drift by tens of percent between runs, so these are ties, not a ranking). Last column: the "
              "slenderness L / h below which a shear-deformable section is needed, the L / h down to which the cable "
              "(a centre line without shear or thickness change) stays within the accuracy of the converged continuum, "
              "from its card's slenderness sweep (the paper's "
              "cantilever under the paper's load parameter, the row's law; the card's interpolation between the "
              "two ratios around the crossing, '> x': within it down to the stoutest beam run, '< x': beyond it "
              "already at the most slender)." + absent_text
              + " The pendulum rows take Table 4's rungs and this study's own runs of the elements Table 4 does "
              "not run, on its ladder.")


def choose_rows(g: dict, pts: list[dict], pend: list[dict], sweeps: dict) -> list[list]:
    """The rows of :func:`choose_element` from the static points (:func:`studies.design.accuracy_cost_points.points`), the
    pendulum points (:func:`studies.design.accuracy_cost_points.all_pendulum_points`) and the cables' slenderness sweeps
    (:func:`cable_slenderness`): scene, accuracy, the cheapest settled run's name, time and
    error, the ties, the scene's L / h and the cables' L / h limits at that accuracy."""
    rows = []
    cables = sorted({el for el, _ in sweeps} | set(cable_elements(g["elements"])))

    def limit(law, formulation, acc) -> str:
        """The cables' cells: 'HC2n-8: 23.4' (the card's crossing), or why there is none."""
        cells = []
        for el in cables:
            if not runs(el, formulation):
                cells.append(f"{el}: - (plane stress only)")
            elif (el, law) not in sweeps:
                cells.append(f"{el}: no card records")
            else:
                cells.append(f"{el}: {_crossing(sweeps[(el, law)], acc)}")
        return "; ".join(cells)

    def pick(label, acc, cands, lh, cable):
        best = {}
        for p in cands:            # each element's cheapest settled run
            el = p["element"]
            if el not in best or p["time"] < best[el]["time"]:
                best[el] = p
        order = sorted(best.values(), key=lambda p: p["time"])
        if not order:
            rows.append([label, f"{100 * acc:g} %", "none", None, None, "", lh, cable])
            return
        top = order[0]
        ties = [p for p in order[1:] if p["time"] <= TIE * top["time"]]
        rows.append([label, f"{100 * acc:g} %", top["name"], top["time"], pct(top["error"]),
                     ", ".join(f"{p['name']} ({p['time']:.3g} s)" for p in ties), lh, cable])

    def lh_of(sel) -> str:
        v = sorted({round(p["slenderness"], 6) for p in sel if p.get("slenderness")})
        return ", ".join(f"{x:g}" for x in v)

    for f in g["formulations"]:
        m = MATCHING[f]
        for law in g["laws"]:
            sel = [p for p in pts if p["solver"] == "ancf" and p["law"] == law and p["model"] == m]
            for a in g["accuracies"]:
                ok = [dict(p, name=f"{p['config']} x {p['mesh']}") for p in settled(sel, a) if p["time"]]
                pick(f"cantilever, {short(law)}, `{f}`", a, ok, lh_of(sel), limit(law, f, a))
    for f in dict.fromkeys(p["formulation"] for p in pend):
        sel = [p for p in pend if p["formulation"] == f]
        laws = sorted({p["law"] for p in sel})
        for a in g["accuracies"]:
            ok = [dict(p, name=f"{p['element']} x {p['n']}, dt {1e3 * p['dt']:g} ms")
                  for p in settled_steps(sel, a) if p["time"]]
            pick(f"pendulum, `{f}`", a, ok, lh_of(sel),
                 limit(laws[0], f, a) if len(laws) == 1 else "-")
    return rows


def cable_elements(elements) -> list[str]:
    """The centre-line cables among ``elements``."""
    return [el for el in elements if not get_element(el).family.section_field]


def cable_slenderness(ctx) -> dict[tuple[str, str], list[tuple[float, float]]]:
    """{(cable, law): [(L / h, error)]} from the card records of the grid's cables
    (``<out>/data/card-<element>.jsonl``, their slenderness sweep, part 9 of the card, of its
    full grid or its CI grid, whichever has records): at
    each L / h the tip of the finest mesh against the converged continuum
    (tests/gold/fem_slenderness.json), as the card reads it. Empty where a cable has no
    card records (``python -m studies card <element>`` makes them)."""
    refs = references(GOLD)
    out: dict = {}
    for el in cable_elements(ctx.study.grid["elements"]):
        tips: dict = {}
        # the card's full grid and its CI grid (a case of both is read once)
        sweep = {c.id: c for tiny in (False, True) for c in card_cases(el, tiny) if c.name.startswith("slenderness-")}
        for c in sweep.values():
            r = ctx.record_for(c, f"card-{slug(el)}")
            if r is None or r.get("status") != "converged" or not r.get("tip"):
                continue
            s = r["scene"]
            tips.setdefault((s["material"]["law"], round(_slenderness(s), 6)), {})[s["ancf"]["elements"]] = r["tip"]
        for (law, ratio), by_n in sorted(tips.items()):
            ref = refs.get((law, float(ratio)))
            if ref:
                out.setdefault((el, law), []).append((ratio, vec_error(by_n[max(by_n)], ref["tip"])))
    return out
