"""Generate the blind set ``fresh43`` of the diagnosis benchmark: records au01-au14 of motor AR
(a 12 V brushed DC motor driving the basket of a motorised tangential honey extractor on the
test bench: a rigid 8:1 spur gear to the output shaft, the rubber flex-disc coupling and the
basket's long shaft a compliance to the basket, the basket meeting its bearings' drag, the
bottom pivot's dry friction and the cages' air drag), some sampled evenly and some UNEVENLY,
three of them giving the diagnosis ONE probe only, and merge their truth into truth.json. The
ids have two letters.

    python benchmarks/diagnosis/make_records_ar.py                # records/au*.csv + truth.json
    python benchmarks/diagnosis/make_records_ar.py --only au03,au12
    python benchmarks/diagnosis/make_records_ar.py --truth-only   # rewrite the au entries only

Uses simulators_ar.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_ar_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the catalog imprints it is compared with are computed on that probe
alone (``OneProbe``). Even records are sampled on the regime's grid k/fs; uneven ones, in the
fast regime, on a 20 kHz grid whose every sample is moved by a random jitter of up to 10-30 %
of the interval, and in the slow regime at a logger's irregular intervals (0.6-1.4 times the
mean of 4 ms) with a few samples dropped. Each uneven record has its own times (from its
seed), and the motor is simulated at those very times (``t_eval``), never interpolated.
truth.json is merged under an exclusive lock (recordkit.merge). An outside record whose
imprint the catalog's effects jointly leave less than OUTSIDE_LEFT of is reported (it would
not be outside in effect). A catalog or two-effect record's ``location_sigma`` covers every
other place its effect has an equal at: a torque effect on the rotor, the hub or the basket
is compared with its equal on each of the other two (across the coupling for rotor-basket and
hub-basket, through the rigid gear for rotor-hub), an added inertia on Jr, Jh or Jb with its
equal on the other two (``PLACES``, ``INERTIAS``). Nobody ran the diagnosis on these
records.
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
import simulators_ar as sa

RECORDS = HERE / "records"
SPLIT = "fresh43"
MOTOR = "AR"
SEED0 = 43500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_ar_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_ar_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.04, "speed": 0.5},
         "slow": {"current": 0.02, "speed": 0.4, "load_speed": 0.1}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: an outside record's imprint must keep at least this fraction after all the catalog's
#: effects jointly (linearised)
OUTSIDE_LEFT = 0.2
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AR
N = P["N"]
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_ar, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The spur gear is rigid and lossless as declared: a
# torque on the body ``hub`` (the output shaft) is 1/N = 1/8 of it on the rotor, and the hub
# turns at 1/N of the rotor's speed (a viscous friction b on the hub is b / N^2 on the rotor).
# The basket lies behind the coupling's compliance (1:1): an effect on it has no exact equal
# on the hub or the rotor.

def source_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] inside the supply (its lead and its connector)."""
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[regime],
        "targets": [SOURCE[regime]], "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": LOOP,
                         "expected": {"R": r}}]}


def series_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] in series with the armature (a marginal record scales it)."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": LOOP,
        "parameters": {"R_series_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


def brush_drop(vb: float) -> Part:
    """A brush contact drop Vb tanh(i / 1 mA) [V] in series with the armature."""
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


def inductance(dl: float) -> Part:
    """The armature's inductance off by a factor 1 + ``dl`` (a correction of La's L)."""
    return {"p": {"L": P["L"] * (1.0 + dl)}}, {
        "effect": "inductance", "target": "La", "targets": ["La"], "correction": True,
        "parameters": {"L_true_H": P["L"] * (1.0 + dl), "dL": dl},
        "expected": {"dL": dl}}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF harmonic w slope sin(order th + phase) [V], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def stribeck_basket(s: float, ws: float) -> Part:
    """A breakaway peak s exp(-(wb/ws)^2) tanh(wb/0.01) [N m] on the basket, ``ws`` [rad/s]
    (behind the coupling)."""
    return {"stribeck": {"basket": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "basket", "targets": ["basket"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "basket takes s exp(-(w/ws)^2) tanh(w/0.01) over its declared "
                               "dry friction"},
        "expected": {"s": s, "ws": ws}}


def viscous_hub(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the hub (accepted on the rotor at
    b / N^2; a marginal record scales it)."""
    return {"visc": {"hub": b}}, {
        "effect": "viscous-friction", "target": "hub", "targets": ["hub"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b wh against the hub"},
        "expected": {"b": b},
        "also_accept": [{"effect": "viscous-friction", "targets": ["rotor"],
                         "expected": {"b": b / N ** 2}}]}


def cogging_rotor(order: int, amp: float, phase: float) -> Part:
    """A detent torque amp sin(order th + phase) [N m] on the rotor (accepted on the hub at
    the order order N and the amplitude amp N)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["hub"], "order": round(order * N),
                         "expected": {"a": a * N, "b": b * N}}]}


