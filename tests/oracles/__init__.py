"""Test oracles: second routes to what a built-in piece computes, written apart from it (in
numpy, with their own loops), that the tests hold the piece equal to.

- :mod:`.assumed_membrane`: the assumed-strain prototype HB2n-20xypm was built from
  (tests/test_hb2n_20xypm.py, tests/test_example_assumed_membrane.py); run as a script,
  ``.venv/bin/python -m tests.oracles.assumed_membrane``, it prints its finding's tables.
"""
