"""Generate the blind set ``fresh52`` of the diagnosis benchmark: records bd01-bd14 of motor BA
(a 12 V brushed DC motor driving the drum of a small 140 L electric site cement mixer on the
service bench: a rigid 135:1 spur gearbox and pinion to the drum's girth ring, turning in the
gearbox's output bearings and the pinion's open mesh, the girth ring's six bolted segments and
the drum's tilting yoke a torsional compliance to the drum with its wet concrete, the drum
meeting the dry friction of its trunnion bearings and the viscous drag of the concrete its
blades churn), some sampled evenly and some UNEVENLY, three of them giving the diagnosis ONE
probe only, and merge their truth into truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_ba.py                # records/bd*.csv + truth.json
    python benchmarks/diagnosis/make_records_ba.py --only bd03,bd12
    python benchmarks/diagnosis/make_records_ba.py --truth-only   # rewrite the bd entries only

As in fresh45 to fresh50, the netlists (motor_ba_fast.yaml, motor_ba_slow.yaml) declare the
motor's parameters as the maker's data give them, and in every record two or three of them are
WRONG by 2-6 % (``FREE``: the record's relative errors, mixed signs): the record is simulated
with the TRUE values of those parameters (and the record's effects), and the user frees exactly
those parameters (truth's ``free``, the netlist's parameter names, and ``declared_error``:
{name: {"declared": the netlist's value, "true": the record's}}). The other parameters are
declared exactly. A null record holds only the declared errors (the right answer: nothing new,
the freed parameters fitted).

A catalog effect that is the same thing as moving a freed parameter cannot be told from it (a
series or source resistance, or a resistance drift, when R is freed; an inertia correction on
a freed inertia -- the ring's inertia is the rotor's through the rigid gear --; a viscous
friction when the drum's churning drag Bl is freed; a dry friction when the ring's Th or the
drum's Tl is freed; a speed sensor's gain when k is freed; the inductance when L is freed): no
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
effect's place (a breakaway friction on the ring against the ring's dry or viscous friction,
torque offset or angle-locked torques; a dry friction on the drum against the drum's other
kinds; a sensor's offset or gain against the same probe's other kinds), linearised,
best-scaled, with the freed parameters' columns and the record's OTHER effect (its own imprint
run alone, best-scaled) beside it; ``own_sigma`` is the same fit with the effect's own imprint
in the neighbour's place (what the linear fit leaves of the effects' interaction: the floor),
``without_sigma`` with nothing in its place.

Every imprint, signature and alternative is computed about the record's TRUE null (the true
values, no effect): ``signature_sigma`` is the effect's own; a null record's
``signature_sigma`` is its declared errors' (the true null against the declared one), and
every record's ``declared_error_signature_sigma`` is that.

Uses simulators_ba.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_ba_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the imprints it is compared with are computed on that probe alone. Even
records are sampled on the regime's grid k/fs; uneven ones, in the fast regime, on a 20 kHz
grid whose every sample is moved by a random jitter of up to 5-20 % of the interval, and in
the slow regime at a logger's irregular intervals (0.6-1.4 times the mean of 10 ms) with a
few samples dropped. Each uneven record has its own times (from its seed), and the motor is
simulated at those very times (``t_eval``), never interpolated. truth.json is merged under an
exclusive lock (recordkit.merge). A catalog or two-effect record's ``location_sigma`` covers
every other place its effect has an equal at: a torque effect on the rotor, the ring or the
drum is compared with its equal on each of the other two (across the segments and the yoke
for rotor-drum and ring-drum, through the rigid gear for rotor-ring), an added inertia on Jr,
Jh or Jl with its equal on the other two (``PLACES``, ``INERTIAS``,
recordkit.places_entry). Nobody ran the diagnosis on these records.
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
import simulators_ba as sb

RECORDS = HERE / "records"
SPLIT = "fresh52"
MOTOR = "BA"
SEED0 = 52500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_ba_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_ba_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.15, "speed": 0.4},
         "slow": {"current": 0.05, "speed": 0.3, "load_speed": 0.003}}
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
P = sb.MOTOR_BA
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
# Each returns (fx fragment for simulators_ba, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The drive is rigid and lossless as declared: a torque on
# the body ``ring`` (the girth ring with the pinion and the gearbox's output shaft) is
# 1/N = 1/135 of it on the rotor, and the ring turns at 1/N of the rotor's speed (a dry
# friction c on the rotor is c N on the ring, a viscous friction b on the rotor b N^2 on the
# ring). The drum lies behind the segments' and the yoke's compliance (1:1): an effect on it
# has no exact equal on the ring or the rotor. No effect here changes a parameter a record
# frees.

def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def saturation(ipar: float, ratio: float) -> Part:
    """The armature inductance saturating: La (ratio + (1 - ratio) / (1 + (i / Ipar)^2))."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def viscous_ring(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the ring (accepted on the rotor at
    b / N^2; a marginal record scales it)."""
    return {"visc": {"ring": b}}, {
        "effect": "viscous-friction", "target": "ring", "targets": ["ring"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b wh against the ring"},
        "expected": {"b": b},
        "also_accept": [{"effect": "viscous-friction", "targets": ["rotor"],
                         "expected": {"b": b / N ** 2}}]}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF harmonic w slope sin(order th + phase) [V], voltage only (a marginal record
    scales the slope)."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def cogging_ring(order: int, amp: float, phase: float) -> Part:
    """A torque amp sin(order angle + phase) [N m] on the ring, angle-locked to it (its
    order over the rotor's turn is not whole: no equal on the rotor)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"ring": [(order, a, b)]}}, {
        "effect": "cogging", "target": "ring", "targets": ["ring"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"ring receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b}}


def warmup(rise: float, tau: float) -> Part:
    """The armature circuit's resistance settling: R (1 + rise (1 - exp(-t / tau)))."""
    return {"warmup": (rise, tau)}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + rise*(1 - exp(-t/tau)))", "rise": rise,
                       "tau_s": tau},
        "expected": {"rise": rise, "tau": tau}}


