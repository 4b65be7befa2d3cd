"""Lsat by nominal inductance at nominal current (Modelica's SaturatingInductor form)."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from scipy.optimize import brentq

from circuitsim_components.passive import knee_current


@pytest.mark.parametrize("lnom", [0.0105, 0.009, 0.005, 0.0021, 0.00100001])
def test_knee_current_solves_the_nominal_condition(lnom: float) -> None:
    lzer, linf, inom = 0.011, 0.001, 2.0
    ipar = float(knee_current(sp.Float(lzer), sp.Float(linf), sp.Float(lnom),
                              sp.Float(inom)).evalf())
    psi = linf * inom + (lzer - linf) * ipar * np.arctan(inom / ipar)
    assert psi / inom == pytest.approx(lnom, rel=1e-12)
    ref = brentq(lambda ip: linf * inom + (lzer - linf) * ip * np.arctan(inom / ip) -
                 lnom * inom, 1e-9, 1e9, xtol=1e-15, rtol=1e-14)
    assert ipar == pytest.approx(ref, rel=1e-8)


def test_nominal_form_equals_the_knee_form(compile_text) -> None:
    """The same coil written both ways (the knee from the nominal point, computed here with
    brentq) gives the same current ramp under a voltage step."""
    lzer, linf, lnom, inom = 0.011, 0.001, 0.005, 2.0
    ipar = brentq(lambda ip: linf * inom + (lzer - linf) * ip * np.arctan(inom / ip) -
                  lnom * inom, 1e-9, 1e9, xtol=1e-15, rtol=1e-14)
    body = """
        components:
          - {{name: V1, type: V, p: a, n: gnd, V: {{step: {{v1: 5 V, rise: 1 us}}}}}}
          - {{name: L1, {coil}, p: a, n: gnd, R: 1 ohm}}
        probes: {{i: L1.i}}
        analysis: {{stop: 50 ms, step: 0.05 ms, rtol: 1e-10, atol: 1e-12}}
    """
    a = compile_text(body.format(coil=f"type: Lsat_nom, Lzer: {lzer}, Linf: {linf}, "
                                      f"Lnom: {lnom}, Inom: {inom}")).simulate()
    b = compile_text(body.format(coil=f"type: Lsat, Lzer: {lzer}, Linf: {linf}, "
                                      f"Ipar: {ipar!r}")).simulate()
    assert np.max(np.abs(a["i"] - b["i"])) < 1e-8
    assert a["i"][-1] == pytest.approx(5.0, rel=1e-3)  # V/R once the coil has charged
