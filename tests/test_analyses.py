"""Operating point, AC small-signal and periodic steady state (issue #4)."""

from __future__ import annotations

import numpy as np
import pytest

from circuitsim.errors import SolverError
from circuitsim.solve.ac import ac, harmonic_response
from circuitsim.solve.op import operating_point, probe_values
from circuitsim.solve.pss import periodic_steady_state

from conftest import NETLISTS
from ngspice import require_ngspice, run_ngspice
from reference import small_signal_i8

BASE = NETLISTS / "kim2024" / "base.yaml"
FIG9 = {1e-9: 0.380641, 1e-8: 0.380637, 1e-7: 0.380599, 1e-6: 0.380221, 1e-5: 0.376479,
        1e-4: 0.342658, 1e-3: 0.179293, 1e-2: 0.030793, 1e-1: 0.0033134}


@pytest.fixture(scope="module")
def base():
    import warnings

    import circuitsim as cs

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cs.compile(cs.load(BASE))


@pytest.fixture(scope="module")
def base_transient(base):
    return base.simulate(rtol=1e-9, atol=1e-11)


def test_op_equals_the_transient_steady_state(base, base_transient):
    op = operating_point(base)
    probes = probe_values(base, op)
    speed = base_transient.harmonic("speed", order=8, window=1 / 6).offset
    current = base_transient.harmonic("i_total", order=8, window=1 / 6).offset
    assert probes["speed"] == pytest.approx(648.505, abs=1e-3)
    assert probes["i_total"] == pytest.approx(1.36649, abs=1e-5)
    assert probes["speed"] == pytest.approx(speed, rel=1e-6)
    assert probes["i_total"] == pytest.approx(current, rel=1e-6)


def test_op_explains_a_missing_dc_path(compile_text):
    """A current source charging a capacitor has no DC solution; the message says why."""
    model = compile_text("""
        components:
          - {name: I1, type: I, p: gnd, n: a, I: 1 mA}
          - {name: C1, type: C, p: a, n: gnd, C: 1 uF}
    """)
    with pytest.raises(SolverError, match=r"no DC path|bleed resistor"):
        operating_point(model)


def test_rlc_ac_against_closed_form():
    import circuitsim as cs

    model = cs.compile(cs.load(NETLISTS / "examples" / "rlc.yaml"))
    f = np.logspace(1, 5, 41)
    res = ac(model, "V1", "v_c", f)
    s = 2j * np.pi * f
    exact = 1 / (1 + s * 10 * 1e-6 + s**2 * 10e-3 * 1e-6)
    np.testing.assert_allclose(res.H, exact, rtol=1e-8)


def test_ripple_as_small_signal_source(base, base_transient):
    """The 8th-order back-EMF ripple as a small-signal input: within 0.5 % of the transient
    (they differ by the second-order speed-ripple term, 4e-6 relative)."""
    h = harmonic_response(base, 8, "i_total")
    assert h.frequency == pytest.approx(825.70, abs=0.01)
    assert h.amplitude == pytest.approx(small_signal_i8(), rel=1e-9)
    transient = base_transient.harmonic("i_total", order=8, window=1 / 6).amplitude
    assert h.amplitude == pytest.approx(transient, rel=5e-3)
    assert h.amplitude == pytest.approx(0.38064, rel=5e-3)


def test_fig9_curve_by_ac():
    import warnings

    import circuitsim as cs

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(cs.load(NETLISTS / "kim2024" / "case1.yaml"))
    for lf, ref in FIG9.items():
        h = harmonic_response(model, 8, "i_total", params={"Lf": lf, "Rf": 0.0})
        assert h.amplitude == pytest.approx(ref, rel=5e-3), lf


NETWORKS = {
    "rc": ("""
        components:
          - {name: V1, type: V, p: in, n: gnd, V: 0}
          - {name: R1, type: R, p: in, n: out, R: 1 kohm}
          - {name: C1, type: C, p: out, n: gnd, C: 100 nF}
        probes: {out: out.v}
    """, "V1 in 0 DC 0 AC 1\nR1 in out 1k\nC1 out 0 100n\n"),
    "rlc": ("""
        components:
          - {name: V1, type: V, p: in, n: gnd, V: 0}
          - {name: R1, type: R, p: in, n: a, R: 10 ohm}
          - {name: L1, type: L, p: a, n: out, L: 10 mH}
          - {name: C1, type: C, p: out, n: gnd, C: 1 uF}
          - {name: R2, type: R, p: out, n: gnd, R: 1 kohm}
        probes: {out: out.v}
    """, "V1 in 0 DC 0 AC 1\nR1 in a 10\nL1 a out 10m\nC1 out 0 1u\nR2 out 0 1k\n"),
    "lc": ("""
        components:
          - {name: V1, type: V, p: in, n: gnd, V: 0}
          - {name: L1, type: L, p: in, n: m, L: 1 mH}
          - {name: C1, type: C, p: m, n: gnd, C: 10 uF}
          - {name: L2, type: L, p: m, n: out, L: 1 mH}
          - {name: R2, type: R, p: out, n: gnd, R: 50 ohm}
        probes: {out: out.v}
    """, "V1 in 0 DC 0 AC 1\nL1 in m 1m\nC1 m 0 10u\nL2 m out 1m\nR2 out 0 50\n"),
}


