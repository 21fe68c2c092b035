"""The scene's ``[fem]`` table: validated here, resolved against the scene's beam.

``contract.scene`` hands the table over raw (``scene.fem``, a dict or None); this module is
the one place that checks it, with the same kind of errors as the scene loader
(:class:`contract.errors.SceneError` naming the field and the allowed values; unknown keys
are rejected). No dolfinx here.

Keys (all optional except ``model`` for ``paper`` scenes):

- ``cells_height`` (int): cells across the height h;
- ``cells_length`` (int) *or* ``aspect`` (cell length / cell height): cells along L;
- ``cell``: "quadrilateral" | "triangle" (2D); "hexahedron" | "tetrahedron" (3D, each
  hexahedron of the structured grid split into 6);
- ``degree`` (int): displacement degree; the pressure (mixed, penalty) is one lower
  (Taylor-Hood Q2/Q1 or P2/P1 by default);
- ``quadrature_degree`` (int): set explicitly, because UFL's estimate for the
  J^(-2/3) terms explodes;
- ``incompressibility``: "mixed" (exact, default) | "penalty" (the scene's
  alpha/2 (J - 1)^2 as a perturbed Lagrangian); plane strain only;
- ``model``: "plane-strain" | "plane-stress"; required for ``paper`` scenes (which
  have no continuum meaning), otherwise it must agree with the scene's formulation.
  "3d": the real beam, length x height x width, with any formulation (the 3D model
  replaces the formulation's 2D assumption; a ``penalty`` needs material.penalty).

3D only (:class:`reference_fem.geometry.BoxGeometry`):

- ``cells_width`` (int): cells across the width (default: cells no more than 1.5 times
  as wide as high, ``ceil(cells_height * w / (1.5 h))``; the paper beam: as many as
  across the height);
- ``progression`` (> 0): cell-to-cell growth of the cell length along x, from the clamp
  to the free end (1: uniform); a refined level uses its ``factor``-th root, so the
  levels stay nested (the clamp's edges are singular: grading toward them makes the
  refinement sequence monotone; README, "The real beam in 3D");
- ``side_faces``: "free" (default) | "plane-strain" (u_z = 0 on both faces z = +-w/2:
  the 3D problem then contains the 2D plane-strain solution exactly; a check).

Any model:

- ``backend``: "dolfinx" (default) | "felupe" (:mod:`reference_fem.felupe_backend`: the
  same problem on a second code; quadrilateral / hexahedral Q2 cells, static analyses).
  Records of "dolfinx" do not name it; a "felupe" record has ``fem.backend`` and ``felupe``
  (its version);
- ``linear_solver``: "direct" (default: MUMPS LU of every Newton increment) |
  "iterative" (FGMRES with the augmented-Lagrangian block preconditioner and a two-level
  p-multigrid on its displacement block,
  :class:`reference_fem.dolfinx_backend.krylov.ALPreconditioner`; PETSc options with the prefix
  ``fem_`` override its defaults). Records of "direct" do not name it.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace
from typing import Any, Mapping

from contract.errors import SceneError, UnknownName
from contract.scene import Scene

from .backends import BACKENDS, DEFAULT as DEFAULT_BACKEND   # the registry of fem.backend
from .geometry import Geometry, geometry_for

CELLS = ("quadrilateral", "triangle")
CELLS_3D = ("hexahedron", "tetrahedron")
INCOMPRESSIBILITY = ("mixed", "penalty")
MODELS = ("plane-strain", "plane-stress", "3d")
SIDE_FACES = ("free", "plane-strain")
LINEAR_SOLVERS = ("direct", "iterative")
# The lowest displacement degree of each incompressibility: a pressure field (mixed,
# penalty) is one degree lower (Taylor-Hood), so the displacement needs degree 2.
MIN_DEGREE = {"mixed": 2, "penalty": 2, "exact": 1}
KEYS = ("cells_height", "cells_length", "aspect", "cell", "degree", "quadrature_degree",
        "incompressibility", "model", "cells_width", "progression", "side_faces", "linear_solver",
        "backend")
KEYS_3D = ("cells_width", "progression", "side_faces")

# Defaults: chosen by the convergence study in reports/reference_fem.md so that the
# paper's beam (L = 160 mm, h = 5 mm; 64 x 4 Q2 cells) is within 0.5 % of the
# converged tip, with margin (0.03 to 0.1 % measured; 32 x 2 would give 0.15 to 0.25 %).
# Checked by tests/test_reference_fem_cantilever.py.
DEFAULT_CELLS_HEIGHT = 4
DEFAULT_ASPECT = 2.0
DEFAULT_CELL = "quadrilateral"
DEFAULT_DEGREE = 2
# The JIT's generated code and the assembly grow fast with the degree: degree 8 compiles
# in 12 s and solves 16 x 2 mixed cells in 62 s here (degree 4: 7 s, 4 s); degree 20
# does not finish.
MAX_DEGREE = 8


@dataclass(frozen=True)
class FemSettings:
    """A resolved [fem] table: the mesh counts are numbers, the model is named."""

    model: str                 # "plane-strain" | "plane-stress" | "3d"
    incompressibility: str     # "mixed" | "penalty" | "exact" (plane stress: F33 = 1/J)
    cells_length: int
    cells_height: int
    cell: str = DEFAULT_CELL
    degree: int = DEFAULT_DEGREE
    quadrature_degree: int = 4
    cells_width: int | None = None   # 3D only
    progression: float = 1.0         # 3D only
    side_faces: str = "free"         # 3D only
    linear_solver: str = "direct"    # "direct" | "iterative"
    backend: str = "dolfinx"         # "dolfinx" | "felupe"

    @property
    def geometry(self) -> Geometry:
        """Where the supports, loads and tip are (:mod:`reference_fem.geometry`)."""
        return geometry_for(self.model)

    @property
    def has_pressure(self) -> bool:
        """Is a pressure field solved for (mixed and penalty models; not plane stress)?"""
        return self.incompressibility != "exact"

    def cells(self, gdim: int = 2) -> tuple[int, ...]:
        """Cells along x and across the height (and across the width in 3D)."""
        if gdim == 3:
            return (self.cells_length, self.cells_height, self.cells_width)
        return (self.cells_length, self.cells_height)

    def refined(self, factor: int) -> "FemSettings":
        """The same discretisation with every cell split ``factor`` times per direction
        (graded 3D meshes: the progression's ``factor``-th root, nested)."""
        if self.model != "3d":
            return replace(self, cells_length=self.cells_length * factor,
                           cells_height=self.cells_height * factor)
        return replace(self, cells_length=self.cells_length * factor, cells_height=self.cells_height * factor,
                       cells_width=self.cells_width * factor, progression=self.progression ** (1.0 / factor))

    def to_dict(self) -> dict:
        d = asdict(self)
        if self.model != "3d":   # 2D records keep their keys
            for k in KEYS_3D:
                d.pop(k)
        if self.linear_solver == "direct":   # records of the direct solver keep their keys
            d.pop("linear_solver")
        if self.backend == "dolfinx":   # records of the default backend keep their keys
            d.pop("backend")
        return d


def default_quadrature_degree(degree: int) -> int:
    """2 p: exact for the polynomial part of the integrand of a degree-p displacement
    (grad u of degree p - 1, energies quadratic in it, times a degree-p test function)."""
    return 2 * degree


def _int(field_, value, minimum=1, maximum=None):
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise SceneError(f"fem.{field_}: must be an integer >= {minimum}, got {value!r}")
    if maximum is not None and value > maximum:
        raise SceneError(f"fem.{field_}: must be an integer in [{minimum}, {maximum}], got {value!r}")
    return value


def _choice(field_, value, allowed):
    if value not in allowed:
        raise UnknownName(f"fem.{field_}", value, allowed)
    return value


def fem_settings(scene: Scene) -> FemSettings:
    """Validate ``scene.fem`` and resolve it against the scene (beam, formulation)."""
    t: Mapping[str, Any] = scene.fem if scene.fem is not None else {}
    if not isinstance(t, Mapping):
        raise SceneError("fem: must be a table ([fem])")
    unknown = sorted(set(t) - set(KEYS))
    if unknown:
        raise SceneError(f"fem: unknown key(s) {unknown}; allowed: {', '.join(sorted(KEYS))}")

    form = scene.material.formulation
    if t.get("model") == "3d":
        model = "3d"
    elif form == "paper":
        if "model" not in t:
            raise SceneError("fem.model: required for material.formulation = \"paper\" "
                             "(no continuum meaning); allowed: 'plane-strain', 'plane-stress', '3d'")
        model = _choice("model", t["model"], MODELS)
    else:
        model = form
        if "model" in t and _choice("model", t["model"], MODELS) != form:
            raise SceneError(f"fem.model: {t['model']!r} contradicts material.formulation = "
                             f"{form!r}; give fem.model only for \"paper\" scenes")

    if model == "plane-stress":
        if "incompressibility" in t:
            raise SceneError("fem.incompressibility: only for plane strain; plane stress is "
                             "exactly incompressible through F33 = 1/det F")
        incompressibility = "exact"
    else:
        incompressibility = _choice("incompressibility", t.get("incompressibility", "mixed"),
                                    INCOMPRESSIBILITY)
        if incompressibility == "penalty" and scene.material.penalty is None:
            raise SceneError("fem.incompressibility: \"penalty\" needs material.penalty")

    if model == "3d":
        cell = _choice("cell", t.get("cell", "hexahedron"), CELLS_3D)
    else:
        cell = _choice("cell", t.get("cell", DEFAULT_CELL), CELLS)
        given = sorted(set(t) & set(KEYS_3D))
        if given:
            raise SceneError(f"fem.{given[0]}: only for fem.model = \"3d\"")
    degree = _int("degree", t.get("degree", DEFAULT_DEGREE), MIN_DEGREE[incompressibility],
                  MAX_DEGREE)
    ny = _int("cells_height", t.get("cells_height", DEFAULT_CELLS_HEIGHT))
    if "cells_length" in t and "aspect" in t:
        raise SceneError("fem.cells_length: give either cells_length or aspect, not both")
    if "cells_length" in t:
        nx = _int("cells_length", t["cells_length"])
    else:
        aspect = t.get("aspect", DEFAULT_ASPECT)
        if isinstance(aspect, bool) or not isinstance(aspect, (int, float)) or not 0 < aspect < float("inf"):
            raise SceneError(f"fem.aspect: must be a positive number (cell length / cell height), got {aspect!r}")
        b = scene.beam
        nx = max(1, round(b.length / b.height * ny / aspect))
    qdeg = _int("quadrature_degree", t.get("quadrature_degree", default_quadrature_degree(degree)), 1,
                4 * MAX_DEGREE)
    solver = _choice("linear_solver", t.get("linear_solver", "direct"), LINEAR_SOLVERS)
    backend = _choice("backend", t.get("backend", DEFAULT_BACKEND), BACKENDS)
    if model != "3d":
        return FemSettings(model, incompressibility, nx, ny, cell, degree, qdeg, linear_solver=solver,
                           backend=backend)
    b = scene.beam
    nz = _int("cells_width", t.get("cells_width", max(1, math.ceil(ny * b.width / (1.5 * b.height) - 1e-9))))
    q = t.get("progression", 1.0)
    if isinstance(q, bool) or not isinstance(q, (int, float)) or not 0 < q < float("inf"):
        raise SceneError(f"fem.progression: must be a positive number (cell-to-cell growth along x), got {q!r}")
    side = _choice("side_faces", t.get("side_faces", "free"), SIDE_FACES)
    return FemSettings(model, incompressibility, nx, ny, cell, degree, qdeg, nz, float(q), side, solver, backend)
