"""Cross-check of motor AD on the records' own times: the noise-free null output of
simulators_ad.py against circuitsim's simulation of the declared netlists (motor_ad_fast.yaml,
motor_ad_slow.yaml), on the times of ag02 (even) and ag03 (jittered) in the fast regime and
of ag01 (a logger's uneven times) and ag10 (even) in the slow one; then every record with its
effects written as circuitsim's own components on the declared netlist, on that record's
times (marginal records scaled first):

- the catalog's effects: a parameter changed (the impeller's inertia), a resistor in series
  with Ra, a behavioural voltage (`BV`) in the loop for the brush drop Vb tanh(La.i / 1 mA)
  and the winding's warm-up R rise (1 - exp(-t / tau)) La.i, a `friction` more on the
  impeller, a behavioural torque (`btorque`) for the Stribeck peak and the rotor's detent
  torque, an `elasto_backlash` in place of the shaft K, and the probe's expression scaled or
  shifted for a sensor's gain or offset;
- the unbaffled tank's swirl: an `inertia` for the liquid, and behavioural torques on the
  impeller, cq wi |wi| - cq (wi - wf) |wi - wf|, and on the liquid,
  cq (wi - wf) |wi - wf| - cw wf |wf|;
- the open armature coil: a behavioural voltage in the loop,
  dR (1 - exp(kappa (cos(2 (rotor.phi - phase)) - 1))) La.i;
- the surface vortex: a behavioural torque on the impeller,
  dv cq wi |wi| (1 + tanh((|wi| - wv) / dw)) / 2;
- the slipping overload clutch: an `inertia` for its driven plate, a `clutch` (fn Ts, w_slip
  ws) from the hub to it, and the shaft K moved to the plate.

Unlike validate_ac.py this does not go through the catalog's patches (crosscheck.truth_patch
imports the diagnosis's own package, which this blind set keeps out of): the catalog's laws
are written here as plain components, the way the catalog states them.

Both netlists must declare the same motor: their parameters and all components but the
source are compared first.

    python benchmarks/diagnosis/validate_ad.py              # every record
    python benchmarks/diagnosis/validate_ad.py ag04,ag14    # some

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
import simulators_ad as sa
from make_records_ad import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_ad_fast.yaml",
            "slow": HERE / "netlists" / "motor_ad_slow.yaml"}
SOURCES = {"fast": "Vin", "slow": "U"}
TARGET = 1e-6
NULL_ON = ("ag01", "ag02", "ag03", "ag10")
#: the impeller's speed and the rotor's angle as the netlist names them
WI, TH = "impeller.w", "rotor.phi"


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw``, located (for messages) where its first component is."""
    raw.comps = [*raw.comps, (dict(entry), *raw.comps[0][1:])]


def _rewire(raw: Any, name: str, **ports: Any) -> None:
    """Change the ports (or parameters) of the component ``name`` of ``raw``."""
    raw.comps = [({**c[0], **ports}, *c[1:]) if str(c[0]["name"]) == name else c
                 for c in raw.comps]


def _in_loop(raw: Any, name: str, expr: str) -> None:
    """A behavioural voltage drop ``expr`` between La and the EMF M (M moved to a new node)."""
    node = f"n_{name.lower()}"
    _rewire(raw, "M", p=node)
    _add(raw, {"name": name, "type": "BV", "p": "m2", "n": node, "expr": expr})


def _probe(raw: Any, probe: str, gain: float = 1.0, offset: float = 0.0) -> None:
    """The probe's expression read with a gain and an offset [probe unit]."""
    text, loc = raw.probes[probe]
    unit = "A" if probe == "current" else "rad/s"
    raw.probes = {**raw.probes, probe: (f"{gain!r}*({text}) + {offset!r}[{unit}]", loc)}


# ---------------------------------------------------------------------- the catalog's laws

def catalog_parts(raw: Any, fx: dict) -> None:
    """Every catalog effect of ``fx`` as components of ``raw`` (SI values)."""
    p = sa.MOTOR_AD
    for name, value in fx.get("p", {}).items():
        loc = raw.params[name][1]
        raw.params = {**raw.params, name: (repr(float(value)), loc)}
    if "Rser" in fx:
        _rewire(raw, "Ra", p="s")
        _add(raw, {"name": "Rser", "type": "R", "p": "a", "n": "s", "R": fx["Rser"]})
    if "Vb" in fx:
        _in_loop(raw, "Brush", f"{fx['Vb']!r}[V]*tanh(La.i/1[mA])")
    if "warmup" in fx:
        rise, tau = fx["warmup"]
        _in_loop(raw, "Warm", f"{p['R'] * rise!r}[ohm]*(1 - exp(-t/{tau!r}[s]))*La.i")
    for probe, s in fx.get("sensor", {}).items():
        _probe(raw, probe, s.get("gain", 1.0), s.get("offset", 0.0))
    if "gap" in fx:
        _rewire(raw, "K", type="backlash", gap=fx["gap"])
    for body, c in fx.get("coul", {}).items():
        _add(raw, {"name": f"Fx_{body}", "type": "friction", "shaft": body, "tau_c": c,
                   "w_brk": 0.1})
    for body, (s, ws) in fx.get("stribeck", {}).items():
        _add(raw, {"name": f"St_{body}", "type": "btorque", "shaft": body,
                   "expr": f"-{s!r}[N*m]*exp(-({body}.w/{ws!r}[rad/s])^2)"
                           f"*tanh({body}.w/0.01[rad/s])"})
    for body, terms in fx.get("cog", {}).items():
        expr = " + ".join(f"{a!r}[N*m]*sin({order}*{body}.phi/1[rad]) + "
                          f"{b!r}[N*m]*cos({order}*{body}.phi/1[rad])"
                          for order, a, b in terms)
        _add(raw, {"name": f"Cog_{body}", "type": "btorque", "shaft": body, "expr": expr})