@pytest.mark.ngspice
@pytest.mark.parametrize("name", sorted(NETWORKS))
def test_ac_against_ngspice(name, compile_text):
    require_ngspice()
    yaml_text, deck = NETWORKS[name]
    ng = run_ngspice(f"* {name}\n{deck}.ac dec 20 10 100k\n", ["vm(out)", "vp(out)"])
    f = ng["time"]  # the scale column: frequency
    model = compile_text(yaml_text)
    res = ac(model, "V1", "out", f)
    np.testing.assert_allclose(res.magnitude, ng["vm(out)"], rtol=1e-6)
    np.testing.assert_allclose(np.radians(res.phase), ng["vp(out)"], rtol=1e-6, atol=1e-9)


def test_pss_of_the_base_model(base, base_transient):
    ps = periodic_steady_state(base, order=8)
    f, amp, _ = ps.harmonic("i_total", 1)
    assert f == pytest.approx(825.70264, abs=1e-3)
    assert amp == pytest.approx(0.3806411, abs=1e-5)
    # the same extraction as the long transient's, to its accuracy
    transient = base_transient.harmonic("i_total", order=8, window=1 / 6)
    assert amp == pytest.approx(transient.amplitude, rel=1e-6)
    assert ps["speed"].mean() == pytest.approx(648.505195, abs=1e-4)
    # a full turn as the section gives the same orbit
    full = periodic_steady_state(base, order=1)
    assert full.harmonic("i_total", 8)[1] == pytest.approx(amp, rel=1e-7)


CLAMP = """
    parameters: {A: 5 V}
    components:
      - {name: V1, type: V, p: in, n: gnd, V: {sine: {amplitude: A, freq: 1 kHz}}}
      - {name: R1, type: R, p: in, n: a, R: 100 ohm}
      - {name: X1, type: varistor, p: a, n: gnd, V_ref: 33 V, I_ref: 1 mA, alpha: 30, C: 10 nF}
    probes: {i: R1.i}
    analysis: {stop: 20 ms, rtol: 1e-9, atol: 1e-12}
"""


def test_pss_and_ac_agree_while_linear_and_part_when_the_varistor_clamps(compile_text):
    model = compile_text(CLAMP)
    for amp, agree in ((5.0, True), (60.0, False)):
        ps = periodic_steady_state(model, {"A": amp}, period=1e-3)
        _, i_pss, _ = ps.harmonic("i", 1)
        # a unit small-signal source in series with V1 (its offset), scaled to the amplitude
        i_ac = amp * ac(model, "V1", "i", [1e3]).magnitude[0]
        if agree:
            assert i_pss == pytest.approx(i_ac, rel=1e-4)
        else:
            assert i_pss > 5 * i_ac  # the clamp conducts: far more current than linear
        # the shooting result is the long transient's periodic state
        tr = model.simulate(stop=0.02, params={"A": amp}, step=1e-6)
        last = tr.t >= 0.019
        i_tr = np.max(np.abs(tr["i"][last]))
        assert np.max(np.abs(ps["i"])) == pytest.approx(i_tr, rel=1e-3)


RC_SINE = """
    components:
      - {name: V1, type: V, p: a, n: gnd, V: {sine: {offset: 1, amplitude: 1, freq: 1 kHz}}}
      - {name: R1, type: R, p: a, n: b, R: 1 kohm}
      - {name: C1, type: C, p: b, n: gnd, C: 1 uF}
    probes: {v: b.v}
"""


@pytest.mark.parametrize("drive", ["1 mA", "{sine: {offset: 1 mA, amplitude: 1 mA, freq: 1 kHz}}"])
def test_pss_refuses_a_drive_that_charges_a_capacitor_every_period(compile_text, drive):
    """A current with a nonzero mean into a capacitor has no periodic steady state. Newton's
    step through a zero derivative threw a.v to 1e9 V, where the 1 V gap passed the relative
    tolerance: 'mean 9.007199e+09 V', exit 0."""
    model = compile_text(f"""
        components:
          - {{name: I1, type: I, p: gnd, n: a, I: {drive}}}
          - {{name: C1, type: C, p: a, n: gnd, C: 1 uF}}
        probes: {{v: a.v}}
    """)
    with pytest.raises(SolverError, match=r"there is none: a\.v ends each period \+(1|0\.9)"):
        periodic_steady_state(model, period=1e-3)


