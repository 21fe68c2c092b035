"""The element report card: everything the harness knows, run on one element.

``python -m studies card NAME [NAME ...] [--import MODULE] [--tiny] [--out DIR]`` (``paper``
names the four paper elements) writes ``<out>/cards/<element>.md`` with its figures:

1. **contract checks** (:mod:`ancf.checks.element`): nodality, reference state, force and tangent
   Taylor tests and rigid motions in the three formulations, the patch test, exact mass;
2. **rank tests** (:mod:`ancf.checks.rank`) of four rules over l_e / h = 10 ... 0.01, and the
   element's default rule at each;
3. **conformity**: the jump of r and r_y across a shared face, and the patch-test
   inconsistency against l_e / h;
4. **static convergence** against the converged continuum (tests/gold/fem_cantilever.json)
   for three laws in plane stress and plane strain, default quadrature: observed order
   (successive differences) and plateau (the finest mesh against the continuum);
5. **locking**: plane strain with penalty alpha = 10 ... 1e5 C10 against the exactly
   incompressible continuum; and **shear locking**: a slender cantilever under a uniform
   load in the linear regime against beam theory (Timoshenko), at fixed element counts
   for three slendernesses L / h (a locking-free element's error does not depend on it);
6. **pendulum** error against the continuum gold (tests/gold/fem_pendulum.json);
7. **cost**: serial warm timings of the plane-stress refinement, beside every other
   element that has a card in the same output directory;
8. **stability**: the inertia verdict of every static equilibrium above;
9. **slenderness** (a cable, ``kinematics = "cable"``): the paper's cantilever at L / h = 140
   ... 4 under the paper's load parameter against the converged continuum
   (tests/gold/fem_slenderness.json): where the centre-line model stops being within 1 %,
   0.3 %, 0.1 %.

What an element cannot run is left out with the reason on its card (a cable: the ``paper``
and ``plane-strain`` formulations, so the volumetric-locking sweep).

Parts 4 to 9 are solver runs: cases in the store ``<out>/data/card-<element>.jsonl``
(reused while nothing they depend on changed, like every study). Parts 1 to 3 are
measured in this process and kept in ``<out>/data/card-<element>-checks.json``, keyed by
the element's definition and the ancf source hash. The card itself is rendered from these
two files only (:mod:`studies.design.card_report`). A user's element: ``--import mymodule``
imports the module (which registers it) here and in every worker.
"""
from __future__ import annotations

import json
from pathlib import Path

from ..engine.audit import register_prebuild
from ..engine.scheduler import dry_run, run_cases
from ..engine.store import store_for
from ..engine.verify import register_case_source
from .card_cases import (GRID, LAWS, SLENDER, SLENDERNESS, SLENDERNESS_TINY, TINY,  # noqa: F401
                         beam_theory, cases, checks_current, checks_path, checks_record, checks_source, clamp_probe,
                         element_imports, formulations_of, grid_for, import_modules, measure_checks,
                         section_model, slender_scene, slender_strains, slenderness_scene, slug)


