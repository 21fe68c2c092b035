"""What counts as a change of code: the one normaliser of the records' fingerprints
(:mod:`studies.engine.fingerprint`) and of the compiled code's cache
(:mod:`ancf.compiled_cache`).

A module is parsed and its docstrings dropped; what is left is dumped without line
numbers, so comments, docstrings, blank lines and line wraps do not count and any change
of behaviour does. :func:`statements` also splits it into its top-level statements
without its imports: a record's fingerprint is the multiset of these over everything its
run reaches, so that moving a definition to another module, renaming or splitting a
module, or reordering a module's definitions leaves it as it was, while an edit of any
line that runs changes it.
"""
from __future__ import annotations

import ast


def _without_docstrings(tree: ast.AST) -> ast.AST:
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
                    and isinstance(body[0].value.value, str):
                node.body = body[1:] or [ast.Pass()]
    return tree


def dump(node: ast.AST) -> str:
    """One node's normalised text (no field names, no line numbers)."""
    return ast.dump(node, annotate_fields=False, include_attributes=False)


def normalised(source: str | bytes) -> str:
    """The module's syntax tree without docstrings, line numbers or comments."""
    return dump(_without_docstrings(ast.parse(source)))


def statements(source: str | bytes) -> list[str]:
    """The normalised text of each top-level statement of a module but its plumbing
    (imports, docstring, ``__all__``: where a definition lives is not what it does), in
    the module's order."""
    tree = ast.parse(source)
    return [dump(_without_docstrings(s)) for s in tree.body if not _plumbing(s)]


def _plumbing(stmt: ast.stmt) -> bool:
    """A top-level statement that computes nothing a run could see: an import, the
    module's docstring, ``pass``, ``__all__`` (a package's ``__init__`` that only gathers
    names adds nothing)."""
    if isinstance(stmt, (ast.Import, ast.ImportFrom, ast.Pass)):
        return True
    if isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Constant) and isinstance(stmt.value.value, str):
        return True
    if isinstance(stmt, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
        targets = stmt.targets if isinstance(stmt, ast.Assign) else [stmt.target]
        return all(isinstance(t, ast.Name) and t.id == "__all__" for t in targets)
    return False
