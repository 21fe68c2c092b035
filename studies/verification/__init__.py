"""Verification: closed forms and published references, the continuum references and their agreement,
manufactured solutions, the hard loads and the integrators' stability."""
