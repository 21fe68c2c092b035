"""The beam's geometry: where the supports, the loads and the tip are (no mesher, no
finite elements: every backend builds its own mesh of this domain).

:class:`PlaneGeometry` (:data:`PLANE`) is the 2D beam [0, L] x [-h/2, h/2] per unit
width; energies and forces of the 2D problem are per unit width, and
:meth:`Geometry.width_factor` turns them into the full beam's. :class:`BoxGeometry`
(:data:`BOX`) is the real beam [0, L] x [-h/2, h/2] x [-w/2, w/2] (``fem.model = "3d"``);
its tip is the centre (L, 0, 0) of the free end face, its pin the line (0, 0, z) across
the width at the left end's mid-height.
"""
from __future__ import annotations

import numpy as np


class Geometry:
    """Where things are on the beam (x along the beam, y up, the left end at x = 0)."""
    gdim = 2

    def tip_point(self, beam) -> np.ndarray:
        """The free-end centre point, reference coordinates."""
        return np.array([beam.length, 0.0] + [0.0] * (self.gdim - 2))

    def line_points(self, beam, n: int) -> np.ndarray:
        """n points of the centre line, reference coordinates (n, gdim)."""
        pts = np.zeros((n, self.gdim))
        pts[:, 0] = np.linspace(0.0, beam.length, n)
        return pts

    def vector(self, v) -> np.ndarray:
        """A scene's in-plane vector (gravity, tip force) in the geometry's dimension."""
        return np.concatenate([np.asarray(v, float), np.zeros(self.gdim - 2)])

    def width_factor(self, beam) -> float:
        """Factor from the problem's energies to the full beam's."""
        return beam.width if self.gdim == 2 else 1.0

    def at_left(self, beam):
        tol = 1e-9 * beam.length
        return lambda x: np.abs(x[0]) < tol

    def at_right(self, beam):
        tol = 1e-9 * beam.length
        return lambda x: np.abs(x[0] - beam.length) < tol

    def pin(self, beam):
        """The pinned points of the left end (a locator of mesh nodes)."""
        raise NotImplementedError

    pin_note = ""


class PlaneGeometry(Geometry):
    gdim = 2
    pin_note = ("the node at the centre (0, 0) of the left face: both displacement components "
                "zero there; the face is otherwise free to rotate and deform")

    def pin(self, beam):
        tol = 1e-9 * beam.length
        return lambda x: (np.abs(x[0]) < tol) & (np.abs(x[1]) < tol)


PLANE = PlaneGeometry()


class BoxGeometry(Geometry):
    gdim = 3
    pin_note = ("the line (0, 0, z) across the width at the left face's mid-height: every "
                "displacement component zero at its nodes (a pin gripping the whole width; the "
                "face turns about it); the line load's field is logarithmically singular, so "
                "the local compliance grows slowly with refinement, as the 2D point pin's")

    def pin(self, beam):
        tol = 1e-9 * beam.length
        return lambda x: (np.abs(x[0]) < tol) & (np.abs(x[1]) < tol)

    def sides(self, beam):
        """The two faces z = +-w/2."""
        tol = 1e-9 * beam.length
        return lambda x: np.abs(np.abs(x[2]) - beam.width / 2) < tol


BOX = BoxGeometry()


def geometry_for(model: str) -> Geometry:
    """The geometry of a continuum model ("plane-strain", "plane-stress": :data:`PLANE`;
    "3d": :data:`BOX`)."""
    return BOX if model == "3d" else PLANE


HINGE_NOTE = ("hinge: the left face kept straight through its fixed centre, u(0, Y) = Y a (a free "
              "in-plane vector: the face turns and stretches), exactly, by eliminating the face's "
              "displacement unknowns for the two of a (u = T w_r: tangent T^T K T, residual T^T R; "
              "pressure unknowns untouched); a support with a mesh limit")
END_MOMENT_NOTE = ("end moment: the couple -M theta, theta = atan2(-d_x, d_y) of the end face's first "
                   "moment d = int (X + u) Y dA / int Y^2 dA (linear in u: d = d0 + G^T u), continued "
                   "along the load path; its rank-2 tangent -t M G H G^T enters the Newton solve exactly")


def support_note(left: str, geometry: Geometry) -> str:
    """How the continuum models the support ``left`` (a record's ``pin`` note)."""
    return {"pin": geometry.pin_note, "hinge": HINGE_NOTE,
            "slide": "slide: u_x = 0 over the face x = 0, u_y = 0 at its centre node",
            }.get(left, "clamp: the whole face x = 0 fixed")


def check_support(left: str, geometry: Geometry, settings) -> None:
    """A support this continuum can apply (:data:`contract.loads.SUPPORTS`), or a
    SceneError naming what it cannot: ``pin`` and ``slide`` hold the face centre's node,
    so the mesh needs an even number of cells across; the 3D model offers ``clamp`` and
    ``pin`` only. The ``hinge`` needs no centre node (the face's nodes are slaved to its
    top node, u = (Y / Y_top) u_top: any number of cells across)."""
    from contract.errors import SceneError

    if left in ("slide", "hinge") and geometry.gdim == 3:
        raise SceneError(f"supports.left: \"{left}\" is not offered by the 3D continuum model "
                         "(fem.model = \"3d\"); allowed there: clamp, pin")
    if left in ("pin", "slide") and settings.cells_height % 2:
        raise SceneError(f"fem.cells_height: supports.left = \"{left}\" holds the node at the centre of the "
                         "left face; needs an even number of cells across")
