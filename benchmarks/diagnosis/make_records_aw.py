"""Generate the blind set ``fresh48`` of the diagnosis benchmark: records az01-az14 of motor AW
(a 24 V brushed DC gearmotor turning the spit of a caterer's hog-roast spit roaster on the
maker's test stand: a rigid 120:1 spur gearhead to the drive socket and the drive-end fork,
turning in their bushes, the 20 mm square spit a torsional compliance to a 38 kg dummy roast,
the roast's far end turning in the far upright's grease-packed sleeve bearing, its dry
friction and its grease's viscous drag), some sampled evenly and some UNEVENLY, three of them
giving the diagnosis ONE probe only, and merge their truth into truth.json. The ids have two
letters.

    python benchmarks/diagnosis/make_records_aw.py                # records/az*.csv + truth.json
    python benchmarks/diagnosis/make_records_aw.py --only az03,az12
    python benchmarks/diagnosis/make_records_aw.py --truth-only   # rewrite the az entries only

As in fresh45 to fresh47, the netlists (motor_aw_fast.yaml, motor_aw_slow.yaml) declare the
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
friction when the far bearing's viscous drag Bl is freed; a dry friction when the hub's Th or
the far bearing's Tl is freed; a speed sensor's gain when k is freed; the inductance when L is
freed): no record puts such an effect with its twin freed (``TWINS``, checked). Each catalog or
two-effect record states, per effect, how far its own imprint (run alone on the record's times
and true values) lies from the freed parameters' imprints jointly, best-scaled
(``free_separation_sigma``; linearised: each freed parameter's column is its 1 % step); a record
below FREE_SEPARATION is reported. An outside record's imprint must keep OUTSIDE_LEFT after the
catalog's effects AND the freed parameters jointly (``unexplained_sigma``, whose alternatives
include the ``free:<name>`` columns). A marginal record's ``separation_sigma`` compares it with
each other catalog effect with the freed parameters beside that effect (as the diagnosis fits
them).

As in fresh47, a two-effect record also states, per effect, whether the record tells the
effect's LAW from the other catalog kinds at the same place (``law_separation_sigma``): the
record's whole imprint against each neighbour kind at the effect's place (a breakaway friction
on the rotor against a dry friction, a viscous friction, a torque offset or an angle-locked
torque on the rotor; a sensor's gain or offset against the same probe's other kinds; an
inertia on the roast against the torque kinds on the roast), linearised, best-scaled, with the
freed parameters' columns and the record's OTHER effect (its own imprint run alone,
best-scaled) beside it; ``own_sigma`` is the same fit with the effect's own imprint in the
neighbour's place (what the linear fit leaves of the effects' interaction: the floor),
``without_sigma`` with nothing in its place.

Every imprint, signature and alternative is computed about the record's TRUE null (the true
values, no effect): ``signature_sigma`` is the effect's own; a null record's
``signature_sigma`` is its declared errors' (the true null against the declared one), and
every record's ``declared_error_signature_sigma`` is that.

Uses simulators_aw.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_aw_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the imprints it is compared with are computed on that probe alone. Even
records are sampled on the regime's grid k/fs; uneven ones, in the fast regime, on a 25 kHz
grid whose every sample is moved by a random jitter of up to 6-22 % of the interval, and in
the slow regime at a logger's irregular intervals (0.6-1.4 times the mean of 4 ms) with a few
samples dropped. Each uneven record has its own times (from its seed), and the motor is
simulated at those very times (``t_eval``), never interpolated. truth.json is merged under an
exclusive lock (recordkit.merge). A catalog or two-effect record's ``location_sigma`` covers
every other place its effect has an equal at: a torque effect on the rotor, the hub or the
roast is compared with its equal on each of the other two (across the spit for rotor-roast and
hub-roast, through the rigid gear for rotor-hub), an added inertia on Jr, Jh or Jl with its
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
import simulators_aw as sw

RECORDS = HERE / "records"
SPLIT = "fresh48"
MOTOR = "AW"
SEED0 = 48500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_aw_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_aw_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.05, "speed": 0.4},
         "slow": {"current": 0.012, "speed": 0.3, "load_speed": 0.008}}
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
P = sw.MOTOR_AW
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
# Each returns (fx fragment for simulators_aw, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearhead is rigid and lossless as declared: a torque
# on the body ``hub`` (the output shaft with the drive socket) is 1/N = 1/120 of it on the
# rotor, and the hub turns at 1/N of the rotor's speed (a dry friction c on the rotor is c N on
# the hub, a viscous friction b on the rotor b N^2 on the hub). The roast lies behind the
# spit's compliance (1:1): an effect on it has no exact equal on the hub or the rotor. No
# effect here changes a parameter a record frees.

def brush_drop(vb: float) -> Part:
    """A brush contact drop Vb tanh(i / 1 mA) [V] in series with the armature."""
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


def inductance(dl: float) -> Part:
    """The armature's inductance off by a factor 1 + ``dl`` (a correction of La's L; a
    marginal record scales it)."""
    return {"p": {"L": P["L"] * (1.0 + dl)}}, {
        "effect": "inductance", "target": "La", "targets": ["La"], "correction": True,
        "parameters": {"L_true_H": P["L"] * (1.0 + dl), "dL": dl},
        "expected": {"dL": dl}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad] in the spit K (its square end worn in the drive
    socket)."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap,
                       "form": "no spit torque while |twist| < gap/2, Ks (twist -+ gap/2) "
                               "+ Ds w_rel in contact, the damping never pulling"},
        "expected": {"gap": gap}}


def viscous_hub(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the hub (accepted on the rotor at
    b / N^2; a marginal record scales it)."""
    return {"visc": {"hub": b}}, {
        "effect": "viscous-friction", "target": "hub", "targets": ["hub"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b wh against the hub"},
        "expected": {"b": b},
        "also_accept": [{"effect": "viscous-friction", "targets": ["rotor"],
                         "expected": {"b": b / N ** 2}}]}


def unbalance_roast(amp: float, phase: float) -> Part:
    """A once-a-turn gravity torque amp sin(roast angle + phase) [N m] on the roast (behind
    the spit: no exact equal on the hub or the rotor; accepted as a cogging of order 1 on the
    roast)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"roast": [(1, a, b)]}}, {
        "effect": "unbalance", "target": "roast", "targets": ["roast"], "order": 1,
        "parameters": {"order": 1, "T_Nm": amp, "phase_rad": phase,
                       "form": "roast receives T sin(1 angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["roast"], "order": 1,
                         "expected": {"a": a, "b": b}}]}


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


def stribeck_rotor(peak: float, ws: float) -> Part:
    """A breakaway peak s exp(-(w/ws)^2) tanh(w/0.01) [N m] on the rotor, ``ws`` [rad/s]
    (accepted on the hub at s N and ws / N)."""
    return {"stribeck": {"rotor": (peak, ws)}}, {
        "effect": "stribeck-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"T_peak_Nm": peak, "w_stribeck_rad_s": ws,
                       "form": "rotor takes s exp(-(w/ws)^2) tanh(w/0.01) over its declared "
                               "Tm tanh(w/0.01)"},
        "expected": {"s": peak, "ws": ws},
        "also_accept": [{"effect": "stribeck-friction", "targets": ["hub"],
                         "expected": {"s": peak * N, "ws": ws / N}}]}


def inertia_roast(dj: float) -> Part:
    """The roast's inertia off by a factor 1 + ``dj`` (a correction of Jl's J, the parameter
    Jl; behind the spit)."""
    return {"p": {"Jl": P["Jl"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jl", "targets": ["Jl"], "correction": True,
        "parameters": {"Jl_true_kgm2": P["Jl"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


outside = recordkit.outside


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None,
         free: dict[str, float] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.declared_spec``): the probes it gives the
    diagnosis (default: all of its regime's) and the declared parameters it frees
    (``free``: name -> relative error of the true value over the declared)."""
    return recordkit.declared_spec(rid, cls, regime, uneven, parts, noise, note, marginal,
                                   size, probes=probes or sw.PROBES[regime], free=free,
                                   params=P, twins=TWINS, mixed_signs=True)


