"""The beam's geometry: its domain as a structured gmsh mesh, and where the supports, the
loads and the tip are.

:class:`PlaneGeometry` (:data:`PLANE`) is the 2D beam [0, L] x [-h/2, h/2] per unit
width: nx cells along x and ny across the height; "quadrilateral" recombines the
transfinite triangles into quads, "triangle" keeps two per quad with alternating
diagonals (no preferred direction). With ny even, the free-end centre point (L, 0)
and the left centre point (0, 0) are mesh vertices. Energies and forces of the 2D
problem are per unit width; :meth:`Geometry.width_factor` turns them into the full
beam's. No dolfinx here (gmsh is imported when a mesh is built).
"""
from __future__ import annotations

import contextlib
import threading

import numpy as np

_LOCK = threading.Lock()  # gmsh is a global state machine


@contextlib.contextmanager
def structured_rectangle(length: float, height: float, nx: int, ny: int, cell: str):
    """Yield ``gmsh.model`` holding the meshed rectangle (physical surface 1)."""
    import gmsh

    if cell not in ("quadrilateral", "triangle"):
        raise ValueError(f"cell {cell!r}; allowed: 'quadrilateral', 'triangle'")
    with _LOCK:
        gmsh.initialize()
        try:
            gmsh.option.setNumber("General.Terminal", 0)
            gmsh.model.add("beam")
            surface = gmsh.model.occ.addRectangle(0.0, -height / 2, 0.0, length, height)
            gmsh.model.occ.synchronize()
            for _, curve in gmsh.model.getBoundary([(2, surface)], oriented=False):
                x0, _, _ = gmsh.model.occ.getCenterOfMass(1, curve)
                vertical = min(abs(x0), abs(x0 - length)) < 1e-9 * length
                gmsh.model.mesh.setTransfiniteCurve(curve, (ny if vertical else nx) + 1)
            gmsh.model.mesh.setTransfiniteSurface(surface, "Alternate")
            if cell == "quadrilateral":
                gmsh.model.mesh.setRecombine(2, surface)
            gmsh.model.addPhysicalGroup(2, [surface], 1)
            gmsh.model.mesh.generate(2)
            yield gmsh.model
        finally:
            gmsh.finalize()


class Geometry:
    """Where things are on the beam (x along the beam, y up, the left end at x = 0)."""
    gdim = 2

    def mesh(self, beam, settings):
        raise NotImplementedError

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

    def mesh(self, beam, settings):
        from . import dolfinx_backend as backend

        return backend.rectangle_mesh(beam.length, beam.height, settings.cells_length,
                                      settings.cells_height, settings.cell)

    def pin(self, beam):
        tol = 1e-9 * beam.length
        return lambda x: (np.abs(x[0]) < tol) & (np.abs(x[1]) < tol)


PLANE = PlaneGeometry()
