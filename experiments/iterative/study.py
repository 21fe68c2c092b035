"""Offline preconditioner study on dumped Newton systems (see dump.py).

python study.py DIR MODE [key=value ...] [-- petsc options]
MODE: block   (Krylov on one displacement block: which=uu|aug)
      outer   (FGMRES on the full system, block-triangular AL preconditioner, inner solver on aug)
Inner displacement-block solver options have the prefix "in_" (PETSc options database).
pc=gamg|pmg|hypre|lu picks the displacement preconditioner; pmg builds a 2-level PCMG with
the Q1 -> Q2 prolongation (Galerkin coarse operator) and the coarse level configured by
in_mg_coarse_* options.
"""
import sys, json, time, glob
import numpy as np
import petsc4py
_popts = [a for a in sys.argv[1:] if a.startswith('-') or (sys.argv[sys.argv.index(a)-1].startswith('-') and '=' not in a)]
petsc4py.init([sys.argv[0]] + [a for i, a in enumerate(sys.argv[1:], 1) if a.startswith('-') or (sys.argv[i-1].startswith('-') and not sys.argv[i-1].startswith('--'))])
from petsc4py import PETSc
from scipy import sparse

_plain = [a for i, a in enumerate(sys.argv[1:], 1) if not a.startswith("-") and not sys.argv[i - 1].startswith("-")]
args = [a for a in _plain if "=" in a]
pos = [a for a in _plain if "=" not in a]
D, mode = pos[0], pos[1]
kw = dict(a.split("=", 1) for a in args)
gamma = float(kw.get("gamma", 3)); pctype = kw.get("pc", "gamg"); which = kw.get("which", "aug")
sysfiles = sorted(glob.glob(f"{D}/sys*.bin"))
if "sys" in kw:
    sel = [int(i) for i in kw["sys"].split(",")]
    sysfiles = [f for f in sysfiles if int(f[-7:-4]) in sel]
meta = json.load(open(f"{D}/meta.json"))
mu = meta["mu"]
comm = PETSc.COMM_SELF
is_u_np = np.load(f"{D}/is_u.npy"); is_p_np = np.load(f"{D}/is_p.npy")
is_u = PETSc.IS().createGeneral(is_u_np.astype(PETSc.IntType), comm=comm)
is_p = PETSc.IS().createGeneral(is_p_np.astype(PETSc.IntType), comm=comm)
lumped = np.load(f"{D}/lumped.npy")[is_p_np]
X = np.load(f"{D}/coords_u.npy")
nu = len(is_u_np)

def rigid_modes():
    vecs = []
    modes = [np.tile(np.eye(3)[i], (len(X), 1)) for i in range(3)]
    for i, j in [(0, 1), (1, 2), (2, 0)]:
        m = np.zeros_like(X); m[:, i], m[:, j] = -X[:, j], X[:, i]; modes.append(m)
    for m in modes:
        v = PETSc.Vec().createWithArray(m.reshape(-1).copy(), comm=comm); vecs.append(v)
    for i, v in enumerate(vecs):
        for u in vecs[:i]:
            v.axpy(-v.dot(u), u)
        v.normalize()
    return PETSc.NullSpace().create(vectors=vecs, comm=comm)

nns = rigid_modes() if kw.get("nns", "1") == "1" else None

def prolongation():
    z = np.load(f"{D}/prolong.npz")
    Pc = sparse.csr_matrix((z["data"], z["indices"], z["indptr"]), shape=tuple(z["shape"]))
    # drop tiny entries
    Pc.data[abs(Pc.data) < 1e-12] = 0; Pc.eliminate_zeros()
    bc = np.load(f"{D}/bc_u.npy")
    keep = np.ones(Pc.shape[0]); keep[bc] = 0    # fine Dirichlet rows: no coarse correction
    Pc = sparse.diags(keep) @ Pc
    Pc = Pc.tocsr(); Pc.sort_indices()
    M = PETSc.Mat().createAIJ(size=Pc.shape, csr=(Pc.indptr.astype(PETSc.IntType), Pc.indices.astype(PETSc.IntType), Pc.data), comm=comm)
    M.setBlockSizes(3, 3)
    M.assemble()
    return M

def coarse_nns():
    X1 = np.load(f"{D}/coords_q1.npy")
    vecs = []
    modes = [np.tile(np.eye(3)[i], (len(X1), 1)) for i in range(3)]
    for i, j in [(0, 1), (1, 2), (2, 0)]:
        m = np.zeros_like(X1); m[:, i], m[:, j] = -X1[:, j], X1[:, i]; modes.append(m)
    for m in modes:
        vecs.append(PETSc.Vec().createWithArray(m.reshape(-1).copy(), comm=comm))
    for i, v in enumerate(vecs):
        for u in vecs[:i]:
            v.axpy(-v.dot(u), u)
        v.normalize()
    return PETSc.NullSpace().create(vectors=vecs, comm=comm)

def load(f):
    v = PETSc.Viewer().createBinary(f, "r", comm=comm)
    A = PETSc.Mat().create(comm=comm); A.load(v)
    b = PETSc.Vec().create(comm=comm); b.load(v); v.destroy()
    return A, b