def stribeck_ring(peak: float, ws: float) -> Part:
    """A breakaway peak s exp(-(wh/ws)^2) tanh(wh/0.01) [N m] on the ring, ``ws`` [rad/s]
    (accepted on the rotor at s / N and ws N)."""
    return {"stribeck": {"ring": (peak, ws)}}, {
        "effect": "stribeck-friction", "target": "ring", "targets": ["ring"],
        "parameters": {"T_peak_Nm": peak, "w_stribeck_rad_s": ws,
                       "form": "ring takes s exp(-(w/ws)^2) tanh(w/0.01) over its declared "
                               "Th tanh(w/0.01)"},
        "expected": {"s": peak, "ws": ws},
        "also_accept": [{"effect": "stribeck-friction", "targets": ["rotor"],
                         "expected": {"s": peak / N, "ws": ws * N}}]}


def coulomb_drum(c: float) -> Part:
    """An extra dry friction c tanh(wl / 0.01) [N m] on the drum (behind the segments and
    the yoke: no exact equal on the ring or the rotor)."""
    return {"coul": {"drum": c}}, {
        "effect": "coulomb-friction", "target": "drum", "targets": ["drum"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(wl/0.01) against the drum"},
        "expected": {"c": c}}


outside = recordkit.outside


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None,
         free: dict[str, float] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.declared_spec``): the probes it gives the
    diagnosis (default: all of its regime's) and the declared parameters it frees
    (``free``: name -> relative error of the true value over the declared)."""
    return recordkit.declared_spec(rid, cls, regime, uneven, parts, noise, note, marginal,
                                   size, probes=probes or sb.PROBES[regime], free=free,
                                   params=P, twins=TWINS, mixed_signs=True)


def run(s: dict[str, Any], fx: dict, t: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """Motor BA's clean probes at the record's times (or ``t``) [s] with its TRUE values and
    the effects ``fx``."""
    return sb.simulate(s["regime"], times(s) if t is None else t, fx, s["ptrue"])


def declared_run(s: dict[str, Any]) -> dict[str, np.ndarray]:
    """Motor BA's clean probes at the record's times with the DECLARED values, no effect."""
    return sb.simulate(s["regime"], times(s), {})


# ---------------------------------------------------------------------- the records

#: the bench's fast acquisition's current channel: a 14-bit ADC over +-128 A (15.6 mA steps)
RIG_STEP = 256.0 / 16384
#: the bench's data logger's current channel: 16 bits over +-40 A (1.22 mA steps)
LOGGER_STEP = 80.0 / 65536
#: the tachogenerator's channel: 16 bits over +-500 rad/s (0.0153 rad/s steps)
TACHO_STEP = 1000.0 / 65536
#: the speed word of the magnetic encoder on the drum's trunnion: 0.5 mrad/s steps
ENCODER_STEP = 0.0005


def nulls() -> list[dict[str, Any]]:
    """bd01, bd02: the null records (the declared errors only)."""
    return [
        spec("bd01", "null", "fast", False, free={"R": 0.035, "Jl": -0.04},
             noise={"current": {"white": 0.15, "ar1": [0.08, 0.9], "quant": RIG_STEP},
                    "speed": {"white": 0.4, "quant": TACHO_STEP}},
             note="an even 20 kHz acquisition of the service bench's test program; the user "
                  "frees the armature circuit's resistance (the bench's motor leads are "
                  "longer than the mixer's own) and the drum's inertia (the manual's test "
                  "batch is a 100 L one; this batch was mixed a little short): R is really "
                  "3.5 % higher, Jl 4 % lower; nothing else; the current with Gauss-Markov "
                  "noise (80 mA, correlation 0.9 over the interval: the shunt amplifier's "
                  "chopper ripple, smeared) on white noise, in the 14-bit ADC's 15.6 mA "
                  "steps; the tachogenerator's speed in 0.0153 rad/s steps"),
        spec("bd02", "null", "slow", True, probes=("current",),
             free={"k": -0.03, "Tl": 0.045, "Ks": 0.05},
             noise={"current": {"white": 0.05, "pink": 0.02, "quant": LOGGER_STEP}},
             note="the bench logger's record of the supply's current alone, at its irregular "
                  "intervals; the user frees k, the drum's trunnion friction Tl and the "
                  "segments' and yoke's stiffness Ks (a motor from a later magnet batch; "
                  "trunnion bearings re-packed with a stiffer grease; the yoke's arms of a "
                  "heavier section on this mixer's frame): k is really 3 % lower, Tl 4.5 % "
                  "higher, Ks 5 % higher; nothing else; 1/f noise (20 mA, the shunt "
                  "amplifier's drift) on white noise, in the logger's 1.22 mA steps"),
    ]


def singles() -> list[dict[str, Any]]:
    """bd03-bd07, bd10: one catalog effect each."""
    return [
        spec("bd03", "catalog", "fast", True, (saturation(35.0, 0.6),), probes=("current",),
             noise={"current": {"white": 0.15, "quant": RIG_STEP}},
             free={"k": 0.03, "Jh": -0.04},
             note="a bench acquisition of the current alone (the 14-bit ADC), jittered "
                  "20 kHz; the motor was rewound by a service shop with a thinner stator "
                  "yoke's laminations: the armature's inductance saturates with the current, "
                  "La (0.6 + 0.4/(1 + (i/35 A)^2)); the user frees k and the ring's inertia "
                  "Jh (really 3 % higher and 4 % lower than declared)"),
        spec("bd04", "catalog", "slow", False, (viscous_ring(2.0),),
             marginal=lambda b: (viscous_ring(b),), size=2.0,
             free={"Jm": 0.03, "Tl": -0.04},
             note="an even record; cement slurry washed into the spur gearbox through its "
                  "breather and emulsified its oil: an extra viscous drag on the gearbox's "
                  "output (the ring), scaled to a 25 sigma signature (marginal); the user "
                  "frees Jm and Tl (really 3 % higher and 4 % lower than declared)"),
        spec("bd05", "catalog", "fast", False, (emf_harmonic(2, 5e-4, 0.9),),
             marginal=lambda s: (emf_harmonic(2, s, 0.9),), size=5e-4,
             noise={"current": {"white": 0.15, "quant": RIG_STEP},
                    "speed": {"white": 0.4, "quant": TACHO_STEP}},
             free={"Th": 0.04, "Bl": -0.035},
             note="an even 20 kHz acquisition; on the replacement motor two opposite magnets "
                  "of the four are of another ferrite grade: the EMF swells and dips twice a "
                  "turn of the rotor (order 2), scaled to a 25 sigma signature (marginal), "
                  "phase 0.9 rad; the user frees Th and Bl (really 4 % higher and 3.5 % lower "
                  "than declared)"),
        spec("bd06", "catalog", "slow", True, (cogging_ring(6, 3.0, 0.7),),
             free={"R": 0.025, "Jh": -0.035, "Bl": 0.04},
             noise={"current": {"white": 0.05, "quant": LOGGER_STEP},
                    "speed": {"white": 0.3, "ar1": [0.15, 0.7]},
                    "load_speed": {"white": 0.003, "quant": ENCODER_STEP}},
             note="the bench logger's irregular intervals; the girth ring's six cast segments "
                  "were refitted after a repair with their butt joints each half a tooth's "
                  "pitch out: the pinion rides over a step six times a turn of the ring, a "
                  "torque of 3 N m on the ring, order 6, phase 0.7 rad; the user frees R, Jh "
                  "and Bl (really 2.5 % higher, 3.5 % lower and 4 % higher than declared); "
                  "Gauss-Markov noise on the speed (0.15 rad/s, correlation 0.7 over the mean "
                  "interval: the tachogenerator's ripple)"),
        spec("bd07", "catalog", "slow", False, (warmup(0.1, 4.0),),
             free={"k": -0.025, "Jl": 0.035},
             noise={"current": {"white": 0.05, "quant": LOGGER_STEP},
                    "speed": {"white": 0.3, "quant": TACHO_STEP},
                    "load_speed": {"white": 0.003, "pink": 0.0015, "quant": ENCODER_STEP}},
             note="an even record; the commutator had just been cleaned with a stone: the "
                  "brushes' contact film builds up again as the motor runs, the armature "
                  "circuit's resistance rising by 10 % with a time constant of 4 s; the user "
                  "frees k and Jl (really 2.5 % lower and 3.5 % higher than declared); 1/f "
                  "noise on the drum's speed (1.5 mrad/s: the encoder's magnet on its "
                  "trunnion's end)"),
        spec("bd10", "catalog", "fast", True, (sensor("speed", "delay", 0.004),),
             probes=("speed",), noise={"speed": {"white": 0.4, "quant": TACHO_STEP}},
             free={"R": 0.03, "Jl": -0.03, "Tl": 0.04},
             note="a bench acquisition of the speed alone, jittered 20 kHz; the "
                  "tachogenerator's channel was fed through the bench's spare isolation "
                  "amplifier, whose output filter lags the speed by 4 ms; the user frees R, "
                  "Jl and Tl (really 3 % higher, 3 % lower and 4 % higher than declared)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """bd08, bd09: two catalog effects at once."""
    return [
        spec("bd08", "two", "fast", True,
             (stribeck_ring(8.0, 0.12), sensor("current", "offset", 0.6)),
             free={"R": -0.03, "Jm": 0.04, "Ks": 0.03},
             noise={"current": {"white": 0.15, "quant": RIG_STEP},
                    "speed": {"white": 0.4, "quant": TACHO_STEP}},
             note="a jittered 20 kHz acquisition; slurry dried in the gearbox's output seal: "
                  "the ring breaks away from rest with a peak of 8 N m over its declared dry "
                  "friction, fading by about 0.12 rad/s; and the shunt amplifier's zero was "
                  "trimmed with the bench's fan running on the same supply: the current reads "
                  "0.6 A high; the user frees R, Jm and Ks (really 3 % lower, 4 % higher and "
                  "3 % higher than declared)"),
        spec("bd09", "two", "slow", False,
             (coulomb_drum(5.0), sensor("load_speed", "gain", 1.0417)),
             free={"R": 0.04, "Jh": -0.03, "Bl": -0.025},
             note="an even record; the yoke's trunnion bearings were pressure-washed dry of "
                  "their grease: an extra dry friction of 5 N m on the drum; and the drum "
                  "encoder's interface was set up for a girth ring of 216 teeth (the 120 L "
                  "model's) instead of 225: the drum's speed reads 225/216 = 1.0417 times "
                  "too high; the user frees R, Jh and Bl (really 4 % higher, 3 % lower and "
                  "2.5 % lower than declared)"),
    ]


#: the batch heeling over: its gravity torque U [N m], its largest heel angle [rad], the speed
#: scale of its heel wc [rad/s] and its lag [s]
HEEL = (22.0, 0.6, 2.5, 3.0)
#: the brushes' sparking: the extra drop's slope Vs [V] and the onset X0 of |i w| [A rad/s]
ARC = (0.4, 6000.0)
#: discharging backwards: the batch's shares of the drum's Jl, Tl and Bl [1] and the angle
#: [rad] the drum turns backwards for the fill to fall by a factor e
DISCHARGE = (0.75, 0.6, 0.9, 5.0)
#: the motor's series stabilising winding: the flux's relative rise per ampere [1/A]
COMPOUND = 0.003


def outside_records() -> list[dict[str, Any]]:
    """bd11-bd14: effects the catalog does not contain."""
    u0, amax, wc, tau = HEEL
    vs, x0 = ARC
    sj, st, sbb, theta = DISCHARGE
    return [
        spec("bd11", "outside", "slow", False, (outside(
            "wet-batch-heels-over-behind-the-drum-speed", {"heel": HEEL},
            {"U_Nm": u0, "amax_rad": amax, "wc_rad_s": wc, "tau_s": tau,
             "form": "the drum receives -U sin(a), da/dt = (amax tanh(wl/wc) - a)/tau, "
                     "a = 0 at rest: the batch's centre of mass carried up the drum's rising "
                     "side by an angle that follows the drum's speed with a lag"}),),
            free={"Jm": 0.04, "Bl": -0.03}, note=NOTE_HEEL),
        spec("bd12", "outside", "fast", True, (outside(
            "brushes-spark-beyond-a-commutating-limit", {"arc": ARC},
            {"Vs_V": vs, "X0_A_rad_s": x0,
             "form": "the loop takes Vs max(|i w|/X0 - 1, 0) tanh(i/1 mA) more: the brushes "
                     "arc at their trailing edges once the commutating coils' reactance "
                     "voltage, in proportion to |i w|, outruns their contact"}),),
            free={"R": -0.035, "Jl": 0.045},
            noise={"current": {"white": 0.15, "quant": RIG_STEP},
                   "speed": {"white": 0.4}},
            note=NOTE_ARC),
        spec("bd13", "outside", "slow", True, (outside(
            "reversing-drum-discharges-its-batch", {"discharge": DISCHARGE},
            {"sJ": sj, "sT": st, "sB": sbb, "theta_rad": theta,
             "form": "the fill f (1 at the start) falls as df/dt = -f max(-wl, 0)/theta; the "
                     "drum's inertia, trunnion friction and churning drag are Jl (1 - sJ "
                     "(1 - f)), Tl (1 - sT (1 - f)), Bl (1 - sB (1 - f)); the concrete "
                     "leaves at the drum's speed"}),),
            free={"R": 0.03, "Jh": -0.04, "Ks": 0.035},
            noise={"current": {"white": 0.05, "ar1": [0.03, 0.8], "quant": LOGGER_STEP},
                   "speed": {"white": 0.3, "quant": TACHO_STEP},
                   "load_speed": {"white": 0.003, "quant": ENCODER_STEP}},
            note=NOTE_DISCHARGE),
        spec("bd14", "outside", "slow", False, (outside(
            "series-winding-compounds-the-magnet-flux", {"compound": COMPOUND},
            {"c_per_A": COMPOUND,
             "form": "the EMF and the torque take k (1 + c i) in place of k, i signed: a "
                     "series winding on the poles strengthens the magnets' flux with a "
                     "forward current and weakens it with a reverse one"}),),
            free={"Jm": 0.025, "Tl": -0.03, "Ks": 0.04},
            noise={"current": {"white": 0.05, "quant": LOGGER_STEP},
                   "speed": {"white": 0.3, "quant": TACHO_STEP},
                   "load_speed": {"white": 0.003, "pink": 0.001, "quant": ENCODER_STEP}},
            note=NOTE_COMPOUND),
    ]


NOTE_HEEL = (
    "the bench logger's record, an even record; the user frees Jm and Bl (really 4 % higher "
    "and 3 % lower than declared); the test batch was mixed stiff (a low-slump mix, too little "
    "water): the blades carry it up the drum's rising side, and its centre of mass heels over "
    "by an angle that follows the drum's speed with a lag of some 3 s (up to 0.6 rad, the "
    "more the faster the drum turns), its weight pulling back on the drum by up to 22 N m "
    "sin(heel); a person sees the current climb above the declared's from the first ramp, "
    "0.44 A high by 3 s, 0.75 A by 5 s and 1.49 A at the end of the full-speed stretch (8.5 "
    "s), the motor up to 4.8 rad/s and the drum up to 36 mrad/s slow, growing all the while "
    "the speed holds; after the stop the batch is still heeled forwards when the drum starts "
    "backwards and helps it round (the current up to 1.03 A less negative, the motor up to "
    "3.3 rad/s faster backwards on the backward ramp); from about 11.5 s the batch heels the "
    "other way: the current up to 1.02 A more negative by 14.2 s, the motor up to 3.3 rad/s "
    "and the drum up to 24 mrad/s slower backwards; not a dry friction, a viscous drag or an "
    "offset: a load that follows the drum's speed seconds late")
NOTE_ARC = (
    "a jittered 20 kHz acquisition; the user frees R and Jl (really 3.5 % lower and 4.5 % "
    "higher than declared); the motor was rebuilt with a soft, high-resistance brush grade "
    "meant for a smaller motor: at the trailing edges the commutating coils' reactance "
    "voltage (in proportion to the current times the speed) outruns the brushes' contact "
    "above about 6000 A rad/s and they spark, the arcs taking an extra 0.4 V for each "
    "multiple of that beyond it; a person sees nothing for the first 0.11 s, then, from "
    "0.112 s to 0.224 s while the motor runs up fast on a heavy current, the current up to "
    "1.3 A low and the motor up to 4.5 rad/s slow; the motor stays up to 3 rad/s slow through "
    "the drop (the current up to 1.0 A high as the deficit recovers), and sparks again from "
    "0.299 s to 0.327 s as the reversal's braking current meets the still-fast rotor (the "
    "current up to 2.0 A less negative); after that within 0.3 A and 0.9 rad/s; not a "
    "resistance, a brush drop or an inductance: a drop that appears only while the product "
    "of the current and the speed is large")
NOTE_DISCHARGE = (
    "the bench logger's irregular intervals; the user frees R, Jh and Ks (really 3 % higher, "
    "4 % lower and 3.5 % higher than declared); the mixer was logged through a real "
    "discharge: running backwards, the blades' spiral throws the batch out of the mouth into "
    "the barrow, the fill falling by a factor e for every 5 rad the drum turns backwards "
    "(the batch is 75 % of the drum's declared inertia, 60 % of its trunnion friction and "
    "lift, 90 % of its churning drag); a person sees everything as declared through the "
    "forward mixing, the stop and the rest until 9.6 s, then, as the drum starts backwards, "
    "the current falling off less and less negative, 1.9 A above the declared's by 11 s, "
    "3.9 A by 12 s and 6.4 A by 14.2 s (18 % of the batch left), the motor up to 21 rad/s and "
    "the drum up to 0.16 rad/s faster backwards, and the stop from 14.2 s quicker; not a "
    "friction, an inertia or a sensor: a load that fades with the angle the drum has turned "
    "backwards only")
NOTE_COMPOUND = (
    "the bench logger's record, an even record; the user frees Jm, Tl and Ks (really 2.5 % "
    "higher, 3 % lower and 4 % higher than declared); the mixer's later motors carry a "
    "series stabilising winding on their four poles (against the ferrite's demagnetisation "
    "when the drum is started full), which the netlist, written from the older data sheet, "
    "does not hold: the flux rises by 0.3 % per ampere of forward current and falls by as "
    "much with a reverse one; a person sees the motor 2.7 rad/s slow at 6 V (the drum 20 "
    "mrad/s) and 8.9 rad/s slow at 12 V (the drum 66 mrad/s) on a current 0.28 A and 0.75 A "
    "lower, but backwards at -10 V the motor 7.6 rad/s FASTER (the drum 56 mrad/s) on a "
    "current 0.69 A more negative; not a sensor's gain or offset, a resistance or k: a "
    "constant that follows the current's sign and size")


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
    return recordkit.record_times(s, sb.REGIMES, sb.grid, 52, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

def scalar_effects(p: dict[str, float]) -> tuple[tuple[str, dict], ...]:
    """Small catalog effects (label, fx) an imprint is compared with, linearised at the
    record's true null (``p``: its true values, the inertias' steps relative to them)."""
    return (
        ("series-resistance", {"Rser": 1e-4}),
        ("brush-drop", {"Vb": 1e-2}),
        ("coulomb-friction:rotor", {"coul": {"rotor": 1e-5}}),
        ("coulomb-friction:ring", {"coul": {"ring": 1e-3}}),
        ("coulomb-friction:drum", {"coul": {"drum": 1e-3}}),
        ("viscous-friction:rotor", {"visc": {"rotor": 1e-8}}),
        ("viscous-friction:ring", {"visc": {"ring": 1e-4}}),
        ("viscous-friction:drum", {"visc": {"drum": 1e-4}}),
        ("force-offset:rotor", {"offset": {"rotor": 1e-5}}),
        ("force-offset:ring", {"offset": {"ring": 1e-3}}),
        ("force-offset:drum", {"offset": {"drum": 1e-3}}),
        ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-5, 10.0)}}),
        ("stribeck-friction:ring", {"stribeck": {"ring": (1e-3, 0.1)}}),
        ("stribeck-friction:drum", {"stribeck": {"drum": (1e-3, 0.1)}}),
        ("backlash:K", {"gap": 1e-5}),
        ("inductance", {"p": {"L": p["L"] * 1.001}}),
        ("inductor-saturation:40", {"lsat": (40.0, 0.999)}),
        ("inertia:Jr", {"p": {"Jm": p["Jm"] * 1.001}}),
        ("inertia:Jh", {"p": {"Jh": p["Jh"] * 1.001}}),
        ("inertia:Jl", {"p": {"Jl": p["Jl"] * 1.001}}),
        ("resistance-drift:linear", {"alpha": 1e-4}),
        ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
        ("resistance-drift:warmup-2", {"warmup": (1e-3, 2.0)}),
    )


#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder); the
#: rotor's order 28 (its 4 poles against its 14 slots), the ring's order 6 (its six bolted
#: segments), the drum's orders 2 (its two mixing blades) and 4
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:ring", lambda a, b: {"cog": {"ring": [(1, a, b)]}}),
    ("unbalance:drum", lambda a, b: {"cog": {"drum": [(1, a, b)]}}),
    ("cogging:rotor:28", lambda a, b: {"cog": {"rotor": [(28, a, b)]}}),
    ("cogging:ring:6", lambda a, b: {"cog": {"ring": [(6, a, b)]}}),
    ("cogging:drum:2", lambda a, b: {"cog": {"drum": [(2, a, b)]}}),
    ("cogging:drum:4", lambda a, b: {"cog": {"drum": [(4, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:28", lambda a, b: {"emf": [(28, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 10 uN m on the
    rotor (and 1e-7 V s/rad of EMF), 1 mN m on the ring and the drum."""
    return 1e-5 if (":rotor" in label or label.startswith("emf")) else 1e-3


