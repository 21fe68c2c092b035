"""The beam's domain as a structured gmsh mesh (DOLFINx reads gmsh models).

:func:`structured_rectangle` is the 2D beam [0, L] x [-h/2, h/2]: nx cells along x and
ny across the height; "quadrilateral" recombines the transfinite triangles into quads,
"triangle" keeps two per quad with alternating diagonals (no preferred direction). With
ny even, the free-end centre point (L, 0) and the left centre point (0, 0) are mesh
vertices. :func:`structured_box` is the real beam [0, L] x [-h/2, h/2] x [-w/2, w/2]:
nx x ny x nz transfinite hexahedra (or each split into 6 tetrahedra), optionally graded
along x toward the clamp.
"""
from __future__ import annotations

import contextlib
import threading

import numpy as np

_LOCK = threading.Lock()  # gmsh is a global state machine


@contextlib.contextmanager
def _gmsh_model(name: str):
    """A fresh, quiet gmsh session holding one empty model ``name``: yields ``gmsh``;
    finalized on exit (gmsh is global state: one session at a time)."""
    import gmsh

    with _LOCK:
        gmsh.initialize()
        try:
            gmsh.option.setNumber("General.Terminal", 0)
            gmsh.model.add(name)
            yield gmsh
        finally:
            gmsh.finalize()


@contextlib.contextmanager
def structured_rectangle(length: float, height: float, nx: int, ny: int, cell: str):
    """Yield ``gmsh.model`` holding the meshed rectangle (physical surface 1)."""
    if cell not in ("quadrilateral", "triangle"):
        raise ValueError(f"cell {cell!r}; allowed: 'quadrilateral', 'triangle'")
    with _gmsh_model("beam") as gmsh:
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


@contextlib.contextmanager
def structured_box(length: float, height: float, width: float, nx: int, ny: int, nz: int,
                   cell: str, progression: float = 1.0, build: bool = True):
    """Yield ``gmsh.model`` holding the meshed box (physical volume 1); ``build=False``
    (the other MPI ranks) yields the untouched ``gmsh.model``, which dolfinx's
    distribution call wants on every rank. ``progression``: cell-to-cell growth of the
    cell length along x, away from x = 0."""
    if cell not in ("hexahedron", "tetrahedron"):
        raise ValueError(f"cell {cell!r}; allowed: 'hexahedron', 'tetrahedron'")
    if not build:
        import gmsh
        yield gmsh.model
        return
    with _gmsh_model("beam3d") as gmsh:
        volume = gmsh.model.occ.addBox(0.0, -height / 2, -width / 2, length, height, width)
        gmsh.model.occ.synchronize()
        counts = (nx, ny, nz)
        for _, curve in gmsh.model.getEntities(1):
            x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(1, curve)
            d = int(np.argmax([x1 - x0, y1 - y0, z1 - z0]))
            if d == 0 and progression != 1.0:
                a, b = gmsh.model.getBoundary([(1, curve)], oriented=True)
                xa = gmsh.model.getValue(0, abs(a[1]), [])[0]
                xb = gmsh.model.getValue(0, abs(b[1]), [])[0]
                q = progression if xa < xb else 1.0 / progression
                gmsh.model.mesh.setTransfiniteCurve(curve, nx + 1, "Progression", q)
            else:
                gmsh.model.mesh.setTransfiniteCurve(curve, counts[d] + 1)
        for _, surface in gmsh.model.getEntities(2):
            gmsh.model.mesh.setTransfiniteSurface(surface)
            if cell == "hexahedron":
                gmsh.model.mesh.setRecombine(2, surface)
        gmsh.model.mesh.setTransfiniteVolume(volume)
        if cell == "hexahedron":
            gmsh.model.mesh.setRecombine(3, volume)
        gmsh.model.addPhysicalGroup(3, [volume], 1)
        gmsh.model.mesh.generate(3)
        yield gmsh.model