def augmented(A):
    Auu = A.createSubMatrix(is_u, is_u)
    Aup = A.createSubMatrix(is_u, is_p)
    Apu = A.createSubMatrix(is_p, is_u)
    d = PETSc.Vec().createWithArray(gamma / (mu * lumped), comm=comm)
    Apu.diagonalScale(L=d)
    Aug = Auu.copy()
    Aug.axpy(1.0, Aup.matMult(Apu), structure=PETSc.Mat.Structure.DIFFERENT_NONZERO_PATTERN)
    Aug.setBlockSize(3)
    return Auu, Aup, Apu, Aug

Pmg = prolongation() if pctype == "pmg" else None
_keep = []
def inner_ksp(M, prefix="in_"):
    ksp = PETSc.KSP().create(comm); ksp.setOptionsPrefix(prefix)
    if nns is not None:
        M.setNearNullSpace(nns)
    ksp.setOperators(M)
    pc = ksp.getPC()
    if pctype == "pmg":
        pc.setType("mg"); pc.setMGLevels(2); pc.setMGType(PETSc.PC.MGType.MULTIPLICATIVE)
        pc.setMGInterpolation(1, Pmg)
        Ac = M.ptap(Pmg); Ac.setBlockSize(3)
        if nns is not None:
            Ac.setNearNullSpace(coarse_nns())
        pc.getMGCoarseSolve().setOperators(Ac)
        pc.getMGSmoother(1).setOperators(M)
        _keep.append(Ac)
    else:
        pc.setType(pctype)
    ksp.setFromOptions()
    return ksp

opts = PETSc.Options()
res = []
for f in sysfiles:
    A, b = load(f)
    t0 = time.perf_counter()
    Auu, Aup, Apu, Aug = augmented(A)
    if mode == "block":
        M = Auu if which == "uu" else Aug
        M.setBlockSize(3)
        rhs = b.getSubVector(is_u).copy(); b.restoreSubVector(is_u, b.getSubVector(is_u))
        if which == "coarse":
            Pq = prolongation(); M = Aug.ptap(Pq); M.setBlockSize(3); r2 = M.createVecLeft(); Pq.multTranspose(rhs, r2); rhs = r2
            M.setNearNullSpace(coarse_nns())
            ksp = PETSc.KSP().create(comm); ksp.setOptionsPrefix("in_"); ksp.setOperators(M); ksp.getPC().setType(pctype); ksp.setFromOptions()
        else:
            ksp = inner_ksp(M)
        x = M.createVecLeft()
        t1 = time.perf_counter(); ksp.solve(rhs, x); t2 = time.perf_counter()
        r = rhs.copy(); M.mult(x, r); r.aypx(-1, rhs)
        res.append(dict(sys=f[-7:-4], its=ksp.getIterationNumber(), reason=ksp.getConvergedReason(),
                        relres=r.norm() / rhs.norm(), setup_s=t1 - t0, solve_s=t2 - t1))
    else:
        ksp_in = inner_ksp(Aug)
        ksp_in.setUp()
        Dinv = PETSc.Vec().createWithArray(-gamma / (mu * lumped), comm=comm)
        ru = PETSc.Vec().createSeq(nu, comm=comm); yu = ru.duplicate(); tu = ru.duplicate()
        rp = Dinv.duplicate(); tp = Dinv.duplicate()
        inner_its = []
        class Shell:
            def apply(self, pc, r, y):
                r.getSubVector(is_u, ru) if False else None
                ru.setArray(r.getArray(readonly=True)[is_u_np]); rp.setArray(r.getArray(readonly=True)[is_p_np])
                tp.pointwiseMult(Dinv, rp)           # D^-1 r_p
                Aup.mult(tp, tu); tu.aypx(-1.0, ru)  # r_u - Bt D^-1 r_p
                ksp_in.solve(tu, yu); inner_its.append(ksp_in.getIterationNumber())
                Apu.mult(yu, tp); tp.aypx(-1.0, rp); tp.pointwiseMult(Dinv, tp)  # D^-1 (r_p - B y_u)
                ya = y.getArray(); ya[is_u_np] = yu.getArray(); ya[is_p_np] = tp.getArray()
        # NB Apu was scaled by gamma/(mu lumped) in augmented(): rebuild the plain one
        Apu = A.createSubMatrix(is_p, is_u)
        ksp = PETSc.KSP().create(comm); ksp.setOptionsPrefix("out_"); ksp.setOperators(A)
        ksp.setType("fgmres"); ksp.setGMRESRestart(200)
        ksp.setTolerances(rtol=float(kw.get("rtol", 1e-10)), atol=0.0, max_it=int(kw.get("maxit", 1000)))
        pc = ksp.getPC(); pc.setType("python"); pc.setPythonContext(Shell())
        ksp.setFromOptions()
        x = A.createVecRight()
        t1 = time.perf_counter(); ksp.solve(b, x); t2 = time.perf_counter()
        res.append(dict(sys=f[-7:-4], its=ksp.getIterationNumber(), reason=ksp.getConvergedReason(),
                        inner_mean=float(np.mean(inner_its)) if inner_its else 0, inner_total=int(np.sum(inner_its)),
                        setup_s=t1 - t0, solve_s=t2 - t1))
    if kw.get("view") == "1":
        (ksp if mode == "block" else ksp_in).view()
its = [r["its"] for r in res]
print(json.dumps(dict(dir=D, mode=mode, kw=kw, opts=" ".join(a for a in sys.argv[1:] if a not in _plain), mean=float(np.mean(its)), max=int(max(its)),
                      setup_s=float(sum(r["setup_s"] for r in res)), solve_s=float(sum(r["solve_s"] for r in res)),
                      rows=res)))
