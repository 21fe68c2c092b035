"""A refactor recomputes nothing, an edit recomputes: the fingerprint is the multiset of the
normalised statements a run reaches, whichever module holds each
(:mod:`studies.engine.fingerprint`, :mod:`contract.source`)."""
import sys
import textwrap

import pytest

from contract.source import statements
from studies.engine import fingerprint as fp

RUN = '''
from fpm_a import f, g
from fpm_b import C


def run(x):
    return f(x) + g(x) * C
'''
A = '''
"""Two functions."""
def f(x):
    return 2.0 * x


def g(x):
    return x + 1.0
'''
B = '''
C = 3.0
'''


@pytest.fixture
def tree(tmp_path, monkeypatch):
    """A user's three modules outside the repository; ``write({name: text})`` rewrites
    them (a name mapped to None is removed) and returns the fingerprint of ``fpm_run``."""
    monkeypatch.syspath_prepend(str(tmp_path))
    names = set()

    def write(files: dict) -> str:
        for name, text in files.items():
            path = tmp_path / f"{name}.py"
            names.add(name)
            if text is None:
                path.unlink()
            else:
                path.write_text(textwrap.dedent(text))
        fp.clear_caches()
        return fp.fingerprint(("fpm_run",))["code"]

    write({"fpm_run": RUN, "fpm_a": A, "fpm_b": B})
    yield write
    fp.clear_caches()
    for m in names:
        sys.modules.pop(m, None)


def test_a_definition_moved_to_another_reached_module_is_reused(tree):
    base = tree({})
    moved = tree({"fpm_a": A.split("def g")[0],
                  "fpm_b": B + "\n\ndef g(x):\n    return x + 1.0\n",
                  "fpm_run": RUN.replace("from fpm_a import f, g", "from fpm_a import f\nfrom fpm_b import g")})
    assert moved == base


def test_a_module_renamed_or_its_definitions_reordered_is_reused(tree):
    base = tree({})
    assert tree({"fpm_b": None, "fpm_c": B, "fpm_run": RUN.replace("fpm_b", "fpm_c")}) == base
    a_reordered = "def g(x):\n    return x + 1.0\n\n\ndef f(x):\n    return 2.0 * x\n"
    assert tree({"fpm_a": a_reordered}) == base


def test_an_edited_line_recomputes(tree):
    base = tree({})
    assert tree({"fpm_a": A.replace("2.0 * x", "2.0 * x * x")}) != base
    tree({"fpm_a": A})
    assert tree({"fpm_b": "C = 3.5\n"}) != base
    tree({"fpm_b": B})
    assert tree({"fpm_run": RUN.replace("f(x) + g(x)", "f(x) - g(x)")}) != base


def test_a_call_through_a_module_name_changes_with_that_name(tree):
    """``module.C`` is written with the module's name: renaming that module is an edit
    of the line (stated in the module doc), unlike ``from module import C``."""
    run = RUN.replace("from fpm_b import C", "import fpm_b").replace("* C", "* fpm_b.C")
    base = tree({"fpm_run": run})
    assert tree({"fpm_b": None, "fpm_c": B, "fpm_run": run.replace("fpm_b", "fpm_c")}) != base


def test_a_move_into_a_module_not_reached_before_brings_that_module(tree):
    """What a move can change is seen: the new home's other code now runs with the case."""
    base = tree({})
    tree({"fpm_d": "D = 1.0\n\n\ndef g(x):\n    return x + 1.0\n"})
    assert tree({"fpm_a": A.split("def g")[0],
                 "fpm_run": RUN.replace("from fpm_a import f, g", "from fpm_a import f\nfrom fpm_d import g")}) != base


def test_plumbing_is_not_code():
    """Imports, docstrings, ``pass`` and ``__all__`` compute nothing: a package's
    ``__init__`` that gathers names adds no statement."""
    assert statements('"""A package."""\nfrom .a import f\nimport numpy as np\n__all__ = ["f"]\npass\n') == []
    assert len(statements("X = 1\ndef f():\n    '''doc'''\n    return X\n")) == 2
    assert statements("def f():\n    '''doc'''\n    return 1\n") == statements("def f():\n    return 1\n")
