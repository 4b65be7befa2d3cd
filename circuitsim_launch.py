"""The ``circuitsim`` command's entry point, outside the package on purpose.

Importing ``circuitsim`` takes about a second (numpy, sympy, the component library); a Ctrl-C
in that second would print a ``KeyboardInterrupt`` traceback, because no code of ours runs
before the package's imports. This module imports nothing heavy, so it can catch it: exit 130
with one line, as the command does once running.
"""

import os
import sys


def main() -> int:
    # circuitsim's dense algebra is small (least squares of a few columns, matrices of a few
    # hundred unknowns at most): BLAS threads cost more in hand-overs than they save, and on a
    # busy machine every threaded call waits for a free core (measured on 2 shared cores: a
    # ripple fit's 1200 x 8 least squares 0.1 ms alone, 8 ms threaded; 0.2-0.3 s of a run).
    # Set before numpy loads OpenBLAS; a user's own setting wins.
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    try:
        from circuitsim.cli.main import main as run
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    return run()


if __name__ == "__main__":
    sys.exit(main())
