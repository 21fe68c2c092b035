"""The hard-case report of the dynamics issue: does the integration stay stable, and
does it hold the energy bound, when the pendulum is made hard?

From a base pendulum (``base`` grid key: law, formulation, element, count, step, time),
and the same with each element of ``elements`` (the lock-free ones), one change at a time: rho_inf over ``rho_inf``; penalty alpha = factor x C10 over
``penalty_factors`` in each of ``penalty_formulations``; ``long_t_end`` s of motion;
``many_elements`` elements; every law constant times ``softer``; every law constant times
``stiffer`` (the near-rigid pendulum, also timed against the rigid compound pendulum's swing to
the vertical, :func:`swing_rows`); a step ``larger_step`` times the base step. Each with every
integrator of ``integrators`` that ANCF admits for the case (rho_inf applies to the methods whose
coefficients depend on it, the two forms of generalized-alpha: for the others those rows are the
base run).

The bound, stated before measuring: |E(t) - E(0)| <= 1e-3 m g L / 2 for the
conservative settings (Newmark average acceleration, the discrete gradient,
generalized-alpha with rho_inf = 1); with numerical dissipation (rho_inf < 1) E may fall,
but never rise above E(0) by more than the bound. The ANCF run itself stops with status
"failed", reason "energy-growth", when E rises above E(0) + bound at any step; that is an
honest outcome and shows as such. E is sampled in the records at the output times
(every ``energy_every`` s; ``long_energy_every`` for the long run). Wall time: median of
serial warm runs (``timing``); for a failed run, its single (warm-up) run.
"""
from __future__ import annotations

from contract import paper

from ..common.pendulum_cases import describe_dynamic, gold_tips, pendulum_dict
from ..engine.case import make_case
from ..engine.report import Section, Table


STUDY = {
    "name": "stability",
    "title": "Hard cases: integrator stability and energy (pendulum)",
    "grid": {
        # one change at a time from the base pendulum (Yeoh); dt 1 ms: the converged step of
        # 32 x HB2n-12 (Table 4)
        "base": {"law": "yeoh",
                 "formulation": "plane-stress",
                 "element": "HB2n-12",
                 "elements": 16,
                 "dt": 0.001,
                 "t_end": 0.5,
                 "rho_inf": 0.5},
        # every hard case again with each of these (stability-elements: the lock-free ones)
        "elements": ["HB2n-12"],
        "integrators": ["generalized-alpha", "arnold-bruls", "newmark", "discrete-gradient"],
        "rho_inf": [0.0, 0.5, 0.8, 1.0],
        "penalty_factors": [10.0, 1000.0, 100000.0],  # alpha = factor x C10
        "penalty_formulations": ["paper", "plane-strain"],
        "long_t_end": 5.0,
        "many_elements": 128,
        "softer": 0.1,
        "stiffer": 2e4,        # near-rigid: C10 = 1.1e10 Pa
        "stiffer_every": 0.005,  # s: its output times (the swing time is read between them)
        "larger_step": 10,
        "energy_every": 0.01,  # s: output times, where E is sampled
        "long_energy_every": 0.05,
        "timing": {"repeats": 1, "budget_s": 0.0},
    },
    "tiny": {
        "elements": ["HB2n-12"],
        "base": {"law": "yeoh",
                 "formulation": "plane-stress",
                 "element": "HB2n-12",
                 "elements": 4,
                 "dt": 0.001,
                 "t_end": 0.1,
                 "rho_inf": 0.5},
        "rho_inf": [0.0, 1.0],
        "penalty_factors": [10.0, 100000.0],
        "penalty_formulations": ["paper"],
        "long_t_end": 0.3,
        "many_elements": 8,
    },
}

