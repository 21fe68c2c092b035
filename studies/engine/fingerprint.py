"""What a record depends on: the code its solver runs and the packages that code uses.

A case's identity (:mod:`.case`) holds a *fingerprint* of its solver, taken per case:

- **the code**: every project module the solver's run function can execute, found by
  reading imports (module level and inside functions, followed to the end), taken as the
  multiset of its top-level statements, each *normalised* (:mod:`contract.source`, the one
  normaliser, shared with the compiled code's cache): parsed, docstrings dropped, dumped
  without line numbers, imports and ``__all__`` left out. Comments, docstrings, blank
  lines and line wraps do not count, and any change of behaviour does; and the statements
  are hashed without the names of the modules they sit in, so a refactor that only moves
  code (a definition to another module that the run reaches, a module renamed, split or
  moved into a package, definitions reordered) recomputes nothing
  (``tests/test_fingerprint_moves.py`` shows a move reused and an edited line recomputed);
- **the packages**: the version of every installed distribution those modules import
  (numpy, scipy, numba, dolfinx, ufl, FElupe, tensortrax, ...), read from its metadata,
  plus the interpreter's minor version (the dump's format is the interpreter's).

What a move can change is seen too: a definition moved into a module the run did not
reach before brings that module's other statements along, and a call written through a
module's name (``module.f``) changes with that name.

Three rules keep it to what runs:

- the run function itself is taken alone, with the top-level names of its module it uses
  (a solver wrapper beside a study's tables does not carry the tables); the same holds
  inside ``studies/``, where solver helpers live beside report code. In the solver
  packages (``ancf``, ``mechanics``, ``contract``, ``reference_fem``, a user's module)
  whole modules count: a registry filled at import, a kernel chosen by name, are
  behaviour that a name-by-name reading could miss;
- a package that loads its own modules by name (``mechanics.laws``) counts whole
  (:data:`DISCOVERS`);
- per backend: a continuum case counts the backend its scene names, never the other one
  (:func:`backends`), so a change to FElupe's backend keeps DOLFINx's records, and the
  reverse;
- modules that cannot change a result (:data:`NOT_RESULTS`: where compiled code is cached,
  the command lines' console and output, the warm-up, the scene checks) never count.

:func:`fingerprint` returns ``{"code": sha256, "packages": {name: version}}``;
:func:`modules` lists what it read (for a reader who wants to see why a record moved).
"""
from __future__ import annotations

import ast
import copy
import hashlib
import importlib.util
import sys
from dataclasses import dataclass
from functools import lru_cache
from importlib import metadata
from pathlib import Path
from typing import Callable, Iterable

from contract.source import statements

ROOT = Path(__file__).resolve().parents[2]
# packages of this repository whose modules count whole (see the module doc)
SOLVER_PACKAGES = ("ancf", "mechanics", "contract", "reference_fem", "examples")
# packages whose code counts name by name (solver helpers beside report code)
BY_NAME_PACKAGES = ("studies",)
# packages that import their own submodules by name at run time: reached, they count whole
DISCOVERS = ("mechanics.laws",)
# modules that cannot change a result: where the compiled code is cached (its own source
# digest keeps stale compiled code from running: tests/test_compiled_cache.py), the command
# lines' console, output writers and warm-up, and the scene checks (a check raises or
# returns its scene untouched, and runs whenever a case is made: tests/test_admission.py);
# never part of a fingerprint
NOT_RESULTS = ("ancf.compiled_cache", "ancf.cli", "ancf.output", "ancf.warm", "ancf.__main__", "contract.console",
               "ancf.admission")


def backends() -> dict[str, str]:
    """{continuum backend: its package} (:data:`reference_fem.backends.BACKENDS`): a case
    counts the one its scene names (scene["fem"]["backend"])."""
    from reference_fem.backends import BACKENDS

    return {name: b.package for name, b in BACKENDS.items()}
# distributions a package's code depends on without importing them (JIT code generators)
IMPLIED = {"fenics-dolfinx": ("fenics-ffcx", "fenics-basix", "fenics-ufl")}


