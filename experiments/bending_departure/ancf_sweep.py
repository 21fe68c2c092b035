import sys, json, subprocess, os
sys.path.insert(0, ".")
from mk import scene, dump
PY = "../../.venv/bin/python"
env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", NUMBA_NUM_THREADS="1")
def run(x, Lh, el="HB2n-40p", eph=2, weight="", steps=None, tag=""):
    name = f"ancf_{el}_kh{x}_L{Lh}_e{eph*Lh}_s{steps}{tag}"
    s = scene(x, Lh, el, elements_per_h=eph, steps=steps, name=name)
    p = f"runs/{name}.toml"; dump(s, p)
    j = f"runs/{name}.json"
    if os.path.exists(j): os.remove(j)
    subprocess.run([PY, "ancf_driver.py", "run", p, "--json", j, "--vtk", f"runs/{name}_vtk", "--quiet"], env=dict(env, BEND_WEIGHT=weight),
                   stdout=open(f"runs/{name}.log", "w"), stderr=subprocess.STDOUT)
    if not os.path.exists(j):
        return dict(name=name, status="crashed", reason=open(f"runs/{name}.log").read().strip().splitlines()[-1])
    r = json.load(open(j))
    o = dict(name=name, kh=x, Lh=Lh, elements=eph * Lh, status=r["status"], reason=r.get("reason"))
    if r["status"] == "converged":
        o.update(rot_err=r["tip"]["rotation"] / (x * Lh) - 1, negative_eigenvalues=r.get("negative_eigenvalues"), lowest_eig=r.get("lowest_eigenvalue"))
    return o
if __name__ == "__main__":
    res = []
    for spec in sys.argv[2:]:
        o = run(**eval(spec)); res.append(o); print(json.dumps(o), flush=True)
    with open(sys.argv[1], "a") as f:
        for o in res: f.write(json.dumps(o) + "\n")
