"""The continuum reference on FElupe (``[fem] backend = "felupe"``): a second, independent
finite-element code behind the same scenes and records as :mod:`reference_fem.dolfinx_backend`.

FElupe (pure Python, numpy/scipy) gives the meshes, the Lagrange elements, the quadrature
and the assembly; tensortrax differentiates the laws' energies (in the invariants; the
chain rule to F is closed-form, checked against tensortrax's derivatives in F). What is
ours: the energy of each continuum model written once for any law of :mod:`mechanics.laws`
(:mod:`.laws`), the pressure terms of the mixed forms, the supports and dead loads, the
Newton system the shared statics (:mod:`reference_fem.statics`) drives (:mod:`.problem`),
and the equations of one time step, with the consistent mass, for the shared continuum
stepper (:mod:`.dynamic_problem`).

Offered: quadrilateral (2D) and hexahedral (3D) cells of degree 2 (Q2, or Q2/Q1
Taylor-Hood with a pressure field), static and dynamic analyses; plane strain (mixed or
penalty), incompressible plane stress (F33 = 1/det F), 3D (mixed or penalty).
"""


def version() -> str:
    import felupe

    return felupe.__version__


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