# -- finding modules --------------------------------------------------------------------

@lru_cache(maxsize=None)
def _path(module: str) -> Path | None:
    """The source file of a module: under the repository for its own packages, else
    wherever Python finds it without importing it (a user's module); None for a package
    installed elsewhere (numpy, ...) or the standard library."""
    top = module.split(".")[0]
    if top in sys.stdlib_module_names:
        return None
    parts = module.split(".")
    if (ROOT / top).is_dir() or (ROOT / f"{top}.py").is_file():
        for p in (ROOT.joinpath(*parts).with_suffix(".py"), ROOT.joinpath(*parts, "__init__.py")):
            if p.is_file():
                return p
        return None
    try:
        spec = importlib.util.find_spec(top) if "." in module else importlib.util.find_spec(module)
    except (ImportError, ValueError):
        return None
    if spec is None or not spec.origin or spec.origin in ("built-in", "frozen"):
        return None
    origin = Path(spec.origin)
    if any(part in ("site-packages", "dist-packages") for part in origin.parts) or "/lib/python" in str(origin):
        return None
    if "." in module:
        base = origin.parent if origin.name == "__init__.py" else origin.parent
        for p in (base.joinpath(*parts[1:]).with_suffix(".py"), base.joinpath(*parts[1:], "__init__.py")):
            if p.is_file():
                return p
        return None
    return origin


def _is_package(module: str) -> bool:
    p = _path(module)
    return p is not None and p.name == "__init__.py"


def _in(module: str, packages: Iterable[str]) -> bool:
    return any(module == p or module.startswith(p + ".") for p in packages)


@lru_cache(maxsize=None)
def _tree(path: Path) -> ast.Module:
    return ast.parse(path.read_text(encoding="utf-8"))


@lru_cache(maxsize=None)
def _statements_file(path: Path) -> tuple[str, ...]:
    return tuple(statements(path.read_text(encoding="utf-8")))


def _absolute(module: str, node: ast.ImportFrom) -> str:
    """The absolute module name of ``from <node.module> import ...`` inside ``module``."""
    if not node.level:
        return node.module or ""
    base = module.split(".")
    base = base if _is_package(module) else base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _targets(module: str, node: ast.AST) -> list[tuple[str, str | None]]:
    """(module, name) pairs an import statement makes available: name None for a whole
    module, else a top-level name of that module."""
    out = []
    if isinstance(node, ast.Import):
        for a in node.names:
            out.append((a.name, None))
    elif isinstance(node, ast.ImportFrom):
        src = _absolute(module, node)
        for a in node.names:
            sub = f"{src}.{a.name}"
            if a.name != "*" and _path(sub) is not None:
                out.append((sub, None))
            else:
                out.append((src, None if a.name == "*" else a.name))
    return out


def _parents(module: str) -> list[str]:
    parts = module.split(".")
    return [".".join(parts[:i]) for i in range(1, len(parts))]


# -- the closure ------------------------------------------------------------------------

