"""Profile of a continuum run: per reference section X, the section's angle theta (of its first
moment d, as the couple reads it), the local curvature dtheta/dX, the deformed thickness / h,
and the hoop stretch at inner and outer faces; compared with Rivlin's flexure."""
import sys, glob, json, math, re
import numpy as np
sys.path.insert(0, "../..")
from studies.verification.closed_forms import rivlin_bending
import xml.etree.ElementTree as ET

def read_vtu(d):
    f = (sorted(glob.glob(d + "/*_p0_*.vtu")) or sorted(glob.glob(d + "/*.vtu")))[-1]
    root = ET.parse(f).getroot()
    pts = None; data = {}
    for da in root.iter("DataArray"):
        arr = np.array(da.text.split(), float)
        nc = int(da.get("NumberOfComponents", "1"))
        name = da.get("Name")
        if name is None and nc == 3 and pts is None:
            pts = arr.reshape(-1, 3)
        elif name:
            data[name] = arr.reshape(-1, nc) if nc > 1 else arr
    return pts, data

def profile(vtkdir, kh, h=0.005, C10=953018.0, quiet=False):
    X, data = read_vtu(vtkdir)
    u = [v for k, v in data.items() if v.ndim == 2 and v.shape[1] == 3][0]
    x = X[:, :2] + u[:, :2]
    xs = np.unique(np.round(X[:, 0], 10)); ys = np.unique(np.round(X[:, 1], 10))
    ref = rivlin_bending("neo-hookean", {"C10": C10}, kh / h, h)
    th, thick, lin, lout, dnorm = [], [], [], [], []
    for xx in xs:
        sel = np.abs(X[:, 0] - xx) < 1e-9
        Y = X[sel, 1]; o = np.argsort(Y); Y = Y[o]; r = x[sel][o]
        # trapezoid first moment (degree-1 interpolation)
        w = np.gradient(Y) if len(Y) > 2 else np.ones_like(Y)
        w = np.array([ (Y[min(i+1,len(Y)-1)] - Y[max(i-1,0)]) / 2 for i in range(len(Y))])
        rc = (w[:, None] * r).sum(0) / w.sum()
        d = (w[:, None] * (r - rc) * Y[:, None]).sum(0) / (w * Y * Y).sum()
        th.append(math.atan2(-d[0], d[1])); dnorm.append(np.linalg.norm(d))
        thick.append(np.linalg.norm(r[-1] - r[0]) / h)
    th = np.unwrap(np.array(th))
    # stretch of the faces: arc length of the deformed faces per reference length
    for yy, lst in ((ys[0], lin), (ys[-1], lout)):
        sel = np.abs(X[:, 1] - yy) < 1e-9
        o = np.argsort(X[sel, 0]); s = x[sel][o]
        seg = np.linalg.norm(np.diff(s, axis=0), axis=1) / np.diff(X[sel, 0][o])
        lst.extend(seg)
    kap = np.gradient(th, xs) * h
    return dict(xs=xs, theta=th, kh_local=kap, thick=np.array(thick), lam_in=np.array(lin), lam_out=np.array(lout),
                dnorm=np.array(dnorm), ref=ref)

if __name__ == "__main__":
    d, kh = sys.argv[1], float(sys.argv[2])
    p = profile(d, kh); h = 0.005; ref = p["ref"]
    print(f"Rivlin kh={kh}: thickness ratio {ref['thickness_ratio']:.4f} lam_in {ref['lambda_inner']:.4f} lam_out {ref['lambda_outer']:.4f}")
    print(" X/h   theta   theta/(kX)-1  local kh   thick/h   |d|")
    for i in range(0, len(p["xs"]), max(1, len(p["xs"]) // 24)):
        X = p["xs"][i]
        print(f"{X/h:5.2f} {p['theta'][i]:7.4f} {p['theta'][i]/(kh*X/h)-1 if X>0 else 0:+.4f} {p['kh_local'][i]:8.4f} {p['thick'][i]:8.4f} {p['dnorm'][i]:.4f}")
    print("lam_in  (per seg) min/max", p["lam_in"].min(), p["lam_in"].max())
    print("lam_out (per seg) min/max", p["lam_out"].min(), p["lam_out"].max())
