"""Cost and accuracy of switching by events against the smooth pwm_leg.

    python benchmarks/bench_events.py

One inverter leg at 10 kHz (m = 0.3, triangle carrier, no dead time) into 5 ohm + 1 mH from
10 V, 20 ms from rest (200 carrier periods, 40 time constants): the ideal ``half_bridge``
(every switching an event) against ``pwm_leg`` with edges eps = 0.01 and 0.001 (its Ron
folded into the load). Each run is timed (best of 2, warm cache) and its load current over
the last two periods compared with the exact periodic steady state of the piecewise-linear
circuit (tests/test_breadth_inverter.py). Also the number of switchings (roots) and the time
per switching of the ideal leg.

With numba installed each model is also run on the compiled route (``CIRCUITSIM_KERNELS=numba``:
the kernels and, for the ideal leg, the compiled root function), and the numbers compared.
Measured 2026-11-26: ideal leg 1.08 s on the Python route, 0.35 s compiled (0.32x: the 400
restarts, each solving consistent values in Python, are most of what is left); pwm_leg 0.43 s
and 0.02 s; every pair the same numbers to the bit.

Measured (2 shared cores, 1 us output step): ideal 1.68 s, 400 roots and 400 carrier
corners (each an IDA restart, about 2 ms with its consistent values), error 1.6e-8 A;
pwm_leg eps 0.01 0.73 s, error 2.3e-5 A; eps 0.001 0.70 s, error 2.5e-8 A. The smooth leg's
error at the samples is far below its first-order bound Vdc ln2 eps / (8 f L) (8.7e-4 A at
eps 0.01): its edge is symmetric and lasts eps/(4 f) = 25 ns at eps 0.001, between samples.
So for a leg without dead time a narrow smooth edge is as accurate at the samples and 2.4x
faster; the events are for what it cannot do: dead time through the diodes, exact instants,
switches and diodes that switch on circuit quantities. At a 0.2 us output step both cost
about 1 s more (IDA's interpolation per output point dominates).
"""

from __future__ import annotations

import os
import sys
import tempfile
import textwrap
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "tests")]

LEG_IDEAL = ("{name: S1, type: half_bridge, p: o, n: gnd, dc: dc, m: 0.3, Ron: 0.01, "
             "carrier: {triangle: {freq: 10 kHz}}}")
LEG_SMOOTH = "{{name: S1, type: pwm_leg, p: o, n: gnd, dc: dc, m: 0.3, f_sw: 10 kHz, eps: {eps}}}"


def _model(leg: str, r_load: float):
    import circuitsim as cs

    text = textwrap.dedent(f"""
        components:
          - {{name: Vdc, type: V, p: dc, n: gnd, V: 10}}
          - {leg}
          - {{name: L1, type: L, p: o, n: gnd, L: 1 mH, R: {r_load}}}
        probes: {{i: L1.i}}
        analysis: {{stop: 20 ms, step: 1 us, rtol: 1e-9, atol: 1e-12}}
    """)
    path = Path(tempfile.mkdtemp()) / "leg.yaml"
    path.write_text(text)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cs.compile(cs.load(path, allow_outside=True))


def _run(model, route: str = "python") -> tuple[float, object]:
    """Best of 2 on a route: ``python`` (scikit-sundae calling the Python residual and
    guards) or ``numba`` (IDA calling the compiled kernels and root function; its first run,
    which loads or compiles them, is not timed)."""
    os.environ["CIRCUITSIM_KERNELS"] = route
    best, res = np.inf, model.simulate() if route == "numba" else None
    for _ in range(2):
        t0 = time.perf_counter()
        res = model.simulate()
        best = min(best, time.perf_counter() - t0)
    return best, res


def main() -> None:
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp())
    from test_breadth_inverter import RON, _pieces, _pss

    from circuitsim.solve import events

    roots = [0]
    note = events.Switching.note

    def counting(self, t, fired):
        roots[0] += 1
        return note(self, t, fired)

    events.Switching.note = counting
    T = 1e-4
    exact = _pss(_pieces([(0.325 * T, 0), (0.675 * T, 1)], 1, 0.0, T))
    rows = [("half_bridge (events)", _model(LEG_IDEAL, 5.0))]
    rows += [(f"pwm_leg eps {eps}", _model(LEG_SMOOTH.format(eps=eps), 5.0 + RON))
             for eps in (0.01, 0.001)]
    for name, model in rows:
        roots[0] = 0
        seconds, res = _run(model)
        last = res.t >= 0.02 - 2 * T
        err = np.max(np.abs(res["i"][last] - exact(np.mod(res.t[last], T))))
        per = f", {roots[0] // 2} roots ({1e3 * seconds / max(roots[0] // 2, 1):.2f} ms each)" \
            if roots[0] else ""
        print(f"{name:24s} {seconds:6.2f} s, error {err:.2g} A{per}")
        if _has_numba():
            fast, res2 = _run(model, "numba")
            same = all(np.array_equal(a, b) for a, b in ((res.t, res2.t), (res.y, res2.y)))
            print(f"{'  compiled route':24s} {fast:6.2f} s ({fast / seconds:.2f}x), "
                  f"{'the same numbers to the bit' if same else 'NUMBERS DIFFER'}")


def _has_numba() -> bool:
    import importlib.util

    return importlib.util.find_spec("numba") is not None


if __name__ == "__main__":
    main()
