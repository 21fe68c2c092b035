import sys; sys.path.insert(0,'.')
from prof import profile
import numpy as np
np.set_printoptions(linewidth=200)
for d, kh in [(a, float(b)) for a, b in zip(sys.argv[1::2], sys.argv[2::2])]:
    p = profile(d, kh)
    print(d, 'Rivlin inner', round(p['ref']['lambda_inner'], 4))
    print(' inner-face (Y=+h/2) stretch per vertex segment:', np.round(p['lam_out'], 3))
    print(' local kh along X (every point):', np.round(p['kh_local'][::2], 3))
