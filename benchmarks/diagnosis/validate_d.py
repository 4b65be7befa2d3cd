"""Cross-check of motor D: the noise-free null output of simulators_d.py against circuitsim's
simulation of the declared netlists (motor_d.yaml, fast; motor_d_slow.yaml, slow).

    PYTHONPATH=<circuitsim checkout> python benchmarks/diagnosis/validate_d.py

Prints, per regime and probe, the NRMSE (RMS difference / std of the signal) and the largest
difference relative to the signal's range, on the record grids. The target is below 1e-4
(the records' noise is ~1e-3 of the range); exit status 1 above it.

It also checks the catalog records' physics and expected values: the scipy model with a
record's effects (sensor effects left out) against circuitsim's simulation of the netlist
carrying that effect in the catalog patch's own form, at the truth's expected value (a BV in
series for a brush drop or a warm-up, a ``friction``/``torque`` component on the output, a
changed L, Rsh or bl). Where these agree, the catalog's patch at the expected value is the
record's physics exactly (a brush drop up to its smoothing: 10 mA in the record, 1 mA in the
catalog; checked here with the record's).
"""

from __future__ import annotations

import os
import shutil
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import simulators_d as sd

NETLISTS = {"fast": HERE / "netlists" / "motor_d.yaml",
            "slow": HERE / "netlists" / "motor_d_slow.yaml"}
TARGET = 1e-4
#: the catalog records' effects in circuitsim's terms: (record, regime, scipy fx, parameter
#: overrides, components added between the source and the shunt or on a shaft). ``SERIES``
#: in a component is the node between the source's + terminal and the shunt.
EFFECT_CASES: tuple[tuple[str, str, dict, dict, tuple[str, ...]], ...] = (
    ("d03 brush drop 0.8 V", "fast", {"Vb": 0.8, "Vb_eps": 0.01}, {},
     ("{name: BD, type: BV, p: SERIES, n: a, expr: '0.8*tanh(Rsh.i/0.01)'}",)),
    ("d06 La + 0.3 mH (dL 1/3)", "fast", {"Ls": 0.3e-3}, {"L": 0.9e-3 * (1 + 1 / 3)}, ()),
    ("d09 Rser 0.15 + b 3e-3 on load", "fast", {"Rser": 0.15, "Bx_load": 3e-3},
     {"Rsh": 0.17, "bl": 5e-3}, ()),
    ("d10 supply current limit 6 A", "fast", {"current_limit": (6.0, 20.0, 0.05)}, {},
     (("{name: CL, type: BV, p: SERIES, n: a, expr: '20*(0.05*log(1 + exp((Rsh.i - 6)/0.05))"
       " - 0.05*log(1 + exp((-Rsh.i - 6)/0.05)))'}"),)),
    ("d04 Coulomb 0.12 N m on load", "slow", {"Fc_load": 0.12}, {},
     ("{name: CF, type: friction, shaft: load, tau_c: 0.12, w_brk: 0.1}",)),
    ("d07 warm-up 10 %, 2 s", "slow", {"warmup": (0.1, 2.0)}, {},
     ("{name: RW, type: BV, p: SERIES, n: a, expr: '0.1*(1 - exp(-t/2))*Ra.v'}",)),
    ("d08 load torque 0.15 N m", "slow", {"T_load": 0.15}, {},
     ("{name: TL, type: torque, shaft: load, T: -0.15}",)),
)


def patched(tmp: Path, regime: str, extra: tuple[str, ...]) -> Path:
    """A copy of the regime's netlist (with its include and input table) in ``tmp`` with
    components ``extra`` added; a series one sits between the source's + terminal (moved to
    node SERIES) and the shunt's node ``a``."""
    src = HERE / "netlists"
    shutil.copy(src / "motor_d_motor.yaml", tmp / "motor_d_motor.yaml")
    (tmp / "inputs").mkdir(exist_ok=True)
    shutil.copy(src / "inputs" / "motor_d_profile.csv", tmp / "inputs" / "motor_d_profile.csv")
    text = NETLISTS[regime].read_text()
    if any("SERIES" in e for e in extra):
        assert text.count("    p: a\n") == 1
        text = text.replace("    p: a\n", "    p: SERIES\n")
    head, tail = text.split("components:\n", 1)
    text = head + "components:\n" + "".join(f"  - {e}\n" for e in extra) + tail
    path = tmp / NETLISTS[regime].name
    path.write_text(text)
    return path


def compare(cs, regime: str, case: tuple[str, dict, dict, tuple[str, ...]] | None = None,
            tmp: Path | None = None) -> float:
    """Print the agreement per probe of one regime (with a case of EFFECT_CASES: its label,
    scipy fx, parameter overrides and added components); return the worst max |diff| /
    range."""
    label, fx, over, extra = case or ("null", {}, {}, ())
    t = sd.grid(regime)
    t0 = time.perf_counter()
    ref = sd.simulate(regime, t, fx)
    t_ref = time.perf_counter() - t0
    path = patched(tmp, regime, extra) if extra and tmp is not None else NETLISTS[regime]
    model = cs.compile(cs.load(path))
    t0 = time.perf_counter()
    res = model.simulate(stop=float(t[-1]), t_eval=t, params=over or None, rtol=1e-10,
                         atol=1e-12)
    t_cs = time.perf_counter() - t0
    worst = 0.0
    for p in sd.PROBES[regime]:
        a, b = np.asarray(ref[p]), np.asarray(res[p])
        nrmse = float(np.sqrt(np.mean((a - b) ** 2)) / np.std(b))
        mx = float(np.max(np.abs(a - b)) / np.ptp(b))
        worst = max(worst, mx)
        print(f"motor D {regime:4s} {label:32s} {p:10s}: NRMSE {nrmse:.2e}, max |diff|/range "
              f"{mx:.2e}  (range {np.ptp(b):.4g}; scipy {t_ref:.1f} s, circuitsim "
              f"{t_cs:.1f} s)")
    return worst


def main() -> int:
    """Compare both regimes; exit 0 when every probe is within TARGET."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    worst = max(compare(cs, regime) for regime in ("fast", "slow"))
    with tempfile.TemporaryDirectory() as tmp:
        for label, regime, fx, over, extra in EFFECT_CASES:
            worst = max(worst, compare(cs, regime, (label, fx, over, extra), Path(tmp)))
    print(f"worst max |diff|/range {worst:.2e} -> {'OK' if worst < TARGET else 'ABOVE'} "
          f"(target {TARGET:g})")
    return 0 if worst < TARGET else 1


if __name__ == "__main__":
    sys.exit(main())
