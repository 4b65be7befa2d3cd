"""Generate the blind set ``fresh56`` of the diagnosis benchmark: records bh01-bh14 of motor BE
(a 36 V brushed DC motor driving the gravure roll of a pilot roll-to-roll coater, a lab-scale
reverse-gravure coater laying battery-electrode slurry on foil, on the maker's test stand: a
rigid 18:1 timing-belt and spur reduction to the drive-side hub, turning in its bearings and
seals, the 0.8 m drive shaft across the frame and its double disc-pack coupling a torsional
compliance to the chromed gravure roll, the roll meeting the dry friction of its journal
bearings and of the doctor blade and the viscous drag of the slurry in its pan), some sampled
evenly and some UNEVENLY, three of them giving the diagnosis ONE probe only, and merge their
truth into truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_be.py                # records/bh*.csv + truth.json
    python benchmarks/diagnosis/make_records_be.py --only bh03,bh12
    python benchmarks/diagnosis/make_records_be.py --truth-only   # rewrite the bh entries only

As in fresh45 to fresh55, the netlists (motor_be_fast.yaml, motor_be_slow.yaml) declare the
motor's parameters as the maker's data give them, and in every record two or three of them are
WRONG by 2-6 % (``FREE``: the record's relative errors, mixed signs): the record is simulated
with the TRUE values of those parameters (and the record's effects), and the user frees exactly
those parameters (truth's ``free``, the netlist's parameter names, and ``declared_error``:
{name: {"declared": the netlist's value, "true": the record's}}). The other parameters are
declared exactly. A null record holds only the declared errors (the right answer: nothing new,
the freed parameters fitted).

A catalog effect that is the same thing as moving a freed parameter cannot be told from it (a
series or source resistance, or a resistance drift, when R is freed; an inertia correction on
a freed inertia -- the hub's inertia is the rotor's through the rigid reduction --; a viscous
friction when the slurry's drag Bg is freed; a dry friction when the hub's Th or the roll's Tg
is freed; a speed sensor's gain when k is freed; the inductance when L is freed): no record
puts such an effect with its twin freed (``TWINS``, checked). Each catalog or two-effect
record states, per effect, how far its own imprint (run alone on the record's times and true
values) lies from the freed parameters' imprints jointly, best-scaled
(``free_separation_sigma``; linearised: each freed parameter's column is its 1 % step); a record
below FREE_SEPARATION is reported. An outside record's imprint must keep OUTSIDE_LEFT after the
catalog's effects AND the freed parameters jointly (``unexplained_sigma``, whose alternatives
include the ``free:<name>`` columns). A marginal record's ``separation_sigma`` compares it with
each other catalog effect with the freed parameters beside that effect (as the diagnosis fits
them).

As in fresh47 to fresh55, a two-effect record also states, per effect, whether the record
tells the effect's LAW from the other catalog kinds at the same place
(``law_separation_sigma``): the record's whole imprint against each neighbour kind at the
effect's place (an EMF harmonic against the armature loop's other kinds; a sensor's delay or
gain against the same probe's other kinds; a play in the drive shaft against nothing else at
K), linearised, best-scaled, with the freed parameters' columns and the record's OTHER effect
(its own imprint run alone, best-scaled) beside it; ``own_sigma`` is the same fit with the
effect's own imprint in the neighbour's place (what the linear fit leaves of the effects'
interaction: the floor), ``without_sigma`` with nothing in its place.

Every imprint, signature and alternative is computed about the record's TRUE null (the true
values, no effect): ``signature_sigma`` is the effect's own; a null record's
``signature_sigma`` is its declared errors' (the true null against the declared one), and
every record's ``declared_error_signature_sigma`` is that.

Uses simulators_be.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_be_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the imprints it is compared with are computed on that probe alone. Even
records are sampled on the regime's grid k/fs; uneven ones, in the fast regime, on the 25 kHz
grid whose every sample is moved by a random jitter of up to 5-20 % of the interval, and in
the slow regime at a logger's irregular intervals (0.6-1.4 times the mean of 10 ms) with a
few samples dropped. Each uneven record has its own times (from its seed), and the motor is
simulated at those very times (``t_eval``), never interpolated. truth.json is merged under an
exclusive lock (recordkit.merge). A catalog or two-effect record's ``location_sigma`` covers
every other place its effect has an equal at: a torque effect on the rotor, the hub or the
roll is compared with its equal on each of the other two (across the drive shaft for
rotor-roll and hub-roll, through the rigid reduction for rotor-hub), an added inertia on Jr,
Jh or Jg with its equal on the other two (``PLACES``, ``INERTIAS``, recordkit.places_entry).
Nobody ran the diagnosis on these records.
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
import simulators_be as se

RECORDS = HERE / "records"
SPLIT = "fresh56"
MOTOR = "BE"
SEED0 = 56500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_be_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_be_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.08, "speed": 0.25},
         "slow": {"current": 0.02, "speed": 0.15, "load_speed": 0.004}}
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
JITTER, DROPS = (0.05, 0.20), (3, 9)
#: the declared values (the netlists'): what the diagnosis starts from
P = se.MOTOR_BE
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
    "Jg": {("inertia", "Jg")},
    "Bg": {("viscous-friction", None)},
    "Th": {("coulomb-friction", None)},
    "Tg": {("coulomb-friction", None)},
    "Ks": set(),
}


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_be, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The reduction is rigid and lossless as declared: a
# torque on the body ``hub`` is 1/N = 1/18 of it on the rotor, and the hub turns at 1/N of the
# rotor's speed. The roll lies behind the drive shaft's compliance (1:1): an effect on it has
# no exact equal on the hub or the rotor. No effect here changes a parameter a record frees.

def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def inductance(dl: float) -> Part:
    """The armature's inductance off by a factor 1 + ``dl`` (a correction of La's L, the
    parameter L)."""
    return {"p": {"L": P["L"] * (1.0 + dl)}}, {
        "effect": "inductance", "target": "La", "targets": ["La"], "correction": True,
        "parameters": {"L_true_H": P["L"] * (1.0 + dl), "dL": dl},
        "expected": {"dL": dl}}


def unbalance_roll(amp: float, phase: float) -> Part:
    """A once-a-turn torque amp sin(roll angle + phase) [N m] on the roll (behind the drive
    shaft: no exact equal on the hub or the rotor; accepted as a cogging of order 1 on the
    roll; a marginal record scales it)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"roll": [(1, a, b)]}}, {
        "effect": "unbalance", "target": "roll", "targets": ["roll"], "order": 1,
        "parameters": {"order": 1, "T_Nm": amp, "phase_rad": phase,
                       "form": "roll receives T sin(1 angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["roll"], "order": 1,
                         "expected": {"a": a, "b": b}}]}


