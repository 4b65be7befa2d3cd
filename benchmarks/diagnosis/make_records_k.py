"""Generate the blind set ``fresh10`` of the diagnosis benchmark: records r01-r14 of motor K
(a 24 V brushed DC motor driving the sealless gear pump of a coolant loop through a 4:1
planetary gearhead and a permanent-magnet drive coupling, a non-linear torsional spring
T = Tm sin(np twist)), and merge their truth into truth.json.

    python benchmarks/diagnosis/make_records_k.py              # records/r*.csv + truth.json
    python benchmarks/diagnosis/make_records_k.py --only r03,r12
    python benchmarks/diagnosis/make_records_k.py --truth-only # rewrite the r entries only

Uses simulators_k.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe [SI] (and, in the slow regime, the command ``u``
[V] that motor_k_slow.yaml reads from its own table). truth.json is merged under an exclusive
lock (``.truth.lock``; other generators merge other ids at the same time): every other entry
is kept, an entry with the same id is replaced, and the file is replaced atomically. Nobody
ran the diagnosis on these records.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import recordkit
import simulators_k as sk

RECORDS = HERE / "records"
TRUTH = HERE / "truth.json"
LOCK = HERE / ".truth.lock"
SPLIT = "fresh10"
MOTOR = "K"
SEED0 = 10500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_k.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_k_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.02, "speed": 0.2},
         "slow": {"current": 0.02, "speed": 0.2, "load_speed": 0.05}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
P = sk.MOTOR_K
N = P["N"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_k, truth effect). ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearhead is rigid and lossless: the hub turns with
# the rotor at 1/N of its speed, so a torque on the hub is one 1/N as large on the rotor, a
# viscous coefficient 1/N^2 (the same observation). The pump follows the hub through the
# magnetic coupling, whose twist stays below 0.25 rad (0.06 rad in steady running): a
# torque on the pump is, but for the coupling's transient, the same observation as one on
# the hub (J's harmonic-drive records treat their flexspline alike).

def _alternatives(effect: str, node: str, key: str, value: float, power: int) -> list[dict]:
    """The physically identical labels of an effect on ``node`` (pump, hub or rotor)."""
    if node == "rotor":
        return [{"effect": effect, "targets": ["hub"], "expected": {key: value * N**power}}]
    alts = [{"effect": effect, "targets": ["rotor"], "expected": {key: value / N**power}}]
    if node == "pump":
        alts.insert(0, {"effect": effect, "targets": ["hub"], "expected": {key: value}})
    return alts


def sensor(probe: str, kind: str, value: float):
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def emf_harmonic(order: int, amp: float, phase: float):
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"emf_h": (order, a, b)}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": amp, "phase_rad": phase,
                       "form": f"the EMF gains w k_h sin({order} th + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def inductor_saturation(ipar: float, ratio: float):
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"I_knee_A": ipar, "L_ratio_saturated": ratio,
                       "form": "L(i) = L (ratio + (1 - ratio)/(1 + (i/Ipar)^2)), the "
                               "differential inductance of Modelica's SaturatingInductor"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def warmup(rise: float, tau: float):
    return {"warmup": (rise, tau)}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + rise*(1 - exp(-t/tau)))", "rise": rise,
                       "tau_s": tau},
        "expected": {"rise": rise, "tau": tau}}


def coulomb(node: str, c: float):
    return {"coul": {node: c}}, {
        "effect": "coulomb-friction", "target": node, "targets": [node],
        "parameters": {"Fc_Nm": c, "form": f"c tanh(w_{node}/0.01) against the {node}"},
        "expected": {"c": c},
        "also_accept": _alternatives("coulomb-friction", node, "c", c, 1)}


def viscous(node: str, b: float):
    return {"visc": {node: b}}, {
        "effect": "viscous-friction", "target": node, "targets": [node],
        "parameters": {"b_extra_Nms_rad": b, "form": f"b w_{node} against the {node}"},
        "expected": {"b": b},
        "also_accept": _alternatives("viscous-friction", node, "b", b, 2)}


def force_offset(node: str, f: float):
    return {"offset": {node: f}}, {
        "effect": "force-offset", "target": node, "targets": [node],
        "parameters": {"T_Nm": f, "form": f"the {node} receives a constant F"},
        "expected": {"F": f},
        "also_accept": _alternatives("force-offset", node, "F", f, 1)}


def source_resistance(r: float, regime: str):
    src = SOURCE[regime]
    return {"Rs": r}, {
        "effect": "source-resistance", "target": src, "targets": [src],
        "parameters": {"R_source_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": ["Ra", "La", "M", src],
                         "expected": {"R": r}}]}


outside = recordkit.outside


combine = recordkit.combine




def sim(regime: str, fx: dict, states: bool = False) -> dict[str, np.ndarray]:
    fx = dict(fx)
    p = {**P, **fx.pop("p", {})}
    return sk.simulate(regime, None, fx, p, states=states)


# ---------------------------------------------------------------------- the records

def spec(rid, cls, regime, parts=(), noise=None, note="", marginal=None, size=None):
    fx, effects = combine(parts)
    return {"id": rid, "class": cls, "regime": regime, "fx": fx, "effects": effects,
            "noise": noise, "note": note, "marginal": marginal, "size": size}


def record_specs() -> list[dict[str, Any]]:
    ecc = (0.08, 0.6)
    odrift = (0.15, 2.0)
    out = [
        spec("r01", "null", "fast", note="white noise"),
        spec("r02", "null", "slow",
             noise={"current": {"ar1": [0.012, 0.85], "quant": 0.025},
                    "speed": {"white": 0.15, "pink": 0.15, "quant": 0.2},
                    "load_speed": {"white": 0.04, "quant": 0.05}},
             note="coloured noise: AR(1) current noise (phi 0.85), 1/f speed noise; ADC steps "
                  "25 mA, 0.2 rad/s, 0.05 rad/s"),
        spec("r03", "catalog", "fast", (inductor_saturation(12.0, 0.6),),
             noise={"current": {"white": 0.02, "quant": 0.025}, "speed": {"white": 0.2}},
             note="the armature's iron saturates: its differential inductance falls to half "
                  "of the declared 0.45 mH at 12 A and towards 0.6 of it at large currents "
                  "(knee 12 A, ratio 0.6); seen in the current's rise and fall at the "
                  "reversal (-25 A) and the braking"),
        spec("r04", "catalog", "fast", (emf_harmonic(18, 1e-3, 0.4),),
             marginal=lambda s: (emf_harmonic(18, s, 0.4),), size=1e-3,
             note="the motor's 9-segment commutator ripples its EMF 18 times per turn: an EMF "
                  "harmonic of order 18 (voltage only), scaled to a 25 sigma signature "
                  "(marginal)"),
        spec("r05", "catalog", "slow", (warmup(0.18, 2.5),),
             note="the armature winding warms up over the record: its resistance rises by "
                  "18 % with a 2.5 s time constant (the record starts from a cold motor)"),
        spec("r06", "catalog", "slow", (coulomb("pump", 0.08),),
             noise={"current": {"ar1": [0.015, 0.7]}, "speed": {"white": 0.2},
                    "load_speed": {"white": 0.05}},
             note="the pump's carbon bushings are worn and its gears rub the housing: an "
                  "extra Coulomb friction of 0.08 N m on the pump (over its declared 0.06 "
                  "N m); the pump reverses, so it is no torque offset"),
        spec("r07", "catalog", "slow", (force_offset("pump", -0.02),),
             marginal=lambda s: (force_offset("pump", s),), size=-0.02,
             note="the loop's outlet rises to a header tank above the pump: a static head "
                  "the pump works against in both directions, a constant torque against "
                  "forward rotation (a force offset on the pump), scaled to a 25 sigma "
                  "signature (marginal)"),
        spec("r08", "two", "fast", (source_resistance(0.15, "fast"),
                                    sensor("current", "offset", 0.06)),
             noise={"current": {"white": 0.02}, "speed": {"white": 0.15, "pink": 0.15}},
             note="the bench supply feeds the drive through 4 m of thin cable (0.15 ohm of "
                  "source resistance), and the current sensor's amplifier reads 60 mA "
                  "high at zero current (an offset)"),
        spec("r09", "two", "slow", (viscous("rotor", 2e-5), sensor("speed", "gain", 0.98)),
             noise={"current": {"white": 0.02}, "speed": {"white": 0.2, "pink": 0.15},
                    "load_speed": {"white": 0.05}},
             note="the motor's rear ball bearing holds stiff grease: an extra viscous "
                  "friction of 2e-5 N m s/rad on the rotor (9 mN m at 460 rad/s), and the "
                  "encoder's speed reads 2 % low (its line count mis-set in the drive)"),
        spec("r10", "outside", "fast", (outside(
            "compliant-hose", {"hose": 0.03},
            {"tau_s": 0.03,
             "form": "the pump's load is bp x instead of bp wp, tau dx/dt = wp - x, x(0) = 0 "
                     "(the loop's pressure behind a compliant hose, a hydraulic RC)"}),),
            note="the loop's hose is soft (and holds an air pocket): the pressure the pump "
                 "works against is the hose's, charged by the pump's flow and discharged "
                 "through the loop's restriction, with a 30 ms time constant. The load torque "
                 "lags the pump's speed: the run-up draws less current and runs ahead (443 "
                 "against 431 rad/s at 100 ms, 4.5 against 5.1 A), and at the braking and the "
                 "reversal the hose's stored pressure keeps pushing on the pump (-289 against "
                 "-265 rad/s at 300 ms). A person sees an inertia and a viscous load that do "
                 "not agree with each other from one transient to the next"),
        spec("r11", "outside", "fast", (outside(
            "eccentric-magnetic-coupling", {"ecc": ecc},
            {"eps": ecc[0], "phase_rad": ecc[1],
             "form": "the coupling's torque is Tm (1 + eps cos(hub angle + phase)) "
                     "sin(np (hub angle - pump angle))"}),),
            note="the outer magnet ring sits off-centre on the gearhead's hub: the air gap "
                 "to the inner rotor goes round once per hub turn, and the coupling's "
                 "strength with it (+-8 %). Nothing happens while the coupling carries no "
                 "torque; under load the twist (and the pump's speed relative to the hub) "
                 "ripples once per hub turn (a quarter of the rotor's order 1) by an amount "
                 "proportional to the torque carried. A person sees a ripple at the hub's "
                 "order 1, like an unbalance of the hub, whose size follows the load and "
                 "whose sign follows the torque's"),
        spec("r12", "outside", "slow", (outside(
            "current-sensor-offset-drift", {"odrift": odrift},
            {"o1_A": odrift[0], "tau_s": odrift[1],
             "form": "the current probe reads i + o1 (1 - exp(-t/tau))"}),),
            note="the Hall current sensor warms up in the drive's enclosure and its offset "
                 "drifts from 0 to 150 mA with a 2 s time constant (95 mA at 2 s, 147 mA at "
                 "8 s). A person sees a current offset that is not constant: the standstill "
                 "currents read 0 at the start and 0.13-0.15 A later, while the speeds say "
                 "the motor is the declared one"),
        spec("r13", "outside", "slow", (outside(
            "direction-dependent-pump-load", {"asym": 0.01},
            {"b2_Nms_rad": 0.01,
             "form": "the pump receives -b2 (wp - sqrt(wp^2 + 0.01^2))/2 (about -b2 min(wp, 0)) "
                     "over the declared -bp wp"}),),
            note="when the pump turns backwards (to drain the loop), the flow returns through "
                 "the relief valve's narrow bypass instead of the loop: a laminar load of 3 "
                 "times the declared one (bp + b2 = 0.015 instead of 0.005 N m s/rad), "
                 "forward the declared load. Backwards at -14 V the pump turns at -53 instead of "
                 "-66 rad/s and the motor draws -4.9 instead of -2.3 A. A person sees a "
                 "pump whose declared viscous load is right forwards and a third of the "
                 "true one backwards: neither a viscous friction nor a Coulomb friction nor an offset, "
                 "but their sum with a |w| term no catalog effect has"),
        spec("r14", "outside", "slow", (outside(
            "pump-inlet-cavitation", {"cavit": 150.0},
            {"wc_rad_s": 150.0,
             "form": "the pump's laminar load bp wp becomes bp wc tanh(wp/wc)"}),),
            noise={"current": {"ar1": [0.02, 0.7]}, "speed": {"white": 0.2},
                   "load_speed": {"white": 0.05}},
            note="the pump's inlet line is throttled (a clogged strainer): at the higher "
                 "speeds the inlet starves and cavitates, the delivered flow stops growing in "
                 "proportion to the speed, and with it the outlet pressure and the load "
                 "torque: 5 % below the declared load at 60 rad/s, 10 % at 87 rad/s, 16 % at "
                 "117 rad/s (at 24 V the pump turns at 117 instead of 115 rad/s, the motor "
                 "draws 3.2 instead of 3.7 A). A person sees a pump that runs faster and draws "
                 "less current than declared at the high speeds only: a load that bends over "
                 "with the speed"),
    ]
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- signatures

IMPRINTS = recordkit.Imprints(sk.simulate, WHITE)
null, signature, imprint = IMPRINTS.null, IMPRINTS.signature, IMPRINTS.imprint


#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-3}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:pump", {"coul": {"pump": 1e-2}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-6}}),
    ("viscous-friction:pump", {"visc": {"pump": 1e-4}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:pump", {"offset": {"pump": 1e-2}}),
    ("stribeck-friction:rotor:1", {"stribeck": {"rotor": (1e-4, 1.0)}}),
    ("stribeck-friction:rotor:3", {"stribeck": {"rotor": (1e-4, 3.0)}}),
    ("stribeck-friction:rotor:10", {"stribeck": {"rotor": (1e-4, 10.0)}}),
    ("stribeck-friction:pump:1", {"stribeck": {"pump": (1e-3, 1.0)}}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:10", {"lsat": (10.0, 0.999)}),
    ("inductor-saturation:30", {"lsat": (30.0, 0.999)}),
    ("inertia:Jp", {"p": {"Jp": P["Jp"] * 1.001}}),
    ("inertia:Jh", {"p": {"Jh": P["Jh"] * 1.001}}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.1", {"warmup": (1e-3, 0.1)}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
    ("resistance-drift:warmup-1", {"warmup": (1e-3, 1.0)}),
)
#: angle-locked catalog effects (two columns each: the sine and the cosine), for what the
#: outside records leave: (label, builder of the fx for one column)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("cogging:rotor:2", lambda a, b: {"cog": {"rotor": [(2, a, b)]}}),
    ("unbalance:hub", lambda a, b: {"cog": {"hub": [(1, a, b)]}}),
    ("unbalance:pump", lambda a, b: {"cog": {"pump": [(1, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf_h": (1, a, b)}),
    ("emf-harmonic:M:2", lambda a, b: {"emf_h": (2, a, b)}),
)


def alternatives(regime: str) -> dict[str, np.ndarray]:
    """Label -> (n, 1) imprint of each scalar catalog effect, per unit size, linearised."""
    return IMPRINTS.of_effects(regime, lambda fx: sim(regime, fx), SCALAR_EFFECTS,
                               sk.PROBES[regime], sk.REGIMES[regime][1], columns=True)


def harmonic_alternatives(regime: str) -> dict[str, np.ndarray]:
    return IMPRINTS.of_harmonics(
        regime, lambda fx: sim(regime, fx), HARMONIC_EFFECTS,
        lambda label: 1e-4 if "emf" in label else (1e-3 if "hub" in label or "pump" in label
                                                    else 1e-4))


def unexplained(regime: str, clean: dict) -> dict:
    """What the catalog's effects leave of an imprint [white sigma], linearised at the null:
    after the best single one, and after all of them at once (least squares). The
    angle-locked ones (an unbalance, cogging of order 2, EMF harmonics of orders 1 and 2)
    count as one effect of two columns."""
    return IMPRINTS.unexplained(regime, clean,
                                {**alternatives(regime), **harmonic_alternatives(regime)})


def separation(regime: str, clean: dict, same: set) -> dict[str, float]:
    """Distance [white sigma] of the imprint from each other scalar effect's best-scaled one."""
    return IMPRINTS.separation(regime, clean, alternatives(regime), same)


