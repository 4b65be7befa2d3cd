"""Cross-check: the noise-free null output of simulators.py against circuitsim's simulation
of the declared netlist (the one place of the benchmark that uses circuitsim to make numbers).

    PYTHONPATH=<circuitsim checkout> python benchmarks/diagnosis/validate.py

Prints, per motor and regime and probe, the NRMSE (RMS difference / std of the signal) and the
largest difference relative to the signal's range. The target is below 1e-4.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))

import simulators as sims

CASES = [  # motor, regime, netlist, sample rate [Hz], duration [s]
    ("A", "fast", ROOT / "netlists" / "kim2024" / "base.yaml", 50e3, 0.4),
    ("B", "fast", HERE / "netlists" / "motor_b_fast.yaml", 20e3, 0.4),
    ("B", "slow", HERE / "netlists" / "motor_b.yaml", 1e3, 5.0),
]


def main() -> int:
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    worst = 0.0
    for motor, regime, path, fs, dur in CASES:
        t = np.arange(round(dur * fs) + 1) / fs
        t0 = time.perf_counter()
        ref = sims.simulate(motor, regime, t)
        t_ref = time.perf_counter() - t0
        net = cs.load(path)
        model = cs.compile(net)
        t0 = time.perf_counter()
        res = model.simulate(stop=float(t[-1]), t_eval=t, rtol=1e-10, atol=1e-12)
        t_cs = time.perf_counter() - t0
        for p in sims.PROBES[motor]:
            a, b = np.asarray(ref[p]), np.asarray(res[p])
            nrmse = float(np.sqrt(np.mean((a - b) ** 2)) / np.std(b))
            mx = float(np.max(np.abs(a - b)) / np.ptp(b))
            worst = max(worst, nrmse)
            print(f"motor {motor} {regime:4s} {p:8s}: NRMSE {nrmse:.2e}, max |diff|/range "
                  f"{mx:.2e}  (scipy {t_ref:.1f} s, circuitsim {t_cs:.1f} s)")
    print(f"worst NRMSE {worst:.2e} -> {'OK' if worst < 1e-4 else 'ABOVE 1e-4'}")
    return 0 if worst < 1e-4 else 1


if __name__ == "__main__":
    sys.exit(main())
