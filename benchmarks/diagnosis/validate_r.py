"""Cross-check of motor R on the records' own times: the noise-free null output of
simulators_r.py against circuitsim's simulation of the declared netlists (motor_r.yaml,
fast; motor_r_slow.yaml, slow), on the times of z01 (even) and z05 (jittered) in the fast
regime and of z02 (a logger's uneven times) and z07 (even) in the slow one; each catalog
and two-effect record against the declared netlist carrying the catalog's own patch
(circuitsim.loop.effects.candidates, through crosscheck.truth_patch) at the truth's
expected values, on that record's times; and every outside record circuitsim's components
can state, as they state it (the self-heating current shunt as a thermal RC driven by a
behavioural current i^2 Rsh, read into the current's probe; the yoke's eddy currents as
the armature's inductance cut down and an inductor in parallel with a resistor in series
with it; the bridge's duty limit as a behavioural source clamp(u, -Umax, Umax) after the
command's own; the rail's splice as a behavioural torque of the door's angle and speed,
IDA's step bounded by the output step so that it does not stride over the bump).
The frozen seal's bond, which breaks for good, has no component: z10 is not compared.

    python benchmarks/diagnosis/validate_r.py            # every record
    python benchmarks/diagnosis/validate_r.py z03,z14    # some

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
import simulators_r as sr
from make_records_r import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_r.yaml",
            "slow": HERE / "netlists" / "motor_r_slow.yaml"}
TARGET = 1e-5
NULL_ON = ("z01", "z02", "z05", "z07")


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw`` as a patch's part."""
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def _source(raw: Any) -> dict:
    """The command's voltage source's entry."""
    return next(e for e, _, _ in raw.comps if e["name"] in ("U", "Vin"))


def shunt(raw: Any, fx: dict) -> None:
    """A thermal RC (1 V per kelvin: Cth farads, Rth ohms) fed by a behavioural current
    i^2 Rsh; the current's probe reads i (1 + a T)."""
    rsh, rth, cth, a = fx["shunt"]
    _add(raw, {"name": "QSH", "type": "BI", "p": "gnd", "n": "trace",
               "expr": f"{rsh!r}*Ra.i^2/1[A]"})
    _add(raw, {"name": "CTH", "type": "C", "p": "trace", "n": "gnd", "C": cth, "v0": 0.0})
    _add(raw, {"name": "RTH", "type": "R", "p": "trace", "n": "gnd", "R": rth})
    text, loc = raw.probes["current"]
    raw.probes["current"] = (f"({text})*(1 + {a!r}*trace.v/1[V])", loc)


def eddy(raw: Any, fx: dict) -> None:
    """The armature's inductance La - L2, then L2 || Re, in series."""
    l2, re = fx["eddy"]
    la = raw.component_entry("La")
    la["L"] = sr.MOTOR_R["L"] - l2
    la["n"] = "yoke"
    _add(raw, {"name": "LE", "type": "L", "p": "yoke", "n": "m2", "L": l2})
    _add(raw, {"name": "RE", "type": "R", "p": "yoke", "n": "m2", "R": re})


def clip(raw: Any, fx: dict) -> None:
    """The command's source drives a node of its own; a behavioural source puts
    clamp(u, -Umax, Umax) on the armature."""
    top = fx["clip"]
    _source(raw)["p"] = "cmd"
    _add(raw, {"name": "RCMD", "type": "R", "p": "cmd", "n": "gnd", "R": 1e3})
    _add(raw, {"name": "DRV", "type": "BV", "p": "a", "n": "gnd",
               "expr": f"clamp(cmd.v, -{top!r}, {top!r})"})


def splice(raw: Any, fx: dict) -> None:
    """The door takes -Tb exp(-((phi - th0)/wb)^2) tanh(w/0.01); IDA's step is bounded by
    the 4 ms output step (``max_step``), else it strides over the 50 ms bump while the door
    cruises."""
    tb, th0, wb = fx["splice"]
    _add(raw, {"name": "SPLICE", "type": "btorque", "shaft": "door",
               "expr": f"-{tb!r}*exp(-((door.phi - {th0!r})/{wb!r})^2)*tanh(door.w/0.01)"})
    _, loc = raw.analysis["step"]
    raw.analysis["max_step"] = ("4 ms", loc)


OUTSIDE_LAWS = {"shunt": shunt, "eddy": eddy, "clip": clip, "splice": splice}


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor R's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=sr.simulate,
                          PROBES=sr.PROBES)
    return crosscheck.compare(cs, sim, "R", sr.MOTOR_R, NETLISTS, s["regime"], label, fx,
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
                                             sr.PROBES[regime], sr.REGIMES[regime][1])
        # the id and class only: the effects stay in truth.json (the set is blind)
        worst = max(worst, compare(cs, s, f"{s['id']} {s['class']}, the catalog's patch",
                                   s["fx"], raw, values))
    elif s["class"] == "outside":
        law = next((f for k, f in OUTSIDE_LAWS.items() if k in s["fx"]), None)
        if law is None:
            print(f"motor R {regime:4s} {s['id']} outside: no component states its law (not "
                  "compared)", flush=True)
            return worst
        raw = cs.load(NETLISTS[regime]).raw.copy()
        law(raw, s["fx"])
        worst = max(worst, compare(cs, s, f"{s['id']} outside, as components", s["fx"], raw))
    return worst


def main() -> int:
    """Every record of fresh17; exit status 1 above TARGET."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    return crosscheck.check_records(cs, record_specs(), times, scale_marginal, check, TARGET,
                                    sys.argv[1:2])


if __name__ == "__main__":
    sys.exit(main())
