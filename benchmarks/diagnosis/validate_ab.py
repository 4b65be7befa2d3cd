"""Cross-check of motor AB on the records' own times: the noise-free null output of
simulators_ab.py against circuitsim's simulation of the declared netlists (motor_ab_fast.yaml,
motor_ab_slow.yaml), on the times of ae02 (even) and ae09 (jittered) in the fast regime and
of ae01 (a logger's uneven times) and ae03 (even) in the slow one; each catalog and
two-effect record against the declared netlist carrying the catalog's own patch
(through crosscheck.truth_patch) at the truth's expected values, on that record's times; and
the outside records as circuitsim's components state them:

- the shear-thinning compound: a behavioural torque (`btorque`) on the barrel,
  -c barrel.w (barrel.w^2 + eps^2)^((n - 1)/2);
- the flat-spotted support roller: a `cogging` element on the barrel at the non-integer
  order 330/70;
- the lossy EMI choke: an inductor Lc in parallel with a resistor Rp, between Ra and La;
- the viscoelastic spider: a Maxwell branch across the coupling (circuitsim refuses a
  massless body between a spring and a damper), its spring's deflection the voltage of an
  electrical analogue: the relative speed as a behavioural current (`BI`) into 1 F
  discharged through D2/K2 ohm, and K2 times it as behavioural torques (`btorque`) on the
  hub and the barrel.

Both netlists must declare the same motor: their parameters and all components but the
source are compared first.

    python benchmarks/diagnosis/validate_ab.py              # every record
    python benchmarks/diagnosis/validate_ab.py ae04,ae14    # some

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
import simulators_ab as sb
from make_records_ab import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_ab_fast.yaml",
            "slow": HERE / "netlists" / "motor_ab_slow.yaml"}
SOURCES = {"fast": "Vin", "slow": "U"}
TARGET = 1e-6
NULL_ON = ("ae01", "ae02", "ae03", "ae09")


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw``, located (for messages) where its first component is."""
    raw.comps = [*raw.comps, (dict(entry), *raw.comps[0][1:])]


def _rewire(raw: Any, name: str, **ports: Any) -> None:
    """Change the ports (or parameters) of the component ``name`` of ``raw``."""
    raw.comps = [({**c[0], **ports}, *c[1:]) if str(c[0]["name"]) == name else c
                 for c in raw.comps]


def shear(raw: Any, fx: dict) -> None:
    """The shear-thinning compound's drag on the barrel."""
    c, n, eps = fx["shear"]
    _add(raw, {"name": "Shear", "type": "btorque", "shaft": "barrel",
               "expr": f"-{c!r}*(barrel.w/1[rad/s])*((barrel.w/1[rad/s])^2 + {eps!r}^2)"
                       f"^({0.5 * (n - 1.0)!r})*1[N*m]"})


def roller(raw: Any, fx: dict) -> None:
    """The flat-spotted support roller: a torque at a non-integer order of the barrel."""
    amp, order, phase = fx["roller"]
    _add(raw, {"name": "Roller", "type": "cogging", "shaft": "barrel",
               "harmonics": [{"order": order, "amplitude": amp, "phase": phase}]})


def choke(raw: Any, fx: dict) -> None:
    """The lossy EMI choke between Ra and La: Lc in parallel with Rp."""
    lc, rp = fx["choke"]
    _rewire(raw, "La", p="mc")
    _add(raw, {"name": "Lc", "type": "L", "p": "m1", "n": "mc", "L": lc})
    _add(raw, {"name": "Rp", "type": "R", "p": "m1", "n": "mc", "R": rp})


def spider(raw: Any, fx: dict) -> None:
    """The spider's Maxwell branch through an electrical analogue of its spring's
    deflection x (the voltage sx.v, 1 V a radian): the relative speed as a behavioural
    current into 1 F, discharged through D2/K2 ohm (dx/dt = w_rel - K2 x / D2), and K2 x as
    behavioural torques on the hub and the barrel."""
    k2, d2 = fx["spider"]
    _add(raw, {"name": "Qx", "type": "BI", "p": "gnd", "n": "sx",
               "expr": "(hub.w - barrel.w)*1[A*s/rad]"})
    _add(raw, {"name": "Cx", "type": "C", "p": "sx", "n": "gnd", "C": 1.0})
    _add(raw, {"name": "Rx", "type": "R", "p": "sx", "n": "gnd", "R": d2 / k2})
    _add(raw, {"name": "Thub", "type": "btorque", "shaft": "hub",
               "expr": f"-{k2!r}*sx.v*1[N*m/V]"})
    _add(raw, {"name": "Tbar", "type": "btorque", "shaft": "barrel",
               "expr": f"{k2!r}*sx.v*1[N*m/V]"})


OUTSIDE_LAWS = {"shear": shear, "roller": roller, "choke": choke, "spider": spider}


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor AB's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=sb.simulate,
                          PROBES=sb.PROBES)
    return crosscheck.compare(cs, sim, "AB", sb.MOTOR_AB, NETLISTS, s["regime"], label, fx,
                              raw, values)


def catalog(cs: Any, s: dict) -> float:
    """A catalog or two-effect record through the catalog's own patch."""
    regime = s["regime"]
    raw, values = crosscheck.truth_patch(cs.load(NETLISTS[regime]), s["effects"],
                                         sb.PROBES[regime], sb.REGIMES[regime][1])
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
    print(f"motor AB: the fast and slow netlists declare the same motor: {same}")
    return same


def main() -> int:
    """Every record of fresh27; exit status 1 above TARGET (or if the netlists differ)."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    same = same_motor(cs)
    status = crosscheck.check_records(cs, record_specs(), times, scale_marginal, check,
                                      TARGET, sys.argv[1:2])
    return status if same else 1


if __name__ == "__main__":
    sys.exit(main())
