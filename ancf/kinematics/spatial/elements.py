"""The built-in spatial elements, registered by name (:data:`SPATIAL_ELEMENTS`), names in the
"abcd" classification of Obrezkov, Matikainen and Kireeva (Nonlinear Dyn. 2022,
doi:10.1007/s11071-022-07518-z), as the LUT solver reads it: the second digit the nodes,
the middle ones the vectors per node, the last the dimension (3243: 2 nodes, 4 vectors,
3D). The default rule of each is the cheapest product rule that passes the rank test at
every l_e / h of :data:`.rank.ASPECTS` (tests/test_spatial_elements.py: it passes, every
rule with a point fewer in one direction fails): the rule exact for the squared basis for
all but the 3243, whose cubic along passes with three points.
Each basis is the one its source writes, checked against the LUT group's open solver
(LUT-CoSmart/ANCF-Beam-based-Solver, ElementTensors/Matlab/FF_<name>.m: the deformation
gradient in the nodal vectors).
"""
from __future__ import annotations

from contract.registry import Registry

from .spec import SpatialSpec

SPATIAL_ELEMENTS: Registry[SpatialSpec] = Registry("ancf.element", "spatial element")


def register_spatial_element(spec: SpatialSpec) -> SpatialSpec:
    import sys

    return SPATIAL_ELEMENTS.register(spec.name, spec, sys._getframe(1).f_globals.get("__name__", "__main__"))


def get_spatial_element(name: str) -> SpatialSpec:
    return SPATIAL_ELEMENTS.lookup(name)


def _monomial(i: int, j: int, k: int) -> str:
    return "*".join([f"{v}^{p}" if p > 1 else v for v, p in zip("xyz", (i, j, k)) if p]) or "1"


def section_modes(degree: int) -> list[tuple[int, int]]:
    """The complete polynomial section of a degree: (power of y, power of z), by degree."""
    return [(d - b, b) for d in range(degree + 1) for b in range(d + 1)]


# the section modes after the quadratic that carry a rectangle's torsion warping (odd in y and
# z): degree 4's, and degree 6's after them
TORSION_MODES = ((3, 1), (1, 3))
TORSION_MODES_6 = TORSION_MODES + ((5, 1), (3, 3), (1, 5))


def hermite_section(name: str, degree: int, pressure_degree: int | None = None, reference: str = "",
                    extra: tuple[tuple[int, int], ...] = (),
                    pressure_extra: tuple[tuple[int, int], ...] = ()) -> SpatialSpec:
    """Two nodes, cubic Hermite along the beam, the complete section of ``degree`` in (y, z):
    at each node the section's field y^a z^b and its slope along the beam, kinds
    r_<y^a z^b> and r_x<y^a z^b> (r, r_x, r_y, r_xy, r_z, r_xz, r_yy, ...), so that the
    position and the section's shape are C1 between elements; ``extra`` adds section modes
    (a, b) beyond the complete ones (y^3 z and y z^3: the next torsion warping). With
    ``pressure_degree`` an element pressure {1, x} x the complete section of that degree and
    the section modes ``pressure_extra``."""
    modes = section_modes(degree)
    modes += [m for m in extra if m not in modes]
    kinds = []
    for a, b in modes:
        d = "y" * a + "z" * b
        kinds += ["r_" + d if d else "r", "r_x" + d]
    basis = tuple(_monomial(i, a, b) for i in range(4) for a, b in modes)
    pmodes = [] if pressure_degree is None else section_modes(pressure_degree)
    pmodes += [m for m in pressure_extra if m not in pmodes]
    pressure = tuple(_monomial(i, a, b) for i in range(2) for a, b in pmodes)
    return SpatialSpec(name, basis, (0.0, 1.0), tuple(kinds), reference, pressure=pressure)


# fully parameterised: position and three slopes at two nodes, cubic along x, linear across
register_spatial_element(SpatialSpec(
    "3243", ("1", "x", "y", "z", "x*y", "x*z", "x^2", "x^3"), (0.0, 1.0), ("r", "r_x", "r_y", "r_z"),
    "Shabana & Yakoub 2001 (J. Mech. Des. 123); Gerstmayr & Shabana 2006 (Nonlinear Dyn. 45)",
    quadrature=(3, 2, 2)))
# shear deformable, three nodes with position and the two transverse slopes, quadratic along x
register_spatial_element(SpatialSpec(
    "3333", ("1", "x", "x^2", "y", "x*y", "x^2*y", "z", "x*z", "x^2*z"), (0.0, 0.5, 1.0), ("r", "r_y", "r_z"),
    "Nachbagauer, Gruber & Gerstmayr 2013 (J. Comput. Nonlinear Dyn. 8)"))