def stribeck_roll(peak: float, ws: float) -> Part:
    """A breakaway peak s exp(-(wg/ws)^2) tanh(wg/0.01) [N m] on the roll, ``ws`` [rad/s]
    (behind the drive shaft: no exact equal on the hub or the rotor)."""
    return {"stribeck": {"roll": (peak, ws)}}, {
        "effect": "stribeck-friction", "target": "roll", "targets": ["roll"],
        "parameters": {"T_peak_Nm": peak, "w_stribeck_rad_s": ws,
                       "form": "roll takes s exp(-(w/ws)^2) tanh(w/0.01) over its declared "
                               "Tg tanh(w/0.01)"},
        "expected": {"s": peak, "ws": ws}}


def source_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] inside the supply (its output lead and its connector)."""
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[regime],
        "targets": [SOURCE[regime]], "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": LOOP,
                         "expected": {"R": r}}]}


def inertia_roll(dj: float) -> Part:
    """The roll's inertia off by a factor 1 + ``dj`` (a correction of Jg's J, the parameter
    Jg; behind the drive shaft)."""
    return {"p": {"Jg": P["Jg"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jg", "targets": ["Jg"], "correction": True,
        "parameters": {"Jg_true_kgm2": P["Jg"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF harmonic w slope sin(order th + phase) [V], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad] in the drive shaft K (the coupling hub's worn
    keyway)."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap,
                       "form": "no shaft torque while |twist| < gap/2, Ks (twist -+ gap/2) "
                               "+ Ds w_rel in contact, the damping never pulling"},
        "expected": {"gap": gap}}


def offset_roll(torque: float) -> Part:
    """A constant torque ``torque`` [N m] the roll receives (behind the drive shaft: no exact
    equal on the hub or the rotor; a marginal record scales it)."""
    return {"offset": {"roll": torque}}, {
        "effect": "force-offset", "target": "roll", "targets": ["roll"],
        "parameters": {"T_Nm": torque,
                       "form": "the roll receives a constant T (T > 0: turning it forwards)"},
        "expected": {"F": torque}}


outside = recordkit.outside


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None,
         free: dict[str, float] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.declared_spec``): the probes it gives the
    diagnosis (default: all of its regime's) and the declared parameters it frees
    (``free``: name -> relative error of the true value over the declared)."""
    return recordkit.declared_spec(rid, cls, regime, uneven, parts, noise, note, marginal,
                                   size, probes=probes or se.PROBES[regime], free=free,
                                   params=P, twins=TWINS, mixed_signs=True)


