"""Any solver through the harness: an external solver, declared in one TOML file
(:mod:`.declaration`), becomes an engine solver (:class:`ExternalSolver`), and any
study's cases can be run on it (:func:`retarget`, :func:`run_study`).

A run writes the case's scene to a file, runs the declared command (or calls the declared
Python function) and reads the record it wrote. Nothing but a record that passes the
schema's check (:func:`contract.record_schema.problems`) is a result: a command that
exits non-zero, runs past its wall time (it is killed), writes no record, a file that is
not JSON, or a record with a bad key ends the case with status ``failed`` and the reason,
as for the harness's own solvers. The harness's own keys (``solver``, ``scene``) are set
to what it ran; the solver's other keys are kept.

A record is reused while its case and the solver's *fingerprint* are unchanged: the
declaration as parsed (comments and its ``[causes]`` do not count), the declared version, the
adapter's files (Python files by their normalised statements, :mod:`contract.source`; others byte for
byte) and, for a Python entry point, the normalised code of its module and what it
imports (:mod:`studies.engine.fingerprint`).
"""
from __future__ import annotations

import hashlib
import json
import os
import signal
import subprocess
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from contract.record import new_record
from contract.record_schema import problems, read
from contract.source import normalised

from ..engine import fingerprint as fp
from ..engine.case import Case, canonical, make_case
from ..engine.solvers import SOLVERS, Solver
from .declaration import Declaration, load_declaration, unsupported

STDERR_TAIL = 600     # characters of a failed command's error output kept in the reason


@dataclass(frozen=True)
class ExternalSolver(Solver):
    declaration: Declaration | None = None

    def fingerprint(self, scene: dict, options: dict | None = None) -> dict:
        d = self.declaration
        what_runs = {k: v for k, v in d.text.items() if k != "causes"}      # the causes explain, not run
        h = hashlib.sha256(canonical(what_runs).encode() + b"\0" + d.version.encode())
        for a in d.adapter:
            text = a.read_bytes()
            h.update(b"\0" + (normalised(text).encode() if a.suffix == ".py" else text))
        packages = {d.name: d.version}
        if d.python:
            inner = fp.fingerprint((d.python.split(":")[0],))
            h.update(b"\0" + inner["code"].encode())
            packages.update(inner["packages"])
        return {"code": h.hexdigest(), "packages": packages}


def failed(decl: Declaration, scene: dict, reason: str) -> dict:
    rec = new_record(decl.name, scene)
    rec["reason"] = reason
    return rec


def _scene_file(decl: Declaration, scene: dict, folder: Path) -> Path:
    if decl.scene_format == "json":
        path = folder / "scene.json"
        path.write_text(json.dumps(scene, indent=1, allow_nan=False))
    else:
        from reference_fem.launch import scene_toml

        path = folder / "scene.toml"
        path.write_text(scene_toml(scene))
    return path


def _checked(decl: Declaration, scene: dict, rec: dict | None, found: list[str]) -> dict:
    """The solver's record if the schema's check found nothing, else a failed record naming
    the first problems."""
    if found:
        return failed(decl, scene, f"{decl.name}: malformed record: {'; '.join(found[:5])}")
    return rec


def _tail(text: str) -> str:
    text = " ".join(text.split())
    return text if len(text) <= STDERR_TAIL else "..." + text[-STDERR_TAIL:]


def _environment() -> dict:
    """The environment a command runs in: this one without the harness's own Python set-up
    (its venv, its path), so that a solver with a Python of its own runs as it would alone."""
    return {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV", "PYTHONHOME")}


def _run_command(decl: Declaration, scene: dict) -> dict:
    with tempfile.TemporaryDirectory(prefix=f"harness-{decl.name}-") as tmp:
        folder = Path(tmp)
        scene_path, out = _scene_file(decl, scene, folder), folder / "record.json"
        argv = [c.replace("{scene}", str(scene_path)).replace("{out}", str(out)) for c in decl.command]
        t0 = time.perf_counter()
        try:
            p = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=folder,
                                 start_new_session=True, env=_environment())
        except OSError as e:
            return failed(decl, scene, f"{decl.name}: the command could not start ({e})")
        try:
            _, err = p.communicate(timeout=decl.wall_time)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)           # the command and whatever it started
            p.communicate()
            return failed(decl, scene, f"{decl.name}: stopped past its wall time of {decl.wall_time:g} s "
                                       "(solver.wall_time)")
        wall = time.perf_counter() - t0
        if p.returncode != 0:
            return failed(decl, scene, f"{decl.name}: the command exited with status {p.returncode}: "
                                       f"{_tail(err) or 'no error output'}")
        rec = _checked(decl, scene, *read(out))
        rec.setdefault("process_s", wall)
        return rec


