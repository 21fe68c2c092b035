"""The continuum's section error, by a route of its own: Saint-Venant's torsion constant of the
5 x 7 mm rectangle on n x n Q2 quadrilaterals (DOLFINx 2D), the warping psi minimising
int |grad psi + (-z, y)|^2 dA, J_h that minimum (a Ritz upper bound of J). The 3D meshes of
run.py carry the same Q2 section, so this sequence is the order and size of their
section error at small twist, without the plates or the length.

A weak mass term (1e-3 / (h w)) int psi v dA fixes psi's constant (a Neumann problem); it
moves psi by about 1e-4 of itself and J, a minimum, by its square.

    .venv/bin/python experiments/spatial_finite_torsion/saint_venant_q2.py
"""
import dolfinx
import dolfinx.fem.petsc
import ufl
from mpi4py import MPI

from studies.verification.torsion import saint_venant_rectangle

h, w = 5e-3, 7e-3
exact = saint_venant_rectangle(h, w)
print("| cells across | J_h (mm^4) | off Saint-Venant (%) |\n|---|---|---|")
for n in (1, 2, 4, 8, 16, 32, 64):
    m = dolfinx.mesh.create_rectangle(MPI.COMM_WORLD, [[-h / 2, -w / 2], [h / 2, w / 2]], [n, n],
                                      dolfinx.mesh.CellType.quadrilateral)
    V = dolfinx.fem.FunctionSpace(m, ("Q", 2))
    y, z = ufl.SpatialCoordinate(m)
    psi, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    g = ufl.as_vector((-z, y))
    a = ufl.inner(ufl.grad(psi), ufl.grad(v)) * ufl.dx + 1e-3 / (h * w) * psi * v * ufl.dx
    L = -ufl.inner(g, ufl.grad(v)) * ufl.dx
    s = dolfinx.fem.petsc.LinearProblem(a, L, petsc_options={"ksp_type": "preonly", "pc_type": "lu"}).solve()
    J = dolfinx.fem.assemble_scalar(dolfinx.fem.form(ufl.inner(ufl.grad(s) + g, ufl.grad(s) + g) * ufl.dx))
    print(f"| {n} | {J * 1e12:.5f} | {100 * (J / exact - 1):+.5f} |")
