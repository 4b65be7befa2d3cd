"""Closed-form circuits and energy conservation (issue #2, acceptance 2).

Accuracy is measured as max |sim - exact| / max |exact| over the whole run: 1e-5.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import cumulative_simpson

import circuitsim as cs

from conftest import NETLISTS
from reference import dc_motor_steady_speed, dc_motor_step, rc_step, rl_step, rlc_series_step


def rel_err(sim: np.ndarray, exact: np.ndarray) -> float:
    return float(np.max(np.abs(sim - exact)) / np.max(np.abs(exact)))


def test_rc_step():
    model = cs.compile(cs.load(NETLISTS / "examples" / "rc.yaml"))
    res = model.simulate()
    assert res.success, res.message
    exact = rc_step(res.t, 1e3, 1e-6, 1.0)
    assert rel_err(res["v_out"], exact) < 1e-5
    # 63.2 % at t = RC, as the netlist header says
    assert np.interp(1e-3, res.t, res["v_out"]) == pytest.approx(1 - np.exp(-1), rel=1e-5)


def test_rl_step(compile_text):
    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {step: {v1: 5 V, rise: 1 ns}}}
          - {name: R1, type: R, p: a, n: b, R: 2 ohm}
          - {name: L1, type: L, p: b, n: gnd, L: 4 mH}
        probes: {i: L1.i, v_l: b.v}
        analysis: {stop: 10 ms, step: 5 us, rtol: 1e-9, atol: 1e-12}
    """)
    res = model.simulate()
    exact = rl_step(res.t, 2.0, 4e-3, 5.0)
    assert rel_err(res["i"], exact) < 1e-5
    # the inductor voltage is an eliminated variable, still available by name
    assert rel_err(res["v_l"][res.t > 1e-6], 5.0 * np.exp(-res.t[res.t > 1e-6] / 2e-3)) < 1e-5


def test_underdamped_rlc():
    model = cs.compile(cs.load(NETLISTS / "examples" / "rlc.yaml"))
    res = model.simulate()
    v, i = rlc_series_step(res.t, 10.0, 10e-3, 1e-6, 1.0)
    assert rel_err(res["v_c"], v) < 1e-5
    assert rel_err(res["i"], i) < 1e-5
    zeta = 10 / 2 * np.sqrt(1e-6 / 10e-3)
    assert res["v_c"].max() == pytest.approx(1 + np.exp(-zeta * np.pi / np.sqrt(1 - zeta**2)),
                                             rel=1e-5)


def test_dc_motor_speed_step():
    model = cs.compile(cs.load(NETLISTS / "examples" / "dc_motor.yaml"))
    res = model.simulate()
    w, i = dc_motor_step(res.t, 12.0, 1.0, 1e-3, 0.05, 1e-5, 1e-5)
    assert rel_err(res["speed"], w) < 1e-5
    assert rel_err(res["i"], i) < 1e-5
    assert res["speed"][-1] == pytest.approx(dc_motor_steady_speed(12.0, 1.0, 0.05, 1e-5),
                                             rel=1e-6)


def _integral(res, name):
    return cumulative_simpson(res[name], x=res.t, initial=0.0)


def test_energy_balance_rlc():
    """Source energy = resistor heat + magnetic + electric energy, at every output time."""
    model = cs.compile(cs.load(NETLISTS / "examples" / "rlc.yaml"))
    res = model.simulate(rtol=1e-11, atol=1e-14)
    source = _integral(res, "p_source")
    heat = _integral(res, "p_r")
    stored = 0.5 * 10e-3 * res["i"] ** 2 + 0.5 * 1e-6 * res["v_c"] ** 2
    scale = source[-1]
    assert np.max(np.abs(source - heat - stored)) / scale < 1e-6


def test_energy_balance_dc_motor():
    """k_e = k_t: source = winding heat + viscous heat + 1/2 L i^2 + 1/2 J w^2; the EMF
    converts without loss (its net power is zero)."""
    model = cs.compile(cs.load(NETLISTS / "examples" / "dc_motor.yaml"))
    res = model.simulate(rtol=1e-11, atol=1e-14)
    source = _integral(res, "p_source")
    heat = _integral(res, "Rw.power") + _integral(res, "Bv.power")
    stored = 0.5 * 1e-3 * res["i"] ** 2 + 0.5 * 1e-5 * res["speed"] ** 2
    assert np.max(np.abs(source - heat - stored)) / source[-1] < 1e-6
    assert np.max(np.abs(res["M.power"])) < 1e-9 * np.max(np.abs(res["p_source"]))
