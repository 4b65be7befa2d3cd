"""Generate the blind set ``fresh47`` of the diagnosis benchmark: records ay01-ay14 of motor AV
(a 20 V brushed DC motor driving the drum of a cordless drum drain cleaner on the service
bench: a rigid 15:1 spur and planetary gear to the drum with its coiled cable, turning on its
axle bushes, 3 m of spring-wound cable paid out through a clear test pipe a torsional
compliance to the cutter head, the head meeting the pipe's dry rubbing and the standing water's
viscous drag), some sampled evenly and some UNEVENLY, three of them giving the diagnosis ONE
probe only, and merge their truth into truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_av.py                # records/ay*.csv + truth.json
    python benchmarks/diagnosis/make_records_av.py --only ay03,ay12
    python benchmarks/diagnosis/make_records_av.py --truth-only   # rewrite the ay entries only

As in fresh45 and fresh46, the netlists (motor_av_fast.yaml, motor_av_slow.yaml) declare the
motor's parameters as the maker's data give them, and in every record two or three of them are
WRONG by 2-6 % (``FREE``: the record's relative errors, mixed signs): the record is simulated
with the TRUE values of those parameters (and the record's effects), and the user frees exactly
those parameters (truth's ``free``, the netlist's parameter names, and ``declared_error``:
{name: {"declared": the netlist's value, "true": the record's}}). The other parameters are
declared exactly. A null record holds only the declared errors (the right answer: nothing new,
the freed parameters fitted).

A catalog effect that is the same thing as moving a freed parameter cannot be told from it (a
series or source resistance, or a resistance drift, when R is freed; an inertia correction on
a freed inertia -- the drum's inertia is the rotor's through the rigid gear --; a viscous
friction when the water's viscous drag Bl is freed; a dry friction when the drum's Th or the
pipe's Tl is freed; a speed sensor's gain when k is freed; the inductance when L is freed): no
record puts such an effect with its twin freed (``TWINS``, checked). Each catalog or two-effect
record states, per effect, how far its own imprint (run alone on the record's times and true
values) lies from the freed parameters' imprints jointly, best-scaled
(``free_separation_sigma``; linearised: each freed parameter's column is its 1 % step); a record
below FREE_SEPARATION is reported. An outside record's imprint must keep OUTSIDE_LEFT after the
catalog's effects AND the freed parameters jointly (``unexplained_sigma``, whose alternatives
include the ``free:<name>`` columns). A marginal record's ``separation_sigma`` compares it with
each other catalog effect with the freed parameters beside that effect (as the diagnosis fits
them).

New in this set: a two-effect record also states, per effect, whether the record tells the
effect's LAW from the other catalog kinds at the same place (``law_separation_sigma``): the
record's whole imprint against each neighbour kind at the effect's place (a dry friction on the
head against a Stribeck friction, a viscous friction, a force offset or an angle-locked torque
on the head; a sensor's gain against the same probe's offset and delay; the inductance against
the armature loop's other kinds), linearised, best-scaled, with the freed parameters' columns
and the record's OTHER effect (its own imprint run alone, best-scaled) beside it; ``own_sigma``
is the same fit with the effect's own imprint in the neighbour's place (what the linear fit
leaves of the effects' interaction: the floor), ``without_sigma`` with nothing in its place.

Every imprint, signature and alternative is computed about the record's TRUE null (the true
values, no effect): ``signature_sigma`` is the effect's own; a null record's
``signature_sigma`` is its declared errors' (the true null against the declared one), and
every record's ``declared_error_signature_sigma`` is that.

Uses simulators_av.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_av_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the imprints it is compared with are computed on that probe alone. Even
records are sampled on the regime's grid k/fs; uneven ones, in the fast regime, on a 32 kHz
grid whose every sample is moved by a random jitter of up to 8-25 % of the interval, and in
the slow regime at a logger's irregular intervals (0.6-1.4 times the mean of 2.5 ms) with a
few samples dropped. Each uneven record has its own times (from its seed), and the motor is
simulated at those very times (``t_eval``), never interpolated. truth.json is merged under an
exclusive lock (recordkit.merge). A catalog or two-effect record's ``location_sigma`` covers
every other place its effect has an equal at: a torque effect on the rotor, the drum (hub) or
the head is compared with its equal on each of the other two (across the cable for rotor-head
and hub-head, through the rigid gear for rotor-hub), an added inertia on Jr, Jh or Jl with its
equal on the other two (``PLACES``, ``INERTIAS``, recordkit.places_entry). Nobody ran the
diagnosis on these records.
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
import simulators_av as sv

RECORDS = HERE / "records"
SPLIT = "fresh47"
MOTOR = "AV"
SEED0 = 47500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_av_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_av_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.08, "speed": 0.5},
         "slow": {"current": 0.02, "speed": 0.4, "load_speed": 0.05}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: an outside record's imprint must keep at least this fraction after all the catalog's
#: effects and the freed parameters jointly (linearised)
OUTSIDE_LEFT = 0.2
#: [white sigma] a catalog effect's imprint must lie at least this far from the freed
#: parameters' imprints jointly
FREE_SEPARATION = 10.0
#: [1] the relative step of a freed parameter's imprint column
FREE_STEP = 0.01
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.08, 0.25), (2, 8)
#: the declared values (the netlists'): what the diagnosis starts from
P = sv.MOTOR_AV
N = P["N"]
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]
#: the parameters a record may free, and the catalog effects (truth label, target; None: any
#: target) each one is the twin of (never in a record that frees it)
TWINS = {
    "R": {("series-resistance", None), ("source-resistance", None),
          ("resistance-drift", None)},
    "L": {("inductance", None)},
    "k": {("sensor-gain", "speed"), ("sensor-gain", "load_speed")},
    "Jm": {("inertia", "Jr"), ("inertia", "Jh")},
    "Jh": {("inertia", "Jr"), ("inertia", "Jh")},
    "Jl": {("inertia", "Jl")},
    "Bl": {("viscous-friction", None)},
    "Th": {("coulomb-friction", None)},
    "Tl": {("coulomb-friction", None)},
    "Ks": set(),
}


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_av, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gear train is rigid and lossless as declared: a
# torque on the body ``hub`` (the drum) is 1/N = 1/15 of it on the rotor, and the drum turns
# at 1/N of the rotor's speed (a dry friction c on the rotor is c N on the drum, a viscous
# friction b on the rotor b N^2 on the drum). The head lies behind the cable's compliance
# (1:1): an effect on it has no exact equal on the drum or the rotor. No effect here changes
# a parameter a record frees.

def series_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] in series with the armature (a marginal record scales it)."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": LOOP,
        "parameters": {"R_series_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


def saturation(ipar: float, ratio: float) -> Part:
    """The armature inductance saturating: La (ratio + (1 - ratio) / (1 + (i / Ipar)^2))."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def inductance(dl: float) -> Part:
    """The armature's inductance off by a factor 1 + ``dl`` (a correction of La's L)."""
    return {"p": {"L": P["L"] * (1.0 + dl)}}, {
        "effect": "inductance", "target": "La", "targets": ["La"], "correction": True,
        "parameters": {"L_true_H": P["L"] * (1.0 + dl), "dL": dl},
        "expected": {"dL": dl}}


