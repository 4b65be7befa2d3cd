"""Generate the blind set ``fresh38`` of the diagnosis benchmark: records ap01-ap14 of motor AM
(a 24 V brushed DC motor with a flywheel-fan in an under-desk walking-pad treadmill: a rigid
3:1 poly-V belt to the front roller, the walking belt's stretch a compliance to the belt and
the rear roller, the belt meeting the deck's silicone film and its dry friction, the fan's
windage on the rotor), some sampled evenly and some UNEVENLY, three of them giving the
diagnosis ONE probe only, and merge their truth into truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_am.py                # records/ap*.csv + truth.json
    python benchmarks/diagnosis/make_records_am.py --only ap03,ap12
    python benchmarks/diagnosis/make_records_am.py --truth-only   # rewrite the ap entries only

Uses simulators_am.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_am_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the catalog imprints it is compared with are computed on that probe
alone (``OneProbe``). Even records are sampled on the regime's grid k/fs; uneven ones, in the
fast regime, on a 25 kHz grid whose every sample is moved by a random jitter of up to 10-30 %
of the interval, and in the slow regime at a logger's irregular intervals (0.6-1.4 times the
mean of 5 ms) with a few samples dropped. Each uneven record has its own times (from its
seed), and the motor is simulated at those very times (``t_eval``), never interpolated.
truth.json is merged under an exclusive lock (recordkit.merge). An outside record whose
imprint the catalog's effects jointly leave less than OUTSIDE_LEFT of is reported (it would
not be outside in effect). Nobody ran the diagnosis on these records.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import recordkit
import simulators_am as sa

RECORDS = HERE / "records"
SPLIT = "fresh38"
MOTOR = "AM"
SEED0 = 38500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_am_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_am_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.08, "speed": 0.5},
         "slow": {"current": 0.05, "speed": 0.4, "load_speed": 0.06}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: an outside record's imprint must keep at least this fraction after all the catalog's
#: effects jointly (linearised)
OUTSIDE_LEFT = 0.2
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AM
N = P["N"]
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_am, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The poly-V belt is rigid and lossless as declared: a
# torque on the body ``hub`` (the front roller) is 1/N = 1/3 of it on the rotor, and the
# roller turns with the rotor. The walking belt lies behind its own stretch (compliant, 1:1
# in the reflected frame): an effect on it has no exact equal on the front roller.

def source_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] inside the source (the supply's leads and its connector)."""
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[regime], "targets": [SOURCE[regime]],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": LOOP,
                         "expected": {"R": r}}]}


def saturation(ipar: float, ratio: float) -> Part:
    """The armature inductance saturating: La (ratio + (1 - ratio) / (1 + (i / Ipar)^2))."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def speed_delay(tau: float) -> Part:
    """The speed sensor read through a lag of ``tau`` [s] (a marginal record scales it)."""
    return sensor("speed", "delay", tau)


def cogging_rotor(order: int, amp: float, phase: float) -> Part:
    """A detent torque amp sin(order th + phase) [N m] on the rotor (accepted on the front
    roller at the order order N and the amplitude amp N)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["hub"], "order": round(order * N),
                         "expected": {"a": a * N, "b": b * N}}]}


def unbalance_rotor(amp: float, phase: float) -> Part:
    """A once-per-turn torque amp sin(th + phase) [N m] on the rotor (accepted as a cogging
    of order 1 on the rotor, and of order N on the front roller at amp N)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(1, a, b)]}}, {
        "effect": "unbalance", "target": "rotor", "targets": ["rotor"], "order": 1,
        "parameters": {"order": 1, "T_Nm": amp, "phase_rad": phase,
                       "form": "rotor receives T sin(1 angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["rotor"], "order": 1,
                         "expected": {"a": a, "b": b}},
                        {"effect": "cogging", "targets": ["hub"], "order": round(N),
                         "expected": {"a": a * N, "b": b * N}}]}


def viscous_rotor(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the rotor (accepted on the front
    roller at b N^2)."""
    return {"visc": {"rotor": b}}, {
        "effect": "viscous-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b w against the rotor"},
        "expected": {"b": b},
        "also_accept": [{"effect": "viscous-friction", "targets": ["hub"],
                         "expected": {"b": b * N ** 2}}]}


