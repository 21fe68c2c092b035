"""Deformed shapes for people: VTK files for ParaView and a frame strip (PNG).

``write_vtk`` samples every element on a small grid in (xi, eta), maps it through the
shape functions and writes one XML UnstructuredGrid (.vtu) of quadrilaterals per state:
the reference geometry with the displacement as point data (the convention of
reference_fem and of FE codes: ParaView's Warp By Vector, scale 1, shows the deformed
beam), plus a .pvd collection indexed by time.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .kinematics.model import ElementModel


def deformed_grid(model: ElementModel, u: np.ndarray, nx: int = 4, ny: int = 2):
    """Points (n, 2) of the deformed beam on an (nx x ny)-cell grid per element, their
    displacements, and the quadrilateral connectivity (m, 4)."""
    m = model.mesh
    xi, eta = np.meshgrid(np.linspace(0, 1, nx + 1), np.linspace(-0.5, 0.5, ny + 1), indexing="ij")
    family = m.element.family                                # the section as its kinematics draws it
    pts = family.section_points(model, u, xi.ravel(), eta.ravel()).reshape(-1, 2)
    disp = pts - family.section_points(model, np.zeros_like(u), xi.ravel(), eta.ravel()).reshape(-1, 2)
    k = np.arange((nx + 1) * (ny + 1)).reshape(nx + 1, ny + 1)
    cell = np.stack([k[:-1, :-1], k[1:, :-1], k[1:, 1:], k[:-1, 1:]], axis=-1).reshape(-1, 4)
    per = (nx + 1) * (ny + 1)
    cells = (cell[None] + per * np.arange(m.n_elements)[:, None, None]).reshape(-1, 4)
    return pts, disp, cells


def _vtu(path: Path, pts, disp, cells) -> None:
    def arr(a, fmt):
        return " ".join(fmt % v for v in np.ravel(a))
    p3 = np.c_[pts, np.zeros(len(pts))]
    d3 = np.c_[disp, np.zeros(len(disp))]
    path.write_text(
        '<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">\n'
        f'<UnstructuredGrid><Piece NumberOfPoints="{len(pts)}" NumberOfCells="{len(cells)}">\n'
        f'<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">{arr(p3, "%.9g")}</DataArray></Points>\n'
        f'<Cells><DataArray type="Int64" Name="connectivity" format="ascii">{arr(cells, "%d")}</DataArray>\n'
        f'<DataArray type="Int64" Name="offsets" format="ascii">{arr(4 * np.arange(1, len(cells) + 1), "%d")}</DataArray>\n'
        f'<DataArray type="UInt8" Name="types" format="ascii">{arr(np.full(len(cells), 9), "%d")}</DataArray></Cells>\n'
        f'<PointData Vectors="displacement"><DataArray type="Float64" Name="displacement" NumberOfComponents="3" '
        f'format="ascii">{arr(d3, "%.9g")}</DataArray></PointData>\n'
        '</Piece></UnstructuredGrid></VTKFile>\n')


def write_vtk(model: ElementModel, states, directory, name: str = "beam") -> Path:
    """One .vtu per (t, u) in ``states`` and a .pvd collection; returns the .pvd path."""
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    entries = []
    for i, (t, u) in enumerate(states):
        f = d / f"{name}_{i:04d}.vtu"
        pts, disp, cells = deformed_grid(model, u)
        _vtu(f, pts - disp, disp, cells)
        entries.append(f'<DataSet timestep="{t:.9g}" part="0" file="{f.name}"/>')
    pvd = d / f"{name}.pvd"
    pvd.write_text('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
                   + "\n".join(entries) + "\n</Collection>\n</VTKFile>\n")
    return pvd


def frame_strip(configurations, path, title: str = "") -> Path:
    """The centre line at each output time on one axes (mm): a PNG of the motion."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4.5))
    cmap = plt.get_cmap("viridis")
    n = max(len(configurations) - 1, 1)
    for i, c in enumerate(configurations):
        ax.plot(np.asarray(c["x"]) * 1e3, np.asarray(c["y"]) * 1e3, color=cmap(i / n), label=f"t = {c['t']:.2f} s")
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(title)
    ax.legend(fontsize=7, loc="best")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return Path(path)