CONSERVATIVE = ("newmark", "discrete-gradient")
# The near-rigid pendulum's swing to the vertical against the rigid compound pendulum
# (studies.verification.closed_forms.rigid_swing_time). Tolerance, stated before the runs: the
# time discretisation of a second-order method, (omega dt)^2 = 4.2e-5 at dt = 1 ms (omega^2 =
# 3 g / (2 L)), plus the flexure under the swing's transverse load rho A g cos(theta) (1 - 3 s /
# (2 L)) (self-equilibrated about the pin, |M| <= 0.03 q L^2: a deflection of ~0.004 q L^3 / EI,
# 3e-6 of L at x 2e4), rounded up; relative
SWING_TOL = 1e-4
HOLDS = ("holds", "no growth (dissipative)")
DAMPED = 0.01    # a dissipative run that lost more than 1 % of m g L / 2 (ten bounds) is named below its table


def hard_cases(grid: dict) -> list[tuple[str, str, dict]]:
    """[(group, label, pendulum_dict keyword changes)] in report order: the hard cases of
    the base pendulum, then of the base pendulum with each other element of ``elements``."""
    b = grid["base"]
    out = []
    for el in grid.get("elements") or [b["element"]]:
        tag, ch0 = ("", {}) if el == b["element"] else (f"{el}: ", {"element": el})
        out += [("base", f"{tag}base: {b['elements']} x {el}, `{b['formulation']}`, dt {1e3 * b['dt']:g} ms, "
                         f"{b['t_end']:g} s, rho_inf {b['rho_inf']}", dict(ch0))]
        out += [("rho_inf", f"{tag}rho_inf = {r:g}", {**ch0, "rho_inf": r}) for r in grid["rho_inf"]]
        out += [("penalty", f"{tag}penalty {p:g} C10, `{f}`", {**ch0, "formulation": f, "penalty_factor": p})
                for f in grid["penalty_formulations"] for p in grid["penalty_factors"]]
        out += [("long", f"{tag}{grid['long_t_end']:g} s of motion", {**ch0, "t_end": grid["long_t_end"],
                                                                       "every": grid["long_energy_every"]}),
                ("many", f"{tag}{grid['many_elements']} elements", {**ch0, "n": grid["many_elements"]}),
                ("softer", f"{tag}material x {grid['softer']:g} (softer)", {**ch0, "stiffness_scale": grid["softer"]}),
                ("stiffer", f"{tag}material x {grid['stiffer']:g} (near-rigid)",
                 {**ch0, "stiffness_scale": grid["stiffer"], "every": grid["stiffer_every"]}),
                ("larger-step", f"{tag}step x {grid['larger_step']:g} ({1e3 * b['dt'] * grid['larger_step']:g} ms)",
                 {**ch0, "dt": b["dt"] * grid["larger_step"]})]
    return out


def scene_for(grid: dict, changes: dict, integrator: str) -> dict:
    b = dict(grid["base"])
    kw = {"element": b["element"], "n": b["elements"], "formulation": b["formulation"], "dt": b["dt"],
          "rho_inf": b["rho_inf"], "law": b.get("law", paper.PENDULUM_LAW), "t_end": b["t_end"], "every": grid["energy_every"]}
    kw.update(changes)
    if not takes_rho_inf(integrator):
        kw["rho_inf"] = b["rho_inf"]          # not used by the method: the same run as the base's
    return pendulum_dict(integrator=integrator, **kw)


def takes_rho_inf(integrator: str) -> bool:
    """Whether the method's coefficients depend on rho_inf (its class in the registry says)."""
    from ancf.solvers.integrators import INTEGRATORS

    c = INTEGRATORS[integrator].coefficients
    return c(0.0) != c(1.0)


def cases(grid: dict, tiny: bool) -> list:
    opts = {"timing": dict(grid["timing"])}
    study = grid.get("study", "stability")
    return [make_case(study, "ancf", scene_for(grid, ch, integ), opts)
            for _, _, ch in hard_cases(grid) for integ in grid["integrators"] if offered(grid, ch, integ)]


def offered(grid: dict, changes: dict, integrator: str) -> bool:
    """Whether ANCF admits the case's scene (:func:`ancf.admission.check`: an integrator the
    element refuses, a formulation a cable does not take; such a scene is refused by name)."""
    from ancf.admission import check
    from contract.errors import SceneError
    from contract.scene import scene_from_dict

    try:
        check(scene_from_dict(scene_for(grid, changes, integrator)))
    except SceneError:
        return False
    return True


