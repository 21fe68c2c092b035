"""Run the 3D cantilever with MUMPS and dump selected Newton systems plus the data an
offline preconditioner study needs (index sets, lumped pressure mass, dof coordinates,
the Q1 -> Q2 displacement prolongation in the u-split ordering).
usage: dump.py NX NY NZ OUTDIR [every]"""
import sys, time, json, os
import numpy as np
from petsc4py import PETSc
import dolfinx, dolfinx.fem, dolfinx.fem.petsc, dolfinx.cpp
from contract.scene import scene_from_dict
from contract import paper
from reference_fem.settings import fem_settings
from reference_fem.dolfinx_backend.problem import set_up, static_problem
from reference_fem.statics import solve_static
from reference_fem.dolfinx_backend import fem as backend

nx, ny, nz = map(int, sys.argv[1:4]); out = sys.argv[4]; every = int(sys.argv[5]) if len(sys.argv) > 5 else 8
os.makedirs(out, exist_ok=True)
fem = {"model": "3d", "cells_length": nx, "cells_height": ny, "cells_width": nz}
scene = scene_from_dict(paper.cantilever_scene("yeoh", "paper", fem=fem, load_steps=10, name="dump"))
settings = fem_settings(scene)
s = set_up(scene, settings)
problem = static_problem(s)
sysm = problem.system
disc = sysm.disc
W = disc.W
# the u/p split sets as the branch builds them
sysm._split_sets()
is_u = sysm.is_u.getIndices().copy(); is_p = sysm.is_p.getIndices().copy()
np.save(f"{out}/is_u.npy", is_u); np.save(f"{out}/is_p.npy", is_p)
lump = sysm.lumped.getArray().copy(); np.save(f"{out}/lumped.npy", lump)
V2, u_all = W.sub(0).collapse(); u_all = np.asarray(u_all)
x2 = V2.tabulate_dof_coordinates()
# coordinates of the u-split rows (node-major, ordering of is_u)
coords_W = np.zeros((len(sysm.w.x.array), 3)); coords_W[u_all.reshape(-1, 3)[:, 0]] = x2
np.save(f"{out}/coords_u.npy", coords_W[is_u[::3]])
# Q1 -> Q2 prolongation (vector), rows in is_u order
V1 = dolfinx.fem.VectorFunctionSpace(disc.mesh, ("Lagrange", 1))
Pm = dolfinx.cpp.fem.petsc.interpolation_matrix(V1._cpp_object, V2._cpp_object)
Pm.assemble()
# V2 (collapsed, blocked dofs: node*3+c) -> W index u_all[node*3+c]; then W -> position in is_u
posW = -np.ones(len(sysm.w.x.array), dtype=np.int64); posW[is_u] = np.arange(len(is_u))
rowmap = posW[u_all]   # V2 dof -> u-split row
assert (rowmap >= 0).all()
ai, aj, av = Pm.getValuesCSR()
rows = np.repeat(np.arange(Pm.getSize()[0]), np.diff(ai))
# bcs: zero rows of clamped dofs in the fine space (A has identity rows there)
from scipy import sparse
Pcsr = sparse.csr_matrix((av, (rowmap[rows], aj)), shape=Pm.getSize())
np.savez(f"{out}/prolong.npz", data=Pcsr.data, indices=Pcsr.indices, indptr=Pcsr.indptr, shape=Pcsr.shape)
x1 = V1.tabulate_dof_coordinates(); np.save(f"{out}/coords_q1.npy", x1)
bcdofs = np.concatenate([bc.dof_indices()[0] for bc in s.bcs])
np.save(f"{out}/bc_u.npy", np.sort(posW[bcdofs]))
meta = {"mu": float(s.mu), "ndof": disc.ndof, "nu": len(is_u), "np": len(is_p)}

count = [0]; saved = []; last = {}
orig = sysm.newton_update
times = []
def patched():
    sysm.A.zeroEntries()
    dolfinx.fem.petsc.assemble_matrix(sysm.A, sysm.K, bcs=sysm.bcs); sysm.A.assemble()
    k = count[0]; count[0] += 1
    if k % every == 0:
        v = PETSc.Viewer().createBinary(f"{out}/sys{k:03d}.bin", "w"); sysm.A.view(v); sysm.b.view(v); v.destroy(); saved.append(k)
    last["A"] = sysm.A.copy(); last["b"] = sysm.b.copy(); last["k"] = k
    t = time.perf_counter(); r = orig(); times.append(time.perf_counter() - t); return r
sysm.newton_update = patched
a = scene.analysis
t0 = time.perf_counter()
res = solve_static(sysm, problem.set_load, a.load_steps, a.newton_rtol, a.max_iterations, a.wall_time)
wall = time.perf_counter() - t0
k = last["k"]
if k not in saved:
    v = PETSc.Viewer().createBinary(f"{out}/sys{k:03d}.bin", "w"); last["A"].view(v); last["b"].view(v); v.destroy(); saved.append(k)
tip = s.model.geometry.tip_point(scene.beam)
u = disc.point_displacement([tip])[0]
import resource
meta.update(status=res.status, updates=count[0], saved=saved, wall_s=wall, newton_iterations=res.newton_iterations,
            solve_s=sum(times), tip=[float(c) for c in u], maxrss_MB=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)
json.dump(meta, open(f"{out}/meta.json", "w"), indent=1)
print(json.dumps(meta))
