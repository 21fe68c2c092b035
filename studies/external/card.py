"""An external solver's element card: the card's sections that need only runs.

``python -m studies card --solver DECLARATION [ELEMENT ...]`` runs the element card's
solver cases (:func:`studies.design.card_cases.cases`) on a declared solver
(:mod:`.protocol`) and renders, from its records alone:

4. static convergence against the converged continuum, 5. volumetric locking (plane strain
as the penalty grows) and shear locking (slender beams against Timoshenko's beam), 6. the
pendulum against the continuum, 7. cost (the serial median of whole runs: a command's
runs include its process start, which is what a user of it waits for), 8. the stability
verdicts it reports, 9. the slenderness sweep, and the benchmark suite's verdicts where
``studies external DECLARATION benchmarks`` left records in the same directory.

Left out, with the reason on the card: the contract checks, the rank tests, conformity and
the clamp's probe, which read an element's basis, forces and tangent, not its runs.

The cases are those of a planar section element's card (both formulations, the locking
sweep) plus the slenderness sweep of a cable's, so that every run-only section has its
cases; what the declaration does not take is skipped and named. A solver with an element of
its own (``solver.element``) has one card, ``<solver>-<element>``; one that runs the
element a scene names gets a card per element named on the command line.
"""
from __future__ import annotations

from pathlib import Path

from ..design.card_cases import SLENDERNESS, SLENDERNESS_TINY, cases, grid_for, slenderness_scene, slug
from ..engine.case import make_case
from ..engine.scheduler import dry_run, run_cases
from ..engine.store import store_for
from .declaration import Declaration
from .protocol import ExternalSolver, register_external, retarget
from .verdicts import benchmark_rows, cause_of_miss, not_run_lines

# the built-in element whose card's cases are the template (a planar section element: its
# card has every run-only section but the cable's sweep, which is added)
TEMPLATE = "HB2n-12"
NEEDS_INTERNALS = ("1. contract checks (force and tangent against finite differences, rigid motions, the patch "
                   "test, exact mass), 2. rank tests, 3. conformity and the clamp's probe: they read the element's "
                   "basis, forces and tangent, which an external solver does not expose")


def card_name(decl: Declaration, element: str) -> str:
    """The card's file stem: ``<solver>-<element>``."""
    return slug(f"{decl.name}-{element}")


def card_cases(solver: ExternalSolver, element: str, tiny: bool = False):
    """(the card's cases on ``solver`` running ``element``, [(case name, why skipped)])."""
    template = list(cases(TEMPLATE, tiny))
    sweep = SLENDERNESS_TINY if tiny else SLENDERNESS
    template += [make_case(f"card-{TEMPLATE}", "ancf", slenderness_scene(law, ratio, TEMPLATE, n))
                 for law in grid_for(tiny)["laws"] for ratio in sweep["ratios"] for n in sweep["counts"]]
    return retarget(template, solver, element=element, study=f"card-{element}")


def elements_of(decl: Declaration, names: list[str]) -> list[str]:
    """The elements the cards are of: the solver's own, or the names given (at least one)."""
    if decl.element:
        if names and names != [decl.element]:
            raise ValueError(f"card --solver: {decl.name} runs its own element {decl.element!r} "
                             f"(solver.element); name no other ({', '.join(names)})")
        return [decl.element]
    if not names:
        raise ValueError(f"card --solver: {decl.name} runs the element a scene names (no solver.element): "
                         "name the elements to card")
    return names


def run_external_cards(paths, names: list[str], out: Path, tiny: bool = False, force: bool = False,
                       dry: bool = False, log=print) -> list[Path]:
    """Runs (or reuses) each card's cases on each declared solver (``paths``: one declaration
    or several), one after another in this process (as :func:`.protocol.run_study`), then
    renders every card, ``<out>/cards/<solver>-<element>.md`` (after all runs: each card's
    cost figure draws the others of ``out``)."""
    made = []
    for path in [paths] if isinstance(paths, (str, Path)) else paths:
        solver = register_external(path)
        decl = solver.declaration
        for element in elements_of(decl, names):
            name = card_name(decl, element)
            cs, skipped = card_cases(solver, element, tiny)
            store = store_for(out, f"card-{name}")
            if dry:
                s = dry_run(f"card-{name}", cs, store, force)
                log(f"card {name}: {s.cases} cases, {s.reused} reused, {s.computed} to compute; {len(skipped)} "
                    "skipped (not declared) (dry run)")
                continue
            s = run_cases(f"card-{name}", cs, store, "serial", 1, force=force, progress=False,
                          timeout_s=decl.wall_time + 30.0)
            have = store.read()       # reused runs that failed count too: the card shows them
            failed = sum(have[c.id]["status"] != "converged" for c in cs if c.id in have)
            log(f"card {name}: {s.cases} cases, {s.reused} reused, {s.computed} computed, {failed} without a "
                f"result; {len(skipped)} skipped (not declared)")
            made.append((decl, element))
    return [render(decl, element, out, tiny) for decl, element in made]


