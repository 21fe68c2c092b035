"""The study engine knows no study: no module of studies/engine/ imports a study, a peer or
the card (at module level or inside a function); what it runs and audits is registered with
it by those modules (solvers, audit hooks, case sources)."""
import ast
from pathlib import Path

import studies
from studies.engine.audit import PREBUILD, RULES
from studies.engine.solvers import SOLVERS
from studies.engine.verify import CASE_SOURCES

ENGINE = Path(studies.__file__).parent / "engine"


def _imports(path: Path) -> list[tuple[int, str]]:
    """(line, absolute module) of every import statement of a module of studies.engine."""
    out = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:       # relative to studies.engine
                base = ["studies", "engine"][: 3 - node.level]
                name = ".".join(base + ([node.module] if node.module else []))
                out += [(node.lineno, f"{name}.{a.name}" if not node.module else name) for a in node.names]
            else:
                out.append((node.lineno, node.module or ""))
    return out


def test_no_engine_module_imports_a_study_a_peer_or_the_card():
    bad = [f"{p.name}:{line}: {mod}" for p in sorted(ENGINE.glob("*.py")) for line, mod in _imports(p)
           if mod.startswith("studies") and not mod.startswith("studies.engine")]
    assert not bad, bad


def test_a_planted_import_is_caught(tmp_path):
    """The scan sees a function-level relative import of a study (the rule can fail)."""
    f = tmp_path / "x.py"
    f.write_text("def f():\n    from ..card import cases\n    from .case import Case\n")
    mods = [m for _, m in _imports(f)]
    assert "studies.card" in mods and "studies.engine.case" in mods


def test_what_the_engine_runs_is_registered_by_its_owners():
    assert {"ancf", "ancf-effects", "ancf-cold", "continuum"} <= set(SOLVERS)
    assert SOLVERS.origin["ancf"] == "studies.solvers"
    assert "cards" in PREBUILD and "cards" in CASE_SOURCES and "peers" in RULES
    from studies.verification import benchmarks, manufactured  # noqa: F401  (a study registers its own solver)
    assert SOLVERS.origin["mms"] == "studies.verification.manufactured" and SOLVERS.origin["ancf-material"] == "studies.verification.benchmarks"
