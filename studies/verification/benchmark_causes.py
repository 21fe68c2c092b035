"""Why the benchmark suite's ANCF misses miss, as measured (:data:`CAUSES`; the sweeps behind
each entry: ``experiments/benchmark_causes.py``), looked up by :func:`cause_of` for the
report's rows (:mod:`studies.verification.benchmark_rows`)."""
from __future__ import annotations


# The cause of each miss of the ANCF elements, measured by small runs around the case: the mesh
# doubled, the rule raised to 5 x 5 (and 8 x 8), the penalty x 10 (experiments/benchmark_causes.py
# re-runs every sweep quoted here). Keys (case kind, element, law, formulation), None for any;
# the most specific entry applies. Signed errors of kappa (bending) and end rotation / phi - 1
# (arc), as measured: "d" elements per h along; "[a, b]" the rule; "C10" the penalty alpha.
_SECTION_2 = ("the quadratic section's own miss of the exact flexure (what a 5 x 5 rule leaves, the same at "
              "twice the elements, as HB2n-20xyp's)")


CAUSES = {
    # HB2n-20xyp / -20xypm: [3, 3] (their default at l_e / h = 0.5), [5, 5], [8, 8] at 2 / 4 / 8 d: neo-Hookean
    # plane stress kappa h 0.2 -0.530 / -0.536 / -0.536 %, 0.5 -2.95 / -3.12 / -3.12 %; plane strain 0.3
    # -0.270 / -0.287 %, Mooney-Rivlin -0.49 / -0.51 %; HB2n-40p (quartic across) 0.000 / -0.003 / +0.024 %.
    # Gent: [3, 3] +0.19 % plane stress / +0.66 % plane strain at 0.2, [5, 5] -0.50 / -0.46 % at 2, 4, 8 d.
    ("bending", "HB2n-20xyp", None, None): "its section, quadratic across (y^2 and x y^2: the thickness stretch "
                                           "linear in y), misses the exact flexure, whose section is no polynomial "
                                           "(about the same with twice and four times the elements and a 5 x 5 or "
                                           "8 x 8 rule; Gent: its 3 points across leave kappa above the exact, "
                                           "5 x 5 points below it as for the other laws)",
    ("bending", "HB2n-20xypm", None, None): "its section, quadratic across (y^2 and x y^2: the thickness stretch "
                                            "linear in y), misses the exact flexure, whose section is no "
                                            "polynomial (about the same with twice and four times the elements "
                                            "and a 5 x 5 or 8 x 8 rule; Gent: its 3 points across leave kappa "
                                            "above the exact, 5 x 5 points below it as for the other laws)",
    # HB2n-40p / -60p: Gent plane strain at 0.2 +2.075 % at 2, 4, 8 d and with [5, 5] and [8, 8] (HB2n-40p); HB2n-40p
    # with y^3 and x y^3 added to its pressure (an element registered by the measuring script): Gent 0.1 / 0.2
    # +0.022 / +0.058 % (as is: +0.169 / +2.075 %), neo-Hookean 0.3 +0.021 % (+0.024 %).
    ("bending", "HB2n-40p", "gent", "plane-strain"): "its element pressure, quadratic in y, leaves J - 1 free in y^3, "
                                                     "which Gent near its lock sees (a pressure cubic in y removes "
                                                     "the miss; the same with twice the elements and a richer rule)",
    ("bending", "HB2n-60p", "gent", "plane-strain"): "its element pressure, quadratic in y, leaves J - 1 free in y^3, "
                                                     "which Gent near its lock sees (a pressure cubic in y removes "
                                                     "the miss)",
    # LB2n-12 plane stress: -24.94 / -24.93 / -24.92 % at 2 / 4 / 8 d (NH 0.2), [5, 5] -25.22 / -25.21 % at 2 / 4 d;
    # every law -23.7 to -26.4 % (Gent -16 to -24 %), the same at 2 and 4 d.
    ("bending", "LB2n-12", None, "plane-stress"): "Poisson locking: its section is linear across (r_y the same at "
                                                  "every y), so the thickness stretch cannot vary across and the "
                                                  "strip bends as one held from contracting, E / (1 - nu^2) = 4/3 E "
                                                  "at small strain (kappa 3/4 of the exact; about the same with twice "
                                                  "and four times the elements and a 5 x 5 rule)",
    # LB2n-12 plane strain: kappa / exact = 7.9e-3 / 7.9e-4 / 7.9e-5 at alpha = 1e3 / 1e4 / 1e5 C10 (NH 0.2; every
    # law alike), the same at 1 to 8 d and with [5, 5].
    ("bending", "LB2n-12", None, "plane-strain"): "volumetric locking: its linear section cannot bend at constant "
                                                  "volume, so the penalty carries the couple and kappa falls as "
                                                  "1 / alpha (10 x alpha: 10 x smaller; the same with 1 to 8 "
                                                  "elements per h and a 5 x 5 rule)",
    # LB2n-12 arc: end rotation / phi 0.7496-0.7503 (phi = 1) and 0.735-0.760 (2 pi) at 32 elements, 0.750 at 64
    # and 128, the same with [5, 5].
    ("arc", "LB2n-12", None, None): "Poisson locking of its linear section (as in its pure bending): the end turns "
                                    "about 3/4 of phi at every L/h, with 32, 64 or 128 elements and a 5 x 5 rule",
    # HB2n-12 arc, end rotation / phi at l_e / h = 0.78 / 1.6 / 3.1 / 6.3 (32 elements, L/h 25 to 200; phi = 1):
    # 0.997 / 0.987 / 0.955 / 0.883; with 64 elements 0.9995 / 0.9967 / 0.9871 / 0.9553 at L/h 25 / 50 / 100 /
    # 200 (l_e / h halved: the values of half that L/h at 32); with [5, 5] the same to 4 digits.
    ("arc", "HB2n-12", None, None): "locking set by l_e / h: its end turns short of phi by an amount that depends "
                                    "on l_e / h alone (the same at 64 elements as at 32 with half the L/h) and not "
                                    "on the rule (5 x 5 the same); its x^2 + y^2 mode ties the section's r_yy to "
                                    "the centre line's r_xx",
    # HB3n-12 arc: end rotation / phi 0.958 / 0.888 / 0.809 / 0.768 at l_e / h = 0.78 / 1.6 / 3.1 / 6.3 (phi = 1),
    # 0.9578 at 64 elements and L/h 50 (l_e / h 0.78), [5, 5] the same: toward LB2n-12's 3/4.
    ("arc", "HB3n-12", None, None): "locking set by l_e / h: its end turns short of phi by an amount that depends "
                                    "on l_e / h alone (the same at 64 elements as at 32 with half the L/h), not on "
                                    "the rule (5 x 5 the same), toward the linear section's 3/4 as l_e / h grows; "
                                    "its x^2 + y^2 mode ties the section's r_yy to the centre line's r_xx",
    # HB2n-16 arc (misses at L/h 100, 200): phi = 1, L/h 200: distance 6.4e-4 / 4.3e-5 / 3.7e-6 at 32 / 64 / 128
    # elements; L/h 100: 1.7e-4 / 1.5e-5; phi = 2 pi, L/h 200: 4.8e-2 / 3.4e-3 / 7.0e-5; [5, 5] the same at 32.
    ("arc", "HB2n-16", None, None): "discretisation at l_e / h of 3 and more: the distance falls 10 x and more with "
                                    "twice the elements and passes with four times; a 5 x 5 rule changes nothing",
    # HB2n-16 plane stress, [3, 2] (its default at l_e / h = 0.5) / [5, 5] at 2 d / [5, 5] at 4 d: NH 0.2 +0.22 /
    # -0.60 / -0.55 %, 0.5 +1.23 / -3.47 / -3.20 %; Mooney-Rivlin and Yeoh alike (HB2n-20xyp: -0.54, -3.12 %).
    ("bending", "HB2n-16", None, "plane-stress"): "its rule's 2 points across (its default at l_e / h = 0.5) soften "
                                                  "it past the exact by more than " + _SECTION_2,
    # Gent plane stress 0.1 / 0.2: [3, 2] +2.07 / +8.45 %, [3, 3] -0.10 / +0.14 %, [5, 5] -0.15 / -0.55 % (2 and 4 d).
    ("bending", "HB2n-16", "gent", "plane-stress"): "its rule's 2 points across do not see the outer fibres' "
                                                    "stiffening near Gent's lock (with 5 x 5 points it is left with "
                                                    + _SECTION_2 + ")",
    # HB2n-16 plane strain, [3, 2]: NH 0.2 +0.76 / +0.80 / +0.81 % at 2 / 4 / 8 d, +0.94 / +0.76 / +0.74 % at
    # alpha = 1e3 / 1e4 / 1e5 C10; 0.3 +1.64 %; [3, 3] or [5, 5]: -64 % (NH 0.2), -37 / -64 / -78 % at 1e3 / 1e4 /
    # 1e5 C10, the same at 4 and 8 d. Gent 0.1 / 0.2: [3, 2] +2.9 / +11.5 %, [5, 5] -47 / -60 %.
    ("bending", "HB2n-16", None, "plane-strain"): "its rule's 2 points across: with 3 or more points across its "
                                                  "section, which has no pressure field, locks (kappa far below the "
                                                  "exact, the further the higher the penalty); the 2 points relieve the "
                                                  "lock and leave it too soft, the same with twice and four times "
                                                  "the elements and at 10 x the penalty",
    ("bending", "HB2n-16", "gent", "plane-strain"): "its rule's 2 points across: with 3 or more points across its "
                                                    "section, which has no pressure field, locks; the 2 points "
                                                    "relieve the lock and do not see the outer fibres' stiffening "
                                                    "near Gent's lock (too soft, the same with twice the elements "
                                                    "and at 10 x the penalty)",
    # HB2n-12 plane stress, [3, 2] (default) / [5, 5] at 2 d / [5, 5] at 4 d: NH 0.5 +0.32 / -2.23 / -1.28 %;
    # Mooney-Rivlin 0.2 +0.13 / -0.42 / -0.19 %, 0.5 +1.18 / -1.99 / -1.00 %; Yeoh 0.2 +0.15 / -0.47 / -0.24 %,
    # 0.5 +1.17 / -2.25 / -1.34 %.
    ("bending", "HB2n-12", None, "plane-stress"): "discretisation of the non-conforming element at 2 elements per "
                                                  "h, which its rule's 2 points across turn into a softening: "
                                                  "fully integrated (5 x 5) its kappa is too small by an error that "
                                                  "about halves with twice the elements",
    # Gent 0.1 / 0.2: [3, 2] +1.90 / +8.20 %, [3, 3] -0.17 / +0.15 %, [5, 5] -0.21 / -0.48 % at 2 d, -0.09 / -0.31 %
    # at 4 d.
    ("bending", "HB2n-12", "gent", "plane-stress"): "its rule's 2 points across do not see the outer fibres' "
                                                    "stiffening near Gent's lock (fully integrated, 5 x 5, the error "
                                                    "is a tenth of it and falls with the mesh)",
    # HB2n-12 plane strain, [3, 2] at 2 d: NH 0.2 -2.75 % (alpha 1e4 C10), -7.40 % (1e5), +0.06 % (1e3); at 4 / 8 d
    # +0.44 / +0.76 %; NH 0.3 -8.3 % (1e4), -10.7 % (1e5), +0.31 % at 4 d; Mooney-Rivlin and Yeoh alike; [5, 5]:
    # -16 to -24 % at 2 d.
    ("bending", "HB2n-12", None, "plane-strain"): "partial volumetric locking at 2 elements per h: kappa too small "
                                                  "by an error that grows with the penalty (10 x alpha: about 3 x at "
                                                  "kappa h 0.2) and turns into a softening like HB2n-16's with twice "
                                                  "and four times the elements; fully integrated (5 x 5) it locks",
    # Gent 0.1 / 0.2: +2.50 / +8.08 % (1e4 C10), +0.75 / +1.89 % (1e5), +2.83 / +11.2 % at 4 d; [5, 5] -19 / -34 %.
    ("bending", "HB2n-12", "gent", "plane-strain"): "its rule's 2 points across do not see the outer fibres' "
                                                    "stiffening near Gent's lock (too soft, more so with twice the "
                                                    "elements), less its partial volumetric locking (10 x alpha: "
                                                    "kappa a third to a quarter as far off); fully integrated it "
                                                    "locks",
    # HB3n-12 plane stress, [3, 2] (default) / [5, 5] at 2 d / [5, 5] at 4 d: NH 0.2 -1.80 / -2.20 / -0.71 %, 0.5
    # -1.32 / -3.65 / -1.73 %; Mooney-Rivlin and Yeoh alike; [5, 5] at 8 d (NH 0.2) -0.30 %.
    ("bending", "HB3n-12", None, "plane-stress"): "discretisation of the non-conforming element at 2 elements per "
                                                  "h: fully integrated (5 x 5) its kappa is too small by an error "
                                                  "that falls about 2 to 3 x with twice the elements; its rule's 2 "
                                                  "points across soften it",
    # Gent 0.1 / 0.2: [3, 2] +0.13 / +6.52 %, [5, 5] -1.85 / -1.71 % at 2 d, -0.52 / -0.64 % at 4 d.
    ("bending", "HB3n-12", "gent", "plane-stress"): "discretisation of the non-conforming element at 2 elements per "
                                                    "h (fully integrated its kappa is too small by an error that "
                                                    "falls about 3 x with twice the elements) and its rule's 2 points "
                                                    "across, which do not see the outer fibres' stiffening near "
                                                    "Gent's lock",
    # HB3n-12 plane strain, [3, 2]: NH 0.2 +0.59 / +0.80 / +0.81 % at 2 / 4 / 8 d (HB2n-16: +0.76 / +0.80 / +0.81 %),
    # +0.96 / +0.59 / -1.10 % at alpha 1e3 / 1e4 / 1e5 C10; 0.3 +0.74 % (1e4), -5.5 % (1e5), +1.70 % at 4 d;
    # Mooney-Rivlin, Yeoh alike; [5, 5] -17 to -22 % at 2 d. Gent 0.1 / 0.2 +2.9 / +11.4 %, 1e5: +2.7 / +9.7 %.
    ("bending", "HB3n-12", None, "plane-strain"): "its rule's 2 points across, as HB2n-16's: fully integrated "
                                                  "(5 x 5) it locks; the 2 points relieve the lock and leave it too "
                                                  "soft (HB2n-16's softening with twice the elements), less a "
                                                  "partial lock that grows with the penalty (10 x alpha: kappa "
                                                  "below the exact)",
    ("bending", "HB3n-12", "gent", "plane-strain"): "its rule's 2 points across, as HB2n-16's: fully integrated "
                                                    "(5 x 5) it locks; the 2 points relieve the lock and do not see "
                                                    "the outer fibres' stiffening near Gent's lock (too soft, the "
                                                    "same with twice the elements and nearly so at 10 x the "
                                                    "penalty)",
}


def cause_of(kind: str, solver: str, law: str, form: str) -> str:
    """The measured cause of a miss of ``solver`` in a case of ``kind`` (:data:`CAUSES`), "" if none."""
    for key in ((kind, solver, law, form), (kind, solver, None, form), (kind, solver, law, None),
                (kind, solver, None, None)):
        if key in CAUSES:
            return CAUSES[key]
    return ""
