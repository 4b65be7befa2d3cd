"""Cross-check of motor T on the records' own times: the noise-free null output of
simulators_t.py against circuitsim's simulation of the declared netlists (motor_t.yaml,
fast; motor_t_slow.yaml, slow), on the times of b01 (even) and b05 (jittered) in the fast
regime and of b02 (a logger's uneven times) and b06 (even) in the slow one; each catalog
and two-effect record against the declared netlist carrying the catalog's own patch
(circuitsim.loop.effects.candidates, through crosscheck.truth_patch) at the truth's
expected values, on that record's times; and every outside record as circuitsim's
components state it:

- the slot-modulated inductance: the extra flux dL(th) i put as a voltage on a 1 F
  capacitor through a 10 pohm resistor (a differentiator of 10 ps: the lag it adds is
  linear in its time constant, 2.3e-6 of the current's range at 10 ns), whose current is the
  voltage d(dL i)/dt a behavioural source adds in series with the armature, and the
  reluctance torque i^2/2 dL/dth as a behavioural torque on the rotor;
- the DC-link shunt: the current's probe rewritten as Ra.i a.v / Vbus;
- the seized roller and the blocked vent: behavioural torques of the pump's angle and
  speed;
- the coarse duty register: the table command replaced by the simulator's own staircase as
  an inline `pwl` (each step a 1 ns ramp centred on its crossing).

    python benchmarks/diagnosis/validate_t.py            # every record
    python benchmarks/diagnosis/validate_t.py b03,b13    # some

Prints, per probe, the largest difference relative to the signal's range at the record's
sample times, and the effect's own size on that scale. Target 1e-5 of the range; exit
status 1 above it. Nothing here runs a diagnosis.
"""

from __future__ import annotations

import itertools
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
import simulators_t as st
from make_records_t import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_t.yaml",
            "slow": HERE / "netlists" / "motor_t_slow.yaml"}
TARGET = 1e-5
NULL_ON = ("b01", "b02", "b05", "b06")
#: [s] the time constant of the differentiator that forms d(dL i)/dt
TAU_DIFF = 1e-11
#: [s] the width of each step of the duty's staircase in its pwl
STEP_RAMP = 1e-9


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw`` as a patch's part."""
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def _source(raw: Any) -> dict:
    """The command's voltage source's entry."""
    return next(e for e, _, _ in raw.comps if e["name"] in ("U", "Vin"))


def slot_inductance(raw: Any, fx: dict) -> None:
    """dL(th) = eps L0 cos(order th + phase): a behavioural source puts dL i (1 V per Wb)
    on a capacitor of 1 F through TAU_DIFF ohm; the capacitor's current d(dL i)/dt (1 V
    per A) is added in series with the armature; the rotor receives i^2/2 dL/dth."""
    from circuitsim.loop.effects import insert_series

    eps, order, ph = fx["lrip"]
    l0 = st.MOTOR_T["L"]
    ang = f"{order!r}*rotor.phi/1[rad] + {ph!r}"
    _add(raw, {"name": "LXV", "type": "BV", "p": "lx_in", "n": "gnd",
               "expr": f"{eps * l0!r}*cos({ang})*Ra.i/1[A]*1[V]"})
    _add(raw, {"name": "LXR", "type": "R", "p": "lx_in", "n": "lx_c", "R": TAU_DIFF})
    _add(raw, {"name": "LXC", "type": "C", "p": "lx_c", "n": "gnd", "C": 1.0, "v0": 0.0})
    insert_series(raw, "La", "LXS", "LXR.i*1[V]/1[A]")
    _add(raw, {"name": "LXT", "type": "btorque", "shaft": "rotor",
               "expr": f"-0.5*(Ra.i/1[A])^2*{eps * l0 * order!r}*sin({ang})*1[N*m]"})


def dc_link(raw: Any, fx: dict) -> None:
    """The current's probe reads the bus current Ra.i a.v / Vbus."""
    _, loc = raw.probes["current"]
    raw.probes["current"] = (f"Ra.i*a.v/{fx['busread']!r}[V]", loc)


def seized(raw: Any, fx: dict) -> None:
    """The pump takes -Ts tanh(w/0.01) 0.5 (1 + tanh((cos(phi - centre) - cos(half)) /
    width))."""
    ts, centre, half, width = fx["seized"]
    win = (f"0.5*(1 + tanh((cos(pump.phi/1[rad] - {centre!r}) - cos({half!r}))/{width!r}))")
    _add(raw, {"name": "SEIZE", "type": "btorque", "shaft": "pump",
               "expr": f"-{ts!r}*tanh(pump.w/0.01[rad/s])*{win}*1[N*m]"})


def vessel(raw: Any, fx: dict) -> None:
    """The pump takes -D p0 D phi / (V0 - D phi)."""
    disp, p0, v0 = fx["vessel"]
    vol = f"{disp!r}*pump.phi/1[rad]"
    _add(raw, {"name": "VENT", "type": "btorque", "shaft": "pump",
               "expr": f"-{disp * p0!r}*{vol}/({v0!r} - {vol})*1[N*m]"})


def staircase(raw: Any, fx: dict, stop: float) -> None:
    """The command's source reads the simulator's staircase (simulators_t.pieces) as an
    inline ``pwl``: each level held, each step a STEP_RAMP ramp centred on its crossing."""
    segs = st.pieces(st.breakpoints("slow"), fx["duty_q"], stop)
    rows = [[0.0, segs[0][1]]]
    for (_, u0, _), (t1, u1, _) in itertools.pairwise(segs):
        if u1 != u0:
            rows += [[t1 - 0.5 * STEP_RAMP, u0], [t1 + 0.5 * STEP_RAMP, u1]]
    rows.append([stop, segs[-1][1]])
    _source(raw)["V"] = {"pwl": rows}


OUTSIDE_LAWS = {"lrip": slot_inductance, "busread": dc_link, "seized": seized,
                "vessel": vessel}


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor T's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=st.simulate,
                          PROBES=st.PROBES)
    return crosscheck.compare(cs, sim, "T", st.MOTOR_T, NETLISTS, s["regime"], label, fx,
                              raw, values)


def catalog(cs: Any, s: dict) -> float:
    """A catalog or two-effect record through the catalog's own patch."""
    regime = s["regime"]
    raw, values = crosscheck.truth_patch(cs.load(NETLISTS[regime]), s["effects"],
                                         st.PROBES[regime], st.REGIMES[regime][1])
    # the id and class only: the effects stay in truth.json (the set is blind)
    return compare(cs, s, f"{s['id']} {s['class']}, the catalog's patch", s["fx"], raw,
                   values)


def outside(cs: Any, s: dict) -> float:
    """An outside record rebuilt from circuitsim's components."""
    raw = cs.load(NETLISTS[s["regime"]]).raw.copy()
    if "duty_q" in s["fx"]:
        staircase(raw, s["fx"], float(times(s)[-1]))
    else:
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
    """Every record of fresh19; exit status 1 above TARGET."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    return crosscheck.check_records(cs, record_specs(), times, scale_marginal, check, TARGET,
                                    sys.argv[1:2])


if __name__ == "__main__":
    sys.exit(main())
