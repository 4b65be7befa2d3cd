"""Cross-check of motor U on the records' own times: the noise-free null output of
simulators_u.py against circuitsim's simulation of the declared netlists (motor_u.yaml,
fast; motor_u_slow.yaml, slow), on the times of j01 (even) and j05 (jittered) in the fast
regime and of j02 (a logger's uneven times) and j04 (even) in the slow one; each catalog
and two-effect record against the declared netlist carrying the catalog's own patch
(circuitsim.loop.effects.candidates, through crosscheck.truth_patch) at the truth's
expected values, on that record's times; and every outside record as circuitsim's
components state it:

- the terminal leakage: a resistor across the supply's terminals, the current's probe the
  armature's current plus the resistor's;
- the logger's fast clock: circuitsim's declared model run at the true times t / (1 + eps)
  of the record's stamps t;
- the direction-blind tachometer: the brush speed's probe rewritten as abs(brush.w);
- the bristles' presliding friction: the declared `friction` replaced by a behavioural
  torque -F on the brush, F the voltage of a 1 F capacitor charged by a behavioural current
  sigma (w - sqrt(w^2 + eps^2) F / Tf) (1 V per N m);
- the shared battery's sag: a behavioural source in series with the armature taking the
  command's share of the bus's drop, u drop(t) / Vbus, switched on at t0 by a relation of
  the time.

    python benchmarks/diagnosis/validate_u.py            # every record
    python benchmarks/diagnosis/validate_u.py j03,j13    # some

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
import simulators_u as su
from make_records_u import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_u.yaml",
            "slow": HERE / "netlists" / "motor_u_slow.yaml"}
TARGET = 1e-6
NULL_ON = ("j01", "j02", "j04", "j05")


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw`` as a patch's part."""
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def leakage(raw: Any, fx: dict) -> None:
    """A resistor Rp across the supply (a to gnd); the current's probe reads the
    armature's current plus the resistor's."""
    _add(raw, {"name": "RLK", "type": "R", "p": "a", "n": "gnd", "R": fx["leak"]})
    _, loc = raw.probes["current"]
    raw.probes["current"] = ("Ra.i + RLK.i", loc)


def direction_blind(raw: Any, fx: dict) -> None:
    """The probe ``fx["absread"]`` reads the magnitude of the brush's speed."""
    _, loc = raw.probes[fx["absread"]]
    raw.probes[fx["absread"]] = ("abs(brush.w)", loc)


def bristles(raw: Any, fx: dict) -> None:
    """The declared floor friction ``Ff`` replaced by Dahl's: the brush takes -F, F the
    voltage of a 1 F capacitor (1 V per N m) charged by sigma (w - sqrt(w^2 + eps^2) F /
    Tf) (1 A per N m/s)."""
    sigma, eps = fx["dahl"]
    tf = su.MOTOR_U["Tf"]
    raw.comps = [c for c in raw.comps if str(c[0]["name"]) != "Ff"]
    w = "brush.w/1[rad/s]"
    f = "dahl_f.v/1[V]"
    _add(raw, {"name": "DAI", "type": "BI", "p": "gnd", "n": "dahl_f",
               "expr": f"{sigma!r}*({w} - sqrt(({w})^2 + {eps * eps!r})*{f}/{tf!r})*1[A]"})
    _add(raw, {"name": "DAC", "type": "C", "p": "dahl_f", "n": "gnd", "C": 1.0, "v0": 0.0})
    _add(raw, {"name": "DAT", "type": "btorque", "shaft": "brush", "expr": f"-{f}*1[N*m]"})


def battery_sag(raw: Any, fx: dict) -> None:
    """A behavioural source in series with the armature drops the command's share of the
    bus's drop, a.v (dV + dVin exp(-(t - t0)/tau)) / Vbus from t0 on."""
    from circuitsim.loop.effects import insert_series

    t0, dv, dvin, tau, vbus = fx["vac"]
    drop = f"({dv!r} + {dvin!r}*exp(-(t - {t0!r}[s])/{tau!r}[s]))"
    insert_series(raw, "Ra", "VAC", f"a.v*(t >= {t0!r}[s])*{drop}/{vbus!r}")


OUTSIDE_LAWS = {"leak": leakage, "absread": direction_blind, "dahl": bristles,
                "vac": battery_sag}


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor U's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=su.simulate,
                          PROBES=su.PROBES)
    return crosscheck.compare(cs, sim, "U", su.MOTOR_U, NETLISTS, s["regime"], label, fx,
                              raw, values)


def clock(cs: Any, s: dict) -> float:
    """The fast clock: circuitsim's declared model at the true times t / (1 + eps), the
    scipy model at the stamps t."""
    eps = s["fx"]["clock"]

    def stamped(regime: str, t: Any, fx: dict | None = None, p: Any = None) -> dict:
        """The scipy model's probes at the true times ``t`` [s], stamped t (1 + eps)."""
        return su.simulate(regime, t * (1.0 + eps), fx, p)

    sim = SimpleNamespace(grid=lambda regime: times(s) / (1.0 + eps), simulate=stamped,
                          PROBES=su.PROBES)
    return crosscheck.compare(cs, sim, "U", su.MOTOR_U, NETLISTS, s["regime"],
                              f"{s['id']} outside, at the true times", s["fx"])


def catalog(cs: Any, s: dict) -> float:
    """A catalog or two-effect record through the catalog's own patch."""
    regime = s["regime"]
    raw, values = crosscheck.truth_patch(cs.load(NETLISTS[regime]), s["effects"],
                                         su.PROBES[regime], su.REGIMES[regime][1])
    # the id and class only: the effects stay in truth.json (the set is blind)
    return compare(cs, s, f"{s['id']} {s['class']}, the catalog's patch", s["fx"], raw,
                   values)


def outside(cs: Any, s: dict) -> float:
    """An outside record rebuilt from circuitsim's components."""
    if "clock" in s["fx"]:
        return clock(cs, s)
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
    """Every record of fresh20; exit status 1 above TARGET."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    return crosscheck.check_records(cs, record_specs(), times, scale_marginal, check, TARGET,
                                    sys.argv[1:2])


if __name__ == "__main__":
    sys.exit(main())
