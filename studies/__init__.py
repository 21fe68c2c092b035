"""Studies: cases -> runs -> JSON-line records -> tables and figures in reports/.

The engine (:mod:`studies.engine`) knows no study; what it runs and checks is registered
with it: the solvers every study uses by :mod:`studies.solvers` (imported here, so that
any use of the package has them), a study's own solver by the study's module, the element
card's records and pages by :mod:`studies.design.card`, the peer reports' audit by
:mod:`studies.peers.audit` (all imported here, so that any use of the package has them).
"""
from . import solvers as _solvers  # noqa: F401  (registers the solvers every study uses)
from .design import card as _card  # noqa: F401  (registers the cards' pages and records with the audit and verify)
from .peers import audit as _peers_audit  # noqa: F401  (registers the peer reports' audit)