# ---------------------------------------------------------------------- the outside laws

def swirl(raw: Any, fx: dict) -> None:
    """The liquid's bulk spinning up with the impeller (the baffles left out)."""
    jf, cw = fx["swirl"]
    rel = f"({WI} - fluid.w)"
    _add(raw, {"name": "Jf", "type": "inertia", "shaft": "fluid", "J": jf})
    _add(raw, {"name": "Swirl", "type": "btorque", "shaft": "impeller",
               "expr": f"cq*{WI}*abs({WI}) - cq*{rel}*abs({rel})"})
    _add(raw, {"name": "Wall", "type": "btorque", "shaft": "fluid",
               "expr": f"cq*{rel}*abs({rel}) - {cw!r}[N*m*s^2/rad^2]*fluid.w*abs(fluid.w)"})


def bar(raw: Any, fx: dict) -> None:
    """The open armature coil's resistance, bridged twice a turn."""
    dr, kappa, phase = fx["bar"]
    _in_loop(raw, "Bar", f"{dr!r}[ohm]*(1 - exp({kappa!r}*(cos(2*({TH} - {phase!r}[rad])"
                         f"/1[rad]) - 1)))*La.i")


def vortex(raw: Any, fx: dict) -> None:
    """The impeller losing a fraction of its drag above the critical speed."""
    dv, wv, dw = fx["vortex"]
    _add(raw, {"name": "Vortex", "type": "btorque", "shaft": "impeller",
               "expr": f"{dv!r}*cq*{WI}*abs({WI})*0.5*(1 + tanh((abs({WI}) - {wv!r}[rad/s])"
                       f"/{dw!r}[rad/s]))"})


def clutch(raw: Any, fx: dict) -> None:
    """The slip clutch between the hub and the shaft, with its driven plate."""
    ts, ws, jp = fx["clutch"]
    _rewire(raw, "K", a="plate")
    _add(raw, {"name": "Jp", "type": "inertia", "shaft": "plate", "J": jp})
    _add(raw, {"name": "Cl", "type": "clutch", "a": "hub", "b": "plate", "fn": ts,
               "w_slip": ws})


OUTSIDE_LAWS = {"swirl": swirl, "bar": bar, "vortex": vortex, "clutch": clutch}


# ---------------------------------------------------------------------- the checks

def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None) -> float:
    """Motor AD's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=sa.simulate,
                          PROBES=sa.PROBES)
    return crosscheck.compare(cs, sim, "AD", sa.MOTOR_AD, NETLISTS, s["regime"], label, fx,
                              raw)


def with_effects(cs: Any, s: dict) -> float:
    """A record's effects as components on its regime's declared netlist."""
    raw = cs.load(NETLISTS[s["regime"]]).raw.copy()
    catalog_parts(raw, s["fx"])
    for key, law in OUTSIDE_LAWS.items():
        if key in s["fx"]:
            law(raw, s["fx"])
    # the id and class only: the effects stay in truth.json (the set is blind)
    return compare(cs, s, f"{s['id']} {s['class']}, as components", s["fx"], raw)


def check(cs: Any, s: dict) -> float:
    """One record's comparisons: the null on its times (NULL_ON), and its effects."""
    worst = 0.0
    if s["id"] in NULL_ON:
        worst = compare(cs, s, f"null on {s['id']}'s {s['timestamps'].split(':')[0]} times",
                        {})
    if s["class"] != "null":
        worst = max(worst, with_effects(cs, s))
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
    print(f"motor AD: the fast and slow netlists declare the same motor: {same}")
    return same


def main() -> int:
    """Every record of fresh29; exit status 1 above TARGET (or if the netlists differ)."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    same = same_motor(cs)
    status = crosscheck.check_records(cs, record_specs(), times, scale_marginal, check,
                                      TARGET, sys.argv[1:2])
    if any(m.startswith("circuitsim.loop") for m in sys.modules):
        print("the diagnosis's package was imported: the check is void")
        return 1
    return status if same else 1


if __name__ == "__main__":
    sys.exit(main())
