"""Diagnosis speed on the issue's reference case (issue #5, "Speed").

    python benchmarks/bench_diagnose.py

A 0.4 s record of the Kim & Kim base motor at 50 kHz with two probes (supply current and
speed), made from the base netlist plus a hidden Coulomb friction torque of 2 mN m (about 5 %
of the load), with white noise (5 mA, 0.05 rad/s) and ADC steps (1 mA, 0.01 rad/s). The
base netlist declares nothing; the diagnosis must find the friction. Prints the time of each
stage (declared fit, screening, refits) and the total; the target is 20 s on 2 cores (issue
#13), printed beside the time of one simulation of the record.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


_T0 = [0.0]


def _stamp(message: str) -> None:
    """A stage's log line with the time since the diagnosis started [s]."""
    now = time.perf_counter()
    if not _T0[0]:
        _T0[0] = now
    print(f"  {now - _T0[0]:7.2f} s  {message}")


def main() -> int:
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="bench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs
    from circuitsim.loop import effects
    from circuitsim.loop.diagnose import diagnose
    from circuitsim.loop.record import Record
    from circuitsim.netlist import build

    net = cs.load(ROOT / "netlists" / "kim2024" / "base.yaml")
    cand = next(c for c in effects.candidates(net) if c.effect == "coulomb-friction")
    (name,) = cand.free
    truth = cs.compile(build(cand.apply(net.raw)))
    t = np.arange(20_001) / 50e3
    t0 = time.perf_counter()
    res = truth.simulate(stop=0.4, t_eval=t, params={name: 2e-3}, rtol=1e-9, atol=1e-11)
    rng = np.random.default_rng(0)
    cols = {"i_total": np.round((res["i_total"] + rng.normal(0, 5e-3, t.size)) / 1e-3) * 1e-3,
            "speed": np.round((res["speed"] + rng.normal(0, 0.05, t.size)) / 0.01) * 0.01}
    print(f"record: {t.size} samples x 2 probes, made in {time.perf_counter() - t0:.1f} s")
    declared = cs.compile(net)  # compiled once, as a user's second run is
    t0 = time.perf_counter()
    declared.simulate(stop=0.4, t_eval=t, rtol=1e-8)
    one_run = time.perf_counter() - t0
    t0 = time.perf_counter()
    d = diagnose(net, Record(t, cols, "bench"), probes=["i_total", "speed"],
                 progress=_stamp)
    total = time.perf_counter() - t0
    print(d.summary())
    for k, v in d.timings.items():
        print(f"  {k:<14} {v:7.1f} s")
    found = [a for a in d.effects if a.effect in ("coulomb-friction", "force-offset")]
    value = abs(next(iter(found[0].parameters.values()))) if found else float("nan")
    print(f"found {'yes' if found else 'NO'}: {value:.4g} N m (truth 0.002)")
    print(f"one simulation of the record: {one_run:.2f} s; the diagnosis costs "
          f"{total / one_run:.0f} of them")
    print(f"total {total:.1f} s -> {'MET' if total <= 20 else 'MISSED'} (target 20 s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
