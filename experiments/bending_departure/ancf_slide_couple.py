"""The proposed end moment in ANCF: the free end face r(L, y) held on a straight line of angle
theta, free along it, by the penalty kp/2 int ((r(L, y) . n(theta)) - a)^2 dy (exact face
integral of the last element's section, Gauss across), theta and a two global unknowns, the
load potential -M theta. The repo's model (element, law, penalty, quadrature, slide support)
is built by ancf.build.build_model as for `ancf run`; the Newton loop (dense), the penalty and
the two unknowns are here. Also: the inertia of the final tangent (negative eigenvalues =
unstable directions of the discrete potential) and the section profile.

usage: ancf_slide_couple.py scene.toml out.json [kp_factor]"""
import sys, json, math
sys.path.insert(0, "../.."); sys.path.insert(0, ".")
import numpy as np
from contract.scene import load_scene
from ancf.build import build_model, plan
from ancf.core.quadrature import gauss
from studies.verification.closed_forms import rivlin_bending

scene = load_scene(sys.argv[1]); out = sys.argv[2]
import os; DEBUG = os.environ.get('DEBUG')
kpf = float(sys.argv[3]) if len(sys.argv) > 3 else 1e4
model = build_model(plan(scene)); m = model.mesh
h, L, w = scene.beam.height, scene.beam.length, scene.beam.width
M = scene.loads.end_moment
n_dof = m.n_dof
fixed = np.asarray(model.fixed if hasattr(model, "fixed") else [], int)
ref = m.reference
rule = gauss(1, 6)
N, _ = m.element.tabulate(np.ones_like(rule.eta), rule.eta, m.element_length, m.height)   # (nq, ns)
yq = rule.eta * h; wq = rule.weight / rule.weight.sum() * h * w
dofs = m.element_dofs[-1]                                  # (ns, 2)
Pq = np.zeros((len(yq), 2, n_dof))
for q in range(len(yq)):
    for s_ in range(N.shape[1]):
        Pq[q, 0, dofs[s_, 0]] += N[q, s_]; Pq[q, 1, dofs[s_, 1]] += N[q, s_]
r0q = np.einsum("qij,j->qi", Pq, ref)
print("face check: r0 at y_q", np.round(r0q[:, 1] / h, 4), np.round(r0q[:, 0] / L, 6), file=sys.stderr)
C10 = scene.material.constants.get("C10", 1.0)
kp = kpf * 2 * C10 / h          # per unit area of the face (N/m^3), times the face area h w in the weights
free = np.setdiff1d(np.arange(n_dof), np.asarray(sorted(set(map(int, getattr(model, "fixed_dofs", fixed))))) )

def parts(u, th, a, Mt):
    f, K = model.internal_force_and_tangent(u)
    Kd = np.zeros((n_dof, n_dof)); b = K.b
    for dgi in range(-b, b + 1):
        row = K.ab[b + dgi] if K.ab.shape[0] == 2 * b + 1 else None
        # general band storage ab[b + i - j, j] = K[i, j]
        j = np.arange(max(0, -dgi), min(n_dof, n_dof - dgi)); i = j + dgi
        Kd[i, j] = K.ab[b + dgi, j]
    n = np.array([math.cos(th), math.sin(th)]); t = np.array([-math.sin(th), math.cos(th)])
    r = r0q + np.einsum("qij,j->qi", Pq, u)
    g = r @ n - a; tr = r @ t; nr = r @ n
    Pn = np.einsum("qij,i->qj", Pq, n); Pt = np.einsum("qij,i->qj", Pq, t)
    R = np.zeros(n_dof + 2); H = np.zeros((n_dof + 2, n_dof + 2))
    R[:n_dof] = f + kp * (wq * g) @ Pn
    R[n_dof] = kp * np.sum(wq * g * tr) - Mt
    R[n_dof + 1] = -kp * np.sum(wq * g)
    H[:n_dof, :n_dof] = Kd + kp * (Pn.T * wq) @ Pn
    H[:n_dof, n_dof] = H[n_dof, :n_dof] = kp * ((wq * tr) @ Pn + (wq * g) @ Pt)
    H[:n_dof, n_dof + 1] = H[n_dof + 1, :n_dof] = -kp * wq @ Pn
    H[n_dof, n_dof] = kp * np.sum(wq * (tr ** 2 - g * nr))
    H[n_dof, n_dof + 1] = H[n_dof + 1, n_dof] = -kp * np.sum(wq * tr)
    H[n_dof + 1, n_dof + 1] = kp * np.sum(wq)
    return R, H

u = np.zeros(n_dof); th = 0.0; a = L
act = np.concatenate([free, [n_dof, n_dof + 1]])
steps = scene.analysis.load_steps
status = "converged"; hist = []
t = 0.0; dt = 1.0 / steps
while t < 1.0 - 1e-12 and status == "converged":
    t1 = min(1.0, t + dt); Mt = M * t1
    u0, th0, a0 = u.copy(), th, a
    ok = False
    for it in range(40):
        try:
            R, H = parts(u, th, a, Mt)
        except Exception as e:
            print("exception", type(e).__name__, str(e)[:120], file=sys.stderr); break
        nr = np.linalg.norm(R[act])
        if it == 0: n0 = nr
        if DEBUG: print(t1, it, nr, file=sys.stderr)
        if nr < max(1e-9 * n0, 1e-8 * abs(M) / h):
            ok = True; break
        Ha = H[np.ix_(act, act)]; sc = 1.0 / np.sqrt(np.abs(np.diag(Ha)))   # Jacobi scaling (dofs of very different sizes)
        dz = sc * np.linalg.solve(Ha * sc[:, None] * sc[None, :], -R[act] * sc)
        z = np.zeros(n_dof + 2); z[act] = dz
        lam = 1.0
        for _ in range(12):      # backtracking: an admissible state whose residual does not blow up
            try:
                Rn, _ = parts(u + lam * z[:n_dof], th + lam * z[n_dof], a + lam * z[n_dof + 1], Mt)
                if np.linalg.norm(Rn[act]) < 10 * nr + 1e-12 or lam < 1e-3:
                    break
            except Exception:
                pass
            lam /= 2
        u += lam * z[:n_dof]; th += lam * z[n_dof]; a += lam * z[n_dof + 1]
    if ok:
        t = t1; hist.append((t, th, it)); dt = min(dt * 1.5, 1.0 / steps)
    else:
        u, th, a = u0, th0, a0; dt /= 2
        if dt < 1e-4: status = f"failed at t = {t:.4f}"
R, H = parts(u, th, a, M * t)
Hf = H[np.ix_(act, act)]; sc = 1.0 / np.sqrt(np.abs(np.diag(Hf)))
ev = np.linalg.eigvalsh(Hf * sc[:, None] * sc[None, :])     # congruent: the same inertia
# stable if the Hessian of the total potential (u, theta, a) is positive definite
neg = int((ev < -1e-10 * abs(ev).max()).sum())
kh = None
res = dict(status=status, load_reached=t, theta=th, a=a, unstable_directions=neg, lowest_eig=float(ev[0]),
           n_free=len(act))
# section profile at the nodes: angle of r_y (first moment of the section, d) and thickness
kinds = m.element.kinds
prof = []
q = ref + u
for node in range(m.n_nodes):
    ry = q[m.dofs(node, ("r_y",))]
    # first moment d of the section at the node (exact over the section polynomial)
    prof.append((float(m.node_x[node]), math.atan2(-ry[0], ry[1])))
res["profile"] = prof
json.dump(res, open(out, "w"), indent=1)
print(json.dumps({k: v for k, v in res.items() if k != "profile"}))
