"""Which route IDA calls a model through: scikit-sundae's Python callback, or the compiled
kernels of ``solve/direct.py`` (numba, ``pip install ".[fast]"``).

Compiled kernels cost about half a second per process (numba's import and the kernels'
load) and save most of every solve, so they pay where one process solves one topology many
times. ``CIRCUITSIM_KERNELS`` decides when set (``numba``: on, anything else: off); unset,
the work that solves many times (fits, diagnoses, sweeps) asks for them through
``many_solves()`` and a single run does not. Without numba every route is the Python one.
"""

from __future__ import annotations

import functools
import os
from collections.abc import Callable
from typing import TypeVar

_many = [False]
_F = TypeVar("_F", bound=Callable)


def serial_blas(fn: _F) -> _F:
    """Run ``fn`` with one BLAS thread (threadpoolctl), restored after.

    A fit or a diagnosis calls BLAS and LAPACK on small matrices (least squares of 10 000
    samples by a few columns) thousands of times, while the second core is busy: the worker
    compiling kernels ahead (``solve/ahead.py``), a sweep's other process, or anything else
    on the machine. OpenBLAS's threads then wait for a core at every call: the slow-feature
    windows of a 0.4 s, 25 kHz record took 0.82 s instead of 0.019 s, and a whole diagnosis
    25.4 s instead of 6.6 s (the benchmark's k10, ``benchmarks/diagnosis/``), with one other
    process busy on this 2-core machine. At these sizes a second thread gains nothing."""
    @functools.wraps(fn)
    def wrapped(*args, **kwargs):
        from threadpoolctl import threadpool_limits

        with threadpool_limits(limits=1, user_api="blas"):
            return fn(*args, **kwargs)

    return wrapped  # type: ignore[return-value]


def many_solves() -> None:
    """Declare that this process is about to solve one topology many times."""
    _many[0] = True


def kernels_requested() -> bool:
    """Whether IDA should be offered the compiled kernels (numba may still be missing)."""
    choice = os.environ.get("CIRCUITSIM_KERNELS", "").strip().lower()
    return choice == "numba" if choice else _many[0]
