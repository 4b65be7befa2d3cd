"""Topologies compiled ahead in a worker process (``solve/ahead.py``): the worker fills the
cache the caller reads, a claim takes a queued topology back, a failing job ends, a warm
cache or ``CIRCUITSIM_AHEAD=off`` starts no worker, and the numbers do not depend on who
compiled."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

pytest.importorskip("numba")

import circuitsim as cs
from circuitsim.solve import ahead, direct

RC = """
title: RC {tag}
components:
  - {{name: V1, type: V, p: in, n: gnd, V: {{step: {{v0: 0, v1: 1 V, t0: 0, rise: 1 ns}}}}}}
  - {{name: R{tag}, type: R, p: in, n: out, R: 1 kohm}}
  - {{name: C1, type: C, p: out, n: gnd, C: 1 uF}}
{extra}
probes:
  v_out: out.v
analysis: {{stop: 4 ms, step: 10 us}}
"""


@pytest.fixture
def fresh(tmp_path, monkeypatch, write_netlist):
    """A cache folder of its own, kernels on, and a raw netlist maker: one topology a tag
    (the resistor's name), the same code whatever the tag (kernels are named by their
    source). The kernels this process loaded before are forgotten, and a module of the same
    name loaded from another test's folder is imported again from this one's
    (``direct._import``): no test meets kernels loaded for another."""
    monkeypatch.setattr(direct, "_LOADED", {})
    monkeypatch.setenv("CIRCUITSIM_CACHE", str(tmp_path / "cache"))
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "numba")
    monkeypatch.delenv("CIRCUITSIM_AHEAD", raising=False)
    # numba's route, as without a C compiler: lending is numba's (the C route compiles a
    # module whole, test_the_worker_builds_the_c_library_the_caller_loads)
    monkeypatch.setenv("CIRCUITSIM_CC", "off")
    # the mechanism works on any machine; only its use is limited to two cores or more
    monkeypatch.setattr(ahead, "_cores", lambda: 2)

    def raw(tag: str, extra: str = ""):
        return cs.load(write_netlist(RC.format(tag=tag, extra=extra), f"{tag}.yaml")).raw

    yield raw
    ahead._close()
    ahead._WORKER.clear()


def _wait_done(raw, timeout: float = 120.0) -> bool:
    worker = ahead._WORKER[0]
    key = ahead._key(raw)
    with worker.cond:
        return worker.cond.wait_for(lambda: key in worker.done or not worker.alive, timeout)


def _compiled(raw):
    from circuitsim.loop.diagnose.context import compile_raw

    return compile_raw(raw)


def test_the_worker_fills_the_cache_the_caller_reads(fresh, monkeypatch):
    raw = fresh("a")
    assert not ahead._kept(raw, direct_cache())
    ahead.expect([raw])
    assert _wait_done(raw) and ahead._WORKER[0].alive
    assert ahead._kept(raw, direct_cache())  # numba keeps the worker's kernels
    model = _compiled(raw)
    module = direct.kernels(model)
    kernels = [direct.cfunc(module, name) for name in module.CFUNCS]
    # read from the cache, not compiled here
    assert all(k.cache_hits for k in kernels)
    # the same numbers as the Python route (the kernels give them to the bit)
    with_kernels = model.simulate()
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "python")
    plain = model.simulate()
    assert with_kernels.success and np.array_equal(with_kernels.y, plain.y)


def test_the_worker_builds_the_c_library_the_caller_loads(fresh, monkeypatch):
    """With a C compiler the worker builds the topology's kernel library; the caller finds
    it kept, loads it without compiling, and its numbers are the Python route's, to the bit."""
    from circuitsim.solve import ccode

    monkeypatch.delenv("CIRCUITSIM_CC")
    if ccode.compiler() is None:
        pytest.skip("no C compiler on this machine: numba's route, tested above")
    raw = fresh("c")
    ahead.expect([raw])
    assert _wait_done(raw) and ahead._WORKER[0].alive
    assert ahead._kept(raw, direct_cache())
    built = set(direct_cache().glob("c*.so"))
    assert len(built) == 1
    model = _compiled(raw)
    assert direct.c_library(direct.kernels(model)) is not None
    assert set(direct_cache().glob("c*.so")) == built  # loaded, not built again
    with_kernels = model.simulate()
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "python")
    plain = model.simulate()
    assert with_kernels.success and np.array_equal(with_kernels.y, plain.y)
    assert np.array_equal(with_kernels.t, plain.t)


def direct_cache():
    from circuitsim.memo import cache_dir

    return cache_dir()


def test_a_topology_of_kept_code_shares_the_kept_kernels(fresh):
    """Kernels are named by their source: a topology of the same code as one the worker
    compiled (another resistor's name) reads as not kept while its model is not cached (its
    model names the source), then as kept, and its kernels load from numba's cache."""
    first, twin = fresh("t1"), fresh("t2")
    ahead.expect([first])
    assert _wait_done(first) and ahead._kept(first, direct_cache())
    assert not ahead._kept(twin, direct_cache())
    model = _compiled(twin)  # its model only: no kernel is compiled for it
    assert ahead._kept(twin, direct_cache())
    module = direct.kernels(model)
    assert all(direct.cfunc(module, name).cache_hits for name in module.CFUNCS)


