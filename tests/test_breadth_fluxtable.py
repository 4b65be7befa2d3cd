"""Lsat_table: a tabulated flux curve whose corners are met by events (issue 15 item 8),
against the closed form of an RL circuit walking the curve's segments up and down."""

from __future__ import annotations

import numpy as np
import pytest

import circuitsim as cs

ROWS = [(1.0, 0.010), (2.0, 0.015), (4.0, 0.018)]  # (i [A], psi [Wb])
R = 1.0  # [ohm]


def _segment_walk(t: np.ndarray, t0: float, i0: float, volts: float) -> np.ndarray:
    """Exact current [A] of L(i) di/dt = volts - R i from i(t0) = i0, L the slope of the
    piecewise-linear flux curve on the segment holding |i| (here |i| stays >= 0): on each
    segment an exponential towards volts/R, crossing the next row at a closed-form time."""
    edges = [0.0] + [r[0] for r in ROWS]
    psis = [0.0] + [r[1] for r in ROWS]
    slopes = [(psis[k + 1] - psis[k]) / (edges[k + 1] - edges[k]) for k in range(len(ROWS))]
    target, out = volts / R, np.full(t.shape, np.nan)
    a, i = t0, i0
    while True:
        k = min(int(np.searchsorted(edges, i, side="right" if target > i else "left")) - 1,
                len(slopes) - 1)
        tau = slopes[k] / R
        nxt = edges[k + 1] if target > i else edges[k]
        cross = (a + tau * np.log((target - i) / (target - nxt))
                 if (target > i and k + 1 < len(edges) - 1) or (target < i and nxt > 0)
                 else np.inf)
        part = (t >= a) & (t < cross)
        out[part] = target + (i - target) * np.exp(-(t[part] - a) / tau)
        if not np.isfinite(cross):
            return out
        a, i = cross, nxt


def test_tabulated_flux_curve_up_and_down(compile_text) -> None:
    """10 V through 1 ohm for 5 ms, then 0 V: the current climbs through the segments of
    10, 5 and 1.5 mH (and the last slope beyond 4 A), then decays back down through them;
    every corner is an event, so the current is exact to the integrator's tolerance."""
    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {pwl: [[0, 10], [5 ms, 10], [5.000001 ms, 0]]}}
          - {name: R1, type: R, p: a, n: b, R: 1}
          - name: L1
            type: Lsat_table
            p: b
            n: gnd
            points:
              - {i: 1, psi: 10 mWb}
              - {i: 2, psi: 15 mWb}
              - {i: 4, psi: 18 mWb}
        probes: {i: L1.i, ld: L1.L_d}
        analysis: {stop: 40 ms, step: 10 us, rtol: 1e-10, atol: 1e-12}
    """)
    res = model.simulate()
    assert res.success, res.message
    t = res.t
    # the source falls over 1 ns: its volt-seconds are those of a step at the ramp's middle
    t_off = 5e-3 + 0.5e-9
    rise = _segment_walk(np.append(t, t_off), 0.0, 0.0, 10.0)
    exact = np.where(t <= 5e-3, rise[:-1], _segment_walk(t, t_off, rise[-1], 0.0))
    assert np.max(np.abs(res["i"] - exact)) < 1e-7  # measured 9.5e-9 A
    assert sorted(set(np.round(res["ld"], 12))) == [0.0015, 0.005, 0.01]


def test_initial_current_beyond_the_first_row(compile_text) -> None:
    """Starting at i0 = 3 A (third segment, 1.5 mH) the events at t = 0 find the segment;
    the current then decays through 1 ohm down the curve: exponentials of 1.5, 5 and 10 ms
    joined where it crosses 2 A and 1 A (closed form; measured 2.5e-9 A)."""
    model = compile_text("""
        parameters: {I1: 1 A}
        components:
          - {name: R1, type: R, p: b, n: gnd, R: 1}
          - name: L1
            type: Lsat_table
            p: b
            n: gnd
            i0: 3
            points:
              - {i: I1, psi: 10 mWb}
              - {i: 2, psi: 15 mWb}
              - {i: 4, psi: 18 mWb}
        probes: {i: L1.i}
        analysis: {stop: 20 ms, step: 10 us, rtol: 1e-10, atol: 1e-12}
    """)
    res = model.simulate()
    assert res.success, res.message
    assert np.max(np.abs(res["i"] - _segment_walk(res.t, 0.0, 3.0, 0.0))) < 1e-7


def test_an_empty_table_is_refused_at_its_line(write_netlist) -> None:
    """A flux table needs a row: the loader says so with the file, line and component."""
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1}
          - {name: L1, type: Lsat_table, p: a, n: gnd, points: []}
    """)
    with pytest.raises(cs.NetlistError, match=r"net\.yaml:3: L1: 'points' needs at least 1"):
        cs.load(path, allow_outside=True)
