"""Errors a user sees: one message naming the field and the allowed values (exit status 2)."""
from __future__ import annotations


class SceneError(ValueError):
    """A scene (or option) that cannot be run; the message names the field."""


class UnknownName(SceneError):
    def __init__(self, field: str, value, allowed):
        allowed = ", ".join(repr(a) for a in sorted(allowed))
        super().__init__(f"{field}: unknown value {value!r}; allowed: {allowed}")
