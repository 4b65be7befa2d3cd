"""Switching with events (issue 15 item 3): ideal switches and diodes whose state is a
discrete mode changed at a root the integrator finds, against closed forms and a
hand-written scipy model."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from ngspice import require_ngspice, run_ngspice

DECKS = Path(__file__).resolve().parent / "decks"
#: an ideal (pwl, event-switched) diode charging 100 uF || 100 ohm from a 10 V 50 Hz sine
RECTIFIER = """
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {sine: {amplitude: 10, freq: 50}}}
          - {name: D1, type: D, p: a, n: b, model: ideal, Vf: 0.7, Ron: 0.1, Goff: 1e-9,
             Vh: 1e-9}
          - {name: C1, type: C, p: b, n: gnd, C: 100 uF}
          - {name: R1, type: R, p: b, n: gnd, R: 100}
        probes: {vc: b.v, on: D1.on}
        analysis: {stop: 60 ms, step: 50 us, rtol: 1e-10, atol: 1e-12}
"""


def _edges(t: np.ndarray, state: np.ndarray) -> np.ndarray:
    """Output times where a 0/1 state changes (the first sample in the new state)."""
    return t[1:][np.diff(state) != 0]


def test_time_switch_ideal_edges_are_exact(compile_text) -> None:
    """An ideal time switch closes at the middle of the pulse's rising edge (1 ms + 5 ns) and
    opens at the middle of its fall (3 ms + 15 ns): the RC follows the exact piecewise
    exponentials, Roff's leak included (closed form, two time constants)."""
    model = compile_text("""
        components:
          - {name: V1, type: V, p: in, n: gnd, V: 1 V}
          - {name: S1, type: tswitch, p: in, n: a, model: ideal, Ron: 1 ohm, Roff: 1 Gohm,
             closed: {pulse: {v2: 1, delay: 1 ms, rise: 10 ns, fall: 10 ns, width: 2 ms,
                              period: 10 ms}}}
          - {name: R1, type: R, p: a, n: b, R: 1 kohm}
          - {name: C1, type: C, p: b, n: gnd, C: 1 uF}
        probes: {v: b.v, on: S1.on}
        analysis: {stop: 5 ms, step: 10 us, rtol: 1e-10, atol: 1e-13}
    """)
    res = model.simulate()
    assert res.success, res.message
    t_on, t_off = 1e-3 + 5e-9, 1e-3 + 1e-8 + 2e-3 + 5e-9  # the middle of each ramp
    tau_off, tau_on = (1e3 + 1e9) * 1e-6, (1e3 + 1.0) * 1e-6
    v_on = 1 - np.exp(-t_on / tau_off)  # Roff leaks a little before the switch closes
    v_off = 1 + (v_on - 1) * np.exp(-(t_off - t_on) / tau_on)
    t = res.t
    exact = np.where(t < t_on, 1 - np.exp(-t / tau_off),
                     np.where(t < t_off, 1 + (v_on - 1) * np.exp(-(t - t_on) / tau_on),
                              1 + (v_off - 1) * np.exp(-(t - t_off) / tau_off)))
    # 1e-8 V on a slope of up to 1 V/ms: each edge within 1e-11 s of the ramp's middle
    assert np.max(np.abs(res["v"] - exact)) < 1e-8
    assert list(_edges(t, res["on"])) == pytest.approx([1.01e-3, 3.01e-3], abs=1e-12)


def _relaxation_period() -> tuple[float, float, float]:
    """Closed form of the relaxation oscillator below: first closing, closed time, open
    time [s]. Open: the capacitor charges through R towards V Roff/(R + Roff); closed: it
    discharges towards V Ron/(R + Ron); thresholds 3.5 V and 1.5 V."""
    V, R, C, Ron, Roff = 5.0, 1e3, 1e-6, 10.0, 1e9
    v_open, tau_open = V * Roff / (R + Roff), R * Roff / (R + Roff) * C
    v_closed, tau_closed = V * Ron / (R + Ron), R * Ron / (R + Ron) * C
    first = tau_open * np.log(v_open / (v_open - 3.5))
    closed = tau_closed * np.log((3.5 - v_closed) / (1.5 - v_closed))
    opened = tau_open * np.log((v_open - 1.5) / (v_open - 3.5))
    return first, closed, opened


