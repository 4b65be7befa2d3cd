"""Source waveforms and the step bound they impose (issue 15, sources).

References: ngspice decks kept in tests/decks/ (SIN with delay, damping and phase; EXP;
PULSE; the diode charging a capacitor from a sine) and closed forms.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

import circuitsim as cs
from circuitsim.errors import CircuitWarning, NetlistError, ParameterError

from conftest import NETLISTS
from ngspice import require_ngspice, run_ngspice

DECKS = Path(__file__).resolve().parent / "decks"
ROOT = Path(__file__).resolve().parent.parent


@pytest.mark.ngspice
def test_diode_charging_capacitor_matches_ngspice_with_no_setting() -> None:
    """The silent wrong answer of issue 15: without a step bound IDA stepped over the
    conduction windows and ended at 6.65 V. ngspice (tmax 1 ms) gives 8.2633 V; its own
    spread between tmax 1 ms and 0.5 ms is ~1e-5 V, so 1 mV is a wide but honest margin
    against a 1.6 V error."""
    require_ngspice()
    ng = run_ngspice((DECKS / "diode_charge.cir").read_text(), ["v(c)"])
    ref = float(ng["v(c)"][-1])
    assert ref == pytest.approx(8.263, abs=1e-3)
    model = cs.compile(cs.load(ROOT / "netlists" / "breadth" / "diode_charge.yaml"))
    res = model.simulate()
    assert res.success
    assert res["v_c"][-1] == pytest.approx(ref, abs=1e-3)


@pytest.mark.ngspice
def test_sin_exp_pulse_match_ngspice(compile_text) -> None:
    """SPICE SIN (delay, damping, phase in degrees), EXP and PULSE: the source voltages at
    ngspice's own time points (ngspice evaluates the waveform exactly there)."""
    require_ngspice()
    ng = run_ngspice((DECKS / "sources.cir").read_text(), ["v(a)", "v(b)", "v(c)"])
    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {sine: {offset: 1 V, amplitude: 2 V,
             freq: 50 Hz, delay: 5 ms, damping: 20, phase: 30 deg}}}
          - {name: R1, type: R, p: a, n: gnd, R: 1}
          - {name: V2, type: V, p: b, n: gnd, V: {exp: {v1: 0.5 V, v2: 3 V, delay1: 2 ms,
             tau1: 1 ms, delay2: 6 ms, tau2: 2 ms}}}
          - {name: R2, type: R, p: b, n: gnd, R: 1}
          - {name: V3, type: V, p: c, n: gnd, V: {pulse: {v1: -1 V, v2: 4 V, delay: 1 ms,
             rise: 0.5 ms, fall: 1 ms, width: 2 ms, period: 5 ms}}}
          - {name: R3, type: R, p: c, n: gnd, R: 1}
        probes: {a: a.v, b: b.v, c: c.v}
        analysis: {stop: 20 ms}
    """)
    t = ng["time"]
    res = model.simulate(t_eval=t)
    assert res.success
    for name in "abc":
        got = np.interp(t, res.t, res[name])
        assert np.max(np.abs(got - ng[f"v({name})"])) < 1e-9, name


def test_breakpoints_of_the_new_waveforms() -> None:
    import circuitsim_components  # noqa: F401
    from circuitsim.component import WAVEFORMS

    sine = {"offset": 0, "amplitude": 1, "freq": 50, "phase": 0, "delay": 2e-3, "damping": 0}
    assert WAVEFORMS["sine"]().breakpoints(sine, 1.0) == [2e-3]
    assert WAVEFORMS["sine"]().max_step(sine) == pytest.approx(1 / 50 / 20)
    ex = {"v1": 0, "v2": 1, "delay1": 1e-3, "tau1": 1e-3, "delay2": 4e-3, "tau2": 1e-3}
    assert WAVEFORMS["exp"]().breakpoints(ex, 1.0) == [1e-3, 4e-3]


def test_rc_driven_by_a_delayed_damped_sine_closed_form(compile_text) -> None:
    """RC low-pass (tau = RC) fed by e^{-a s} sin(w s) after the delay (s = t - td): the
    exact response is the convolution with e^{-s/tau}/tau, integrated in closed form."""
    model = compile_text("""
        components:
          - {name: V1, type: V, p: in, n: gnd, V: {sine: {amplitude: 1 V, freq: 100 Hz,
             delay: 3 ms, damping: 50}}}
          - {name: R1, type: R, p: in, n: out, R: 1 kohm}
          - {name: C1, type: C, p: out, n: gnd, C: 1 uF}
        probes: {v: out.v}
        analysis: {stop: 30 ms, step: 0.1 ms, rtol: 1e-9, atol: 1e-12}
    """)
    res = model.simulate()
    tau, td, a, w = 1e-3, 3e-3, 50.0, 2 * np.pi * 100
    # v' = (u - v)/tau with u = e^{-a s} sin(w s), s = t - td >= 0: the closed form
    s = np.clip(res.t - td, 0, None)
    b = 1 / tau - a  # e^{-t/tau} * integral_0^s e^{x/tau} e^{-a x} sin(w x) dx / tau
    integ = (np.exp(b * s) * (b * np.sin(w * s) - w * np.cos(w * s)) + w) / (b**2 + w**2)
    exact = np.exp(-s / tau) * integ / tau
    assert np.max(np.abs(res["v"] - exact)) < 1e-6


def test_pwl_from_csv_equals_inline(compile_text, tmp_path) -> None:
    (tmp_path / "pts.csv").write_text("time,v\n0,0\n0.001,2\n0.003,2\n0.004,-1\n")
    body = """
        components:
          - {{name: V1, type: V, p: in, n: gnd, V: {{pwl: {pwl}}}}}
          - {{name: R1, type: R, p: in, n: out, R: 1 kohm}}
          - {{name: C1, type: C, p: out, n: gnd, C: 1 uF}}
        probes: {{v: out.v, u: in.v}}
        analysis: {{stop: 6 ms, step: 0.05 ms, rtol: 1e-9, atol: 1e-12}}
    """
    a = compile_text(body.format(pwl="{file: pts.csv, column: v}")).simulate()
    b = compile_text(body.format(pwl="[[0, 0], [1 ms, 2 V], [3 ms, 2 V], [4 ms, -1 V]]"))
    b = b.simulate()
    assert np.allclose(a["u"], b["u"], atol=1e-12)
    assert np.allclose(a["v"], b["v"], atol=1e-9)
    assert a["u"][np.searchsorted(a.t, 2e-3)] == pytest.approx(2.0)


def test_pwl_file_errors_name_the_line(write_netlist, tmp_path) -> None:
    (tmp_path / "pts.csv").write_text("time,v\n0,0\n0.001,2\n")
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: in, n: gnd, V: {pwl: {file: pts.csv, column: w}}}
          - {name: R1, type: R, p: in, n: gnd, R: 1}
    """)
    with pytest.raises(NetlistError, match=r"net.yaml:2: V1: .*no column 'w'"):
        cs.load(path)


