"""The continuum's gold data: the converged DOLFINx values of the paper's two examples that
the tests compare against without dolfinx, the tables of reports/reference_fem.md drawn from
them, and the commands that make both (``python -m studies continuum``, :mod:`.cli`).

- :mod:`.cantilever`: the static cantilever's refinement sequences and Richardson values,
  2D (tests/gold/fem_cantilever.json) and the 3D beam (fem_cantilever_3d.json);
- :mod:`.cantilever_tables`: the cantilever gold file's tables (never a solver call);
- :mod:`.pendulum_timing`: the pendulum gold's base scenes on both continuum codes, their
  wall times and tips;
- :mod:`.pendulum`: the pendulum's gold (tests/gold/fem_pendulum.json: scenes, step and mesh
  convergence, tables).

Study code, not the continuum solver: it drives :mod:`reference_fem` (scene -> record,
refinement studies) and writes files, and reference_fem imports none of it.
"""
