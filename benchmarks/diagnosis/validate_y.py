"""Cross-check of motor Y on the records' own times: the noise-free null output of
simulators_y.py against circuitsim's simulation of the declared netlists (motor_y_fast.yaml,
motor_y_slow.yaml), on the times of ab01 (even) and ab03 (jittered) in the fast regime and
of ab02 (a logger's uneven times) and ab05 (even) in the slow one; each catalog and
two-effect record against the declared netlist carrying the catalog's own patch
(circuitsim.loop.effects.candidates, through crosscheck.truth_patch) at the truth's
expected values, on that record's times; and the outside records as circuitsim's
components state them (each a behavioural torque on the plate):

- the limp-home spring: (T1 - c2 (plate.phi - thl)) (1 - tanh((plate.phi - thl)/wl))/2;
- the return spring's coil friction: -mu (T0 + c plate.phi) tanh(plate.w/0.01);
- the intake pulsation: A (plate.phi + phc) sin(2 pi f t + psi);
- the carbon ring: -dT exp(-((plate.phi - thc)/wc)^2) tanh(plate.w/0.01).

Both netlists must declare the same motor: their parameters and all components but the
source are compared first.

    python benchmarks/diagnosis/validate_y.py              # every record
    python benchmarks/diagnosis/validate_y.py ab04,ab14    # some

Prints, per probe, the largest difference relative to the signal's range at the record's
sample times, and the effect's own size on that scale. Target 1e-6 of the range; exit
status 1 above it. Nothing here runs a diagnosis.
"""

from __future__ import annotations

import os
import sys
import tempfile
import warnings
from pathlib import Path
from types import SimpleNamespace
from typing import Any

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import crosscheck
import simulators_y as sy
from make_records_y import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_y_fast.yaml",
            "slow": HERE / "netlists" / "motor_y_slow.yaml"}
SOURCES = {"fast": "Vin", "slow": "U"}
TARGET = 1e-6
NULL_ON = ("ab01", "ab02", "ab03", "ab05")


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw`` as a patch's part."""
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def _plate_torque(raw: Any, name: str, expr: str) -> None:
    """A behavioural torque ``expr`` [N m] on the plate."""
    _add(raw, {"name": name, "type": "btorque", "shaft": "plate", "expr": expr})


def limp(raw: Any, fx: dict) -> None:
    """The limp-home spring below limp-home."""
    t1, c2, thl, wl = fx["limp"]
    x = f"(plate.phi - {thl!r}[rad])"
    _plate_torque(raw, "Limp", f"({t1!r}[N*m] - {c2!r}[N*m/rad]*{x})*0.5*"
                               f"(1 - tanh({x}/{wl!r}[rad]))")


def coil(raw: Any, fx: dict) -> None:
    """The return spring's coil friction, in proportion to its wind-up torque."""
    _plate_torque(raw, "Coil", f"-{fx['coil']!r}*(T0 + c*plate.phi)*tanh(plate.w/0.01[rad/s])")


def pulse(raw: Any, fx: dict) -> None:
    """The intake manifold's pulsation on the plate."""
    amp, phc, f, psi = fx["pulse"]
    _plate_torque(raw, "Pulse", f"{amp!r}[N*m/rad]*(plate.phi + {phc!r}[rad])*"
                                f"sin({2.0 * f!r}*pi*t/1[s] + {psi!r})")


def coke(raw: Any, fx: dict) -> None:
    """The carbon ring's friction in a band of angles."""
    dt, thc, wc = fx["coke"]
    _plate_torque(raw, "Coke", f"-{dt!r}[N*m]*exp(-((plate.phi - {thc!r}[rad])/{wc!r}[rad])^2)"
                               f"*tanh(plate.w/0.01[rad/s])")


OUTSIDE_LAWS = {"limp": limp, "coil": coil, "pulse": pulse, "coke": coke}


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor Y's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=sy.simulate,
                          PROBES=sy.PROBES)
    return crosscheck.compare(cs, sim, "Y", sy.MOTOR_Y, NETLISTS, s["regime"], label, fx,
                              raw, values)


def catalog(cs: Any, s: dict) -> float:
    """A catalog or two-effect record through the catalog's own patch."""
    regime = s["regime"]
    raw, values = crosscheck.truth_patch(cs.load(NETLISTS[regime]), s["effects"],
                                         sy.PROBES[regime], sy.REGIMES[regime][1])
    # the id and class only: the effects stay in truth.json (the set is blind)
    return compare(cs, s, f"{s['id']} {s['class']}, the catalog's patch", s["fx"], raw,
                   values)


def outside(cs: Any, s: dict) -> float:
    """An outside record rebuilt from circuitsim's components."""
    law = next(f for k, f in OUTSIDE_LAWS.items() if k in s["fx"])
    raw = cs.load(NETLISTS[s["regime"]]).raw.copy()
    law(raw, s["fx"])
    return compare(cs, s, f"{s['id']} outside, as components", s["fx"], raw)


def check(cs: Any, s: dict) -> float:
    """One record's comparisons: the null on its times (NULL_ON), and its effects as the
    catalog's patch or as components."""
    worst = 0.0
    if s["id"] in NULL_ON:
        worst = compare(cs, s, f"null on {s['id']}'s {s['timestamps'].split(':')[0]} times",
                        {})
    if s["class"] in ("catalog", "two"):
        worst = max(worst, catalog(cs, s))
    elif s["class"] == "outside":
        worst = max(worst, outside(cs, s))
    return worst


def same_motor(cs: Any) -> bool:
    """Whether the two netlists declare the same parameters and components (but for the
    source)."""
    nets = {r: cs.load(path).raw for r, path in NETLISTS.items()}

    def motor(r: str) -> tuple:
        raw = nets[r]
        comps = [dict(c[0]) for c in raw.comps if str(c[0]["name"]) != SOURCES[r]]
        return repr({k: v for k, (v, _) in raw.params.items()}), repr(comps)

    same = motor("fast") == motor("slow")
    print(f"motor Y: the fast and slow netlists declare the same motor: {same}")
    return same


def main() -> int:
    """Every record of fresh24; exit status 1 above TARGET (or if the netlists differ)."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    same = same_motor(cs)
    status = crosscheck.check_records(cs, record_specs(), times, scale_marginal, check,
                                      TARGET, sys.argv[1:2])
    return status if same else 1


if __name__ == "__main__":
    sys.exit(main())
