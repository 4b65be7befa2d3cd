"""Each component alone in a rig with an analytic answer (issue #2, components)."""

from __future__ import annotations

import numpy as np
import pytest


def rel_err(sim, exact):
    return float(np.max(np.abs(sim - exact)) / np.max(np.abs(exact)))


def test_torque_source_inertia_damper(compile_text):
    model = compile_text("""
        components:
          - {name: T1, type: torque, shaft: s, T: {step: {v1: 0.02 N*m, rise: 1 ns}}}
          - {name: Jr, type: inertia, shaft: s, J: 2e-5}
          - {name: Bv, type: damper, shaft: s, b: 1e-4}
        probes: {w: s.w, phi: s.phi}
        analysis: {stop: 1.0, step: 1 ms, rtol: 1e-10, atol: 1e-12}
    """)
    res = model.simulate()
    tau = 2e-5 / 1e-4
    w = 200 * (1 - np.exp(-res.t / tau))
    assert rel_err(res["w"], w) < 1e-6
    assert rel_err(res["phi"], 200 * (res.t - tau * (1 - np.exp(-res.t / tau)))) < 1e-6
    # ``in`` asks for a name (a probe, a variable), never for an index
    assert "w" in res and "s.w" in res and "speeed" not in res and 0 not in res


def test_mass_damper_force_source(compile_text):
    model = compile_text("""
        components:
          - {name: F1, type: force, flange: x, F: {step: {v1: 10 N, rise: 1 ns}}}
          - {name: M1, type: mass, flange: x, m: 2 kg}
          - {name: D1, type: tdamper, flange: x, d: 4}
        probes: {v: x.v, pos: x.x}
        analysis: {stop: 3.0, step: 1 ms, rtol: 1e-10, atol: 1e-12}
    """)
    res = model.simulate()
    assert rel_err(res["v"], 2.5 * (1 - np.exp(-2 * res.t))) < 1e-6


def test_coulomb_friction_steady_speed(compile_text):
    """Far above the breakaway speed the smooth friction is tau_c + b w (tanh -> 1, the
    Stribeck bump -> 0), so the speed settles at (T - tau_c) / b."""
    model = compile_text("""
        components:
          - {name: T1, type: torque, shaft: s, T: 0.05}
          - {name: Jr, type: inertia, shaft: s, J: 1e-5}
          - {name: F1, type: friction, shaft: s, tau_c: 0.02, tau_brk: 0.03, w_brk: 0.1,
             b: 1e-4}
        probes: {w: s.w, tau: F1.tau}
        analysis: {stop: 2.0, step: 1 ms, rtol: 1e-10, atol: 1e-12}
    """)
    res = model.simulate()
    assert res["w"][-1] == pytest.approx(0.03 / 1e-4, rel=1e-6)
    # breakaway: the peak friction torque at low speed reaches tau_brk
    assert res["tau"].max() == pytest.approx(0.05, rel=1e-3) or res["tau"].max() <= 0.05


def test_friction_holds_below_breakaway(compile_text):
    """A torque below the Coulomb level barely moves the shaft (creep ~ w_brk / 10)."""
    model = compile_text("""
        components:
          - {name: T1, type: torque, shaft: s, T: 0.01}
          - {name: Jr, type: inertia, shaft: s, J: 1e-5}
          - {name: F1, type: friction, shaft: s, tau_c: 0.02, w_brk: 0.01}
        probes: {w: s.w}
        analysis: {stop: 0.5, rtol: 1e-9, atol: 1e-12}
    """)
    res = model.simulate()
    # tau_c tanh(w / (w_brk/10)) + bump = 0.01 has a solution with |w| < w_brk / 10
    assert 0 < res["w"][-1] < 1e-3