def swing_time(rec: dict) -> float | None:
    """The first time the tip reaches x = 0 (the vertical), by the cubic through the four outputs
    around the crossing (its own error is of order (omega dt_out)^4 / 100, 1e-8 at 5 ms); None if
    the record never gets there."""
    import numpy as np

    t = np.array([h["t"] for h in rec.get("tip_history") or []])
    x = np.array([h["x"] for h in rec.get("tip_history") or []])
    below = np.nonzero(x <= 0)[0]
    if len(below) == 0 or below[0] < 2 or below[0] + 2 > len(t):
        return None
    i = int(below[0])
    p = np.polynomial.Polynomial.fit(t[i - 2:i + 2], x[i - 2:i + 2], 3)
    roots = [r.real for r in p.roots() if abs(r.imag) < 1e-12 and t[i - 1] <= r.real <= t[i]]
    return float(roots[0]) if roots else None


def rigid_swing_reference() -> float:
    """The paper's pendulum as a rigid bar: its time (s) from the horizontal to the vertical
    (:func:`.closed_forms.rigid_swing_time`)."""
    from .closed_forms import rigid_swing_time

    b = paper.PENDULUM
    return rigid_swing_time(b["length"], b["height"], paper.GRAVITY)


def swing_rows(rows: list[dict]) -> list[list]:
    """[case, integrator, status, swing time, closed form, relative error, verdict] of the
    near-rigid rows (:data:`SWING_TOL`)."""
    T = rigid_swing_reference()
    out = []
    for x in rows:
        if x["group"] != "stiffer" or x["same_as_base"]:
            continue
        d = x["d"]
        ts = swing_time(x["record"]) if d["status"] == "converged" else None
        err = None if ts is None else ts / T - 1
        if err is not None:
            v = "meets" if abs(err) <= SWING_TOL else "misses"
        elif d["status"] == "converged":
            v = f"not reached by t = {d['t_end']:g} s"
        else:
            v = "failed: " + str(d["reason"] or "?").split(":")[0]
        out.append([x["label"], x["integrator"], d["status"], ts, T, err, v])
    return out


def _definitions() -> str:
    from ancf.solvers.stability import SINGULAR_TOL
    return (
        "## Verdicts\n\n"
        "Static (ancf.solvers.stability, on the converged state's tangent K with the supports applied, scaled to unit "
        "diagonal: S = D^-1/2 K D^-1/2, the same signs of eigenvalues as K; eigenvalues within "
        f"SINGULAR_TOL = {SINGULAR_TOL:g} of zero are not resolved in double precision):\n\n"
        "- **stable**: no eigenvalue of S below +SINGULAR_TOL (counted by Sylvester's law of inertia); the "
        "record's lowest_eigenvalue is the margin;\n"
        "- **unstable** (indefinite): eigenvalues below -SINGULAR_TOL; their number is negative_eigenvalues; "
        "the solver perturbs along the lowest mode and descends, and the record states where it ended;\n"
        "- **singular**: the lowest eigenvalue lies within the round-off band and its mode strains nothing at "
        "the quadrature points while a full rule sees it strain (a zero-energy mode of the rule);\n"
        "- **undetermined**: the lowest eigenvalue lies within the round-off band and is not such a mode, or the "
        "eigen solve did not converge.\n\n"
        "Energy (below, dynamic runs): **holds**: max |E(t) - E(0)| within the bound (conservative settings); "
        "**no growth (dissipative)**: max (E(t) - E(0)) within the bound (rho_inf < 1); **exceeds the bound** / "
        "**growth above the bound**: otherwise; **failed**: the run did not finish (e.g. stopped by the energy "
        "guard). The rise is taken over every accepted step where the record carries energy_peak, else over "
        "the output times.")


DEFINITIONS = None   # (built on first use: it states SINGULAR_TOL from ancf.solvers.stability)


