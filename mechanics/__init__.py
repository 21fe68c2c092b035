"""What both solvers run: the rules of mechanics that are not one solver's business.

- :mod:`mechanics.time_loop`: the one implicit time loop (landing on output times,
  rejection and retry, the energy check, the counters, the dynamic record keys);
- :mod:`mechanics.load_path`: the one static load-path rule (adaptive increments);
- :mod:`mechanics.end_rotation`: the end face's rotation, its continuation along a load path
  and its derivatives, which every solver's couple needs.

It imports only :mod:`contract` and numpy; ``ancf`` and ``reference_fem`` build on it and
never on each other.
"""
