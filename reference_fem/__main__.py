import sys

try:
    from .cli import main
except KeyboardInterrupt:   # Ctrl-C while the modules load: one line, as later (contract.console)
    print("reference_fem: interrupted", file=sys.stderr)
    sys.exit(130)

sys.exit(main())
