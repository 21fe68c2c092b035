"""A case: one solver run of one scene, as pure data with an identity.

A :class:`Case` is frozen and hashable: (study, solver, scene, options), the scene and
the options held as canonical JSON. Its :attr:`Case.id` is a hash of

- the canonical scene JSON and the options (a ``timing`` option changes what is measured,
  and so does how its runs are warmed, :func:`studies.engine.worker.execute_timed`;
  ``imports``, the modules a worker imports to register a user's element, does not: the
  element itself counts, below);
- the solver's fingerprint (:mod:`studies.engine.fingerprint`): the normalised code the
  solver runs (comments and docstrings do not count) and the versions of the packages that
  code imports, per continuum backend;
- for a scene that names a user's element or law (one not built in), that element's
  specification and the code of the law's module, so that an edit of either recomputes
  and an unrelated import does not,

so that a record can be reused exactly while none of these changed. The study name is
not part of the id: the records of each study live in their own file.
"""
from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any, Mapping

from .solvers import SOLVERS, get_solver

# options that say how to run a case, not what it is: left out of its identity
TRANSPORT = ("imports",)


def canonical(obj: Any) -> str:
    """The canonical JSON of ``obj``: sorted keys, no spaces, tuples as lists."""
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), allow_nan=False)


@dataclass(frozen=True)
class Case:
    study: str
    solver: str         # a key of studies.engine.solvers.SOLVERS
    scene_json: str     # canonical JSON of the scene dict (contract.scene format, SI)
    options_json: str   # canonical JSON of the options dict (e.g. {"timing": {...}})
    # the id, fixed where the case is made and carried to any worker with the case: a
    # worker never re-derives it from sources that may have changed since (see
    # :meth:`Case.sources_changed`)
    id: str = field(default="", compare=False)
    # the module that registered the solver (how to run the case, not what it is): a worker
    # imports it before it looks the solver up (studies.engine.solvers.get_solver)
    solver_module: str | None = field(default=None, compare=False)

    def __post_init__(self):
        if not self.id:
            object.__setattr__(self, "id", case_id(self.solver, self.scene_json, self.options_json))

    def sources_changed(self) -> bool:
        """Whether the solver's sources (or versions) differ from those the id was made
        with: a record computed now would not be what the id names."""
        return _fresh_id(self.solver, self.scene_json, self.options_json) != self.id

    @property
    def scene(self) -> dict:
        return json.loads(self.scene_json)

    @property
    def options(self) -> dict:
        return json.loads(self.options_json)

    @property
    def timing(self) -> dict | None:
        """The ``timing`` option ({"repeats": N, "budget_s": s}) or None."""
        return self.options.get("timing")

    @property
    def name(self) -> str:
        return self.scene["name"]

    def to_dict(self) -> dict:
        return {"id": self.id, "study": self.study, "solver": self.solver,
                "name": self.name, "options": self.options}


def user_definitions(scene: Mapping) -> dict:
    """What a scene takes from a user's module (empty for built-in ones): the element's
    specification as plain data (its free-text reference and its tags left out), and the normalised
    code of the module that defines the law's energy (a law is code, an element data)."""
    import dataclasses

    out = {}
    element = (scene.get("ancf") or {}).get("element")
    from ancf.elements import BUILTIN, ELEMENTS
    if isinstance(element, str) and element not in BUILTIN and element in ELEMENTS:
        spec = dataclasses.asdict(ELEMENTS[element])
        spec.pop("reference", None)
        spec.pop("tags", None)          # which studies take it, not what it computes
        out["element_spec"] = spec
    law = (scene.get("material") or {}).get("law")
    from mechanics.laws import BUILTIN as BUILTIN_LAWS, LAWS
    if isinstance(law, str) and law not in BUILTIN_LAWS and law in LAWS:
        from .fingerprint import fingerprint
        out["law_code"] = fingerprint((LAWS[law].energy.__module__,))["code"]
    return out


def solver_fingerprint(solver: str, scene: dict, options: dict) -> dict:
    """{"code", "packages"} of what the solver runs for this scene
    (:meth:`studies.engine.solvers.Solver.fingerprint`)."""
    return get_solver(solver).fingerprint(scene, options)


def identity(solver: str, scene: dict, options: dict) -> dict:
    """What a case's id is a hash of (see the module doc)."""
    fp = solver_fingerprint(solver, scene, options)
    ident = {"solver": solver, "scene": scene,
             "options": {k: v for k, v in options.items() if k not in TRANSPORT},
             "code": fp["code"], "packages": fp["packages"]}
    if "timing" in options and get_solver(solver).warm is not None:
        ident["warmup"] = "compiled code loaded by a two-element copy"   # how a timed run is warmed
    ident.update(user_definitions(scene))
    return ident


def _fresh_id(solver: str, scene_json: str, options_json: str) -> str:
    ident = identity(solver, json.loads(scene_json), json.loads(options_json))
    return hashlib.sha256(canonical(ident).encode()).hexdigest()[:20]


@lru_cache(maxsize=None)
def _memo_id(solver_object, solver: str, scene_json: str, options_json: str) -> str:
    return _fresh_id(solver, scene_json, options_json)


def case_id(solver: str, scene_json: str, options_json: str) -> str:
    """The case's id, its sources read once per process; the memo is keyed by the solver
    object registered now too, so that an id made while a solver was replaced (a test's
    refusing stand-in) is not the id of the real solver's case."""
    return _memo_id(get_solver(solver), solver, scene_json, options_json)


def packages(case: "Case") -> dict:
    """{package: version} the case's solver uses (the record's ``versions``)."""
    return solver_fingerprint(case.solver, case.scene, case.options)["packages"]


def user_modules(scene: Mapping) -> list[str]:
    """The modules that registered the scene's element and law where they are not built in
    (what a worker imports to have them: the case's ``imports``); a script's (``__main__``)
    cannot be imported and is left out."""
    from ancf.elements import BUILTIN, ELEMENTS
    from mechanics.laws import BUILTIN as BUILTIN_LAWS, LAWS

    out = []
    for name, registry, builtin in (((scene.get("ancf") or {}).get("element"), ELEMENTS, BUILTIN),
                                    ((scene.get("material") or {}).get("law"), LAWS, BUILTIN_LAWS)):
        origin = registry.origin.get(name) if isinstance(name, str) and name not in builtin else None
        if origin and origin != "__main__":
            out.append(origin)
    return out


def make_case(study: str, solver: str, scene: Mapping, options: Mapping | None = None) -> Case:
    """A case from plain data; the solver name and the scene are checked here (an
    unknown solver fails with the list of valid ones; a bad scene with a SceneError). A
    scene naming a user's element or law carries the modules that register them in its
    options' ``imports`` (:func:`user_modules`: how it is run, not what it is)."""
    get_solver(solver).check(dict(scene))
    options = dict(options or {})
    if user := user_modules(scene):
        options["imports"] = sorted(set(options.get("imports", ())) | set(user))
    return Case(study, solver, canonical(scene), canonical(options), solver_module=SOLVERS.origin[solver])


__all__ = ["Case", "make_case", "case_id", "packages", "canonical", "SOLVERS"]