def margin_rows(ctx) -> list[list]:
    """[cell, status, verdict, negative eigenvalues, lowest, lowest / SINGULAR_TOL] of every Table 3 record."""
    from ancf.solvers.stability import SINGULAR_TOL
    from ..engine.report import verdict as run_verdict

    out = []
    for r in ctx.records("table3"):
        sc = r["scene"]
        lo = r.get("lowest_eigenvalue")
        out.append([f"{sc['ancf']['element']} `{sc['material']['formulation']}` {sc['material']['law']}",
                    r["status"], run_verdict(r), r.get("negative_eigenvalues"), lo,
                    lo / SINGULAR_TOL if lo is not None else None])
    return out


def bound_J(scene: dict) -> float:
    """1e-3 m g L / 2 of the scene (J)."""
    b, m = scene["beam"], scene["material"]
    mass = m["density"] * b["length"] * b["height"] * b["width"]
    g = abs(scene["loads"]["gravity"][1])
    return 1e-3 * mass * g * b["length"] / 2


def energy_drift(rec: dict) -> tuple[float | None, float | None]:
    """(max |E(t) - E(0)|, max E(t) - E(0)) (J): the rise over every checked step
    (``energy_peak``, every accepted step in ANCF records) where the record has it,
    never below the rise at the output times; the drift over the output times (a fall
    between them is not kept)."""
    e = [x["total"] for x in rec.get("energy") or [] if x.get("total") is not None]
    if not e:
        return None, None
    rise = max(x - e[0] for x in e)
    peak = rec.get("energy_peak") or {}
    if peak.get("rise") is not None:
        rise = max(rise, peak["rise"])
    return max(max(abs(x - e[0]) for x in e), rise), rise


def energy_lost(rec: dict, bound: float) -> float | None:
    """(E(0) - E(t_end)) / (m g L / 2) over the output times: what numerical damping took (a
    fraction; negative if E ended above E(0)); ``bound`` is 1e-3 m g L / 2."""
    e = [x["total"] for x in rec.get("energy") or [] if x.get("total") is not None]
    return (e[0] - e[-1]) / (bound / 1e-3) if e else None


def energy_checked(rec: dict) -> str:
    """Which steps the rise is taken over."""
    every = (rec.get("energy_peak") or {}).get("checked_every_steps")
    if every == 1:
        return "every step"
    return f"every {every} steps" if every else "output times"


def verdict(d: dict, drift: float | None, rise: float | None, bound: float) -> str:
    if d["status"] != "converged":
        reason = str(d["reason"] or "")
        if reason.startswith("energy-growth"):
            return "energy-growth (stopped)"
        return "failed: " + (reason.split(":")[0] if reason else "?")
    if drift is None:
        return "no energy"
    conservative = d["integrator"] in CONSERVATIVE or d["rho_inf"] == 1.0
    if conservative:
        return "holds" if drift <= bound else "exceeds the bound"
    return "no growth (dissipative)" if rise <= bound else "growth above the bound"


def rows_of(ctx) -> list[dict]:
    g = ctx.study.grid
    out, seen = [], set()      # a run (record) shown in several rows counts once: in its first row
    for group, label, ch in hard_cases(g):
        for integ in [i for i in g["integrators"] if offered(g, ch, i)]:
            c = make_case(ctx.study.name, "ancf", scene_for(g, ch, integ), {"timing": dict(g["timing"])})
            r = ctx.record_for(c)
            if r is None:
                continue
            d = describe_dynamic(r)
            drift, rise = energy_drift(r)
            bound = bound_J(r["scene"])
            lost = energy_lost(r, bound)
            med = (d["timing"] or {}).get("median_s")
            out.append({"group": group, "label": label, "changes": ch, "integrator": integ, "d": d, "drift": drift, "rise": rise,
                        "lost": lost, "bound": bound, "enforced": r.get("energy_limit"), "verdict": verdict(d, drift, rise, bound),
                        "wall": med if med is not None else d["wall_s"], "timed": med is not None,
                        "checked": energy_checked(r), "record": r,
                        "same_as_base": c.id in seen or r["case_id"] in seen})
            seen.update((c.id, r["case_id"]))
    return out


