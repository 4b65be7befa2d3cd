"""Topologies compiled ahead of need, in a second process, while this one works.

A diagnosis compiles a dozen topologies, and from an empty cache most of its time is numba
compiling their kernels: type inference in Python, which holds the interpreter, about half a
second a topology. On a machine with two cores or more, a worker process
(``python -m circuitsim.solve.ahead``) compiles the topologies a caller expects to need into
the cache folder they share, one at a time in the order given. Before compiling a topology
itself the caller claims it: one the worker finished is read from the cache, one the worker is
compiling is waited for, one still queued is taken off the queue and compiled here. The
numbers are the same either way; only who pays the compile changes. A caller queues its
guesses as well (a diagnosis: the circuits its next step needs if the best candidate wins,
and those it needs if none does), in the order they would be needed, and replaces them when
it knows more. The kernels are named by their source (``direct.kernel_name``): topologies
whose equations give the same code share one compile. A topology the caller compiles itself
is shared too: while it compiles the residual's kernel, the Jacobian's is lent to the worker
(``lend``, at the head of the queue), and loaded from the cache once the worker has it.

With a C compiler (``solve/ccode.py``) a topology's kernels are one quick build of a
library, so nothing is lent; the worker still derives the topologies' models ahead.

A plain subprocess with a pipe, not ``multiprocessing``: that would re-run the user's main
script in the worker. ``CIRCUITSIM_AHEAD=off`` turns it off; it is off without numba, without
a trusted cache folder, and on a single core.
"""

from __future__ import annotations

import atexit
import contextlib
import hashlib
import os
import pickle
import struct
import subprocess
import sys
import threading
from collections.abc import Iterable
from pathlib import Path
from typing import Any

#: the longest a claim waits for the worker's compile of one topology [s] (then it compiles
#: the topology itself)
WAIT = 120.0


def _key(raw) -> str | None:
    """The job's name: its pickle's hash (None for a netlist that cannot be pickled: it is
    compiled where it is needed, as without a worker)."""
    try:
        return hashlib.sha256(pickle.dumps(raw, protocol=4)).hexdigest()
    except (pickle.PicklingError, TypeError, AttributeError, RecursionError):
        return None