# the 3333 with the transverse second derivatives: a section that deforms quadratically
register_spatial_element(SpatialSpec(
    "3363", ("1", "x", "x^2", "y", "x*y", "x^2*y", "z", "x*z", "x^2*z",
             "y*z", "x*y*z", "x^2*y*z", "y^2", "x*y^2", "x^2*y^2", "z^2", "x*z^2", "x^2*z^2"),
    (0.0, 0.5, 1.0), ("r", "r_y", "r_z", "r_yz", "r_yy", "r_zz"),
    "Obrezkov, Matikainen & Kireeva 2022 (Nonlinear Dyn.; the LUT solver's 3363)"))
# this harness: the 3363 with the penalty on the element-wise projection of J - 1 onto
# {1, x} x {1, y, z}, the planar HB2n-40p's idea carried into the section
register_spatial_element(SpatialSpec(
    "3363p", SPATIAL_ELEMENTS["3363"].basis, (0.0, 0.5, 1.0), SPATIAL_ELEMENTS["3363"].kinds,
    "this harness: the 3363 with an element pressure {1, x} x {1, y, z}", pressure=("1", "x", "y", "x*y", "z", "x*z")))
# this harness: cubic Hermite along, the complete quadratic section (r, r_y, r_z, r_yy, r_yz,
# r_zz and their slopes along the beam at two nodes, 72 dof), the pressure {1, x} x {1, y, z}:
# the lock-free spatial element, limited by its section: 0.15 % stiff of the continuum on the
# paper's clamped cantilever once the clamp's end zone is resolved, 18 % stiff in torsion on
# its 5 x 7 mm section (experiments/spatial_cantilever, experiments/spatial_torsion)
register_spatial_element(hermite_section(
    "HS2n-72p", 2, 1, "this harness: the planar HB2n-40p's Hermite section and element pressure, in 3D"))
# this harness: HS2n-72p's section with the torsion warping modes y^3 z and y z^3 added (16
# vectors per node, 96 dof): the cubic section's bending limit, 0.075 % stiff on the clamped
# cantilever, and the quartic's torsion, 0.24 % stiff on the 5 x 7 mm section
register_spatial_element(hermite_section(
    "HS2n-96p", 2, 1, "this harness: HS2n-72p with the torsion warping modes y^3 z and y z^3", TORSION_MODES))
# this harness: HS2n-96p with degree 6's torsion warping modes y^5 z, y^3 z^3 and y z^5 too (22
# vectors per node, 132 dof, the exact rule (4, 6, 6)): degree 6's torsion, 0.055 % stiff on
# the 5 x 7 mm section at 16 elements, 0.081 % at 8 (experiments/spatial_torsion)
register_spatial_element(hermite_section(
    "HS2n-132p", 2, 1, "this harness: HS2n-96p with the torsion warping modes of degree 6", TORSION_MODES_6))
# this harness: the complete cubic section with degree 4's and 6's torsion warping (15 vectors
# per node, 180 dof) and the pressure {1, x} x the complete quadratic section: the section
# modes y^3, y^2 z, y z^2, z^3 carry the in-plane second-order fields of a finite twist, the
# pressure's y^2, z^2 and y z its second-order volume change and the restrained warping's at
# a plate, both needed for finite torsion (experiments/spatial_finite_torsion: either alone
# leaves it soft or locks it; together the twist's stiffening and the plates' end zones come
# right); the cubic section also removes HS2n-96p's stiff limit in bending
# (experiments/spatial_end_force)
register_spatial_element(hermite_section(
    "HS2n-180p", 3, 2, "this harness: the cubic section, degree 6's torsion warping, a quadratic element pressure",
    TORSION_MODES_6))
# this harness: HS2n-180p with the complete quartic section (18 vectors per node, 216 dof, the
# rule (4, 6, 6) by its rank test): the quartic's even modes y^4, y^2 z^2, z^4 carry the
# section's second-order shape in bending, which HS2n-180p misses at a plate turned about all
# three axes (its axial force and bending moment 0.19 and 0.23 % stiff on the converged
# meshes, this one's 0.08 and 0.05 %; experiments/spatial_finite_torsion, twist-bend)
register_spatial_element(hermite_section(
    "HS2n-216p", 4, 2, "this harness: the complete quartic section, degree 6's torsion warping, a quadratic "
    "element pressure", TORSION_MODES_6))
BUILTIN = SPATIAL_ELEMENTS.freeze_builtin()