def report(ctx) -> Section:
    g = ctx.study.grid
    rows = rows_of(ctx)
    bound = rows[0]["bound"] if rows else None
    sec = Section(ctx.study.title,
                  "The bound, stated before the numbers: |E(t) - E(0)| <= 1e-3 m g L / 2"
                  + (f" = {bound:.3e} J" if bound else "") + " for the conservative settings (Newmark, discrete "
                  "gradient, generalized-alpha with rho_inf = 1); with dissipation (generalized-alpha rho_inf < 1) E "
                  "may fall but must not rise above E(0) by more than the bound. A run whose energy rises above it is "
                  "stopped with status failed, reason energy-growth: shown as such. The rise is the largest E - E(0) over every "
                  "accepted step where the record carries it (energy_peak), else over the output times "
                  f"(every {1e3 * g['energy_every']:g} ms; {1e3 * g['long_energy_every']:g} ms for the long run).")
    table = []
    for x in rows:
        d = x["d"]
        table.append([x["label"], x["integrator"] + (" (= base)" if x["same_as_base"] else ""), d["status"],
                      x["verdict"], x["drift"], x["rise"],
                      None if x["lost"] is None else 100 * x["lost"], x["checked"], x["bound"], d["steps"], d["rejected"], d["newton"],
                      x["wall"], "" if x["timed"] else "single run",
                      (str(d["reason"])[:90] if d["reason"] else "")])
    stem = ctx.study.name.replace("-", "_")
    sec.table(ctx, Table(f"{stem}_runs", ["hard case", "integrator", "status", "verdict", "max abs(E - E0) (J)",
                                       "max E - E0 (J)", "lost (% of m g L / 2)", "E checked", "bound (J)", "steps",
                                       "rejected", "Newton", "wall s", "timing", "reason"], table,
                         {4: ".2e", 5: ".2e", 6: ".3g", 8: ".2e", 12: ".3f"}),
              "Every hard case with every integrator: status, the energy verdict against the bound, the largest energy "
              "change and rise (over every step where the record keeps its energy peak, else over the output times), the "
              "energy lost by the end, E(0) - E(t_end), as a share of m g L / 2 (numerical damping where the verdict is "
              "dissipative), accepted and rejected steps, Newton iterations and wall time.")
    bad = [x for x in rows if x["verdict"] not in HOLDS and not x["same_as_base"]]
    runs = [x for x in rows if not x["same_as_base"]]    # each run once: "(= base)" rows repeat the base run
    lines = [f"- {sum(1 for x in runs if x['verdict'] in HOLDS)} of {len(runs)} distinct runs "
             "hold the bound (conservative) or do not gain energy (dissipative)"
             + (f"; the table's {len(rows) - len(runs)} rows marked (= base) repeat the base run and are not counted"
                if len(rows) > len(runs) else "") + "."]
    lines += [f"- {x['label']}, {x['integrator']}: **{x['verdict']}**"
              + (f" ({str(x['d']['reason'])[:120]})" if x["d"]["reason"] else
                 f" (max |E - E0| = {x['drift']:.2e} J)" if x["drift"] is not None else "") for x in bad]
    damped = [x for x in runs if x["verdict"] == "no growth (dissipative)" and x["lost"] is not None
              and x["lost"] > DAMPED]
    lines += [f"- {x['label']}, {x['integrator']}: no energy gained, but numerical damping took "
              f"{100 * x['lost']:.3g} % of m g L / 2 by t = {x['d']['t_end']:g} s." for x in damped]
    swings = swing_rows(rows)
    if swings:
        sec.table(ctx, Table(f"{stem}_swing", ["hard case", "integrator", "status", "swing time (s)",
                                              "rigid pendulum (s)", "relative error", "verdict"], swings,
                             {3: ".6f", 4: ".6f", 5: "+.2e"}),
                  "The near-rigid pendulum's time from the horizontal to the vertical against the rigid compound "
                  "pendulum's, K(1/sqrt 2) sqrt(I / (m g L / 2)) with I / m = L^2 / 3 + h^2 / 12 (the closed form: "
                  "studies.verification.closed_forms.rigid_swing_time). Tolerance stated before the runs: "
                  f"{SWING_TOL:g} relative, the time discretisation (omega dt)^2 = 4.2e-5 at dt = 1 ms plus the "
                  "bar's flexure under the swing's self-equilibrated transverse load (3e-6 of L), rounded up.")
        lines.append(f"- Near-rigid pendulum: {sum(1 for r in swings if r[-1] == 'meets')} of {len(swings)} runs "
                     f"swing to the vertical within {SWING_TOL:g} of the rigid pendulum's time"
                     + "".join(f"; {r[0]}, {r[1]}: {r[-1]}" for r in swings if r[-1] != "meets") + ".")
    sec.text = "\n".join(lines)
    margins = margin_rows(ctx) if ctx.study.name == "stability" else []
    if margins:
        sec.table(ctx, Table("stability_margins", ["cell (table3)", "status", "verdict", "negative eigenvalues",
                                                   "lowest scaled eigenvalue", "margin / SINGULAR_TOL"], margins,
                             {4: ".3e", 5: ".3g"}),
                  "The static verdict of every Table 3 cell with its margin: the lowest eigenvalue of the "
                  "Jacobi-scaled constrained tangent (record key lowest_eigenvalue; '-' in records written before "
                  "the key existed) and its ratio to the round-off band SINGULAR_TOL.")
    global DEFINITIONS
    DEFINITIONS = DEFINITIONS or _definitions()
    name = ctx.study.name
    (ctx.out / f"{stem}.md").write_text(
        f"# {ctx.study.title}\n\n{DEFINITIONS}\n\n{sec.intro}\n\n{(ctx.out / f'{stem}_runs.md').read_text()}\n"
        f"{sec.text}\n\n"
        + (f"## The near-rigid pendulum's swing time\n\n{(ctx.out / f'{stem}_swing.md').read_text()}\n" if swings else "")
        + (f"## Static verdicts and their margins\n\n{(ctx.out / 'stability_margins.md').read_text()}\n" if margins else "")
        + f"Generated by `python -m studies run {name}` from the records in `data/{name}.jsonl`"
        + (" and `data/table3.jsonl`" if margins else "") + f" (CSV: [{stem}_runs.csv]({stem}_runs.csv)"
        + (", [stability_margins.csv](stability_margins.csv)" if margins else "") + ").\n")
    sec.text += f"\n- The hard-case report as one page: [{stem}.md]({stem}.md)."
    return sec