class _Worker:
    """The worker process, the jobs queued for it, and the one it is compiling."""

    def __init__(self, folder: Path):
        import circuitsim

        env = dict(os.environ, CIRCUITSIM_CACHE=str(folder))
        # the worker imports this very package, wherever it was imported from
        env["PYTHONPATH"] = os.pathsep.join(
            [str(Path(circuitsim.__file__).resolve().parents[1]), env.get("PYTHONPATH", "")])
        self.folder = folder
        self.proc = subprocess.Popen([sys.executable, "-m", "circuitsim.solve.ahead"],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.DEVNULL, env=env)
        self.cond = threading.Condition()
        self.queue: list[tuple[str, Any]] = []
        self.running: str | None = None  # sent to the worker
        self.compiling: str | None = None  # the worker found it not compiled yet: at work
        self.done: set[str] = set()
        self.alive = True
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        """Collect the worker's reports ('start <key>' when it compiles, 'done <key>' when
        the job is over) and feed it the next job."""
        try:
            for line in self.proc.stdout:
                self._heard(line.decode(errors="replace").strip())
        except (OSError, ValueError):  # the pipe broke or was closed under the reader
            pass
        finally:
            self.proc.stdout.close()  # the worker has ended: its pipe is not left to the GC
        with self.cond:
            self.alive, self.running, self.compiling = False, None, None
            self.queue.clear()
            self.cond.notify_all()

    def _heard(self, line: str) -> None:
        """One report line of the worker."""
        what, _, key = line.partition(" ")
        with self.cond:
            if what == "start":
                self.compiling = key
            elif what == "done":  # anything else is no report (a stray print in the worker)
                self.done.add(key)
                self.running = self.compiling = None
                self._next()
                self.cond.notify_all()

    def _next(self) -> None:
        """Send the first queued job when the worker is idle (the caller holds the lock)."""
        if self.running is not None or not self.queue or not self.alive:
            return
        key, raw = self.queue.pop(0)
        blob = pickle.dumps((key, raw), protocol=4)
        try:
            self.proc.stdin.write(struct.pack("<Q", len(blob)) + blob)
            self.proc.stdin.flush()
        except OSError:
            self.alive = False
            return
        self.running = key

    def submit(self, raws: Iterable[Any], replace: bool) -> None:
        with self.cond:
            if replace:
                self.queue.clear()
            queued = {k for k, _ in self.queue}
            for raw in raws:
                key = _key(raw)
                if key is not None and key not in self.done and key != self.running and \
                        key not in queued:
                    self.queue.append((key, raw))
                    queued.add(key)
            self._next()

    def lend(self, jobs: list[tuple[str, Any]]) -> None:
        """Put jobs at the head of the queue, in their order (a caller waits for them soon)."""
        with self.cond:
            jobs = [(k, r) for k, r in jobs if k not in self.done and k != self.running]
            keys = {k for k, _ in jobs}
            self.queue = [*jobs, *((k, r) for k, r in self.queue if k not in keys)]
            self._next()

    def claim(self, raw) -> None:
        key = _key(raw)
        if key is not None:
            self.claim_key(key)

    def claim_key(self, key: str, sent: bool = False) -> None:
        """Take the job back when it is queued, else wait while the worker compiles it (and,
        with ``sent``, while it is sent: a lent job starts at once)."""
        with self.cond:
            self.queue = [(k, r) for k, r in self.queue if k != key]
            # a topology the worker still checks (or imports for) is not waited for: the
            # caller may load it from the cache, or compile it, as fast
            self.cond.wait_for(lambda: self.compiling != key and not (sent and
                                                                      self.running == key),
                               timeout=WAIT)

    def close(self) -> None:
        with self.cond:
            self.queue.clear()
        try:
            self.proc.stdin.close()
            # a compile it is at is not waited for long: numba and the model cache write
            # their files whole (to a temporary name, then renamed), so a kill loses no file
            self.proc.wait(timeout=1)
        except (OSError, subprocess.TimeoutExpired):
            self.proc.kill()
            with contextlib.suppress(subprocess.TimeoutExpired):
                self.proc.wait(timeout=5)  # reaped: no zombie, no "still running" warning


_WORKER: list[_Worker | None] = []


def _worker() -> _Worker | None:
    """The process's worker, started at the first use (again when the cache folder changed);
    None when compiling ahead is off, the folder is not trusted, or the worker died (it is
    not started again for that folder: whatever killed it would again)."""
    from circuitsim.memo import open_cache_dir

    folder, why = open_cache_dir()
    old = _WORKER[0] if _WORKER else None
    if old is not None and old.folder == folder:
        return old if old.alive else None
    if old is not None:
        old.close()
    _WORKER[:] = [None]
    if why is None and enabled():
        from circuitsim.solve import direct

        try:
            _WORKER[0] = _Worker(folder)
        except OSError:
            return None
        direct.lend_to(lend, claim_job)
    return _WORKER[0]


@atexit.register
def _close() -> None:
    """Stop the worker (it finishes the topology it compiles; the queue is dropped)."""
    if _WORKER and _WORKER[0] is not None:
        _WORKER[0].close()


def enabled() -> bool:
    """Compiling ahead is on: not turned off, kernels in use, two cores or more."""
    from circuitsim.solve.direct import wanted

    if os.environ.get("CIRCUITSIM_AHEAD", "").strip().lower() in ("0", "off", "no"):
        return False
    return _cores() >= 2 and wanted()


