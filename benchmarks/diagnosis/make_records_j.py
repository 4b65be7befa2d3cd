"""Generate the blind set ``fresh9`` of the diagnosis benchmark: records q01-q14 of motor J
(a 30 V brushed DC servo motor driving a horizontal robot-arm joint through a 100:1 harmonic
drive whose flexspline is a declared torsional compliance), and merge their truth into
truth.json.

    python benchmarks/diagnosis/make_records_j.py              # records/q*.csv + truth.json
    python benchmarks/diagnosis/make_records_j.py --only q03,q12
    python benchmarks/diagnosis/make_records_j.py --truth-only # rewrite the q entries only

Uses simulators_j.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe [SI] (and, in the slow regime, the command ``u``
[V] that motor_j_slow.yaml reads from its own table). truth.json is merged under an exclusive
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
import simulators_j as sj

RECORDS = HERE / "records"
TRUTH = HERE / "truth.json"
LOCK = HERE / ".truth.lock"
SPLIT = "fresh9"
MOTOR = "J"
SEED0 = 9500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_j.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_j_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.02, "speed": 0.2},
         "slow": {"current": 0.02, "speed": 0.2, "load_speed": 0.005}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
P = sj.MOTOR_J
N = P["N"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_j, truth effect). ``expected`` is keyed by the
# catalog patch's parameter suffixes. The harmonic drive's reduction is rigid and lossless: a
# torque on the arm is one 1/N as large on the rotor, a viscous coefficient 1/N^2; the cup
# `hd` turns with the arm but for the flexspline's twist (below a milliradian), so a torque
# on `hd` is the same observation as one on the arm.

def _arm_alternatives(effect: str, key: str, value: float, power: int) -> list[dict]:
    return [{"effect": effect, "targets": ["hd"], "expected": {key: value}},
            {"effect": effect, "targets": ["rotor"], "expected": {key: value / N**power}}]


def sensor(probe: str, kind: str, value: float):
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def cogging(node: str, order: int, amp: float, phase: float):
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    e = {"effect": "unbalance" if order == 1 else "cogging", "target": node,
         "targets": [node], "order": order,
         "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                        "form": f"{node} receives T sin({order} angle + phase)"},
         "expected": {"a": a, "b": b}}
    if order == 1:
        e["also_accept"] = [{"effect": "cogging", "targets": [node], "order": 1,
                             "expected": {"a": a, "b": b}}]
        if node == "arm":
            # the cup turns with the arm (its angle differs by the flexspline's twist)
            e["also_accept"] += [{"effect": lab, "targets": ["hd"], "order": 1,
                                  "expected": {"a": a, "b": b}}
                                 for lab in ("unbalance", "cogging")]
    return {"cog": {node: [(order, a, b)]}}, e


def stribeck(node: str, s: float, ws: float):
    return {"stribeck": {node: (s, ws)}}, {
        "effect": "stribeck-friction", "target": node, "targets": [node],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": f"{node} takes s exp(-(w/ws)^2) tanh(w/0.01) over the "
                               "declared Tc tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def viscous_arm(b: float):
    return {"visc": {"arm": b}}, {
        "effect": "viscous-friction", "target": "arm", "targets": ["arm"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b w_arm against the arm"},
        "expected": {"b": b},
        "also_accept": _arm_alternatives("viscous-friction", "b", b, 2)}


def coulomb_arm(c: float):
    return {"coul": {"arm": c}}, {
        "effect": "coulomb-friction", "target": "arm", "targets": ["arm"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(w_arm/0.01) against the arm"},
        "expected": {"c": c},
        "also_accept": _arm_alternatives("coulomb-friction", "c", c, 1)}


def brush_drop(vb: float):
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with M"},
        "expected": {"Vb": vb}}


def series_resistance(r: float, regime: str):
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": ["Ra", "La", "M"],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


outside = recordkit.outside


combine = recordkit.combine




def sim(regime: str, fx: dict, states: bool = False) -> dict[str, np.ndarray]:
    fx = dict(fx)
    p = {**P, **fx.pop("p", {})}
    return sj.simulate(regime, None, fx, p, states=states)


# ---------------------------------------------------------------------- the records

def spec(rid, cls, regime, parts=(), noise=None, note="", marginal=None, size=None):
    fx, effects = combine(parts)
    return {"id": rid, "class": cls, "regime": regime, "fx": fx, "effects": effects,
            "noise": noise, "note": note, "marginal": marginal, "size": size}


def record_specs() -> list[dict[str, Any]]:
    kinerr = (1.2e-4, 0.7)       # [rad] at the output (0.41 arcmin), phase
    demag = (0.06, 27.0, 2.0, 2e4)
    out = [
        spec("q01", "null", "fast", note="white noise"),
        spec("q02", "null", "slow",
             noise={"current": {"ar1": [0.012, 0.85], "quant": 0.025},
                    "speed": {"white": 0.15, "pink": 0.15, "quant": 0.2},
                    "load_speed": {"white": 0.004, "quant": 0.005}},
             note="coloured noise: AR(1) current noise (phi 0.85), 1/f speed noise; ADC steps "
                  "25 mA, 0.2 rad/s, 0.005 rad/s"),
        spec("q03", "catalog", "fast", (sensor("current", "gain", 0.97),),
             note="the current sensor's amplifier reads 3 % low (a shunt amplifier's gain "
                  "resistor out of tolerance): every current, inrush, braking and running, "
                  "reads 0.97 of itself"),
        spec("q04", "catalog", "fast", (cogging("rotor", 10, 2e-3, 1.1),),
             noise={"current": {"white": 0.02, "quant": 0.025}, "speed": {"white": 0.2}},
             marginal=lambda s: (cogging("rotor", 10, s, 1.1),), size=2e-3,
             note="the motor's detent (cogging) torque: a 2-pole, 5-slot motor pulls its "
                  "rotor 10 times per turn, scaled to a 25 sigma signature (marginal)"),
        spec("q05", "catalog", "slow", (cogging("arm", 1, 0.6, 0.8),),
             note="the robot stands on a floor tilted by about 3 degrees: the arm's own "
                  "weight (11.8 N m of m g l) pulls it towards the low side with 0.6 N m "
                  "sin(arm angle + 0.8): an unbalance of the arm, once per arm turn; the arm "
                  "swings over 4.7 rad"),
        spec("q06", "catalog", "slow", (stribeck("rotor", 8e-3, 3.0),),
             noise={"current": {"ar1": [0.015, 0.7]}, "speed": {"white": 0.2},
                    "load_speed": {"white": 0.005}},
             note="the harmonic drive's wave generator sticks before it slides: a breakaway "
                  "peak of 8 mN m over the declared 6 mN m running friction (a breakaway of 14 "
                  "mN m), fading over 3 rad/s of the rotor; seen in the jogs and the stops"),
        spec("q07", "catalog", "slow", (viscous_arm(0.05),),
             marginal=lambda s: (viscous_arm(s),), size=0.05,
             note="the arm's output bearing has stiffer grease than declared: an extra "
                  "viscous friction on the arm, scaled to a 25 sigma signature (marginal)"),
        spec("q08", "two", "fast", (brush_drop(0.5), sensor("speed", "delay", 3e-4)),
             noise={"current": {"white": 0.02}, "speed": {"white": 0.15, "pink": 0.15}},
             note="the carbon brushes take a contact drop of 0.5 V, and the speed, estimated "
                  "by the drive from encoder edges, lags the shaft by 0.3 ms"),
        spec("q09", "two", "slow", (series_resistance(0.12, "slow"), coulomb_arm(0.5)),
             noise={"current": {"white": 0.02}, "speed": {"white": 0.2, "pink": 0.15},
                    "load_speed": {"white": 0.005}},
             note="a 0.12 ohm contact resistance in the motor's connector, and the arm's "
                  "output seal drags with 0.5 N m of Coulomb friction"),
        spec("q10", "outside", "fast", (outside(
            "harmonic-drive-transmission-error", {"kinerr": kinerr},
            {"eps_rad": kinerr[0], "phase_rad": kinerr[1],
             "form": "the flexspline's output angle is th/N + eps sin(2 th + phase), th the "
                     "rotor (wave generator) angle; the rotor receives -T_K (1/N + 2 eps "
                     "cos(2 th + phase))"}),),
            note="the harmonic drive's transmission error: its output runs ahead of and "
                 "behind the perfect 100:1 gear by 0.12 mrad (0.41 arcmin), twice per turn "
                 "of the wave generator. The flexspline is pumped at twice the rotor's "
                 "frequency: a torque ripple of order 2 of the rotor whose size and phase "
                 "follow the joint's 35.8 Hz resonance (met when the rotor turns at 112 "
                 "rad/s; about c eps = 0.72 N m at the arm well above it) and which grows with "
                 "the transmitted torque (0.6-1.6 rad/s of speed ripple, 40-100 mA of current "
                 "ripple). A person sees a speed ripple at twice the rotor's "
                 "frequency, like a cogging of order 2, but one whose amplitude and phase "
                 "change with the speed and the load"),
        spec("q11", "outside", "fast", (outside(
            "current-sensor-hysteresis", {"hyst": 0.08},
            {"h_A": 0.08,
             "form": "the current probe reads the play operator of half-width h of the "
                     "current (the reading follows the current h behind in the direction it "
                     "last moved, and holds while the current turns back within 2 h)"}),),
            note="the Hall current sensor's core is magnetised by the large currents and "
                 "its reading carries a hysteresis of +-80 mA: while the current rises the "
                 "reading is 80 mA low, while it falls 80 mA high, and at each turn of the "
                 "current the reading holds still until the current has moved 160 mA. A "
                 "person sees an offset that flips sign with the current's slope, as if the "
                 "current were read late but by the same amount at every slope"),
        spec("q12", "outside", "slow", (outside(
            "cable-harness-spring", {"harness": (0.8, 0.4)},
            {"kc_Nm_rad": 0.8, "th0_rad": 0.4,
             "form": "the arm receives -kc (arm angle - th0)"}),),
            note="the cable harness that runs along the arm to its gripper twists with it "
                 "like a torsion spring of 0.8 N m/rad, relaxed at 0.4 rad from the start "
                 "position: 1.7 to 2.0 N m at the arm's extremes (0.35-0.4 A of current). A "
                 "person sees a holding current that follows the arm's position, and an arm "
                 "that drifts back towards the harness's rest angle when the motor is "
                 "short-circuited at standstill; close to an unbalance of the arm over a "
                 "small swing, but linear in the angle over the 4.7 rad the arm travels"),
        spec("q13", "outside", "slow", (outside(
            "dragging-holding-brake", {"brake": (8e-3, 2.0)},
            {"Tb_Nm": 8e-3, "phase_rad": 2.0,
             "form": "the rotor receives -Tb (1 + cos(th + phase))/2 tanh(w/0.01)"}),),
            noise={"current": {"ar1": [0.02, 0.7]}, "speed": {"white": 0.2},
                   "load_speed": {"white": 0.005}},
            note="the servo motor's spring-applied holding brake is not fully released: its "
                 "warped friction disc rubs once per rotor turn, a friction between 0 and 8 "
                 "mN m (half of it on average) that always opposes the rotor's motion. A "
                 "person sees extra Coulomb friction plus a ripple once per rotor turn whose "
                 "phase flips with the direction of rotation, which no torque locked to the "
                 "angle (an unbalance of the rotor) does"),
        spec("q14", "outside", "fast", (outside(
            "irreversible-demagnetisation", {"demag": demag},
            {"delta": demag[0], "I1_A": demag[1], "Iw_A": demag[2], "G_per_s": demag[3],
             "form": "kf = 1 - delta (1 - exp(-(max(m - I1, 0)/Iw)^2)), m the peak |i| so "
                     "far; EMF kf k w and torque kf k i"}),),
            note="the plugging reversal at 200 ms drives the current to -30 A, beyond the "
                 "magnets' limit (27 A): they lose 5.3 % of their flux for good. Before the "
                 "reversal the motor is exactly the declared one; after it, it runs about "
                 "5.5 % faster on the same voltage (-416 instead of -395 rad/s at -20 V) and "
                 "needs 5.6 % more current for the same torque. A person sees the record split in two at the reversal"),
    ]
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- signatures

IMPRINTS = recordkit.Imprints(sj.simulate, WHITE)
null, signature, imprint = IMPRINTS.null, IMPRINTS.signature, IMPRINTS.imprint


#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-3}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:arm", {"coul": {"arm": 1e-2}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:arm", {"visc": {"arm": 1e-3}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:arm", {"offset": {"arm": 1e-2}}),
    ("stribeck-friction:rotor:1", {"stribeck": {"rotor": (1e-4, 1.0)}}),
    ("stribeck-friction:rotor:3", {"stribeck": {"rotor": (1e-4, 3.0)}}),
    ("stribeck-friction:rotor:10", {"stribeck": {"rotor": (1e-4, 10.0)}}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:10", {"lsat": (10.0, 0.999)}),
    ("inductor-saturation:30", {"lsat": (30.0, 0.999)}),
    ("inertia:Ja", {"p": {"Ja": P["Ja"] * 1.001}}),
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
    ("unbalance:arm", lambda a, b: {"cog": {"arm": [(1, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf_h": (1, a, b)}),
    ("emf-harmonic:M:2", lambda a, b: {"emf_h": (2, a, b)}),
)


def alternatives(regime: str) -> dict[str, np.ndarray]:
    """Label -> (n, 1) imprint of each scalar catalog effect, per unit size, linearised."""
    return IMPRINTS.of_effects(regime, lambda fx: sim(regime, fx), SCALAR_EFFECTS,
                               sj.PROBES[regime], sj.REGIMES[regime][1], columns=True)


def harmonic_alternatives(regime: str) -> dict[str, np.ndarray]:
    return IMPRINTS.of_harmonics(
        regime, lambda fx: sim(regime, fx), HARMONIC_EFFECTS,
        # "emf-harmonic" holds "arm": the EMF's test comes first
        lambda label: 1e-4 if "emf" in label else (1e-2 if "arm" in label else 1e-4))


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
    fs, dur = sj.REGIMES[regime]
    ns = recordkit.noise_or_white(s, WHITE)
    return {
        "id": s["id"], "class": s["class"], "split": SPLIT, "motor": MOTOR,
        "netlist": NETLIST[regime], "regime": regime, "sample_rate_Hz": fs,
        "duration_s": dur, "csv": f"benchmarks/diagnosis/records/{s['id']}.csv",
        "probes": list(sj.PROBES[regime]), "inputs": ["u"] if regime == "slow" else [],
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
        cols = {p: sj.add_noise(rng, clean[p], ns[p]) for p in sj.PROBES[regime]}
        if regime == "slow":
            cols["u"] = clean["u"]
        RECORDS.mkdir(exist_ok=True)
        recordkit.write_csv(RECORDS / f"{s['id']}.csv", sj.grid(regime), cols)
    return entry


def main(argv: list[str] | None = None) -> int:
    return recordkit.main(argv, __doc__, record_specs, make, "J")


if __name__ == "__main__":
    sys.exit(main())
