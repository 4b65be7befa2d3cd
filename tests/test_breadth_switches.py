"""Time- and voltage-controlled switches against closed forms (issue 15 item 3, without
events: the time switch's edges are breakpoints; the voltage switch is algebraic here)."""

from __future__ import annotations

import numpy as np

TAU = 1e-3  # [s] 1 kohm * 1 uF


def test_time_switch_charges_and_discharges_at_exact_instants(compile_text) -> None:
    """A switch closes at 1 ms and opens at 3 ms (10 ns edges) between a 1 V source and an
    RC: the capacitor is flat, charges as 1 - e^{-(t-1ms)/tau}, then holds (Roff = 1 Gohm
    leaks ~1e-6 of it per ms; the edges shift the charge by ~1e-5)."""
    model = compile_text("""
        components:
          - {name: V1, type: V, p: in, n: gnd, V: 1 V}
          - {name: S1, type: tswitch, p: in, n: a,
             closed: {pulse: {v2: 1, delay: 1 ms, rise: 10 ns, fall: 10 ns, width: 2 ms,
                              period: 10 ms}}}
          - {name: R1, type: R, p: a, n: b, R: 1 kohm}
          - {name: C1, type: C, p: b, n: gnd, C: 1 uF}
        probes: {v: b.v}
        analysis: {stop: 5 ms, step: 10 us, rtol: 1e-10, atol: 1e-13}
    """)
    res = model.simulate()
    t = res.t
    rise = 1 - np.exp(-np.clip(t - 1e-3, 0, None) / (TAU * (1 + 1e-6)))
    held = rise[np.searchsorted(t, 3e-3)]
    exact = np.where(t <= 3e-3, rise, held)
    assert np.max(np.abs(res["v"] - exact)) < 5e-5


def test_voltage_switch_as_a_rectifier(compile_text) -> None:
    """A switch controlled by the source itself (closed above 0.5 V) passes the sine into a
    1 kohm load and blocks it otherwise: a divider of 1000/(1000 + Ron) or of
    1000/(1000 + Roff), outside the 1 mV transition window."""
    model = compile_text("""
        components:
          - {name: V1, type: V, p: in, n: gnd, V: {sine: {amplitude: 2 V, freq: 50 Hz}}}
          - {name: S1, type: S, p: in, n: out, cp: in, cn: gnd, Vt: 0.5 V, Ron: 1 ohm,
             Roff: 1 Mohm}
          - {name: R1, type: R, p: out, n: gnd, R: 1 kohm}
        probes: {vo: out.v, vin: in.v}
        analysis: {stop: 40 ms, step: 0.1 ms, rtol: 1e-10, atol: 1e-13}
    """)
    res = model.simulate()
    u = res["vin"]
    exact = np.where(u > 0.5, u * 1000 / 1001, u * 1000 / (1000 + 1e6))
    away = np.abs(u - 0.5) > 1e-3
    assert away.sum() > 390
    assert np.max(np.abs(res["vo"] - exact)[away]) < 1e-8