def _cores() -> int:
    """The cores this process may run on."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def expect(raws: Iterable[Any], replace: bool = False) -> None:
    """Queue raw netlists whose topologies will be needed soon, in order of need (after the
    queued ones; ``replace``: instead of them). Those whose model is cached and whose kernels
    numba keeps are left out, and no worker is started for none (a warm cache: it would only
    compete)."""
    if not enabled():
        return
    from circuitsim.memo import cache_dir

    folder = cache_dir()
    todo = [raw for raw in raws if not _kept(raw, folder)]
    worker = _worker() if todo or (_WORKER and _WORKER[0] is not None) else None
    if worker is not None:
        worker.submit(todo, replace)


def _kept(raw, folder: Path) -> bool:
    """Whether numba keeps the kernels of the raw netlist's topology in the cache folder (also
    when the netlist cannot be built: nothing to compile ahead). The kernels are named by their
    source, which the topology's cached model holds; a topology not compiled yet may share its
    kernels with another (``direct.kernel_name``), and is found kept once its model is built."""
    import warnings

    from circuitsim.compiler.cache import cache_key, load_cached
    from circuitsim.errors import CircuitsimError
    from circuitsim.netlist.load import build
    from circuitsim.solve import ccode
    from circuitsim.solve.direct import kernel_name

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            key = cache_key(build(raw).topology_key())
    except (CircuitsimError, KeyError, ValueError):
        return True
    hit = load_cached(key)
    if hit is None:
        return False
    source = hit[1].get("kernels")
    return not source or ccode.built(folder, source) or any(
        (folder / "__pycache__").glob(f"{kernel_name(source)}_kernels.*.nbi"))


def claim(raw) -> None:
    """Before compiling ``raw`` here: take it off the queue, or wait for the worker's compile."""
    worker = _WORKER[0] if _WORKER else None
    if worker is not None:
        worker.claim(raw)


def lend(source: str, *names: list[str]) -> list[str] | None:
    """Have the worker compile cfuncs of the kernel module of ``source`` now, before anything
    queued, while the caller compiles others: one job for each list of ``names``, in their
    order. The jobs' keys for ``claim_job``, or None without a worker (the caller compiles
    them itself)."""
    from circuitsim.memo import open_cache_dir
    from circuitsim.solve.direct import kernel_name

    worker = _WORKER[0] if _WORKER else None
    if worker is None or not worker.alive or not enabled() or \
            open_cache_dir()[0] != worker.folder:  # it compiles into another folder
        return None
    jobs = [(f"kernels {kernel_name(source)} {' '.join(part)}", ("kernels", source, tuple(part)))
            for part in names if part]
    worker.lend(jobs)
    return [key for key, _ in jobs]


def claim_job(key: str) -> None:
    """Before doing a lent job here: take it back when the worker has not started on it, or
    wait for the worker to finish it."""
    worker = _WORKER[0] if _WORKER else None
    if worker is not None:
        worker.claim_key(key, sent=True)


def _compile_kernels(source: str, names: tuple[str, ...], folder: Path, started) -> None:
    """The worker's lent job: cfuncs of one kernel module, into numba's cache."""
    from circuitsim.solve import direct

    started()
    module = direct.kernel_module(folder, source)
    for name in names:
        direct.cfunc(module, name)


def _compile(raw, folder: Path, started) -> None:
    """The worker's job: the topology's model and all its kernels, into the cache (nothing
    when numba keeps the kernels of that topology already: the caller loads them as fast)."""
    import warnings

    from circuitsim.compiler.model import compile as compile_model
    from circuitsim.netlist.load import build
    from circuitsim.solve import direct

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if _kept(raw, folder):
            return
        started()
        module = direct.kernels(compile_model(build(raw)))
        for name in getattr(module, "CFUNCS", ()):
            direct.cfunc(module, name)


def main() -> None:
    """The worker: read jobs from stdin until it closes, report each key when done."""
    from circuitsim.memo import cache_dir
    from circuitsim.solve.route import many_solves

    many_solves()
    folder = cache_dir()
    stdin, stdout = sys.stdin.buffer, sys.stdout.buffer

    def say(what: str, key: str) -> None:
        stdout.write(f"{what} {key}\n".encode())
        stdout.flush()

    while head := stdin.read(8):
        key, job = pickle.loads(stdin.read(struct.unpack("<Q", head)[0]))
        try:
            if isinstance(job, tuple) and job[0] == "kernels":
                _compile_kernels(*job[1:], folder, lambda key=key: say("start", key))
            else:
                _compile(job, folder, lambda key=key: say("start", key))
        except Exception:  # noqa: BLE001, S110 - the caller compiles it itself and reports
            pass
        say("done", key)


if __name__ == "__main__":
    main()