def drift(alpha: float) -> Part:
    """The armature's resistance changing linearly, R (1 + alpha t) [1/s]."""
    return {"alpha": alpha}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + alpha*t)", "alpha_per_s": alpha},
        "expected": {"alpha": alpha}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def offset_head(torque: float) -> Part:
    """A constant torque ``torque`` [N m] the head receives (behind the cable: no exact equal
    on the drum or the rotor; a marginal record scales it)."""
    return {"offset": {"head": torque}}, {
        "effect": "force-offset", "target": "head", "targets": ["head"],
        "parameters": {"T_Nm": torque,
                       "form": "the head receives a constant T (T < 0: turning it backwards)"},
        "expected": {"F": torque}}


def stribeck_hub(peak: float, ws: float) -> Part:
    """A breakaway peak s exp(-(wh/ws)^2) tanh(wh/0.01) [N m] on the drum, ``ws`` [rad/s]
    (accepted on the rotor at s / N and ws N)."""
    return {"stribeck": {"hub": (peak, ws)}}, {
        "effect": "stribeck-friction", "target": "hub", "targets": ["hub"],
        "parameters": {"T_peak_Nm": peak, "w_stribeck_rad_s": ws,
                       "form": "hub takes s exp(-(w/ws)^2) tanh(w/0.01) over the declared "
                               "Th tanh(w/0.01)"},
        "expected": {"s": peak, "ws": ws},
        "also_accept": [{"effect": "stribeck-friction", "targets": ["rotor"],
                         "expected": {"s": peak / N, "ws": ws * N}}]}