def stribeck_belt(s: float, ws: float) -> Part:
    """A breakaway peak s exp(-(wb/ws)^2) tanh(wb/0.01) [N m] over the walking belt's
    declared dry friction, ``ws`` [rad/s] (behind the belt's stretch)."""
    return {"stribeck": {"belt": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "belt", "targets": ["belt"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "F_peak_N": s / sa.R_ROLLER, "v_stribeck_m_s": ws * sa.R_ROLLER,
                       "form": "belt takes s exp(-(w/ws)^2) tanh(w/0.01) over the declared "
                               "Td tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def viscous_belt(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the walking belt (behind its
    stretch)."""
    return {"visc": {"belt": b}}, {
        "effect": "viscous-friction", "target": "belt", "targets": ["belt"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b wb against the walking belt"},
        "expected": {"b": b}}


def inertia_belt(dj: float) -> Part:
    """The walking belt's inertia (with the rear roller) off by a factor 1 + ``dj`` (a
    correction of Jt's J, the parameter Jt)."""
    return {"p": {"Jt": P["Jt"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jt", "targets": ["Jt"], "correction": True,
        "parameters": {"Jt_true_kgm2": P["Jt"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AM's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sa.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sa.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the shunt amplifier's current: a 12-bit ADC over +-64 A (31.3 mA steps)
ADC_STEP = 128.0 / 4096
#: the flywheel-fan's optical speed sensor, 12-bit over +-400 rad/s (0.195 rad/s steps)
SPEED_STEP = 800.0 / 4096
#: the rear roller's reed sensor, as the logger stores it: 0.02 rad/s steps
BELT_STEP = 0.02


def nulls() -> list[dict[str, Any]]:
    """ap01, ap02: the null records."""
    return [
        spec("ap01", "null", "slow", True,
             noise={"current": {"white": 0.04, "pink": 0.03, "quant": ADC_STEP},
                    "speed": {"white": 0.3, "ar1": [0.3, 0.8]},
                    "load_speed": {"white": 0.05, "quant": BELT_STEP}},
             note="the treadmill controller's service log at its logger's irregular "
                  "intervals; the current with 1/f noise (30 mA: the brushes' contact on a "
                  "worn commutator) on white noise, read by the 12-bit ADC (31.3 mA steps); "
                  "the flywheel-fan's optical speed with Gauss-Markov noise (correlation 0.8 "
                  "over the interval, 0.3 rad/s: the stripes' uneven print) on white noise; "
                  "the rear roller's reed sensor on white noise, stored in 0.02 rad/s steps"),
        spec("ap02", "null", "fast", False, probes=("speed",),
             noise={"speed": {"white": 0.4, "pink": 0.3, "quant": SPEED_STEP}},
             note="a bench log of the speed alone, an even 25 kHz acquisition; the "
                  "flywheel-fan's optical speed with 1/f noise (0.3 rad/s) on white noise, "
                  "read as 12 bits (0.195 rad/s steps)"),
    ]


def singles() -> list[dict[str, Any]]:
    """ap03-ap07, ap10: one catalog effect each."""
    return [
        spec("ap03", "catalog", "fast", True, (cogging_rotor(18, 0.1, 0.4),),
             note="the motor was replaced by a 2-pole, 9-slot motor with stronger ferrite "
                  "magnets whose slots were not skewed: a detent torque 18 times a turn of "
                  "the rotor, 0.1 N m, phase 0.4 rad"),
        spec("ap04", "catalog", "slow", False, (viscous_rotor(1.7e-5),),
             marginal=lambda b: (viscous_rotor(b),), size=1.7e-5,
             note="the motor's ball bearings were regreased with a stiff, low-temperature "
                  "grease: an extra viscous drag on the rotor over the declared bearings' and "
                  "fan's, scaled to a 25 sigma signature (marginal)"),
        spec("ap05", "catalog", "fast", False, (inertia_belt(0.25),),
             note="the walking belt was replaced by a thicker, heavier cushioned belt: the "
                  "belt with the rear roller has 25 % more inertia than the declared"),
        spec("ap06", "catalog", "slow", True, (stribeck_belt(0.35, 1.5),),
             note="the treadmill stood folded under the desk for a fortnight and the deck's "
                  "silicone film has crept from under the belt: the belt's underside sticks "
                  "to the deck on starting, a breakaway of 0.35 N m at the rollers (15 N at "
                  "the belt) over the declared dry friction, fading above about 1.5 rad/s "
                  "(36 mm/s of the belt)"),
        spec("ap07", "catalog", "fast", False, (saturation(12.0, 0.45),),
             probes=("current",), noise={"current": {"white": 0.08, "quant": ADC_STEP}},
             note="a bench log of the current alone (the 12-bit ADC); the replacement "
                  "motor's thin stator ring saturates under the armature's field at the "
                  "start's and the reversal's high currents: the armature inductance falls "
                  "to 45 % of the declared, half way at 12 A"),
        spec("ap10", "catalog", "fast", True, (speed_delay(7e-5),),
             marginal=lambda tau: (speed_delay(tau),), size=7e-5, probes=("speed",),
             note="a bench log of the optical speed alone; the sensor's new interface board "
                  "filters its speed output: the speed lags the flywheel-fan by a small "
                  "delay, scaled to a 25 sigma signature (marginal)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """ap08, ap09: two catalog effects at once."""
    return [
        spec("ap08", "two", "slow", True,
             (viscous_belt(1.5e-3), sensor("load_speed", "gain", 0.96)),
             note="the deck was re-lubricated with a thick silicone grease instead of the "
                  "thin oil: an extra viscous drag of 1.5e-3 N m s/rad on the walking belt; "
                  "and the rear roller was replaced by a 50 mm one while the logger still "
                  "converts its reed pulses for the declared 48 mm: the belt's speed reads "
                  "4 % low"),
        spec("ap09", "two", "fast", False,
             (source_resistance(0.12, "fast"), unbalance_rotor(0.04, 2.1)),
             note="the bench supply was wired through a long, thin extension lead: 0.12 Ohm "
                  "inside the source; and the flywheel-fan lost its balancing slug (about 60 "
                  "g at 68 mm): a once-a-turn gravity torque of 0.04 N m on the horizontal "
                  "rotor, phase 2.1 rad"),
    ]


#: the walker: the deck's friction under their weight Tw [N m] at the rollers (a 70 kg
#: person on a deck of friction 0.08), the cadence's swing a [1] of it at f [Hz], stepping on
#: at t1 and off at t2 [s], each over about d [s]
WALKER = (1.3, 0.3, 1.8, 4.3, 8.1, 0.08)
#: the belt's wavy edge: the rub's torque Tr [N m], the loop's length over r Lb [rad] (2.7 m
#: over 24 mm), where the stretch's middle meets the guide x0 [rad], its sharpness n
RUB = (0.3, 112.5, 40.0, 6)
#: the walking belt slipping on the front roller: the wrap's inertia Jc [kg m^2] (75 mm of
#: the belt on the roller), the grip's limit Tc [N m] at the roller, the slip's speed scale
#: ws [rad/s]
SLIP = (4.5e-5, 1.6, 0.5)
#: the motor's housing on rubber mounts: its inertia Js [kg m^2], the mounts' torsional
#: stiffness Km [N m/rad] and damping Dm [N m s/rad]
ROCK = (2.5e-3, 120.0, 0.1)


def outside_records() -> list[dict[str, Any]]:
    """ap11-ap14: effects the catalog does not contain."""
    return outside_slow() + outside_fast()


def outside_slow() -> list[dict[str, Any]]:
    """ap11, ap13: a person walking on the belt and the belt's wavy edge (slow)."""
    return [
        spec("ap11", "outside", "slow", True, (outside(
            "walker-steps-on-belt", {"walker": WALKER},
            {"Tw_Nm": WALKER[0], "a": WALKER[1], "f_Hz": WALKER[2], "t1_s": WALKER[3],
             "t2_s": WALKER[4], "d_s": WALKER[5],
             "form": "the belt receives -Tw (1 + a cos(2 pi f (t - t1))) s((t - t1)/d) "
                     "s((t2 - t)/d) tanh(wb/0.01), s(x) = 1/(1 + exp(-x)): a person steps "
                     "onto the running belt at t1 and off at t2; their weight presses the "
                     "belt onto the deck, whose friction (0.08) takes Tw at the rollers "
                     "(70 kg: 55 N at the belt), their vertical load swinging by a at the "
                     "walking cadence f; their feet ride the belt, adding no other "
                     "horizontal force on average"}),),
            note="someone tried the treadmill during the service log: stepping on at 4.3 s "
                 "(the belt at 3.7 km/h), walking at 108 steps a minute, and off at 8.1 s as "
                 "the program slowed the belt; a person sees the current rise from 0.85 A to "
                 "4-7 A, swinging at 1.8 Hz, the motor up to 27 rad/s slower (the belt 9 "
                 "rad/s), and all as declared once they are off; close to a dry friction on "
                 "the belt, but only while someone is on it, and swinging with their steps"),
        spec("ap13", "outside", "slow", False, (outside(
            "belt-edge-rubs-side-rail-once-a-loop", {"rub": RUB},
            {"Tr_Nm": RUB[0], "Lb_rad": RUB[1], "x0_rad": RUB[2], "n": RUB[3],
             "form": "the belt receives -Tr ((1 + cos(2 pi (thb - x0)/Lb))/2)^n "
                     "tanh(wb/0.01), thb the belt's angle (its travel over the rollers' "
                     "24 mm radius from where the record starts): the walking belt has "
                     "tracked to the left, and a wavy stretch of its edge (about a fifth of "
                     "the 2.7 m loop, its middle at x0) rubs the side rail's guide once each "
                     "loop, the rub's force peaking at Tr/r = 12.5 N"}),),
            note="the walking belt has tracked to the left and a stretch of its edge, made "
                 "wavy by an earlier mis-tracking, rubs the side rail's guide once a loop of "
                 "the belt (2.7 m, 112.5 rad of its angle); a person sees the current up by "
                 "0.9 A for about half a second three times: at 3.6 s (the belt 0.96 m from "
                 "the start), at 6.2 s and at 7.7 s, the motor up to 4.9 rad/s slower and the belt 1.6 "
                 "rad/s, and nothing between; close to a dry friction on the belt, but one "
                 "that acts once a loop of the belt, not at any whole order of a body's "
                 "turn"),
    ]


def outside_fast() -> list[dict[str, Any]]:
    """ap12, ap14: the walking belt slipping on the front roller and the housing rocking on
    its rubber mounts (fast)."""
    return [
        spec("ap12", "outside", "fast", False, (outside(
            "walking-belt-slips-on-front-roller", {"slip": SLIP},
            {"Jc_kgm2": SLIP[0], "Tc_Nm": SLIP[1], "ws_rad_s": SLIP[2],
             "form": "the walking belt's tension was let down and it slips on the front "
                     "roller: the stretch of belt wrapped on the roller (Jc of the declared "
                     "Jt, its own speed wc) receives +Tc tanh((w/N - wc)/ws) from the roller, "
                     "the roller the opposite; the belt's stretch K lies between the wrap "
                     "and the rest of the belt, which carries Jt - Jc"}),),
            noise={"current": {"white": 0.06, "ar1": [0.05, 0.7], "quant": ADC_STEP},
                   "speed": {"white": 0.5}},
            note="a bench acquisition of the current (the 12-bit ADC, the shunt amplifier's "
                 "own noise as Gauss-Markov noise, correlation 0.7 over the interval, 50 mA, "
                 "on white noise) and the optical speed; the walking belt's tension was let "
                 "down after it had been re-centred and it slips on the front roller whenever "
                 "the roller's pull passes 1.6 N m (67 N at the belt); a person sees the belt "
                 "slip late in the start's ramp (0.037 s to 0.131 s, the roller up to 11 "
                 "rad/s ahead of the belt), briefly as the supply drops to 12 V (0.24 s to "
                 "0.26 s), through the reversal (0.33 s to 0.43 s, up to 16 rad/s) and in the "
                 "stop (0.47 s to 0.49 s): the motor up to 7.8 rad/s faster than declared in "
                 "the start and reversing up to 11 rad/s sooner, the start's current up to "
                 "1.5 A lower and the reversal's braking current up to 2.1 A weaker; close "
                 "to a smaller inertia of the belt, but only while the roller's pull is "
                 "high"),
        spec("ap14", "outside", "fast", True, (outside(
            "motor-housing-rocks-on-rubber-mounts", {"rock": ROCK},
            {"Js_kgm2": ROCK[0], "Km_Nm_rad": ROCK[1], "Dm_Nms_rad": ROCK[2],
             "form": "the motor's housing (Js) turns about the motor's axis on its rubber "
                     "mounts (Km, Dm) under the reaction of the armature's torque: it "
                     "receives -k i - Km ths - Dm ws; the EMF is k (w - ws), w the rotor's "
                     "speed against the frame (the probe speed); the rotor's declared "
                     "frictions stay against the frame"}),),
            noise={"current": {"white": 0.08}, "speed": {"white": 0.4, "pink": 0.4}},
            note="the motor's cradle is held by four rubber bushings that have aged soft: "
                 "the housing (2.5e-3 kg m^2) rolls on them under the armature's reaction, "
                 "up to 0.027 rad, ringing at about 33 Hz; the speed column carries 1/f "
                 "noise (0.4 rad/s) on white noise; a person sees the current ring by up to "
                 "0.23 A after the start's ramp, the drop to 12 V and the reversal, and the "
                 "speed up to 0.4 rad/s off the declared; close to a resonance of the "
                 "walking belt, but at its own frequency and read mostly in the current"),
    ]


def record_specs() -> list[dict[str, Any]]:
    """The 14 records in id order, each with its seed."""
    out = sorted(nulls() + singles() + pairs() + outside_records(), key=lambda s: s["id"])
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- sample times

def times(s: dict[str, Any]) -> np.ndarray:
    """The record's sample times [s] (even, or uneven from its seed), once; described in
    ``s["timestamps"]`` (``recordkit.record_times``)."""
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 38, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:hub", {"coul": {"hub": 3e-4}}),
    ("coulomb-friction:belt", {"coul": {"belt": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:belt", {"visc": {"belt": 1e-5}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:belt", {"offset": {"belt": 1e-3}}),
    ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-4, 20.0)}}),
    ("stribeck-friction:belt", {"stribeck": {"belt": (1e-3, 1.5)}}),
    ("backlash:K", {"gap": 1e-4}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:30", {"lsat": (30.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jt", {"p": {"Jt": P["Jt"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:belt", lambda a, b: {"cog": {"belt": [(1, a, b)]}}),
    ("cogging:rotor:18", lambda a, b: {"cog": {"rotor": [(18, a, b)]}}),
    ("cogging:belt:2", lambda a, b: {"cog": {"belt": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:18", lambda a, b: {"emf": [(18, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1e-6 V s/rad of EMF), 1 mN m on the walking belt."""
    return 1e-4 if (":rotor" in label or label.startswith("emf")) else 1e-3


@dataclass(frozen=True)
class OneProbe(recordkit.Plumbing):
    """recordkit.Plumbing for records that may give the diagnosis fewer probes than their
    regime has: the signatures, the marginal scaling, the imprints of the catalog's effects
    (and of the sensors of the probes given only) and the CSV are those of the record's own
    ``probes``."""

    def white_of(self, s: dict[str, Any]) -> dict[str, dict[str, float]]:
        """The white sigma [probe unit] of the record's probes, in its regime."""
        return {s["regime"]: {p: self.white[s["regime"]][p] for p in s["probes"]}}

    def imprints(self, s: dict[str, Any]) -> recordkit.Imprints:
        """The null run and the imprints on the record's own times and probes, once."""
        if "imprints" not in s:
            t = self.times(s)
            s["imprints"] = recordkit.Imprints(lambda regime: self.sim(regime, t, {}),
                                               self.white_of(s))
        return s["imprints"]

    def alternatives(self, s: dict[str, Any]) -> dict[str, np.ndarray]:
        """Label -> (n, 1) imprint of each scalar catalog effect, per unit size, linearised
        (the sensor effects of the record's probes only)."""
        regime, t = s["regime"], self.times(s)
        return self.imprints(s).of_effects(
            regime, lambda fx: self.sim(regime, t, fx), self.scalar_effects, s["probes"],
            self.simulator.REGIMES[regime][1], self.sensor_steps, columns=True)

    def truth_entry(self, s: dict[str, Any], sig: dict) -> dict:
        """The record's entry of truth.json: its probes and their noise only."""
        entry = super().truth_entry(s, sig)
        ns = {p: v for p, v in recordkit.noise_or_white(s, self.white).items()
              if p in s["probes"]}
        entry.update(probes=list(s["probes"]), noise=ns,
                     noise_text=recordkit.noise_text(ns))
        return entry

    def scale_marginal(self, s: dict[str, Any]) -> None:
        """Scale a marginal record's size so that its best probe's signature is the set's
        marginal size on its own times: recordkit's proportional passes, repeated (up to
        eight) until within 1 % of it (a dry friction's imprint is not linear in its
        size)."""
        for _ in range(4):
            super().scale_marginal(s)
            clean = self.sim(s["regime"], self.times(s), s["fx"])
            best = max(self.imprints(s).signature(s["regime"], clean).values())
            if abs(best / self.marginal_sigma - 1.0) < 0.01:
                return

    def make(self, s: dict[str, Any], write: bool) -> dict:
        """One record: its truth entry, and its CSV (the record's probes, the command in
        the slow regime) when ``write``."""
        entry = super().make(s, False)
        if write:
            regime, t = s["regime"], self.times(s)
            clean = self.sim(regime, t, s["fx"])
            rng = np.random.default_rng(s["seed"])
            ns = recordkit.noise_or_white(s, self.white)
            cols = {p: self.simulator.add_noise(rng, t, clean[p], ns[p]) for p in s["probes"]}
            if regime == "slow":
                cols["u"] = clean["u"]
            RECORDS.mkdir(exist_ok=True)
            recordkit.write_csv(RECORDS / f"{s['id']}.csv", t, cols)
        return entry


#: across the walking belt's stretch (a spring and a damper, 1:1 in the reflected frame): the
#: body an effect on each is compared with, and the factor its size takes there per kind (the
#: front roller and the belt turn at one mean speed)
ACROSS = {"belt": ("hub", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0}),
          "hub": ("belt", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` across the walking belt's
    stretch (``recordkit.location_entry``), after a marginal record's scaling."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term of the catalog's kinds (the fan's windage is a behavioural torque of the
#: declared model)
KIT = OneProbe(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sa, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=harmonic_size, marginal_sigma=MARGINAL_SIGMA, declared=(),
    extra=_location_entry)
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def check_outside(entries: list[dict[str, Any]]) -> None:
    """Report an outside record that the catalog's effects jointly (linearised) leave less
    than OUTSIDE_LEFT of its imprint: it would not be outside in effect."""
    for e in entries:
        u = e.get("unexplained_sigma")
        if u and u["all_scalar_effects_jointly"] < OUTSIDE_LEFT * u["imprint"]:
            print(f"WARNING {e['id']}: the catalog's effects jointly leave "
                  f"{u['all_scalar_effects_jointly']:.3g} of its {u['imprint']:.3g} sigma")


def checked_make(s: dict[str, Any], write: bool) -> dict:
    """``make``, and the outside check of its entry."""
    entry = make(s, write)
    check_outside([entry])
    return entry


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, checked_make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
