"""The registry of ANCF elements: one place where an element's name becomes its spec.

To add an element, register a spec (:class:`ancf.core.spec.ElementSpec`, data)::

    register_element(ElementSpec(
        name="HB2n-cubic", basis=("1", "x", "y", "x*y", "x^2", "y^2", "x*y^2", "x^3", "y^3", "x*y^3"),
        nodes=(0.0, 1.0), kinds=("r", "r_x", "r_y", "r_yy", "r_yyy")))

(a kind is "r" and its derivatives, :data:`KINDS`); scenes can then name it. Its
kinematics (``kinematics``, default "continuum") is a registered family
(:mod:`ancf.kinematics`), which checks the spec. The built-in elements are data files of
their families: :mod:`.section` and :mod:`.cable`.

The studies, the cards and the peers' diagram take their elements from this registry
(:func:`select`), by the elements' tags (:data:`TAGS`: "paper", "locking", "costly") and
the formulations they run: an element registered once, untagged, joins every study that
runs its formulations.
"""
from __future__ import annotations

import sys
from typing import Iterable

from contract.registry import Registry

from .. import kinematics  # noqa: F401  (fills KINEMATICS: an element names one)
from ..core.spec import KINDS, KINEMATICS, SLENDER, TAGS, ElementSpec, rules  # noqa: F401  (the names element authors use)

# (ELEMENTS.origin: element name -> the module that registered it, what a fresh process
# imports to have it)
ELEMENTS: Registry[ElementSpec] = Registry("ancf.element", "element")


def register_element(spec: ElementSpec) -> ElementSpec:
    spec.dimensionless(1.0, 1.0)  # fail at registration, not at first use
    return ELEMENTS.register(spec.name, spec, sys._getframe(1).f_globals.get("__name__", "__main__"))


def get_element(name: str) -> ElementSpec:
    return ELEMENTS.lookup(name)


def select(tagged: str | None = None, without: Iterable[str] = (), running: Iterable[str] = ()) -> list[str]:
    """The registered elements a study takes, in the registry's order: those tagged
    ``tagged`` (every one if None), none tagged with any of ``without``, each running
    every formulation of ``running``. A study names its elements this way, so that an
    element registered (a user's module too) joins every study its tags admit."""
    for t in (tagged, *without):
        if t is not None and t not in TAGS:
            raise ValueError(f"unknown element tag {t!r}; tags are {sorted(TAGS)}")
    without, running = set(without), tuple(running)
    return [name for name, spec in ELEMENTS.items()
            if (tagged is None or tagged in spec.tags) and not without & set(spec.tags)
            and all(spec.family.runs(f) for f in running)]


from . import section  # noqa: E402,F401  (the built-in elements register themselves,
from . import cable  # noqa: E402,F401   in the order the registry lists them)

# the elements of this package; any other was registered by a user's module
BUILTIN = ELEMENTS.freeze_builtin()
