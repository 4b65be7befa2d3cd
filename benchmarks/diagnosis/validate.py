"""Cross-check: the noise-free null output of simulators.py against circuitsim's simulation
of the declared netlist (the one place of the benchmark that uses circuitsim to make numbers).

    PYTHONPATH=<circuitsim checkout> python benchmarks/diagnosis/validate.py

Motor C is also compared with a play in its coupling: circuitsim's ``backlash`` component in
place of the spring_damper K against simulators.py's backlash (gap 20 mrad). Prints, per motor
and regime and probe, the NRMSE (RMS difference / std of the signal) and the
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
    ("C", "reversing", HERE / "netlists" / "motor_c.yaml", 10e3, 0.6),
]
# motor C with a play in its coupling: circuitsim's `backlash` component in place of the
# spring_damper K, against simulators.py's own backlash (the law the records carry)
BACKLASH_GAP = 0.02  # [rad]


def _backlash_netlist(tmp: Path) -> Path:
    """motor_c.yaml with K replaced by a backlash of total play BACKLASH_GAP [rad]."""
    text = (HERE / "netlists" / "motor_c.yaml").read_text()
    old = "{name: K, type: spring_damper, a: rotor, b: load, c: cK, d: dK}"
    assert old in text
    new = f"{{name: K, type: backlash, a: rotor, b: load, gap: {BACKLASH_GAP}, c: cK, d: dK}}"
    path = tmp / "motor_c_backlash.yaml"
    path.write_text(text.replace(old, new))
    return path


def _compare(cs, motor, regime, path, t, fx=None) -> float:
    """Prints the agreement per probe; returns the worst NRMSE."""
    t0 = time.perf_counter()
    ref = sims.simulate(motor, regime, t, fx)
    t_ref = time.perf_counter() - t0
    model = cs.compile(cs.load(path))
    t0 = time.perf_counter()
    res = model.simulate(stop=float(t[-1]), t_eval=t, rtol=1e-10, atol=1e-12)
    t_cs = time.perf_counter() - t0
    worst = 0.0
    for p in sims.PROBES[motor]:
        a, b = np.asarray(ref[p]), np.asarray(res[p])
        nrmse = float(np.sqrt(np.mean((a - b) ** 2)) / np.std(b))
        mx = float(np.max(np.abs(a - b)) / np.ptp(b))
        worst = max(worst, nrmse)
        tag = f"{regime}{' +backlash' if fx else ''}"
        print(f"motor {motor} {tag:4s} {p:10s}: NRMSE {nrmse:.2e}, max |diff|/range "
              f"{mx:.2e}  (scipy {t_ref:.1f} s, circuitsim {t_cs:.1f} s)")
    return worst


def main() -> int:
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    worst = 0.0
    for motor, regime, path, fs, dur in CASES:
        t = np.arange(round(dur * fs) + 1) / fs
        worst = max(worst, _compare(cs, motor, regime, path, t))
    t = np.arange(6001) / 10e3
    with tempfile.TemporaryDirectory() as tmp:
        worst = max(worst, _compare(cs, "C", "reversing", _backlash_netlist(Path(tmp)), t,
                                    {"backlash": BACKLASH_GAP}))
    print(f"worst NRMSE {worst:.2e} -> {'OK' if worst < 1e-4 else 'ABOVE 1e-4'}")
    return 0 if worst < 1e-4 else 1


if __name__ == "__main__":
    sys.exit(main())