def test_cogging_conserves_energy(compile_text):
    """Inertia + cogging only: 1/2 J w^2 + (T/N) cos(N phi) is constant."""
    model = compile_text("""
        components:
          - name: C1
            type: cogging
            shaft: s
            harmonics: [{order: 6, amplitude: 0.01 N*m, phase: 0}]
          - {name: Jr, type: inertia, shaft: s, J: 1e-5, w0: 50 rad/s}
        probes: {w: s.w, phi: s.phi}
        analysis: {stop: 0.5, step: 0.1 ms, rtol: 1e-11, atol: 1e-13}
    """)
    res = model.simulate()
    energy = 0.5 * 1e-5 * res["w"] ** 2 + 0.01 / 6 * np.cos(6 * res["phi"])
    assert np.ptp(energy) < 1e-8 * energy[0]
    assert np.ptp(res["w"]) > 1.0  # the cogging does modulate the speed


def test_varistor_clamp_current(compile_text):
    """Across an ideal sine source the varistor current is explicit: C dv/dt + clamp(v)."""
    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {sine: {amplitude: 40 V, freq: 50 Hz}}}
          - {name: X1, type: varistor, p: a, n: gnd, V_ref: 33 V, I_ref: 1 mA, alpha: 30,
             C: 1 nF}
        probes: {i: X1.i}
        analysis: {stop: 20 ms, step: 10 us, rtol: 1e-10, atol: 1e-14}
    """)
    res = model.simulate()
    v = 40 * np.sin(100 * np.pi * res.t)
    u = v / 33
    exact = 1e-9 * 40 * 100 * np.pi * np.cos(100 * np.pi * res.t) + \
        1e-3 * u * (u**2 + 1e-12) ** 14.5
    assert rel_err(res["i"], exact) < 1e-6
    assert res["i"].max() == pytest.approx(1e-3 * (40 / 33) ** 30, rel=1e-3)


def test_varistor_rc_is_r_in_series_with_c(compile_text):
    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {step: {v1: 10 V, rise: 1 ns}}}
          - {name: X1, type: varistor_rc, p: a, n: gnd, R: 1 kohm, C: 1 uF}
        probes: {i: X1.i}
        analysis: {stop: 5 ms, step: 5 us, rtol: 1e-10, atol: 1e-14}
    """)
    res = model.simulate()
    late = res.t > 1e-6
    assert rel_err(res["i"][late], 10e-3 * np.exp(-res.t[late] / 1e-3)) < 1e-5


def test_pulse_pwl_and_table_sources(compile_text, write_netlist, tmp_path):
    t = np.linspace(0, 1e-3, 11)
    v = np.sin(t * 3000)
    np.savetxt(tmp_path / "in.csv", np.column_stack([t, v]), delimiter=",", header="time,u",
               comments="")
    model = compile_text("""
        components:
          - name: V1
            type: V
            p: a
            n: gnd
            V: {pulse: {v1: 0, v2: 5 V, delay: 0.1 ms, rise: 10 us, fall: 20 us, width: 0.2 ms,
                        period: 0.5 ms}}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
          - {name: V2, type: V, p: b, n: gnd, V: {pwl: [[0, 0], [0.3 ms, 3 V], [0.6 ms, -1 V]]}}
          - {name: R2, type: R, p: b, n: gnd, R: 2 ohm}
          - {name: V3, type: V, p: c, n: gnd, V: {table: {file: in.csv, column: u}}}
          - {name: R3, type: R, p: c, n: gnd, R: 1 ohm}
        probes: {i1: R1.i, i2: R2.i, i3: R3.i}
        analysis: {stop: 1 ms, step: 1 us, rtol: 1e-10, atol: 1e-12}
    """)
    res = model.simulate()
    tt = res.t
    tau = np.mod(tt - 1e-4, 5e-4)
    shape = np.select([tau < 1e-5, tau < 2.1e-4, tau < 2.3e-4],
                      [tau / 1e-5, 1.0, 1 - (tau - 2.1e-4) / 2e-5], 0.0)
    pulse = np.where(tt < 1e-4, 0.0, 5 * shape)
    np.testing.assert_allclose(res["i1"], pulse, atol=1e-9)
    np.testing.assert_allclose(res["i2"], np.interp(tt, [0, 3e-4, 6e-4], [0, 3, -1]) / 2,
                               atol=1e-9)
    np.testing.assert_allclose(res["i3"], np.interp(tt, t, v), atol=1e-9)


