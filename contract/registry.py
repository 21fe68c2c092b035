"""One registry type for every vocabulary the harness resolves by name: elements, laws,
formulations and integrators (``ancf``, ``mechanics``), continuum backends
(``reference_fem``), the study engine's solvers and hooks (``studies``).

A :class:`Registry` maps names to objects of one kind and reads like a dict (``in``,
``[name]``, iteration in registration order, ``len``). :meth:`Registry.register` refuses a
name twice and records the module that registered it (:attr:`Registry.origin`: what a fresh
process imports to have it again); :meth:`Registry.lookup` raises the scene's one-line
error naming the field and the allowed values (:class:`contract.errors.UnknownName`);
:meth:`Registry.freeze_builtin` marks what the package registered itself, so that a name
registered later is known to be a user's (:attr:`Registry.builtin`). ``del registry[name]``
and item assignment (a test's monkeypatch) bypass the duplicate check.
"""
from __future__ import annotations

import sys
from collections.abc import MutableMapping
from typing import Generic, Iterator, TypeVar

from .errors import UnknownName

T = TypeVar("T")


class Registry(MutableMapping, Generic[T]):
    def __init__(self, field: str, kind: str):
        self.field = field          # what a scene or a command line calls it, e.g. "ancf.element"
        self.kind = kind            # what one entry is, e.g. "element"
        self._items: dict[str, T] = {}
        self.origin: dict[str, str] = {}
        self._builtin: frozenset[str] | None = None

    def register(self, name: str, obj: T, origin: str | None = None) -> T:
        """Add ``obj`` under ``name`` (a ValueError if the name is taken); ``origin``: the
        registering module's name (default: the caller's)."""
        if name in self._items:
            raise ValueError(f"{self.kind} {name!r} is registered already")
        self._items[name] = obj
        self.origin[name] = origin or sys._getframe(1).f_globals.get("__name__", "__main__")
        return obj

    def lookup(self, name: str) -> T:
        """The object named ``name``, or the error that names the field and the allowed values."""
        try:
            return self._items[name]
        except (KeyError, TypeError):
            raise UnknownName(self.field, name, self._items) from None

    def copy(self) -> "Registry[T]":
        """A registry with the same entries, origins and built-in names (a test's sandbox)."""
        new = Registry(self.field, self.kind)
        new._items, new.origin, new._builtin = dict(self._items), dict(self.origin), self._builtin
        return new

    def freeze_builtin(self) -> frozenset[str]:
        """Mark every name registered so far as built in; returns them."""
        self._builtin = frozenset(self._items)
        return self._builtin

    @property
    def builtin(self) -> frozenset[str]:
        return self._builtin if self._builtin is not None else frozenset(self._items)

    def __getitem__(self, name: str) -> T:
        return self._items[name]

    def __setitem__(self, name: str, obj: T) -> None:
        self._items[name] = obj
        self.origin.setdefault(name, sys._getframe(1).f_globals.get("__name__", "__main__"))

    def __delitem__(self, name: str) -> None:
        del self._items[name]
        self.origin.pop(name, None)

    def __iter__(self) -> Iterator[str]:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __repr__(self) -> str:
        return f"Registry({self.field!r}: {', '.join(self._items)})"