def test_a_claim_takes_a_queued_topology_back(fresh):
    first, second, third = fresh("b1"), fresh("b2", "  - {name: R2, type: R, p: out, n: gnd, "
                                                     "R: 1 Mohm}"), fresh("b3")
    ahead.expect([first, second, third])
    worker = ahead._WORKER[0]
    ahead.claim(third)
    with worker.cond:
        assert ahead._key(third) not in [k for k, _ in worker.queue]
        assert worker.running == ahead._key(first)  # one job at a time, in order
    assert _wait_done(second)
    assert ahead._key(third) not in worker.done


def _lender(fresh, tag: str):
    """A worker that is up, having compiled another topology of other code (it holds no
    kernels of the lender's), and the lender: topology ``tag``'s model and kernel module."""
    other = fresh(f"{tag}1", "  - {name: R2, type: R, p: out, n: gnd, R: 1 Mohm}")
    ahead.expect([other])
    assert _wait_done(other)
    model = _compiled(fresh(f"{tag}2"))
    return model, direct.kernels(model)


def test_a_lent_jacobian_is_compiled_by_the_worker_and_loaded_here(fresh, monkeypatch):
    model, module = _lender(fresh, "m")
    direct._compile_shared(module, model, ("residual", "jacobian"))
    worker = ahead._WORKER[0]
    # compiled there, not here
    assert f"kernels {direct.kernel_name(model.meta['kernels'])} jacobian" in worker.done
    assert direct.cfunc(module, "jacobian").cache_hits  # and loaded from the cache
    assert not direct.cfunc(module, "residual").cache_hits  # this one compiled here
    with_kernels = model.simulate()
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "python")
    plain = model.simulate()
    assert with_kernels.success and np.array_equal(with_kernels.y, plain.y)


def test_a_batch_lends_the_single_kernels_for_later(fresh, monkeypatch):
    """The stacked kernels' compile lends the band Jacobian and, behind it, the single
    member's kernels; a single run later claims them and loads them from the cache."""
    from circuitsim.solve.batch import simulate_batch

    model, module = _lender(fresh, "b")
    direct._compile_shared(module, model, ("residual_batch", "jacobian_band"))
    name = direct.kernel_name(model.meta["kernels"])
    singles = f"kernels {name} " + " ".join(n for n in direct._SINGLES if n in module.CFUNCS)
    assert set(module._LENT) == {n for n in direct._SINGLES if n in module.CFUNCS}
    direct._compile_shared(module, model, ("residual", "jacobian"))  # claims, then loads
    worker = ahead._WORKER[0]
    assert f"kernels {name} jacobian_band" in worker.done and singles in worker.done
    assert direct.cfunc(module, "residual").cache_hits  # compiled there, loaded here
    assert not direct.cfunc(module, "residual_batch").cache_hits
    sets = [{"Rb2.R": 1000.0 * (1 + 1e-3 * j)} for j in range(3)]
    batch = simulate_batch(model, sets)
    single = model.simulate(params=sets[1])
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "python")
    plain = model.simulate(params=sets[1])
    assert all(r.success for r in batch) and np.array_equal(single.y, plain.y)


def test_a_job_that_cannot_compile_ends(fresh):
    # two voltage sources in parallel: the netlist builds, its model does not
    bad = fresh("c", "  - {name: V2, type: V, p: in, n: gnd, V: 2 V}")
    good = fresh("c2")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ahead.expect([bad, good])
    assert _wait_done(bad) and _wait_done(good)
    assert ahead._WORKER[0].alive
    assert ahead._kept(good, direct_cache())


def test_a_warm_cache_starts_no_worker(fresh):
    raw = fresh("d")
    model = _compiled(raw)
    module = direct.kernels(model)
    for name in module.CFUNCS:
        direct.cfunc(module, name)
    ahead.expect([raw])
    assert not ahead._WORKER or ahead._WORKER[0] is None


def test_one_core_starts_no_worker(fresh, monkeypatch):
    monkeypatch.setattr(ahead, "_cores", lambda: 1)
    assert not ahead.enabled()
    ahead.expect([fresh("h")])
    assert not ahead._WORKER or ahead._WORKER[0] is None


def test_off_starts_no_worker(fresh, monkeypatch):
    monkeypatch.setenv("CIRCUITSIM_AHEAD", "off")
    ahead.expect([fresh("e")])
    assert not ahead._WORKER or ahead._WORKER[0] is None



def test_a_dead_worker_is_not_started_again(fresh):
    raw = fresh("f")
    ahead.expect([raw])
    worker = ahead._WORKER[0]
    worker.proc.kill()
    with worker.cond:
        assert worker.cond.wait_for(lambda: not worker.alive, 30)
    ahead.expect([fresh("g")])
    assert ahead._WORKER[0] is worker and not worker.alive
    ahead.claim(raw)  # returns at once: nothing is compiling
    assert _compiled(raw).key  # compiled here instead
