"""Cost and benefit of the sources' step bound (a sine bounds IDA's step to period/20).

    python benchmarks/bench_step_bound.py

For the diode charging a capacitor from a 1 Hz sine (netlists/breadth/diode_charge.yaml, the
ngspice reference 8.2633 V) and an RC low-pass fed by a 1 kHz sine for 1 s, each run is timed
with the default bound (period/20) against looser ones (period/4, period/2, none) in the
same process: the time ratio to the unbounded run and the error are printed. Best of 3,
warm cache. For the RC the "error" against 1 - 1/e is the true 1 kHz ripple at t = 1 s, the
same with or without the bound.

Measured (2 shared cores): diode T/20 0.034 s (2.8x the unbounded run), error -2e-5 V; T/4
-0.21 V (one earlier run at T/4 agreed to 1e-5: where the steps fall decides); T/2 and none
-4.18 V. RC: T/20 costs 1.18x, no change in the answer.
"""

from __future__ import annotations

import os
import sys
import tempfile
import textwrap
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "benchmarks"), str(ROOT / "tests")]
DIODE_REF = 8.2633  # [V] ngspice 39, tests/decks/diode_charge.cir

RC = textwrap.dedent("""
    components:
      - {name: V1, type: V, p: in, n: gnd, V: {sine: {offset: 1 V, amplitude: 1 V,
         freq: 1 kHz}}}
      - {name: R1, type: R, p: in, n: out, R: 1 kohm}
      - {name: C1, type: C, p: out, n: gnd, C: 1 mF}
    probes: {v: out.v}
    analysis: {stop: 1 s, step: 0.1 ms}
""")


def main() -> int:
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="bench-cache-"))
    warnings.simplefilter("ignore")
    from common import best_of

    import circuitsim as cs
    from circuitsim_components import waveforms

    diode = cs.compile(cs.load(ROOT / "netlists" / "breadth" / "diode_charge.yaml"))
    rc_path = Path(tempfile.mkdtemp(prefix="bench-")) / "rc.yaml"
    rc_path.write_text(RC)
    rc = cs.compile(cs.load(rc_path))
    rc_exact = 1.0 - 0.3678794411714423  # 1 - e^-1 (the 1 kHz ripple on it is ~1.6e-4)
    default = waveforms.STEPS_PER_PERIOD
    print(f"{'case':<8} {'bound':<12} {'time [s]':>9} {'ratio':>7} {'error':>10}")
    for name, model, probe, ref in (("diode", diode, "v_c", DIODE_REF),
                                    ("rc 1kHz", rc, "v", rc_exact)):
        rows = []
        for steps in (default, 4, 2, 0):
            waveforms.STEPS_PER_PERIOD = steps if steps else 1e-300  # 0: effectively none
            secs, res = best_of(3, model.simulate)
            rows.append((f"T/{steps}" if steps else "none", secs, res[probe][-1] - ref))
        waveforms.STEPS_PER_PERIOD = default
        base = rows[-1][1]
        for label, secs, err in rows:
            print(f"{name:<8} {label:<12} {secs:9.3f} {secs / base:7.2f} {err:10.2e}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
