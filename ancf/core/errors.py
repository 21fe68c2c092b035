"""The solver's own exceptions (a module below every other, so that any may raise them)."""
from __future__ import annotations


class InadmissibleState(ArithmeticError):
    """A deformation gradient with det F <= 0 (or a non-finite one) somewhere."""
