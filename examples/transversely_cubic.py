"""A user's element, registered from outside the package (README "Elements, laws,
formulations"): HB2n-20, transversely cubic (r, r_x, r_y, r_yy, r_yyy at two nodes).

    .venv/bin/python -m studies card HB2n-20 --import examples.transversely_cubic

It declares no default quadrature: scenes get the rule exact for its basis (4 x 4).
"""
from ancf.elements import ELEMENTS, ElementSpec, register_element

if "HB2n-20" not in ELEMENTS:
    register_element(ElementSpec(
        name="HB2n-20",
        basis=("1", "x", "y", "x*y", "x^2", "y^2", "x*y^2", "x^3", "y^3", "x*y^3"),
        nodes=(0.0, 1.0), kinds=("r", "r_x", "r_y", "r_yy", "r_yyy"),
        reference="README example: transversely cubic"))