def run_cards(elements: list[str], out: Path, tiny: bool = False, imports=(), workers: int = 2,
              progress: bool = True, force: bool = False, log=print, dry: bool = False) -> list[Path]:
    """Runs (or reuses) every named element's cases and checks, then renders every card.
    ``dry``: say per card how many runs would be reused and computed and whether its checks
    record is current; run and render nothing."""
    from ancf.elements import get_element
    from .card_report import render

    import_modules(imports)
    for el in elements:
        get_element(el)                                  # an unknown name fails here, with the list
    if dry:
        for el in elements:
            s = dry_run(f"card-{el}", cases(el, tiny), store_for(out, f"card-{slug(el)}"), force)
            log(f"card {el}: {s.cases} cases, {s.reused} reused, {s.computed} to compute, checks "
                f"{'current' if checks_current(el, out, tiny) and not force else 'to measure'} (dry run)")
        return []
    for el in elements:
        cs = cases(el, tiny)
        s = run_cases(f"card-{el}", cs, store_for(out, f"card-{slug(el)}"), None, workers,
                      force=force, progress=progress)
        log(f"card {el}: {s.cases} cases, {s.reused} reused, {s.computed} computed, {s.failed} failed, "
            f"{s.seconds:.1f} s")
        checks_record(el, out, tiny, force)
    from ..engine import stamp
    if stamp.current(out):
        log("cards: as the last full audit stamped them (records, report code and every card unchanged); "
            "not rendered again")
        return [Path(out) / "cards" / f"{slug(el)}.md" for el in elements]
    paths = [render(el, out, tiny) for el in elements]
    # every other card's cost figure draws these elements' runs: rendered again with them
    # (but a card whose cases have changed since its runs: its own `studies card` redoes it)
    stale: list[str] = []
    render_recorded(out, skip=elements, stale=stale)
    for el in stale:
        log(f"card {el}: no runs match its cases (they changed since its runs); not rendered again here, "
            f"`studies card {el}` runs and renders it")
    if (Path(out) / "README.md").exists():   # link the cards from the results page
        from ..engine.pipeline import build_reports
        build_reports(Path(out), tiny, log)
    return paths


def recorded_cards(out: Path, stale: list | None = None) -> list[tuple[str, bool]]:
    """(element, tiny) of every card whose records are in ``out``/data: the element and
    grid from its checks record; a user's element is registered by importing the module
    its runs name (their ``imports`` option). A card none of whose cases has a run
    (stale: its cases changed, or its module is gone) raises LookupError, or, given a
    ``stale`` list, is appended to it and left out."""
    from contract.errors import SceneError

    found = []
    for path in sorted((Path(out) / "data").glob("card-*-checks.json")):
        chk = json.loads(path.read_text())
        element, tiny = chk["element"], bool(chk["tiny"])
        have = store_for(out, f"card-{slug(element)}").read()
        named = sorted({m for r in have.values() for m in (r.get("case", {}).get("options") or {}).get("imports") or ()})
        try:
            import_modules(named)
            held = sum(c.id in have for c in cases(element, tiny))
        except (ImportError, SceneError, ValueError):
            held = 0
        if not held:
            if stale is not None:
                stale.append(element)
                continue
            raise LookupError(f"card {element}: no runs of it in {path.parent} match its cases with the modules "
                              f"its records name ({', '.join(named) or 'none'}; one must import and register "
                              "the element)")
        found.append((element, tiny))
    return found


def render_recorded(out: Path, skip=(), stale: list | None = None) -> list[Path]:
    """Every card of ``out`` (but those in ``skip``) rendered again from its records alone
    (no solver runs; the audit's route: ``studies audit`` compares these with the
    committed cards); ``stale``: see :func:`recorded_cards`."""
    from .card_report import render

    return [render(element, out, tiny) for element, tiny in recorded_cards(out, stale) if element not in skip]


def _recorded_cases(reports: Path) -> dict:
    """{store name: {case id: case}} of every card recorded under ``reports`` (what verify draws from)."""
    return {f"card-{slug(element)}": {c.id: c for c in cases(element, tiny)}
            for element, tiny in recorded_cards(reports, stale=[])}


# the cards' records and pages, known to the engine's audit and verify
def render_for_audit(out: Path) -> list[Path]:
    """The audit's hook: every card rendered again from its records; cards whose records are
    not of today's code (no run matches a case) are named in one LookupError, after the
    others are rendered, with the command that recomputes them."""
    stale: list = []
    paths = render_recorded(out, stale=stale)
    if stale:
        raise LookupError(f"the cards of {', '.join(stale)} have no records of today's code (no run matches a "
                          f"case): recompute them with `python -m studies card {' '.join(stale)}` (with the --import "
                          "of a user's element)")
    return paths


register_prebuild("cards", render_for_audit)
register_case_source("cards", _recorded_cases)
