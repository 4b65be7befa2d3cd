"""Cross-check of motor P on the records' own times: the noise-free null output of
simulators_p.py against circuitsim's simulation of the declared netlists (motor_p.yaml,
fast; motor_p_slow.yaml, slow), on the times of x01 (even) and x03 (jittered) in the fast
regime and of x02 (a logger's uneven times) and x06 (even) in the slow one; each catalog
and two-effect record against the declared netlist carrying the catalog's own patch
(circuitsim.loop.effects.candidates, through crosscheck.truth_patch) at the truth's
expected values, on that record's times; and every outside record as circuitsim's
components state it (the high mica as a behavioural voltage in series with the armature,
the eddy drag and the leaking housing's windage as behavioural torques on the flywheel, the
drive's slew-rate limiter as a 1 F capacitor charged by a behavioural current, and the
current's sample-and-hold as circuitsim's current read at the hold instants).

    python benchmarks/diagnosis/validate_p.py            # every record
    python benchmarks/diagnosis/validate_p.py x03,x14    # some

Prints, per probe, the largest difference relative to the signal's range at the record's
sample times, and the effect's own size on that scale. Target 1e-5 of the range; exit
status 1 above it. Nothing here runs a diagnosis.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
import warnings
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import crosscheck
import simulators_p as sp
from make_records_p import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_p.yaml",
            "slow": HERE / "netlists" / "motor_p_slow.yaml"}
TARGET = 1e-5
NULL_ON = ("x01", "x02", "x03", "x06")


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw`` as a patch's part."""
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def mica(raw: Any, fx: dict) -> None:
    """A voltage Rm P(th) i in series with the armature's resistance."""
    from circuitsim.loop.effects import insert_series

    rm, order, kappa, phase = fx["mica"]
    pulse = f"exp({kappa!r}*(cos({order!r}*rotor.phi - {phase!r}) - 1))"
    insert_series(raw, "Ra", "MICA", f"{rm!r}*{pulse}*Ra.i")


def eddy(raw: Any, fx: dict) -> None:
    """The flywheel takes 2 Tp (wf/wc)/(1 + (wf/wc)^2) against its motion."""
    tp, wc = fx["eddy"]
    r = f"(fly.w/{wc!r})"
    _add(raw, {"name": "EDDY", "type": "btorque", "shaft": "fly",
               "expr": f"-2*{tp!r}*{r}/(1 + {r}^2)"})


def leak(raw: Any, fx: dict) -> None:
    """The flywheel takes bf (t / tau_l) wf more windage."""
    _add(raw, {"name": "LEAK", "type": "btorque", "shaft": "fly",
               "expr": f"-bf*fly.w*t/{fx['leak']!r}"})


def slew(raw: Any, fx: dict) -> None:
    """The command's source drives a node of its own; a 1 F capacitor charged by
    S tanh((u - v)/(S tau)) holds the drive's output v, which a behavioural source puts on
    the armature."""
    s, tau = fx["slew"]
    src = next(e for e, _, _ in raw.comps if e["name"] in ("U", "Vin"))
    src["p"] = "cmd"
    _add(raw, {"name": "RCMD", "type": "R", "p": "cmd", "n": "gnd", "R": 1e3})
    _add(raw, {"name": "CSL", "type": "C", "p": "slw", "n": "gnd", "C": 1.0, "v0": 0.0})
    _add(raw, {"name": "ISL", "type": "BI", "p": "gnd", "n": "slw",
               "expr": f"{s!r}*tanh((cmd.v - slw.v)/{s * tau!r})"})
    _add(raw, {"name": "DRV", "type": "BV", "p": "a", "n": "gnd", "expr": "slw.v"})


OUTSIDE_LAWS = {"mica": mica, "eddy": eddy, "leak": leak, "slew": slew}


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor P's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=sp.simulate,
                          PROBES=sp.PROBES)
    return crosscheck.compare(cs, sim, "P", sp.MOTOR_P, NETLISTS, s["regime"], label, fx,
                              raw, values)


def compare_hold(cs: Any, s: dict) -> float:
    """The held current reading: circuitsim's current at the hold instants, each sample
    taking the last of them, against the scipy model's reading."""
    t, regime, th = times(s), s["regime"], s["fx"]["hold"]
    ref = sp.simulate(regime, t, s["fx"])["current"]
    held = sp.hold_instants(t, th)
    grid, back = np.unique(held, return_inverse=True)
    t0 = time.perf_counter()
    res = cs.compile(cs.load(NETLISTS[regime])).simulate(
        stop=float(t[-1]), t_eval=np.union1d(grid, t), rtol=1e-10, atol=1e-12)
    t_cs = time.perf_counter() - t0
    run = np.union1d(grid, t)
    got = np.asarray(res["current"])[np.searchsorted(run, grid)][back]
    base = sp.simulate(regime, t)["current"]
    rng = float(np.ptp(got))
    mx = float(np.max(np.abs(ref - got)) / rng)
    print(f"motor P {regime:4s} {s['id'] + ' outside, held at the instants':52s} current   : "
          f"max |diff|/range {mx:.1e} (range {rng:.4g}; effect "
          f"{np.max(np.abs(ref - base)) / rng:.1e} of range; circuitsim {t_cs:.1f} s)",
          flush=True)
    return mx


def check(cs: Any, s: dict) -> float:
    """One record's comparisons: the null on its times (NULL_ON), and its effects as the
    catalog's patch or as components."""
    regime, worst = s["regime"], 0.0
    if s["id"] in NULL_ON:
        worst = compare(cs, s, f"null on {s['id']}'s {s['timestamps'].split(':')[0]} times",
                        {})
    if s["class"] in ("catalog", "two"):
        raw, values = crosscheck.truth_patch(cs.load(NETLISTS[regime]), s["effects"],
                                             sp.PROBES[regime], sp.REGIMES[regime][1])
        # the id and class only: the effects stay in truth.json (the set is blind)
        worst = max(worst, compare(cs, s, f"{s['id']} {s['class']}, the catalog's patch",
                                   s["fx"], raw, values))
    elif s["class"] == "outside" and "hold" in s["fx"]:
        worst = max(worst, compare_hold(cs, s))
    elif s["class"] == "outside":
        law = next(f for k, f in OUTSIDE_LAWS.items() if k in s["fx"])
        raw = cs.load(NETLISTS[regime]).raw.copy()
        law(raw, s["fx"])
        worst = max(worst, compare(cs, s, f"{s['id']} outside, as components", s["fx"], raw))
    return worst


def main() -> int:
    """Every record of fresh15; exit status 1 above TARGET."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    return crosscheck.check_records(cs, record_specs(), times, scale_marginal, check, TARGET,
                                    sys.argv[1:2])


if __name__ == "__main__":
    sys.exit(main())
