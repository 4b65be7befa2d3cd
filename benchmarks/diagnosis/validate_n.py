"""Cross-check of motor N on the records' own times: the noise-free null output of
simulators_n.py against circuitsim's simulation of the declared netlists (motor_n.yaml,
fast; motor_n_slow.yaml, slow) on the times of several records of each regime (v01 even,
v03 jittered; v02 a logger's uneven times, v06 even); each catalog and two-effect record
against the declared netlist carrying the catalog's own patch (circuitsim.loop.effects
.candidates, through crosscheck.truth_patch) at the truth's expected values, on that
record's times; and the outside records whose law circuitsim's components can state (the
bouncing brushes as a behavioural voltage in series with the armature, the parcels' pitch
load and the holding brake as behavioural torques, the dropped parcel as a sliding `mass`
with a behavioural force and torque). The current sensor's filter (a law of the reading)
is not compared.

    python benchmarks/diagnosis/validate_n.py

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
import simulators_n as sn
from make_records_n import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_n.yaml",
            "slow": HERE / "netlists" / "motor_n_slow.yaml"}
TARGET = 1e-5
P = sn.MOTOR_N
#: the records on whose times the null is compared
NULL_ON = ("v01", "v02", "v03", "v06")


# ---------------------------------------------------------------------- outside laws

def _add(raw: Any, entry: dict) -> None:
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def bounce(raw: Any, fx: dict) -> None:
    """Rb (1 + tanh((|w| - w1)/dw))/2 i in series with the armature's resistor."""
    from circuitsim.loop.effects import insert_series

    rb, w1, dw = fx["bounce"]
    insert_series(raw, "Ra", "BNC", f"0.5*{rb!r}[ohm]*(1 + tanh((sqrt((rotor.w/1[rad/s])^2"
                                    f" + 1) - {w1!r})/{dw!r}))*Ra.i")


def items(raw: Any, fx: dict) -> None:
    """-dT tanh(kappa sin(2 pi r thd / pitch + phase)) on the drum."""
    dt, pitch, r, kappa, ph = fx["items"]
    _add(raw, {"name": "ITM", "type": "btorque", "shaft": "drum",
               "expr": f"-{dt!r}[N*m]*tanh({kappa!r}*sin({2 * math.pi * r / pitch!r}*drum.phi"
                       f" + {ph!r}))"})


def brake(raw: Any, fx: dict) -> None:
    """-Tb g(t) tanh(w / 0.01) on the rotor."""
    tb, tr, spans = fx["brake"]
    g = " - ".join(["1", *(f"(tanh((t - {a!r}[s])/{tr!r}[s]) - tanh((t - {b!r}[s])/{tr!r}[s]))"
                           "/2" for a, b in spans)])
    _add(raw, {"name": "BRK", "type": "btorque", "shaft": "rotor",
               "expr": f"-{tb!r}[N*m]*({g})*tanh(rotor.w/{sn.W_SIGN!r}[rad/s])"})


def parcel(raw: Any, fx: dict) -> None:
    """The parcel as a sliding mass on its own flange: it receives h (F - m g sin(slope)),
    the drum -h F r, F = mu m g cos(slope) tanh((r wd - vp) / eps)."""
    m, mu, slope, r, ta, tr, eps = fx["parcel"]
    f = (f"{mu * m * 9.81 * math.cos(slope)!r}[N]*tanh(({r!r}[m]*drum.w/1[rad] - pk.v)"
         f"/{eps!r}[m/s])")
    h = f"(1 + tanh((t - {ta!r}[s])/{tr!r}[s]))/2"
    _add(raw, {"name": "PKM", "type": "mass", "flange": "pk", "m": m})
    _add(raw, {"name": "PKF", "type": "bforce", "flange": "pk",
               "expr": f"{h}*({f} - {m * 9.81 * math.sin(slope)!r}[N])"})
    _add(raw, {"name": "PKT", "type": "btorque", "shaft": "drum",
               "expr": f"-{h}*{f}*{r!r}[m]/1[rad]"})


OUTSIDE_LAWS = {"bounce": bounce, "items": items, "brake": brake, "parcel": parcel}


# ---------------------------------------------------------------------- comparison

def on_times(t: Any) -> SimpleNamespace:
    """simulators_n seen through crosscheck.compare, its grid being the times ``t`` [s]."""
    return SimpleNamespace(grid=lambda regime: t, simulate=sn.simulate, PROBES=sn.PROBES)


def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict | None = None) -> float:
    """Motor N's scipy model against circuitsim at the record's own times."""
    return crosscheck.compare(cs, on_times(times(s)), "N", P, NETLISTS, s["regime"],
                              label, fx, raw, values)


def check_effects(cs: Any, s: dict) -> float:
    """A record's effects as the catalog's patch or as components (the worst difference
    over a probe's range), or 0 when no component states them."""
    regime = s["regime"]
    if s["class"] in ("catalog", "two"):
        raw, values = crosscheck.truth_patch(cs.load(NETLISTS[regime]), s["effects"],
                                             sn.PROBES[regime], sn.REGIMES[regime][1])
        # the id and class only: the effects stay in truth.json (the set is blind)
        return compare(cs, s, f"{s['id']} {s['class']}, the catalog's patch", s["fx"], raw,
                       values)
    law = next((f for k, f in OUTSIDE_LAWS.items() if k in s["fx"]), None)
    if law is None:
        print(f"motor N {regime:4s} {s['id']} outside: no component states its law "
              "(a law of the reading; not compared)")
        return 0.0
    raw = cs.load(NETLISTS[regime]).raw.copy()
    law(raw, s["fx"])
    return compare(cs, s, f"{s['id']} outside, as components", s["fx"], raw)


def check(cs: Any, s: dict) -> float:
    """One record's comparisons: the null on its times (NULL_ON), and its effects."""
    worst = 0.0
    if s["id"] in NULL_ON:
        kind = "even" if s["timestamps"].startswith("even") else "uneven"
        worst = compare(cs, s, f"null on {s['id']}'s {kind} times", {})
    if s["class"] != "null":
        worst = max(worst, check_effects(cs, s))
    return worst


def main() -> int:
    """Every record of fresh13 that a netlist can state; exit status 1 above TARGET."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    return crosscheck.check_records(cs, record_specs(), times, scale_marginal, check, TARGET,
                                    sys.argv[1:2])


if __name__ == "__main__":
    sys.exit(main())
