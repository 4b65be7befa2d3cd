"""Mechanics between bodies: springs, dampers, gears, speed and position sources, against
closed forms (issue 15 item 4)."""

from __future__ import annotations

import numpy as np
import pytest

import circuitsim as cs

from conftest import NETLISTS


def test_two_inertia_drive_train_torsional_resonance_closed_form() -> None:
    """netlists/breadth/drivetrain.yaml: the twist after a torque step on the rotor is the
    step response of Jr tw'' + d tw' + c tw = T Jr / J1 (Jr = J1 J2 / (J1 + J2))."""
    net = cs.load(NETLISTS / "breadth" / "drivetrain.yaml")
    res = cs.compile(net).simulate()
    J1, J2, c, d, T = 0.01, 0.04, 100.0, 0.04, 1.0
    jr = J1 * J2 / (J1 + J2)
    w0 = np.sqrt(c / jr)
    zeta = d / (2 * np.sqrt(c * jr))
    wd = w0 * np.sqrt(1 - zeta**2)
    final = T * jr / (J1 * c)
    t = res.t
    exact = final * (1 - np.exp(-zeta * w0 * t) * (np.cos(wd * t) + zeta * w0 / wd *
                                                    np.sin(wd * t)))
    assert w0 / (2 * np.pi) == pytest.approx(17.794, abs=1e-3)
    # the twist is the difference of two angles of up to 10 rad, each integrated to rtol 1e-9
    assert np.max(np.abs(res["twist"] - exact)) < 1e-7
    # the pair as a whole accelerates at T / (J1 + J2)
    mean = (J1 * res["w_rotor"] + J2 * res["w_load"]) / (J1 + J2)
    assert np.max(np.abs(mean - T * t / (J1 + J2))) < 1e-6


def test_free_torsional_oscillation_conserves_energy(compile_text) -> None:
    model = compile_text("""
        components:
          - {name: M1, type: inertia, shaft: s1, J: 0.01, w0: 10 rad/s}
          - {name: K1, type: spring, a: s1, b: s2, c: 100}
          - {name: M2, type: inertia, shaft: s2, J: 0.04}
        probes: {twist: K1.phi_rel, e: M1.energy + M2.energy + K1.energy}
        analysis: {stop: 0.5, step: 0.1 ms, rtol: 1e-10, atol: 1e-13}
    """)
    res = model.simulate()
    w0 = np.sqrt(100 * 0.05 / 0.0004)
    assert np.max(np.abs(res["twist"] - 10 / w0 * np.sin(w0 * res.t))) < 1e-7
    assert np.max(np.abs(res["e"] - 0.5)) < 1e-7


def test_geared_load_with_efficiency_closed_form() -> None:
    """netlists/breadth/geared_load.yaml: w_load = eta N T / b (1 - exp(-t b / (Jl + eta N^2
    Jm))), the gear loses (1 - eta) of the power the motor side puts in."""
    res = cs.compile(cs.load(NETLISTS / "breadth" / "geared_load.yaml")).simulate()
    N, eta, jm, jl, b, T = 10.0, 0.9, 1e-3, 0.31, 2.0, 1.0
    tau = (jl + eta * N**2 * jm) / b
    exact = eta * N * T / b * (1 - np.exp(-res.t / tau))
    assert np.max(np.abs(res["w_load"] - exact)) < 1e-6
    assert np.allclose(res["w_motor"], N * res["w_load"], atol=1e-9)
    p_in = T * res["w_motor"] - 0.5 * jm * np.gradient(res["w_motor"] ** 2, res.t)
    assert np.allclose(res["gear_loss"][5:], (1 - eta) * p_in[5:], rtol=1e-3, atol=1e-6)


def test_lossless_gear_reflects_inertia(compile_text) -> None:
    model = compile_text("""
        components:
          - {name: T1, type: torque, shaft: m, T: 1}
          - {name: M1, type: inertia, shaft: m, J: 0.001}
          - {name: G1, type: gear, a: m, b: l, ratio: 10}
          - {name: M2, type: inertia, shaft: l, J: 0.5}
          - {name: B2, type: damper, shaft: l, b: 2}
        probes: {wm: m.w}
        analysis: {stop: 1, step: 1 ms, rtol: 1e-10, atol: 1e-12}
    """)
    res = model.simulate()
    exact = 50 * (1 - np.exp(-res.t * 0.02 / 0.006))  # T/b_eff, J_eff = J1 + J2/N^2
    assert np.max(np.abs(res["wm"] - exact)) < 1e-6


