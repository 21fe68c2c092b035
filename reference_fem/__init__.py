"""Continuum reference in FEniCSx (DOLFINx 0.5): the only package that imports dolfinx.

The scene's beam as a 2D continuum on a structured gmsh mesh: plane strain, exactly
incompressible (Taylor-Hood, mixed) or with the ANCF penalty (perturbed Lagrangian),
or incompressible plane stress (F33 = 1/det F). Same scene files (``ancf.scene``)
and records (``ancf.record``) as ``ancf``.

Modules, one concept each:

- :mod:`.settings`: the scene's [fem] table, validated and resolved (no dolfinx);
- :mod:`.energies`: the laws and continuum models in UFL;
- :mod:`.geometry`: the gmsh rectangle; :mod:`.dolfinx_backend`: every DOLFINx call;
- :mod:`.problem`: energy + loads + supports -> nonlinear system;
- :mod:`.newton`: load stepping with step cutting (no dolfinx);
- :mod:`.run`: scene -> record; :mod:`.convergence`: refinement and Richardson;
- :mod:`.cases`, :mod:`.gold`, :mod:`.report`: the paper's cantilever, gold data, tables;
- :mod:`.cli`: ``python -m reference_fem run | converge | gold | report``.

Importing the package imports nothing heavy; dolfinx is loaded when a problem is built.
"""
