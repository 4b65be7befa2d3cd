"""Initial values: on states, on expressions of states, conflicting ones (issue #2)."""

from __future__ import annotations

import numpy as np
import pytest

from circuitsim.compiler.model import CircuitWarning


def test_capacitor_between_floating_nodes_keeps_its_initial_voltage(compile_text):
    """C1 sits between two nodes, neither of them ground; its v0 = 2 V is an expression of
    two states and discharges through R1 + R2: v = 2 exp(-t / ((R1 + R2) C))."""
    model = compile_text("""
        components:
          - {name: R1, type: R, p: a, n: gnd, R: 1 kohm}
          - {name: C1, type: C, p: a, n: b, C: 1 uF, v0: 2 V}
          - {name: R2, type: R, p: b, n: gnd, R: 1 kohm}
        probes: {v: C1.v}
        analysis: {stop: 5 ms, step: 5 us, rtol: 1e-10, atol: 1e-13}
    """)
    res = model.simulate()
    assert res["v"][0] == pytest.approx(2.0, rel=1e-12)
    np.testing.assert_allclose(res["v"], 2 * np.exp(-res.t / 2e-3), rtol=1e-6, atol=1e-9)


def test_initial_current_of_an_eliminated_inductor_is_honoured(compile_text):
    """Two inductors in series share one state; i0 given on the second one (whichever is
    eliminated) sets it, and the current decays with tau = (L1 + L2) / R."""
    model = compile_text("""
        components:
          - {name: R1, type: R, p: a, n: gnd, R: 3 ohm}
          - {name: L1, type: L, p: a, n: m, L: 1 mH}
          - {name: L2, type: L, p: m, n: gnd, L: 2 mH, i0: 0.5 A}
        probes: {i: L1.i}
        analysis: {stop: 5 ms, step: 5 us, rtol: 1e-10, atol: 1e-13}
    """)
    res = model.simulate()
    np.testing.assert_allclose(res["i"], 0.5 * np.exp(-res.t / 1e-3), rtol=1e-6, atol=1e-10)


def test_conflicting_initial_values_warn(compile_text):
    model = compile_text("""
        components:
          - {name: R1, type: R, p: a, n: gnd, R: 3 ohm}
          - {name: L1, type: L, p: a, n: m, L: 1 mH, i0: 0.2 A}
          - {name: L2, type: L, p: m, n: gnd, L: 2 mH, i0: 0.5 A}
        probes: {i: L1.i}
        analysis: {stop: 1 ms}
    """)
    with pytest.warns(CircuitWarning, match="initial values .* not met"):
        res = model.simulate()
    assert 0.2 <= res["i"][0] <= 0.5  # the least-squares compromise


def test_emf_on_a_locked_rotor(compile_text):
    """An EMF whose shaft is the fixed reference: a locked rotor is an R-L circuit."""
    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {step: {v1: 12 V, rise: 1 ns}}}
          - {name: R1, type: R, p: a, n: b, R: 2 ohm}
          - {name: L1, type: L, p: b, n: c, L: 2 mH}
          - {name: M, type: emf, p: c, n: gnd, shaft: fixed, k_t: 0.05}
        probes: {i: L1.i, tau: M.tau}
        analysis: {stop: 10 ms, step: 10 us, rtol: 1e-10, atol: 1e-13}
    """)
    res = model.simulate()
    # the step ramps over 1 ns: the response is the ideal one delayed by half the ramp
    i = 6 * (1 - np.exp(-np.maximum(res.t - 0.5e-9, 0) / 1e-3))
    np.testing.assert_allclose(res["i"], i, rtol=1e-5, atol=1e-7)
    np.testing.assert_allclose(res["tau"], -0.05 * i, rtol=1e-5, atol=1e-8)


def test_initial_value_overridden_at_run_time_is_honoured(compile_text):
    """An initial value given only through params= counts as given (issue #6 found this)."""
    model = compile_text("""
        components:
          - {name: Jr, type: inertia, shaft: s, J: 1e-5}
          - {name: Bv, type: damper, shaft: s, b: 1e-5}
        probes: {w: s.w, phi: s.phi}
        analysis: {stop: 1.0, step: 10 ms, rtol: 1e-10, atol: 1e-13}
    """)
    res = model.simulate(params={"Jr.w0": 10.0, "Jr.phi0": 0.5})
    np.testing.assert_allclose(res["w"], 10 * np.exp(-res.t), rtol=1e-6)
    assert res["phi"][0] == pytest.approx(0.5)
