import sys, json, math, tomllib
sys.path.insert(0, "../..")
from studies.verification import benchmarks as B
def scene(x, lengths, solver="dolfinx", law="neo-hookean", cells=4, steps=None, incompress="mixed", elements_per_h=2, name=None, fem=None):
    g = dict(B.STUDY["grid"]); g["bending_cells_per_h"] = cells; g["bending_elements_per_h"] = elements_per_h
    d = B.bending_scene(g, law, "plane-strain", x, lengths, solver)
    if steps: d["analysis"]["load_steps"] = steps
    if "fem" in d: d["fem"]["incompressibility"] = incompress
    if name: d["name"] = name
    if fem and "fem" in d: d["fem"].update(fem)
    return d
def _v(v):
    if isinstance(v, bool): return "true" if v else "false"
    if isinstance(v, str): return '"%s"' % v
    if isinstance(v, float): return repr(v)
    if isinstance(v, (list, tuple)): return "[" + ", ".join(_v(x) for x in v) + "]"
    return str(v)
def dump(d, path):
    out = []
    for k, v in d.items():
        if not isinstance(v, dict): out.append(f"{k} = {_v(v)}")
    for k, v in d.items():
        if isinstance(v, dict):
            out.append(f"\n[{k}]")
            for kk, vv in v.items(): out.append(f"{kk} = {_v(vv)}")
    open(path, "w").write("\n".join(out) + "\n")
if __name__ == "__main__":
    import argparse
    p = argparse.ArgumentParser()
    p.add_argument("x", type=float); p.add_argument("lengths", type=float); p.add_argument("out")
    p.add_argument("--solver", default="dolfinx"); p.add_argument("--cells", type=int, default=4)
    p.add_argument("--steps", type=int); p.add_argument("--inc", default="mixed"); p.add_argument("--eph", type=int, default=2)
    p.add_argument("--law", default="neo-hookean")
    a = p.parse_args()
    L = a.lengths if a.lengths != int(a.lengths) else int(a.lengths)
    dump(scene(a.x, L, a.solver, a.law, a.cells, a.steps, a.inc, a.eph), a.out)