@dataclass
class _Reader:
    exclude: tuple[str, ...]
    code: dict                 # key -> its normalised top-level statements
    third_party: set
    by_name: tuple[str, ...] = BY_NAME_PACKAGES

    def module(self, module: str) -> None:
        """A module imported whole: its parents, its normalised source, its imports. A
        module of a by-name package adds nothing by being imported (its names count
        when they are used)."""
        if _in(module, self.exclude):
            return
        if _path(module) is None:
            top = module.split(".")[0]
            if top not in sys.stdlib_module_names and top != "__future__":
                self.third_party.add(top)
            return
        if _in(module, self.by_name):
            return
        for parent in _parents(module):
            if _path(parent) is not None:
                self._whole(parent)
        self._whole(module)

    def _whole(self, module: str) -> None:
        if module in self.code or _in(module, self.exclude):
            return
        path = _path(module)
        self.code[module] = _statements_file(path)
        for node in ast.walk(_tree(path)):
            for target, nm in _targets(module, node):
                self.name(target, nm) if nm else self.module(target)
        if module in DISCOVERS:
            for p in sorted(path.parent.glob("*.py")):
                if p.name != "__init__.py":
                    self.module(f"{module}.{p.stem}")

    def name(self, module: str, name: str) -> None:
        """A top-level name of a module, with what it uses (a whole module outside the
        by-name packages)."""
        if _path(module) is None or not _in(module, self.by_name):
            self.module(module)
            return
        key = f"{module}:{name}"
        if key in self.code or _in(module, self.exclude):
            return
        defs = [_unannotated(s) for s in _tree(_path(module)).body if _binds(s, name)]
        self.code[key] = tuple(t for s in defs for t in statements(ast.unparse(s)))
        for s in defs:
            self._statement(module, s)

    def _statement(self, module: str, stmt: ast.AST) -> None:
        """Follow what a statement imports and the module's top-level names it uses."""
        tops = _top_names(module)
        local: dict[str, str] = {}       # names bound to whole modules inside the statement
        for node in ast.walk(stmt):
            for target, nm in _targets(module, node):
                self.name(target, nm) if nm else self.module(target)
                if nm is None and isinstance(node, ast.ImportFrom):
                    local[target.rsplit(".", 1)[-1]] = target
            if isinstance(node, ast.Import):
                for a in node.names:
                    local[a.asname or a.name.split(".")[0]] = a.name if a.asname else a.name.split(".")[0]
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
                bound = local.get(node.value.id)
                kind, target, nm = tops.get(node.value.id, (None, None, None))
                if bound is None and kind == "import" and nm is None:
                    bound = target
                if bound and _in(bound, self.by_name):
                    self.name(bound, node.attr)
            if isinstance(node, ast.Name) and node.id in tops:
                kind, target, nm = tops[node.id]
                if kind == "def":
                    self.name(module, node.id)
                elif nm:
                    self.name(target, nm)
                else:
                    self.module(target)


def _unannotated(stmt: ast.AST) -> ast.AST:
    """A function's definition without the annotations of its arguments and result (a
    type named in a signature runs nothing); other statements as they are."""
    if not isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef)):
        return stmt
    stmt = copy.deepcopy(stmt)
    for node in ast.walk(stmt):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            node.returns = None
        elif isinstance(node, ast.arg):
            node.annotation = None
    return stmt


