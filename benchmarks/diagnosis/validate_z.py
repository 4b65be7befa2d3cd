"""Cross-check of motor Z on the records' own times: the noise-free null output of
simulators_z.py against circuitsim's simulation of the declared netlists (motor_z_fast.yaml,
motor_z_slow.yaml), on the times of ac01 (even) and ac04 (jittered) in the fast regime and
of ac02 (a logger's uneven times) and ac05 (even) in the slow one; each catalog and
two-effect record against the declared netlist carrying the catalog's own patch
(circuitsim.loop.effects.candidates, through crosscheck.truth_patch) at the truth's
expected values, on that record's times; and the outside records as circuitsim's
components state them:

- the resettable fuse: a heated resistor (`RT`, R0 (1 + a (T - T_ref))) between the source
  and Ra, its heat capacity (`heat_capacitor`) and its conductance (`thermal_conductor`) to
  the housing at the ambient (`fixed_temperature`);
- the chipped tooth: a behavioural torque on the sprocket,
  -A exp(kappa (cos(spr.phi - th0) - 1)) tanh(spr.w/0.01);
- the commutation's reactance drop: a behavioural voltage (`BV`) ka smooth_abs(rotor.w, 1)
  La.i between Ra and La;
- the floating cable: a behavioural torque on the robot,
  -cb smooth_abs(robot.phi, x0) robot.w.

Both netlists must declare the same motor: their parameters and all components but the
source are compared first.

    python benchmarks/diagnosis/validate_z.py              # every record
    python benchmarks/diagnosis/validate_z.py ac04,ac14    # some

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
import simulators_z as sz
from make_records_z import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_z_fast.yaml",
            "slow": HERE / "netlists" / "motor_z_slow.yaml"}
SOURCES = {"fast": "Vin", "slow": "U"}
TARGET = 1e-6
NULL_ON = ("ac01", "ac02", "ac04", "ac05")
#: [K] the water-cooled housing's temperature, the fuse's reference
T_AMB = 293.15


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw`` as a patch's part."""
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def _rewire(raw: Any, name: str, **ports: str) -> None:
    """Move the ports of the component ``name`` of ``raw`` to other nodes."""
    raw.comps = [({**c[0], **ports}, *c[1:]) if str(c[0]["name"]) == name else c
                 for c in raw.comps]


def fuse(raw: Any, fx: dict) -> None:
    """The resettable fuse between the source and Ra, heated by its own loss."""
    r0, a, cap, g = fx["fuse"]
    _rewire(raw, "Ra", p="af")
    _add(raw, {"name": "Fuse", "type": "RT", "p": "a", "n": "af", "h": "fuse",
               "R_ref": r0, "T_ref": T_AMB, "alpha": a})
    _add(raw, {"name": "Cf", "type": "heat_capacitor", "port": "fuse", "C": cap,
               "T0": T_AMB})
    _add(raw, {"name": "Gf", "type": "thermal_conductor", "a": "fuse", "b": "housing",
               "G": g})
    _add(raw, {"name": "Housing", "type": "fixed_temperature", "port": "housing",
               "T": T_AMB})


def tooth(raw: Any, fx: dict) -> None:
    """The chipped tooth's binding pulse on the sprocket, once per output turn."""
    amp, kappa, th0 = fx["tooth"]
    _add(raw, {"name": "Tooth", "type": "btorque", "shaft": "spr",
               "expr": f"-{amp!r}[N*m]*exp({kappa!r}*(cos(spr.phi - {th0!r}[rad]) - 1))"
                       f"*tanh(spr.w/0.01[rad/s])"})


def arc(raw: Any, fx: dict) -> None:
    """The commutation's reactance drop between Ra and La."""
    _rewire(raw, "La", p="mb")
    _add(raw, {"name": "Arc", "type": "BV", "p": "m1", "n": "mb",
               "expr": f"{fx['arc']!r}*smooth_abs(rotor.w, 1[rad/s])*La.i"})


def cable(raw: Any, fx: dict) -> None:
    """The floating cable's drag, growing with the robot's travel."""
    cb, x0 = fx["cable"]
    _add(raw, {"name": "Cable", "type": "btorque", "shaft": "robot",
               "expr": f"-{cb!r}*smooth_abs(robot.phi, {x0!r}[rad])*robot.w"})


OUTSIDE_LAWS = {"fuse": fuse, "tooth": tooth, "arc": arc, "cable": cable}


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor Z's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=sz.simulate,
                          PROBES=sz.PROBES)
    return crosscheck.compare(cs, sim, "Z", sz.MOTOR_Z, NETLISTS, s["regime"], label, fx,
                              raw, values)


def catalog(cs: Any, s: dict) -> float:
    """A catalog or two-effect record through the catalog's own patch."""
    regime = s["regime"]
    raw, values = crosscheck.truth_patch(cs.load(NETLISTS[regime]), s["effects"],
                                         sz.PROBES[regime], sz.REGIMES[regime][1])
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
    print(f"motor Z: the fast and slow netlists declare the same motor: {same}")
    return same


def main() -> int:
    """Every record of fresh25; exit status 1 above TARGET (or if the netlists differ)."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    same = same_motor(cs)
    status = crosscheck.check_records(cs, record_specs(), times, scale_marginal, check,
                                      TARGET, sys.argv[1:2])
    return status if same else 1


if __name__ == "__main__":
    sys.exit(main())