def viscous_head(b: float) -> Part:
    """An extra viscous drag b wl [N m s/rad] on the head (behind the cable)."""
    return {"visc": {"head": b}}, {
        "effect": "viscous-friction", "target": "head", "targets": ["head"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b wl against the head"},
        "expected": {"b": b}}


def unbalance_hub(amp: float, phase: float) -> Part:
    """A once-a-turn gravity torque amp sin(drum angle + phase) [N m] on the drum (no whole
    order on the rotor; accepted as a cogging of order 1 on the drum)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"hub": [(1, a, b)]}}, {
        "effect": "unbalance", "target": "hub", "targets": ["hub"], "order": 1,
        "parameters": {"order": 1, "T_Nm": amp, "phase_rad": phase,
                       "form": "hub receives T sin(1 angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["hub"], "order": 1,
                         "expected": {"a": a, "b": b}}]}


outside = recordkit.outside


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None,
         free: dict[str, float] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.declared_spec``): the probes it gives the
    diagnosis (default: all of its regime's) and the declared parameters it frees
    (``free``: name -> relative error of the true value over the declared)."""
    return recordkit.declared_spec(rid, cls, regime, uneven, parts, noise, note, marginal,
                                   size, probes=probes or sv.PROBES[regime], free=free,
                                   params=P, twins=TWINS, mixed_signs=True)


def run(s: dict[str, Any], fx: dict, t: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """Motor AV's clean probes at the record's times (or ``t``) [s] with its TRUE values and
    the effects ``fx``."""
    return sv.simulate(s["regime"], times(s) if t is None else t, fx, s["ptrue"])


def declared_run(s: dict[str, Any]) -> dict[str, np.ndarray]:
    """Motor AV's clean probes at the record's times with the DECLARED values, no effect."""
    return sv.simulate(s["regime"], times(s), {})


# ---------------------------------------------------------------------- the records

#: the fast acquisition's current channel: a 12-bit ADC over +-50 A (24.4 mA steps)
BENCH_STEP = 100.0 / 4096
#: the bench logger's current channel: 16 bits over +-10 A (0.31 mA steps)
LOGGER_STEP = 20.0 / 65536
#: the tachogenerator's channel: 16 bits over +-1600 rad/s (0.049 rad/s steps)
TACHO_STEP = 3200.0 / 65536
#: the optical tachometer's head speed: 0.01 rad/s steps
OPTICAL_STEP = 0.01


def nulls() -> list[dict[str, Any]]:
    """ay01, ay02: the null records (the declared errors only)."""
    return [
        spec("ay01", "null", "slow", False, free={"Tl": 0.05, "Jh": -0.03},
             noise={"current": {"white": 0.015, "ar1": [0.01, 0.85], "quant": LOGGER_STEP},
                    "speed": {"white": 0.4, "quant": TACHO_STEP},
                    "load_speed": {"white": 0.04, "pink": 0.03, "quant": OPTICAL_STEP}},
             note="the bench logger's record of the service program, an even record; the user "
                  "frees the pipe's dry rubbing (the manual's figure is for the maker's test "
                  "pipe; the bench's has a tighter second bend) and the drum's inertia (the "
                  "manual's is for a full 7.5 m coil; this drum's cable was shortened after a "
                  "kink was cut out): Tl is really 5 % higher, Jh 3 % lower; nothing else; the "
                  "current with Gauss-Markov noise (10 mA, correlation 0.85 over the interval) "
                  "on white noise, in the logger's 0.31 mA steps; the tachogenerator's speed in "
                  "0.049 rad/s steps; the head's speed with 1/f noise (0.03 rad/s: water "
                  "droplets on the pipe's wall) on white noise, in 0.01 rad/s steps"),
        spec("ay02", "null", "fast", True, probes=("speed",),
             free={"k": 0.03, "Jm": -0.04, "Bl": 0.05},
             noise={"speed": {"white": 0.45, "ar1": [0.3, 0.7], "quant": TACHO_STEP}},
             note="a bench acquisition of the tachogenerator's speed alone, a jittered 32 kHz "
                  "acquisition; the user frees the motor constant, the rotor's inertia and the "
                  "water's viscous drag (a replacement motor of another batch, the test pipe's "
                  "water colder than the manual's): k is really 3 % higher, Jm 4 % lower, Bl "
                  "5 % higher; nothing else; Gauss-Markov noise (0.3 rad/s, correlation 0.7 "
                  "over the interval: the tachogenerator's commutator ripple, smeared) on white "
                  "noise, in 0.049 rad/s steps"),
    ]


def singles() -> list[dict[str, Any]]:
    """ay03-ay07, ay10: one catalog effect each."""
    return [
        spec("ay03", "catalog", "fast", True, (saturation(14.0, 0.55),), probes=("current",),
             noise={"current": {"white": 0.07, "quant": BENCH_STEP}},
             free={"R": -0.03, "Ks": 0.04},
             note="a bench acquisition of the current alone (the 12-bit ADC), jittered 32 kHz; "
                  "the replacement armature's laminations are "
                  "thinner than the original's: its inductance saturates at the start's and "
                  "the reversal's currents, down to 55 % of the declared L at high current "
                  "(half way at 14 A); the user frees R and the cable's stiffness Ks (really "
                  "3 % lower and 4 % higher than declared: a new cable of the same size)"),
        spec("ay04", "catalog", "slow", False, (offset_head(-0.01),),
             marginal=lambda c: (offset_head(c),), size=-0.01,
             free={"Bl": -0.04, "Jm": 0.03},
             note="the bench's flush valve was left a little open: water runs down the test "
                  "pipe past the cutter head, whose helical bulb turns in the flow like a "
                  "turbine: a constant torque on the head turning it backwards, scaled to a "
                  "25 sigma signature (marginal); the user frees Bl and Jm (really 4 % lower "
                  "and 3 % higher than declared)"),
        spec("ay05", "catalog", "fast", True, (stribeck_hub(0.2, 1.5),),
             free={"k": -0.03, "Jl": 0.05},
             note="a jittered 32 kHz acquisition; drain water has washed the grease "
                  "out of the drum's axle bushes: the drum breaks away from rest with a peak of "
                  "0.2 N m over its declared dry friction, fading by about 1.5 rad/s of the "
                  "drum; the user frees k and the head's inertia Jl (really 3 % lower and 5 % "
                  "higher than declared: a heavier cutter head was fitted)"),
        spec("ay06", "catalog", "slow", False, (drift(-3e-3),),
             free={"k": 0.025, "Th": -0.04},
             noise={"current": {"white": 0.02, "quant": LOGGER_STEP},
                    "speed": {"white": 0.4, "pink": 0.2},
                    "load_speed": {"white": 0.05, "quant": OPTICAL_STEP}},
             note="an even record taken straight after the bench's stall test: the armature "
                  "winding is still hot and cools through the record, its resistance falling "
                  "by 0.3 % a second (2.7 % over the 9 s); the user frees k and Th (really "
                  "2.5 % higher and 4 % lower than declared); 1/f noise on the speed "
                  "(0.2 rad/s, the tachogenerator's brushes)"),
        spec("ay07", "catalog", "fast", False, (series_resistance(0.02, "fast"),),
             marginal=lambda r: (series_resistance(r, "fast"),), size=0.02,
             noise={"current": {"white": 0.08, "quant": BENCH_STEP}, "speed": {"white": 0.5}},
             free={"Jh": 0.04, "Ks": -0.03},
             note="an even 32 kHz acquisition (the current by the 12-bit ADC); one of the "
                  "motor's leads was repaired with a crimped butt splice, a small contact "
                  "resistance in series with the armature, scaled to a 25 sigma signature "
                  "(marginal: a fraction of a milliohm); the user "
                  "frees Jh and Ks (really 4 % higher and 3 % lower than declared)"),
        spec("ay10", "catalog", "fast", True, (unbalance_hub(0.1, 2.4),), probes=("speed",),
             noise={"speed": {"white": 0.5, "quant": TACHO_STEP}},
             free={"k": 0.03, "Jm": -0.05},
             note="a bench acquisition of the tachogenerator's speed alone, jittered; the cable "
                  "coil inside the drum has slumped into a tangle on one side (the drum was "
                  "carried on its side): a once-a-turn gravity torque of 0.1 N m on the drum, "
                  "phase 2.4 rad; the user frees k and Jm (really 3 % higher and 5 % lower "
                  "than declared)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """ay08, ay09: two catalog effects at once."""
    return [
        spec("ay08", "two", "slow", True,
             (viscous_head(1.2e-3), sensor("load_speed", "gain", 0.955)),
             free={"R": 0.03, "Ks": -0.04, "Tl": 0.025},
             note="the bench logger's irregular intervals; the test pipe was filled with the "
                  "bench's cleaning solution instead of water, more viscous: 1.2 mN m s/rad more "
                  "viscous drag on the head (48 % more than declared); and the optical "
                  "tachometer's analog output is scaled for a 1050 rpm full scale while the "
                  "logger's input assumes 1000 rpm: the head's speed reads 4.5 % low; the user "
                  "frees R, Ks and Tl (really 3 % higher, 4 % lower and 2.5 % higher than "
                  "declared)"),
        spec("ay09", "two", "fast", False,
             (inductance(-0.2), sensor("current", "offset", 0.25)),
             free={"R": 0.05, "Jh": -0.04, "Th": 0.03},
             noise={"current": {"white": 0.08, "quant": BENCH_STEP}, "speed": {"white": 0.5}},
             note="an even 32 kHz acquisition; the declared armature inductance was measured "
                  "at 1 kHz with the rotor turned to a high-inductance position: the armature "
                  "has 20 % less inductance than declared; and the bench's current channel "
                  "reads 0.25 A high (its shunt amplifier's zero drifted); the user frees R, Jh "
                  "and Th (really 5 % higher, 4 % lower and 3 % higher than declared)"),
    ]


#: the optical tachometer's band on the cable at the test pipe's mouth: the fraction of the
#: paid-out cable's length between the drum and it [1]
PARTWAY = 0.4
#: the floating armature: the motor constant's loss a [1] with the armature pushed out by its
#: end play, the current I1 [A] about which the pinion's thrust beats the wave washer and the
#: width dI [A] of that change
FLOAT = (0.03, 12.0, 1.0)
#: the spring-wound cable's stiffness ratio r [1] while its coils open (backwards twist) and
#: the width e [rad] of the change at zero twist
HELIX = (0.45, 0.02)
#: the tachogenerator's reversal error a [1] (its constant a higher forwards, a lower
#: backwards) and the speed w0 [rad/s] within which its sign changes
TACHREV = (0.012, 1.0)


def outside_records() -> list[dict[str, Any]]:
    """ay11-ay14: effects the catalog does not contain."""
    a_f, i1, di = FLOAT
    r, e = HELIX
    a_t, w0 = TACHREV
    return [
        spec("ay11", "outside", "slow", False, (outside(
            "head-speed-read-partway-along-the-cable", {"partway": PARTWAY},
            {"f": PARTWAY,
             "form": "load_speed reads (1 - f) wh + f wl, wh = w/N the drum's speed, wl the "
                     "head's: the angle of a point a fraction f along the cable from the drum, "
                     "the twist shared evenly along it; the motor itself is not touched"}),),
            free={"R": -0.04, "Bl": 0.03}, note=NOTE_PARTWAY),
        spec("ay12", "outside", "fast", False, (outside(
            "armature-floats-out-under-the-pinion-thrust", {"float": FLOAT},
            {"a": a_f, "I1_A": i1, "dI_A": di,
             "form": "the EMF and the torque take k (1 - a s) in place of k, s = (1 + tanh((i "
                     "- I1)/dI))/2: the helical pinion's thrust, once the current's forward "
                     "torque beats the wave washer's preload, pushes the armature out of the "
                     "magnets by its end play; none while the current is negative"}),),
            free={"k": 0.04, "Jm": -0.03}, note=NOTE_FLOAT),
        spec("ay13", "outside", "slow", True, (outside(
            "spring-wound-cable-softer-as-its-coils-open", {"helix": HELIX},
            {"r": r, "e_rad": e,
             "form": "the cable's torque is Ks ((1 + r)/2 x + (1 - r)/2 (sqrt(x^2 + e^2) - e)) "
                     "+ Ds v, x = th/N - thl, v = w/N - wl: as declared while the drum leads "
                     "the head (the coils tightening), r times as stiff while the head leads "
                     "(the coils opening)"}),),
            free={"R": 0.025, "Jh": 0.04, "Tl": -0.03},
            noise={"current": {"white": 0.02, "pink": 0.01, "quant": LOGGER_STEP},
                   "speed": {"white": 0.4, "quant": TACHO_STEP},
                   "load_speed": {"white": 0.05, "quant": OPTICAL_STEP}},
            note=NOTE_HELIX),
        spec("ay14", "outside", "slow", True, (outside(
            "tachogenerator-brushes-off-neutral", {"tachrev": TACHREV},
            {"a": a_t, "w0_rad_s": w0,
             "form": "speed reads w (1 + a tanh(w/w0)): the tachogenerator's constant a higher "
                     "than declared forwards and a lower backwards (its reversal error); the "
                     "motor itself is not touched"}),),
            free={"k": -0.04, "Jl": 0.05, "Bl": -0.03},
            noise={"current": {"white": 0.02, "quant": LOGGER_STEP},
                   "speed": {"white": 0.4, "quant": TACHO_STEP},
                   "load_speed": {"white": 0.05, "ar1": [0.03, 0.8], "quant": OPTICAL_STEP}},
            note=NOTE_TACHREV),
    ]


NOTE_PARTWAY = (
    "the bench logger's record, an even record; the user frees R and Bl (really 4 % lower and "
    "3 % higher than declared); the optical tachometer's reflective band was stuck on the cable "
    "where it enters the test pipe, 1.2 m of the 3 m paid out from the drum (0.4 of the way), "
    "instead of on the cutter head: it reads the cable's speed there, which shares the cable's "
    "twist with the drum, not the head's; the current and the tachogenerator's speed as "
    "declared; a person sees the head's speed move before the head breaks away at the start "
    "(3.2 rad/s ahead at 0.73 s), its swings on the cable at every corner of the command "
    "smaller, 1.7 rad/s off at the stop (5.03 s) and 6.0 rad/s ahead at the start of the "
    "backing out (5.98 s), the steady runs as declared; not a gain, an offset or a delay of "
    "the tachometer: a mix of the drum's speed and the head's")
NOTE_FLOAT = (
    "an even 32 kHz acquisition; the user frees k and Jm (really 4 % higher and 3 % lower than "
    "declared); the motor's armature has 0.6 mm of end play and its wave washer is weak: "
    "whenever the current's torque is strong and forward (above about 12 A: the start, and the "
    "braking of the backward run at the stop), the helical pinion's thrust pushes the armature "
    "out of the magnets and the motor constant falls by 3 % (0.87 mV s/rad); a person sees the "
    "start draw up to 0.85 A more current (0.14-0.17 s), the motor's speed up to 1.9 rad/s "
    "off, and the stop's braking of the backward run take 0.54 A less, the motor still "
    "turning 4.1 rad/s faster backwards at the end; next to nothing in the drop, the reversal "
    "and the backward run; not a different k: one that changes with the current's sign and "
    "size")
NOTE_HELIX = (
    "the bench logger's irregular intervals; the user frees R, Jh and Tl (really 2.5 % higher, "
    "4 % higher and 3 % lower than declared); the cable fitted is a spring-wound cable made to "
    "turn forwards only: driven forwards its coils tighten and it is as stiff as declared, but "
    "whenever its twist goes the other way (backing out) its coils open and it is only 45 % as "
    "stiff; a person sees the forward runs and their stop as declared, and in the backing out "
    "the head start late and lag the drum (its speed up to 10.5 rad/s behind at 6.10 s, the "
    "cable wound up to -2.4 rad instead of -0.9 rad), then ring slower and longer (3.6 rad/s "
    "off at 6.31 s, 2.0 rad/s at the stop, 8.14 s), the motor's current up to 0.2 A and its "
    "speed up to 3 rad/s off while the head catches up; not a softer cable: softer one way "
    "only")
NOTE_TACHREV = (
    "the bench logger's irregular intervals; the user frees k, Jl and Bl (really 4 % lower, 5 % "
    "higher and 3 % lower than declared); the tachogenerator's brush holder was refitted off "
    "its neutral: its constant is 1.2 % higher forwards and 1.2 % lower backwards than its "
    "calibration; the current and the head's speed as declared; a person sees the motor's "
    "speed read 3.2 rad/s high at 8 V, 7.6 rad/s high at 18 V (642 instead of 634 rad/s) and "
    "5.0 rad/s less negative at -12 V; not a gain of the tachometer: a gain that differs with "
    "the direction, and not the motor: the current and the head's speed show nothing")


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
    return recordkit.record_times(s, sv.REGIMES, sv.grid, 47, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

def scalar_effects(p: dict[str, float]) -> tuple[tuple[str, dict], ...]:
    """Small catalog effects (label, fx) an imprint is compared with, linearised at the
    record's true null (``p``: its true values, the inertias' steps relative to them)."""
    return (
        ("series-resistance", {"Rser": 1e-3}),
        ("brush-drop", {"Vb": 1e-2}),
        ("coulomb-friction:rotor", {"coul": {"rotor": 1e-5}}),
        ("coulomb-friction:hub", {"coul": {"hub": 1e-4}}),
        ("coulomb-friction:head", {"coul": {"head": 1e-4}}),
        ("viscous-friction:rotor", {"visc": {"rotor": 1e-8}}),
        ("viscous-friction:hub", {"visc": {"hub": 1e-6}}),
        ("viscous-friction:head", {"visc": {"head": 1e-6}}),
        ("force-offset:rotor", {"offset": {"rotor": 1e-5}}),
        ("force-offset:hub", {"offset": {"hub": 1e-4}}),
        ("force-offset:head", {"offset": {"head": 1e-4}}),
        ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-5, 30.0)}}),
        ("stribeck-friction:hub", {"stribeck": {"hub": (1e-4, 2.0)}}),
        ("stribeck-friction:head", {"stribeck": {"head": (1e-4, 2.0)}}),
        ("backlash:K", {"gap": 1e-5}),
        ("inductance", {"p": {"L": p["L"] * 1.001}}),
        ("inductor-saturation:15", {"lsat": (15.0, 0.999)}),
        ("inertia:Jr", {"p": {"Jm": p["Jm"] * 1.001}}),
        ("inertia:Jh", {"p": {"Jh": p["Jh"] * 1.001}}),
        ("inertia:Jl", {"p": {"Jl": p["Jl"] * 1.001}}),
        ("resistance-drift:linear", {"alpha": 1e-4}),
        ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
        ("resistance-drift:warmup-2", {"warmup": (1e-3, 2.0)}),
    )


#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:hub", lambda a, b: {"cog": {"hub": [(1, a, b)]}}),
    ("unbalance:head", lambda a, b: {"cog": {"head": [(1, a, b)]}}),
    ("cogging:rotor:18", lambda a, b: {"cog": {"rotor": [(18, a, b)]}}),
    ("cogging:hub:2", lambda a, b: {"cog": {"hub": [(2, a, b)]}}),
    ("cogging:head:2", lambda a, b: {"cog": {"head": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:18", lambda a, b: {"emf": [(18, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 10 uN m on the
    rotor (and 1e-7 V s/rad of EMF), 0.1 mN m on the drum and the head."""
    return 1e-5 if (":rotor" in label or label.startswith("emf")) else 1e-4


#: the places a torque effect may sit at, each with its gear factor (its speed over the
#: drum's: the rotor turns N times the drum, the head at the drum's mean speed across the 1:1
#: cable); rotor-hub is exact (the rigid gear), rotor-head and hub-head lie across the cable's
#: compliance
PLACES = {"rotor": N, "hub": 1.0, "head": 1.0}
#: the same for an inertia (component: (parameter, gear factor)); Jr is the rotor's, the
#: parameter Jm
INERTIAS = {"Jr": ("Jm", N), "Jh": ("Jh", 1.0), "Jl": ("Jl", 1.0)}
#: the places behind the cable
BEYOND = ("head", "Jl")
#: the catalog's kinds of the armature loop (one place: the loop)
LOOP_KINDS = ("series-resistance", "source-resistance", "brush-drop", "inductance",
              "inductor-saturation", "resistance-drift", "emf-harmonic")
#: an inertia component's body
INERTIA_BODY = {"Jr": "rotor", "Jh": "hub", "Jl": "head"}


def place(kind: str, target: str | None) -> str:
    """Where a catalog effect of ``kind`` on ``target`` acts: a body for a torque effect or
    an inertia, a probe for a sensor effect, ``loop`` for the armature loop's kinds, the
    compliance K for a backlash."""
    if kind in LOOP_KINDS:
        return "loop"
    if kind == "inertia":
        return INERTIA_BODY[str(target)]
    return str(target)


def label_place(label: str) -> tuple[str, str]:
    """An alternative's label -> (its kind, its place)."""
    kind, _, rest = label.partition(":")
    return kind, place(kind, rest.split(":")[0] if rest else None)


@dataclass(frozen=True)
class LawSeparated(recordkit.DeclaredOff):
    """recordkit.DeclaredOff, and for a two-effect record each effect's separation from the
    other catalog kinds at its place (``law_separation_sigma``, ``law_separation``)."""

    def own_imprints(self, s: dict[str, Any]) -> list[np.ndarray]:
        """Each truth effect's own imprint, run alone [white sigma], once."""
        if "own" not in s:
            imp = self.imprints(s)
            s["own"] = [imp.imprint(s["regime"], self.run(s, frag)) for frag, _ in s["parts"]]
        return s["own"]

    def free_separation(self, s: dict[str, Any]) -> list[dict[str, Any]]:
        """Each truth effect's own imprint (run alone) against the freed parameters' columns
        jointly, best-scaled [white sigma]."""
        cols = np.column_stack(list(self.freed(s).values()))
        return [{"effect": e["effect"], "target": e["target"], "free": list(s["free"]),
                 "sigma": recordkit.left(y, cols), "imprint_sigma": float(np.linalg.norm(y))}
                for (_, e), y in zip(s["parts"], self.own_imprints(s), strict=True)]

    def law_separation(self, s: dict[str, Any]) -> list[dict[str, Any]]:
        """Per truth effect of a two-effect record: the record's whole imprint against each
        other catalog kind at the effect's place (linearised columns), with the freed
        parameters' columns and the record's other effects' own imprints beside it,
        best-scaled [white sigma]; ``own_sigma`` with the effect's own imprint in the
        neighbour's place, ``without_sigma`` with none."""
        imp, regime = self.imprints(s), s["regime"]
        y = imp.imprint(regime, self.run(s, s["fx"]))
        freed = np.column_stack(list(self.freed(s).values()))
        own = self.own_imprints(s)
        alts = {**self.alternatives(s), **self.harmonic_alternatives(s)}
        out = []
        for j, (_, e) in enumerate(s["parts"]):
            beside = np.column_stack([freed, *(own[m] for m in range(len(own)) if m != j)])
            here = place(e["effect"], e["target"])
            same = {e["effect"], *(a["effect"] for a in e.get("also_accept", []))}
            near: dict[str, float] = {}
            for label, cols in alts.items():
                kind, where = label_place(label)
                if where != here or kind in same:
                    continue
                near[kind] = min(near.get(kind, math.inf),
                                 recordkit.left(y, np.column_stack([cols, beside])))
            out.append({
                "effect": e["effect"], "target": e["target"], "place": here,
                "free": list(s["free"]),
                "beside": [x["effect"] for m, (_, x) in enumerate(s["parts"]) if m != j],
                "imprint_sigma": float(np.linalg.norm(y)),
                "own_sigma": recordkit.left(y, np.column_stack([own[j], beside])),
                "without_sigma": recordkit.left(y, beside),
                "neighbours": near})
        return out

    def make(self, s: dict[str, Any], write: bool) -> dict:
        """recordkit.DeclaredOff's record, and a two-effect record's law separations."""
        entry = super().make(s, write)
        if s["class"] == "two":
            entry["law_separation_sigma"] = self.law_separation(s)
        return entry


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AV's clean probes at the DECLARED values (Plumbing's field; every record's own
    runs go through ``run``, at its true values)."""
    return sv.simulate(regime, t, fx)


#: the plumbing of this set; each probe's sensor effects are its gain, its offset and its
#: delay; the netlist declares no harmonic term of the catalog's kinds
KIT = LawSeparated(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sv, sim=sim,
    times=times, scalar_effects=(), harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=harmonic_size, marginal_sigma=MARGINAL_SIGMA, declared=(),
    run=run, declared_run=declared_run, params=P, effects_of=scalar_effects,
    free_step=FREE_STEP, places=PLACES, inertias=INERTIAS, beyond=BEYOND)
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def check_entry(e: dict[str, Any]) -> None:
    """Report an outside record that the catalog's effects and the freed parameters jointly
    (linearised) leave less than OUTSIDE_LEFT of its imprint, a catalog effect nearer than
    FREE_SEPARATION to the freed parameters jointly, a marginal record nearer than 2 sigma to
    another catalog effect, and a two-effect record's effect whose law lies within 2 sigma of
    a neighbour's."""
    u = e.get("unexplained_sigma")
    if u and u["all_scalar_effects_jointly"] < OUTSIDE_LEFT * u["imprint"]:
        print(f"WARNING {e['id']}: the catalog's effects and the freed parameters jointly "
              f"leave {u['all_scalar_effects_jointly']:.3g} of its {u['imprint']:.3g} sigma")
    for f in e.get("free_separation_sigma", []):
        if f["sigma"] < FREE_SEPARATION:
            print(f"WARNING {e['id']}: {f['effect']} on {f['target']} lies {f['sigma']:.3g} "
                  f"sigma from the freed {', '.join(f['free'])}")
    sep = e.get("separation_sigma") or {}
    for kind, v in sep.items():
        if v < 2.0:
            print(f"WARNING {e['id']}: {kind} lies {v:.3g} sigma from its imprint")
    for f in e.get("law_separation_sigma", []):
        for kind, v in f["neighbours"].items():
            if v < 2.0:
                print(f"WARNING {e['id']}: {f['effect']} on {f['target']} lies {v:.3g} sigma "
                      f"from a {kind} there")


def checked_make(s: dict[str, Any], write: bool) -> dict:
    """``make``, its checks, and a line of what it holds."""
    entry = make(s, write)
    check_entry(entry)
    extra = []
    if "free_separation_sigma" in entry:
        extra.append("from the freed " + ", ".join(
            f"{f['effect']} {f['sigma']:.3g} of {f['imprint_sigma']:.3g}"
            for f in entry["free_separation_sigma"]))
    if entry.get("separation_sigma"):
        near = sorted(entry["separation_sigma"].items(), key=lambda kv: kv[1])[:3]
        extra.append("nearest " + ", ".join(f"{k} {v:.3g}" for k, v in near))
    if entry.get("location_sigma"):
        extra.append("places " + ", ".join(
            f"{x['target']}->{x['other']} {x['sigma']:.3g}" for x in entry["location_sigma"]))
    for f in entry.get("law_separation_sigma", []):
        near = sorted(f["neighbours"].items(), key=lambda kv: kv[1])
        extra.append(f"law of {f['effect']}: own {f['own_sigma']:.3g}, without "
                     f"{f['without_sigma']:.3g}, " + ", ".join(f"{k} {v:.3g}" for k, v in near))
    u = entry.get("unexplained_sigma")
    if u:
        extra.append(f"best single {u['best_single'][0]} leaves {u['best_single'][1]:.3g}; "
                     f"left {u['all_scalar_effects_jointly'] / u['imprint']:.2f} of it")
    dec = ", ".join(f"{k} {v:.3g}" for k, v in entry["declared_error_signature_sigma"].items())
    print(f"   {entry['id']} {entry.get('timestamps', '')[:40]}; declared errors {dec}; "
          + "; ".join(extra))
    return entry


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, checked_make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
