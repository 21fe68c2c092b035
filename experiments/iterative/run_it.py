"""Run the 3D cantilever (yeoh, 10 load steps) with the direct or iterative solver and
print Newton / Krylov counts, times, peak memory and the tip.
usage: run_it.py NX NY NZ direct|iterative [PETSc options]"""
import sys, time, json, resource
import petsc4py
petsc4py.init([sys.argv[0]] + sys.argv[5:])
from petsc4py import PETSc
import numpy as np
from contract.scene import scene_from_dict
from contract import paper
from reference_fem.settings import fem_settings
from reference_fem.dolfinx_backend.problem import set_up, static_problem
from reference_fem.statics import solve_static

nx, ny, nz = map(int, sys.argv[1:4]); solver = sys.argv[4]
fem = {"model": "3d", "cells_length": nx, "cells_height": ny, "cells_width": nz, "linear_solver": solver}
scene = scene_from_dict(paper.cantilever_scene("yeoh", "paper", fem=fem, load_steps=10, name="it"))
t0 = time.perf_counter()
s = set_up(scene, fem_settings(scene))
problem = static_problem(s)
sysm = problem.system
setup = time.perf_counter() - t0
a = scene.analysis
t1 = time.perf_counter()
res = solve_static(sysm, problem.set_load, a.load_steps, a.newton_rtol, a.max_iterations, a.wall_time)
wall = time.perf_counter() - t1
tip = s.model.geometry.tip_point(scene.beam)
u = s.disc.point_displacement([tip])[0]
k = sysm.krylov_iterations
comm = s.disc.comm
out = dict(mesh=f"{nx}x{ny}x{nz}", solver=solver, ranks=comm.size, ndof=s.disc.ndof, status=res.status,
           newton=res.newton_iterations, load_steps=res.load_steps, rejected=res.rejected_steps,
           krylov_mean=float(np.mean(k)) if k else None, krylov_max=int(max(k)) if k else None, krylov=k,
           setup_s=setup, solve_wall_s=wall,
           maxrss_MB=comm.allreduce(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, op=__import__("mpi4py.MPI").MPI.MAX),
           tip=[float(c) for c in u], opts=sys.argv[5:])
if comm.rank == 0:
    print(json.dumps(out))
