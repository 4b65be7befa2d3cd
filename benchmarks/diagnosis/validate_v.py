"""Cross-check of motor V on the records' own times: the noise-free null output of
simulators_v.py against circuitsim's simulation of the declared netlists (motor_v.yaml,
fast; motor_v_slow.yaml, slow), on the times of i01 (even) and i05 (jittered) in the fast
regime and of i02 (a logger's uneven times) and i04 (even) in the slow one; each catalog
and two-effect record against the declared netlist carrying the catalog's own patch
(circuitsim.loop.effects.candidates, through crosscheck.truth_patch) at the truth's
expected values, on that record's times; and every outside record as circuitsim's
components state it:

- the universal joints' phasing: the intermediate shaft's `spring_damper` replaced by two
  behavioural torques, the pinion's c (phi - pinion.phi) + d (g column.w - pinion.w) and
  the column's -g times it, phi = column.phi + e (sin(2 column.phi + psi) - sin(psi)),
  g = 1 + 2 e cos(2 column.phi + psi);
- the slipping encoder hub: a shaft `enc` with the hub's inertia (taken from the rotor's),
  dragged by a behavioural torque Tc tanh((rotor.w - enc.w)/eps) whose reaction the rotor
  takes; the speed's probe reads enc.w;
- the kerb strike: a behavioural torque on the pinion, A sin(pi (t - t0)/Tw)^2 switched on
  and off by relations of the time;
- the tyres' relaxation: the declared aligning `spring` replaced by a behavioural torque -Mz
  on the pinion, Mz the voltage of a 1 F capacitor charged by a behavioural current
  (Ka pinion.phi - Mz)/tau (1 V per N m);
- the aligning moment's saturation: the declared `spring` replaced by a behavioural torque
  -Ka theta0 tanh(pinion.phi/theta0).

    python benchmarks/diagnosis/validate_v.py            # every record
    python benchmarks/diagnosis/validate_v.py i03,i13    # some

Prints, per probe, the largest difference relative to the signal's range at the record's
sample times, and the effect's own size on that scale. Target 1e-6 of the range; exit
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
import simulators_v as sv
from make_records_v import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_v.yaml",
            "slow": HERE / "netlists" / "motor_v_slow.yaml"}
TARGET = 1e-6
NULL_ON = ("i01", "i02", "i04", "i05")


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw`` as a patch's part."""
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def _drop(raw: Any, name: str) -> None:
    """Remove the component ``name`` from ``raw``."""
    raw.comps = [c for c in raw.comps if str(c[0]["name"]) != name]


def cardan(raw: Any, fx: dict) -> None:
    """The intermediate shaft ``K`` replaced by the joints' kinematics and the shaft's
    spring-damper as two behavioural torques (the column's by virtual work)."""
    e, psi = fx["cardan"]
    _drop(raw, "K")
    ang = f"(2*column.phi/1[rad] + {psi!r})"
    phi = f"(column.phi + {e!r}[rad]*(sin{ang} - {math.sin(psi)!r}))"
    g = f"(1 + {2.0 * e!r}*cos{ang})"
    tk = f"(c*({phi} - pinion.phi) + d*({g}*column.w - pinion.w))"
    _add(raw, {"name": "KP", "type": "btorque", "shaft": "pinion", "expr": tk})
    _add(raw, {"name": "KC", "type": "btorque", "shaft": "column", "expr": f"-{g}*{tk}"})


def slipping_hub(raw: Any, fx: dict) -> None:
    """The encoder's hub as its own shaft ``enc`` (its inertia taken from the rotor's),
    dragged by the set screw's friction; the speed's probe reads it."""
    jenc, tc, eps = fx["slip"]
    jr = sv.MOTOR_V["Jm"] - jenc
    raw.comps = [({**c[0], "J": jr}, *c[1:]) if str(c[0]["name"]) == "Jr" else c
                 for c in raw.comps]
    drag = f"{tc!r}[N*m]*tanh((rotor.w - enc.w)/{eps!r}[rad/s])"
    _add(raw, {"name": "JE", "type": "inertia", "shaft": "enc", "J": jenc})
    _add(raw, {"name": "TE", "type": "btorque", "shaft": "enc", "expr": drag})
    _add(raw, {"name": "TR", "type": "btorque", "shaft": "rotor", "expr": f"-{drag}"})
    _, loc = raw.probes["speed"]
    raw.probes["speed"] = ("enc.w", loc)


def kerb(raw: Any, fx: dict) -> None:
    """The kerb stone's torque pulse on the pinion, switched by relations of the time."""
    t0, amp, tw = fx["kerb"]
    on = f"(t >= {t0!r}[s])*(t <= {t0 + tw!r}[s])"
    _add(raw, {"name": "KB", "type": "btorque", "shaft": "pinion",
               "expr": f"{on}*{amp!r}[N*m]*sin(pi*(t - {t0!r}[s])/{tw!r}[s])^2"})


def relaxation(raw: Any, fx: dict) -> None:
    """The aligning spring ``Ka`` replaced by its lagged moment: the pinion takes -Mz, Mz
    the voltage of a 1 F capacitor (1 V per N m) charged by (Ka phi - Mz)/tau (1 A per
    N m/s)."""
    tau = fx["relax"]
    ka = sv.MOTOR_V["Ka"]
    _drop(raw, "Ka")
    mz = "relax_m.v/1[V]"
    _add(raw, {"name": "RLI", "type": "BI", "p": "gnd", "n": "relax_m",
               "expr": f"({ka!r}*pinion.phi/1[rad] - {mz})/{tau!r}*1[A]"})
    _add(raw, {"name": "RLC", "type": "C", "p": "relax_m", "n": "gnd", "C": 1.0, "v0": 0.0})
    _add(raw, {"name": "RLT", "type": "btorque", "shaft": "pinion", "expr": f"-{mz}*1[N*m]"})


def saturation(raw: Any, fx: dict) -> None:
    """The aligning spring ``Ka`` replaced by its saturating law."""
    th0 = fx["alsat"]
    ka = sv.MOTOR_V["Ka"]
    _drop(raw, "Ka")
    _add(raw, {"name": "ALS", "type": "btorque", "shaft": "pinion",
               "expr": f"-{ka * th0!r}[N*m]*tanh(pinion.phi/{th0!r}[rad])"})


OUTSIDE_LAWS = {"cardan": cardan, "slip": slipping_hub, "kerb": kerb, "relax": relaxation,
                "alsat": saturation}


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor V's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=sv.simulate,
                          PROBES=sv.PROBES)
    return crosscheck.compare(cs, sim, "V", sv.MOTOR_V, NETLISTS, s["regime"], label, fx,
                              raw, values)


def catalog(cs: Any, s: dict) -> float:
    """A catalog or two-effect record through the catalog's own patch."""
    regime = s["regime"]
    raw, values = crosscheck.truth_patch(cs.load(NETLISTS[regime]), s["effects"],
                                         sv.PROBES[regime], sv.REGIMES[regime][1])
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
    """Every record of fresh21; exit status 1 above TARGET."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    return crosscheck.check_records(cs, record_specs(), times, scale_marginal, check, TARGET,
                                    sys.argv[1:2])


if __name__ == "__main__":
    sys.exit(main())
