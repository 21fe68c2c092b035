"""Will a run fit on this machine? Checked before it starts, from the solver's estimate.

A solver estimates a scene's unknowns, peak memory and time steps without building
anything (:func:`ancf.build.estimate`, :func:`reference_fem.simulation.estimate`);
:func:`check_capacity` refuses (a :class:`SceneError` naming the field that sets the size,
and how much memory the run would need) what cannot fit in the memory this machine
has available, and returns warnings for what is large: more than half of that memory,
more than ``WARN_UNKNOWNS`` unknowns or ``WARN_STEPS`` time steps. The estimates are
upper bounds calibrated on this project's runs (see each solver's ``estimate``).
"""
from __future__ import annotations

import os
from dataclasses import dataclass

from .errors import SceneError

WARN_UNKNOWNS = 10 ** 6
WARN_STEPS = 10 ** 6
WARN_MEMORY_FRACTION = 0.5


@dataclass(frozen=True)
class Estimate:
    unknowns: int
    memory_bytes: float
    steps: int | None = None      # time steps of a dynamic run (fixed step), else None
    field: str = ""               # the scene field that sets the size, for the message


def available_memory() -> float:
    """Bytes of memory available to a new run (MemAvailable, else the physical total)."""
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return float(line.split()[1]) * 1024
    except OSError:
        pass
    return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))


def gib(x: float) -> str:
    return f"{x / 2 ** 30:.3g} GiB"


def check_capacity(e: Estimate, solver: str, available: float | None = None) -> list[str]:
    """Raise a SceneError if the run cannot fit in memory; return warnings otherwise."""
    available = available_memory() if available is None else available
    if e.memory_bytes > available:
        raise SceneError(f"{e.field}: too large for this machine: {solver} would need about "
                         f"{gib(e.memory_bytes)} for {e.unknowns:.3g} unknowns, {gib(available)} "
                         "is available")
    warnings = []
    if e.memory_bytes > WARN_MEMORY_FRACTION * available:
        warnings.append(f"large run: about {gib(e.memory_bytes)} of the {gib(available)} available")
    if e.unknowns > WARN_UNKNOWNS:
        warnings.append(f"large run: {e.unknowns:.3g} unknowns")
    if e.steps is not None and e.steps > WARN_STEPS:
        warnings.append(f"long run: {e.steps:.3g} time steps")
    return warnings
