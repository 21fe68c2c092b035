"""The compiled code a scene needs, loaded (or compiled) before its run and timed apart.

numba compiles the element loops, the static Newton loop and the step loop on their
first call, or loads them from its disk cache (:mod:`ancf.compiled_cache`). The first
call is therefore not the solve's cost: :func:`load` runs a tiny copy of the scene
(:func:`tiny`: the same element, law, formulation, rule, supports, loads, analysis and
integrator on two elements, two time steps) so that every compiled function the scene's
run calls is in memory before it starts; ``ancf run`` prints and records that time as
``load_s``, apart from the solve.

:func:`warm` does this for every shipped scene and for the variants the tests and the
studies run (:data:`VARIANTS`): the set-up (``tools/setup.sh``, ``ancf warm``) calls it
once per clone, so that a user's first ``ancf run`` loads compiled code from the cache
instead of compiling it. Nothing here is imported by the solver itself.
"""
from __future__ import annotations

import sys
import time
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

from contract.scene import Scene, load_scene, scene_from_dict

from .admission import refused_integrators
from .elements import ELEMENTS

if TYPE_CHECKING:
    from .build import Plan

ROOT = Path(__file__).resolve().parent.parent
SCENES = ROOT / "scenes"


def tiny(scene: Scene) -> Scene:
    """The scene on two elements and, for a dynamic one, two steps with no output times
    and no wall-time limit (a dynamic run still checks its energy, as the scene does)."""
    a = scene.analysis
    if a.kind == "dynamic":
        a = replace(a, t_end=2 * a.dt, output_times=None, wall_time=None)
    else:
        a = replace(a, wall_time=None)
    return replace(scene, ancf=replace(scene.ancf, elements=min(2, scene.ancf.elements)), analysis=a)


def compiled_signatures() -> int:
    """How many compiled specialisations the ANCF solver's modules hold in memory."""
    from numba.core.registry import CPUDispatcher

    n = 0
    for name, mod in list(sys.modules.items()):
        if mod is None or not name.startswith(("ancf.", "mechanics.")):
            continue
        for v in vars(mod).values():
            if isinstance(v, CPUDispatcher):
                n += len(v.signatures)
    return n


def load(p: Plan) -> float:
    """Load (or compile) the compiled code the planned scene runs, and take the one-off
    checks its record carries (the rank tests of a rule the scene chose,
    :attr:`ancf.build.Plan.rule_warnings`, cached per element, rule and l_e / h: about a
    second, which a timed run's first sample would otherwise hold); return the wall time
    it took."""
    from .simulation import run_scene

    t0 = time.perf_counter()
    run_scene(tiny(p.scene))
    p.rule_warnings
    return time.perf_counter() - t0


# Beside the shipped scenes, what the studies and tests run: each integrator and Newton
# variant of the step loop, and the elements whose kernels differ (a pressure field, an
# assumed strain, a cable), each in a penalised and a plane-stress formulation where the
# element runs it (a cable: plane stress, no discrete gradient).
VARIANTS = (
    {"integrator": "generalized-alpha", "newton": "chord"},
    {"integrator": "generalized-alpha", "newton": "full"},
    {"integrator": "generalized-alpha", "newton": "modified"},
    {"integrator": "newmark", "newton": "chord"},
    {"integrator": "discrete-gradient"},
)


def kernel_representatives() -> list[str]:
    """One built-in element of each kind of compiled kernel, from the registry: the first of
    each (kinematics, pressure field, assumed strain) in registration order (every element of
    a kind runs the same compiled specialisations)."""
    seen = {}
    for name, el in ELEMENTS.items():
        if name not in ELEMENTS.builtin:
            continue
        seen.setdefault((el.kinematics, bool(el.pressure), bool(el.assumed)), name)
    return list(seen.values())


def variants() -> list[Scene]:
    """The scenes :func:`warm` loads besides the shipped ones."""
    from contract import paper

    out = []
    for element in kernel_representatives():
        el = ELEMENTS[element]
        for form in ("plane-stress", "plane-strain"):
            if not el.family.runs(form):
                continue                           # its kinematics refuses it (a cable: plane stress alone)
            out.append(scene_from_dict(paper.cantilever_scene("yeoh", form, element, 2, quadrature=None)))
            for v in VARIANTS:
                if v["integrator"] in refused_integrators(el):
                    continue                       # the element refuses it (an assumed strain, a cable)
                d = paper.pendulum_scene("yeoh", form, 1e-3, element, 2, t_end=2e-3, **v)
                out.append(scene_from_dict(d))
    return out


def shipped() -> list[Scene]:
    """The shipped scenes that ANCF runs (those with an [ancf] table)."""
    out = []
    for p in sorted(SCENES.glob("*.toml")):
        s = load_scene(p)
        if s.ancf is not None:
            out.append(s)
    return out


def prune() -> list[Path]:
    """Remove the caches of earlier versions of the code compiled by this toolchain
    (``numba-<digest>-<toolchain>`` beside the current one, 25 MB each; another venv's
    stay) and the digest memos of earlier sources (:func:`ancf.compiled_cache.source_digest`);
    return the caches removed."""
    import re
    import shutil

    from .compiled_cache import PACKAGE, cache_dir, toolchain

    current = cache_dir()
    mine = re.compile(rf"numba-[0-9a-f]{{16}}(-{toolchain()})?$")    # (no suffix: before the toolchain key)
    gone = [d for d in current.parent.glob("numba-*") if d.is_dir() and d != current and mine.match(d.name)]
    for d in gone:
        shutil.rmtree(d, ignore_errors=True)
    memos = sorted((PACKAGE / "__pycache__").glob("digest-*"), key=lambda p: p.stat().st_mtime)
    for p in memos[:-1]:                     # the newest is the current sources'
        p.unlink(missing_ok=True)
    return gone


def warm(log=print) -> float:
    """Load or compile what every shipped scene and every variant runs (and remove the
    caches of earlier code); the time taken."""
    from .build import plan
    from .compiled_cache import cache_dir

    t0 = time.perf_counter()
    gone = prune()
    for s in shipped() + variants():
        load(plan(s))
    dt = time.perf_counter() - t0
    log(f"ancf: compiled code ready in {cache_dir()} ({dt:.1f} s"
        + (f"; {len(gone)} cache(s) of earlier code removed)" if gone else ")"))
    return dt
