"""What a load and a support of a scene are, once, for every solver.

A scene names its loads and supports (:mod:`contract.scene`); each solver applies them
(ANCF: :mod:`ancf.beam`, :mod:`ancf.mesh`; the continuum: the backends of
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
- **the supports** at x = 0 (:data:`SUPPORTS`): ``clamp`` fixes the end face (ANCF: r and
  every y-derivative kind of the first node, or with ``clamp = "all"`` every nodal
  coordinate; the continuum: every displacement component on the face); ``pin`` is the
  paper's point pin at the face centre (0, 0), free to turn: a point support, singular in
  the 2D continuum (its local compliance grows as the mesh is refined, slowly, like the
  logarithm of the cell size), so a continuum pendulum on it has no mesh limit, only
  error bars; ``slide`` holds the face on the plane x = 0 and free along it (u_x = 0 over
  the face, u_y = 0 at its centre): the support of homogeneous uniaxial tension, under
  which the face contracts freely.
"""
from __future__ import annotations

import numpy as np

SUPPORTS = {
    "clamp": "the end face x = 0 fixed",
    "pin": "the face centre (0, 0) fixed, the face free to turn (a point support: singular in the continuum)",
    "slide": "the face held on the plane x = 0 (u_x = 0), free along it but for its centre (u_y = 0 there)",
}


def end_traction(tip_force, height: float, width: float) -> np.ndarray:
    """The traction (Pa) uniform over the free end face whose resultant is ``tip_force``
    (N): F / (h w)."""
    return np.asarray(tip_force, float) / (height * width)