def test_pwm_duty_cycle_average(compile_text):
    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd,
             V: {pwm: {low: 0, high: 12 V, freq: 1 kHz, duty: 0.25, rise: 1 us}}}
          - {name: R1, type: R, p: a, n: b, R: 10 ohm}
          - {name: C1, type: C, p: b, n: gnd, C: 1 mF}
        probes: {v: b.v}
        analysis: {stop: 0.1, step: 10 us, rtol: 1e-8, atol: 1e-10}
    """)
    res = model.simulate()
    # In periodic steady state the capacitor carries no mean current, so the mean of v over
    # whole periods is the PWM mean 12 (w + r) / T: width 0.25 ms plus half of each 1 us edge.
    # After 10 RC the start-up transient is e^-10 = 4.5e-5 of 3 V.
    last = res.t > 0.09
    assert np.trapezoid(res["v"][last], res.t[last]) / 0.01 == pytest.approx(
        12 * (0.25e-3 + 1e-6) / 1e-3, rel=2e-4)


def test_rotational_and_translational_share_the_fixed_reference(compile_text):
    """'fixed' is the reference of each mechanical domain; bare-number arithmetic in values
    (2*5e-6, 1/1000) is taken in the parameter's SI unit like a bare number."""
    model = compile_text("""
        components:
          - {name: T1, type: torque, shaft: s, T: 0.1}
          - {name: Jr, type: inertia, shaft: s, J: 2*5e-6}
          - {name: Bv, type: damper, shaft: s, b: 1/1000}
          - {name: F1, type: force, flange: x, F: 1}
          - {name: M1, type: mass, flange: x, m: 1}
          - {name: D1, type: tdamper, flange: x, d: 1}
        probes: {w: s.w, v: x.v}
        analysis: {stop: 0.1, rtol: 1e-10, atol: 1e-12}
    """)
    res = model.simulate()
    np.testing.assert_allclose(res["w"], 100 * (1 - np.exp(-res.t / 0.01)), rtol=1e-6,
                               atol=1e-9)
    np.testing.assert_allclose(res["v"], 1 - np.exp(-res.t), rtol=1e-6, atol=1e-12)


def test_behavioural_force_closes_a_pd_loop(compile_text):
    """A B-source force Kp (ref - x) - Kd v on a 1 kg mass; Kp = 400, Kd = 40: critically
    damped with w0 = 20 rad/s, x = r (1 - (1 + w0 t) exp(-w0 t))."""
    model = compile_text("""
        parameters: {Kp: 400, Kd: 40}
        components:
          - {name: Vref, type: V, p: ref, n: gnd, V: {step: {v1: 0.1, rise: 1 ns}}}
          - {name: Rref, type: R, p: ref, n: gnd, R: 1 kohm}
          - {name: F1, type: bforce, flange: cart, expr: "Kp*(ref.v - cart.x) - Kd*cart.v"}
          - {name: M1, type: mass, flange: cart, m: 1}
        probes: {x: cart.x, f: -F1.f}
        analysis: {stop: 1.0, step: 1 ms, rtol: 1e-10, atol: 1e-13}
    """)
    res = model.simulate()
    x = 0.1 * (1 - (1 + 20 * res.t) * np.exp(-20 * res.t))
    np.testing.assert_allclose(res["x"], x, rtol=1e-6, atol=1e-9)
    # parameters of the expression are run-time values like any other
    stiff = model.simulate(params={"Kp": 1600, "Kd": 80})
    np.testing.assert_allclose(stiff["x"], 0.1 * (1 - (1 + 40 * stiff.t) *
                                                  np.exp(-40 * stiff.t)), rtol=1e-6, atol=1e-9)


def test_behavioural_expression_errors_name_the_line(write_netlist):
    import circuitsim as cs

    path = write_netlist("""
        components:
          - {name: M1, type: mass, flange: cart, m: 1}
          - {name: F1, type: bforce, flange: cart, expr: "3*cart.xx"}
    """)
    with pytest.raises(cs.CircuitsimError, match=r"net.yaml:3: F1: .*'cart.xx'.*cart.x"):
        cs.compile(cs.load(path))
    path = write_netlist("""
        components:
          - {name: M1, type: mass, flange: cart, m: 1}
          - {name: F1, type: bforce, flange: cart, expr: "__import__('os')"}
    """, "b.yaml")
    with pytest.raises(cs.NetlistError, match=r"b.yaml:3: F1: .*unknown function"):
        cs.load(path)


