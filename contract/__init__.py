"""The contract both solvers share: scene files, result records, errors, and the paper.

- :mod:`contract.scene`: a scene file (TOML, SI) loaded and checked for structure and
  types; the names a solver resolves are checked by that solver (``check_names``);
- :mod:`contract.record`: one JSON record per run, the same keys for every solver;
- :mod:`contract.errors`: the one-line errors a user sees (exit status 2);
- :mod:`contract.loads`: what each load and support of a scene is, stated once for every
  solver;
- :mod:`contract.console`: how every command line ends (exit statuses, output paths
  checked before a run, the progress bar), here because it is the one floor that ``ancf``,
  ``reference_fem`` and ``studies`` all stand on and it is mechanics of no kind;
- :mod:`contract.paper`: the paper's constants, tables and scenes.

It imports no solver: ``ancf`` and ``reference_fem`` build on it, ``studies`` on all three.
"""
