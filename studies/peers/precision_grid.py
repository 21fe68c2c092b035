"""The work-precision bench's grid and scenes (:mod:`studies.peers.work_precision` runs it,
:mod:`studies.peers.precision_report` draws its records): one place for both."""
STEPS_PER_OUTPUT = (10, 20, 40, 80, 160, 320)       # dt = 0.1 s / k
COUNTS = (2, 4, 8, 16, 32, 64)
ACCURACIES = (0.01, 0.003, 0.001)     # 0.3 % added after the thick scene's run: its floors lie between 1 % and 0.1 %
NAME = "peers-work-precision"
SCENE = "pendulum"          # the default scene
# scene -> cross-section height (m) and what its reference is
SCENES = {"pendulum": {"height": 0.005, "title": "the paper's slender pendulum, h = 5 mm (L / h = 70)",
                       "reference": "the converged continuum plane-stress Yeoh pendulum (tests/gold/fem_pendulum.json)"},
          "thick": {"height": 0.020, "title": "thick pendulum, h = 20 mm (L / h = 17.5)",
                    "reference": "the continuum plane-stress Yeoh pendulum with h = 20 mm "
                                 "(data/peers/thick-pendulum-reference.json, studies.peers.thick_reference: 8, 16 "
                                 "and 32 Q2 cells across; the tip moves by the same 0.14 mm at each halving, the point "
                                 "pin's logarithmic singularity, so the reference is the 16-cell run, a 1.25 mm pin as "
                                 "in the slender pendulum's gold, and its estimate is the time error plus one pin "
                                 "halving)"}}
# The same rule for both sides: Exudyn's fixed-step run has no energy check, so ours runs
# without its guard too (a run that gains energy shows it in its error, not by stopping).
ENERGY_GUARD = "none"
MIN_REPEATS = 5


def elements() -> list[str]:
    """Our elements on the diagram: every registered one that runs plane stress (as every
    run of ours here), but one that locks; the hyperelastic cable HC2n-8 among them (the
    peer's kinematics, r and r_x at two nodes, with the law's exact uniaxial energy)."""
    from ancf.elements import select

    return select(without=["locking"], running=["plane-stress"])


# The cable's runs, by the label its records carry as their element -> its Newton
# (exudyn_pendulum.py --newton). "linear" solves each step's equations linearised at the
# predictor, once, with no convergence test: Exudyn offers it (newton.active =
# False), and on this diagram a setting counts by the error it reaches, so the cable's
# cheapest run at an accuracy is taken over both (measured 2026-11-27, thick scene, 2
# cables, 10 ms: 50 linear solves against 385 Newton iterations, 0.6 of the time, error
# 0.57 % against 0.29 %).
CABLE_SETTINGS = {"ANCFCable2D": "modified", "ANCFCable2D-linear": "linear"}


# Our runs likewise, by the suffix their records' element carries -> the scene's [analysis]
# settings it sets: our defaults (chord Newton to rtol 1e-8) and the loosest Newton
# tolerance a scene accepts (contract.scene.NEWTON_RTOL), where a step stops after its first
# correction whenever that leaves the residual below 1e-3 (|f_ext| + |M a_n|) (measured 2026-11-27:
# thick, 2 x HB2n-20xyp, 10 ms, 70 iterations against 264, error 0.58 % against 0.62 %; at
# 5 ms and below every point's error within 3 % of the defaults').
# " (linear)": one solve per step and no convergence test, as the cable's linear mode (its
# state's det F and the energies still checked; ancf.solvers.compiled_steps).
OUR_SETTINGS = {"": {}, " (rtol 1e-3)": {"newton_rtol": 1e-3}, " (linear)": {"newton": "linear"}}


def our_element(label: str) -> tuple[str, dict]:
    """(registered element, [analysis] settings) of one of our runs' element label."""
    for suffix, settings in OUR_SETTINGS.items():
        if suffix and label.endswith(suffix):
            return label[: -len(suffix)], settings
    return label, {}


def cable_mode(element: str) -> str:
    """', linear' for a cable run with one linear solve per step, '' for Newton (as the
    tables append it to the cable's runs)."""
    mode = CABLE_SETTINGS.get(element, element)
    return "" if mode == "modified" else f", {mode}"


# The step cost's settings (studies.peers.step_cost times a missed row's deciding run under
# each, the report draws them): the compiled loop's Newtons (contract.scene.NEWTON) at the
# loosest tolerance a scene accepts, and the default: label -> [analysis] settings
MODES = {"chord, rtol 1e-3": {"newton": "chord", "newton_rtol": 1e-3},
         "full, rtol 1e-3": {"newton": "full", "newton_rtol": 1e-3},
         "modified, rtol 1e-3": {"newton": "modified", "newton_rtol": 1e-3},
         "chord, default rtol": {"newton": "chord"},
         "linear": {"newton": "linear"}}
