"""Cross-check of motor Q on the records' own times: the noise-free null output of
simulators_q.py against circuitsim's simulation of the declared netlists (motor_q.yaml,
fast; motor_q_slow.yaml, slow), on the times of y01 (even) and y03 (jittered) in the fast
regime and of y02 (a logger's uneven times) and y06 (even) in the slow one; each catalog
and two-effect record against the declared netlist carrying the catalog's own patch
(circuitsim.loop.effects.candidates, through crosscheck.truth_patch) at the truth's
expected values, on that record's times; and every outside record as circuitsim's
components state it (the battery's polarisation as a resistor and a capacitor in parallel
between the source and the armature, the slipping tyres as the wheels' inertia cut down
and a cart-body inertia pushed by a behavioural torque pair, the throttle's dead zone as a
behavioural source after the command's own, the sloshing liquid as an inertia on a
spring_damper with the wheels' inertia cut down, the ramp as a behavioural torque of the
wheels' angle).

    python benchmarks/diagnosis/validate_q.py            # every record
    python benchmarks/diagnosis/validate_q.py y03,y14    # some

Prints, per probe, the largest difference relative to the signal's range at the record's
sample times, and the effect's own size on that scale. Target 1e-5 of the range; exit
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
import simulators_q as sq
from make_records_q import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_q.yaml",
            "slow": HERE / "netlists" / "motor_q_slow.yaml"}
TARGET = 1e-5
NULL_ON = ("y01", "y02", "y03", "y06")


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw`` as a patch's part."""
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def _source(raw: Any) -> dict:
    """The command's voltage source's entry."""
    return next(e for e, _, _ in raw.comps if e["name"] in ("U", "Vin"))


def _set_inertia(raw: Any, name: str, value: float) -> None:
    """The inertia component ``name`` given the value ``value`` [kg m^2]."""
    comp = next(e for e, _, _ in raw.comps if e["name"] == name)
    comp["J"] = value


def polar(raw: Any, fx: dict) -> None:
    """The source drives a node of its own; Rp and Cp in parallel join it to the armature."""
    rp, cp = fx["polar"]
    _source(raw)["p"] = "bat"
    _add(raw, {"name": "RP", "type": "R", "p": "bat", "n": "a", "R": rp})
    _add(raw, {"name": "CP", "type": "C", "p": "bat", "n": "a", "C": cp, "v0": 0.0})


def traction(raw: Any, fx: dict) -> None:
    """The wheels keep Jw; the cart body (Jv - Jw) is pushed by Tmax tanh(ks dw / Tmax)."""
    jw, tmax, ks = fx["traction"]
    _set_inertia(raw, "Jv", jw)
    push = f"{tmax!r}*tanh({ks!r}*(wheel.w - body.w)/{tmax!r})"
    _add(raw, {"name": "JB", "type": "inertia", "shaft": "body",
               "J": sq.MOTOR_Q["Jv"] - jw})
    _add(raw, {"name": "TRW", "type": "btorque", "shaft": "wheel", "expr": f"-{push}"})
    _add(raw, {"name": "TRB", "type": "btorque", "shaft": "body", "expr": push})


def deadband(raw: Any, fx: dict) -> None:
    """The command's source drives a node of its own; a behavioural source puts
    u - clamp(u, -db, db) on the armature."""
    db = fx["deadband"]
    _source(raw)["p"] = "cmd"
    _add(raw, {"name": "RCMD", "type": "R", "p": "cmd", "n": "gnd", "R": 1e3})
    _add(raw, {"name": "DRV", "type": "BV", "p": "a", "n": "gnd",
               "expr": f"cmd.v - clamp(cmd.v, -{db!r}, {db!r})"})


def slosh(raw: Any, fx: dict) -> None:
    """The wheels keep Jv - Js; the liquid Js hangs on them through a spring_damper."""
    js, cs, ds = fx["slosh"]
    _set_inertia(raw, "Jv", sq.MOTOR_Q["Jv"] - js)
    _add(raw, {"name": "JS", "type": "inertia", "shaft": "liquid", "J": js})
    _add(raw, {"name": "KS", "type": "spring_damper", "a": "wheel", "b": "liquid",
               "c": cs, "d": ds})


def grade(raw: Any, fx: dict) -> None:
    """The wheels take -Tg (1 + tanh((phi - th0)/dth))/2."""
    tg, th0, dth = fx["grade"]
    _add(raw, {"name": "RAMP", "type": "btorque", "shaft": "wheel",
               "expr": f"-0.5*{tg!r}*(1 + tanh((wheel.phi - {th0!r})/{dth!r}))"})


OUTSIDE_LAWS = {"polar": polar, "traction": traction, "deadband": deadband, "slosh": slosh,
                "grade": grade}


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor Q's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=sq.simulate,
                          PROBES=sq.PROBES)
    return crosscheck.compare(cs, sim, "Q", sq.MOTOR_Q, NETLISTS, s["regime"], label, fx,
                              raw, values)


def check(cs: Any, s: dict) -> float:
    """One record's comparisons: the null on its times (NULL_ON), and its effects as the
    catalog's patch or as components."""
    regime, worst = s["regime"], 0.0
    if s["id"] in NULL_ON:
        worst = compare(cs, s, f"null on {s['id']}'s {s['timestamps'].split(':')[0]} times",
                        {})
    if s["class"] in ("catalog", "two"):
        raw, values = crosscheck.truth_patch(cs.load(NETLISTS[regime]), s["effects"],
                                             sq.PROBES[regime], sq.REGIMES[regime][1])
        # the id and class only: the effects stay in truth.json (the set is blind)
        worst = max(worst, compare(cs, s, f"{s['id']} {s['class']}, the catalog's patch",
                                   s["fx"], raw, values))
    elif s["class"] == "outside":
        law = next(f for k, f in OUTSIDE_LAWS.items() if k in s["fx"])
        raw = cs.load(NETLISTS[regime]).raw.copy()
        law(raw, s["fx"])
        worst = max(worst, compare(cs, s, f"{s['id']} outside, as components", s["fx"], raw))
    return worst


def main() -> int:
    """Every record of fresh16; exit status 1 above TARGET."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    return crosscheck.check_records(cs, record_specs(), times, scale_marginal, check, TARGET,
                                    sys.argv[1:2])


if __name__ == "__main__":
    sys.exit(main())