def gold_values(ctx) -> dict:
    out = {}
    for x in rows_of(ctx):
        if x["verdict"] in ("holds", "no growth (dissipative)") and not x["same_as_base"]:
            d = x["d"]
            key = "/".join([ctx.study.name, x["group"], x["integrator"]]
                           + [f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}" for k, v in sorted(x["changes"].items())])
            out.update(gold_tips(key, d, last_only=True))
    return out


def audit(ctx) -> list[str]:
    """The count line of the findings against the runs table: 'n of m distinct runs'
    recounted from stability_runs.csv (rows marked '(= ' repeat an earlier run)."""
    import csv
    import re

    stem = ctx.study.name.replace("-", "_")
    table, page = ctx.out / f"{stem}_runs.csv", ctx.out / f"{stem}.md"
    if not (table.exists() and page.exists()):
        return []
    rows = [r for r in csv.DictReader(open(table)) if "(= " not in r["integrator"]]
    hold = sum(1 for r in rows if r["verdict"] in HOLDS)
    for i, line in enumerate(page.read_text().splitlines(), start=1):
        m = re.match(r"- (\d+) of (\d+) distinct runs", line)
        if m and (int(m[1]), int(m[2])) != (hold, len(rows)):
            return [f"{stem}.md:{i}: says {m[1]} of {m[2]}, the runs table gives {hold} of {len(rows)}"]
    return []
