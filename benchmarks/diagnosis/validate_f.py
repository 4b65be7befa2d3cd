"""Cross-check of motor F: the noise-free null output of simulators_f.py against circuitsim's
simulation of the declared netlists (motor_f.yaml, fast; motor_f_slow.yaml, slow), and each
catalog and two-effect record against the declared netlist carrying the catalog's own patch
at the truth's expected values.

    PYTHONPATH=<circuitsim checkout> python benchmarks/diagnosis/validate_f.py

Prints, per probe, the largest difference relative to the signal's range on the record grid
(and the effect's own size on that scale). Target 1e-5; exit status 1 above it. One outside
case is also checked where circuitsim can build the law from its components: the input LC
filter (k12). Nothing here runs a diagnosis.
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

import simulators_f as sf
from make_records_f import record_specs, scale_marginal

NETLISTS = {"fast": HERE / "netlists" / "motor_f.yaml",
            "slow": HERE / "netlists" / "motor_f_slow.yaml"}
UNITS = {"current": "A", "speed": "rad/s", "load_speed": "rad/s"}
TARGET = 1e-5


def _alias(key: str) -> str:
    return {"offset": "o", "gain": "g", "delay": "tau"}.get(key, key)


def catalog_raw(net, regime, effects):
    """The declared netlist with each truth effect's catalog patch; (raw, parameter values)."""
    from circuitsim.loop.effects import candidates

    raw, values = net.raw, {}
    probes = {p: UNITS[p] for p in sf.PROBES[regime]}
    for e in effects:
        cands = [c for c in candidates(net, probes=probes, duration=sf.REGIMES[regime][1])
                 if c.effect == e["effect"] and c.target == e["target"]]
        cand = next(c for c in cands if all(any(n.endswith("_" + _alias(k)) for n in c.free)
                                            for k in e["expected"]))
        raw = cand.apply(raw)
        for k, v in e["expected"].items():
            name = next(n for n in cand.free if n.endswith("_" + _alias(k)))
            values[name] = float(v) - 1.0 if k == "gain" else float(v)
    return raw, values


def compare(cs, regime, label, fx, raw=None, values=None, net_path=None) -> float:
    from circuitsim.netlist.load import build

    t = sf.grid(regime)
    fx = dict(fx)
    p = {**sf.MOTOR_F, **fx.pop("p", {})}
    ref = sf.simulate(regime, t, fx, p)
    base = sf.simulate(regime, t) if (fx or p != sf.MOTOR_F) else None
    net = cs.load(net_path or NETLISTS[regime]) if raw is None else build(raw)
    t0 = time.perf_counter()
    res = cs.compile(net).simulate(stop=float(t[-1]), t_eval=t, params=values or None,
                                   rtol=1e-10, atol=1e-12)
    t_cs = time.perf_counter() - t0
    worst = 0.0
    for pr in sf.PROBES[regime]:
        a, b = np.asarray(ref[pr]), np.asarray(res[pr])
        mx = float(np.max(np.abs(a - b)) / np.ptp(b))
        worst = max(worst, mx)
        size = "" if base is None else \
            f"; effect {np.max(np.abs(a - base[pr])) / np.ptp(b):.1e} of range"
        print(f"motor F {regime:4s} {label:58s} {pr:10s}: max |diff|/range {mx:.1e} "
              f"(range {np.ptp(b):.4g}{size}; circuitsim {t_cs:.1f} s)", flush=True)
    return worst


LC_EXTRA = """  - {name: Rf, type: R, p: sup, n: lf1, R: %r}
  - {name: Lf, type: L, p: lf1, n: a, L: %r}
  - {name: Cf, type: C, p: a, n: gnd, C: %r}
"""


def lc_netlist(lf, rf, cf) -> Path:
    """motor_f.yaml with the supply behind an Rf-Lf series and Cf across the bridge."""
    text = NETLISTS["fast"].read_text()
    text = text.replace("    p: a\n", "    p: sup\n", 1)
    text = text.replace("analysis:", LC_EXTRA % (rf, lf, cf) + "analysis:", 1)
    path = HERE / "netlists" / "_validate_f_lc.yaml"
    path.write_text(text)
    return path


def main() -> int:
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    worst = max(compare(cs, r, "null", {}) for r in ("fast", "slow"))
    for spec in record_specs():
        regime = spec["regime"]
        if spec["marginal"] is not None:
            scale_marginal(spec)
        if spec["class"] in ("catalog", "two"):
            raw, values = catalog_raw(cs.load(NETLISTS[regime]), regime, spec["effects"])
            label = spec["id"] + " " + " + ".join(
                f"{e['effect']}@{e['target']} " + ",".join(f"{k} {v:.4g}" for k, v in
                                                           e["expected"].items())
                for e in spec["effects"])
            worst = max(worst, compare(cs, regime, label, spec["fx"], raw, values))
        elif "lc_in" in spec["fx"]:
            path = lc_netlist(*spec["fx"]["lc_in"])
            try:
                worst = max(worst, compare(cs, regime, f"{spec['id']} outside: LC filter "
                                           "as R, L, C components", spec["fx"], net_path=path))
            finally:
                path.unlink()
    print(f"worst max |diff|/range {worst:.2e} -> {'OK' if worst < TARGET else 'ABOVE'} "
          f"(target {TARGET:g})")
    return 0 if worst < TARGET else 1


if __name__ == "__main__":
    sys.exit(main())
