#!/bin/bash
# usage: sc_sweep.sh kh Lh cells kfac [celltype]
x=$1; L=$2; c=$3; kf=$4; cell=${5:-quadrilateral}
n=runs/sc_${x}_L${L}_c${c}_k${kf}_${cell}
../../.venv/bin/python mk.py $x $L $n.toml --cells $c
[ "$cell" != quadrilateral ] && echo "cell = \"$cell\"" >> $n.toml
OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 timeout 900 ../../.venv/bin/python slide_couple.py $n.toml $n.json $kf > $n.log 2>&1
tail -1 $n.log | cut -c1-200
../../.venv/bin/python - "$n" "$x" "$L" <<'PY'
import sys, json, numpy as np; sys.path.insert(0, ".")
from prof import profile
n, x, L = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]); h = 0.005
r = json.load(open(n + ".json"))
if r["status"] == "converged":
    p = profile(n + "_vtk", x); xs, th = p["xs"], p["theta"]
    m = (xs >= h - 1e-12) & (xs <= L * h - 2 * h + 1e-12)
    sl = np.polyfit(xs[m], th[m], 1)[0] * h
    o = dict(name=n, kh=x, Lh=L, theta_err=r["theta"] / (x * L) - 1, vert_end_err=th[-1] / (x * L) - 1, interior_err=sl / x - 1,
             unstable=r.get("unstable_directions"), thick_end=p["thick"][-1], thick_rivlin=p["ref"]["thickness_ratio"], lam_inner_min=float(np.nanmin(p["lam_out"])),
             lam_inner_max=float(np.nanmax(p["lam_out"])), lam_rivlin=p["ref"]["lambda_inner"], gap_rms=r["gap_rms"])
else:
    o = dict(name=n, status=r["status"])
print(json.dumps(o)); open("./res_slide.jsonl", "a").write(json.dumps(o) + "\n")
PY
