"""What every kinematics and solver of ancf stands on: the element specification's data
(:mod:`.spec`), polynomials, quadrature, the mesh, the material and its formulations, the
law's jets and tape, the band matrices and their compiled solves, the error of an
inadmissible state."""
