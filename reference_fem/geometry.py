"""The beam's geometry in gmsh: a structured (transfinite) mesh of a rectangle.

[0, L] x [-h/2, h/2], nx cells along x and ny across the height; "quadrilateral"
recombines the transfinite triangles into quads, "triangle" keeps two per quad with
alternating diagonals (no preferred direction). With ny even, the free-end centre
point (L, 0) and the left centre point (0, 0) are mesh vertices.
"""
from __future__ import annotations

import contextlib
import threading

import gmsh

_LOCK = threading.Lock()  # gmsh is a global state machine


@contextlib.contextmanager
def structured_rectangle(length: float, height: float, nx: int, ny: int, cell: str):
    """Yield ``gmsh.model`` holding the meshed rectangle (physical surface 1)."""
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
