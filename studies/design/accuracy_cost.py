"""Accuracy against cost, static half of study 6: a work-precision diagram.

Error: |u - u_ref| / |u_ref| over (ux, uy), u_ref the converged continuum value of the
matching model (ANCF plane-stress against continuum plane stress, plane-strain against
continuum plane strain with the same penalty). Cost: the median wall time of serial warm
runs of the whole solver call (build + solve + tip), one process, after a warm-up
(the cases' ``timing`` option; never timed inside a pool). Every element, formulation,
quadrature and mesh, and the continuum model's own curve: its levels timed the same
way, their error against the continuum's own Richardson value.

The hyperelastic cable HC2n-8 runs beside the other elements where it can: its plane-stress
cells, and the pendulum on Table 4's step ladder (this study's own pendulum cases, the
``pendulum`` grid: Table 4 runs the paper's elements); it refuses plane strain (its section is
uniaxial with free faces), and the tables say so (:func:`absent`). The choose-an-element
table adds, from the cable's card records (its slenderness sweep), the L / h below which the
cable stops being within each accuracy of the continuum: below it a shear-deformable section
is needed (:func:`cable_slenderness`).
"""
from __future__ import annotations

from ..engine.case import make_case
from ..verification.continuum import scene as continuum_scene
from ..common.grid import DEFAULT, cantilever_case, counts_of, qlabel, takes
from ..common.gold import short, MATCHING, continuum_references, describe, variant_of
from ..engine.report import GOOD, Section, Table, draw, figure, hollow_legend, marker, pct, vec_error, verdict


STUDY = {
    "name": "accuracy-cost",
    "title": "Accuracy against cost (static cantilever and pendulum)",
    # the pendulum half reads Table 4's timed step ladder (no cases of its own)
    "needs": ["continuum", "table4"],
    "grid": {
        "laws": ["neo-hookean", "mooney-rivlin", "yeoh"],
        # HC2n-8, the hyperelastic cable, runs plane stress alone (its plane-strain cells are absent, :func:`absent`)
        "elements": ["HB2n-12", "HB3n-12", "HB2n-16", "LB2n-12", "HB2n-20xyp", "HB2n-20xypm", "HB2n-40p", "HB2n-60p",
                     "HC2n-8"],
        "formulations": ["plane-strain", "plane-stress"],
        # "default": each element's own rule at each mesh's l_e / h; the fixed rules of the paper's
        # elements are the study accuracy-cost-rules (make study-full), drawn here when recorded
        "quadratures": ["default"],
        "counts": [4, 8, 16, 32, 64, 160, 320, 640],
        "clamp": "face",
        # serial warm timings: the compiled code loaded, then up to `repeats` runs within `budget_s`
        "timing": {"repeats": 3, "budget_s": 2.0},
        # the continuum curve: these levels of the continuum study's variants, timed the same way
        "continuum_levels": [[16, 1], [32, 2], [64, 4], [128, 8]],
        "accuracies": [0.01, 0.001],
        # the pendulum beside Table 4's rungs (the paper's elements): the elements Table 4 does not
        # run, on its grid (its step ladder, 8 ms halving to dt_last, its counts and timing)
        "pendulum": {"elements": ["HC2n-8"], "counts": [4, 8, 16, 32], "formulations": ["plane-stress"],
                     "rho_inf": 0.5, "t_end": 0.5, "dt_last": 0.00025, "timing": {"repeats": 3, "budget_s": 1.5}},
    },
    "tiny": {
        "laws": ["yeoh"],
        "elements": ["HB2n-12", "HB3n-12", "HC2n-8"],
        "counts": [4, 8],
        "timing": {"repeats": 2, "budget_s": 0.5},
        "continuum_levels": [[8, 1]],
        "pendulum": {"elements": ["HC2n-8"], "counts": [8], "formulations": ["plane-stress"], "rho_inf": 0.5,
                     "t_end": 0.5, "dt_last": 0.0005, "timing": {"repeats": 1, "budget_s": 0.0}},
    },
}