def _binds(stmt: ast.AST, name: str) -> bool:
    if isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        return stmt.name == name
    if isinstance(stmt, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
        targets = stmt.targets if isinstance(stmt, ast.Assign) else [stmt.target]
        return any(isinstance(n, ast.Name) and n.id == name for t in targets for n in ast.walk(t))
    return False


@lru_cache(maxsize=None)
def _top_names(module: str) -> dict[str, tuple[str, str, str | None]]:
    """{name: ("def", module, None) | ("import", module, name or None)} of a module's
    top level."""
    out = {}
    for s in _tree(_path(module)).body:
        if isinstance(s, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            out[s.name] = ("def", module, None)
        elif isinstance(s, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
            targets = s.targets if isinstance(s, ast.Assign) else [s.target]
            for t in targets:
                for n in ast.walk(t):
                    if isinstance(n, ast.Name):
                        out[n.id] = ("def", module, None)
        elif isinstance(s, (ast.Import, ast.ImportFrom)):
            for a, (target, nm) in zip(s.names, _targets(module, s)):
                out[a.asname or a.name.split(".")[0]] = ("import", target, nm)
    return out


# -- packages ---------------------------------------------------------------------------

@lru_cache(maxsize=None)
def _distributions() -> dict[str, list[str]]:
    return metadata.packages_distributions()


@lru_cache(maxsize=None)
def _version(dist: str) -> str | None:
    try:
        return metadata.version(dist)
    except metadata.PackageNotFoundError:
        return None


@lru_cache(maxsize=None)
def _source_version(top: str) -> str | None:
    """``__version__`` as its module's source states it (a literal, or a name bound to
    one): for the packages that Debian ships without metadata (gmsh, mpi4py, petsc4py);
    None where there is none (the module is then a stand-alone file of the user's)."""
    try:
        spec = importlib.util.find_spec(top)
    except (ImportError, ValueError):
        return None
    if spec is None or not spec.origin or not spec.origin.endswith(".py"):
        return None
    literals = {}
    for s in ast.parse(Path(spec.origin).read_text(encoding="utf-8")).body:
        if isinstance(s, ast.Assign) and len(s.targets) == 1 and isinstance(s.targets[0], ast.Name):
            v = s.value
            if isinstance(v, ast.Constant) and isinstance(v.value, str):
                literals[s.targets[0].id] = v.value
            elif isinstance(v, ast.Name) and v.id in literals:
                literals[s.targets[0].id] = literals[v.id]
    return literals.get("__version__")


def packages(top_level: Iterable[str]) -> dict[str, str | None]:
    """{distribution: version} of the top-level modules (those of no installed
    distribution, e.g. a module beside the interpreter, are left out), with the
    distributions they imply (:data:`IMPLIED`) and ``python`` (major.minor)."""
    out = {}
    for top in sorted(set(top_level)):
        dists = _distributions().get(top, ())
        for dist in dists:
            out[dist.lower()] = _version(dist)
            for extra in IMPLIED.get(dist.lower(), ()):
                out[extra] = _version(extra)
        if not dists and (v := _source_version(top)):
            out[top] = v
    out["python"] = f"{sys.version_info.major}.{sys.version_info.minor}"
    return dict(sorted(out.items()))


# -- the fingerprint --------------------------------------------------------------------

def _read(entries: tuple[str, ...], exclude: tuple[str, ...], whole: bool = False) -> _Reader:
    r = _Reader(exclude + NOT_RESULTS, {}, set(), () if whole else BY_NAME_PACKAGES)
    for e in entries:
        module, _, name = e.partition(":")
        r.name(module, name) if name else r.module(module)
    return r


@lru_cache(maxsize=None)
def _fingerprint(entries: tuple[str, ...], exclude: tuple[str, ...], whole: bool = False) -> tuple[str, tuple]:
    r = _read(entries, exclude, whole)
    return code_digest(r.code.values()), tuple(packages(r.third_party).items())


def code_digest(parts: Iterable[Iterable[str]]) -> str:
    """sha256 of the multiset of normalised statements, whichever module holds each."""
    h = hashlib.sha256()
    for text in sorted(t for part in parts for t in part):
        h.update(text.encode() + b"\0")
    return h.hexdigest()


def entry(fn: Callable) -> str:
    """``module:name`` of a top-level function."""
    return f"{fn.__module__}:{fn.__qualname__}"


def fingerprint(entries: Iterable[str], backend: str | None = None, whole: bool = False) -> dict:
    """{"code": sha256 of the normalised code reachable from ``entries`` (``module`` or
    ``module:name``), "packages": {distribution: version}}; with ``backend``, the other
    continuum backends are left out (see the module doc); ``whole``: every module reached
    counts whole, ``studies`` too (what report code reaches)."""
    exclude = tuple(sorted(p for b, p in backends().items() if backend is not None and b != backend))
    code, pkgs = _fingerprint(tuple(entries), exclude, whole)
    return {"code": code, "packages": dict(pkgs)}


def clear_caches() -> None:
    """Forget every file read (a long-lived process that wants to see edits)."""
    for f in (_path, _tree, _statements_file, _top_names, _fingerprint):
        f.cache_clear()


def digest(fingerprint: dict) -> str:
    """One hex string for a fingerprint (its code and packages)."""
    text = fingerprint["code"] + "".join(f"\0{k}={v}" for k, v in sorted(fingerprint["packages"].items()))
    return hashlib.sha256(text.encode()).hexdigest()[:20]


def modules(entries: Iterable[str], backend: str | None = None) -> list[str]:
    """What :func:`fingerprint` reads, sorted (``module`` or ``module:name``)."""
    exclude = tuple(sorted(p for b, p in backends().items() if backend is not None and b != backend))
    return sorted(_read(tuple(entries), exclude).code)
