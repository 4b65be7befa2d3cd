"""Cross-check of motor L on the records' own uneven times: the noise-free null output of
simulators_l.py against circuitsim's simulation of the declared netlists (motor_l.yaml,
fast; motor_l_slow.yaml, slow), on the times of a null record of each regime; each catalog
and two-effect record against the declared netlist carrying the catalog's own patch
(circuitsim.loop.effects.candidates, through crosscheck.truth_patch) at the truth's expected
values, on that record's times; and the outside records whose law circuitsim's components
can state (the raised commutator bar as a behavioural voltage in series with the armature,
the advanced brush timing as a behavioural voltage and a behavioural torque, the cutting
load as a behavioural torque, the creeping belt as two behavioural torques in place of the
rigid `gear`). The speed computed from encoder counts (a law of the
logger's reading over its own intervals) has no component and is not compared.

    PYTHONPATH=<circuitsim checkout> python benchmarks/diagnosis/validate_l.py

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
import simulators_l as sl
from make_records_l import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_l.yaml",
            "slow": HERE / "netlists" / "motor_l_slow.yaml"}
TARGET = 1e-5
P = sl.MOTOR_L


# ---------------------------------------------------------------------- outside laws

def _series(raw: Any, target: str, name: str, expr: str) -> None:
    from circuitsim.loop.effects import insert_series

    insert_series(raw, target, name, expr)


def _add(raw: Any, entry: dict) -> None:
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def bar(raw: Any, fx: dict) -> None:
    """R a exp(kappa (cos(2 (th - phase)) - 1)) i in series with the armature's resistor."""
    a, kappa, ph = fx["bar"]
    _series(raw, "Ra", "BAR", f"R*{a!r}*exp({kappa!r}*(cos(2*(rotor.phi - {ph!r})) - 1))"
                              "*Ra.i")


def timing(raw: Any, fx: dict) -> None:
    """k (1 - delta tanh(w/w0)): an EMF -delta k tanh(w/w0) w in series with M and a torque
    -delta k tanh(w/w0) i on the rotor."""
    delta, w0 = fx["timing"]
    shape = f"{delta!r}*k*tanh(rotor.w/{w0!r}[rad/s])"
    _series(raw, "M", "TIM", f"-{shape}*rotor.w")
    _add(raw, {"name": "TIT", "type": "btorque", "shaft": "rotor", "expr": f"-{shape}*Ra.i"})


def cut(raw: Any, fx: dict) -> None:
    """-T g(t) tanh(ws / 1 rad/s) on the spindle."""
    tc, t1, t2, tr = fx["cut"]
    g = (f"(tanh((t - {t1!r}[s])/{tr!r}[s]) - tanh((t - {t2!r}[s])/{tr!r}[s]))/2")
    _add(raw, {"name": "CUT", "type": "btorque", "shaft": "spindle",
               "expr": f"-{tc!r}[N*m]*{g}*tanh(spindle.w/{sl.W_CUT!r}[rad/s])"})


def creep(raw: Any, fx: dict) -> None:
    """The rigid belt G replaced by the creeping one: the spindle receives c (w/N - ws),
    the rotor that torque over N, against its motion (two behavioural torques)."""
    raw.comps = [c for c in raw.comps if c[0].get("name") != "G"]
    belt = f"{fx['creep']!r}[N*m*s/rad]*(rotor.w/N - spindle.w)"
    _add(raw, {"name": "BLS", "type": "btorque", "shaft": "spindle", "expr": belt})
    _add(raw, {"name": "BLR", "type": "btorque", "shaft": "rotor", "expr": f"-{belt}/N"})


OUTSIDE_LAWS = {"bar": bar, "timing": timing, "cut": cut, "creep": creep}


# ---------------------------------------------------------------------- comparison

def on_times(t: Any) -> SimpleNamespace:
    """simulators_l seen through crosscheck.compare, its grid being the times ``t`` [s]."""
    return SimpleNamespace(grid=lambda regime: t, simulate=sl.simulate, PROBES=sl.PROBES)


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor L's scipy model against circuitsim at the record's own times."""
    return crosscheck.compare(cs, on_times(times(s)), "L", P, NETLISTS, s["regime"],
                              label, fx, raw, values)


def check(cs: Any, s: dict) -> float:
    """One record's comparison (the worst difference over a probe's range), or 0."""
    regime = s["regime"]
    if s["class"] == "null":
        return compare(cs, s, f"{s['id']} null (its times)", {})
    if s["class"] in ("catalog", "two"):
        raw, values = crosscheck.truth_patch(cs.load(NETLISTS[regime]), s["effects"],
                                             sl.PROBES[regime], sl.REGIMES[regime][1])
        # the id and class only: the effects stay in truth.json (the set is blind)
        return compare(cs, s, f"{s['id']} {s['class']}, the catalog's patch", s["fx"], raw,
                       values)
    law = next((f for k, f in OUTSIDE_LAWS.items() if k in s["fx"]), None)
    if law is None:
        print(f"motor L {regime:4s} {s['id']} outside: no component states its law "
              "(not compared)")
        return 0.0
    raw = cs.load(NETLISTS[regime]).raw.copy()
    law(raw, s["fx"])
    return compare(cs, s, f"{s['id']} outside, as components", s["fx"], raw)


def main() -> int:
    """Every record of fresh11 that a netlist can state; exit status 1 above TARGET."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    worst = 0.0
    for s in record_specs():
        if s["marginal"] is not None:
            scale_marginal(s)
        worst = max(worst, check(cs, s))
    print(f"worst max |diff|/range {worst:.2e} -> {'OK' if worst < TARGET else 'ABOVE'} "
          f"(target {TARGET:g})")
    return 0 if worst < TARGET else 1


if __name__ == "__main__":
    sys.exit(main())
