"""Cross-check of motor AT on the records' own times: the noise-free output of simulators_at.py
against circuitsim's simulation of the declared netlists (motor_at_fast.yaml,
motor_at_slow.yaml), first at the netlists' DECLARED values (on the times of aw05 (even) and
aw03 (jittered) in the fast regime and of aw01 (even) and aw06 and aw08 (a logger's uneven
times) in the slow one), then on every record's times at the record's TRUE values (the
declared parameters it frees set to their true values through circuitsim's parameter
overrides, ``params``), then every record with its effects written as circuitsim's own
components on the declared netlist, at its true values (overrides again; marginal records
scaled first):

- the catalog's effects: a parameter changed, a resistor between the source and Ra, a
  behavioural voltage (`BV`) in the loop for the brush drop and the EMF's harmonic, the collet
  K turned into a `backlash`, behavioural torques (`btorque`) for a Stribeck breakaway and a
  cogging, a `damper` on a body, the probe read through a sensor's offset;
- the water spinning up in the flask: a body ``water`` with an `inertia` Jl, a
  `shaft_damper` c between the flask and it, and the flask's Jf overridden to Jf - Jl;
- the suppression varistor: a behavioural current (`BI`) I0 (a.v/V0)^n across the supply's
  output, the current probe read as Ra.i plus its current (the shunt in the supply's lead);
- the vacuum drawing the duct into its seal: a behavioural torque on the flask,
  -Tv (1 + tanh((t - t0)/tr))/2 tanh(flask.w/0.01 rad/s);
- the centrifugal governor: a behavioural voltage (`BV`) Rg (1 + tanh((smooth_abs(rotor.w,
  1 rad/s) - wg)/dw))/2 La.i in the loop.

Like validate_ar.py this does not go through the catalog's patches (crosscheck.truth_patch
imports the diagnosis's own package, which this blind set keeps out of): the catalog's laws
are written here as plain components, the way the catalog states them.

Both netlists must declare the same motor: their parameters and all components but the
source are compared first.

    python benchmarks/diagnosis/validate_at.py              # every record
    python benchmarks/diagnosis/validate_at.py aw04,aw14    # some

Prints, per probe, the largest difference relative to the signal's range at the record's
sample times, and the effect's own size on that scale. Target 1e-7 of the range; exit
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
import simulators_at as sa
from make_records_at import record_specs, scale_marginal, times

NETLISTS = {"fast": HERE / "netlists" / "motor_at_fast.yaml",
            "slow": HERE / "netlists" / "motor_at_slow.yaml"}
SOURCES = {"fast": "Vin", "slow": "U"}
TARGET = 1e-7
NULL_ON = ("aw01", "aw03", "aw05", "aw06", "aw08")
#: the probes' units, and their expressions' unit for a Pade stage's voltage
UNITS = {"current": "A", "speed": "rad/s", "load_speed": "rad/s"}
VOLTS_PER = {"current": "V/A", "speed": "V*s/rad", "load_speed": "V*s/rad"}


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


def _set_probe(raw: Any, probe: str, text: str) -> None:
    """Read the probe ``probe`` as the expression ``text``."""
    loc = raw.probes[probe][1]
    raw.probes = {**raw.probes, probe: (text, loc)}


def _sensor(raw: Any, probe: str, s: dict) -> None:
    """The probe read through a sensor: a first-order Pade stage of ``delay`` (a behavioural
    voltage y, a resistor and a capacitor with R C = delay / 2, read as 2 q - y), then a
    ``gain`` and an ``offset``."""
    text = raw.probes[probe][0]
    if s.get("delay"):
        ys, q, per = f"ys_{probe}", f"q_{probe}", VOLTS_PER[probe]
        _add(raw, {"name": f"Ys_{probe}", "type": "BV", "p": ys, "n": "gnd",
                   "expr": f"({text})*1[{per}]"})
        _add(raw, {"name": f"Rq_{probe}", "type": "R", "p": ys, "n": q, "R": 1.0})
        _add(raw, {"name": f"Cq_{probe}", "type": "C", "p": q, "n": "gnd",
                   "C": 0.5 * float(s["delay"])})
        text = f"(2*{q}.v - {ys}.v)/1[{per}]"
    gain, offset = s.get("gain", 1.0), s.get("offset", 0.0)
    _set_probe(raw, probe, f"{gain!r}*({text}) + {offset!r}[{UNITS[probe]}]")


# ---------------------------------------------------------------------- the catalog's laws

def loop_parts(raw: Any, fx: dict) -> None:
    """The catalog's effects of ``fx`` on the armature loop as components of ``raw``."""
    p = sa.MOTOR_AT
    if "lsat" in fx:
        ipar, ratio = fx["lsat"]
        _replace(raw, "La", {"name": "La", "type": "Lsat", "p": "m1", "n": "m2", "Lzer": "L",
                             "Linf": p["L"] * ratio, "Ipar": ipar})
    for key, name in (("Rs", "Rsrc"), ("Rser", "Rser")):
        if key in fx:
            _rewire(raw, "Ra", p=f"s_{name.lower()}")
            _add(raw, {"name": name, "type": "R", "p": "a", "n": f"s_{name.lower()}",
                       "R": fx[key]})
    if "Vb" in fx:
        _in_loop(raw, "Brush", f"{fx['Vb']!r}[V]*tanh(La.i/1[mA])")
    if "warmup" in fx:
        rise, tau = fx["warmup"]
        _in_loop(raw, "Warm", f"{p['R'] * rise!r}[ohm]*(1 - exp(-t/{tau!r}[s]))*La.i")
    if "alpha" in fx:
        _in_loop(raw, "Drift", f"{p['R'] * fx['alpha']!r}[ohm/s]*t*La.i")
    if fx.get("emf"):
        expr = " + ".join(f"{a!r}[V*s/rad]*sin({order}*rotor.phi/1[rad]) + "
                          f"{b!r}[V*s/rad]*cos({order}*rotor.phi/1[rad])"
                          for order, a, b in fx["emf"])
        _in_loop(raw, "Emfh", f"rotor.w*({expr})")