STYLE = {(2, 2): ":", (3, 2): "-", (5, 3): "--", (3, 3): "-.", DEFAULT: "-"}
# the fixed rules of the paper's elements (make study-full), drawn here when recorded
RULES = "accuracy-cost-rules"


def cases(grid: dict, tiny: bool, study: str = "accuracy-cost") -> list:
    """The static cantilever of every law, formulation, element (where it runs the
    formulation: :func:`absent`), rule and mesh; the continuum's levels; the ``pendulum``
    grid's runs on Table 4's step ladder (where the grid has one)."""
    from ancf.checks import runs
    from ..common.pendulum_cases import ladder, pendulum_case

    opts = {"timing": dict(grid["timing"])}
    out = [cantilever_case(study, law, f, el, n, q, grid["clamp"], opts)
           for law in grid["laws"] for f in grid["formulations"] for el in grid["elements"] if runs(el, f)
           for q in grid["quadratures"] if takes(grid, el, q) for n in counts_of(grid, el)]
    out += [make_case(study, "continuum", continuum_scene(law, MATCHING[f], tuple(lv)), opts)
            for law in grid["laws"] for f in grid["formulations"] for lv in grid["continuum_levels"]]
    pd = grid.get("pendulum")
    if pd:
        popts = {"timing": dict(pd["timing"])}
        out += [pendulum_case(study, el, n, f, dt, rho_inf=pd["rho_inf"], t_end=pd["t_end"], options=popts)
                for f in pd["formulations"] for el in pd["elements"] if runs(el, f) for n in pd["counts"]
                for dt in ladder(last=pd.get("dt_last"))]
    return out


def absent(grid: dict) -> list[str]:
    """Why the grid's elements that refuse one of its formulations have no cells there
    (a cable: plane stress alone), one sentence each."""
    from ancf.checks import runs
    from ancf.elements import get_element
    from .card_report import CABLE_NOT_RUN

    out = []
    for el in grid["elements"]:
        miss = [f for f in grid["formulations"] if not runs(el, f)]
        if miss:
            why = CABLE_NOT_RUN if get_element(el).cable else f"it runs {', '.join(get_element(el).formulations)} only"
            out.append(f"{el} has no {' or '.join(f'`{f}`' for f in miss)} cells: {why}.")
    return out


def _static(r: dict) -> bool:
    return (r.get("scene") or {}).get("analysis", {}).get("kind", "static") == "static"


def _slenderness(scene: dict) -> float:
    b = scene["beam"]
    return b["length"] / b["height"]


def points(ctx) -> list[dict]:
    """One point per record: configuration, time (s), error (fraction) or None."""
    refs = continuum_references(ctx.records("continuum"))
    out = []
    for r in [r for r in ctx.records() if _static(r)] + ctx.records(RULES):
        d = describe(r)
        t = (r.get("timing") or {}).get("median_s")
        if r["solver"] == "ancf":
            ref = refs.get((d["law"], MATCHING[d["formulation"]]))
            p = {"law": d["law"], "model": MATCHING[d["formulation"]], "solver": "ancf",
                 "config": f"{d['element']} {qlabel(d['quadrature'])}", "element": d["element"],
                 "quadrature": d["quadrature"], "mesh": d["elements"], "ndof": r.get("ndof"),
                 "slenderness": _slenderness(r["scene"])}
        else:
            ref = refs.get((d["law"], variant_of(r["scene"])))
            p = {"law": d["law"], "model": variant_of(r["scene"]), "solver": "continuum", "config": "continuum Q2",
                 "element": "continuum", "quadrature": None, "mesh": f"{d['cells'][0]}x{d['cells'][1]}",
                 "ndof": r.get("ndof")}
        ok = d["status"] == "converged"
        p.update(status=d["status"], verdict=verdict(r), time=t if ok else None,
                 error=vec_error(d["tip"], ref.tip if ref else None) if ok else None)
        out.append(p)
    return out


