"""The proposed end moment, tested in DOLFINx: the free end face held on a straight line of
angle theta (a 'slide' on a rotating plane, free along it: the face may thin and slide), by a
penalty k/2 int_face ((X + u) . n(theta) - a)^2 dY, n = (cos theta, sin theta), with theta and
the offset a two global unknowns, and the load potential -M theta. Stationarity in a gives a
zero resultant, in theta a moment M of the face's (normal) constraint tractions: a pure couple
whose distribution is whatever the block demands; Rivlin's flexure (straight radial end faces,
normal traction only) solves this problem exactly. The repo's set-up (mesh, mixed energy,
slide support at x = 0) is used as it is; the Newton loop, the penalty and the two global
unknowns are here (scipy SuperLU on the assembled matrix bordered by two rows).

usage: slide_couple.py scene.toml out.json [k_factor]"""
import sys, json, math
sys.path.insert(0, "../..")
import numpy as np, scipy.sparse as sp, scipy.sparse.linalg as spla
import ufl, dolfinx, dolfinx.fem.petsc
from petsc4py import PETSc
from contract.scene import load_scene
from reference_fem.settings import fem_settings
from reference_fem.dolfinx_backend import problem as P

scene = load_scene(sys.argv[1]); out = sys.argv[2]
kfac = float(sys.argv[3]) if len(sys.argv) > 3 else 1e3
st = fem_settings(scene)
s = P.set_up(scene, st)
d = s.disc
h, L = scene.beam.height, scene.beam.length
M = s.moment                                   # per unit width
ds = d.boundary_measure(s.traction_where)
X = ufl.SpatialCoordinate(d.mesh)
u = d.u
v = ufl.split(d.test)[0] if d.pressure else d.test
x = X + u
th, a = d.constant(0.0), d.constant(0.0)
k = d.constant(kfac * s.mu / h)                # penalty stiffness (Pa/m)
n = ufl.as_vector((ufl.cos(th), ufl.sin(th))); t = ufl.as_vector((-ufl.sin(th), ufl.cos(th)))
g = ufl.dot(x, n) - a
Pi = s.energy(s.gradient(u), d.phat) * d.dx + 0.5 * k * g * g * ds
R_w = ufl.derivative(Pi, d.w, d.test)
J_ww = ufl.derivative(R_w, d.w, d.trial)
# derivatives in theta and a (by hand)
R_th = k * g * ufl.dot(x, t) * ds
R_a = -k * g * ds
V_wth = k * (ufl.dot(x, t) * ufl.dot(v, n) + g * ufl.dot(v, t)) * ds
V_wa = -k * ufl.dot(v, n) * ds
K_thth = k * (ufl.dot(x, t) ** 2 - g * ufl.dot(x, n)) * ds
K_tha = -k * ufl.dot(x, t) * ds
K_aa = k * ds
F = {nm: dolfinx.fem.form(f) for nm, f in dict(R_w=R_w, R_th=R_th, R_a=R_a, V_wth=V_wth, V_wa=V_wa,
                                                 K_thth=K_thth, K_tha=K_tha, K_aa=K_aa).items()}
Jf = dolfinx.fem.form(J_ww)
bc_dofs = np.unique(np.concatenate([bc.dof_indices()[0] for bc in s.bcs]))
def vec(f):
    b = dolfinx.fem.petsc.assemble_vector(f); b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    return b.array.copy()
def scal(f): return float(dolfinx.fem.assemble_scalar(f))
def system(Mt):
    A = dolfinx.fem.petsc.assemble_matrix(Jf); A.assemble()
    ia, ja, va = A.getValuesCSR(); K = sp.csr_matrix((va, ja, ia), shape=A.getSize())
    r = vec(F["R_w"]); vt = vec(F["V_wth"]); va_ = vec(F["V_wa"])
    r[bc_dofs] = 0; vt[bc_dofs] = 0; va_[bc_dofs] = 0
    K = K.tolil(); K[bc_dofs, :] = 0; K[:, bc_dofs] = 0; K[bc_dofs, bc_dofs] = 1.0; K = K.tocsr()
    B = sp.bmat([[K, sp.csr_matrix(vt[:, None]), sp.csr_matrix(va_[:, None])],
                 [sp.csr_matrix(vt[None, :]), scal(F["K_thth"]), scal(F["K_tha"])],
                 [sp.csr_matrix(va_[None, :]), scal(F["K_tha"]), scal(F["K_aa"])]], format="csc")
    res = np.concatenate([r, [scal(F["R_th"]) - Mt, scal(F["R_a"])]])
    return B, res
