"""Other people's solvers through the harness: a declaration file (:mod:`.declaration`),
the protocol that runs it and keys its records (:mod:`.protocol`)."""
