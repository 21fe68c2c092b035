"""The solvers of a built model: the static Newton with load stepping (:mod:`.statics`, compiled
in :mod:`.compiled_statics`), the end couple's loading (:mod:`.couple`), the stability verdict
of a static state (:mod:`.stability`), and the time integrators (:mod:`.integrators`, their
compiled step loop in :mod:`.compiled_steps`)."""
