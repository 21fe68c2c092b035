"""Continuum reference in FEniCSx (DOLFINx 0.5): the only package that imports dolfinx.

The scene's beam as a continuum on a structured gmsh mesh: plane strain, exactly
incompressible (Taylor-Hood, mixed) or with the ANCF penalty (perturbed Lagrangian),
or incompressible plane stress (F33 = 1/det F); or the real beam in 3D
(``[fem] model = "3d"``, hexahedra, full 3D invariants), distributed over the ranks of
an ``mpiexec`` launch. Same scene files (``contract.scene``)
and records (``contract.record``) as ``ancf``, the same load-path rule
(``mechanics.load_path``) and time loop (``mechanics.time_loop``).

Modules, one concept each. Shared by every backend (no dolfinx):

- :mod:`.settings`: the scene's [fem] table, validated and resolved;
- :mod:`.geometry`: where supports, the tip and the probes are, per model;
- :mod:`.statics`: Newton and static load stepping; :mod:`.stepper`: the time stepper;
- :mod:`.simulation`: scene -> record; :mod:`.convergence`: refinement and Richardson;
- :mod:`.cli`: ``python -m reference_fem run | converge``;
- :mod:`.launch`: the ``mpiexec`` / ``srun`` command line of a run on N ranks.

The DOLFINx backend, :mod:`.dolfinx_backend` (the only place dolfinx is imported):
``laws`` (the laws in UFL), ``models`` (continuum models as strategies), ``meshing``
(gmsh), ``problem`` (scene -> spaces, law, model, supports, loads; the static problem),
``dynamic_problem`` (the forms of one time step), ``fem`` (every DOLFINx call: the
discretisation, the end face's terms, the nonlinear system, forms as numbers),
``krylov`` (the iterative solver's PETSc side).

The FElupe backend, :mod:`.felupe_backend` (``[fem] backend = "felupe"``): ``laws`` (each
model's energy on tensortrax, its derivatives), ``problem`` (mesh, fields, supports,
loads; the static Newton system), ``dynamic_problem`` (one time step's residual, tangent
and mass). Each backend offers ``static_model`` and ``dynamic_model`` of a scene, driven by
the shared :mod:`.statics` and :mod:`.stepper`.

Importing the package imports nothing heavy; dolfinx is loaded when a problem is built.
"""
