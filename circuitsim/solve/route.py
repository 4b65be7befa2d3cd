"""Which route IDA calls a model through: scikit-sundae's Python callback, or the compiled
kernels of ``solve/direct.py`` (numba, ``pip install ".[fast]"``).

Compiled kernels cost about half a second per process (numba's import and the kernels'
load) and save most of every solve, so they pay where one process solves one topology many
times. ``CIRCUITSIM_KERNELS`` decides when set (``numba``: on, anything else: off); unset,
the work that solves many times (fits, diagnoses, sweeps) asks for them through
``many_solves()`` and a single run does not. Without numba every route is the Python one.
"""

from __future__ import annotations

import os

_many = [False]


def many_solves() -> None:
    """Declare that this process is about to solve one topology many times."""
    _many[0] = True


def kernels_requested() -> bool:
    """Whether IDA should be offered the compiled kernels (numba may still be missing)."""
    choice = os.environ.get("CIRCUITSIM_KERNELS", "").strip().lower()
    return choice == "numba" if choice else _many[0]