def inertia_basket(dj: float) -> Part:
    """The basket's inertia off by a factor 1 + ``dj`` (a correction of Jb's J, the parameter
    Jb; behind the coupling)."""
    return {"p": {"Jb": P["Jb"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jb", "targets": ["Jb"], "correction": True,
        "parameters": {"Jb_true_kgm2": P["Jb"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AR's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sa.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sa.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the bench's shunt amplifier: a 12-bit ADC over +-25 A (12.2 mA steps)
BENCH_STEP = 50.0 / 4096
#: the extractor controller's current sense: a 12-bit ADC over +-10 A (4.9 mA steps)
CONTROLLER_STEP = 20.0 / 4096
#: the motor's Hall encoder's speed report: 0.1 rad/s steps at the rotor
SPEED_STEP = 0.1
#: the controller's basket speed from its Hall switch: 0.02 rad/s steps
BASKET_STEP = 0.02


def nulls() -> list[dict[str, Any]]:
    """au01, au02: the null records."""
    return [
        spec("au01", "null", "slow", False,
             noise={"current": {"white": 0.01, "pink": 0.01, "quant": CONTROLLER_STEP},
                    "speed": {"white": 0.3, "ar1": [0.2, 0.8], "quant": SPEED_STEP},
                    "load_speed": {"white": 0.08, "quant": BASKET_STEP}},
             note="the extractor controller's log of the bench test program, an even record; "
                  "the current with 1/f noise (10 mA: the brushes on the commutator) on white "
                  "noise, read by the controller's 12-bit ADC (4.9 mA steps); the motor's Hall "
                  "speed with Gauss-Markov noise (correlation 0.8 over the interval, 0.2 "
                  "rad/s: the magnet ring's uneven poles) on white noise, reported in 0.1 "
                  "rad/s steps; the basket's speed from the Hall switch on white noise, "
                  "reported in 0.02 rad/s steps"),
        spec("au02", "null", "fast", True, probes=("current",),
             noise={"current": {"white": 0.03, "ar1": [0.02, 0.75], "quant": BENCH_STEP}},
             note="a bench log of the current alone, a jittered 20 kHz acquisition; "
                  "Gauss-Markov noise (correlation 0.75 over the interval, 20 mA: the shunt "
                  "amplifier's drift) on white noise, read by the 12-bit ADC (12.2 mA steps)"),
    ]


def singles() -> list[dict[str, Any]]:
    """au03-au07, au10: one catalog effect each."""
    return [
        spec("au03", "catalog", "fast", True, (inductance(0.4),),
             note="the declared armature inductance was read off an LCR meter at 10 kHz, "
                  "where the laminations' eddy currents hide part of it; at the current's own "
                  "frequencies the armature has 40 % more inductance (0.7 mH)"),
        spec("au04", "catalog", "slow", False, (series_resistance(0.02, "slow"),),
             marginal=lambda r: (series_resistance(r, "slow"),), size=0.02,
             note="the motor's lead was extended to reach the new controller box with a "
                  "thinner cable and two butt splices: an extra resistance in series with "
                  "the armature, scaled to a 25 sigma signature (marginal)"),
        spec("au05", "catalog", "fast", False, (brush_drop(0.5),),
             note="the motor came back from a repair shop with electrographitic brushes of a "
                  "harder grade than the original copper-graphite ones: a contact drop of "
                  "0.5 V across the pair, whichever the current's direction"),
        spec("au06", "catalog", "slow", True, (stribeck_basket(0.06, 2.0),),
             note="honey crept down the basket's shaft into the bottom pivot's bronze thrust "
                  "bush over the winter and crystallised there: a breakaway of 60 mN m on "
                  "the basket fading above about 2 rad/s, over the bush's declared friction"),
        spec("au07", "catalog", "fast", False, (emf_harmonic(1, 3e-4, 0.6),),
             probes=("current",), noise={"current": {"white": 0.03, "quant": BENCH_STEP}},
             note="a bench log of the current alone (the 12-bit ADC); one of the motor's two "
                  "ferrite magnets is chipped at an edge after the motor was dropped: the EMF "
                  "swings by 1 % of k (0.3 mV s/rad) once a turn of the rotor"),
        spec("au10", "catalog", "fast", True, (viscous_hub(2e-3),),
             marginal=lambda b: (viscous_hub(b),), size=2e-3, probes=("speed",),
             note="a bench log of the motor's Hall speed alone; the gearbox was refilled "
                  "with a stiff food-grade grease instead of the light one: an extra viscous "
                  "drag on the output shaft, scaled to a 25 sigma signature (marginal)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """au08, au09: two catalog effects at once."""
    return [
        spec("au08", "two", "slow", True,
             (inertia_basket(0.35), source_resistance(0.15, "slow")),
             note="the maker fitted the basket with its heavier stainless frame cages (the "
                  "ones for deep frames): 35 % more inertia on the basket than the declared; "
                  "and the controller is fed from the bench's battery through a long, thin "
                  "cable with a worn car-plug: 0.15 Ohm inside the source"),
        spec("au09", "two", "fast", False,
             (cogging_rotor(10, 4e-3, 1.3), sensor("speed", "offset", 1.5)),
             note="the motor is a replacement whose 10 slots are not skewed: a cogging of "
                  "4 mN m, ten times a turn of the rotor; and the bench's speed channel is "
                  "read through a frequency-to-voltage converter whose zero has shifted: the "
                  "speed reads 1.5 rad/s high"),
    ]


#: the broken cage door: its drag coefficient Cd [N m s^2/rad^2], the basket's speed w0
#: [rad/s] about which it swings out and the width dw [rad/s] of its opening
DOOR = (4e-5, 40.0, 2.0)
#: the flex-disc coupling's rubbing flanges: their dry friction Fr [N m] on the twist rate
RUB = (0.08,)
#: the single-supply current-sense amplifier: the rounding eps [A] of its output floor
CLIP = (0.02,)
#: the bench supply's slow voltage loop: the transient resistance Rt [ohm] and the loop's
#: recovery time tau [s]
DROOP = (0.3, 0.015)


def outside_records() -> list[dict[str, Any]]:
    """au11-au14: effects the catalog does not contain."""
    return outside_slow() + outside_fast()


def outside_slow() -> list[dict[str, Any]]:
    """au11, au13: a cage door swinging out and a single-supply current amplifier (slow)."""
    cd, w0, dw = DOOR
    eps, = CLIP
    return [
        spec("au11", "outside", "slow", True, (outside(
            "cage-door-swings-out-above-a-speed", {"door": DOOR},
            {"Cd_Nms2_rad2": cd, "w0_rad_s": w0, "dw_rad_s": dw,
             "form": "the basket takes an extra air drag Cd wb a (1 + tanh((a - w0)/dw))/2, "
                     "a = sqrt(wb^2 + (1 rad/s)^2): a drag like the cages' own that switches "
                     "on about w0 as the door swings open, in either direction"}),),
            note=NOTE_DOOR),
        spec("au13", "outside", "slow", False, (outside(
            "single-supply-current-amplifier", {"clip": CLIP},
            {"eps_A": eps,
             "form": "the current reads (i + sqrt(i^2 + eps^2))/2: the current while it is "
                     "positive, about 0 while the motor regenerates or runs backwards; the "
                     "motor itself is not touched"}),),
            noise={"current": {"white": 0.02, "quant": CONTROLLER_STEP},
                   "speed": {"white": 0.4, "quant": SPEED_STEP},
                   "load_speed": {"white": 0.1, "ar1": [0.05, 0.8], "quant": BASKET_STEP}},
            note=NOTE_CLIP),
    ]


def outside_fast() -> list[dict[str, Any]]:
    """au12, au14: rubbing coupling flanges and a supply's slow voltage loop (fast)."""
    fr, = RUB
    rt, tau = DROOP
    return [
        spec("au12", "outside", "fast", False, (outside(
            "coupling-flanges-rub", {"rub": RUB},
            {"Fr_Nm": fr,
             "form": "the coupling's torque takes Fr tanh(v/0.01), v = w/N - wb the twist "
                     "rate (on the basket, and opposite on the hub): a dry friction between "
                     "the two flanges, not against either body's own motion"}),),
            noise={"current": {"white": 0.04, "pink": 0.02, "quant": BENCH_STEP},
                   "speed": {"white": 0.5}},
            note=NOTE_RUB),
        spec("au14", "outside", "fast", True, (outside(
            "bench-supply-slow-voltage-loop", {"droop": DROOP},
            {"Rt_ohm": rt, "tau_s": tau,
             "form": "the supply's output is u - Rt (i - q), dq/dt = (i - q)/tau, q = 0 at "
                     "rest: a resistance to the current's changes that its voltage loop "
                     "removes within tau, none in the steady state"}),),
            noise={"current": {"white": 0.04}, "speed": {"white": 0.5, "pink": 0.2}},
            note=NOTE_DROOP),
    ]


NOTE_DOOR = (
    "the extractor controller's log; the latch of one frame cage's mesh door is broken and "
    "the door, held shut only by its hinge spring, swings out into the drum's air once the "
    "basket passes about 40 rad/s (380 rpm), either way: it roughly doubles the cages' air "
    "drag there; a person sees nothing at 4 V and 8 V nor in the reverse run (the basket "
    "below 32 rad/s), and from 5.36 s on the top speed the current 0.36 A higher (1.32 A "
    "instead of 0.96 A), the motor 6 rad/s and the basket 0.75 rad/s slower, as declared "
    "again once the stop brings the basket below 40 rad/s; close to more viscous friction on the "
    "basket, but only above a speed")
NOTE_CLIP = (
    "the bench log of the controller; its current-sense board was replaced by one with a "
    "single-supply (0-5 V) shunt amplifier whose output cannot go below 0 V: it reads the "
    "current while it is positive, and about 0 (a 10 mA floor) while the motor regenerates "
    "or runs backwards; a person sees the current as declared through the three speeds, "
    "then flat at about 0 through the stop (where the declared current falls to -3.7 A) "
    "and the whole reverse run (down to -4.8 A at 8.4 s, -0.74 A held), while the two "
    "speeds stay as declared; not a gain nor an offset: the reading folds at zero current")
NOTE_RUB = (
    "a bench acquisition of the current (the 12-bit ADC, with 1/f noise of 20 mA on white "
    "noise) and the motor's Hall speed; the flex-disc coupling was reassembled with its "
    "bolts over-tightened and the two three-armed flanges now rub each other's arms: a dry "
    "friction of 80 mN m on the coupling's twist rate, not on either shaft's own motion; a "
    "person sees the coupling's 17 Hz ringing (the rotor with the hub against the basket) "
    "die out sooner after the start, the drop to 4 V, the reversal and the stop, and the "
    "twist lock where the friction leaves it: the motor's speed up to 4.8 rad/s and the "
    "current up to 0.29 A off, most in the reversal, nothing once the ringing has died out "
    "in a steady run; close to a damper across the coupling, but a dry one")
NOTE_DROOP = (
    "a bench acquisition of the current and the motor's Hall speed (1/f noise of 0.2 rad/s "
    "on white noise); the bench's switch-mode supply was left in its slow 'battery charger' "
    "loop setting: its output sags by 0.3 Ohm times each change of the current and its "
    "voltage loop recovers it with a 15 ms time constant; a person sees the current follow "
    "every corner of the command more sluggishly, by up to 1.7 A after the drop to 4 V and "
    "2.3 A after the stop (0.56 s), and the motor's speed up to 14 rad/s off in the "
    "reversal, while the supply gives its set voltage again wherever the current "
    "settles; close to a resistance in the source, but only for changes, and close to more "
    "inductance, but 15 times slower than the armature's own L/R")


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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 43, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-5}}),
    ("coulomb-friction:hub", {"coul": {"hub": 1e-4}}),
    ("coulomb-friction:basket", {"coul": {"basket": 1e-4}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:basket", {"visc": {"basket": 1e-6}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-5}}),
    ("force-offset:basket", {"offset": {"basket": 1e-4}}),
    ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-5, 20.0)}}),
    ("stribeck-friction:hub", {"stribeck": {"hub": (1e-4, 4.0)}}),
    ("stribeck-friction:basket", {"stribeck": {"basket": (1e-4, 4.0)}}),
    ("backlash:K", {"gap": 1e-5}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:5", {"lsat": (5.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jh", {"p": {"Jh": P["Jh"] * 1.001}}),
    ("inertia:Jb", {"p": {"Jb": P["Jb"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
    ("resistance-drift:warmup-2", {"warmup": (1e-3, 2.0)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:hub", lambda a, b: {"cog": {"hub": [(1, a, b)]}}),
    ("unbalance:basket", lambda a, b: {"cog": {"basket": [(1, a, b)]}}),
    ("cogging:rotor:10", lambda a, b: {"cog": {"rotor": [(10, a, b)]}}),
    ("cogging:hub:3", lambda a, b: {"cog": {"hub": [(3, a, b)]}}),
    ("cogging:basket:2", lambda a, b: {"cog": {"basket": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:10", lambda a, b: {"emf": [(10, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 10 uN m on the
    rotor (and 1e-7 V s/rad of EMF), 0.1 mN m on the hub and the basket."""
    return 1e-5 if (":rotor" in label or label.startswith("emf")) else 1e-4


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
        eight) until within 1 % of it (an imprint need not be linear in its size)."""
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


#: the places a torque effect may sit at, each with its gear factor g (its speed over the
#: hub's: the rotor turns N times the hub, the basket at the hub's mean speed across the 1:1
#: coupling). A torque effect of kind k on a place of factor ga equals, on a place of factor
#: gb, a dry friction or an offset of ga/gb of it, a viscous friction of (ga/gb)^2, a Stribeck
#: peak of ga/gb at gb/ga times the speed scale, a cogging (or unbalance) of order k ga/gb
#: (when whole) at ga/gb of the amplitude. Rotor-hub is exact (the rigid gear); rotor-basket
#: and hub-basket lie across the coupling's compliance, where a record at these sample rates
#: may not tell the two apart: every other place is listed.
PLACES = {"rotor": N, "hub": 1.0, "basket": 1.0}
#: the same for an inertia (component: (parameter, gear factor)): an added inertia dJ on a
#: place of factor ga is dJ (ga/gb)^2 on a place of factor gb (Jr is the rotor's, the
#: parameter Jm)
INERTIAS = {"Jr": ("Jm", N), "Jh": ("Jh", 1.0), "Jb": ("Jb", 1.0)}
#: the places on the far side of the train's compliance: a pair with one of them is ``across``
BEYOND = ("basket", "Jb")


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma``, after a marginal record's
    scaling: recordkit.places_entry over PLACES and INERTIAS (each truth effect's own clean
    imprint, run alone on the record's times, against the same effect at its equivalent size
    at each other place, best-scaled)."""
    return recordkit.places_entry(s, times(s), imprints(s), sim, PLACES, INERTIAS, P, BEYOND)


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term of the catalog's kinds (the cages' air drag is a behavioural torque of
#: the declared model)
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
