"""Cross-check of motor AE on the records' own times: the noise-free null output of
simulators_ae.py against circuitsim's simulation of the declared netlists (motor_ae_fast.yaml,
motor_ae_slow.yaml), on the times of ah01 (jittered) and ah09 (even) in the fast regime and
of ah02 (even) and ah06 (a logger's uneven times) in the slow one; then every record with its
effects written as circuitsim's own components on the declared netlist, on that record's
times (marginal records scaled first):

- the catalog's effects: a saturating inductor (`Lsat`: Lzer La, Linf ratio La, Ipar) in
  place of La, a drifting resistor (`Rdrift`) in place of Ra for the linear drift, a resistor
  in series with Ra, a behavioural voltage (`BV`) in the loop for the brush drop
  Vb tanh(La.i / 1 mA), a behavioural torque (`btorque`) for the boom's constant torque, its
  Stribeck peak and the rotor's detent torque, a `damper` more on the boom, and the probe's
  expression scaled or shifted for a sensor's gain or offset;
- the wind on the raised boom: a behavioural torque on the boom,
  -Tw sin(boom.phi) |sin(boom.phi)|;
- the relay's braking resistor: a behavioural voltage in the loop, Rb exp(-(a.v / u0)^2) La.i
  (a.v: the source's voltage, the bridge's command);
- the gyroscope's full scale: the probe load_speed read as clamp(boom.w, -ws, ws);
- the cracked boom root: behavioural torques on the boom, -dk Kc max(hub.phi - boom.phi, 0),
  and its reaction on the hub.

Like validate_ad.py this does not go through the catalog's patches (crosscheck.truth_patch
imports the diagnosis's own package, which this blind set keeps out of): the catalog's laws
are written here as plain components, the way the catalog states them.

Both netlists must declare the same motor: their parameters and all components but the
source are compared first.

    python benchmarks/diagnosis/validate_ae.py              # every record
    python benchmarks/diagnosis/validate_ae.py ah04,ah14    # some

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
import simulators_ae as sa
from make_records_ae import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_ae_fast.yaml",
            "slow": HERE / "netlists" / "motor_ae_slow.yaml"}
SOURCES = {"fast": "Vin", "slow": "U"}
TARGET = 1e-6
NULL_ON = ("ah01", "ah02", "ah06", "ah09")
#: the boom's angle as the netlist names it
THB = "boom.phi"


def _add(raw: Any, entry: dict) -> None:
    """Add a component to ``raw``, located (for messages) where its first component is."""
    raw.comps = [*raw.comps, (dict(entry), *raw.comps[0][1:])]


def _rewire(raw: Any, name: str, **ports: Any) -> None:
    """Change the ports (or parameters) of the component ``name`` of ``raw``."""
    raw.comps = [({**c[0], **ports}, *c[1:]) if str(c[0]["name"]) == name else c
                 for c in raw.comps]


def _replace(raw: Any, name: str, entry: dict) -> None:
    """Put ``entry`` in place of the component ``name`` of ``raw`` (its own parameters)."""
    raw.comps = [(dict(entry), *c[1:]) if str(c[0]["name"]) == name else c
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
    p = sa.MOTOR_AE
    for name, value in fx.get("p", {}).items():
        loc = raw.params[name][1]
        raw.params = {**raw.params, name: (repr(float(value)), loc)}
    if "lsat" in fx:
        ipar, ratio = fx["lsat"]
        _replace(raw, "La", {"name": "La", "type": "Lsat", "p": "m1", "n": "m2", "Lzer": "L",
                             "Linf": p["L"] * ratio, "Ipar": ipar})
    if "alpha" in fx:
        _replace(raw, "Ra", {"name": "Ra", "type": "Rdrift", "p": "a", "n": "m1", "R0": "R",
                             "alpha": fx["alpha"]})
    if "Rser" in fx:
        _rewire(raw, "Ra", p="s")
        _add(raw, {"name": "Rser", "type": "R", "p": "a", "n": "s", "R": fx["Rser"]})
    if "Vb" in fx:
        _in_loop(raw, "Brush", f"{fx['Vb']!r}[V]*tanh(La.i/1[mA])")
    for probe, s in fx.get("sensor", {}).items():
        _probe(raw, probe, s.get("gain", 1.0), s.get("offset", 0.0))
    for body, f in fx.get("offset", {}).items():
        _add(raw, {"name": f"Off_{body}", "type": "btorque", "shaft": body,
                   "expr": f"{f!r}[N*m]"})
    for body, b in fx.get("visc", {}).items():
        _add(raw, {"name": f"Bx_{body}", "type": "damper", "shaft": body, "b": b})
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

def wind(raw: Any, fx: dict) -> None:
    """The wind's pressure on the raised boom's face."""
    s = f"sin({THB}/1[rad])"
    _add(raw, {"name": "Wind", "type": "btorque", "shaft": "boom",
               "expr": f"-{fx['wind']!r}[N*m]*{s}*abs({s})"})


def brake_r(raw: Any, fx: dict) -> None:
    """The braking relay's resistor while the command is near 0 V."""
    rb, u0 = fx["brake_r"]
    _in_loop(raw, "Brake", f"{rb!r}[ohm]*exp(-(a.v/{u0!r}[V])^2)*La.i")


def clip(raw: Any, fx: dict) -> None:
    """The boom's gyroscope clipping at its full scale."""
    ws = fx["clip"]
    text, loc = raw.probes["load_speed"]
    raw.probes = {**raw.probes,
                  "load_speed": (f"clamp({text}, -{ws!r}[rad/s], {ws!r}[rad/s])", loc)}


def crack(raw: Any, fx: dict) -> None:
    """The boom root's crack: the drive softer while the hub leads the boom."""
    k = fx["crack"] * sa.MOTOR_AE["Kc"]
    law = f"{k!r}[N*m/rad]*max(hub.phi - {THB}, 0[rad])"
    _add(raw, {"name": "CrackB", "type": "btorque", "shaft": "boom", "expr": f"-{law}"})
    _add(raw, {"name": "CrackH", "type": "btorque", "shaft": "hub", "expr": law})


OUTSIDE_LAWS = {"wind": wind, "brake_r": brake_r, "clip": clip, "crack": crack}


# ---------------------------------------------------------------------- the checks

def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None) -> float:
    """Motor AE's scipy model against circuitsim at the record's own times."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=sa.simulate,
                          PROBES=sa.PROBES)
    return crosscheck.compare(cs, sim, "AE", sa.MOTOR_AE, NETLISTS, s["regime"], label, fx,
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
    print(f"motor AE: the fast and slow netlists declare the same motor: {same}")
    return same


def main() -> int:
    """Every record of fresh30; exit status 1 above TARGET (or if the netlists differ)."""
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
