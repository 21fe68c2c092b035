"""The checks an element's card runs on it: the contract checks (:mod:`.element`: nodality,
reference state, force and tangent, rigid motions, patch tests, mass, conformity), the rank
tests that choose its default quadrature (:mod:`.rank`), and the beam theories its
convergence is read against (:mod:`.beam_theory`)."""
