"""Generate the blind set ``fresh51`` of the diagnosis benchmark: records bc01-bc14 of motor AZ
(a 24 V brushed DC gearmotor in the rotation drive of a lighthouse's rotating optic on the
lighthouse service's workshop test stand: a rigid 800:1 worm gearbox and spur stage to the
pedestal's bull wheel, turning in its bronze bearings, the 1.4 m vertical drive spindle a
torsional compliance to the third-order four-panel Fresnel lens floating on its mercury bath,
the lens meeting the dry friction of the float's centring rollers and the viscous drag of the
roller carriage's grease and of the mercury), some sampled evenly and some UNEVENLY, three of
them giving the diagnosis ONE probe only, and merge their truth into truth.json. The ids have
two letters.

    python benchmarks/diagnosis/make_records_az.py                # records/bc*.csv + truth.json
    python benchmarks/diagnosis/make_records_az.py --only bc03,bc12
    python benchmarks/diagnosis/make_records_az.py --truth-only   # rewrite the bc entries only

As in fresh45 to fresh50, the netlists (motor_az_fast.yaml, motor_az_slow.yaml) declare the
motor's parameters as the maker's data give them, and in every record two or three of them are
WRONG by 2-6 % (``FREE``: the record's relative errors, mixed signs): the record is simulated
with the TRUE values of those parameters (and the record's effects), and the user frees exactly
those parameters (truth's ``free``, the netlist's parameter names, and ``declared_error``:
{name: {"declared": the netlist's value, "true": the record's}}). The other parameters are
declared exactly. A null record holds only the declared errors (the right answer: nothing new,
the freed parameters fitted).

A catalog effect that is the same thing as moving a freed parameter cannot be told from it (a
series or source resistance, or a resistance drift, when R is freed; an inertia correction on
a freed inertia -- the hub's inertia is the rotor's through the rigid gear --; a viscous
friction when the lens's viscous drag Bl is freed; a dry friction when the hub's Th or the
lens's Tl is freed; a speed sensor's gain when k is freed; the inductance when L is freed): no
record puts such an effect with its twin freed (``TWINS``, checked). Each catalog or
two-effect record states, per effect, how far its own imprint (run alone on the record's times
and true values) lies from the freed parameters' imprints jointly, best-scaled
(``free_separation_sigma``; linearised: each freed parameter's column is its 1 % step); a record
below FREE_SEPARATION is reported. An outside record's imprint must keep OUTSIDE_LEFT after the
catalog's effects AND the freed parameters jointly (``unexplained_sigma``, whose alternatives
include the ``free:<name>`` columns). A marginal record's ``separation_sigma`` compares it with
each other catalog effect with the freed parameters beside that effect (as the diagnosis fits
them).

As in fresh47 to fresh50, a two-effect record also states, per effect, whether the record
tells the effect's LAW from the other catalog kinds at the same place
(``law_separation_sigma``): the record's whole imprint against each neighbour kind at the
effect's place (a dry friction on the hub against a viscous friction, a breakaway friction, a
torque offset, an angle-locked torque or an inertia on the hub; a viscous drag on the lens
against the lens's other kinds; a sensor's gain, offset or delay against the same probe's other
kinds), linearised, best-scaled, with the freed parameters' columns and the record's OTHER
effect (its own imprint run alone, best-scaled) beside it; ``own_sigma`` is the same fit with
the effect's own imprint in the neighbour's place (what the linear fit leaves of the effects'
interaction: the floor), ``without_sigma`` with nothing in its place.

Every imprint, signature and alternative is computed about the record's TRUE null (the true
values, no effect): ``signature_sigma`` is the effect's own; a null record's
``signature_sigma`` is its declared errors' (the true null against the declared one), and
every record's ``declared_error_signature_sigma`` is that.

Uses simulators_az.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_az_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the imprints it is compared with are computed on that probe alone. Even
records are sampled on the regime's grid k/fs; uneven ones, in the fast regime, on a 20 kHz
grid whose every sample is moved by a random jitter of up to 6-22 % of the interval, and in
the slow regime at a logger's irregular intervals (0.6-1.4 times the mean of 5 ms) with a few
samples dropped. Each uneven record has its own times (from its seed), and the motor is
simulated at those very times (``t_eval``), never interpolated. truth.json is merged under an
exclusive lock (recordkit.merge). A catalog or two-effect record's ``location_sigma`` covers
every other place its effect has an equal at: a torque effect on the rotor, the hub or the
lens is compared with its equal on each of the other two (across the drive spindle for
rotor-lens and hub-lens, through the rigid gear for rotor-hub), an added inertia on Jr, Jh or
Jl with its equal on the other two (``PLACES``, ``INERTIAS``, recordkit.places_entry). Nobody
ran the diagnosis on these records.
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
import simulators_az as sz

RECORDS = HERE / "records"
SPLIT = "fresh51"
MOTOR = "AZ"
SEED0 = 51500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_az_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_az_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.03, "speed": 0.25},
         "slow": {"current": 0.008, "speed": 0.2, "load_speed": 0.0015}}
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
JITTER, DROPS = (0.06, 0.22), (2, 8)
#: the declared values (the netlists'): what the diagnosis starts from
P = sz.MOTOR_AZ
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
# Each returns (fx fragment for simulators_az, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The drive is rigid and lossless as declared: a torque on
# the body ``hub`` (the bull wheel with the drive spindle's foot) is 1/N = 1/800 of it on the
# rotor, and the hub turns at 1/N of the rotor's speed (a dry friction c on the hub is c / N
# on the rotor, a viscous friction b on the rotor b N^2 on the hub). The lens lies behind the
# drive spindle's compliance (1:1): an effect on it has no exact equal on the hub or the rotor.
# No effect here changes a parameter a record frees.

def saturation(ipar: float, ratio: float) -> Part:
    """The armature inductance saturating: La (ratio + (1 - ratio) / (1 + (i / Ipar)^2))."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def drift(alpha: float) -> Part:
    """The armature's resistance changing linearly, R (1 + alpha t) [1/s]."""
    return {"alpha": alpha}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + alpha*t)", "alpha_per_s": alpha},
        "expected": {"alpha": alpha}}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF harmonic w slope sin(order th + phase) [V], voltage only (a marginal record
    scales the slope)."""
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


def coulomb_lens(c: float) -> Part:
    """An extra dry friction c tanh(wl / 0.01) [N m] on the lens (behind the spindle; a
    marginal record scales it)."""
    return {"coul": {"lens": c}}, {
        "effect": "coulomb-friction", "target": "lens", "targets": ["lens"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(wl/0.01) against the lens"},
        "expected": {"c": c}}


def coulomb_hub(c: float) -> Part:
    """An extra dry friction c tanh(wh / 0.01) [N m] on the hub (accepted on the rotor at
    c / N)."""
    return {"coul": {"hub": c}}, {
        "effect": "coulomb-friction", "target": "hub", "targets": ["hub"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(wh/0.01) against the hub"},
        "expected": {"c": c},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["rotor"],
                         "expected": {"c": c / N}}]}


def offset_hub(torque: float) -> Part:
    """A constant torque ``torque`` [N m] the hub receives (accepted on the rotor at
    torque / N)."""
    return {"offset": {"hub": torque}}, {
        "effect": "force-offset", "target": "hub", "targets": ["hub"],
        "parameters": {"T_Nm": torque,
                       "form": "the hub receives a constant T (T > 0: turning it forwards)"},
        "expected": {"F": torque},
        "also_accept": [{"effect": "force-offset", "targets": ["rotor"],
                         "expected": {"F": torque / N}}]}


def viscous_lens(b: float) -> Part:
    """An extra viscous drag b wl [N m s/rad] on the lens (behind the spindle)."""
    return {"visc": {"lens": b}}, {
        "effect": "viscous-friction", "target": "lens", "targets": ["lens"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b wl against the lens"},
        "expected": {"b": b}}


def viscous_rotor(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the rotor (accepted on the hub at
    b N^2)."""
    return {"visc": {"rotor": b}}, {
        "effect": "viscous-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b w against the rotor"},
        "expected": {"b": b},
        "also_accept": [{"effect": "viscous-friction", "targets": ["hub"],
                         "expected": {"b": b * N ** 2}}]}


