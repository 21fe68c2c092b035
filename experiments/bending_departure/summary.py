"""Light post-processing: ANCF straight-face runs' section angle along x, and the end traction of
the repo's couple against Rivlin's at the same moment."""
import sys, json, math, glob
sys.path.insert(0, "../..")
import numpy as np
from studies.verification.closed_forms import rivlin_bending
h, w, C10 = 0.005, 0.007, 953018.0
for f in sorted(glob.glob("runs/asc_*.json")):
    r = json.load(open(f)); x = float(f.split("_")[1]); p = np.array(r["profile"])
    X, th = p[:, 0], np.unwrap(p[:, 1]); loc = np.diff(th) / np.diff(X) * h
    print(f, "theta/kL-1 = %+.2e" % (r["theta"] / (x * 8) - 1), "unstable", r["unstable_directions"],
          "local kh per element: min %.5f max %.5f (target %.2f)" % (loc.min(), loc.max(), x))
print()
for x in (0.30, 0.35, 0.39, 0.45):
    ref = rivlin_bending("neo-hookean", {"C10": C10}, x / h, h); k = x / h
    M = ref["moment_per_width"]
    la2 = ref["lambda_inner"] ** 2
    Y = np.array([h / 2, -h / 2])                       # inner (compressed, M > 0) and outer face
    lam2 = la2 + 2 * k * (h / 2 - Y); lam = np.sqrt(lam2)
    P = C10 * (3 * lam2 - 1 / lam2 - la2 - 1 / la2) / lam   # Rivlin's nominal hoop traction (Pa)
    lin = -12 * M / h ** 3 * Y                          # the couple's traction at |d| = 1 (nominal, Pa)
    print(f"kh {x}: Rivlin nominal end traction inner {P[0]/1e6:+.3f} MPa, outer {P[1]/1e6:+.3f}; "
          f"the couple's (linear in Y) {lin[0]/1e6:+.3f} / {lin[1]/1e6:+.3f} MPa (x 1/|d|); inner excess {lin[0]/P[0]-1:+.1%}")
