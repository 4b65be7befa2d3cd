"""``python -m circuitsim.cli``: the same as the ``circuitsim`` command."""

import sys

from circuitsim.cli.main import main

sys.exit(main())
