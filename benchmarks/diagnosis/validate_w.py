"""Cross-check of motor W on the records' own times: the noise-free null output of
simulators_w.py against circuitsim's simulation of the declared netlists (motor_w.yaml,
fast; motor_w_slow.yaml, slow), on the times of l01 (even) and l03 (jittered) in the fast
regime and of l02 (a logger's uneven times) and l07 (even) in the slow one; each catalog
and two-effect record against the declared netlist carrying the catalog's own patch
(circuitsim.loop.effects.candidates, through crosscheck.truth_patch) at the truth's
expected values, on that record's times; and every outside record as circuitsim's
components state it:

- the propeller's ventilation: the declared `Prop` and `Thrust` torques replaced by the same
  laws times 1 - depth s(t), s switched on and off by relations of the time;
- the flooded motor's churning: a behavioural torque -cw rotor.w abs(rotor.w) on the rotor;
- the towed tender: a body `tender` with its inertia, its drag and the rope's tension
  kr s log(1 + exp((hull.phi - tender.phi - L0)/s)) as behavioural torques, the hull taking
  the tension's reaction;
- the head sea: the declared `Prop` and `Thrust` torques replaced by the same laws with the
  inflow hull.w + Wo sin(2 pi f0 t + kx hull.phi + psi).

Every probe of the regime is compared, also on the records that give the diagnosis one
probe only (their CSV holds that one; the model behind it is the same).

    python benchmarks/diagnosis/validate_w.py            # every record
    python benchmarks/diagnosis/validate_w.py l04,l13    # some

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
import simulators_w as sw
from make_records_w import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_w.yaml",
            "slow": HERE / "netlists" / "motor_w_slow.yaml"}
TARGET = 1e-6
NULL_ON = ("l01", "l02", "l03", "l07")


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw`` as a patch's part."""
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def _drop(raw: Any, name: str) -> None:
    """Remove the component ``name`` from ``raw``."""
    raw.comps = [c for c in raw.comps if str(c[0]["name"]) != name]


def _propeller(raw: Any, inflow: str, factor: str) -> None:
    """The declared propeller laws ``Prop`` and ``Thrust`` replaced by the same laws with
    the propeller's ``inflow`` [rad/s] in place of hull.w, both times ``factor`` [1]."""
    _drop(raw, "Prop")
    _drop(raw, "Thrust")
    _add(raw, {"name": "PropX", "type": "btorque", "shaft": "prop",
               "expr": f"-{factor}*cq*abs(prop.w)*(prop.w - {inflow})"})
    _add(raw, {"name": "ThrustX", "type": "btorque", "shaft": "hull",
               "expr": f"{factor}*ct*abs(prop.w)*(lam*prop.w - {inflow})"})


def ventilation(raw: Any, fx: dict) -> None:
    """The propeller's torque and thrust times 1 - depth s(t), switched by relations of the
    time."""
    t0, t1, te, depth = fx["vent"]
    rise = (f"(t >= {t0!r}[s])*(t < {t0 + te!r}[s])"
            f"*sin(pi/2*(t - {t0!r}[s])/{te!r}[s])^2")
    hold = f"(t >= {t0 + te!r}[s])*(t <= {t1!r}[s])"
    fall = (f"(t > {t1!r}[s])*(t <= {t1 + te!r}[s])"
            f"*cos(pi/2*(t - {t1!r}[s])/{te!r}[s])^2")
    _propeller(raw, "hull.w", f"(1 - {depth!r}*({rise} + {hold} + {fall}))")


def churning(raw: Any, fx: dict) -> None:
    """The water in the motor's can: -cw w |w| on the rotor."""
    _add(raw, {"name": "Churn", "type": "btorque", "shaft": "rotor",
               "expr": f"-{fx['churn']!r}*rotor.w*abs(rotor.w)"})


def tender(raw: Any, fx: dict) -> None:
    """The tender as its own body, its drag, and the rope's tension between it and the
    hull."""
    jt, kr, l0, s, cht = fx["tender"]
    rope = f"{kr * s!r}*log(1 + exp((hull.phi - tender.phi - {l0!r})/{s!r}))"
    _add(raw, {"name": "Jt", "type": "inertia", "shaft": "tender", "J": jt})
    _add(raw, {"name": "RopeT", "type": "btorque", "shaft": "tender",
               "expr": f"{rope} - {cht!r}*tender.w*abs(tender.w)"})
    _add(raw, {"name": "RopeH", "type": "btorque", "shaft": "hull", "expr": f"-{rope}"})


def head_sea(raw: Any, fx: dict) -> None:
    """The waves' orbital velocity in the propeller's inflow."""
    wo, f0, kx, psi = fx["wave"]
    inflow = (f"(hull.w + {wo!r}*sin({2.0 * f0!r}*pi*t/1[s] + {kx!r}*hull.phi/1[rad] "
              f"+ {psi!r}))")
    _propeller(raw, inflow, "1")


OUTSIDE_LAWS = {"vent": ventilation, "churn": churning, "tender": tender, "wave": head_sea}


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor W's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=sw.simulate,
                          PROBES=sw.PROBES)
    return crosscheck.compare(cs, sim, "W", sw.MOTOR_W, NETLISTS, s["regime"], label, fx,
                              raw, values)


def catalog(cs: Any, s: dict) -> float:
    """A catalog or two-effect record through the catalog's own patch."""
    regime = s["regime"]
    raw, values = crosscheck.truth_patch(cs.load(NETLISTS[regime]), s["effects"],
                                         sw.PROBES[regime], sw.REGIMES[regime][1])
    # the id and class only: the effects stay in truth.json (the set is blind)
    return compare(cs, s, f"{s['id']} {s['class']}, the catalog's patch", s["fx"], raw,
                   values)


def outside(cs: Any, s: dict) -> float:
    """An outside record rebuilt from circuitsim's components."""
    raw = cs.load(NETLISTS[s["regime"]]).raw.copy()
    law = next(f for k, f in OUTSIDE_LAWS.items() if k in s["fx"])
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


def main() -> int:
    """Every record of fresh22; exit status 1 above TARGET."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    return crosscheck.check_records(cs, record_specs(), times, scale_marginal, check, TARGET,
                                    sys.argv[1:2])


if __name__ == "__main__":
    sys.exit(main())
