"""Cross-check of motor BG on the records' own times: the noise-free output of
simulators_bg.py against circuitsim's simulation of the declared netlists (motor_bg_fast.yaml,
motor_bg_slow.yaml) with NO effect: first at the netlists' DECLARED values (on the nominal grid
of each regime, and on the times of bj01 (even) and bj03 (jittered) in the fast regime and of
bj04 (even) and bj02 (a logger's uneven times) in the slow one), then on every record's times
at the record's TRUE values (the declared parameters it frees set to their true values through
circuitsim's parameter overrides, ``params``). The records' effects are not run through
circuitsim here (this blind set keeps circuitsim to the null models).

Both netlists must declare the same motor: their parameters and all components but the source
are compared first. The set's generator and simulator must not touch circuitsim: their sources
(make_records_bg.py, simulators_bg.py and the recordkit.py they share) are read first and any
import of circuitsim in them fails the check; and at the end no module of the diagnosis's
package (``circuitsim.loop``) may have been imported by anything run here.

    python benchmarks/diagnosis/validate_bg.py              # every record
    python benchmarks/diagnosis/validate_bg.py bj04,bj14    # some

Prints, per probe, the largest difference relative to the signal's range at the record's
sample times. Target 1e-7 of the range; exit status 1 above it. Nothing here runs a
diagnosis.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
import warnings
from pathlib import Path
from types import SimpleNamespace
from typing import Any

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import crosscheck
import simulators_bg as sb
from make_records_bg import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_bg_fast.yaml",
            "slow": HERE / "netlists" / "motor_bg_slow.yaml"}
SOURCES = {"fast": "Vin", "slow": "U"}
TARGET = 1e-7
NULL_ON = ("bj01", "bj02", "bj03", "bj04")
OWN_CODE = ("make_records_bg.py", "simulators_bg.py", "recordkit.py")


def compare(cs: Any, s: dict, label: str, fx: dict,
            values: dict[str, float] | None = None) -> float:
    """Motor BG's scipy model against circuitsim at the record's own times (``values``:
    circuitsim's parameter overrides)."""
    model = SimpleNamespace(grid=lambda regime: times(s), simulate=sb.simulate,
                            PROBES=sb.PROBES)
    return crosscheck.compare(cs, model, "BG", sb.MOTOR_BG, NETLISTS, s["regime"], label, fx,
                              None, values)


def check(cs: Any, s: dict) -> float:
    """The declared null on the record's times (NULL_ON) and its true null, no effect."""
    worst = 0.0
    kind = s["timestamps"].split(":")[0]
    if s["id"] in NULL_ON:
        worst = compare(cs, s, f"declared null on {s['id']}'s {kind} times", {})
    return max(worst, compare(cs, s, f"true null of {s['id']} ({kind} times)",
                              {"p": dict(s["ptrue"])}, dict(s["ptrue"])))


def same_motor(cs: Any) -> bool:
    """Whether the two netlists declare the same parameters and components (but the
    source)."""
    nets = {r: cs.load(path).raw for r, path in NETLISTS.items()}

    def motor(r: str) -> tuple:
        raw = nets[r]
        comps = [dict(c[0]) for c in raw.comps if str(c[0]["name"]) != SOURCES[r]]
        return repr({k: v for k, (v, _) in raw.params.items()}), repr(comps)

    same = motor("fast") == motor("slow")
    print(f"motor BG: the fast and slow netlists declare the same motor: {same}")
    return same


def main() -> int:
    """Every record of fresh58; exit status 1 above TARGET (or if the netlists differ, the
    set's code imports circuitsim, or circuitsim.loop was imported)."""
    t0 = time.perf_counter()
    clean = crosscheck.own_code_clean(HERE, OWN_CODE)
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    same = same_motor(cs)
    grid = SimpleNamespace(grid=sb.grid, simulate=sb.simulate, PROBES=sb.PROBES)
    worst = max(crosscheck.compare(cs, grid, "BG", sb.MOTOR_BG, NETLISTS, r,
                                   "declared null, nominal grid", {})
                for r in ("fast", "slow"))
    print(f"declared nulls on the nominal grids: worst {worst:.2e}")
    status = crosscheck.check_records(cs, record_specs(), times, scale_marginal, check,
                                      TARGET, sys.argv[1:2])
    if worst >= TARGET:
        status = 1
    loaded = sorted(m for m in sys.modules if m.startswith("circuitsim.loop"))
    print(f"validate_bg: {time.perf_counter() - t0:.0f} s")
    if loaded:
        print(f"the diagnosis's package was imported ({', '.join(loaded)}): the check is void")
        return 1
    print("circuitsim.loop: not imported")
    if not clean:
        print("the set's generator or simulator imports circuitsim: the check is void")
        return 1
    return status if same else 1


if __name__ == "__main__":
    sys.exit(main())
