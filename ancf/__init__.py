"""2D ANCF beam elements with incompressible hyperelastic laws.

Elements are data (:mod:`ancf.elements`), laws are energies (:mod:`mechanics.laws`, shared with the continuum), a
formulation says which invariants a law sees (:mod:`ancf.core.formulations`); a scene file
(:mod:`contract.scene`, shared with the continuum solver) names them and
:mod:`ancf.build` checks the names and turns them into objects.
"""
__version__ = "0.2.0"

from . import compiled_cache as _compiled_cache

_compiled_cache.configure()      # before any compiled function is defined
