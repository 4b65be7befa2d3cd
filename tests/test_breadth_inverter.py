"""The ideal PWM half-bridge (issue 15 item 3): its switching against the exact periodic
steady state of an RL load (closed form of the piecewise-linear circuit), dead time through
the diodes, the carriers, and the smooth ``pwm_leg`` converging to it as its edge narrows."""

from __future__ import annotations

import itertools
import warnings

import numpy as np
import pytest

import circuitsim as cs

from conftest import NETLISTS

VDC, R, L, F = 10.0, 5.0, 1e-3, 10e3  # [V], [ohm], [H], [Hz]
RON, RD, VF = 0.01, 0.02, 0.7  # switch and diode


def _pss(pieces: list[tuple[float, float, float]]):
    """Exact periodic steady state of L di/dt = a - (b + R) i over pieces (duration [s],
    a [V], b [ohm]) of the output voltage v = a - b i; returns i(tau) [A] for tau in one
    period (the period map is affine: i(T) = alpha i(0) + beta)."""
    alpha, beta = 1.0, 0.0
    for dt, a, b in pieces:
        k = np.exp(-(b + R) * dt / L)
        inf = a / (b + R)
        alpha, beta = k * alpha, k * beta + (1 - k) * inf
    i0 = beta / (1 - alpha)

    def current(tau: np.ndarray) -> np.ndarray:
        out = np.empty_like(tau)
        start, i = 0.0, i0
        for dt, a, b in pieces:
            inside = (tau >= start) & (tau < start + dt)
            inf = a / (b + R)
            out[inside] = inf + (i - inf) * np.exp(-(b + R) * (tau[inside] - start) / L)
            k = np.exp(-(b + R) * dt / L)
            i, start = inf + (i - inf) * k, start + dt
        return out

    return current


def _pieces(edges: list[tuple[float, int]], cmd0: int, td: float, T: float):
    """Output-voltage pieces of one carrier period from the comparator's edges (time in the
    period [s], new state) and its state at 0: after each edge td of dead time with the
    current (positive, out of the leg) in the lower diode, then the new switch."""
    on, off, dead = (VDC, RON), (0.0, RON), (-VF, RD)
    out, t, cmd = [], 0.0, cmd0
    for te, new in [*edges, (T, None)]:
        if te > t:
            out.append((te - t, *(on if cmd else off)))
        if new is None:
            break
        out.append((td, *dead))
        t, cmd = te + td, new
    return out


CASES = {
    # triangle carrier, m = 0.3: the upper switch is on while the carrier is below 0.3
    "triangle, dead time": ("{triangle: {freq: 10 kHz}}", 0.3, "false", 2e-6,
                            lambda T: ([(0.325 * T, 0), (0.675 * T, 1)], 1), 0.0),
    # sawtooth shifted by a quarter period, comparison inverted: on while m < carrier, i.e.
    # from 0.4 of its period to its fall (a dead time follows both edges)
    "sawtooth, phase, inverted": ("{sawtooth: {freq: 10 kHz, phase: 90 deg}}", -0.2, "true",
                                  1e-6, lambda T: ([(0.0, 0), (0.4 * T, 1)], 1), 0.25),
}


@pytest.mark.parametrize("case", list(CASES))
def test_half_bridge_rl_periodic_steady_state(compile_text, case: str) -> None:
    """A leg at 10 kHz into 5 ohm + 1 mH from a 10 V link: after 40 time constants the load
    current equals the exact periodic steady state of the piecewise-linear circuit (switch
    1/Ron, diode Vf + Rd i during the dead time), sample by sample."""
    carrier, m, invert, td, edges_of, shift = CASES[case]
    model = compile_text(f"""
        components:
          - {{name: Vdc, type: V, p: dc, n: gnd, V: {VDC}}}
          - {{name: S1, type: half_bridge, p: o, n: gnd, dc: dc, m: {m}, carrier: {carrier},
             invert: {invert}, td: {td}, Ron: {RON}, Vf: {VF}, Rd: {RD}}}
          - {{name: L1, type: L, p: o, n: gnd, L: {L}, R: {R}}}
        probes: {{i: L1.i, v: o.v}}
        analysis: {{stop: 8 ms, step: 0.2 us, rtol: 1e-9, atol: 1e-12}}
    """)
    res = model.simulate()
    assert res.success, res.message
    T = 1 / F
    edges, cmd0 = edges_of(T)
    exact = _pss(_pieces(edges, cmd0, td, T))
    last = res.t >= 8e-3 - 2 * T
    tau = np.mod(res.t[last] + shift * T, T)  # time within the carrier's own period
    assert res["i"][last].min() > 0.1  # the current never reverses (the pieces assume it)
    err = np.max(np.abs(res["i"][last] - exact(tau)))
    assert err < 1e-7  # measured 2.0e-8 A (triangle) and 6.3e-9 A (sawtooth) on ~1.3 A


