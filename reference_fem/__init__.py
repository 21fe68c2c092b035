"""Continuum reference in FEniCSx (DOLFINx 0.5): the only package that imports dolfinx.

The scene's beam as a continuum on a structured gmsh mesh: plane strain, exactly
incompressible (Taylor-Hood, mixed) or with the ANCF penalty (perturbed Lagrangian),
or incompressible plane stress (F33 = 1/det F); or the real beam in 3D
(``[fem] model = "3d"``, hexahedra, full 3D invariants), distributed over the ranks of
an ``mpiexec`` launch. Same scene files (``contract.scene``)
and records (``contract.record``) as ``ancf``, the same load-path rule
(``ancf.loadpath``) and time loop (``ancf.timeloop``).

Modules, one concept each:

- :mod:`.settings`: the scene's [fem] table, validated and resolved (no dolfinx);
- :mod:`.energies`: the laws in UFL and their invariants;
- :mod:`.models`: the continuum models as strategies (invariants, incompressibility,
  geometry); :mod:`.geometry`: the gmsh meshes and where supports and the tip are;
- :mod:`.dolfinx_backend`: every DOLFINx call; :mod:`.krylov`: the iterative Newton
  solver's PETSc side (options, the augmented-Lagrangian preconditioner);
- :mod:`.setup`: scene -> spaces, law, model, supports, loads; the static problem;
- :mod:`.dynamic_problem`: the forms of one time step; :mod:`.dynamics`: its stepper;
- :mod:`.newton`: Newton and static load stepping (no dolfinx);
- :mod:`.run`: scene -> record; :mod:`.convergence`: refinement and Richardson;
- :mod:`.gold`, :mod:`.pendulum`, :mod:`.report`: gold data of the paper's examples, tables;
- :mod:`.cli`: ``python -m reference_fem run | converge | gold | pendulum | report``.
- :mod:`.launch`: the ``mpiexec`` / ``srun`` command line of a run on N ranks (no dolfinx).

Importing the package imports nothing heavy; dolfinx is loaded when a problem is built.
"""