def run(s: dict[str, Any], fx: dict, t: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """Motor BE's clean probes at the record's times (or ``t``) [s] with its TRUE values and
    the effects ``fx``."""
    return se.simulate(s["regime"], times(s) if t is None else t, fx, s["ptrue"])


def declared_run(s: dict[str, Any]) -> dict[str, np.ndarray]:
    """Motor BE's clean probes at the record's times with the DECLARED values, no effect."""
    return se.simulate(s["regime"], times(s), {})


# ---------------------------------------------------------------------- the records

#: the stand's fast acquisition's current channel: a 14-bit ADC over +-80 A (9.77 mA steps)
STAND_STEP = 160.0 / 16384
#: the stand's data logger's current channel: 16 bits over +-20 A (0.61 mA steps)
LOGGER_STEP = 40.0 / 65536
#: the motor encoder's speed word: 0.01 rad/s steps
MOTOR_STEP = 0.01
#: the speed word of the encoder on the roll's operator-side journal: 1 mrad/s steps
ROLL_STEP = 0.001


def nulls() -> list[dict[str, Any]]:
    """bh01, bh02: the null records (the declared errors only)."""
    return [
        spec("bh01", "null", "slow", False, free={"Jg": -0.04, "Bg": 0.035},
             noise={"current": {"white": 0.02, "ar1": [0.01, 0.8], "quant": LOGGER_STEP},
                    "speed": {"white": 0.15, "quant": MOTOR_STEP},
                    "load_speed": {"white": 0.004, "pink": 0.002, "quant": ROLL_STEP}},
             note="an even record of the stand's test program; the user frees the roll's "
                  "inertia (the stand's roll is of a thinner-walled tube than the build "
                  "sheet's) and the slurry's drag (the stand's test slurry is a little "
                  "thicker than the build sheet's): Jg is really 4 % lower, Bg 3.5 % higher; "
                  "nothing else; the current with Gauss-Markov noise (10 mA, correlation "
                  "0.8 over the interval: the shunt amplifier's drift) on white noise, in "
                  "the logger's 0.61 mA steps; 1/f noise (2 mrad/s) on the roll's speed"),
        spec("bh02", "null", "fast", True, probes=("speed",),
             free={"R": 0.03, "Ks": -0.045, "Tg": 0.025},
             noise={"speed": {"white": 0.25, "ar1": [0.1, 0.9], "quant": MOTOR_STEP}},
             note="a stand acquisition of the motor's speed alone, jittered 25 kHz; the user "
                  "frees R, the drive shaft's stiffness Ks and the roll's dry friction Tg "
                  "(the stand's motor leads are longer than the coater's; the disc packs are "
                  "of the thinner laminations; the doctor blade was newly set): R is really "
                  "3 % higher, Ks 4.5 % lower, Tg 2.5 % higher; nothing else; Gauss-Markov "
                  "noise on the speed (0.1 rad/s, correlation 0.9 over the interval: the "
                  "encoder's interpolation error, smeared)"),
    ]


def singles() -> list[dict[str, Any]]:
    """bh03-bh07, bh10: one catalog effect each."""
    return [
        spec("bh03", "catalog", "fast", True, (inductance(0.14),), probes=("current",),
             noise={"current": {"white": 0.08, "quant": STAND_STEP}},
             free={"k": -0.03, "Jh": 0.045},
             note="a stand acquisition of the current alone (the 14-bit ADC), jittered "
                  "25 kHz; the data sheet's inductance was measured on a 1 kHz bridge, where "
                  "the armature stack's eddy currents hide part of it: at the drive's slower "
                  "changes the armature's inductance is 14 % higher than declared; the user "
                  "frees k and the hub's inertia Jh (really 3 % lower and 4.5 % higher than "
                  "declared)"),
        spec("bh04", "catalog", "slow", False, (unbalance_roll(0.05, 0.9),),
             marginal=lambda a: (unbalance_roll(a, 0.9),), size=0.05,
             noise={"current": {"white": 0.02, "quant": LOGGER_STEP},
                    "speed": {"white": 0.15, "quant": MOTOR_STEP},
                    "load_speed": {"white": 0.004, "quant": ROLL_STEP}},
             free={"R": 0.03, "Tg": -0.04},
             note="an even record; a crust of dried slurry has built up on one of the roll's "
                  "end bells: the roll is out of balance, a torque once a turn of the roll "
                  "(its weight's lever), phase 0.9 rad, scaled to a 25 sigma signature "
                  "(marginal); the user frees R and Tg (really 3 % higher and 4 % lower than "
                  "declared)"),
        spec("bh05", "catalog", "slow", True, (stribeck_roll(0.45, 0.6),),
             free={"Jm": -0.035, "Th": 0.03},
             noise={"current": {"white": 0.02, "quant": LOGGER_STEP},
                    "speed": {"white": 0.15, "pink": 0.05, "quant": MOTOR_STEP},
                    "load_speed": {"white": 0.004, "quant": ROLL_STEP}},
             note="the stand logger's irregular intervals; the slurry's film dried under "
                  "the doctor blade while the coater stood: the blade sticks to the chrome "
                  "and breaks away, a friction peak of 0.45 N m on the roll that fades above "
                  "about 0.6 rad/s; the user frees Jm and Th (really 3.5 % lower and 3 % "
                  "higher than declared); 1/f noise on the motor's speed (50 mrad/s)"),
        spec("bh06", "catalog", "fast", True, (source_resistance(0.1, "fast"),),
             free={"k": 0.03, "Jg": -0.04},
             noise={"current": {"white": 0.08, "ar1": [0.04, 0.6], "quant": STAND_STEP},
                    "speed": {"white": 0.25, "quant": MOTOR_STEP}},
             note="a jittered 25 kHz acquisition; the supply was fed to the coater through "
                  "the lab's 8 m cable reel and a worn connector: 0.1 ohm inside the source; "
                  "the user frees k and Jg (really 3 % higher and 4 % lower than declared); "
                  "Gauss-Markov noise on the current (40 mA, correlation 0.6 over the "
                  "interval: the shunt amplifier's chopper ripple, smeared)"),
        spec("bh07", "catalog", "fast", False, (inertia_roll(0.2),), probes=("speed",),
             noise={"speed": {"white": 0.25, "quant": MOTOR_STEP}},
             free={"R": -0.025, "Th": 0.04, "Ks": 0.03},
             note="a stand acquisition of the motor's speed alone, even 25 kHz; the roll "
                  "fitted for the test is the 120-line roll with the thicker chrome and steel "
                  "shell, not the build sheet's: the roll's inertia is 20 % higher than "
                  "declared; the user frees R, Th and Ks (really 2.5 % lower, 4 % higher and "
                  "3 % higher than declared)"),
        spec("bh10", "catalog", "fast", False, (offset_roll(0.05),),
             marginal=lambda f: (offset_roll(f),), size=0.05,
             noise={"current": {"white": 0.08, "pink": 0.03, "quant": STAND_STEP},
                    "speed": {"white": 0.25, "quant": MOTOR_STEP}},
             free={"Jm": -0.03, "Bg": 0.04},
             note="an even 25 kHz acquisition; the foil web was left threaded and gripped in "
                  "the nip against the roll, the rewinder's torque motor holding it taut: "
                  "the web pulls the roll's face forwards with a constant torque whichever "
                  "way the roll turns, scaled to a 25 sigma signature (marginal); the user "
                  "frees Jm and Bg (really 3 % lower and 4 % higher than declared); 1/f "
                  "noise on the current (30 mA)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """bh08, bh09: two catalog effects at once."""
    return [
        spec("bh08", "two", "fast", True,
             (emf_harmonic(2, 1.5e-3, 0.7), sensor("current", "delay", 6e-5)),
             free={"Jm": 0.03, "Tg": -0.035, "Ks": 0.04},
             noise={"current": {"white": 0.08, "quant": STAND_STEP},
                    "speed": {"white": 0.25, "quant": MOTOR_STEP}},
             note="a jittered 25 kHz acquisition; the armature stack was pressed onto a "
                  "knurled shaft and went slightly oval: the air gap under the two poles "
                  "narrows and widens twice a turn, and the EMF with it (order 2), "
                  "1.5 mV s/rad (1.5 % of k), phase 0.7 rad; and the current was taken "
                  "through the stand's isolation amplifier, whose filter lags it by 60 us; "
                  "the user frees Jm, Tg and Ks (really 3 % higher, 3.5 % lower and 4 % "
                  "higher than declared)"),
        spec("bh09", "two", "slow", False,
             (backlash(0.02), sensor("load_speed", "gain", 0.9766)),
             free={"R": -0.03, "Jh": 0.04, "Bg": 0.03},
             noise={"current": {"white": 0.02, "quant": LOGGER_STEP},
                    "speed": {"white": 0.15, "ar1": [0.05, 0.7], "quant": MOTOR_STEP},
                    "load_speed": {"white": 0.004, "quant": ROLL_STEP}},
             note="an even record; the coupling hub's key has worn its keyway on the drive "
                  "shaft: a play of 20 mrad (1.15 degree) in the drive to the roll; and the "
                  "logger was set up for the roll encoder's 2048 lines while the fitted "
                  "encoder has 2000: the roll's speed reads 2000/2048 = 0.9766 of the true; "
                  "the user frees R, Jh and Bg (really 3 % lower, 4 % higher and 3 % higher "
                  "than declared); Gauss-Markov noise on the motor's speed (50 mrad/s, "
                  "correlation 0.7 over the interval)"),
    ]


#: the nip: the controller's threshold [rad/s] and its smoothness [rad/s], the cylinders'
#: time constant [s], the traction's limit [N m] and its slip scale [rad/s], the nip
#: roller's inertia at the roll's speed [kg m^2], its bearings' drag [N m s/rad] and the
#: pressed rubber's rolling resistance [N m]
NIP = (12.0, 0.3, 0.15, 1.2, 0.5, 0.012, 0.004, 0.15)
#: the disc packs' fretting: the friction [N m] and its slip scale [rad/s]
FRET = (0.4, 0.01)
#: the thixotropic slurry: the structure's extra drag [N m s/rad], its rebuilding time [s]
#: and the roll's turning that breaks it down [rad]
THIX = (0.15, 20.0, 10.0)
#: the true-RMS converter's averaging time constant [s]
RMS = 0.1


def outside_records() -> list[dict[str, Any]]:
    """bh11-bh14: effects the catalog does not contain."""
    w_on, dw, tau, tmax, v0, ji, bi, tr = NIP
    tf, vf = FRET
    db, t_rec, theta_b = THIX
    return [
        spec("bh11", "outside", "slow", True, (outside(
            "nip-roller-thrown-on-above-a-speed-spun-up-by-the-roll", {"nip": NIP},
            {"w_on_rad_s": w_on, "dw_rad_s": dw, "tau_s": tau, "Tmax_Nm": tmax,
             "v0_rad_s": v0, "Ji_kgm2": ji, "bi_Nms_rad": bi, "Tr_Nm": tr,
             "form": "the nip's engagement s follows ds/dt = (sig((|wg| - w_on)/dw) - s)/tau "
                     "from 0, sig(x) = 1/(1 + exp(-x)); the nip roller (Ji at the roll's "
                     "speed, its speed wi from rest, its drag bi wi) is driven by the "
                     "traction Tc = s Tmax tanh((wg - wi)/v0), which the roll gives up, and "
                     "the pressed rubber's rolling resistance s Tr tanh(wg/0.01) acts "
                     "against the roll"}),),
            free={"k": -0.035, "Bg": 0.03},
            noise={"current": {"white": 0.02, "quant": LOGGER_STEP},
                   "speed": {"white": 0.15, "quant": MOTOR_STEP},
                   "load_speed": {"white": 0.004, "quant": ROLL_STEP}},
            note=NOTE_NIP),
        spec("bh12", "outside", "slow", False, (outside(
            "loose-disc-pack-bolts-fret-across-the-coupling", {"fret": FRET},
            {"Tf_Nm": tf, "v0_rad_s": vf,
             "form": "beside the drive shaft's spring and damper, the coupling passes "
                     "Tf tanh((w/N - wg)/v0) from the hub to the roll: a dry friction on "
                     "the shaft's twist rate, not on either body's speed"}),),
            free={"R": 0.03, "Jg": -0.045},
            noise={"current": {"white": 0.02, "ar1": [0.012, 0.85], "quant": LOGGER_STEP},
                   "speed": {"white": 0.15, "quant": MOTOR_STEP},
                   "load_speed": {"white": 0.004, "quant": ROLL_STEP}},
            note=NOTE_FRET),
        spec("bh13", "outside", "slow", True, (outside(
            "thixotropic-slurry-thins-as-the-roll-shears-it-and-rebuilds-at-rest",
            {"thix": THIX},
            {"db_Nms_rad": db, "t_rec_s": t_rec, "theta_b_rad": theta_b,
             "form": "the slurry's drag is (Bg + db lam) wg, its structure lam (1 at the "
                     "start) following dlam/dt = (1 - lam)/t_rec - lam |wg|/theta_b"}),),
            free={"Jh": 0.035, "Tg": -0.03},
            noise={"current": {"white": 0.02, "quant": LOGGER_STEP},
                   "speed": {"white": 0.15, "quant": MOTOR_STEP},
                   "load_speed": {"white": 0.004, "ar1": [0.002, 0.75], "quant": ROLL_STEP}},
            note=NOTE_THIX),
        spec("bh14", "outside", "slow", False, (outside(
            "current-channel-reads-a-true-rms-converter", {"rms": RMS},
            {"tau_s": RMS,
             "form": "the current reads sqrt(m), dm/dt = (i^2 - m)/tau from 0: the root of "
                     "the current's mean square over tau, never negative"}),),
            free={"L": 0.04, "Th": -0.03}, probes=("current", "speed"),
            noise={"current": {"white": 0.02, "quant": LOGGER_STEP},
                   "speed": {"white": 0.15, "pink": 0.05, "quant": MOTOR_STEP}},
            note=NOTE_RMS),
    ]


NOTE_NIP = (
    "the stand logger's irregular intervals; the user frees k and Bg (really 3.5 % lower and "
    "3 % higher than declared); the coater's controller was left in its production mode, "
    "which closes the rubber nip roller onto the gravure roll by its pneumatic cylinders "
    "once the roll runs faster than 12 rad/s and opens it again below that: a person sees "
    "everything as declared at threading speed, then, as the command ramps towards 36 V, the "
    "nip closes at 5.5 s and the roll has to spin the nip roller up from rest by traction "
    "(it catches up within 0.3 s): the current up to 0.64 A higher and the motor up to "
    "3.2 rad/s slower at 5.7 s, the roll up to 0.19 rad/s slower; through the rest of the "
    "36 V run the pressed rubber's rolling resistance and the nip roller's drag take 0.135 A "
    "more current and 0.69 rad/s of the motor's speed (40 mrad/s of the roll's); the nip "
    "opens in the stop at about 10.0 s, the nip roller's own inertia pushing the roll "
    "along until then (the motor up to 0.69 rad/s faster at 9.6 s); backwards at -18 V (the roll at -10 rad/s) nothing differs from the declared; "
    "not a friction or an inertia of the roll: a second roller pressed on above a speed, "
    "which the roll must bring up to its own speed")
NOTE_FRET = (
    "an even record; the user frees R and Jg (really 3 % higher and 4.5 % lower than "
    "declared); the bolts clamping the double disc-pack coupling's packs to its centre spool "
    "had worked loose, and the packs' laminations fret on each other and on the spool "
    "whenever the drive shaft winds up or unwinds: a dry friction of 0.4 N m on the shaft's "
    "twist rate, beside its spring and damper; a person sees nothing in any steady run (the "
    "twist at rest with the load), but the roll's swinging on the shaft after each change of "
    "the command is choked off: at the start the motor up to 0.68 rad/s and the current up "
    "to 0.13 A off (0.58 s), entering the 36 V ramp 0.55 rad/s and 0.11 A (5.1 s), leaving "
    "it 0.63 rad/s and 0.13 A (6.1 s), at the stop 0.80 rad/s and 0.15 A (10.3 s) and "
    "at the reversal 0.89 rad/s and 0.18 A (11.05 s), the roll up to 0.13 rad/s off; not a "
    "friction on the hub or the roll, a damping or a play: a friction across the coupling "
    "that acts only while the shaft's twist changes")
NOTE_THIX = (
    "the stand logger's irregular intervals; the user frees Jh and Tg (really 3.5 % higher "
    "and 3 % lower than declared); the pan was filled from a drum of electrode slurry that "
    "had stood overnight and set to a gel: the slurry is thixotropic, its structure (and an "
    "extra drag of up to 0.15 N m s/rad on the roll) breaking down as the roll shears it, "
    "within about 10 rad of the roll's turning, and building up again only slowly at rest "
    "(time constant 20 s); a person sees the first start heavy: at threading speed the "
    "current up to 0.34 A higher and the motor up to 1.7 rad/s slower at 2.05 s, the roll "
    "up to 94 mrad/s slower, still 0.26 A and 1.3 rad/s at 2.5 s, fading through the 12 V "
    "run (the structure at 0.36 of its start at 3 s, 0.14 at 5 s), 0.12 A and 0.57 rad/s "
    "entering the 36 V run and nearly nothing at the stop; after the 0.7 s at rest the "
    "reversal is only a little heavier (0.066 A and 0.32 rad/s at 11.9 s); not a viscous "
    "or a dry friction or a breakaway: a drag that remembers how long the slurry rested and "
    "how far the roll has sheared it")
NOTE_RMS = (
    "an even record of the current and the motor's speed; the user frees L and Th (really 4 % "
    "higher and 3 % lower than declared); the current was logged from the analog output of "
    "the lab's clamp meter (put round the motor lead in place of the stand's shunt "
    "channel), which had been left in its true-RMS mode: it reads the root of the current's "
    "mean square over about 0.1 s, never a negative current; a person sees the speed as "
    "declared and the current as declared while it is positive but lagging each change (up to "
    "0.54 A low at the start, 0.63 s, 0.86 A low and 0.96 A high as the ramp to 36 V starts "
    "and ends, 5.07 s and 6.08 s), then positive all through the stop's braking (3.5 A "
    "high at 10.3 s) and the whole backward run: 1.25 A where the motor takes -1.25 A, and "
    "5.1 A high as the reversal's ramp ends at 11.8 s; not a gain, an offset or a delay of the "
    "current's reading: a reading of the current's magnitude, averaged")


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
    return recordkit.record_times(s, se.REGIMES, se.grid, 56, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

def scalar_effects(p: dict[str, float]) -> tuple[tuple[str, dict], ...]:
    """Small catalog effects (label, fx) an imprint is compared with, linearised at the
    record's true null (``p``: its true values, the inertias' steps relative to them)."""
    return (
        ("series-resistance", {"Rser": 1e-4}),
        ("brush-drop", {"Vb": 1e-2}),
        ("coulomb-friction:rotor", {"coul": {"rotor": 1e-5}}),
        ("coulomb-friction:hub", {"coul": {"hub": 1e-4}}),
        ("coulomb-friction:roll", {"coul": {"roll": 1e-4}}),
        ("viscous-friction:rotor", {"visc": {"rotor": 1e-8}}),
        ("viscous-friction:hub", {"visc": {"hub": 1e-5}}),
        ("viscous-friction:roll", {"visc": {"roll": 1e-5}}),
        ("force-offset:rotor", {"offset": {"rotor": 1e-5}}),
        ("force-offset:hub", {"offset": {"hub": 1e-4}}),
        ("force-offset:roll", {"offset": {"roll": 1e-4}}),
        ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-5, 5.0)}}),
        ("stribeck-friction:hub", {"stribeck": {"hub": (1e-4, 0.3)}}),
        ("stribeck-friction:roll", {"stribeck": {"roll": (1e-4, 0.3)}}),
        ("backlash:K", {"gap": 1e-5}),
        ("inductance", {"p": {"L": p["L"] * 1.001}}),
        ("inductor-saturation:40", {"lsat": (40.0, 0.999)}),
        ("inertia:Jr", {"p": {"Jm": p["Jm"] * 1.001}}),
        ("inertia:Jh", {"p": {"Jh": p["Jh"] * 1.001}}),
        ("inertia:Jg", {"p": {"Jg": p["Jg"] * 1.001}}),
        ("resistance-drift:linear", {"alpha": 1e-4}),
        ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
        ("resistance-drift:warmup-2", {"warmup": (1e-3, 2.0)}),
    )


#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder); the
#: rotor's order 12 (its 2 poles against its 12 slots), the roll's order 6 (the six bolts of
#: the coupling's disc packs)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:hub", lambda a, b: {"cog": {"hub": [(1, a, b)]}}),
    ("unbalance:roll", lambda a, b: {"cog": {"roll": [(1, a, b)]}}),
    ("cogging:rotor:12", lambda a, b: {"cog": {"rotor": [(12, a, b)]}}),
    ("cogging:roll:6", lambda a, b: {"cog": {"roll": [(6, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:12", lambda a, b: {"emf": [(12, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 10 uN m on the
    rotor (and 1e-7 V s/rad of EMF), 0.1 mN m on the hub and the roll."""
    return 1e-5 if (":rotor" in label or label.startswith("emf")) else 1e-4


#: the places a torque effect may sit at, each with its gear factor (its speed over the
#: hub's: the rotor turns N times the hub, the roll at the hub's mean speed across the
#: 1:1 drive shaft); rotor-hub is exact (the rigid reduction), rotor-roll and hub-roll lie
#: across the compliance
PLACES = {"rotor": N, "hub": 1.0, "roll": 1.0}
#: the same for an inertia (component: (parameter, gear factor)); Jr is the rotor's, the
#: parameter Jm
INERTIAS = {"Jr": ("Jm", N), "Jh": ("Jh", 1.0), "Jg": ("Jg", 1.0)}
#: the places behind the drive shaft
BEYOND = ("roll", "Jg")
#: the catalog's kinds of the armature loop (one place: the loop)
LOOP_KINDS = ("series-resistance", "source-resistance", "brush-drop", "inductance",
              "inductor-saturation", "resistance-drift", "emf-harmonic")
#: an inertia component's body
INERTIA_BODY = {"Jr": "rotor", "Jh": "hub", "Jg": "roll"}


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
    """Motor BE's clean probes at the DECLARED values (Plumbing's field; every record's own
    runs go through ``run``, at its true values)."""
    return se.simulate(regime, t, fx)


#: the plumbing of this set; each probe's sensor effects are its gain, its offset and its
#: delay; the netlist declares no harmonic term of the catalog's kinds
KIT = LawSeparated(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=se, sim=sim,
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
