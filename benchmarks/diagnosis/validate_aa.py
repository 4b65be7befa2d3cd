"""Cross-check of motor AA on the records' own times: the noise-free null output of
simulators_aa.py against circuitsim's simulation of the declared netlists (motor_aa_fast.yaml,
motor_aa_slow.yaml), on the times of ad02 (even) and ad03 (jittered) in the fast regime and
of ad01 (a logger's uneven times) and ad07 (even) in the slow one; each catalog and
two-effect record against the declared netlist carrying the catalog's own patch
(through crosscheck.truth_patch) at the truth's expected values, on that record's times; and
the outside records as circuitsim's components state them:

- the synchroniser's RC lag: a behavioural voltage (`BV`) head.w 1[V*s/rad] feeding an RC
  (1 ohm, tau farad), the probe load_speed read on the capacitor;
- the tarnished connector's film: a behavioural voltage (`BV`)
  a La.i (La.i^2 + eps^2)^(-1/4) between Ra and La;
- the bent rotor shaft: the `emf` M with a harmonic of order 1 (slope k e, phase) acting on
  the torque too (`ripple_torque`);
- the dry bushing: a behavioural torque on the head, -T0 (1 + beta tb.v) tanh(head.w/0.01),
  its temperature rise the voltage tb.v of an electrical analogue of its heat network: a
  behavioural current (`BI`, its loss) into a capacitor C (its heat capacity) and a resistor
  1/G (its conductance to the casting).

Both netlists must declare the same motor: their parameters and all components but the
source are compared first.

    python benchmarks/diagnosis/validate_aa.py              # every record
    python benchmarks/diagnosis/validate_aa.py ad04,ad14    # some

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
import simulators_aa as sa
from make_records_aa import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_aa_fast.yaml",
            "slow": HERE / "netlists" / "motor_aa_slow.yaml"}
SOURCES = {"fast": "Vin", "slow": "U"}
TARGET = 1e-6
NULL_ON = ("ad01", "ad02", "ad03", "ad07")


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw`` as a patch's part."""
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def _rewire(raw: Any, name: str, **ports: Any) -> None:
    """Change the ports (or parameters) of the component ``name`` of ``raw``."""
    raw.comps = [({**c[0], **ports}, *c[1:]) if str(c[0]["name"]) == name else c
                 for c in raw.comps]


def lag(raw: Any, fx: dict) -> None:
    """The speed converter's RC filter: the probe read on a capacitor fed through 1 ohm."""
    probe, tau = fx["lag"]
    _add(raw, {"name": "Fv", "type": "BV", "p": "fv", "n": "gnd", "expr": "head.w*1[V*s/rad]"})
    _add(raw, {"name": "Rf", "type": "R", "p": "fv", "n": "fo", "R": 1.0})
    _add(raw, {"name": "Cf", "type": "C", "p": "fo", "n": "gnd", "C": tau})
    loc = raw.probes[probe][1]
    raw.probes = {**raw.probes, probe: ("fo.v", loc)}


def film(raw: Any, fx: dict) -> None:
    """The tarnished connector's film between Ra and La."""
    a, eps = fx["film"]
    _rewire(raw, "La", p="mf")
    _add(raw, {"name": "Film", "type": "BV", "p": "m1", "n": "mf",
               "expr": f"{a!r}*La.i*(La.i^2 + {eps!r}^2)^(-0.25)"})


def ecc(raw: Any, fx: dict) -> None:
    """The bent shaft: a once-per-turn harmonic of the EMF, on the torque too."""
    e, phase = fx["ecc"]
    _rewire(raw, "M", harmonics=[{"order": 1, "slope": sa.MOTOR_AA["k"] * e, "offset": 0.0,
                                  "phase": phase}], ripple_torque=True)


def bushing(raw: Any, fx: dict) -> None:
    """The dry bushing's friction on the head, heated through an electrical analogue."""
    t0, beta, cap, g = fx["bushing"]
    force = f"{t0!r}*(1 + {beta!r}*tb.v)*tanh(head.w/0.01)"
    _add(raw, {"name": "Cb", "type": "C", "p": "tb", "n": "gnd", "C": cap})
    _add(raw, {"name": "Gb", "type": "R", "p": "tb", "n": "gnd", "R": 1.0 / g})
    _add(raw, {"name": "Qb", "type": "BI", "p": "gnd", "n": "tb", "expr": f"{force}*head.w"})
    _add(raw, {"name": "Bush", "type": "btorque", "shaft": "head", "expr": f"-{force}"})


OUTSIDE_LAWS = {"lag": lag, "film": film, "ecc": ecc, "bushing": bushing}


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor AA's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=sa.simulate,
                          PROBES=sa.PROBES)
    return crosscheck.compare(cs, sim, "AA", sa.MOTOR_AA, NETLISTS, s["regime"], label, fx,
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
    print(f"motor AA: the fast and slow netlists declare the same motor: {same}")
    return same


def main() -> int:
    """Every record of fresh26; exit status 1 above TARGET (or if the netlists differ)."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    same = same_motor(cs)
    status = crosscheck.check_records(cs, record_specs(), times, scale_marginal, check,
                                      TARGET, sys.argv[1:2])
    return status if same else 1


if __name__ == "__main__":
    sys.exit(main())