def _causes(recs: list[dict], decl: Declaration) -> list[str]:
    """Each kind of run (its name's first word) that failed, with the cause the declaration's
    ``[causes]`` gives for it, as measured ("cause not found" without one)."""
    failed: dict = {}
    for r in recs:
        if r["status"] != "converged":
            failed.setdefault(r["case"]["name"].split("-")[0], []).append(r)
    if not failed:
        return []
    return ([f"Why runs failed (`[causes]` of `{decl.path.name}`, as measured):", ""]
            + [f"- {kind} ({len(rs)} runs): {decl.causes.get(kind) or 'cause not found'}"
               for kind, rs in sorted(failed.items())] + [""])


def _benchmarks(out: Path, decl: Declaration, tiny: bool) -> list[str]:
    lines = ["## 10. The benchmark suite", ""]
    if not store_for(out, f"benchmarks@{decl.name}").read():
        return lines + [f"Not run here: `python -m studies external {decl.path.name} benchmarks --out {out}` "
                        "runs it and adds its verdicts to this card.", ""]
    rows = benchmark_rows(out, decl, tiny)
    misses = [r for r in rows if r.verdict != "pass"]
    lines += [f"{len(rows) - len(misses)} of {len(rows)} cases it ran pass (every case, its reference and "
              f"tolerance: `benchmarks@{decl.name}.md` beside the cards)."]
    if misses:
        lines += ["", "Its misses:", "", "| case | error | tolerance | verdict |", "|---|---|---|---|"]
        lines += [f"| {r.case} | {'-' if r.error is None else format(r.error, '.2e')} | {r.tolerance:.2g} | "
                  f"{r.verdict} |" for r in misses]
        causes = {}
        for r in misses:     # one cause per kind of case, as the declaration gives it
            causes.setdefault(r.case.split()[0], cause_of_miss(decl, r.case, r.cause))
        lines += ["", "Why, per kind of case (`[causes]` of the declaration, as measured):", ""]
        lines += [f"- {kind}: {why}" for kind, why in causes.items()]
    return lines + [""]


def render(decl: Declaration, element: str, out: Path, tiny: bool = False) -> Path:
    """The card from the records in ``out``/data alone (no run; what it skipped comes from
    the declaration)."""
    from ..common.gold import gold_references
    from ..design.card_cable import _sweep
    from ..design.card_locking import _locking, _shear_locking
    from ..design.card_records import _is_locking
    from ..design.card_report import FEM_STATIC, _convergence, _cost, _pendulum, _stability

    out = Path(out)
    cards = out / "cards"
    cards.mkdir(parents=True, exist_ok=True)
    name = card_name(decl, element)
    solver = register_external(decl.path)
    have = store_for(out, f"card-{name}").read()
    cs, skipped = card_cases(solver, element, tiny)
    recs = [have[c.id] for c in cs if c.id in have]
    refs = gold_references(FEM_STATIC)
    laws = grid_for(tiny)["laws"]
    strain = [why for case, why in skipped if "plane-strain" in case]
    swings = [why for case, why in skipped if case.startswith("pendulum-")]
    dynamic = any(r["scene"]["analysis"]["kind"] == "dynamic" for r in recs)
    head = [f"# Element report card: {element} in {decl.name} {decl.version}", "",
            f"Generated by `python -m studies card --solver {decl.path.name}"
            + ("" if decl.element else f" {element}") + ("` (tiny grid)." if tiny else "`.")
            + f" The card's runs on the external solver `{decl.name}` (its declaration `{decl.path.name}`), "
            f"judged as an element's card judges them; {len(recs)} solver runs, {len(skipped)} of the card's "
            "runs outside its declaration.", "",
            "## Left out", "", f"- {NEEDS_INTERNALS}.", *not_run_lines(skipped, "runs"), ""]
    text = (head + _convergence(recs, refs, cards, name)
            + _locking(recs, refs, strain[0] if strain and not any(_is_locking(r) for r in recs) else None)
            + _shear_locking(recs)
            + (_pendulum(recs) if dynamic or not swings else
               ["## 6. Pendulum against the continuum", "", f"Not run: {swings[0]}.", ""])
            + _cost(name, "yeoh" if "yeoh" in laws else laws[0], out, cards, name) + _stability(recs) + _causes(recs, decl)
            + _sweep(recs, cards, name, tiny) + _benchmarks(out, decl, tiny))
    path = cards / f"{name}.md"
    path.write_text("\n".join(text) + "\n")
    return path