def _run_python(decl: Declaration, scene: dict) -> dict:
    import importlib

    module, function = decl.python.split(":")
    rec = getattr(importlib.import_module(module), function)(json.loads(json.dumps(scene)))
    try:
        rec = json.loads(json.dumps(rec, allow_nan=False))
    except (TypeError, ValueError) as e:
        return failed(decl, scene, f"{decl.name}: malformed record: not JSON ({e})")
    return _checked(decl, scene, rec, problems(rec))


def _runner(decl: Declaration):
    def run(scene: dict) -> dict:
        rec = (_run_command if decl.command else _run_python)(decl, scene)
        rec["solver"], rec["scene"] = decl.name, scene
        return rec
    return run


def _checker(decl: Declaration):
    from contract.errors import SceneError

    def check(scene: dict) -> None:
        why = unsupported(decl, scene)
        if why:
            raise SceneError(why)
    return check


def register_external(path: str | Path) -> ExternalSolver:
    """The solver a declaration describes, registered with the engine under its name (the
    same declaration twice: the one registered already)."""
    decl = load_declaration(path)
    if decl.name in SOLVERS:
        known = SOLVERS.lookup(decl.name)
        if isinstance(known, ExternalSolver) and known.declaration == decl:
            return known
        raise ValueError(f"solver.name: {decl.name!r} is a solver of the harness already; choose another name")
    solver = ExternalSolver(decl.name, _runner(decl), _checker(decl), declaration=decl)
    SOLVERS.register(decl.name, solver, __name__)
    return solver


def retarget(cases: list[Case], solver: ExternalSolver, of: str = "ancf", element: str | None = None,
             study: str | None = None) -> tuple[list[Case], list[tuple[str, str]]]:
    """The cases of solver ``of`` run on ``solver`` instead, and (case name, reason) of
    each one it does not take (skipped, never run). A solver with an element of its own
    (``solver.element``), or ``element`` if given, gets that element's name in
    ``ancf.element`` (and in the scene's name), and cases that then coincide run once. The
    cases' study is ``<study>@<solver>`` (``study``: the cases' own by default)."""
    decl, out, skipped, seen = solver.declaration, [], [], set()
    element = element or decl.element
    for c in cases:
        if c.solver != of:
            continue
        why = unsupported(decl, c.scene)
        if why:
            skipped.append((c.name, why))
            continue
        scene = c.scene
        if element and scene.get("ancf"):
            given = scene["ancf"].get("element", "")
            scene = {**scene, "name": scene["name"].replace(given, element) if given else scene["name"],
                     "ancf": {**scene["ancf"], "element": element}}
        options = {k: v for k, v in c.options.items() if k != "imports"}
        case = make_case(f"{study or c.study}@{decl.name}", decl.name, scene, options)
        if case not in seen:
            seen.add(case)
            out.append(case)
    return out, skipped


def run_study(path: str | Path, study_names: list[str], out: Path, tiny: bool = False, log=print) -> dict:
    """Every ANCF case of the named studies run on the declared solver, one after the other
    in this process (the engine's pool workers start afresh and would not know a solver
    registered from a declaration here; a command runs in a process of its own anyway), into
    ``out/data/<study>@<solver>.jsonl`` (and, for the benchmark suite, its verdicts:
    :func:`studies.external.verdicts.benchmark_report`, and for the dynamic benchmarks
    :func:`~studies.external.verdicts.dynamic_report`); returns {study: {"cases", "computed", "reused",
    "failed", "skipped": [(name, reason)]}} and logs one line per study."""
    from ..engine.catalog import load_catalog
    from ..engine.scheduler import run_cases
    from ..engine.store import store_for

    solver = register_external(path)
    catalog = load_catalog(tiny=tiny)
    summary = {}
    for name in study_names:
        if name not in catalog:
            raise ValueError(f"study: unknown value {name!r}; allowed: {', '.join(sorted(catalog))}")
        cases, skipped = retarget(catalog[name].cases(), solver)
        store = store_for(out, f"{name}@{solver.name}")
        s = run_cases(f"{name}@{solver.name}", cases, store, "serial", 1, progress=False,
                      timeout_s=solver.declaration.wall_time + 30.0)
        summary[name] = {"cases": s.cases, "computed": s.computed, "reused": s.reused, "failed": s.failed,
                         "skipped": skipped}
        log(f"{name} on {solver.name}: {s.cases} cases, {s.reused} reused, {s.computed} computed, {s.failed} "
            f"failed; {len(skipped)} skipped (not declared)")
        for case_name, why in skipped[:3]:
            log(f"  skipped: {case_name}: {why}")
        if name in ("benchmarks", "dynamic-benchmarks"):
            from .verdicts import benchmark_report, dynamic_report

            report = benchmark_report if name == "benchmarks" else dynamic_report
            log(f"  verdicts: {report(out, solver.declaration, skipped, tiny)}")
    return summary
