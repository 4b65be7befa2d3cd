"""The ``circuitsim`` command's entry point, outside the package on purpose.

Importing ``circuitsim`` takes a few tenths of a second (numpy, the component library); a
Ctrl-C then would print a ``KeyboardInterrupt`` traceback, because no code of ours runs before
the package's imports. This module imports nothing heavy, so it can catch it: exit 130 with one
line, as the command does once running. It also notes the signal itself: an interrupt that
lands inside an extension module's initialisation (numpy's) surfaces as an ImportError.
"""

import os
import signal
import sys


class _Interrupt:
    """SIGINT handler for the import: remembers that it ran, then interrupts as usual."""

    seen = False

    def __call__(self, signum, frame):
        self.seen = True
        raise KeyboardInterrupt


def main() -> int:
    # circuitsim's dense algebra is small (least squares of a few columns, matrices of a few
    # hundred unknowns at most): BLAS threads cost more in hand-overs than they save, and on a
    # busy machine every threaded call waits for a free core (measured on 2 shared cores: a
    # ripple fit's 1200 x 8 least squares 0.1 ms alone, 8 ms threaded; 0.2-0.3 s of a run).
    # Set before numpy loads OpenBLAS; a user's own setting wins.
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    interrupt = _Interrupt()
    signal.signal(signal.SIGINT, interrupt)
    try:
        from circuitsim.cli.main import main as run
    except BaseException:
        if not interrupt.seen:
            raise
        print("interrupted", file=sys.stderr)
        return 130
    finally:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    return run()


if __name__ == "__main__":
    sys.exit(main())
