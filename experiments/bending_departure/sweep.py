"""Run DOLFINx bending scenes one at a time; tabulate the record's end rotation against kappa L,
the interior curvature (fit of the vertex sections' angle over X in [h, L - 2h]), the end face's
vertex-based angle, its thickness ratio and |d|, and the record's smallest det F."""
import sys, json, subprocess, os, math
import numpy as np
sys.path.insert(0, "."); sys.path.insert(0, "../..")
from mk import scene, dump
from prof import profile
PY = "../../.venv/bin/python"
env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
h = 0.005
def run(x, Lh, cells=4, inc="mixed", steps=None, tag="", driver="driver.py", fem=None, weight=""):
    name = f"kh{x}_L{Lh}_c{cells}_{inc}_s{steps}{tag}"
    s = scene(x, Lh, "dolfinx", cells=cells, steps=steps, incompress=inc, name=name, fem=fem)
    os.makedirs("runs", exist_ok=True)
    p = f"runs/{name}.toml"; dump(s, p)
    cmd = [PY] + ([driver] if driver else ["-m", "reference_fem"]) + ["run", p, "--json", f"runs/{name}.json", "--vtk", f"runs/{name}_vtk", "--quiet"]
    if os.path.exists(f"runs/{name}.json"): os.remove(f"runs/{name}.json")
    subprocess.run(cmd, env=dict(env, BEND_WEIGHT=weight), cwd=".", stdout=open(f"runs/{name}.log", "w"), stderr=subprocess.STDOUT)
    if not os.path.exists(f"runs/{name}.json"):
        return dict(name=name, kh=x, Lh=Lh, cells=cells, inc=inc, status="crashed", reason=open(f"runs/{name}.log").read().strip().splitlines()[-1])
    r = json.load(open(f"runs/{name}.json"))
    out = dict(name=name, kh=x, Lh=Lh, cells=cells, inc=inc, status=r["status"], load=r.get("load_reached"))
    if r["status"] != "converged":
        out["reason"] = r.get("reason"); return out
    kL = x * Lh
    p = profile(f"runs/{name}_vtk", x)
    xs, th = p["xs"], p["theta"]
    m = (xs >= min(1, Lh / 4) * h - 1e-12) & (xs <= Lh * h - max(2, Lh / 4) * h + 1e-12) if Lh >= 4 else (xs >= 0.25 * Lh * h) & (xs <= 0.5 * Lh * h)
    slope = np.polyfit(xs[m], th[m], 1)[0] * h
    out.update(rot_err=r["tip"]["rotation"] / kL - 1, vert_end_err=th[-1] / kL - 1, interior_kh=slope,
               interior_err=slope / x - 1, thick_end=p["thick"][-1], thick_mid=p["thick"][len(xs)//2],
               thick_rivlin=p["ref"]["thickness_ratio"], d_end=p["dnorm"][-1], detF_min=r["admissibility"]["det_F"],
               detF_at=r["admissibility"]["at"], newton=r["newton_iterations"], steps=r["load_steps"])
    return out
if __name__ == "__main__":
    import ast
    res = []
    for spec in sys.argv[2:]:
        kw = eval(spec)
        o = run(**kw); res.append(o); print(json.dumps(o), flush=True)
    with open(sys.argv[1], "a") as f:
        for o in res: f.write(json.dumps(o) + "\n")
