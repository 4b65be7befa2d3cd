"""Periodic steady state and AC against transient-to-steady-state, Kim & Kim base model.

    python benchmarks/bench_analyses.py

Reference I8 = 0.380644390 A (LSODA rtol 1e-11, same extraction; see bench_base.py). For each
target accuracy the cheapest transient (0.3 s from rest, IDA at the rtol that meets it) is
timed against the periodic steady state by shooting at the rtol that meets it. The Fig. 9 curve
is timed by AC (the order-8 shaft harmonic as a small-signal source) and by transient.
Times are best of 5, in-process, warm cache.
"""

from __future__ import annotations

import os
import sys
import tempfile
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "benchmarks"), str(ROOT / "tests")]
I8_REF = 0.380644390
FIG9 = {1e-9: 0.380641, 1e-8: 0.380637, 1e-7: 0.380599, 1e-6: 0.380221, 1e-5: 0.376479,
        1e-4: 0.342658, 1e-3: 0.179293, 1e-2: 0.030793, 1e-1: 0.0033134}


def main() -> int:
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="bench-cache-"))
    warnings.simplefilter("ignore")
    from common import best_of

    import circuitsim as cs
    from circuitsim.solve.ac import harmonic_response
    from circuitsim.solve.pss import periodic_steady_state

    base = cs.compile(cs.load(ROOT / "netlists" / "kim2024" / "base.yaml"))
    case1 = cs.compile(cs.load(ROOT / "netlists" / "kim2024" / "case1.yaml"))

    def transient(rtol):
        r = base.simulate(rtol=rtol, atol=rtol * 1e-3)
        return r.harmonic("i_total", order=8, window=1 / 6).amplitude

    def pss(rtol):
        return periodic_steady_state(base, order=8, rtol=rtol, atol=rtol * 1e-2,
                                     tol=max(rtol * 10, 1e-10)).harmonic("i_total", 1)[1]

    print("periodic steady state vs transient to steady state (0.3 s from rest)")
    print(f"{'target':>8} {'transient':>28} {'pss (shooting)':>28} {'speed-up':>9}")
    for target in (1e-5, 1e-6, 1e-7):
        rows = {}
        for name, fn, rtols in (("transient", transient, (2e-6, 1e-6, 3e-7, 1e-7, 3e-8, 1e-8,
                                                          1e-9)),
                                ("pss", pss, (1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10))):
            for rtol in rtols:
                t, amp = best_of(5, lambda fn=fn, rtol=rtol: fn(rtol))
                err = abs(amp - I8_REF) / I8_REF
                if err <= target:
                    rows[name] = (t, rtol, err)
                    break
        if len(rows) == 2:
            (tt, rt, et), (tp, rp, ep) = rows["transient"], rows["pss"]
            print(f"{target:>8.0e} {tt:8.4f} s (rtol {rt:.0e}, {et:.1e}) "
                  f"{tp:8.4f} s (rtol {rp:.0e}, {ep:.1e}) {tt / tp:8.1f}x")
    t_ac, amps = best_of(5, lambda: [harmonic_response(case1, 8, "i_total",
                                                        params={"Lf": lf, "Rf": 0.0}).amplitude
                                     for lf in FIG9])
    worst = max(abs(a - r) / r for a, r in zip(amps, FIG9.values(), strict=True))
    t_tr, _ = best_of(1, lambda: [case1.simulate(stop=0.3, params={"Lf": lf, "Rf": 0.0})
                                  for lf in FIG9])
    print(f"\nFig. 9 (9 points): AC {t_ac:.3f} s (worst deviation from the reference "
          f"{worst:.1e}); transient 0.3 s each {t_tr:.2f} s -> {t_tr / t_ac:.0f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())