@pytest.mark.parametrize("period", [0.7e-3, 1e-15])
def test_pss_refuses_a_period_that_is_not_the_drives(compile_text, period):
    """Shot over 0.7 ms, an RC fed a 1 kHz sine 'settled' at a mean of 1.30 V (1 V), exit 0;
    over 1 fs the state at rest passed as periodic."""
    from circuitsim.errors import ParameterError

    model = compile_text(RC_SINE)
    with pytest.raises(ParameterError, match=r"V1: the shooting period .* is not a whole "
                                             r"number of the sine source's period 0\.001 s"):
        periodic_steady_state(model, period=period)
    ps = periodic_steady_state(model, period=3e-3)  # a whole number of periods is a period
    assert ps["v"].mean() == pytest.approx(1.0, abs=1e-6)


@pytest.mark.parametrize("order", [3, 1.5, 16])
def test_pss_over_a_fraction_of_a_turn_the_circuit_does_not_repeat_is_refused(base, order):
    """The base model's ripple is of order 8: over 1/3, 2/3 or 1/16 of a turn the circuit is
    not the same, so no steady state repeats there. Shooting at order 1.5 had 'converged' to a
    mean speed 0.6 % off the true one (644.34 against 648.51 rad/s), said as a result."""
    with pytest.raises(ValueError, match=rf"not the same after 1/{order:g} of a turn"):
        periodic_steady_state(base, order=order)


def test_pss_at_a_divisor_of_the_ripple_order_is_the_orbit_of_order_8(base):
    quarter = periodic_steady_state(base, order=4)
    assert quarter["speed"].mean() == pytest.approx(648.505195, abs=1e-4)
    assert quarter.harmonic("i_total", 2)[1] == pytest.approx(0.3806411, abs=1e-5)


def test_pss_of_a_shaft_at_rest_says_why(compile_text):
    """A motor on a step source that starts at 0: the operating point at t = 0 stands still,
    the period 2 pi / (order w) was infinite and the user read "'tspan' must stictly
    increase" after two numpy warnings."""
    model = compile_text((NETLISTS / "examples" / "dc_motor.yaml").read_text(encoding="utf-8"))
    with pytest.raises(ValueError, match=r"the shaft stands still at the operating point "
                                         r"\(speed 0 rad/s"):
        periodic_steady_state(model, order=1)


@pytest.mark.parametrize("series", ["", "1 mohm"])
def test_ac_of_a_source_across_a_capacitor(compile_text, series):
    """A voltage source straight across a capacitor: index reduction writes the capacitor's
    current with the source value's derivative, zero for a constant, so ac answered |H| =
    1/R (no j w C) for the source current and 0 for the capacitor's, exit 0. Refused now,
    and right once the source has a series resistance."""
    from circuitsim.errors import ParameterError

    wire = ("{name: Rs, type: R, p: s, n: a, R: " + series + "}") if series else \
        "{name: Rs, type: R, p: a, n: gnd, R: 1 kohm}"
    model = compile_text(f"""
        components:
          - {{name: V1, type: V, p: {'s' if series else 'a'}, n: gnd, V: 1}}
          - {wire}
          - {{name: C1, type: C, p: a, n: gnd, C: 1 uF}}
          - {{name: R1, type: R, p: a, n: gnd, R: 1 kohm}}
        probes: {{ic: C1.i}}
    """)
    if not series:
        with pytest.raises(ParameterError, match=r"net\.yaml:\d+: V1: ac: the input 'V1'.*"
                                                 r"series resistance"):
            ac(model, "V1", "ic", [1e3])
        return
    res = ac(model, "V1", "ic", [1e3])
    assert res.magnitude[0] == pytest.approx(2 * np.pi * 1e3 * 1e-6, rel=1e-5)