steps = scene.analysis.load_steps
hist = []
status = "converged"
for i in range(1, steps + 1):
    Mt = M * i / steps
    for it in range(40):
        B, res = system(Mt)
        nr = np.linalg.norm(res)
        if it == 0: n0 = max(nr, 1e-30)
        if nr < max(1e-9 * n0, 1e-10 * abs(M) / h):
            break
        dz = spla.spsolve(B, -res)
        d.w.x.array[:] += dz[:-2]; th.value += dz[-2]; a.value += dz[-1]
    else:
        status = f"failed at step {i}: residual {nr:.3e}"; break
    hist.append((Mt, float(th.value), int(it)))
    print(f"step {i}: M {Mt:.5g} theta {float(th.value):.6f} iterations {it}", flush=True)
# inertia of the bordered tangent at the final state: negative eigenvalues beyond the
# pressure unknowns' count = unstable directions of the (constrained) potential
import os as _os
if _os.environ.get("INERTIA") and status == "converged":
    B, _ = system(M)
    ev = np.linalg.eigvalsh(B.toarray())
    n_p = len(d.W.sub(1).collapse()[1]) if d.pressure else 0
    neg = int((ev < 0).sum())
    print(f"inertia: {neg} negative eigenvalues, {n_p} pressure dofs -> unstable directions {neg - n_p}", flush=True)
    unstable = neg - n_p
else:
    unstable = None
# outputs: theta, the face's max constraint gap, the interior profile via vertices
gap = dolfinx.fem.assemble_scalar(dolfinx.fem.form(g * g * ds)) ** 0.5 / h ** 0.5
res = dict(unstable_directions=unstable, status=status, theta=float(th.value), a=float(a.value), gap_rms=float(gap), history=hist, k_factor=kfac,
           moment_per_width=M, L=L, h=h)
# write a vtk like the CLI's (degree-1 at the vertices) for prof.py
import os
vdir = out.replace(".json", "_vtk"); os.makedirs(vdir, exist_ok=True)
Vp1 = dolfinx.fem.VectorFunctionSpace(d.mesh, ("Lagrange", 1))
uu = dolfinx.fem.Function(Vp1); uu.name = "displacement"
usub = d.w.sub(0).collapse() if d.pressure else d.w
uu.interpolate(usub)
gx = d.mesh.geometry.x
import xml.etree.ElementTree as ET
# minimal vtu: points and displacement at vertices (prof.py reads those two)
vals = uu.x.array.reshape(-1, 2)
# map geometry nodes to dofs of P1 (same ordering for P1 on a degree-1 mesh)
pts = Vp1.tabulate_dof_coordinates()
with open(f"{vdir}/slide_p0_000000.vtu", "w") as f:
    f.write('<?xml version="1.0"?><VTKFile type="UnstructuredGrid"><UnstructuredGrid><Piece>\n')
    f.write('<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">' + " ".join(f"{p[0]!r} {p[1]!r} 0" for p in pts) + '</DataArray></Points>\n')
    f.write('<PointData><DataArray type="Float64" Name="displacement" NumberOfComponents="3" format="ascii">' + " ".join(f"{q[0]!r} {q[1]!r} 0" for q in vals) + '</DataArray></PointData>\n')
    f.write('</Piece></UnstructuredGrid></VTKFile>\n')
json.dump(res, open(out, "w"), indent=1)
print(json.dumps({k: v for k, v in res.items() if k != "history"}))