def settled(pts: list[dict], target: float) -> list[dict]:
    """The points that reach ``target`` without resting on cancellation: the point and
    every finer mesh (at least as many unknowns) of the same solver and configuration
    are good (stable, unwarned: :data:`GOOD`) and within ``target``; a failed, singular,
    indefinite or warned finer run disqualifies."""
    def ok(q):
        return q["verdict"] in GOOD and q["error"] is not None and q["error"] <= target
    return [p for p in pts
            if all(ok(q) for q in pts
                   if q["solver"] == p["solver"] and q["config"] == p["config"] and (q["ndof"] or 0) >= (p["ndof"] or 0))]


def cheapest(pts: list[dict], target: float) -> dict | None:
    ok = [p for p in pts if p["error"] is not None and p["time"] is not None and p["error"] <= target]
    return min(ok, key=lambda p: p["time"]) if ok else None


def _panel(ax, g: dict, sel: list[dict]) -> None:
    """One law and model: a curve per configuration (ANCF element and rule) over its meshes,
    and the continuum's own levels in black."""
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
    for a in g["accuracies"]:
        ax.axhline(a, color="grey", lw=0.6, ls=":")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.grid(True, which="major", alpha=0.3)


def _figure(ctx, sec: Section, g: dict, pts: list[dict], models: list[str]) -> None:
    fig, axes = figure(len(models), len(g["laws"]), figsize=(4.6 * len(g["laws"]), 4.0 * len(models)),
                       squeeze=False, sharey=True)
    for i, (f, m) in enumerate(zip(g["formulations"], models)):
        for j, law in enumerate(g["laws"]):
            ax = axes[i][j]
            _panel(ax, g, [p for p in pts if p["law"] == law and p["model"] == m])
            ax.set_title(f"{law}\nANCF {f} vs continuum {m}", fontsize=9)
            ax.set_xlabel("wall time, serial warm (s)")
            if j == 0:
                ax.set_ylabel("|u - u_ref| / |u_ref|")
    axes[0][-1].legend(*hollow_legend(axes[0][-1]), fontsize=6, loc="lower left", ncol=2)
    sec.figure(ctx, fig, "accuracy_cost", "Work-precision diagram of the static cantilever: each line one ANCF element "
               "and quadrature over its meshes (4 to 640 elements), black the continuum model's own refinement; "
               "lower left is better. Hollow markers: runs that converged to a singular or indefinite state, or "
               "carry a warning (verdict column of the points table). The ANCF curves level off at the beam model's "
               "distance from the continuum.")


def _cheapest_rows(g: dict, pts: list[dict], models: list[str]) -> list[list]:
    """Per law, formulation and accuracy: the cheapest settled ANCF run and continuum level."""
    rows = []
    for f, m in zip(g["formulations"], models):
        for law in g["laws"]:
            sel = [p for p in pts if p["law"] == law and p["model"] == m]
            for a in g["accuracies"]:
                best_a = cheapest(settled([p for p in sel if p["solver"] == "ancf"], a), a)
                best_c = cheapest(settled([p for p in sel if p["solver"] == "continuum"], a), a)
                rows.append([short(law), f, f"{100 * a:g} %",
                             f"{best_a['config']} x {best_a['mesh']}" if best_a else "none",
                             best_a["verdict"] if best_a else None,
                             best_a["time"] if best_a else None, pct(best_a["error"]) if best_a else None,
                             f"{best_c['mesh']} Q2" if best_c else "none",
                             best_c["time"] if best_c else None, pct(best_c["error"]) if best_c else None])
    return rows


def _points_table(ctx, sec: Section, pts: list[dict]) -> None:
    long = [[p["law"], p["model"], p["solver"], p["config"], p["mesh"], p["ndof"], p["status"], p["verdict"],
             p["time"], pct(p["error"])] for p in pts]
    t = Table("accuracy_cost_points", ["law", "model", "solver", "configuration", "mesh", "ndof", "status",
                                       "verdict", "time (s)", "error (%)"], long, {8: ".4f", 9: ".4f"})
    t.write(ctx.out)
    sec.items.append(("link", t.name + ".md", "Every point of the diagram."))


