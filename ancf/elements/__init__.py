"""The registry of ANCF elements: one place where an element's name becomes its spec.

To add an element, register a spec (:class:`ancf.core.spec.ElementSpec`, data)::

    register_element(ElementSpec(
        name="HB2n-cubic", basis=("1", "x", "y", "x*y", "x^2", "y^2", "x*y^2", "x^3", "y^3", "x*y^3"),
        nodes=(0.0, 1.0), kinds=("r", "r_x", "r_y", "r_yy", "r_yyy")))

(a kind is "r" and its derivatives, :data:`KINDS`); scenes can then name it. Its
kinematics (``kinematics``, default "continuum") is a registered family
(:mod:`ancf.kinematics`), which checks the spec. The built-in elements are data files of
their families: :mod:`.section` and :mod:`.cable`.
"""
from __future__ import annotations

import sys

from contract.registry import Registry

from .. import kinematics  # noqa: F401  (fills KINEMATICS: an element names one)
from ..core.spec import KINDS, KINEMATICS, SLENDER, ElementSpec, rules  # noqa: F401  (the names element authors use)

# (ELEMENTS.origin: element name -> the module that registered it, what a fresh process
# imports to have it)
ELEMENTS: Registry[ElementSpec] = Registry("ancf.element", "element")


def register_element(spec: ElementSpec) -> ElementSpec:
    spec.dimensionless(1.0, 1.0)  # fail at registration, not at first use
    return ELEMENTS.register(spec.name, spec, sys._getframe(1).f_globals.get("__name__", "__main__"))


def get_element(name: str) -> ElementSpec:
    return ELEMENTS.lookup(name)


from . import section  # noqa: E402,F401  (the built-in elements register themselves,
from . import cable  # noqa: E402,F401   in the order the registry lists them)

# the elements of this package; any other was registered by a user's module
BUILTIN = ELEMENTS.freeze_builtin()