def test_speed_and_angle_sources(compile_text) -> None:
    """An angle source sin(2 pi t) drives an inertia through a spring; a speed source turns
    its shaft at 3 rad/s: the shafts follow exactly, and the spring-inertia obeys
    J phi_l'' = c (sin(2 pi t) - phi_l) (solved in closed form)."""
    model = compile_text("""
        components:
          - {name: P1, type: angle, shaft: m, Phi: {sine: {amplitude: 1 rad, freq: 1 Hz}}}
          - {name: K1, type: spring, a: m, b: l, c: 10}
          - {name: M2, type: inertia, shaft: l, J: 0.1}
          - {name: S1, type: speed, shaft: q, W: 3}
          - {name: M3, type: inertia, shaft: q, J: 0.1}
        probes: {phim: m.phi, wm: m.w, phil: l.phi, q: q.phi}
        analysis: {stop: 2, step: 1 ms, rtol: 1e-10, atol: 1e-12}
    """)
    res = model.simulate()
    t = res.t
    assert np.allclose(res["phim"], np.sin(2 * np.pi * t), atol=1e-8)
    assert np.allclose(res["wm"], 2 * np.pi * np.cos(2 * np.pi * t), atol=1e-6)
    assert np.allclose(res["q"], 3 * t, atol=1e-8)
    wn, w = np.sqrt(10 / 0.1), 2 * np.pi  # phi'' + wn^2 phi = wn^2 sin(w t), from rest
    exact = wn**2 / (wn**2 - w**2) * (np.sin(w * t) - w / wn * np.sin(wn * t))
    assert np.max(np.abs(res["phil"] - exact)) < 1e-6


def test_two_masses_on_a_spring_damper_and_a_velocity_source(compile_text) -> None:
    """A velocity source pulls mass m through a spring-damper: the relative motion is a
    damped oscillator driven by the constant speed; it settles where the spring carries
    the ground damper's force: x_rel = d V / c."""
    model = compile_text("""
        components:
          - {name: V1, type: tspeed, flange: a, V: 0.5}
          - {name: K1, type: tspring_damper, a: a, b: b, c: 400, d: 4}
          - {name: M1, type: mass, flange: b, m: 1}
          - {name: M0, type: mass, flange: a, m: 1}
          - {name: D1, type: tdamper, flange: b, d: 4}
        probes: {xr: K1.x_rel, vb: b.v}
        analysis: {stop: 3, step: 1 ms, rtol: 1e-10, atol: 1e-13}
    """)
    res = model.simulate()
    # m xb'' = c xr + d xr' - d vb with xr = xa - xb, xa = V t: m xr'' + 2 d xr' + c xr = d V
    # (the ground damper on b adds to the coupling's), from xr(0) = 0, xr'(0) = V
    m, c, d, V = 1.0, 400.0, 4.0, 0.5
    w0, zeta = np.sqrt(c / m), 2 * d / (2 * np.sqrt(c * m))
    wd, sigma = w0 * np.sqrt(1 - zeta**2), zeta * w0
    fin = d * V / c
    t = res.t
    a = -fin
    b = (V + sigma * a) / wd
    exact = fin + np.exp(-sigma * t) * (a * np.cos(wd * t) + b * np.sin(wd * t))
    assert np.max(np.abs(res["xr"] - exact)) < 1e-7


def test_translational_position_source(compile_text) -> None:
    """A position source x = 0.01 sin(2 pi 5 t) shakes a mass on a spring: the mass obeys
    m x'' = c (xs - x), solved in closed form from rest."""
    model = compile_text("""
        components:
          - {name: P1, type: tposition, flange: s, X: {sine: {amplitude: 10 mm, freq: 5 Hz}}}
          - {name: K1, type: tspring, a: s, b: m, c: 1000}
          - {name: M1, type: mass, flange: m, m: 1}
        probes: {xs: s.x, xm: m.x}
        analysis: {stop: 1, step: 1 ms, rtol: 1e-10, atol: 1e-13}
    """)
    res = model.simulate()
    t = res.t
    wn, w = np.sqrt(1000.0), 2 * np.pi * 5
    assert np.allclose(res["xs"], 0.01 * np.sin(w * t), atol=1e-10)
    exact = 0.01 * wn**2 / (wn**2 - w**2) * (np.sin(w * t) - w / wn * np.sin(wn * t))
    assert np.max(np.abs(res["xm"] - exact)) < 1e-8