def test_voltage_switch_ideal_relaxation_oscillator(compile_text) -> None:
    """A capacitor charged through 1 kohm from 5 V is shorted (10 ohm) by an ideal switch
    controlled by its own voltage with hysteresis: closes above Vt + Vh = 3.5 V, opens below
    1.5 V. Every switching instant matches the closed form of the exponential pieces."""
    res = compile_text(RELAXATION).simulate(stop=8e-3, step=1e-6)
    assert res.success, res.message
    first, closed, opened = _relaxation_period()
    n = 2 * int((8e-3 - first) / (closed + opened)) + 1
    exact = first + np.cumsum([0.0] + [closed if k % 2 == 0 else opened for k in range(n)])
    exact = exact[exact < 8e-3 - 1e-6]
    got = _edges(res.t, res["on"])
    assert got.size == exact.size >= 9
    # an edge shows at the first output sample after it (1 us grid)
    assert np.all((got - exact >= -1e-12) & (got - exact <= 1e-6 + 1e-12))
    # the waveform itself: exponential pieces between the exact instants
    assert np.max(np.abs(res["v"] - _relaxation_wave(res.t, exact))) < 1e-6  # measured 3.3e-7


RELAXATION = """
    components:
      - {name: V1, type: V, p: in, n: gnd, V: 5 V}
      - {name: R1, type: R, p: in, n: c, R: 1 kohm}
      - {name: C1, type: C, p: c, n: gnd, C: 1 uF}
      - {name: S1, type: S, p: c, n: gnd, cp: c, cn: gnd, model: ideal, Vt: 2.5 V,
         Vh: 1 V, Ron: 10 ohm, Roff: 1 Gohm}
    probes: {v: c.v, on: S1.on}
    analysis: {stop: 3 ms, rtol: 1e-10, atol: 1e-12}
"""


@pytest.mark.ngspice
def test_voltage_switch_ideal_against_ngspice(compile_text) -> None:
    """The relaxation oscillator above against ngspice's switch (VT 2.5, VH 1: the same
    hysteresis law; tests/decks/vswitch_relax.cir, tmax 10 ns): the instants where the
    capacitor turns (closings and openings) agree within 50 ns over three periods (ngspice
    switches at its own time points; measured up to 3.4e-8 s, growing by about 1e-8 s a
    period)."""
    require_ngspice()
    ng = run_ngspice((DECKS / "vswitch_relax.cir").read_text(), ["v(c)"])
    t, v = ng["time"], ng["v(c)"]
    d = np.diff(v)
    ng_edges = np.sort(np.concatenate([t[1:-1][(d[:-1] > 0) & (d[1:] <= 0)],  # closings
                                       t[1:-1][(d[:-1] < 0) & (d[1:] >= 0)]]))  # openings
    res = compile_text(RELAXATION).simulate(t_eval=np.concatenate([[0.0], t]))
    assert res.success, res.message
    ours = _edges(res.t, res["on"])
    assert ours.size == ng_edges.size == 6
    assert np.max(np.abs(ours - ng_edges)) < 5e-8


