"""The contract both solvers share: scene files, result records, errors, and the paper.

- :mod:`contract.scene`: a scene file (TOML, SI) loaded and checked for structure and
  types; the names a solver resolves are checked by that solver (``check_names``);
- :mod:`contract.record`: one JSON record per run, the same keys for every solver;
- :mod:`contract.errors`: the one-line errors a user sees (exit status 2);
- :mod:`contract.paper`: the paper's constants, tables and scenes.

It imports no solver: ``ancf`` and ``reference_fem`` build on it, ``studies`` on all three.
"""
