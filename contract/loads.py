"""What a load and a support of a scene are, once, for every solver.

A scene names its loads and supports (:mod:`contract.scene`); each solver applies them
(ANCF: :mod:`ancf.kinematics.section.model`, :mod:`ancf.core.mesh`; the continuum: the backends of
:mod:`reference_fem`), and each states here what it applies, so that the two models of a
scene carry the same load on the same support:

- **the end load** ``loads.tip_force = [Fx, Fy]`` (N, its resultant) is a dead traction
  uniform over the free end face x = L: t = F / (h w) (Pa) at every point of the face,
  :func:`end_traction`. ANCF takes its exact virtual work, f = integral over the face of
  N(L, y)^T t w dy (a Gauss rule across the thickness exact for the element's degree in
  y); the continuum integrates the same traction over its end facets. It is not a point
  load on the centre line: for an element whose section is richer than linear in y the two
  differ (the traction does work on r_yy, and a point load indents a continuum-like section
  under the very point where the tip is read);
- **the end moment** ``loads.end_moment = M`` (N m, counter-clockwise positive) is a
  conservative couple on the rotation of the free end face: its potential is -M theta,
  theta the angle of the face's first moment

      d = int_face r(L, y) y dA / int_face y^2 dA,     theta = atan2(-d_x, d_y)

  (:func:`mechanics.end_rotation.face_rotation`; d = (0, 1) in the reference state, and for a face that stays
  straight, d points along it). d is linear in the displacements, so the couple's force
  is M dtheta/dd . dd/du and its tangent M (dd/du)^T d2theta/dd2 (dd/du)
  (:func:`mechanics.end_rotation.rotation_derivatives`, a rank-2 term on the face's unknowns), in every solver:
  ANCF integrates d exactly over its section polynomial (for an element linear in y,
  d = r_y(L)); the continuum assembles d over its end facets. Unlike a dead linear
  traction, whose moment falls as M cos(theta) and can never turn the end past 90
  degrees, the couple keeps its moment at any rotation: a cantilever with
  M = 2 pi EI / L rolls up into a full circle. theta is continued along the load path
  (:func:`mechanics.end_rotation.continued`), so a rotation past pi is not folded back. Static scenes only;
- **the supports** at x = 0 (:data:`SUPPORTS`): ``clamp`` fixes the end face (ANCF: r and
  every y-derivative kind of the first node, or with ``clamp = "all"`` every nodal
  coordinate; the continuum: every displacement component on the face); ``pin`` is the
  paper's point pin at the face centre (0, 0), free to turn: a point support, singular in
  the 2D continuum (its local compliance grows as the mesh is refined, slowly, like the
  logarithm of the cell size), so a continuum pendulum on it has no mesh limit, only
  error bars; ``hinge`` holds the face straight through its fixed centre, free to turn
  and to stretch: r(0, y) = y a for one free vector a (ANCF: r and every y-derivative
  kind of order two or more fixed, r_y free: for an element linear in y it is the pin;
  the continuum: the face's displacements eliminated for the two components of a), a
  support with a mesh limit; ``slide`` holds the face on the plane x = 0 and free along it
  (u_x = 0 over the face, u_y = 0 at its centre): the support of homogeneous uniaxial
  tension, under which the face contracts freely.

A cable (ANCF ``HC2n-8``, ``kinematics = "cable"``: a centre line whose section is the
segment r + Y n, n the unit normal of r_x) takes the same definitions on that section: the
end load's work is F . delta r(L) (the uniform traction's, int Y dY = 0), the end face's
first moment is n(L), so d = R90 r_x(L) (its length, the stretch, does not enter theta); the
``clamp`` fixes r and the direction of r_x (``clamp = "all"``: r and r_x), ``pin`` and
``hinge`` fix r (its section is straight and free to stretch), and ``slide`` is the clamp
(the section held on x = 0 fixes r_x's direction, its centre held fixes r).
"""
from __future__ import annotations

import numpy as np

SUPPORTS = {
    "clamp": "the end face x = 0 fixed",
    "pin": "the face centre (0, 0) fixed, the face free to turn (a point support: singular in the continuum)",
    "hinge": "the face kept straight through its fixed centre, free to turn and to stretch: r(0, y) = y a",
    "slide": "the face held on the plane x = 0 (u_x = 0), free along it but for its centre (u_y = 0 there)",
}


def end_traction(tip_force, height: float, width: float) -> np.ndarray:
    """The traction (Pa) uniform over the free end face whose resultant is ``tip_force``
    (N): F / (h w)."""
    return np.asarray(tip_force, float) / (height * width)


def face_moment_weight(height: float) -> float:
    """1 / int y^2 dy over the face (1/m^3, per unit width): d = this x int r(L, y) y dy."""
    return 12.0 / height ** 3