def _verdicts_prose(pts: list[dict]) -> str:
    ancf = [p for p in pts if p["solver"] == "ancf"]
    counts = {v: sum(1 for p in ancf if p["verdict"] == v) for v in dict.fromkeys(p["verdict"] for p in ancf)}
    text = (f"\nVerdicts of the {len(ancf)} static ANCF runs: "
            + ", ".join(f"{n} {v}" for v, n in sorted(counts.items(), key=lambda kv: -kv[1]))
            + "; only stable, unwarned runs count for the cheapest cells.")
    failed = [p for p in pts if p["status"] != "converged"]
    if failed:
        text += f"\n{len(failed)} of {len(pts)} static runs failed: " + "; ".join(
            f"{short(p['law'])} {p['model']} {p['config']} x {p['mesh']}" for p in failed)
    return text


def report(ctx) -> Section:
    g = ctx.study.grid
    pts = points(ctx)
    sec = Section(ctx.study.title,
                  "Error |u - u_ref| / |u_ref| of the static tip against the median wall time of serial warm runs "
                  "(build + solve), for every element, formulation, quadrature and mesh, and for the continuum "
                  "model's own refinement levels; u_ref is the converged continuum value of the matching model.")
    models = [MATCHING[f] for f in g["formulations"]]
    _figure(ctx, sec, g, pts, models)
    sec.table(ctx, Table("accuracy_cost", ["law", "formulation", "accuracy", "cheapest ANCF", "verdict", "time (s)",
                                           "error (%)", "cheapest continuum", "time (s)", "error (%)"],
                         _cheapest_rows(g, pts, models), {5: ".3f", 6: ".3f", 8: ".3f", 9: ".3f"}),
              "For 1 % and 0.1 % accuracy, the cheapest configuration (median serial warm wall time) of ANCF and of "
              "the continuum model that reaches it and stays within it on every finer mesh of the same configuration "
              "(a curve that crosses the target on its way to a plateau above it, or through zero error, does not "
              "count), counting only stable, unwarned runs whose finer meshes are stable and unwarned too; 'none' "
              "where no configuration of the grid does." + "".join(" " + t for t in absent(g)))
    _points_table(ctx, sec, pts)
    pendulum_part(ctx, sec)
    choose_element(ctx, sec, pts)
    sec.text += _verdicts_prose(pts)
    return sec


# runs within this factor of the cheapest one's time are named beside it: timings drift by
# 10 to 30 % between runs of one machine (the peers' rounds), so a closer order is not a ranking
TIE = 1.3


