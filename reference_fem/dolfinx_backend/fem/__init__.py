"""Every DOLFINx call of reference_fem, written against DOLFINx 0.5.2.

A newer DOLFINx changes this package only (gmsh import, element constructors, point
evaluation, assembly and PETSc glue). The 2D meshes are built on ``MPI.COMM_SELF``, so
cases can run side by side in separate processes or threads of a study. The 3D mesh
(:func:`~.discretisation.box_mesh`) is distributed over ``MPI.COMM_WORLD`` when the
process was started by ``mpiexec -n N`` with N > 1 (else ``COMM_SELF``); everything else
takes its communicator from the mesh, and every number a decision reads (norms, counts,
point values) is global and the same on every rank.

Its modules, whose names this package gathers (the backend's problems call them as
``fem.<name>``):

- :mod:`.discretisation`: :func:`rectangle_mesh`, a structured gmsh mesh of
  [0, L] x [-h/2, h/2]; :func:`box_mesh`, the 3D beam, built on rank 0 and distributed;
  :class:`Discretisation`: displacement (and optionally scaled pressure) space on a
  mesh, the unknown, test functions, measures, constants, Dirichlet conditions, point
  evaluation and output;
- :mod:`.end_face`: :class:`FaceFirstMoment`, the end face's first moment (the end
  moment's rotation), and :class:`FaceHinge`, the hinge's exact elimination;
- :mod:`.nonlinear_system`: :class:`NonlinearSystem`, residual, Newton increment (LU, or
  the Krylov solver of :mod:`..krylov`), state save/restore;
- :mod:`.forms`: :class:`Functional`, :class:`VectorNorm`, a compiled scalar form's
  value, the norm of an assembled vector form (for energies and Newton scales in
  dynamics); :class:`PointwiseEvaluator`: a UFL expression of a constant F (and phat)
  evaluated as numbers, for checking the UFL laws against :mod:`ancf`.
"""
from .discretisation import (COMM, VERSION, Discretisation, Locator, beam_mesh, box_mesh, fixed_dof_count,
                             rectangle_mesh, solver_comm)
from .end_face import FaceFirstMoment, FaceHinge
from .forms import Functional, PointwiseEvaluator, VectorNorm
from .nonlinear_system import NonlinearSystem