#: the places a torque effect may sit at, each with its gear factor (its speed over the
#: ring's: the rotor turns N times the ring, the drum at the ring's mean speed across the 1:1
#: segments and yoke); rotor-ring is exact (the rigid gear), rotor-drum and ring-drum lie
#: across the compliance
PLACES = {"rotor": N, "ring": 1.0, "drum": 1.0}
#: the same for an inertia (component: (parameter, gear factor)); Jr is the rotor's, the
#: parameter Jm
INERTIAS = {"Jr": ("Jm", N), "Jh": ("Jh", 1.0), "Jl": ("Jl", 1.0)}
#: the places behind the segments and the yoke
BEYOND = ("drum", "Jl")
#: the catalog's kinds of the armature loop (one place: the loop)
LOOP_KINDS = ("series-resistance", "source-resistance", "brush-drop", "inductance",
              "inductor-saturation", "resistance-drift", "emf-harmonic")
#: an inertia component's body
INERTIA_BODY = {"Jr": "rotor", "Jh": "ring", "Jl": "drum"}


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
    """Motor BA's clean probes at the DECLARED values (Plumbing's field; every record's own
    runs go through ``run``, at its true values)."""
    return sb.simulate(regime, t, fx)


#: the plumbing of this set; each probe's sensor effects are its gain, its offset and its
#: delay; the netlist declares no harmonic term of the catalog's kinds
KIT = LawSeparated(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sb, sim=sim,
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
