"""Cross-check of motor E: the noise-free null output of simulators_e.py against circuitsim's
simulation of the declared netlists (motor_e.yaml, fast; motor_e_slow.yaml, slow), and each
catalog record's effect against the catalog's own patch at the truth's expected values.

    PYTHONPATH=<circuitsim checkout> python benchmarks/diagnosis/validate_e.py

Prints, per regime and probe, the NRMSE (RMS difference / std of the signal) and the largest
difference relative to the signal's range, on the record grids. The target is below 1e-4
(the records' noise is ~1e-3 of the range); exit status 1 above it.

The catalog cases take the candidate that ``circuitsim.loop.effects.candidates`` proposes for
the truth's effect and target, apply its patch to the declared netlist and set its free
parameters (matched by the suffix of their names, as run.py scores them) to the truth's
``expected`` values; the scipy model carries the record's effects (all of them, sensor
effects included). Where the two agree, the catalog's patch at the expected value is the
record's physics. One outside case is checked the same way where circuitsim has the law as a
component option: the belt's efficiency (e12) as the ``gear``'s ``eta``.

This is the only use of circuitsim for motor E: nothing here runs a diagnosis.
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
sys.path.insert(0, str(HERE))

import simulators_e as se
from make_records_e import record_specs, scale_marginal, split_fx

NETLISTS = {"fast": HERE / "netlists" / "motor_e.yaml",
            "slow": HERE / "netlists" / "motor_e_slow.yaml"}
UNITS = {"current": "A", "speed": "rad/s", "load_speed": "rad/s"}
TARGET = 1e-4
#: outside records checked with a circuitsim component option: id -> (component, key, value)
OUTSIDE_CASES = {"e12": ("Belt", "eta", 0.85)}


def _catalog_raw(cs, net, regime: str, effects: list[dict]):
    """The declared netlist ``net`` with each truth effect's catalog patch (proposed for the
    declared netlist) applied; returns (raw, parameter values [SI]): the patches' free
    parameters at the expected values."""
    from circuitsim.loop.effects import candidates

    raw, values = net.raw, {}
    dur = se.REGIMES[regime][1]
    for e in effects:
        probes = {p: UNITS[p] for p in se.PROBES[regime]}
        cands = [c for c in candidates(net, probes=probes, duration=dur)
                 if c.effect == e["effect"] and c.target == e["target"]]
        expected = e["expected"]
        # a straight drift and a warm-up share the label: take the one with these names
        cand = next(c for c in cands if all(any(n.endswith("_" + _alias(k)) for n in c.free)
                                            for k in expected))
        raw = cand.apply(raw)
        for k, v in expected.items():
            name = next(n for n in cand.free if n.endswith("_" + _alias(k)))
            values[name] = float(v) - 1.0 if k == "gain" else float(v)
    return raw, values


def _alias(key: str) -> str:
    """The catalog's parameter suffix for a truth ``expected`` key."""
    return {"offset": "o", "gain": "g", "delay": "tau"}.get(key, key)


def compare(cs, regime: str, label: str, fx: dict, raw=None, values=None) -> float:
    """Print the agreement per probe of the scipy model with effects ``fx`` (a ``p`` entry:
    motor parameters changed) against
    circuitsim's simulation of ``raw`` (default: the declared netlist) with parameter
    ``values`` [SI]; return the worst max |diff| / range."""
    from circuitsim.netlist.load import build

    t = se.grid(regime)
    t0 = time.perf_counter()
    sim_fx, motor = split_fx(fx)
    ref = se.simulate(regime, t, sim_fx, motor)
    t_ref = time.perf_counter() - t0
    net = cs.load(NETLISTS[regime]) if raw is None else build(raw)
    model = cs.compile(net)
    t0 = time.perf_counter()
    res = model.simulate(stop=float(t[-1]), t_eval=t, params=values or None, rtol=1e-10,
                         atol=1e-12)
    t_cs = time.perf_counter() - t0
    base = se.simulate(regime, t) if fx else None
    worst = 0.0
    for p in se.PROBES[regime]:
        a, b = np.asarray(ref[p]), np.asarray(res[p])
        nrmse = float(np.sqrt(np.mean((a - b) ** 2)) / np.std(b))
        mx = float(np.max(np.abs(a - b)) / np.ptp(b))
        worst = max(worst, mx)
        # the effect's own size on this probe, to set the agreement against
        size = "" if base is None else \
            f"; effect max |fx - null|/range {np.max(np.abs(a - base[p])) / np.ptp(b):.1e}"
        print(f"motor E {regime:4s} {label:44s} {p:10s}: NRMSE {nrmse:.2e}, max |diff|/range "
              f"{mx:.2e}  (range {np.ptp(b):.4g}{size}; scipy {t_ref:.1f} s, circuitsim "
              f"{t_cs:.1f} s)", flush=True)
    return worst


def main() -> int:
    """Compare the null in both regimes and every catalog record; exit 0 when every probe is
    within TARGET."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    worst = max(compare(cs, regime, "null", {}) for regime in ("fast", "slow"))
    for spec in record_specs():
        regime = spec["regime"]
        if spec["marginal"] is not None:
            scale_marginal(spec)
        if spec["class"] in ("catalog", "two"):
            net = cs.load(NETLISTS[regime])
            raw, values = _catalog_raw(cs, net, regime, spec["effects"])
            label = spec["id"] + " " + " + ".join(
                f"{e['effect']}@{e['target']} " + ",".join(f"{k} {v:.4g}" for k, v in
                                                           e["expected"].items())
                for e in spec["effects"])
            worst = max(worst, compare(cs, regime, label, spec["fx"], raw, values))
        elif spec["id"] in OUTSIDE_CASES:
            comp, key, val = OUTSIDE_CASES[spec["id"]]
            raw = cs.load(NETLISTS[regime]).raw.copy()
            raw.component_entry(comp)[key] = val
            label = f"{spec['id']} outside: {comp}.{key} = {val:g}"
            worst = max(worst, compare(cs, regime, label, spec["fx"], raw))
    print(f"worst max |diff|/range {worst:.2e} -> {'OK' if worst < TARGET else 'ABOVE'} "
          f"(target {TARGET:g})")
    return 0 if worst < TARGET else 1


if __name__ == "__main__":
    sys.exit(main())
