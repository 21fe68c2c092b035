"""The DOLFINx backend of the continuum reference (DOLFINx 0.5, gmsh meshes): the only
code that imports dolfinx, ufl, petsc4py or gmsh.

- :mod:`.fem`: every DOLFINx call, a package of four: ``discretisation`` (meshes, spaces),
  ``end_face`` (the face's first moment, the hinge), ``nonlinear_system`` (Newton's
  system), ``forms`` (forms as numbers, point values);
- :mod:`.meshing`: the structured gmsh meshes of the beam;
- :mod:`.krylov`: the iterative solver's PETSc side;
- :mod:`.laws`: the laws in UFL and the invariants they see;
- :mod:`.models`: the continuum models as strategies (invariants, incompressibility);
- :mod:`.problem`: scene -> spaces, law, model, supports, loads; the static problem;
- :mod:`.dynamic_problem`: the forms of one time step.
"""


def version() -> str:
    from .fem import VERSION

    return VERSION


def static_model(scene, settings):
    """The static model of a scene (:func:`.problem.static_model`)."""
    from .problem import static_model

    return static_model(scene, settings)


def dynamic_model(scene, settings):
    """The equations of one time step of a dynamic scene (:mod:`.dynamic_problem`), for
    :class:`reference_fem.stepper.ContinuumStepper` (not named ``dynamic_problem``: importing
    that submodule would replace a package attribute of the same name)."""
    from .dynamic_problem import build_dynamic_problem

    return build_dynamic_problem(scene, settings)


def manufactured(solution, cells: int) -> dict:
    """One level of a manufactured solution on ``cells`` cells (:func:`.mms.solve`)."""
    from .manufactured import solve

    return solve(solution, cells)