def test_a_terahertz_sine_is_refused_not_aliased(compile_text) -> None:
    """Issue 15: a 1 THz sine through an RC silently gave 0.645 V (0.632 V expected). Now the
    run is refused with the component and what to do."""
    model = compile_text("""
        components:
          - {name: V1, type: V, p: in, n: gnd, V: {sine: {offset: 1 V, amplitude: 1 V,
             freq: 1 THz}}}
          - {name: R1, type: R, p: in, n: out, R: 1 kohm}
          - {name: C1, type: C, p: out, n: gnd, C: 1 mF}
        probes: {v: out.v}
        analysis: {stop: 1 s, step: 1 ms}
    """)
    with pytest.raises(ParameterError, match=r"net.yaml:\d+: V1: the sine source repeats"):
        model.simulate()


def test_output_coarser_than_the_source_warns_and_stays_right(compile_text) -> None:
    """A 1 kHz sine sampled every 5 ms: warned about; the integration still follows the sine,
    so the RC (tau = 1 s) output is the closed form of its mean response (1 - e^{-t}) plus a
    ripple of amplitude 1/(2 pi 1000) ~ 1.6e-4."""
    model = compile_text("""
        components:
          - {name: V1, type: V, p: in, n: gnd, V: {sine: {offset: 1 V, amplitude: 1 V,
             freq: 1 kHz}}}
          - {name: R1, type: R, p: in, n: out, R: 1 kohm}
          - {name: C1, type: C, p: out, n: gnd, C: 1 mF}
        probes: {v: out.v}
        analysis: {stop: 1 s, step: 5 ms}
    """)
    with warnings.catch_warnings(record=True) as got:
        warnings.simplefilter("always")
        res = model.simulate()
    assert any(issubclass(w.category, CircuitWarning) and "aliases" in str(w.message)
               for w in got)
    assert np.max(np.abs(res["v"] - (1 - np.exp(-res.t)))) < 2e-4


def test_corners_of_two_sources_an_ulp_apart_restart_after_both(compile_text) -> None:
    """A pwl's corner at 0.6 ms and a pulse's at 0.1 ms + 0.5 ms (one ulp later) merge into
    one restart. Restarted at the earlier, y' took the pulse's flat slope before its rise;
    with every unknown algebraic (all in IDA's error test) it failed at 0.6 ms. The currents
    are the sources over R (closed form)."""
    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {pulse: {v1: 0, v2: 5 V, delay: 0.1 ms,
             rise: 10 us, fall: 20 us, width: 0.2 ms, period: 0.5 ms}}}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
          - {name: V2, type: V, p: b, n: gnd, V: {pwl: [[0, 0], [0.3 ms, 3 V], [0.6 ms, -1 V]]}}
          - {name: R2, type: R, p: b, n: gnd, R: 2 ohm}
        probes: {i1: R1.i, i2: R2.i}
        analysis: {stop: 1 ms, step: 1 us, rtol: 1e-10, atol: 1e-12}
    """)
    res = model.simulate()
    assert res.success and res.t.size == 1001
    t = res.t
    ph = np.mod(t - 1e-4, 5e-4)
    pulse = np.where(t < 1e-4, 0.0, np.interp(ph, [0, 1e-5, 2.1e-4, 2.3e-4, 5e-4],
                                              [0, 5, 5, 0, 0]))
    pwl = np.interp(t, [0, 3e-4, 6e-4], [0, 3, -1])
    assert np.allclose(res["i1"], pulse, atol=1e-9)
    assert np.allclose(res["i2"], pwl / 2, atol=1e-9)


def test_a_fast_rise_at_t0_is_resolved_however_long_the_run() -> None:
    """A step with a 1 ns rise at t = 0, read 100 s later (a record whose clock runs on from
    the inputs'): its two corners were merged when the merge distance was relative to the
    run's length (1e-11 * 100 s = 1 ns), and IDA failed at t = 0. The DC motor's steady speed
    is its closed form k V / (k^2 + b R) [rad/s]."""
    model = cs.compile(cs.load(NETLISTS / "examples" / "dc_motor.yaml"))
    t = np.linspace(100.0, 100.5, 101)
    res = model.simulate(stop=float(t[-1]), t_eval=t, rtol=1e-8)
    assert res.success, res.message
    assert np.allclose(res["speed"], 0.05 * 12 / (0.05**2 + 1e-5 * 1), rtol=1e-6)