outside = recordkit.outside


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None,
         free: dict[str, float] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.declared_spec``): the probes it gives the
    diagnosis (default: all of its regime's) and the declared parameters it frees
    (``free``: name -> relative error of the true value over the declared)."""
    return recordkit.declared_spec(rid, cls, regime, uneven, parts, noise, note, marginal,
                                   size, probes=probes or sz.PROBES[regime], free=free,
                                   params=P, twins=TWINS, mixed_signs=True)


def run(s: dict[str, Any], fx: dict, t: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """Motor AZ's clean probes at the record's times (or ``t``) [s] with its TRUE values and
    the effects ``fx``."""
    return sz.simulate(s["regime"], times(s) if t is None else t, fx, s["ptrue"])


def declared_run(s: dict[str, Any]) -> dict[str, np.ndarray]:
    """Motor AZ's clean probes at the record's times with the DECLARED values, no effect."""
    return sz.simulate(s["regime"], times(s), {})


# ---------------------------------------------------------------------- the records

#: the stand's fast acquisition's current channel: a 14-bit ADC over +-20 A (2.44 mA steps)
RIG_STEP = 40.0 / 16384
#: the stand's data logger's current channel: 16 bits over +-5 A (0.153 mA steps)
LOGGER_STEP = 10.0 / 65536
#: the tachogenerator's channel: 16 bits over +-500 rad/s (0.0153 rad/s steps)
TACHO_STEP = 1000.0 / 65536
#: the lens encoder interface's speed word: 0.2 mrad/s steps
ENCODER_STEP = 2e-4


def nulls() -> list[dict[str, Any]]:
    """bc01, bc02: the null records (the declared errors only)."""
    return [
        spec("bc01", "null", "slow", False, free={"Ks": 0.05, "Tl": -0.04},
             noise={"current": {"white": 0.008, "ar1": [0.004, 0.8], "quant": LOGGER_STEP},
                    "speed": {"white": 0.2, "quant": TACHO_STEP},
                    "load_speed": {"white": 0.0014, "pink": 0.0006, "quant": ENCODER_STEP}},
             note="the stand's logger's record of the acceptance program, an even record; the "
                  "user frees the drive spindle's stiffness (the drawings' figure is for the "
                  "original wrought-iron spindle; the refurbished pedestal has a new steel one) "
                  "and the centring rollers' dry friction (the drawings' figure is for bronze "
                  "rollers; these were re-bushed in PTFE): Ks is really 5 % higher, Tl 4 % "
                  "lower; nothing else; the current with Gauss-Markov noise (4 mA, correlation "
                  "0.8 over the interval) on white noise, in the logger's 0.153 mA steps; the "
                  "tachogenerator's speed in 0.0153 rad/s steps; the lens's speed with 1/f noise "
                  "(0.6 mrad/s: the encoder's friction wheel on the lens table's rim) on white "
                  "noise, in 0.2 mrad/s steps"),
        spec("bc02", "null", "fast", True, probes=("current",),
             free={"R": 0.03, "Jl": -0.045, "Bl": 0.035},
             noise={"current": {"white": 0.03, "ar1": [0.015, 0.7], "quant": RIG_STEP}},
             note="a stand acquisition of the current alone (the 14-bit ADC), a jittered 20 kHz "
                  "acquisition; the user frees the armature's resistance, the lens's inertia "
                  "and its viscous drag (a motor of another winding batch; two of the lens's "
                  "brass-framed panels re-glazed with lighter glass; the roller carriage packed "
                  "with a stiffer grease than the drawings'): R is really 3 % higher, Jl "
                  "4.5 % lower, Bl 3.5 % higher; nothing else; Gauss-Markov noise (15 mA, "
                  "correlation 0.7 over the interval: the brushes' ripple, smeared) on white "
                  "noise, in 2.44 mA steps"),
    ]


def singles() -> list[dict[str, Any]]:
    """bc03-bc07, bc10: one catalog effect each."""
    return [
        spec("bc03", "catalog", "fast", True, (saturation(6.0, 0.55),), probes=("current",),
             noise={"current": {"white": 0.03, "quant": RIG_STEP}},
             free={"k": -0.03, "Ks": 0.04},
             note="a stand acquisition of the current alone (the 14-bit ADC), jittered 20 kHz; "
                  "the motor was rewound with a thinner stator return path (the refurbisher's "
                  "own laminations): its armature's inductance saturates with the current, "
                  "down to 55 % of the declared at high currents (Ipar 6 A); the user frees k "
                  "and Ks (really 3 % lower and 4 % higher than declared)"),
        spec("bc04", "catalog", "slow", False, (coulomb_lens(0.5),),
             marginal=lambda c: (coulomb_lens(c),), size=0.5,
             free={"R": 0.035, "Jh": -0.04},
             note="an even record; one of the float's sprung centring rollers was refitted with "
                  "a stiffer spring: an extra dry friction on the lens, scaled to a 25 sigma "
                  "signature (marginal); the user frees R and Jh (really 3.5 % higher and 4 % "
                  "lower than declared)"),
        spec("bc05", "catalog", "fast", True, (offset_hub(7.0),),
             free={"Jm": 0.03, "Tl": -0.05},
             noise={"current": {"white": 0.03, "quant": RIG_STEP},
                    "speed": {"white": 0.25, "quant": TACHO_STEP}},
             note="a jittered 20 kHz acquisition; the old clockwork's driving weight (kept as "
                  "the light's standby drive) was left hooked to its drum on the bull wheel's "
                  "shaft, hanging well clear of its tube's floor: a constant forward torque of "
                  "7 N m on the hub; the user frees Jm and Tl (really 3 % higher and 5 % lower "
                  "than declared)"),
        spec("bc06", "catalog", "slow", False, (drift(-0.004),),
             free={"k": -0.025, "Bl": 0.04, "Ks": -0.05},
             noise={"current": {"white": 0.008, "quant": LOGGER_STEP},
                    "speed": {"white": 0.2, "pink": 0.08},
                    "load_speed": {"white": 0.0015, "quant": ENCODER_STEP}},
             note="an even record; the motor's armature had been dried in the workshop's oven "
                  "after the lighthouse's damp winter and went onto the stand still warm: its "
                  "resistance falls as it cools, by 0.4 % of the declared per second "
                  "through the record; the user frees k, Bl and Ks (really 2.5 % lower, 4 % "
                  "higher and 5 % lower than declared); 1/f noise on the speed (0.08 rad/s, the "
                  "tachogenerator's brushes)"),
        spec("bc07", "catalog", "fast", False, (emf_harmonic(1, 2e-3, 0.7),),
             marginal=lambda a: (emf_harmonic(1, a, 0.7),), size=2e-3,
             noise={"current": {"white": 0.03, "quant": RIG_STEP}, "speed": {"white": 0.25}},
             free={"Th": 0.04, "Jl": -0.035},
             note="an even 20 kHz acquisition (the current by the 14-bit ADC); one of the "
                  "motor's two ferrite magnet arcs was chipped and re-bonded in the "
                  "refurbishment: the EMF is weaker under it, an EMF harmonic once a turn of "
                  "the rotor, scaled to a 25 sigma signature (marginal), phase 0.7 rad; the "
                  "user frees Th and Jl (really 4 % higher and 3.5 % lower than declared)"),
        spec("bc10", "catalog", "fast", True, (viscous_rotor(6e-5),),
             probes=("speed",), noise={"speed": {"white": 0.25, "quant": TACHO_STEP}},
             free={"R": 0.03, "Jl": -0.04},
             note="a stand acquisition of the tachogenerator's speed alone, jittered 20 kHz; "
                  "the motor was fitted with a shaft-mounted cooling fan for the lantern's "
                  "summer heat: an extra viscous friction of 6e-5 N m s/rad on the rotor; the "
                  "user frees R and Jl (really 3 % higher and 4 % lower than declared)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """bc08, bc09: two catalog effects at once."""
    return [
        spec("bc08", "two", "slow", True,
             (viscous_lens(8.0), sensor("load_speed", "offset", 0.004)),
             free={"Jl": -0.04, "Th": 0.03, "k": 0.025},
             note="the stand's logger's irregular intervals; the mercury bath was topped up "
                  "with mercury that had not been cleaned of its oxide scum: an extra viscous "
                  "drag of 8 N m s/rad on the lens; and the lens encoder interface's zero was "
                  "trimmed off: the lens's speed reads 4 mrad/s high; the user frees Jl, Th "
                  "and k (really 4 % lower, 3 % higher and 2.5 % higher than declared)"),
        spec("bc09", "two", "fast", False,
             (coulomb_hub(2.5), sensor("current", "delay", 4e-4)),
             free={"R": 0.04, "Jm": -0.03, "Ks": 0.045},
             noise={"current": {"white": 0.03, "quant": RIG_STEP}, "speed": {"white": 0.25}},
             note="an even 20 kHz acquisition; the bull wheel's lower bronze bearing was "
                  "re-bushed a little tight: an extra dry friction of 2.5 N m on the hub; and "
                  "the shunt amplifier was set to its filtered mode: the current lags by "
                  "0.4 ms; the user frees R, Jm and Ks (really 4 % higher, 3 % lower and 4.5 % "
                  "higher than declared)"),
    ]


#: the freewheel diode left across the motor's terminals: the stand's supply's current limit
#: Ilim [A], the diode's n Vt [V] and saturation current Is [A]
CLAMP = (3.0, 0.0514, 1e-6)
#: the tachogenerator's pair beside the motor's lead: M / Kt [s] (40 uH of mutual inductance
#: over the tachogenerator's 9.55 mV s/rad)
PICKUP = 4.2e-3
#: the lens encoder's ratiometric output: rho [1/A] (0.6 ohm of shared return on its 24 V
#: rail)
RATIO = 0.025
#: the overtravel switch: the lens's angle where its cam opens the contact [rad], the cam's
#: ramp [rad], the contact's suppression resistor [ohm], the bypass diode's n Vt [V] and Is [A]
LIMIT = (0.02, 0.002, 100.0, 0.0514, 1e-6)


def outside_records() -> list[dict[str, Any]]:
    """bc11-bc14: effects the catalog does not contain."""
    ilim, nvt, isat = CLAMP
    th_lim, dth, roff, _, _ = LIMIT
    return [
        spec("bc11", "outside", "slow", False, (outside(
            "old-panel-freewheel-diode-in-the-terminal-box-clamps-the-reversal",
            {"clamp": CLAMP},
            {"Ilim_A": ilim, "nVt_V": nvt, "Is_A": isat,
             "form": "the motor's terminals see v = max(u, -nVt ln(1 + (Ilim + i)/Is)) and "
                     "the current (the supply's) reads i - Is (exp(-v/nVt) - 1): a diode "
                     "across the terminals (cathode to the positive one) conducts whenever "
                     "the supply drives them negative, the supply then held at -Ilim by its "
                     "current limit, the terminals at the diode's forward drop"}),),
            free={"R": -0.03, "Bl": 0.035}, note=NOTE_CLAMP),
        spec("bc12", "outside", "fast", False, (outside(
            "tacho-pair-picks-up-the-motor-lead-current-rate", {"pickup": PICKUP},
            {"M_over_Kt_s": PICKUP, "M_H": 4e-5, "Kt_V_s_rad": 9.55e-3,
             "form": "speed reads w + (M/Kt) di/dt, di/dt the armature current's rate: the "
                     "voltage the motor lead's current induces in the tachogenerator's "
                     "unscreened pair; the motor itself is not touched"}),),
            free={"L": 0.04, "Jl": -0.03},
            noise={"current": {"white": 0.03, "quant": RIG_STEP},
                   "speed": {"white": 0.25, "quant": TACHO_STEP}},
            note=NOTE_PICKUP),
        spec("bc13", "outside", "slow", True, (outside(
            "lens-speed-output-ratiometric-to-a-rail-sharing-the-motor-return",
            {"ratio": RATIO},
            {"rho_per_A": RATIO,
             "form": "load_speed reads wl (1 - rho i): the encoder's analog speed output is "
                     "ratiometric to its 24 V rail, whose return conductor (0.6 ohm) carries "
                     "the motor's current i too; the motor itself is not touched"}),),
            free={"k": -0.03, "Th": 0.04, "Ks": 0.05},
            noise={"current": {"white": 0.008, "pink": 0.003, "quant": LOGGER_STEP},
                   "speed": {"white": 0.2, "quant": TACHO_STEP},
                   "load_speed": {"white": 0.0015, "quant": ENCODER_STEP}},
            note=NOTE_RATIO),
        spec("bc14", "outside", "fast", True, (outside(
            "overtravel-limit-switch-with-bypass-diode-opens-the-lead", {"limit": LIMIT},
            {"theta_lim_rad": th_lim, "dtheta_rad": dth, "Roff_ohm": roff, "nVt_V": nvt,
             "Is_A": isat,
             "form": "the loop takes h (Roff (i + a)/2 - nVt ln(1 + (a - i)/(2 Is))), "
                     "a = sqrt(i^2 + (1 uA)^2), h = (1 + tanh((thl - theta_lim)/dtheta))/2, "
                     "thl the lens's angle from the start: past theta_lim the switch's "
                     "contact is open, the forward current passes only its suppression "
                     "resistor Roff, the backward current its bypass diode"}),),
            free={"R": 0.035, "Tl": -0.045, "L": 0.025},
            noise={"current": {"white": 0.03, "quant": RIG_STEP},
                   "speed": {"white": 0.25, "quant": TACHO_STEP}},
            note=NOTE_LIMIT),
    ]


NOTE_CLAMP = (
    "the stand's logger's record, an even record; the user frees R and Bl (really 3 % lower "
    "and 3.5 % higher than declared); the refurbished motor came from a lantern whose old "
    "drive panel was a one-direction chopper, and the chopper's freewheel diode was left in "
    "the motor's terminal box, across the terminals (its cathode to the positive one): while "
    "the supply drives the motor forwards nothing is seen, but from 7.445 s, when the "
    "backward ramp takes the supply's output below -0.75 V, the diode conducts, the supply "
    "goes into its 3 A current limit and the terminals sit at the diode's forward drop; a "
    "person sees the current read a flat -3.00 A from 7.45 s to 10.97 s (the declared -0.60 "
    "to -1.57 A), the motor creeping backwards at -5.7 rad/s instead of running at -160 to "
    "-169 rad/s, the lens at -7.2 mrad/s instead of -0.20 to -0.22 rad/s, then the motor "
    "coasting to rest from -2.3 rad/s as the command returns to 0 V; everything as declared "
    "before 7.44 s; not a current limit of the supply alone, a resistance or a dry friction: "
    "a diode across the terminals that the supply cannot drive the motor backwards through")
NOTE_PICKUP = (
    "an even 20 kHz acquisition; the user frees L and Jl (really 4 % higher and 3 % lower "
    "than declared); on the stand the tachogenerator's unscreened signal pair was run "
    "through the same trunking as the motor's leads, loop beside loop: the armature "
    "current's changes induce a voltage in it (40 uH of mutual inductance over the "
    "tachogenerator's 9.55 mV s/rad); a person sees the speed read up to 0.83 rad/s high on "
    "the ramp up, -0.6 to +0.2 rad/s off at 22 V, up to 2.2 rad/s low through the drop to "
    "9 V (from 0.22 s), -0.9 to +1.1 rad/s off at 9 V, up to 1.6 rad/s low through the "
    "reversal, up to 2.3 rad/s high through the stop (0.42-0.45 s) and -1.1 to +1.0 rad/s "
    "off after it; the current as declared; not a delay, a gain or an offset of the speed's "
    "channel: the speed reading carries the current's rate of change")
NOTE_RATIO = (
    "the stand's logger's irregular intervals; the user frees k, Th and Ks (really 3 % lower, "
    "4 % higher and 5 % higher than declared); the lens encoder's analog speed output is "
    "ratiometric to its 24 V supply rail, and the stand's wiring returns that rail through "
    "the same 0.6 ohm conductor as the motor's current: the rail sags by 0.6 V per ampere of "
    "the motor's current, and the reading with it (2.5 % per ampere); a person sees the "
    "lens's speed read 3.0-5.3 mrad/s low at 12 V, 6.7-14 mrad/s low at 22 V and on the ramp "
    "up to it, up to 13 mrad/s high through the stop (the braking current is negative), "
    "3.4-8.1 mrad/s more negative than declared backwards, and as declared at rest; the "
    "current and the motor's speed as declared; not a gain, an offset or a delay of the "
    "encoder: a reading scaled by the motor's current")
NOTE_LIMIT = (
    "a jittered 20 kHz acquisition; the user frees R, Tl and L (really 3.5 % higher, 4.5 % "
    "lower and 2.5 % higher than declared); the stand's overtravel switch (guarding its "
    "temporary encoder cable), its cam on the lens table, was left set for the parking "
    "check, to open 0.02 rad (1.1 degrees) from where the record starts; it is wired into "
    "the motor's lead with the usual bypass diode (so that the motor can drive back off it) "
    "and a 100 ohm suppression resistor across its contact; a person sees everything as "
    "declared until 0.198 s, then the current fall from 5.4 A to 0.09-0.10 A at 22 V and "
    "the motor slow to 142-151 rad/s instead of holding 231 rad/s, the drop's braking current "
    "and the reversal's backward current still passing (through the diode, 0.2-4.1 A less "
    "negative than declared; the motor -45 to -108 rad/s), and at the stop (from 0.42 s) no "
    "braking current at all: the current reads 0.04-0.06 A instead of 1.7-4.6 A and the "
    "motor coasts at -51 to -74 rad/s instead of slowing to -17 rad/s; the lens never comes "
    "back below 0.02 rad; not a resistance, a brush drop or a dry friction: a switch that "
    "opens the forward path once the lens has turned 0.02 rad")


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
    return recordkit.record_times(s, sz.REGIMES, sz.grid, 51, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

def scalar_effects(p: dict[str, float]) -> tuple[tuple[str, dict], ...]:
    """Small catalog effects (label, fx) an imprint is compared with, linearised at the
    record's true null (``p``: its true values, the inertias' steps relative to them)."""
    return (
        ("series-resistance", {"Rser": 1e-3}),
        ("brush-drop", {"Vb": 1e-2}),
        ("coulomb-friction:rotor", {"coul": {"rotor": 1e-5}}),
        ("coulomb-friction:hub", {"coul": {"hub": 1e-2}}),
        ("coulomb-friction:lens", {"coul": {"lens": 1e-2}}),
        ("viscous-friction:rotor", {"visc": {"rotor": 1e-8}}),
        ("viscous-friction:hub", {"visc": {"hub": 1e-2}}),
        ("viscous-friction:lens", {"visc": {"lens": 1e-2}}),
        ("force-offset:rotor", {"offset": {"rotor": 1e-5}}),
        ("force-offset:hub", {"offset": {"hub": 1e-2}}),
        ("force-offset:lens", {"offset": {"lens": 1e-2}}),
        ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-5, 20.0)}}),
        ("stribeck-friction:hub", {"stribeck": {"hub": (1e-2, 0.03)}}),
        ("stribeck-friction:lens", {"stribeck": {"lens": (1e-2, 0.03)}}),
        ("backlash:K", {"gap": 1e-5}),
        ("inductance", {"p": {"L": p["L"] * 1.001}}),
        ("inductor-saturation:8", {"lsat": (8.0, 0.999)}),
        ("inertia:Jr", {"p": {"Jm": p["Jm"] * 1.001}}),
        ("inertia:Jh", {"p": {"Jh": p["Jh"] * 1.001}}),
        ("inertia:Jl", {"p": {"Jl": p["Jl"] * 1.001}}),
        ("resistance-drift:linear", {"alpha": 1e-4}),
        ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
        ("resistance-drift:warmup-2", {"warmup": (1e-3, 2.0)}),
    )


#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder); the
#: rotor's order 18 (its 9 slots against the 2 poles), the hub's order 20 (the spur stage's
#: pinion, 20 turns to the bull wheel's one), the lens's order 4 (its four panels)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:hub", lambda a, b: {"cog": {"hub": [(1, a, b)]}}),
    ("unbalance:lens", lambda a, b: {"cog": {"lens": [(1, a, b)]}}),
    ("cogging:rotor:18", lambda a, b: {"cog": {"rotor": [(18, a, b)]}}),
    ("cogging:hub:20", lambda a, b: {"cog": {"hub": [(20, a, b)]}}),
    ("cogging:lens:4", lambda a, b: {"cog": {"lens": [(4, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:18", lambda a, b: {"emf": [(18, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 10 uN m on the
    rotor (and 1e-7 V s/rad of EMF), 10 mN m on the hub and the lens."""
    return 1e-5 if (":rotor" in label or label.startswith("emf")) else 1e-2


