"""HB2n-60p, the candidate for the plane-stress target of issue 20 (README "An element for
incompressible rubber"): HB2n-40p made quintic along the beam, quartic across, with an element
pressure {1, x, x^2, x^3} x {1, y, y^2}. It began here as an example element; with the
pressure term in the compiled kernels (its penalised solves no longer run on the Python
Newton loop) it is built in: :mod:`ancf.elements` registers it, with its measurements and
rules. This module is kept so that ``--import examples.quintic_pressure`` still works:

    .venv/bin/python -m studies card HB2n-60p
"""
from ancf.elements import ELEMENTS

assert "HB2n-60p" in ELEMENTS
