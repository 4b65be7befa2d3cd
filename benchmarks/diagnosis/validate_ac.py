"""Cross-check of motor AC on the records' own times: the noise-free null output of
simulators_ac.py against circuitsim's simulation of the declared netlists (motor_ac_fast.yaml,
motor_ac_slow.yaml), on the times of af02 (even) and af03 (jittered) in the fast regime and
of af01 (a logger's uneven times) and af06 (even) in the slow one; each catalog and
two-effect record against the declared netlist carrying the catalog's own patch
(through crosscheck.truth_patch) at the truth's expected values, on that record's times; and
the outside records as circuitsim's components state them:

- the thrust-dependent nut friction: a behavioural torque (`btorque`) on the screw,
  -mu |Kc (hub.phi - screw.phi) + Dc (hub.w - screw.w)| tanh(screw.w / 0.01);
- the cold grease thinning: a behavioural torque on the screw, -b1 exp(-t / tau) screw.w;
- the seat heater on the shared harness: a resistor Rh between the source and Ra, and the
  heater's current Ih (1 + tanh((t - t1) / tr)) / 2 as a behavioural current (`BI`) drawn
  from the node between them;
- the bent track's tight stretch: a behavioural torque on the screw,
  -Tb exp(-((screw.phi - th0) / wd)^2) tanh(screw.w / 0.01).

Both netlists must declare the same motor: their parameters and all components but the
source are compared first.

    python benchmarks/diagnosis/validate_ac.py              # every record
    python benchmarks/diagnosis/validate_ac.py af04,af14    # some

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
import simulators_ac as sa
from make_records_ac import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_ac_fast.yaml",
            "slow": HERE / "netlists" / "motor_ac_slow.yaml"}
SOURCES = {"fast": "Vin", "slow": "U"}
TARGET = 1e-6
NULL_ON = ("af01", "af02", "af03", "af06")


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw``, located (for messages) where its first component is."""
    raw.comps = [*raw.comps, (dict(entry), *raw.comps[0][1:])]


def _rewire(raw: Any, name: str, **ports: Any) -> None:
    """Change the ports (or parameters) of the component ``name`` of ``raw``."""
    raw.comps = [({**c[0], **ports}, *c[1:]) if str(c[0]["name"]) == name else c
                 for c in raw.comps]


def nutload(raw: Any, fx: dict) -> None:
    """The nut's friction growing with the flexible shaft's torque."""
    mu, p = fx["nutload"], sa.MOTOR_AC
    _add(raw, {"name": "Nut", "type": "btorque", "shaft": "screw",
               "expr": f"-{mu!r}*abs({p['Kc']!r}[N*m/rad]*(hub.phi - screw.phi) + "
                       f"{p['Dc']!r}[N*m*s/rad]*(hub.w - screw.w))*tanh(screw.w/0.01[rad/s])"})


def grease(raw: Any, fx: dict) -> None:
    """The cold grease's extra drag on the screw, fading."""
    b1, tau = fx["grease"]
    _add(raw, {"name": "Grease", "type": "btorque", "shaft": "screw",
               "expr": f"-{b1!r}[N*m*s/rad]*exp(-t/{tau!r}[s])*screw.w"})


def heater(raw: Any, fx: dict) -> None:
    """The harness resistance Rh shared with the seat heater's current, between the source
    and Ra."""
    rh, ih, t1, tr = fx["heater"]
    _rewire(raw, "Ra", p="h")
    _add(raw, {"name": "Rh", "type": "R", "p": "a", "n": "h", "R": rh})
    _add(raw, {"name": "Heat", "type": "BI", "p": "h", "n": "gnd",
               "expr": f"{ih!r}[A]*0.5*(1 + tanh((t - {t1!r}[s])/{tr!r}[s]))"})


def tight(raw: Any, fx: dict) -> None:
    """The bent track's dry friction bump over a stretch of the screw's angle."""
    tb, th0, wd = fx["tight"]
    _add(raw, {"name": "Tight", "type": "btorque", "shaft": "screw",
               "expr": f"-{tb!r}[N*m]*exp(-((screw.phi - {th0!r}[rad])/{wd!r}[rad])^2)"
                       f"*tanh(screw.w/0.01[rad/s])"})


OUTSIDE_LAWS = {"nutload": nutload, "grease": grease, "heater": heater, "tight": tight}


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor AC's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=sa.simulate,
                          PROBES=sa.PROBES)
    return crosscheck.compare(cs, sim, "AC", sa.MOTOR_AC, NETLISTS, s["regime"], label, fx,
                              raw, values)


def catalog(cs: Any, s: dict) -> float:
    """A catalog or two-effect record through the catalog's own patch."""
    regime = s["regime"]
    raw, values = crosscheck.truth_patch(cs.load(NETLISTS[regime]), s["effects"],
                                         sa.PROBES[regime], sa.REGIMES[regime][1])
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
    print(f"motor AC: the fast and slow netlists declare the same motor: {same}")
    return same


def main() -> int:
    """Every record of fresh28; exit status 1 above TARGET (or if the netlists differ)."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    same = same_motor(cs)
    status = crosscheck.check_records(cs, record_specs(), times, scale_marginal, check,
                                      TARGET, sys.argv[1:2])
    return status if same else 1


if __name__ == "__main__":
    sys.exit(main())