def catalog_parts(raw: Any, fx: dict) -> None:
    """Every catalog effect of ``fx`` as components of ``raw`` (SI values)."""
    for name, value in fx.get("p", {}).items():
        loc = raw.params[name][1]
        raw.params = {**raw.params, name: (repr(float(value)), loc)}
    loop_parts(raw, fx)
    if "gap" in fx:
        _rewire(raw, "K", type="backlash", gap=fx["gap"])
    for probe, s in fx.get("sensor", {}).items():
        _sensor(raw, probe, s)
    for body, c in fx.get("coul", {}).items():
        _add(raw, {"name": f"Fx_{body}", "type": "friction", "shaft": body, "tau_c": c,
                   "w_brk": 0.1})
    for body, b in fx.get("visc", {}).items():
        _add(raw, {"name": f"Bx_{body}", "type": "damper", "shaft": body, "b": b})
    for body, f in fx.get("offset", {}).items():
        _add(raw, {"name": f"Off_{body}", "type": "btorque", "shaft": body,
                   "expr": f"{f!r}[N*m]"})
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

def spinup(raw: Any, fx: dict) -> dict[str, float]:
    """The water in the flask: a body ``water`` of inertia Jl behind a shaft damper c from
    the flask; returns the override of the flask's own inertia (Jf - Jl, its true Jf)."""
    jl, c = fx["spinup"]
    _add(raw, {"name": "Jw", "type": "inertia", "shaft": "water", "J": float(jl)})
    _add(raw, {"name": "Cw_l", "type": "shaft_damper", "a": "flask", "b": "water",
               "d": float(c)})
    jf = float(fx.get("p", {}).get("Jf", sa.MOTOR_AT["Jf"]))
    return {"Jf": jf - float(jl)}


