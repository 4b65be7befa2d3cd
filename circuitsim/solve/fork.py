"""Independent pieces of one computation shared with this machine's other cores, by fork.

A diagnosis refits several candidates a round, and several combinations of effects when it
revises its choice: each refit is seconds of simulations that do not depend on the others.
``fork_map`` runs such pieces in this process and in forked copies of it, which inherit
everything built so far (compiled models, fitted states, caches), so nothing is pickled on
the way in and only the results come back. The pieces are taken from a shared queue (a pipe
of indices), so a long one does not hold up the rest. Each piece runs the same code on the
same values wherever it runs: the results are the same numbers as one after another.

A copy that fails or dies leaves its pieces to this process, which computes them again (an
exception is then raised here, with its own traceback). Forked copies never start a process
of their own (compiling ahead, ``solve/ahead.py``, or a nested ``fork_map``), and die with
this one. ``CIRCUITSIM_FORK=off`` turns it off; it is off on a single core and where the
platform has no ``fork`` (Windows; macOS's system libraries are not safe to fork either).
"""

from __future__ import annotations

import os
import pickle
import signal
import struct
import sys
import warnings
from collections.abc import Callable, Sequence
from typing import Any, TypeVar

_T = TypeVar("_T")
_R = TypeVar("_R")
#: set in a forked copy: it computes its share alone
_IN_COPY = [False]
_INDEX = struct.Struct("<i")
#: the most pieces one call shares: their indices must fit in a pipe's buffer (64 KiB on
#: Linux, never less than a page) before any copy reads them
MAX_PIECES = 1000


def copies() -> int:
    """How many forked copies ``fork_map`` runs beside this process (0: it runs serially)."""
    if _IN_COPY[0] or not sys.platform.startswith("linux") or not hasattr(os, "fork"):
        return 0
    if os.environ.get("CIRCUITSIM_FORK", "").strip().lower() in ("0", "off", "no"):
        return 0
    return max(len(os.sched_getaffinity(0)) - 1, 0)


def in_copy() -> bool:
    """Whether this process is a forked copy computing its share."""
    return _IN_COPY[0]


def fork_map(fn: Callable[[_T], _R], items: Sequence[_T]) -> list[_R]:
    """``[fn(x) for x in items]``, shared with forked copies of this process. ``fn``'s result
    must pickle; its side effects in a copy are lost (return what the caller needs)."""
    items = list(items)
    n_copies = min(copies(), len(items) - 1)
    if n_copies <= 0 or len(items) > MAX_PIECES:
        return [fn(x) for x in items]
    queue_r, queue_w = os.pipe()
    os.write(queue_w, b"".join(_INDEX.pack(i) for i in range(len(items))))
    os.close(queue_w)  # an empty queue then reads as its end, in every copy
    children = []
    for _ in range(n_copies):
        try:
            children.append(_spawn(fn, items, queue_r))
        except OSError:  # no process or pipe to spare: fewer copies, or none
            break
    done: dict[int, Any] = {}
    try:
        for i in _taken(queue_r):
            done[i] = fn(items[i])
    except BaseException:
        for pid, out in children:  # an interrupt or an error here: the copies stop too
            os.kill(pid, signal.SIGKILL)
            _collect(pid, out)
        raise
    finally:
        os.close(queue_r)
    for pid, out in children:
        got = _collect(pid, out)
        done.update((i, v) for i, (ok, v) in got.items() if ok)
    # a piece whose copy raised or died is computed here: the same error, raised here
    return [done[i] if i in done else fn(items[i]) for i in range(len(items))]


def _taken(queue_r: int):
    """The indices this process takes off the shared queue, one at a time."""
    while True:
        data = os.read(queue_r, _INDEX.size)  # a pipe's reads of 4 bytes are whole
        if len(data) < _INDEX.size:
            return
        yield _INDEX.unpack(data)[0]


def _spawn(fn: Callable, items: list, queue_r: int) -> tuple[int, int]:
    """A forked copy taking pieces off the queue; its pid and the pipe its results come by."""
    out_r, out_w = os.pipe()
    try:
        with warnings.catch_warnings():
            # Python 3.12+ warns of forking beside threads; the copy runs only its own code
            # and touches none of their locks (beside a diagnosis: compiling ahead's reader)
            warnings.simplefilter("ignore", DeprecationWarning)
            pid = os.fork()
    except OSError:
        os.close(out_r)
        os.close(out_w)
        raise
    if pid:
        os.close(out_w)
        return pid, out_r
    status = 1
    try:  # the copy: never returns into the caller's code
        os.close(out_r)
        _become_copy()
        results: dict[int, tuple[bool, Any]] = {}
        for i in _taken(queue_r):
            try:
                results[i] = (True, fn(items[i]))
            except BaseException:  # noqa: BLE001 - the caller computes it again, and raises
                results[i] = (False, None)
        data = _pickled(results)
        with os.fdopen(out_w, "wb") as pipe:
            pipe.write(data)
        status = 0
    finally:
        os._exit(status)


def _pickled(results: dict[int, tuple[bool, Any]]) -> bytes:
    """The results as bytes; one that does not pickle is left to the caller to compute."""
    try:
        return pickle.dumps(results, protocol=pickle.HIGHEST_PROTOCOL)
    except Exception:  # noqa: BLE001 - any of pickle's errors: send what does pickle
        kept = {}
        for i, v in results.items():
            try:
                pickle.dumps(v, protocol=pickle.HIGHEST_PROTOCOL)
                kept[i] = v
            except Exception:  # noqa: BLE001
                kept[i] = (False, None)
        return pickle.dumps(kept, protocol=pickle.HIGHEST_PROTOCOL)


def _become_copy() -> None:
    """A forked copy: it dies with its parent, starts no process and shares no worker."""
    _IN_COPY[0] = True
    os.environ["CIRCUITSIM_AHEAD"] = "off"
    from circuitsim.solve import ahead

    ahead._WORKER[:] = []  # the parent's worker: its pipes are the parent's to use
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    try:
        import ctypes

        ctypes.CDLL(None).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass
    if os.getppid() == 1:  # the parent died before prctl took effect
        os._exit(1)


def _collect(pid: int, out: int) -> dict[int, tuple[bool, Any]]:
    """What a copy sent (nothing when it died), once it has ended."""
    chunks = []
    with os.fdopen(out, "rb") as pipe:
        while chunk := pipe.read(1 << 20):
            chunks.append(chunk)
    _, status = os.waitpid(pid, 0)
    if status != 0 or not chunks:
        return {}
    try:
        return pickle.loads(b"".join(chunks))
    except Exception:  # noqa: BLE001 - a truncated message: its pieces are computed here
        return {}
