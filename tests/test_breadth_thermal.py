"""The thermal domain and self-heating resistances, against closed forms (issue 15 item 5)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

import circuitsim as cs

from conftest import NETLISTS


def test_heat_capacity_and_conductance_first_order_closed_form(compile_text) -> None:
    """A heat source P into C, conducting G to a fixed ambient: T = Ta + P/G (1 - e^{-tG/C});
    the heat flows balance (P = C T' + G (T - Ta))."""
    model = compile_text("""
        components:
          - {name: P1, type: heat_flow, port: n, P: 10 W}
          - {name: C1, type: heat_capacitor, port: n, C: 50 J/K, T0: 300 K}
          - {name: G1, type: thermal_conductor, a: n, b: amb, G: 0.5 W/K}
          - {name: A1, type: fixed_temperature, port: amb, T: 300 K}
        probes: {T: n.T, q: G1.Q, pc: C1.power}
        analysis: {stop: 500 s, step: 0.5 s, rtol: 1e-10, atol: 1e-12}
    """)
    res = model.simulate()
    exact = 300 + 20 * (1 - np.exp(-res.t * 0.5 / 50))
    assert np.max(np.abs(res["T"] - exact)) < 1e-6
    assert np.allclose(res["pc"] + res["q"], 10.0, atol=1e-7)


def test_self_heating_resistor_steady_state_closed_form(compile_text) -> None:
    """10 V across a copper resistor (10 ohm at Ta) cooled by G = 0.1 W/K: at steady state
    alpha dT^2 + dT = V^2 / (G R0), a quadratic."""
    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 10 V}
          - {name: R1, type: RT, p: a, n: gnd, h: hot, R_ref: 10 ohm}
          - {name: C1, type: heat_capacitor, port: hot, C: 5 J/K, T0: 293.15 K}
          - {name: G1, type: thermal_conductor, a: hot, b: amb, G: 0.1 W/K}
          - {name: A1, type: fixed_temperature, port: amb, T: 293.15 K}
        probes: {T: hot.T, pe: R1.power_electrical, pt: R1.power_thermal, p: R1.power}
        analysis: {stop: 1000 s, step: 1 s, rtol: 1e-10, atol: 1e-12}
    """)
    res = model.simulate()
    alpha, k = 3.93e-3, 100 / (0.1 * 10)
    dT = (-1 + np.sqrt(1 + 4 * alpha * k)) / (2 * alpha)
    assert res["T"][-1] == pytest.approx(293.15 + dT, abs=1e-6)
    # the resistor converts: what it takes electrically it gives as heat
    assert np.allclose(res["pe"], -res["pt"], rtol=1e-9, atol=1e-9)
    assert np.max(np.abs(res["p"])) < 1e-8


def test_thermally_coupled_motor_reaches_the_fixed_point() -> None:
    """netlists/breadth/thermal_motor.yaml: the steady state solves i = V/(R(T) + k^2/b),
    R(T) i^2 = Gth (T - Ta) (root-found here with brentq, independently of the DAE)."""
    res = cs.compile(cs.load(NETLISTS / "breadth" / "thermal_motor.yaml")).simulate()
    V, R20, k, b, G, Ta, a = 12.0, 2.0, 0.05, 1.167e-3, 0.5, 293.15, 3.93e-3

    def excess(T: float) -> float:
        R = R20 * (1 + a * (T - Ta))
        return R * (V / (R + k * k / b)) ** 2 - G * (T - Ta)

    T = brentq(excess, Ta, Ta + 500, xtol=1e-12)
    i = V / (R20 * (1 + a * (T - Ta)) + k * k / b)
    assert res["T_winding"][-1] == pytest.approx(T, abs=1e-3)
    assert res["i"][-1] == pytest.approx(i, rel=1e-6)
    assert res["w"][-1] == pytest.approx(k * i / b, rel=1e-6)


@pytest.mark.parametrize("ambient", ["20 degC", "68 degF", "20°C", "293.15 K"])
def test_an_ambient_in_celsius_or_fahrenheit_is_the_same_kelvin(write_netlist, ambient) -> None:
    """'20 degC' became 20 x 274.15 = 5483 K (pint's factor of an offset unit): the winding
    'settled' at 5517 K, exit 0. Alone, it is 293.15 K; anywhere else it is refused."""
    text = (NETLISTS / "breadth" / "thermal_motor.yaml").read_text(encoding="utf-8")
    net = cs.load(write_netlist(text.replace("T_amb: 293.15 K", f"T_amb: {ambient}")))
    assert net.parameters["T_amb"].value == pytest.approx(293.15, abs=1e-9)
    for bad in ("2 * 20 degC", "T_c + 5[degC]"):
        with pytest.raises(cs.CircuitsimError, match=r"'degC' is an offset unit \(0 degC = "
                                                    r"273.15 K\).*'20 degC' is 293.15 K"):
            cs.load(write_netlist(text.replace("T_amb: 293.15 K",
                                               f"T_amb: {bad}\n  T_c: 290 K")))


def test_a_temperature_where_a_voltage_belongs_is_refused(write_netlist) -> None:
    # rewritten as '293.15 K' it was read as a SPICE kilo: a 293 kV supply
    text = (NETLISTS / "breadth" / "thermal_motor.yaml").read_text(encoding="utf-8")
    with pytest.raises(cs.ParameterError, match=r"Vs: .*has dimension K"):
        cs.load(write_netlist(text.replace("V: V}", "V: 20 degC}")))
