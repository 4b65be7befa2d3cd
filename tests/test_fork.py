"""solve/fork.py: independent pieces shared with forked copies give the serial results."""

from __future__ import annotations

import os
import time

import numpy as np
import pytest

from circuitsim.solve import fork
from circuitsim.solve.fork import fork_map, in_copy

from conftest import kim_steps

needs_copies = pytest.mark.skipif(fork.copies() == 0, reason="one core, or no fork here: "
                                  "fork_map runs serially (tested by test_off_is_serial)")


def _square_and_where(x: int) -> tuple[int, int]:
    time.sleep(0.01)  # long enough for a copy to start taking pieces
    return x * x, os.getpid()


@needs_copies
def test_pieces_run_in_copies_and_come_back_in_order():
    out = fork_map(_square_and_where, range(40))
    assert [v for v, _ in out] == [x * x for x in range(40)]
    # the queue is shared: both this process and a copy took pieces
    pids = {pid for _, pid in out}
    assert os.getpid() in pids and len(pids) >= 2


def test_off_is_serial(monkeypatch):
    monkeypatch.setenv("CIRCUITSIM_FORK", "off")
    assert fork.copies() == 0
    out = fork_map(_square_and_where, range(5))
    assert out == [(x * x, os.getpid()) for x in range(5)]


def _fails_on_three(x: int) -> int:
    if x == 3:
        raise ValueError("piece three")
    return x


def test_an_error_is_raised_here_whoever_met_it():
    with pytest.raises(ValueError, match="piece three"):
        fork_map(_fails_on_three, range(8))


def _dies_in_a_copy(x: int) -> int:
    if in_copy():
        os._exit(7)  # a copy killed mid-way: its pieces are lost with it
    return -x


@needs_copies
def test_pieces_of_a_copy_that_died_are_computed_here():
    assert fork_map(_dies_in_a_copy, range(12)) == [-x for x in range(12)]


def _unpicklable_in_a_copy(x: int):
    # a lambda does not pickle: a copy cannot send it, so this process computes it
    return (lambda: x) if in_copy() else x


@needs_copies
def test_a_result_that_does_not_pickle_is_computed_here():
    out = fork_map(_unpicklable_in_a_copy, range(12))
    assert out == list(range(12))


@needs_copies
def test_batches_shared_with_copies_are_the_serial_numbers_to_the_bit(monkeypatch):
    """Finite-difference steps beyond one banded block run as batches (``_in_chunks``), which
    the copies share: the same members, bit for bit, as one after another."""
    from circuitsim.solve import batch as batch_mod
    from circuitsim.solve.batch import simulate_batch

    model, n, sets = kim_steps(monkeypatch)
    monkeypatch.setattr(batch_mod, "BAND_MAX", 3 * n)
    shared = simulate_batch(model, sets, stop=0.02, rtol=1e-8, atol=1e-10, nearby=True)
    monkeypatch.setenv("CIRCUITSIM_FORK", "off")
    alone = simulate_batch(model, sets, stop=0.02, rtol=1e-8, atol=1e-10, nearby=True)
    assert len(shared) == len(alone) == len(sets)
    for a, b in zip(shared, alone, strict=True):
        assert a.success and b.success and a.model is model
        assert np.array_equal(a.t, b.t) and np.array_equal(a.y, b.y)
        assert np.array_equal(a["speed"], b["speed"])


def test_no_process_to_spare_runs_here(monkeypatch):
    """A fork refused (no process or memory to spare) leaves every piece to this process."""
    def refused():
        raise OSError("Resource temporarily unavailable")

    monkeypatch.setattr(os, "fork", refused)
    assert fork_map(_square_and_where, range(4)) == [(x * x, os.getpid()) for x in range(4)]
