"""Compile once per topology: the second compile imports the cached code, no sympy work."""

from __future__ import annotations

import pickle
import warnings

import pytest

import circuitsim as cs
from circuitsim.compiler import mna

from conftest import NETLISTS


def test_second_compile_uses_the_cache(monkeypatch):
    net = cs.load(NETLISTS / "examples" / "dc_motor.yaml")
    first = cs.compile(net)

    def boom(*a, **k):
        raise AssertionError("re-derived a cached topology")

    monkeypatch.setattr(mna, "assemble", boom)
    second = cs.compile(cs.load(NETLISTS / "examples" / "dc_motor.yaml"))
    assert second.key == first.key
    assert second.simulate(stop=0.05).success


def test_values_do_not_change_the_key_but_structure_does(write_netlist):
    a = cs.load(write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1}
          - {name: R1, type: R, p: a, n: gnd, R: 1}
    """, "a.yaml"))
    b = cs.load(write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 5 V}
          - {name: R1, type: R, p: a, n: gnd, R: 3 kohm}
    """, "b.yaml"))
    c = cs.load(write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1}
          - {name: R1, type: C, p: a, n: gnd, C: 1}
    """, "c.yaml"))
    assert a.topology_key() == b.topology_key() != c.topology_key()


def test_compiled_model_pickles_for_worker_processes():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(cs.load(NETLISTS / "kim2024" / "base.yaml"))
    clone = pickle.loads(pickle.dumps(model))
    res = clone.simulate(stop=0.01, params={"Ra": 1.2})
    ref = model.simulate(stop=0.01, params={"Ra": 1.2})
    assert res["i_total"][-1] == pytest.approx(ref["i_total"][-1], rel=1e-12)


def test_init_op_starts_at_the_averaged_steady_state():
    """Kim base: the operating point (ripple averaged over a turn) is the closed-form DC
    state, and a run from it is already steady."""
    from circuitsim.solve.op import operating_point

    from reference import kim_dc_steady_state

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(cs.load(NETLISTS / "kim2024" / "base.yaml"))
    w, _, _ = kim_dc_steady_state()
    op = operating_point(model)
    assert op["rotor.w"] == pytest.approx(w, rel=1e-9)
    res = model.simulate(stop=0.02, init="op")
    assert res["speed"][0] == pytest.approx(w, rel=1e-9)
    # only the ripple (2.2 rad/s at the 8th order) starts up; the mean is already there
    assert res.harmonic("speed", order=8, window=0.5).offset == pytest.approx(w, abs=0.02)