def test_saturating_inductor_flux_and_energy(compile_text):
    """A current ramp i = k t through Lsat: v = dpsi/dt with psi = Linf i + (Lzer - Linf)
    Ipar atan(i / Ipar); the absorbed energy equals the stored energy."""
    model = compile_text("""
        components:
          - {name: I1, type: I, p: gnd, n: a, I: {pwl: [[0, 0], [10 ms, 2 A]]}}
          - {name: L1, type: Lsat, p: a, n: gnd, Lzer: 100 mH, Linf: 0.2 mH, Ipar: 0.07 A}
        probes: {v: a.v, i: L1.i, e: L1.energy, p: L1.power}
        analysis: {stop: 10 ms, step: 10 us, rtol: 1e-10, atol: 1e-13}
    """)
    res = model.simulate()
    k = 2 / 10e-3
    i = k * res.t
    v = (0.2e-3 + (100e-3 - 0.2e-3) / (1 + (i / 0.07) ** 2)) * k
    np.testing.assert_allclose(res["i"], i, rtol=1e-9, atol=1e-12)
    inner = (res.t > 0) & (res.t < 10e-3)  # the ramp's corners are where dI/dt jumps
    np.testing.assert_allclose(res["v"][inner], v[inner], rtol=1e-6)
    from scipy.integrate import cumulative_simpson

    absorbed = cumulative_simpson(res["p"][inner], x=res.t[inner], initial=0.0)
    stored = res["e"][inner]
    assert absorbed[-1] == pytest.approx(stored[-1] - stored[0], rel=1e-6)


def test_drifting_resistor(compile_text):
    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 10 V}
          - {name: R1, type: Rdrift, p: a, n: gnd, R0: 5 ohm, alpha: 0.1}
        probes: {i: R1.i}
        analysis: {stop: 10, step: 0.1, rtol: 1e-11, atol: 1e-14}
    """)
    res = model.simulate()
    np.testing.assert_allclose(res["i"], 10 / (5 * (1 + 0.1 * res.t)), rtol=1e-9)


def test_a_signed_bare_number_parameter_is_taken_in_the_expected_unit(compile_text):
    """'-0.9' in the parameters block is a bare number like '0.9' (diagnose writes fitted
    cogging coefficients so); a cogging amplitude of -a equals a phase shift of pi."""
    text = """
        parameters: {a: '-0.002', b: 0.002}
        components:
          - {name: Jr, type: inertia, shaft: s, J: 1e-4, w0: 10}
          - name: CG
            type: cogging
            shaft: s
            harmonics: [{order: 3, amplitude: %s, phase: %s}]
        probes: {w: s.w}
        analysis: {stop: 0.5, rtol: 1e-10, atol: 1e-12}
    """
    neg = compile_text(text % ("a", "0")).simulate()
    pos = compile_text(text % ("b", "3.141592653589793")).simulate()
    np.testing.assert_allclose(neg["w"], pos["w"], rtol=1e-7, atol=1e-9)
    assert np.ptp(neg["w"]) > 0.1  # the cogging acts


def test_a_power_whose_derivative_is_singular_at_the_start_runs(compile_text):
    """v = max(u, 0)^1.5 with u = t: its Jacobian has 0^0.5/0 at t = 0, which Python floats
    raise on; the run must go through (not a traceback) and follow t^1.5."""
    model = compile_text("""
        parameters: {n: 1.5}
        components:
          - {name: U, type: V, p: u, n: gnd, V: {pwl: [[0, 0], [1, 1]]}}
          - {name: Ru, type: R, p: u, n: gnd, R: 1}
          - {name: B1, type: BV, p: a, n: gnd, expr: "max(u.v, 0)^n"}
          - {name: R1, type: R, p: a, n: gnd, R: 1}
        probes: {va: a.v}
        analysis: {stop: 1, rtol: 1e-9, atol: 1e-12}
    """)
    res = model.simulate()
    assert res.success
    np.testing.assert_allclose(res["va"], res.t**1.5, rtol=1e-7, atol=1e-9)