def _leg_current(compile_text, leg: str, r_load: float, stop: float = 2.5e-3) -> np.ndarray:
    model = compile_text(f"""
        components:
          - {{name: Vdc, type: V, p: dc, n: gnd, V: 10}}
          - {leg}
          - {{name: L1, type: L, p: o, n: gnd, L: 1 mH, R: {r_load}}}
        probes: {{i: L1.i}}
        analysis: {{stop: {stop}, step: 0.5 us, rtol: 1e-9, atol: 1e-12}}
    """)
    res = model.simulate()
    assert res.success, res.message
    return res["i"]


def test_smooth_leg_converges_to_the_ideal_half_bridge(compile_text) -> None:
    """pwm_leg's tanh edge (width eps in carrier units) against the ideal half-bridge on the
    same triangle carrier (no dead time, so the diodes never conduct): the lossless smooth leg
    gets the ideal one's Ron added to its 10 ohm load. The largest difference of the RL current
    falls monotonically as eps narrows, in proportion to it: the tanh edge lasts
    eps/(4 f_sw) and lags a hard one by a volt-second area Vdc ln2 eps/(8 f_sw), so the
    current differs at most by Vdc ln2 eps/(8 f_sw L) (0.087 A per unit eps here; 8.7e-5 A,
    1.2e-4 of the mean, at eps = 0.001)."""
    ideal = _leg_current(compile_text, "{name: S1, type: half_bridge, p: o, n: gnd, dc: dc, "
                         "m: 0.5, carrier: {triangle: {freq: 10 kHz}}, Ron: 1e-3}", 10.0)
    errors = []
    for eps in (0.1, 0.03, 0.01, 0.003, 0.001):
        smooth = _leg_current(compile_text, "{name: S1, type: pwm_leg, p: o, n: gnd, dc: dc, "
                              f"m: 0.5, f_sw: 10 kHz, eps: {eps}}}", 10.001)
        errors.append(np.max(np.abs(smooth - ideal)))
    assert all(b < a for a, b in itertools.pairwise(errors)), errors
    bound = 10 * np.log(2) * np.array([0.1, 0.03, 0.01, 0.003, 0.001]) / (8 * 10e3 * 1e-3)
    assert np.allclose(errors[1:], bound[1:], rtol=0.02), errors  # measured within 0.3 %


@pytest.mark.slow
def test_h_bridge_drives_the_kim_motor_at_the_averaged_speed() -> None:
    """netlists/inverters/kim_hbridge.yaml with Rf = 0 (the mean link voltage is then the
    supply's): the mean speed over 20-30 ms equals the averaged machine's closed form with
    V = m Vdc - 2 f_sw td (Vdc + 2 Vf) (the dead times' diode conduction) and the loop
    resistance Ra + 2 Ron. Measured 3.0e-4 high over 20-30 ms (2.3e-4 low over 30-40 ms:
    the slow transient of the LC filter and the rotor is not quite over)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(cs.load(NETLISTS / "inverters" / "kim_hbridge.yaml"))
    res = model.simulate(stop=0.03, params={"Rf": 0.0})
    assert res.success, res.message
    k_t, k_e, B, e0 = 0.14, 0.1017 / (2 * np.pi), 2.95e-4, 1.151e-4
    volts = 0.8 * 12 - 2 * 20e3 * 1e-6 * (12 + 2 * 0.7)
    w = k_t * (volts - e0) / (k_t * k_e + B * (1.1 + 2e-3))
    window = res.t >= 0.02
    assert res["i_motor"][window].min() > 0  # the dead-time loss above assumes it
    assert res["speed"][window].mean() == pytest.approx(w, rel=5e-4)


@pytest.mark.slow
def test_three_phase_inverter_matches_the_smooth_legs() -> None:
    """netlists/inverters/bldc_inverter.yaml without dead time against
    netlists/kapun2008/pwm.yaml (the same drive, smooth legs, eps 0.02): the rotor speed 20 ms
    after the start agrees within 1e-3 (measured 1.8e-4, the smooth edge's own error); the
    phase currents of the floating wye sum to zero."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ideal = cs.compile(cs.load(NETLISTS / "inverters" / "bldc_inverter.yaml"))
        smooth = cs.compile(cs.load(NETLISTS / "kapun2008" / "pwm.yaml"))
    a = ideal.simulate(stop=0.02, params={"td": 0.0})
    b = smooth.simulate(stop=0.02)
    assert a.success and b.success, (a.message, b.message)
    assert a["omega"][-1] == pytest.approx(b["omega"][-1], rel=1e-3)
    assert np.max(np.abs(a["i1"] + a["i2"] + a["i3"])) < 1e-6