@pytest.mark.parametrize("kind", ["V-across-C", "I-through-L"])
def test_op_holds_the_sources_at_the_instant(compile_text, kind):
    """Index reduction writes a capacitor's current across a source as C dV/dt (an inductor's
    voltage in series with a current source as L dI/dt). The operating point at time t holds
    the sources at their values there: that current (voltage) is 0 and R carries V/R (the
    source current). It reported C.i = 2 pi f C A at t = 0, the transient's value. The
    transient keeps it: C dV/dt (L dI/dt) to rounding at every output point."""
    f, amp, x, r = 1e3, 1.0, 1e-6, 1e3
    if kind == "V-across-C":
        parts = f"""
          - {{name: S1, type: V, p: a, n: gnd, V: {{sine: {{amplitude: {amp}, freq: {f}}}}}}}
          - {{name: X1, type: C, p: a, n: gnd, C: {x}}}
          - {{name: R1, type: R, p: a, n: gnd, R: {r}}}"""
        probe = "X1.i"
    else:  # the source pushes its current into a, through the inductor and R to ground
        parts = f"""
          - {{name: S1, type: I, p: gnd, n: a, I: {{sine: {{amplitude: {amp}, freq: {f}}}}}}}
          - {{name: X1, type: L, p: a, n: b, L: {x}}}
          - {{name: R1, type: R, p: b, n: gnd, R: {r}}}"""
        probe = "X1.v"
    model = compile_text(f"""
        components:{parts}
        probes: {{x: {probe}, r: R1.i}}
        analysis: {{stop: 1 ms, step: 1 us, rtol: 1e-9}}
    """)
    for t in (0.0, 0.1e-3, 0.25e-3):
        held = amp * np.sin(2 * np.pi * f * t)  # the source's value at t
        got = probe_values(model, operating_point(model, t=t), t=t)
        assert got["x"] == pytest.approx(0.0, abs=1e-15)
        assert got["r"] == pytest.approx(held / r if kind == "V-across-C" else held,
                                         abs=1e-12)
    res = model.simulate()
    dual = x * amp * 2 * np.pi * f * np.cos(2 * np.pi * f * res.t)  # C dV/dt, or L dI/dt
    assert np.max(np.abs(res["x"] - dual)) <= 1e-9 * np.max(np.abs(dual))


def test_pss_over_a_whole_turn_of_the_filtered_motor_is_the_orbit_of_order_8():
    """Kim & Kim's case 4 (connector and filter): shooting over a whole turn at the default
    rtol 1e-10 wandered at 1e-9 of the speed, Newton's noise floor, and stopped after 20
    steps; the map is integrated more finely until Newton converges. Its orbit is order 8's:
    eight times the period, the same mean speed and ripple."""
    import warnings

    import circuitsim as cs

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(cs.load(NETLISTS / "kim2024" / "case4.yaml"))
    whole = periodic_steady_state(model, order=1)
    eighth = periodic_steady_state(model, order=8)
    assert whole.period == pytest.approx(8 * eighth.period, rel=1e-8)
    assert whole["speed"].mean() == pytest.approx(eighth["speed"].mean(), rel=1e-9)
    assert whole.harmonic("i_total", 8)[1] == pytest.approx(
        eighth.harmonic("i_total", 1)[1], rel=1e-6)


def test_pss_of_a_machine_turning_backwards():
    """Kim & Kim's case 6 at Vin = -5 V turns backwards: the period was taken as 2 pi /
    (order w) < 0, and the shooting integrated the stable orbit backwards in time until IDA
    ran out of steps. The period is a time whatever the sense; the angle travels backwards.
    Its orbit: one turn in one period, and the transient's mean speed."""
    import warnings

    import circuitsim as cs

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(cs.load(NETLISTS / "kim2024" / "case6.yaml"))
    ps = periodic_steady_state(model, {"Vin": -5.0})
    w = ps["speed"].mean()
    assert ps.period > 0 and w < 0
    assert ps.period * abs(w) == pytest.approx(2 * np.pi, rel=1e-5)
    run = model.simulate(params={"Vin": -5.0}, stop=0.6, rtol=1e-9, atol=1e-11)
    assert run.harmonic("speed", order=8, window=0.1).offset == pytest.approx(w, rel=1e-5)


def test_the_ripple_of_a_shaft_turning_backwards_has_a_positive_frequency(base):
    """``ac --order`` and ``SimResult.harmonic(order=)`` on the base motor at -12 V: the
    order-8 ripple's frequency is 8 |w| / 2 pi (it was -825.7 Hz, and the transient's
    harmonic was refused as a negative frequency); its amplitude is the transient's."""
    resp = harmonic_response(base, 8, "i_total", {"Vin": -12.0})
    run = base.simulate(params={"Vin": -12.0}, rtol=1e-9, atol=1e-11)
    h = run.harmonic("i_total", order=8, window=1 / 6)
    assert resp.frequency == pytest.approx(h.frequency, rel=1e-4)
    assert resp.frequency == pytest.approx(8 * 648.52 / (2 * np.pi), rel=1e-4)
    assert resp.amplitude == pytest.approx(h.amplitude, rel=1e-4)