def scale_marginal(s: dict) -> None:
    """Scale a marginal record's size so that its best probe's signature is MARGINAL_SIGMA
    (its effect is linear in its size; two passes)."""
    size = s["size"]
    for _ in range(2):
        best = max(signature(s["regime"], sim(s["regime"], s["fx"])).values())
        size = float(f"{size * MARGINAL_SIGMA / best:.4g}")
        s["fx"], s["effects"] = combine(s["marginal"](size))
    s["size"] = size


def truth_entry(s: dict, sig: dict) -> dict:
    regime = s["regime"]
    fs, dur = sk.REGIMES[regime]
    ns = recordkit.noise_or_white(s, WHITE)
    return {
        "id": s["id"], "class": s["class"], "split": SPLIT, "motor": MOTOR,
        "netlist": NETLIST[regime], "regime": regime, "sample_rate_Hz": fs,
        "duration_s": dur, "csv": f"benchmarks/diagnosis/records/{s['id']}.csv",
        "probes": list(sk.PROBES[regime]), "inputs": ["u"] if regime == "slow" else [],
        "free": [], "declared_error": {}, "noise": ns, "noise_text": recordkit.noise_text(ns),
        "seed": s["seed"], "effects": s["effects"], "declared_terms": [],
        "signature_sigma": sig, "marginal": s["marginal"] is not None, "note": s["note"],
    }


def make(s: dict, write: bool) -> dict:
    regime = s["regime"]
    if s["marginal"] is not None:
        scale_marginal(s)
    clean = sim(regime, s["fx"])
    entry = truth_entry(s, signature(regime, clean))
    if s["class"] == "outside":
        entry["unexplained_sigma"] = unexplained(regime, clean)
    if s["marginal"] is not None:
        e = s["effects"][0]
        same = {e["effect"], *(a["effect"] for a in e.get("also_accept", []))}
        entry["separation_sigma"] = separation(regime, clean, same)
    if write:
        rng = np.random.default_rng(s["seed"])
        ns = recordkit.noise_or_white(s, WHITE)
        cols = {p: sk.add_noise(rng, clean[p], ns[p]) for p in sk.PROBES[regime]}
        if regime == "slow":
            cols["u"] = clean["u"]
        RECORDS.mkdir(exist_ok=True)
        recordkit.write_csv(RECORDS / f"{s['id']}.csv", sk.grid(regime), cols)
    return entry


def main(argv: list[str] | None = None) -> int:
    return recordkit.main(argv, __doc__, record_specs, make, "K")


if __name__ == "__main__":
    sys.exit(main())