def _relaxation_wave(t: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """Closed-form capacitor voltage [V] of the relaxation oscillator, given its switching
    instants: open pieces charge from 1.5 V (from 0 at first), closed pieces discharge from
    3.5 V."""
    V, R, C, Ron, Roff = 5.0, 1e3, 1e-6, 10.0, 1e9
    v_open, tau_open = V * Roff / (R + Roff), R * Roff / (R + Roff) * C
    v_closed, tau_closed = V * Ron / (R + Ron), R * Ron / (R + Ron) * C
    k = np.searchsorted(edges, t, side="right")  # pieces before t
    start = np.where(k > 0, edges[np.maximum(k - 1, 0)], 0.0)
    closed = k % 2 == 1
    v0 = np.where(k == 0, 0.0, np.where(closed, 3.5, 1.5))
    target = np.where(closed, v_closed, v_open)
    tau = np.where(closed, tau_closed, tau_open)
    return target + (v0 - target) * np.exp(-(t - start) / tau)


def _rectifier_reference(t_eval: np.ndarray) -> np.ndarray:
    """Hand-written half-wave rectifier (scipy, independent of circuitsim): sine 10 V 50 Hz,
    pwl diode (Vf 0.7 V, Ron 0.1 ohm, Goff 1e-9 S), 100 uF || 100 ohm. The diode state
    switches at v_d = Vf by solve_ivp's event location; returns v_C [V] at t_eval."""
    Vf, Ron, Goff, C, R = 0.7, 0.1, 1e-9, 100e-6, 100.0

    def current(t, v, on):
        vd = 10 * np.sin(2 * np.pi * 50 * t) - v
        return (vd - Vf) / Ron + Vf * Goff if on else Goff * vd

    def knee(t, y):
        return 10 * np.sin(2 * np.pi * 50 * t) - y[0] - Vf

    knee.terminal = True
    t0, y, on, out_t, out_v = 0.0, [0.0], False, [], []
    while t0 < t_eval[-1]:
        knee.direction = -1 if on else 1  # off: watch v_d rise through Vf; on: fall
        sol = solve_ivp(lambda t, y, on=on: [(current(t, y[0], on) - y[0] / R) / C],
                        (t0, t_eval[-1]), y, events=knee, rtol=1e-12, atol=1e-14, dense_output=True,
                        method="LSODA", max_step=1e-4)
        te = sol.t_events[0]
        end = te[0] if te.size else t_eval[-1]
        pick = (t_eval >= t0) & (t_eval <= end)
        if pick.any():
            out_t.append(t_eval[pick])
            out_v.append(sol.sol(t_eval[pick])[0])
        t0, y, on = end, [sol.sol(end)[0]], not on
    t_all, v_all = np.concatenate(out_t), np.concatenate(out_v)
    _, first = np.unique(t_all, return_index=True)
    return v_all[first]


def test_ideal_diode_rectifier_against_scipy(compile_text) -> None:
    """An ideal (pwl, event-switched) diode charging 100 uF || 100 ohm from a 10 V 50 Hz
    sine: the capacitor voltage over three periods agrees with a hand-written scipy model
    that switches the same pwl diode by its own event location."""
    model = compile_text(RECTIFIER)
    res = model.simulate()
    assert res.success, res.message
    ref = _rectifier_reference(res.t)
    assert np.max(np.abs(res["vc"] - ref)) < 2e-8  # measured 2.7e-9 V
    assert _edges(res.t, res["on"]).size == 6  # on and off once per period


def _brake_speed(t: np.ndarray) -> np.ndarray:
    """Closed form of the brake test below [rad/s]: J = 0.01, w0 = 10, Tc = 0.5, Ts = 0.8,
    load torque 0.2 N m ramping by 1 N m/s from 0.5 s to 1.2 N m at 1.5 s. Slips down to
    rest at 1/3 s, stuck until the torque reaches Ts at 1.1 s, then slips forward."""
    J, Tc = 0.01, 0.5
    torque_area = np.where(t < 1.5, (t - 0.5) ** 2 / 2 + 0.2 * (t - 0.5),  # int_0.5^t T
                           0.5 + 0.2 + 1.2 * (t - 1.5))
    at_break = (1.1 - 0.5) ** 2 / 2 + 0.2 * 0.6
    slip = (torque_area - at_break - Tc * (t - 1.1)) / J
    return np.where(t < 1 / 3, 10 - 30 * t, np.where(t < 1.1, 0.0, slip))


def test_stick_slip_brake_holds_exactly_and_breaks_away_at_static_capacity(compile_text
                                                                           ) -> None:
    """A braked inertia (kinetic 0.5 N m, static 0.8 N m) under a load torque: it slides to
    rest, stays exactly at rest while the load rises, and breaks away when the load reaches
    the static capacity (closed form in three pieces). The regularised clutch creeps
    instead."""
    model = compile_text("""
        components:
          - {name: J1, type: inertia, shaft: s, J: 0.01, w0: 10}
          - {name: B1, type: stick_clutch, a: s, b: fixed, fn: 1, mu: 0.5, mu_s: 0.8}
          - {name: T1, type: torque, shaft: s,
             T: {pwl: [[0, 0.2], [0.5, 0.2], [1.5, 1.2]]}}
        probes: {w: s.w, mode: B1.mode, tau: B1.tau}
        analysis: {stop: 2, step: 1 ms, rtol: 1e-10, atol: 1e-12}
    """)
    res = model.simulate()
    assert res.success, res.message
    exact = _brake_speed(res.t)
    stuck = (res.t > 1 / 3 + 1e-3) & (res.t < 1.1)
    assert np.max(np.abs(res["w"][stuck])) < 1e-9  # no creep
    assert np.max(np.abs(res["w"] - exact)) < 1e-9  # measured 1.7e-12 rad/s
    late = _edges(res.t, res["mode"]) - np.array([1 / 3, 1.1])  # shown at the next sample
    assert np.all((late > -1e-12) & (late <= 1e-3 + 1e-12)), late


def test_stick_slip_clutch_locks_exactly(compile_text) -> None:
    """The smooth clutch's test (tests/test_breadth_mechanics.py) with exact adhesion: a
    shaft held at 10 rad/s drags an inertia at rest through 0.5 N m until their speeds meet
    at 0.2 s, then carries it along: w = min(50 t, 10) with no creep at the lock."""
    model = compile_text("""
        components:
          - {name: S1, type: speed, shaft: drive, W: 10}
          - {name: M0, type: inertia, shaft: drive, J: 1}
          - {name: K1, type: stick_clutch, a: drive, b: out, fn: 0.5}
          - {name: M1, type: inertia, shaft: out, J: 0.01}
        probes: {w: out.w, mode: K1.mode}
        analysis: {stop: 0.5, step: 1 ms, rtol: 1e-9, atol: 1e-12}
    """)
    res = model.simulate()
    assert res.success, res.message
    assert np.max(np.abs(res["w"] - np.minimum(50 * res.t, 10.0))) < 1e-9  # measured 1.1e-11
    assert res["mode"][-1] == 0 and res["mode"][1] == 1


def test_a_switching_that_cannot_settle_stops_with_the_element_named(compile_text) -> None:
    """A switch that shorts its own control (closes above 2.6 V, which closing pulls to 0 V,
    which opens it again) has no consistent state: the run stops at t = 0 naming S1,
    instead of switching forever."""
    model = compile_text("""
        components:
          - {name: V1, type: V, p: in, n: gnd, V: 5}
          - {name: R1, type: R, p: in, n: c, R: 1 kohm}
          - {name: S1, type: S, p: c, n: gnd, cp: c, cn: gnd, model: ideal, Vt: 2.5,
             Vh: 0.1, Ron: 1}
        probes: {v: c.v}
        analysis: {stop: 1 ms}
    """)
    res = model.simulate()
    assert not res.success
    assert "S1" in res.message and "does not settle" in res.message


def test_analyses_that_cannot_switch_say_so(compile_text) -> None:
    """The operating point and the periodic steady state do not follow events: a model with
    an ideal switch is refused with the element named (issue 15)."""
    from circuitsim.errors import SolverError
    from circuitsim.solve.op import operating_point
    from circuitsim.solve.pss import periodic_steady_state

    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {sine: {amplitude: 10, freq: 50}}}
          - {name: D1, type: D, p: a, n: b, model: ideal}
          - {name: R1, type: R, p: b, n: gnd, R: 100}
    """)
    with pytest.raises(SolverError, match="D1"):
        operating_point(model)
    with pytest.raises(SolverError, match="D1"):
        periodic_steady_state(model, period=0.02)