#: the places a torque effect may sit at, each with its gear factor (its speed over the hub's:
#: the rotor turns N times the hub, the lens at the hub's mean speed across the 1:1 drive
#: spindle); rotor-hub is exact (the rigid gear), rotor-lens and hub-lens lie across the
#: spindle's compliance
PLACES = {"rotor": N, "hub": 1.0, "lens": 1.0}
#: the same for an inertia (component: (parameter, gear factor)); Jr is the rotor's, the
#: parameter Jm
INERTIAS = {"Jr": ("Jm", N), "Jh": ("Jh", 1.0), "Jl": ("Jl", 1.0)}
#: the places behind the drive spindle
BEYOND = ("lens", "Jl")
#: the catalog's kinds of the armature loop (one place: the loop)
LOOP_KINDS = ("series-resistance", "source-resistance", "brush-drop", "inductance",
              "inductor-saturation", "resistance-drift", "emf-harmonic")
#: an inertia component's body
INERTIA_BODY = {"Jr": "rotor", "Jh": "hub", "Jl": "lens"}


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
    """Motor AZ's clean probes at the DECLARED values (Plumbing's field; every record's own
    runs go through ``run``, at its true values)."""
    return sz.simulate(regime, t, fx)


#: the plumbing of this set; each probe's sensor effects are its gain, its offset and its
#: delay; the netlist declares no harmonic term of the catalog's kinds
KIT = LawSeparated(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sz, sim=sim,
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