def varistor(raw: Any, fx: dict) -> dict[str, float]:
    """The suppression varistor: a behavioural current across the supply's output, the
    current probe reading Ra.i plus its current."""
    i0, v0, power = fx["varistor"]
    _add(raw, {"name": "Var", "type": "BI", "p": "a", "n": "gnd",
               "expr": f"{float(i0)!r}[A]*(a.v/{float(v0)!r}[V])^{int(power)}"})
    text = raw.probes["current"][0]
    _set_probe(raw, "current", f"({text}) + Var.i")
    return {}


def vacuum(raw: Any, fx: dict) -> dict[str, float]:
    """The vacuum's seal friction: a behavioural torque on the flask growing in time."""
    tv, t0, tr = fx["vacuum"]
    _add(raw, {"name": "Vac", "type": "btorque", "shaft": "flask",
               "expr": f"-{float(tv)!r}[N*m]*0.5*(1 + tanh((t - {float(t0)!r}[s])/"
                       f"{float(tr)!r}[s]))*tanh(flask.w/0.01[rad/s])"})
    return {}


def governor(raw: Any, fx: dict) -> dict[str, float]:
    """The centrifugal governor: its resistor in the loop as its contacts open."""
    rg, wg, dw = fx["governor"]
    _in_loop(raw, "Gov", f"{float(rg)!r}[ohm]*0.5*(1 + tanh((smooth_abs(rotor.w, 1[rad/s]) - "
                         f"{float(wg)!r}[rad/s])/{float(dw)!r}[rad/s]))*La.i")
    return {}


OUTSIDE_LAWS = {"spinup": spinup, "varistor": varistor, "vacuum": vacuum,
                "governor": governor}


# ---------------------------------------------------------------------- the checks

def compare(cs: Any, s: dict, label: str, fx: dict, raw: Any = None,
            values: dict[str, float] | None = None) -> float:
    """Motor AT's scipy model against circuitsim at the record's own times (``values``:
    circuitsim's parameter overrides)."""
    sim = SimpleNamespace(grid=lambda regime: times(s), simulate=sa.simulate,
                          PROBES=sa.PROBES)
    return crosscheck.compare(cs, sim, "AT", sa.MOTOR_AT, NETLISTS, s["regime"], label, fx,
                              raw, values)


def with_effects(cs: Any, s: dict) -> float:
    """A record's effects as components on its regime's declared netlist, at its true
    values (circuitsim's overrides)."""
    raw = cs.load(NETLISTS[s["regime"]]).raw.copy()
    catalog_parts(raw, s["fx"])
    fx = {**s["fx"], "p": {**s["ptrue"], **s["fx"].get("p", {})}}
    values = dict(s["ptrue"])
    for key, law in OUTSIDE_LAWS.items():
        if key in s["fx"]:
            values.update(law(raw, fx))
    # the id and class only: the effects stay in truth.json (the set is blind)
    return compare(cs, s, f"{s['id']} {s['class']}, as components, true values", fx, raw,
                   values)


def check(cs: Any, s: dict) -> float:
    """One record's comparisons: the declared null on its times (NULL_ON), the true null
    (the overrides), and its effects."""
    worst = 0.0
    kind = s["timestamps"].split(":")[0]
    if s["id"] in NULL_ON:
        worst = compare(cs, s, f"declared null on {s['id']}'s {kind} times", {})
    worst = max(worst, compare(cs, s, f"true null of {s['id']} ({kind} times)",
                               {"p": dict(s["ptrue"])}, None, dict(s["ptrue"])))
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
    print(f"motor AT: the fast and slow netlists declare the same motor: {same}")
    return same


def main() -> int:
    """Every record of fresh45; exit status 1 above TARGET (or if the netlists differ)."""
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
