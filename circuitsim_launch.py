"""The ``circuitsim`` command's entry point, outside the package on purpose.

Importing ``circuitsim`` takes about a second (numpy, sympy, the component library); a Ctrl-C
in that second would print a ``KeyboardInterrupt`` traceback, because no code of ours runs
before the package's imports. This module imports nothing heavy, so it can catch it: exit 130
with one line, as the command does once running.
"""

import sys


def main() -> int:
    try:
        from circuitsim.cli.main import main as run
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    return run()


if __name__ == "__main__":
    sys.exit(main())