def choose_element(ctx, sec: Section, pts: list[dict]) -> None:
    """For each scene (the static cantilever per law and 2D assumption, the pendulum per
    formulation) and accuracy: the cheapest element and mesh (its settled run: it and every
    finer one within the accuracy), the other elements within :data:`TIE` of its time, the
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
    """The rows of :func:`choose_element` from the static points (:func:`points`), the
    pendulum points (:func:`all_pendulum_points`) and the cables' slenderness sweeps
    (:func:`cable_slenderness`): scene, accuracy, the cheapest settled run's name, time and
    error, the ties, the scene's L / h and the cables' L / h limits at that accuracy."""
    from ancf.checks import runs

    rows = []
    cables = sorted({el for el, _ in sweeps} | set(cable_elements(g["elements"])))

    def limit(law, formulation, acc) -> str:
        """The cables' cells: 'HC2n-8: 23.4' (the card's crossing), or why there is none."""
        from .card_report import _crossing
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
    from ancf.elements import get_element

    return [el for el in elements if get_element(el).cable]


def cable_slenderness(ctx) -> dict[tuple[str, str], list[tuple[float, float]]]:
    """{(cable, law): [(L / h, error)]} from the card records of the grid's cables
    (``<out>/data/card-<element>.jsonl``, their slenderness sweep, part 9 of the card, of its
    full grid or its CI grid, whichever has records): at
    each L / h the tip of the finest mesh against the converged continuum
    (tests/gold/fem_slenderness.json), as the card reads it. Empty where a cable has no
    card records (``python -m studies card <element>`` makes them)."""
    from .card_cases import cases as card_cases, slug
    from ..verification.slenderness_gold import GOLD, references

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


def _pendulum_point(r: dict, cont: dict) -> dict:
    """A pendulum record as a point: its median serial warm wall time and its error max over
    t of |r - r_ref| / L against the converged continuum plane-stress pendulum."""
    from ..common.pendulum_cases import describe_dynamic, tip_errors

    d = describe_dynamic(r)
    ref = cont.get((d["law"], "plane-stress"))
    e = tip_errors(d["tips"], ref.tips) if (ref and d["ok"]) else {}
    t = (d["timing"] or {}).get("median_s")
    return {"formulation": d["formulation"], "element": d["element"], "n": d["elements"], "dt": d["dt"],
            "law": d["law"], "slenderness": _slenderness(r["scene"]), "status": d["status"], "verdict": verdict(r),
            "time": t if d["ok"] else None, "error": max(e.values()) if e else None}


def pendulum_points(ctx) -> list[dict]:
    """The dynamic half: every timed rung of Table 4 (element, count, step) as a point:
    its median serial warm wall time and its pendulum error max over t of |r - r_ref| / L
    against the converged continuum plane-stress pendulum (`paper` against it too)."""
    from ..common.pendulum_cases import continuum_pendulum

    cont = continuum_pendulum()
    return [_pendulum_point(r, cont) for r in ctx.records("table4")]


def own_pendulum_points(ctx) -> list[dict]:
    """This study's own pendulum runs (the ``pendulum`` grid: the elements Table 4 does not
    run, on its ladder) as points, as :func:`pendulum_points`."""
    from ..common.pendulum_cases import continuum_pendulum

    cont = continuum_pendulum()
    return [_pendulum_point(r, cont) for r in ctx.records() if not _static(r)]


def all_pendulum_points(ctx) -> list[dict]:
    """Table 4's rungs and this study's own pendulum runs."""
    return pendulum_points(ctx) + own_pendulum_points(ctx)


def settled_steps(pts: list[dict], target: float) -> list[dict]:
    """The pendulum points within ``target`` whose every finer run (same formulation and
    element, at least as many elements and at most the step) is good and within it too."""
    def ok(q):
        return q["verdict"] in GOOD and q["error"] is not None and q["error"] <= target
    return [p for p in pts
            if all(ok(q) for q in pts if (q["formulation"], q["element"]) == (p["formulation"], p["element"])
                   and q["n"] >= p["n"] and q["dt"] <= p["dt"])]


def pendulum_part(ctx, sec: Section) -> None:
    from ..common.pendulum_cases import continuum_pendulum

    pts = all_pendulum_points(ctx)
    if not pts:
        return
    g = ctx.study.grid
    laws = sorted({p["law"] for p in pts})
    law = laws[0] if len(laws) == 1 else None
    cont = continuum_pendulum().get((law, "plane-stress"))
    forms = list(dict.fromkeys(p["formulation"] for p in pts))
    fig, axes = figure(1, len(forms), figsize=(5.2 * len(forms), 4.2), squeeze=False, sharey=True)
    for j, f in enumerate(forms):
        ax = axes[0][j]
        els = list(dict.fromkeys(p["element"] for p in pts))
        for el in els:
            for n in sorted({p["n"] for p in pts if p["element"] == el}):
                ser = sorted([p for p in pts if (p["formulation"], p["element"], p["n"]) == (f, el, n)
                              and p["error"] is not None and p["time"]], key=lambda p: -p["dt"])
                if ser:
                    draw(ax, [p["time"] for p in ser], [max(p["error"], 1e-7) for p in ser],
                         [p["verdict"] for p in ser], f"{el} x {n}", marker=marker(el, els), lw=0.8, ms=3)
        if cont and cont.wall_s and cont.error_estimate:
            ax.plot([cont.wall_s], [cont.error_estimate / 0.350], "kD", ms=7,
                    label="continuum (gold base run, own error estimate)")
        for a in g["accuracies"]:
            ax.axhline(a, color="grey", lw=0.6, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.grid(True, which="major", alpha=0.3)
        ax.set_xlabel("wall time, serial warm (s)")
        ax.set_title(f"pendulum ({', '.join(laws)}): ANCF `{f}` vs continuum plane stress", fontsize=9)
        if j == 0:
            ax.set_ylabel("max over t of |r - r_ref| / L")
    axes[0][-1].legend(*hollow_legend(axes[0][-1]), fontsize=5, ncol=2, loc="lower left")
    sec.figure(ctx, fig, "accuracy_cost_pendulum",
               "Work-precision diagram of the pendulum: each line one element and count along the step ladder of "
               "Table 4 (8 ms halving; larger dt to the left; Table 4's elements and this study's own runs of the "
               "cable), error against the converged continuum plane-stress "
               "pendulum; the black diamond is the continuum's own run (one run's wall time, its error estimate).")
    rows = []
    for f in forms:
        for a in g["accuracies"]:
            ok = [p for p in settled_steps([p for p in pts if p["formulation"] == f], a) if p["time"]]
            best = min(ok, key=lambda p: p["time"]) if ok else None
            rows.append([f, f"{100 * a:g} %", f"{best['element']} x {best['n']}, dt {1e3 * best['dt']:g} ms"
                         if best else "none", best["time"] if best else None, pct(best["error"]) if best else None,
                         cont.wall_s if cont else None, pct(cont.error_estimate / 0.350) if cont and cont.error_estimate
                         else None])
    sec.table(ctx, Table("accuracy_cost_pendulum", ["ANCF formulation", "accuracy", "cheapest ANCF", "time (s)",
                                                    "error (%)", "continuum run (s)", "continuum error estimate (%)"],
                         rows, {3: ".3f", 4: ".3f", 5: ".1f", 6: ".4f"}),
              "For 1 % and 0.1 % pendulum accuracy (max over t of |r - r_ref| / L), the cheapest ANCF run of the Table 4 "
              "ladder (Table 4's elements and this study's own cable runs; median serial warm wall time) whose every finer run (more elements, smaller step, same element) "
              "converged and stays within the accuracy, beside the wall time of the continuum gold's base run (DOLFINx, one run inside the generator's 2-process pool, not warm, "
              "timed when the gold was generated, on that day's machine: a scale, not a ratio to this run's times) and its own "
              "error estimate.")


def audit(ctx) -> list[str]:
    """A referee's recheck from the written CSVs alone: every 'cheapest ANCF' cell of
    accuracy_cost.csv is a stable point of accuracy_cost_points.csv within the accuracy,
    and so is every finer mesh of its configuration (no cell rests on cancellation)."""
    import csv

    out = []
    cells, pts = ctx.out / "accuracy_cost.csv", ctx.out / "accuracy_cost_points.csv"
    if not (cells.exists() and pts.exists()):
        return out
    points = list(csv.DictReader(open(pts)))
    for i, row in enumerate(csv.DictReader(open(cells)), start=2):
        if row["cheapest ANCF"] == "none":
            continue
        config, mesh = row["cheapest ANCF"].rsplit(" x ", 1)
        a = float(row["accuracy"].rstrip(" %"))
        model = MATCHING[row["formulation"]]
        law = next((p["law"] for p in points if short(p["law"]) == row["law"]), row["law"])
        same = [p for p in points if p["solver"] == "ancf" and p["law"] == law and p["model"] == model
                and p["configuration"] == config]
        me = [p for p in same if p["mesh"] == mesh]
        if not me:
            out.append(f"accuracy_cost.csv:{i}: {row['cheapest ANCF']} is not a point of accuracy_cost_points.csv")
            continue
        finer = [p for p in same if int(p["ndof"] or 0) >= int(me[0]["ndof"] or 0)]
        bad = [p for p in finer if p["verdict"] not in GOOD or not p["error (%)"] or float(p["error (%)"]) > a]
        if bad:
            out.append(f"accuracy_cost.csv:{i}: cheapest at {row['accuracy']} {row['cheapest ANCF']} rests on "
                       f"{', '.join(p['mesh'] + ' (' + p['verdict'] + ', ' + (p['error (%)'] or '-') + ' %)' for p in bad)}")
    return out
