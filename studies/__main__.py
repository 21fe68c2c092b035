import os
import sys

# One BLAS / OpenMP thread per process (before numpy loads): pool workers share the
# cores, and serial timings must not depend on a thread pool (the Makefile sets the same).
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

try:
    from .cli import main  # noqa: E402
except KeyboardInterrupt:   # Ctrl-C while the modules load: one line, as later (contract.console)
    print("studies: interrupted (nothing was run)", file=sys.stderr)
    sys.exit(130)

if __name__ == "__main__":
    sys.exit(main())
