"""Cross-check of motor X on the records' own times: the noise-free null output of
simulators_x.py against circuitsim's simulation of the declared netlists (motor_x_fast.yaml,
motor_x_slow.yaml), on the times of aa01 (even) and aa03 (jittered) in the fast regime and
of aa02 (a logger's uneven times) and aa05 (even) in the slow one; each catalog and
two-effect record against the declared netlist carrying the catalog's own patch
(circuitsim.loop.effects.candidates, through crosscheck.truth_patch) at the truth's
expected values, on that record's times; and the outside records as circuitsim's
components state them:

- the upper frame's seal: a behavioural torque -dT (1 + tanh((pane.phi - th1)/wth))/2
  tanh(pane.w/0.01) on the pane;
- the alternator's ripple through the bridge's duty: a behavioural voltage a.v (a1 sin(2 pi
  f t) + a2 sin(4 pi f t + psi2))/U in series between the source and `Ra`;
- the seals' dwell stiction: the freshness u as the speed of a body `age` of 1 kg m^2 driven
  by a behavioural torque -u/tau + (1 - u) abs(pane.w)/D (everything rests at t = 0, so
  u(0) = 0), and a behavioural torque -dT (1 - u) tanh(pane.w/0.01) on the pane;
- the worm's mesh efficiency (aa11), on a drum all but massless (the worm wheel's and the
  drum's Jd set to 1e-12 kg m^2 in both models, as circuitsim wants an inertia on every
  shaft: the declared Jd / N^2 is 0.03 % of Jm; with it gone the wheel's demand is the
  cable's torque Tk to 1e-9): the declared lossless `gear` and a behavioural torque
  -(s/eta_f + (1 - s) eta_b - 1) Tk / N on the rotor, s = (1 + tanh(Tk drum.w / P0))/2.
  No component states the law with the drum's inertia (circuitsim's `gear` has one `eta`
  for both directions of power flow, and its sharp switch stalls IDA where the pane, hanging
  on the worm at rest, creeps through zero speed: "mxstep steps taken" at the first start).

Both netlists must declare the same motor: their parameters and all components but the
source are compared first.

    python benchmarks/diagnosis/validate_x.py              # every record
    python benchmarks/diagnosis/validate_x.py aa04,aa14    # some

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
import simulators_x as sx
from make_records_x import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_x_fast.yaml",
            "slow": HERE / "netlists" / "motor_x_slow.yaml"}
SOURCES = {"fast": "Vin", "slow": "U"}
TARGET = 1e-6
NULL_ON = ("aa01", "aa02", "aa03", "aa05")
#: [kg m^2] the drum's inertia in aa11's check (circuitsim wants one on every shaft)
JD_TINY = 1e-12


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw`` as a patch's part."""
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def _drop(raw: Any, name: str) -> None:
    """Remove the component ``name`` from ``raw``."""
    raw.comps = [c for c in raw.comps if str(c[0]["name"]) != name]


def header_seal(raw: Any, fx: dict) -> None:
    """The upper frame seal's friction, switched on by the pane's height."""
    dt, th1, wth = fx["header"]
    _add(raw, {"name": "Header", "type": "btorque", "shaft": "pane",
               "expr": f"-{dt!r}[N*m]*0.5*(1 + tanh((pane.phi - {th1!r}[rad])/{wth!r}[rad]))"
                       f"*tanh(pane.w/0.01[rad/s])"})


def alternator(raw: Any, fx: dict) -> None:
    """The supply's ripple times the duty: a behavioural voltage between the source's node
    ``a`` and a new node ``a2`` that feeds ``Ra``."""
    big_u, a1, f, a2, psi2 = fx["ripple"]
    _drop(raw, "Ra")
    _add(raw, {"name": "Ra", "type": "R", "p": "a2", "n": "m1", "R": sx.MOTOR_X["R"]})
    ripple = (f"({a1!r}*sin({2.0 * f!r}*pi*t/1[s]) + {a2!r}*sin({4.0 * f!r}*pi*t/1[s] "
              f"+ {psi2!r}))/{big_u!r}")
    _add(raw, {"name": "Ripple", "type": "BV", "p": "a2", "n": "a", "expr": f"a.v*{ripple}"})


def dwell(raw: Any, fx: dict) -> None:
    """The seals' freshness as a body's speed, and the friction it takes away."""
    dt, tau, dist = fx["dwell"]
    _add(raw, {"name": "Jage", "type": "inertia", "shaft": "age", "J": 1.0})
    _add(raw, {"name": "Aging", "type": "btorque", "shaft": "age",
               "expr": f"1[N*m*s^2/rad]*(-age.w/{tau!r}[s] + (1[rad/s] - age.w)*abs(pane.w)"
                       f"/{dist!r}[rad])"})
    _add(raw, {"name": "Grip", "type": "btorque", "shaft": "pane",
               "expr": f"-{dt!r}[N*m]*(1 - age.w/1[rad/s])*tanh(pane.w/0.01[rad/s])"})


def worm(raw: Any, fx: dict) -> None:
    """The worm mesh's loss as a torque on the rotor, on a massless drum."""
    eta_f, eta_b, p0 = fx["worm"]
    _drop(raw, "Jd")
    _add(raw, {"name": "Jd", "type": "inertia", "shaft": "drum", "J": JD_TINY})
    tk = "(c*(drum.phi - pane.phi) + d*(drum.w - pane.w))"
    s = f"0.5*(1 + tanh({tk}*drum.w/1[rad/s]/{p0!r}[N*m]))"
    _add(raw, {"name": "Mesh", "type": "btorque", "shaft": "rotor",
               "expr": f"-({s}/{eta_f!r} + (1 - {s})*{eta_b!r} - 1)*{tk}/N"})


OUTSIDE_LAWS = {"header": header_seal, "ripple": alternator, "dwell": dwell, "worm": worm}


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor X's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=sx.simulate,
                          PROBES=sx.PROBES)
    return crosscheck.compare(cs, sim, "X", sx.MOTOR_X, NETLISTS, s["regime"], label, fx,
                              raw, values)


def catalog(cs: Any, s: dict) -> float:
    """A catalog or two-effect record through the catalog's own patch."""
    regime = s["regime"]
    raw, values = crosscheck.truth_patch(cs.load(NETLISTS[regime]), s["effects"],
                                         sx.PROBES[regime], sx.REGIMES[regime][1])
    # the id and class only: the effects stay in truth.json (the set is blind)
    return compare(cs, s, f"{s['id']} {s['class']}, the catalog's patch", s["fx"], raw,
                   values)


def outside(cs: Any, s: dict) -> float:
    """An outside record rebuilt from circuitsim's components (aa11 on a drum all but massless)."""
    key, law = next((k, f) for k, f in OUTSIDE_LAWS.items() if k in s["fx"])
    raw = cs.load(NETLISTS[s["regime"]]).raw.copy()
    law(raw, s["fx"])
    if key == "worm":
        return compare(cs, s, f"{s['id']} outside, as components, drum 1e-12 kg m^2",
                       {**s["fx"], "p": {"Jd": JD_TINY}}, raw)
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
    print(f"motor X: the fast and slow netlists declare the same motor: {same}")
    return same


def main() -> int:
    """Every record of fresh23; exit status 1 above TARGET (or if the netlists differ)."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    same = same_motor(cs)
    status = crosscheck.check_records(cs, record_specs(), times, scale_marginal, check,
                                      TARGET, sys.argv[1:2])
    return status if same else 1


if __name__ == "__main__":
    sys.exit(main())
