"""Cross-check of motor O on the records' own times: the noise-free null output of
simulators_o.py against circuitsim's simulation of the declared netlists (motor_o.yaml,
fast; motor_o_slow.yaml, slow), on the times of w01 (even) and w03 (jittered) in the fast
regime and of w02 (a logger's uneven times) and w07 (even) in the slow one; each catalog
and two-effect record against the declared netlist carrying the catalog's own patch
(circuitsim.loop.effects.candidates, through crosscheck.truth_patch) at the truth's
expected values, on that record's times; and every outside record as circuitsim's
components state it (the plungers' pulsation, the relief valve and the air-bound start as
behavioural torques on the crank, the missing tooth as the speed probe's law, the weak
battery as a 250 F capacitor chopped by a behavioural source).

    python benchmarks/diagnosis/validate_o.py            # every record
    python benchmarks/diagnosis/validate_o.py w03,w13    # some

Prints, per probe, the largest difference relative to the signal's range at the record's
sample times, and the effect's own size on that scale. Target 1e-5 of the range; exit
status 1 above it. Nothing here runs a diagnosis.
"""

from __future__ import annotations

import math
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
import simulators_o as so
from make_records_o import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_o.yaml",
            "slow": HERE / "netlists" / "motor_o_slow.yaml"}
TARGET = 1e-5
NULL_ON = ("w01", "w02", "w03", "w07")
#: the declared pressure load's expression (motor_o_motor.yaml)
Q = "cq*crank.w*abs(crank.w)"


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw`` as a patch's part."""
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def pulse(raw: Any, fx: dict) -> None:
    """The crank receives -kappa q (S^3/<S^3> - 1), S the plungers' summed rate."""
    s = " + ".join(f"max(0, sin(crank.phi - {2.0 * math.pi * j / 3.0!r}))" for j in range(3))
    _add(raw, {"name": "PUL", "type": "btorque", "shaft": "crank",
               "expr": f"-{fx['pulse']!r}*{Q}*(({s})^3/{so.S3_MEAN!r} - 1)"})


def relief(raw: Any, fx: dict) -> None:
    """The crank gets back (1 - s)(sp(q - Tc) - sp(-q - Tc)) of the declared load q."""
    tc, s, dl = fx["relief"]

    def sp(y: str) -> str:
        return f"{dl!r}*log(1 + exp(({y})/{dl!r}))"

    _add(raw, {"name": "REL", "type": "btorque", "shaft": "crank",
               "expr": f"{1.0 - s!r}*({sp(f'{Q} - {tc!r}')} - {sp(f'-{Q} - {tc!r}')})"})


def prime(raw: Any, fx: dict) -> None:
    """The crank gets back (1 - alpha(thp)) of the declared load q."""
    a0, th1, dth = fx["prime"]
    alpha = f"({a0!r} + {1.0 - a0!r}*(1 + tanh((crank.phi - {th1!r})/{dth!r}))/2)"
    _add(raw, {"name": "PRM", "type": "btorque", "shaft": "crank",
               "expr": f"{Q}*(1 - {alpha})"})


def tooth(raw: Any, fx: dict) -> None:
    """The speed probe reads w (1 - G/2) of the rotor's angle."""
    thc, width, kappa = fx["tooth"]
    text, loc = raw.probes["speed"]
    g = f"(1 + tanh({kappa!r}*(cos(rotor.phi - {thc!r}) - {math.cos(0.5 * width)!r})))/2"
    raw.probes["speed"] = (f"({text})*(1 - {g}/2)", loc)


def battery(raw: Any, fx: dict) -> None:
    """The command's source drives a node of its own; the armature gets u v_bat/Vnom from
    a behavioural source, and the battery (a capacitor 1/kq charged to V0) gives u i/Vnom."""
    v0, kq, vnom = fx["battery"]
    src = next(e for e, _, _ in raw.comps if e["name"] in ("U", "Vin"))
    src["p"] = "cmd"
    _add(raw, {"name": "RCMD", "type": "R", "p": "cmd", "n": "gnd", "R": 1e3})
    _add(raw, {"name": "DRV", "type": "BV", "p": "a", "n": "gnd",
               "expr": f"cmd.v*bat.v/{vnom!r}[V]"})
    _add(raw, {"name": "CBAT", "type": "C", "p": "bat", "n": "gnd", "C": 1.0 / kq, "v0": v0})
    _add(raw, {"name": "IBAT", "type": "BI", "p": "bat", "n": "gnd",
               "expr": f"cmd.v/{vnom!r}[V]*Ra.i"})


OUTSIDE_LAWS = {"pulse": pulse, "relief": relief, "prime": prime, "tooth": tooth,
                "battery": battery}


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor O's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=so.simulate,
                          PROBES=so.PROBES)
    return crosscheck.compare(cs, sim, "O", so.MOTOR_O, NETLISTS, s["regime"], label, fx,
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
                                             so.PROBES[regime], so.REGIMES[regime][1])
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
    """Every record of fresh14; exit status 1 above TARGET."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    return crosscheck.check_records(cs, record_specs(), times, scale_marginal, check, TARGET,
                                    sys.argv[1:2])


if __name__ == "__main__":
    sys.exit(main())
