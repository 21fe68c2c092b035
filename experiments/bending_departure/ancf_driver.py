"""ancf's CLI with one patch in this process only: with BEND_WEIGHT=rivlin:<kappa h>, the end
couple's first moment is weighted by Rivlin's exact nominal end traction phi(y) (mean removed)
instead of y: d = int r(L, y) phi dy / int y phi dy (a pure couple of moment M, whose traction
is Rivlin's at Rivlin's state); else unpatched."""
import os, sys, math
sys.path.insert(0, "../..")
import numpy as np
import ancf.build as B, ancf.solvers.couple as C
from ancf.core.quadrature import gauss
spec = os.environ.get("BEND_WEIGHT", "")
if spec.startswith("rivlin:"):
    kh = float(spec.split(":")[1]); C10 = 953018.0
    def end_face(model):
        m = model.mesh
        h = m.height; k = kh / h; la2 = math.exp(-math.asinh(kh))
        rule = gauss(1, 16)
        y = rule.eta * h; w = rule.weight / rule.weight.sum() * h
        lam2 = la2 + 2 * k * (h / 2 - y); lam = np.sqrt(lam2)
        phi = C10 * (3 * lam2 - 1 / lam2 - la2 - 1 / la2) / lam
        phi = phi - (w * phi).sum() / w.sum()
        N, _ = m.element.tabulate(np.ones_like(rule.eta), rule.eta, m.element_length, m.height)
        c = ((w * phi) @ N) / (w * phi * y).sum()
        dofs = m.element_dofs[-1]
        keep = np.abs(c) > 1e-12 * np.abs(c).max()
        c, dofs = c[keep], dofs[keep]
        rows = dofs.reshape(-1).astype(np.int64)
        A = np.zeros((2, len(rows))); A[0, 0::2], A[1, 1::2] = c, c
        d0 = A @ m.reference[rows]
        print("rivlin-weighted couple: d0 =", d0, file=sys.stderr)
        return C.EndFace(rows, A, d0)
    B.end_face = end_face
from ancf.cli import main
sys.exit(main())
