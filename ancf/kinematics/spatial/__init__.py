"""Spatial (3D) ANCF beam elements: the element layer of the third kinematics.

A spatial element is data (:class:`.spec.SpatialSpec`): basis polynomials in (x, y, z), node
positions along the beam and the nodal coordinate kinds at each node (r, r_x, r_y, r_z,
r_yy, r_yz, r_zz, ...); its shape functions are derived from them (:mod:`.spec`). Its energy
is the registered law's on the full deformation gradient, F = sum_k q_k (x) grad N_k, with
nothing planar in between (:mod:`.energy`: the law's psi(I1bar, I2bar) plus the volumetric
penalty alpha/2 (J - 1)^2, stress and tangent by second-order forward derivatives in the
invariants, the same law function the planar solver and the continuum codes evaluate).
:mod:`.beam` assembles a straight beam of them: energy, internal force and tangent (by sum
factorisation over the section and along the beam, :mod:`.product`).

Built in (:mod:`.elements`, :data:`SPATIAL_ELEMENTS`): the fully parameterised 3243, the
3333 and the 3363 (names as in Obrezkov et al. 2022), each with its source, the 3363p of
this harness (the 3363 with an element pressure) and its lock-free HS2n-72p (cubic Hermite
along, the complete quadratic section, the element pressure {1, x} x {1, y, z}; the family
:func:`.elements.hermite_section`) and HS2n-96p (HS2n-72p's section with the torsion warping
modes y^3 z and y z^3: within 0.1 % of the continuum on the clamped cantilever under its
weight and under an end force once the clamp's end zone is resolved, 0.24 % stiff in
torsion) and HS2n-132p (with degree 6's odd-odd modes too: within 0.1 % in small-twist
torsion, 0.16 % soft at half a turn) and HS2n-180p (the complete cubic section, degree 6's
warping and the complete quadratic element pressure: within 0.1 % of the continuum at half a
turn for three laws and under an end force, converging at a measured rate, 0.2 % stiff in the
axial force and bending moment at a plate turned about all three axes) and HS2n-216p (its
section completed to the quartic, for that case). Each has a default rule chosen by the rank
test (:mod:`.rank`). :mod:`.beam` takes equal or graded elements
(graded from one end or from both); :mod:`.statics` holds the supports (the clamp, the
free-warping support of torsion), gravity, a dead traction on either end face, a small-twist
torque, a rigid plate turned to a given rotation and its reaction, and the static solve;
``experiments/spatial_cantilever`` and ``experiments/spatial_end_force`` measure the elements
against the 3D continuum under the weight and under an end force,
``experiments/spatial_torsion`` against Saint-Venant's torsion
(``tests/test_spatial_torsion.py``: the torsion constants and every element's uniform twist)
and ``experiments/spatial_finite_torsion`` against two continuum codes at half a turn.

What is here is the element layer and its contract checks (``tests/test_spatial_elements.py``:
shape functions, patch and rigid-motion tests, Taylor tests, the plane-strain limit against
the planar formulation, the rank test of the default rule, the force's round-off floor). Not
here yet, and so not in any scene: the spatial family's registration as a kinematics of
:mod:`ancf.kinematics`, its supports, end face and loads, the 3D scene keys of
:mod:`contract`, the dynamic solves and a compiled assembly.
"""
from __future__ import annotations

from .elements import SPATIAL_ELEMENTS, get_spatial_element  # noqa: F401
from .spec import SpatialSpec  # noqa: F401
