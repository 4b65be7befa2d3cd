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


def test_the_knee_runs_on_every_route_to_the_bit(compile_text, monkeypatch, tmp_path) -> None:
    """The nominal form's knee (a Newton iteration in the generated code) is compiled by
    numba and by the C compiler alike -- numba cannot type the Python route's inline walrus
    chain, so the kernels call kernel_lib.knee_u -- and every route gives the same run."""
    pytest.importorskip("numba", reason="the compiled routes need numba (the test extra)")
    import warnings

    from circuitsim.errors import CircuitWarning
    from circuitsim.solve import ccode, direct

    body = """
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {step: {v1: 5 V, rise: 1 us}}}
          - {name: L1, type: Lsat_nom, Lzer: 0.011, Linf: 0.001, Lnom: 0.005, Inom: 2.0,
             p: a, n: gnd, R: 1 ohm}
        probes: {i: L1.i}
        analysis: {stop: 20 ms, step: 0.05 ms}
    """
    routes = [("python", "off"), ("numba", "off")]
    if ccode.compiler() is not None:  # without a compiler the C route is numba's
        routes.append(("numba", "on"))
    runs = []
    for kernels, cc in routes:
        monkeypatch.setenv("CIRCUITSIM_CACHE", str(tmp_path / f"{kernels}-{cc}"))
        monkeypatch.setenv("CIRCUITSIM_KERNELS", kernels)
        if cc == "off":
            monkeypatch.setenv("CIRCUITSIM_CC", "off")
        else:
            monkeypatch.delenv("CIRCUITSIM_CC", raising=False)
        monkeypatch.setattr(direct, "_LOADED", {})
        monkeypatch.setattr(direct, "_WARNED", set())
        model = compile_text(body)
        with warnings.catch_warnings():
            warnings.simplefilter("error", CircuitWarning)
            runs.append(model.simulate())
        if kernels == "numba":
            loaded = direct._LOADED[model.key]
            assert loaded is not None, "the kernels must compile"
            assert (direct.c_library(loaded) is None) == (cc == "off")
    for run in runs[1:]:
        assert (run.nfev, run.njev) == (runs[0].nfev, runs[0].njev)
        assert np.array_equal(run.y, runs[0].y) and np.array_equal(run.t, runs[0].t)