def run(s: dict[str, Any], fx: dict, t: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """Motor AW's clean probes at the record's times (or ``t``) [s] with its TRUE values and
    the effects ``fx``."""
    return sw.simulate(s["regime"], times(s) if t is None else t, fx, s["ptrue"])


def declared_run(s: dict[str, Any]) -> dict[str, np.ndarray]:
    """Motor AW's clean probes at the record's times with the DECLARED values, no effect."""
    return sw.simulate(s["regime"], times(s), {})


# ---------------------------------------------------------------------- the records

#: the test stand's fast acquisition's current channel: a 12-bit ADC over +-25 A (12.2 mA
#: steps)
STAND_STEP = 50.0 / 4096
#: the stand's data logger's current channel: 16 bits over +-5 A (0.15 mA steps)
LOGGER_STEP = 10.0 / 65536
#: the tachogenerator's channel: 16 bits over +-1000 rad/s (0.031 rad/s steps)
TACHO_STEP = 2000.0 / 65536
#: the far-end encoder's speed: 2 mrad/s steps
ENCODER_STEP = 0.002


def nulls() -> list[dict[str, Any]]:
    """az01, az02: the null records (the declared errors only)."""
    return [
        spec("az01", "null", "slow", False, free={"Th": 0.04, "Jl": -0.05},
             noise={"current": {"white": 0.01, "ar1": [0.008, 0.8], "quant": LOGGER_STEP},
                    "speed": {"white": 0.3, "quant": TACHO_STEP},
                    "load_speed": {"white": 0.007, "pink": 0.004, "quant": ENCODER_STEP}},
             note="the stand's logger's record of the end-of-line program, an even record; "
                  "the user frees the hub's bushes' dry friction (the manual's figure is for "
                  "run-in bushes; this roaster's drive-end bush is new) and the roast's "
                  "inertia (the manual's is for the maker's standard dummy; this stand's dummy "
                  "was refilled with drier sand): Th is really 4 % higher, Jl 5 % lower; "
                  "nothing else; the current with Gauss-Markov noise (8 mA, correlation 0.8 "
                  "over the interval) on white noise, in the logger's 0.15 mA steps; the "
                  "tachogenerator's speed in 0.031 rad/s steps; the roast's speed with 1/f "
                  "noise (4 mrad/s: the encoder's flexible coupling) on white noise, in "
                  "2 mrad/s steps"),
        spec("az02", "null", "fast", True, probes=("speed",),
             free={"k": -0.03, "Jm": 0.04, "Bl": 0.05},
             noise={"speed": {"white": 0.35, "ar1": [0.25, 0.75], "quant": TACHO_STEP}},
             note="a test-stand acquisition of the tachogenerator's speed alone, a jittered "
                  "25 kHz acquisition; the user frees the motor constant, the rotor's inertia "
                  "and the far bearing's viscous drag (a gearmotor of another batch, the far "
                  "bearing packed with a stiffer grease than the manual's): k is really 3 % "
                  "lower, Jm 4 % higher, Bl 5 % higher; nothing else; Gauss-Markov noise "
                  "(0.25 rad/s, correlation 0.75 over the interval: the tachogenerator's "
                  "commutator ripple, smeared) on white noise, in 0.031 rad/s steps"),
    ]


def singles() -> list[dict[str, Any]]:
    """az03-az07, az10: one catalog effect each."""
    return [
        spec("az03", "catalog", "fast", True, (brush_drop(0.35),), probes=("current",),
             noise={"current": {"white": 0.045, "quant": STAND_STEP}},
             free={"L": 0.04, "Jl": -0.03},
             note="a test-stand acquisition of the current alone (the 12-bit ADC), jittered "
                  "25 kHz; the gearmotor was rebuilt with brushes of a harder electrographitic "
                  "grade (for the heat beside the fire box): a contact drop of 0.35 V across "
                  "the pair whichever the current's direction; the user frees L and the roast's "
                  "inertia Jl (really 4 % higher and 3 % lower than declared)"),
        spec("az04", "catalog", "slow", False, (viscous_hub(0.5),),
             marginal=lambda b: (viscous_hub(b),), size=0.5,
             free={"k": 0.03, "Tl": -0.04},
             note="the gearhead's output shaft was refitted with a double-lip seal packed with "
                  "high-temperature grease: a viscous drag on the hub, scaled to a 25 sigma "
                  "signature (marginal); the user frees k and Tl (really 3 % higher and 4 % "
                  "lower than declared)"),
        spec("az05", "catalog", "fast", True, (backlash(0.02),),
             free={"Jm": -0.04, "Th": 0.05},
             note="a jittered 25 kHz acquisition; the spit's square end has worn round in the "
                  "gearhead's drive socket: 20 mrad (1.1 degrees) of play before the socket "
                  "takes the spit along; the user frees Jm and Th (really 4 % lower and 5 % "
                  "higher than declared)"),
        spec("az06", "catalog", "slow", False, (unbalance_roast(1.0, 0.8),),
             free={"R": 0.03, "k": -0.025, "Ks": -0.04},
             noise={"current": {"white": 0.012, "quant": LOGGER_STEP},
                    "speed": {"white": 0.3, "pink": 0.15},
                    "load_speed": {"white": 0.008, "quant": ENCODER_STEP}},
             note="an even record; the dummy roast stood on end in the store and its sand "
                  "bags slumped to one side: its centre of mass lies 2.7 mm off the spit's "
                  "axis, a once-a-turn gravity torque of 1.0 N m on the roast, phase 0.8 rad; the "
                  "user frees R, k and the spit's stiffness Ks (really 3 % higher, 2.5 % lower "
                  "and 4 % lower than declared: a spit of another batch); 1/f noise on the "
                  "speed (0.15 rad/s, the tachogenerator's brushes)"),
        spec("az07", "catalog", "fast", False, (inductance(-0.15),),
             marginal=lambda d: (inductance(d),), size=-0.15,
             noise={"current": {"white": 0.05, "quant": STAND_STEP}, "speed": {"white": 0.4}},
             free={"Jh": 0.04, "Ks": -0.03},
             note="an even 25 kHz acquisition (the current by the 12-bit ADC); the declared "
                  "armature inductance was measured at 1 kHz with the rotor turned to a "
                  "high-inductance position: the armature has less inductance than declared, "
                  "scaled to a 25 sigma signature (marginal); the user frees Jh and Ks (really "
                  "4 % higher and 3 % lower than declared)"),
        spec("az10", "catalog", "fast", True, (cogging_rotor(14, 0.006, 2.1),),
             probes=("speed",), noise={"speed": {"white": 0.4, "quant": TACHO_STEP}},
             free={"R": -0.05, "Jh": 0.04},
             note="a test-stand acquisition of the tachogenerator's speed alone, jittered; the "
                  "replacement motor's ferrite magnets are of a stronger grade than the "
                  "original's: its 7-slot armature's detent torque, 14 times a turn, is now "
                  "6 mN m, phase 2.1 rad; the user frees R and Jh (really 5 % lower and 4 % "
                  "higher than declared)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """az08, az09: two catalog effects at once."""
    return [
        spec("az08", "two", "slow", True,
             (inertia_roast(0.12), sensor("load_speed", "offset", 0.03)),
             free={"R": 0.03, "Ks": -0.04, "Th": 0.025},
             note="the stand's logger's irregular intervals; the dummy roast was loaded with a "
                  "second ballast bag inside its tube (for a heavier roaster model): its "
                  "inertia is 12 % above the declared; and the encoder interface's speed "
                  "output has a zero error of 30 mrad/s; the user frees R, Ks and Th (really "
                  "3 % higher, 4 % lower and 2.5 % higher than declared)"),
        spec("az09", "two", "fast", False,
             (stribeck_rotor(0.015, 40.0), sensor("current", "gain", 1.04)),
             free={"R": 0.05, "Jl": -0.04, "Tl": 0.03},
             noise={"current": {"white": 0.05, "quant": STAND_STEP}, "speed": {"white": 0.4}},
             note="an even 25 kHz acquisition; the motor's sintered bronze bushes have run dry "
                  "in the heat: the rotor breaks away from rest with a peak of 15 mN m over its "
                  "declared dry friction, fading by about 40 rad/s; and the stand's shunt "
                  "amplifier reads 4 % high (its gain resistor replaced); the user frees R, Jl "
                  "and Tl (really 5 % higher, 4 % lower and 3 % higher than declared)"),
    ]


#: the loose counterweight: its gravity torque U = m g r [N m] a quarter turn from hanging,
#: the clamp's slipping torque Tc [N m] and its inertia about the spit Jc [kg m^2]
WEIGHT = (1.5, 1.15, 0.02)
#: the stand's speed module: its direction comparator's hysteresis h [rad/s]
DIRBIT = 8.0
#: the spit controller's reed switch: n magnets on the far fork, the window's half-width
#: delta [rad], the timeout T0 [s] and the first magnet's angle theta0 [rad]
REED = (8, 0.06, 1.2, 0.2)
#: the control box's bus capacitor C [F], its charging path's resistance r [ohm], the two
#: body diodes' drop Vd [V] and its bleeder Rb [ohm]
BUS = (2200e-6, 0.3, 1.4, 10e3)


def outside_records() -> list[dict[str, Any]]:
    """az11-az14: effects the catalog does not contain."""
    u_w, tc, jc = WEIGHT
    n, delta, t0, theta0 = REED
    c, r, vd, rb = BUS
    return [
        spec("az11", "outside", "slow", False, (outside(
            "loose-counterweight-slips-on-the-spit", {"weight": WEIGHT},
            {"U_Nm": u_w, "Tc_Nm": tc, "Jc_kgm2": jc,
             "form": "an undeclared body, the counterweight (angle thc from hanging straight "
                     "down, speed wc, both 0 at the start): Jc dwc/dt = Tc tanh((wl - wc)/0.01) "
                     "- U sin(thc); the roast receives -Tc tanh((wl - wc)/0.01): a pendulum "
                     "dragged round by its clamp's friction, turning with the spit until its "
                     "gravity beats the clamp, then slipping"}),),
            free={"R": -0.04, "Bl": 0.03}, note=NOTE_WEIGHT),
        spec("az12", "outside", "fast", False, (outside(
            "speed-module-direction-comparator-hysteresis", {"dirbit": DIRBIT},
            {"h_rad_s": DIRBIT,
             "form": "speed reads s |w|, s the direction comparator's state: +1 from when w "
                     "rises through +h, -1 from when w falls through -h (+1 at the start): the "
                     "speed's magnitude with a direction that turns only beyond +-h; the motor "
                     "itself is not touched"}),),
            free={"k": 0.04, "Jm": -0.03},
            noise={"current": {"white": 0.05, "quant": STAND_STEP}, "speed": {"white": 0.4}},
            note=NOTE_DIRBIT),
        spec("az13", "outside", "slow", True, (outside(
            "spit-speed-from-the-controller-reed-switch", {"reed": REED},
            {"n": n, "delta_rad": delta, "T0_s": t0, "theta0_rad": theta0,
             "form": "load_speed reads (2 pi/n)/(t_k - t_k-1) from the last pulse t_k on, "
                     "signed as the command's direction at t_k (its last nonzero sign), 0 "
                     "when t - t_k > T0 or t_k - t_k-1 > T0; a pulse whenever the roast's angle "
                     "enters a window of +-delta about theta0 + m 2 pi/n (a reed switch and n "
                     "magnets): the period of the last magnet's passing, held; the motor "
                     "itself is not touched"}),),
            free={"R": 0.025, "Jl": 0.04, "Tl": -0.03},
            noise={"current": {"white": 0.012, "pink": 0.006, "quant": LOGGER_STEP},
                   "speed": {"white": 0.3, "quant": TACHO_STEP},
                   "load_speed": {"white": 0.008, "quant": ENCODER_STEP}},
            note=NOTE_REED),
        spec("az14", "outside", "slow", True, (outside(
            "control-box-bus-capacitor-charged-through-body-diodes", {"bus": BUS},
            {"C_F": c, "r_ohm": r, "Vd_V": vd, "Rb_ohm": rb,
             "form": "the current reads i + sign(u) ic, ic = (0.01 V/r) ln(1 + exp((|u| - Vd "
                     "- vc)/0.01 V)), C dvc/dt = ic - vc/Rb, vc = 0 at rest, u the supply's "
                     "output: a capacitor charged through a diode bridge to the peak of |u| "
                     "(less the diodes' drop), bleeding slowly, behind the shunt; the motor "
                     "itself is not touched"}),),
            free={"k": -0.04, "Jh": 0.05, "Bl": -0.03},
            noise={"current": {"white": 0.012, "quant": LOGGER_STEP},
                   "speed": {"white": 0.3, "pink": 0.12},
                   "load_speed": {"white": 0.008, "ar1": [0.005, 0.8], "quant": ENCODER_STEP}},
            note=NOTE_BUS),
    ]


NOTE_WEIGHT = (
    "the stand's logger's record, an even record; the user frees R and Bl (really 4 % lower and "
    "3 % higher than declared); the roaster's counterweight kit (a 1.3 kg weight on a 120 mm "
    "arm, clamped to the spit beside the far fork to balance a lopsided roast) was left on the "
    "spit with its clamp screw barely snug: it hangs straight down at the start, and the spit "
    "drags it round by the clamp's friction until its weight beats the clamp (about 50 degrees "
    "up), then turns under it; a person sees the first 6 V run's current creep up by up to "
    "0.19 A (the motor up to 3.8 rad/s slower) as the counterweight is lifted (it reaches its "
    "slipping angle after about 2.2 s), then 0.18 A more current and the motor 3.7 rad/s "
    "slower (the spit 0.03 rad/s) through the rest of the forward runs and their stop, like a "
    "dry friction; but backwards the current is first 0.10 A smaller, then, as the "
    "counterweight swings through the bottom and up the other side, 0.19 A larger (the motor "
    "up to 3.9 rad/s slower), and after the last stop the motor creeps forwards (up to "
    "0.6 rad/s) under the counterweight left up on the other side; not a dry friction nor an "
    "unbalance: a weight dragged round by friction")
NOTE_DIRBIT = (
    "an even 25 kHz acquisition; the user frees k and Jm (really 4 % higher and 3 % lower than "
    "declared); the stand's speed channel was moved to its new speed module, which takes the "
    "tachogenerator's magnitude and gives it the sign of a direction comparator whose "
    "hysteresis was set to 8 rad/s (for a noisy tachogenerator): the direction turns only once "
    "the speed is beyond +-8 rad/s; the current as declared; a person sees the speed as "
    "declared but through the reversal, where it still reads positive for 2.1 ms "
    "(0.4424-0.4444 s: up to 15.7 rad/s off, the motor at -7.9 rad/s read +7.9), and at the "
    "end, where the rotor, pushed by the roast still swinging on the spit, turns forwards again "
    "at up to 2.6 rad/s while the speed reads it backwards (from 0.588 s); not a gain, an "
    "offset or a delay of the tachogenerator: a sign that lags near zero")
NOTE_REED = (
    "the stand's logger's irregular intervals; the user frees R, Jl and Tl (really 2.5 % "
    "higher, 4 % higher and 3 % lower than declared); the logger's load_speed input was wired "
    "to the spit controller's speed output instead of the stand's encoder: the controller "
    "times 8 magnets on the far fork passing a reed switch and gives 2 pi/8 over the last "
    "period, signed as it drives, held until the next magnet (0 after 1.2 s without one); the "
    "current and the motor's speed as declared; a person sees the roast's speed read 0 through "
    "the first ramp and the first 2.2 s of the 6 V run (the first two magnets pass at 1.19 s "
    "and 2.16 s), then a staircase of held periods (0.81 rad/s for 0.87, 2.72 rad/s for 3.21 "
    "during the climb to 20 V), the last forward value, 3.07 rad/s, held through the stop to "
    "7.09 s (the spit at rest from 6.2 s), 0 until the second magnet backwards (7.93 s), and "
    "-1.50 rad/s held to the end (the spit at rest from 9.4 s); not a gain, an offset or a "
    "delay of the encoder: a speed timed by magnets and held")
NOTE_BUS = (
    "the stand's logger's irregular intervals; the user frees k, Jh and Bl (really 4 % lower, "
    "5 % higher and 3 % lower than declared); the roaster's control box was left connected to "
    "the motor's terminals with its own supply switched off: its H-bridge's body diodes "
    "rectify the motor's terminal voltage into the box's 2200 uF bus capacitor (with its "
    "10 kohm bleeder), behind the stand's shunt, so the shunt also carries the capacitor's "
    "charging current whenever the supply's voltage rises past the capacitor's (plus the "
    "diodes' 1.4 V); the motor itself and the speeds as declared; a person sees the current "
    "read 13.7 mA high through the first ramp (from 0.72 s, as the voltage passes 1.4 V), "
    "0.46 mA high on the 6 V run, 63 mA high through the ramp to 20 V, 1.9 mA high on the "
    "20 V run, and as declared from the stop on (the capacitor, charged to 18.6 V and bleeding "
    "slowly, stays above the later voltages); not a gain, an offset or a delay of the current's "
    "channel, nor a resistance: a charging current that only the supply's rising voltage "
    "draws")


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
    return recordkit.record_times(s, sw.REGIMES, sw.grid, 48, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

def scalar_effects(p: dict[str, float]) -> tuple[tuple[str, dict], ...]:
    """Small catalog effects (label, fx) an imprint is compared with, linearised at the
    record's true null (``p``: its true values, the inertias' steps relative to them)."""
    return (
        ("series-resistance", {"Rser": 1e-3}),
        ("brush-drop", {"Vb": 1e-2}),
        ("coulomb-friction:rotor", {"coul": {"rotor": 1e-5}}),
        ("coulomb-friction:hub", {"coul": {"hub": 1e-3}}),
        ("coulomb-friction:roast", {"coul": {"roast": 1e-3}}),
        ("viscous-friction:rotor", {"visc": {"rotor": 1e-8}}),
        ("viscous-friction:hub", {"visc": {"hub": 1e-4}}),
        ("viscous-friction:roast", {"visc": {"roast": 1e-4}}),
        ("force-offset:rotor", {"offset": {"rotor": 1e-5}}),
        ("force-offset:hub", {"offset": {"hub": 1e-3}}),
        ("force-offset:roast", {"offset": {"roast": 1e-3}}),
        ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-5, 30.0)}}),
        ("stribeck-friction:hub", {"stribeck": {"hub": (1e-3, 0.25)}}),
        ("stribeck-friction:roast", {"stribeck": {"roast": (1e-3, 0.25)}}),
        ("backlash:K", {"gap": 1e-5}),
        ("inductance", {"p": {"L": p["L"] * 1.001}}),
        ("inductor-saturation:5", {"lsat": (5.0, 0.999)}),
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
    ("unbalance:roast", lambda a, b: {"cog": {"roast": [(1, a, b)]}}),
    ("cogging:rotor:14", lambda a, b: {"cog": {"rotor": [(14, a, b)]}}),
    ("cogging:hub:2", lambda a, b: {"cog": {"hub": [(2, a, b)]}}),
    ("cogging:roast:2", lambda a, b: {"cog": {"roast": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:14", lambda a, b: {"emf": [(14, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 10 uN m on the
    rotor (and 1e-7 V s/rad of EMF), 1 mN m on the hub and the roast."""
    return 1e-5 if (":rotor" in label or label.startswith("emf")) else 1e-3


#: the places a torque effect may sit at, each with its gear factor (its speed over the hub's:
#: the rotor turns N times the hub, the roast at the hub's mean speed across the 1:1 spit);
#: rotor-hub is exact (the rigid gear), rotor-roast and hub-roast lie across the spit's
#: compliance
PLACES = {"rotor": N, "hub": 1.0, "roast": 1.0}
#: the same for an inertia (component: (parameter, gear factor)); Jr is the rotor's, the
#: parameter Jm
INERTIAS = {"Jr": ("Jm", N), "Jh": ("Jh", 1.0), "Jl": ("Jl", 1.0)}
#: the places behind the spit
BEYOND = ("roast", "Jl")
#: the catalog's kinds of the armature loop (one place: the loop)
LOOP_KINDS = ("series-resistance", "source-resistance", "brush-drop", "inductance",
              "inductor-saturation", "resistance-drift", "emf-harmonic")
#: an inertia component's body
INERTIA_BODY = {"Jr": "rotor", "Jh": "hub", "Jl": "roast"}


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
    """Motor AW's clean probes at the DECLARED values (Plumbing's field; every record's own
    runs go through ``run``, at its true values)."""
    return sw.simulate(regime, t, fx)


#: the plumbing of this set; each probe's sensor effects are its gain, its offset and its
#: delay; the netlist declares no harmonic term of the catalog's kinds
KIT = LawSeparated(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sw, sim=sim,
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
