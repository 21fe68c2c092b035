"""Continuum reference in FEniCSx (DOLFINx 0.5): the only package that imports dolfinx."""