def test_clutch_slips_then_locks_closed_form(compile_text) -> None:
    """A clutch of capacity 0.5 N m couples a shaft held at 10 rad/s to an inertia at rest:
    it slips with J w' = 0.5 until w = 10 (t = 0.2 s), then carries the shaft along (the
    regularised friction creeps by w_rel ~ w_slip * tau/capacity, 0 here: no load)."""
    model = compile_text("""
        components:
          - {name: S1, type: speed, shaft: drive, W: 10}
          - {name: M0, type: inertia, shaft: drive, J: 1}
          - {name: K1, type: clutch, a: drive, b: out, fn: 0.5, w_slip: 1e-4}
          - {name: M1, type: inertia, shaft: out, J: 0.01}
        probes: {w: out.w}
        analysis: {stop: 0.5, step: 1 ms, rtol: 1e-9, atol: 1e-12}
    """)
    res = model.simulate()
    exact = np.minimum(50 * res.t, 10.0)
    # exact while slipping; at the lock the regularised friction approaches with time constant
    # J w_slip / capacity = 2 us, leaving a deviation of order w_slip there (4.8e-5 measured)
    assert np.max(np.abs(res["w"] - exact)[res.t < 0.19]) < 1e-9
    assert np.max(np.abs(res["w"] - exact)) < 5 * 1e-4
    assert res["w"][-1] == pytest.approx(10.0, abs=1e-6)


def test_backlash_free_flight_then_elastic_contact(compile_text) -> None:
    """Two equal inertias, one moving at 1 rad/s, with 0.2 rad of play (0.1 rad each way):
    free flight to contact at t = 0.1 s, then half a period of the contact spring
    (omega = sqrt(2 c / J)), after which the speeds have exchanged (an elastic impact)."""
    model = compile_text("""
        components:
          - {name: M1, type: inertia, shaft: a, J: 1, w0: 1 rad/s}
          - {name: B1, type: backlash, a: a, b: b, gap: 0.2, c: 400}
          - {name: M2, type: inertia, shaft: b, J: 1}
        probes: {wa: a.w, wb: b.w, rel: B1.phi_rel}
        analysis: {stop: 0.3, step: 0.1 ms, rtol: 1e-10, atol: 1e-12}
    """)
    res = model.simulate()
    t = res.t
    w = np.sqrt(2 * 400 / 1)
    t_out = 0.1 + np.pi / w
    before = t < 0.1
    assert np.allclose(res["rel"][before], t[before], atol=1e-8)
    contact = (t > 0.1) & (t < t_out)
    assert np.allclose(res["rel"][contact], 0.1 + np.sin(w * (t[contact] - 0.1)) / w,
                       atol=1e-6)
    after = t > t_out + 1e-3
    assert np.allclose(res["wa"][after], 0.0, atol=1e-5)
    assert np.allclose(res["wb"][after], 1.0, atol=1e-5)


def test_a_gear_of_ratio_zero_is_refused_and_a_negative_one_reverses() -> None:
    """Ratio 0 locked the motor (a.w = 0 b.w): every speed 0 under a 1 N m torque, exit 0."""
    path = NETLISTS / "breadth" / "geared_load.yaml"
    model = cs.compile(cs.load(path))
    with pytest.raises(cs.ParameterError, match=r"Gear: Gear.ratio = 0 \[1\]: must not be zero"):
        model.simulate(params={"N": 0.0})
    ahead, back = (model.simulate(params={"N": n}, stop=0.2) for n in (10.0, -10.0))
    assert np.allclose(back["w_load"], -ahead["w_load"], rtol=1e-6, atol=1e-9)
    assert np.allclose(back["w_motor"], ahead["w_motor"], rtol=1e-6, atol=1e-9)
