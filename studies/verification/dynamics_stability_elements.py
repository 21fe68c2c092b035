"""The pendulum's hard cases with each lock-free element: the stability study's cases and
report (:mod:`studies.verification.dynamics_stability`) on this grid."""
from __future__ import annotations

from .dynamics_stability import audit, cases, gold_values, report  # noqa: F401  (the study's functions)

STUDY = {
    "name": "stability-elements",
    "title": "Hard cases: integrator stability and energy, the lock-free elements (pendulum)",
    "full": True,
    "grid": {
        "study": "stability-elements",
        # one change at a time from the base pendulum (Yeoh); dt 1 ms: the converged step of
        # 32 x HB2n-12 (Table 4)
        "base": {"law": "yeoh",
                 "formulation": "plane-stress",
                 "element": "HB2n-12",
                 "elements": 16,
                 "dt": 0.001,
                 "t_end": 0.5,
                 "rho_inf": 0.5},
        # every hard case again with each of these: every element but the paper's (whose
        # HB2n-12 is the base)
        "elements": {"registered": {"without": ["paper"]}},
        "integrators": ["generalized-alpha", "arnold-bruls", "newmark", "discrete-gradient"],
        "rho_inf": [0.0, 0.5, 0.8, 1.0],
        "penalty_factors": [10.0, 1000.0, 100000.0],  # alpha = factor x C10
        "penalty_formulations": ["paper", "plane-strain"],
        "long_t_end": 5.0,
        "many_elements": 128,
        "softer": 0.1,
        "stiffer": 2e4,        # near-rigid: C10 = 1.1e10 Pa
        "stiffer_every": 0.005,
        "larger_step": 10,
        "energy_every": 0.01,  # s: output times, where E is sampled
        "long_energy_every": 0.05,
        "timing": {"repeats": 1, "budget_s": 0.0},
    },
    "tiny": {
        "elements": ["HB2n-20xyp"],
        "base": {"law": "yeoh",
                 "formulation": "plane-stress",
                 "element": "HB2n-12",
                 "elements": 4,
                 "dt": 0.001,
                 "t_end": 0.1,
                 "rho_inf": 0.5},
        "rho_inf": [0.0, 1.0],
        "penalty_factors": [10.0, 100000.0],
        "penalty_formulations": ["paper"],
        "long_t_end": 0.3,
        "many_elements": 8,
    },
}
