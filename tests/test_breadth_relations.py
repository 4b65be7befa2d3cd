"""Events where behavioural relations switch (issue 15 item 6): a comparison inside if, sign,
abs, min or max that depends on the circuit's unknowns is held as a mode between events and
switched at the root of its distance, as Modelica treats relations. Against a hand-written
scipy model with its own event location and against closed forms."""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

#: A diode as a behavioural current source (100 ohm forward, 1 nS reverse) charging 1 mF,
#: loaded by 10 kohm, from a 1 Hz, 10 V sine.
DIODE = """
    parameters: {{Ron: 100 ohm, Goff: 1 nS}}
    components:
      - {{name: V1, type: V, p: in, n: gnd, V: {{sine: {{amplitude: 10 V, freq: 1 Hz}}}}}}
      - {{name: D1, type: BI, p: in, n: out, expr: "{law}"}}
      - {{name: C1, type: C, p: out, n: gnd, C: 1 mF}}
      - {{name: R1, type: R, p: out, n: gnd, R: 10 kohm}}
    probes: {{vc: out.v}}
    analysis: {{stop: 5 s, step: 1 ms, rtol: 1e-9, atol: 1e-12}}
"""
IF_LAW = "if(in.v - out.v > 0, (in.v - out.v)/Ron, (in.v - out.v)*Goff)"
MAX_LAW = "max(in.v - out.v, 0)/Ron + min(in.v - out.v, 0)*Goff"


def _diode_reference(t_out: np.ndarray) -> tuple[np.ndarray, list[float]]:
    """v_C at t_out and the switching instants: one mode at a time (solve_ivp, DOP853), each
    stopped at the root of v_in - v_C found by solve_ivp's own event location."""
    ron, goff, c, r = 100.0, 1e-9, 1e-3, 1e4

    def vin(t):
        return 10 * np.sin(2 * np.pi * t)

    def rhs(on):
        g = 1 / ron if on else goff
        return lambda t, v: [(g * (vin(t) - v[0]) - v[0] / r) / c]

    def crossing(t, v):
        return vin(t) - v[0]

    crossing.terminal = True
    t, v, on, switches = 0.0, 0.0, True, []  # v_in rises from 0 at t = 0: conducting
    out = np.full(t_out.size, np.nan)
    while t < t_out[-1]:
        crossing.direction = -1 if on else 1  # the way out of the mode held
        sol = solve_ivp(rhs(on), (t, t_out[-1]), [v], method="DOP853", rtol=1e-12,
                        atol=1e-14, events=crossing, dense_output=True,
                        first_step=1e-9)
        mask = (t_out >= t) & (t_out <= sol.t[-1])
        out[mask] = sol.sol(t_out[mask])[0]
        t, v = sol.t[-1], sol.y[0, -1]
        if sol.status == 1:
            switches.append(t)
            on = not on
    return out, switches


def test_diode_by_if_switches_at_the_roots_of_its_relation(compile_text) -> None:
    """if(v > 0, v/Ron, v*Goff): v_C within 2e-7 V of the scipy model over 5 periods (4e-8 measured), every
    switching instant found (9: off, then on and off in each later period) within
    10 ns (2e-9 s measured)."""
    res = compile_text(DIODE.format(law=IF_LAW)).simulate()
    assert res.success, res.message
    ref, switches = _diode_reference(res.t)
    assert np.max(np.abs(res["vc"] - ref)) < 2e-7
    assert len(res.t_events) == len(switches) == 9
    assert np.max(np.abs(res.t_events - switches)) < 1e-8


def test_diode_by_max_and_min_is_the_same_law(compile_text) -> None:
    """The same diode written with max and min: each relation is its own crossing (two
    switch at every instant), the instants and v_C as for if()."""
    res = compile_text(DIODE.format(law=MAX_LAW)).simulate()
    assert res.success, res.message
    ref, switches = _diode_reference(res.t)
    assert np.max(np.abs(res["vc"] - ref)) < 2e-7
    assert len(res.t_events) == len(switches)
    assert np.max(np.abs(res.t_events - switches)) < 1e-8
