"""Generate the blind set ``fresh57`` of the diagnosis benchmark: records bi01-bi14 of motor BF
(a 24 V brushed DC gearmotor driving the lower drive roll of a bench three-roll section bender,
a ring roller for tubes and profiles, on the maker's test stand: a rigid 40:1 two-stage spur
gearhead to the hub, turning in its output bearings and lip seal, the 0.6 m cardan shaft
under the table with its rubber-bushed flange a torsional compliance to the drive roll, the
roll meeting the dry friction of its bronze bushes and of the clamped test tube and the viscous
drag of the bushes' grease), some sampled evenly and some UNEVENLY, three of them giving the
diagnosis ONE probe only, and merge their truth into truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_bf.py                # records/bi*.csv + truth.json
    python benchmarks/diagnosis/make_records_bf.py --only bi03,bi12
    python benchmarks/diagnosis/make_records_bf.py --truth-only   # rewrite the bi entries only

As in fresh45 to fresh56, the netlists (motor_bf_fast.yaml, motor_bf_slow.yaml) declare the
motor's parameters as the maker's data give them, and in every record two or three of them are
WRONG by 2-6 % (``FREE``, mixed signs): the record is simulated with the TRUE values of those
parameters (and its effects), and the user frees exactly those parameters (truth's ``free``
and ``declared_error``: {name: {"declared": the netlist's value, "true": the record's}}). The
other parameters are declared exactly. A null record holds only the declared errors.

A catalog effect that is the same thing as moving a freed parameter cannot be told from it (a
series or source resistance or a resistance drift when R is freed; an inertia correction on a
freed inertia -- the hub's inertia is the rotor's through the rigid gearhead --; a viscous
friction when the grease's drag Bl is freed; a dry friction when the hub's Th or the roll's Tl
is freed; a speed sensor's gain when k is freed; the inductance, or its saturation, when L is
freed): no record puts such an effect with its twin freed (``TWINS``, checked). Each catalog or
two-effect record states, per effect, how far its own imprint lies from the freed parameters'
imprints jointly, best-scaled (``free_separation_sigma``; each freed parameter's column its
1 % step); an outside record's imprint must keep OUTSIDE_LEFT after the catalog's effects AND
the freed parameters jointly (``unexplained_sigma``, alternatives including ``free:<name>``);
a marginal record's ``separation_sigma`` compares it with each other catalog effect with the
freed parameters beside it. A two-effect record states, per effect, whether it tells the
effect's LAW from the other catalog kinds at the same place (``law_separation_sigma``: the
record's whole imprint against each neighbour kind there, with the freed parameters' columns
and the record's other effect beside it; ``own_sigma`` with the effect's own imprint in the
neighbour's place, ``without_sigma`` with nothing there). Every imprint, signature and
alternative is computed about the record's TRUE null; a null record's ``signature_sigma`` is
its declared errors' (``declared_error_signature_sigma`` on every record).

Uses simulators_bf.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the command
``u`` [V] that motor_bf_slow.yaml's pwl states). A single-probe record holds that probe's column
only; its signatures, its marginal scaling and its comparisons use that probe alone. Even
records are sampled on the regime's grid k/fs; uneven ones, in the fast regime, on the 20 kHz
grid whose every sample is moved by a random jitter of up to 5-20 % of the interval, and in the
slow regime at a logger's irregular intervals (0.6-1.4 times the mean of 8 ms) with a few
samples dropped. The motor is simulated at the record's very times (``t_eval``), never
interpolated. truth.json is merged under an exclusive lock (recordkit.merge). A catalog or
two-effect record's ``location_sigma`` compares a torque effect on the rotor, the hub or the
roll with its equal on each of the other two, an added inertia on Jr, Jh or Jl with its equal
on the other two (``PLACES``, ``INERTIAS``). Nobody ran the diagnosis on these records.
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
import simulators_bf as sf

SPLIT = "fresh57"
MOTOR = "BF"
SEED0 = 57500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_bf_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_bf_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.08, "speed": 0.25},
         "slow": {"current": 0.02, "speed": 0.15, "load_speed": 0.004}}
MARGINAL_SIGMA = 25.0
OUTSIDE_LEFT = 0.2
FREE_SEPARATION = 10.0
FREE_STEP = 0.01
JITTER, DROPS = (0.05, 0.20), (3, 9)
P = sf.MOTOR_BF
N = P["N"]
Part = tuple[dict, dict]
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]
TWINS = {
    "R": {("series-resistance", None), ("source-resistance", None),
          ("resistance-drift", None)},
    "L": {("inductance", None), ("inductor-saturation", None)},
    "k": {("sensor-gain", "speed"), ("sensor-gain", "load_speed")},
    "Jm": {("inertia", "Jr"), ("inertia", "Jh")},
    "Jh": {("inertia", "Jr"), ("inertia", "Jh")},
    "Jl": {("inertia", "Jl")},
    "Bl": {("viscous-friction", None)},
    "Th": {("coulomb-friction", None)},
    "Tl": {("coulomb-friction", None)},
    "Ks": set(),
}


# ---------------------------------------------------------------------- catalog effects
# (simulator fragment, truth entry); ``expected`` keyed by the catalog patch's parameter
# suffixes. The gearhead is rigid and lossless: a torque T on the hub is T / 40 on the rotor.
# The roll lies behind the cardan shaft's compliance: no exact equal on the hub or the rotor.

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


def viscous_roll(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the roll (a marginal record scales it)."""
    return {"visc": {"roll": b}}, {
        "effect": "viscous-friction", "target": "roll", "targets": ["roll"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b wl against the roll"},
        "expected": {"b": b}}


def brush_drop(vb: float) -> Part:
    """A brush contact drop Vb tanh(i / 1 mA) [V] in series with the armature."""
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


def warmup(rise: float, tau: float) -> Part:
    """The armature circuit's resistance settling: R (1 + rise (1 - exp(-t / tau)))."""
    return {"warmup": (rise, tau)}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + rise*(1 - exp(-t/tau)))", "rise": rise,
                       "tau_s": tau},
        "expected": {"rise": rise, "tau": tau}}


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


def offset_hub(torque: float) -> Part:
    """A constant torque [N m] the hub receives (its exact equal: torque / N on the rotor; a
    marginal record scales it)."""
    return {"offset": {"hub": torque}}, {
        "effect": "force-offset", "target": "hub", "targets": ["hub"],
        "parameters": {"T_Nm": torque,
                       "form": "the hub receives a constant T (T > 0: turning it forwards)"},
        "expected": {"F": torque},
        "also_accept": [{"effect": "force-offset", "targets": ["rotor"],
                         "expected": {"F": torque / N}}]}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF harmonic w slope sin(order th + phase) [V], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad] in the cardan shaft K."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap,
                       "form": "no shaft torque while |twist| < gap/2, Ks (twist -+ gap/2) "
                               "+ Ds w_rel in contact, the damping never pulling"},
        "expected": {"gap": gap}}


outside = recordkit.outside


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None,
         free: dict[str, float] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.declared_spec``)."""
    return recordkit.declared_spec(rid, cls, regime, uneven, parts, noise, note, marginal,
                                   size, probes=probes or sf.PROBES[regime], free=free,
                                   params=P, twins=TWINS, mixed_signs=True)


def run(s: dict[str, Any], fx: dict, t: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """Motor BF's clean probes at the record's times (or ``t``) with its TRUE values."""
    return sf.simulate(s["regime"], times(s) if t is None else t, fx, s["ptrue"])


def declared_run(s: dict[str, Any]) -> dict[str, np.ndarray]:
    """Motor BF's clean probes at the record's times with the DECLARED values, no effect."""
    return sf.simulate(s["regime"], times(s), {})


# ---------------------------------------------------------------------- the records

#: the stand's fast acquisition's current channel: a 12-bit ADC over +-80 A (39.1 mA steps)
STAND_STEP = 160.0 / 4096
#: the stand's data logger's current channel: 16 bits over +-10 A (0.305 mA steps)
LOGGER_STEP = 20.0 / 65536
#: the motor encoder's speed word: 0.01 rad/s steps
MOTOR_STEP = 0.01
#: the roll encoder's speed word: 1 mrad/s steps
ROLL_STEP = 0.001
SLOW_WHITE = {"current": {"white": 0.02, "quant": LOGGER_STEP},
              "speed": {"white": 0.15, "quant": MOTOR_STEP},
              "load_speed": {"white": 0.004, "quant": ROLL_STEP}}


def slow_noise(**over: dict) -> dict[str, dict]:
    """The logger's noise per probe, with the probes in ``over`` replaced."""
    return {p: over.get(p, v) for p, v in SLOW_WHITE.items()}


def nulls() -> list[dict[str, Any]]:
    """bi01, bi02: the null records (the declared errors only)."""
    return [
        spec("bi01", "null", "slow", False, free={"Jh": 0.04, "Tl": -0.03},
             noise=slow_noise(current={"white": 0.02, "ar1": [0.008, 0.85],
                                       "quant": LOGGER_STEP},
                              load_speed={"white": 0.004, "pink": 0.002, "quant": ROLL_STEP}),
             note="an even record of the stand's test program; the user frees the hub's "
                  "inertia (the stand's gearhead has the heavier cast output wheel) and the "
                  "roll's dry friction (the test tube is of a thinner wall than the build "
                  "sheet's): Jh is really 4 % higher, Tl 3 % lower; nothing else; the current "
                  "with Gauss-Markov noise (8 mA, correlation 0.85 over the interval: the "
                  "shunt amplifier's drift) on white noise, in the logger's 0.31 mA steps; "
                  "1/f noise (2 mrad/s) on the roll's speed"),
        spec("bi02", "null", "fast", True, probes=("speed",),
             free={"R": 0.03, "Ks": -0.045, "Tl": 0.025},
             noise={"speed": {"white": 0.25, "ar1": [0.1, 0.9], "quant": MOTOR_STEP}},
             note="a stand acquisition of the motor's speed alone, jittered 20 kHz; the user "
                  "frees R, the cardan shaft's stiffness Ks and the roll's dry friction Tl "
                  "(longer stand leads; softer replacement bushes in the shaft's flange; a "
                  "tube clamped a little harder): R is really 3 % higher, Ks 4.5 % lower, Tl "
                  "2.5 % higher; nothing else; Gauss-Markov noise on the speed (0.1 rad/s, "
                  "correlation 0.9 over the interval: the encoder's interpolation error)"),
    ]


def singles() -> list[dict[str, Any]]:
    """bi03-bi07, bi10: one catalog effect each."""
    return [
        spec("bi03", "catalog", "fast", True, (saturation(18.0, 0.7),), probes=("current",),
             noise={"current": {"white": 0.08, "quant": STAND_STEP}},
             free={"k": 0.03, "Jl": -0.04},
             note="a stand acquisition of the current alone (the 12-bit ADC), jittered 20 kHz; "
                  "the armature's teeth saturate at the start's and the reversal's currents: "
                  "the inductance falls towards 0.7 of the declared, halfway (of the fall) at "
                  "18 A; the user frees k and the roll's inertia Jl (really 3 % higher and "
                  "4 % lower than declared)"),
        spec("bi04", "catalog", "slow", False, (viscous_roll(0.02),),
             marginal=lambda b: (viscous_roll(b),), size=0.02, noise=slow_noise(),
             free={"R": 0.03, "Jh": -0.04},
             note="an even record; the roll's bushes were regreased with a stiffer winter "
                  "grease: an extra viscous drag on the roll, scaled to a 25 sigma signature "
                  "(marginal); the user frees R and Jh (really 3 % higher and 4 % lower than "
                  "declared)"),
        spec("bi05", "catalog", "slow", True, (brush_drop(0.5),),
             free={"Jm": -0.035, "Tl": 0.03},
             noise=slow_noise(speed={"white": 0.15, "pink": 0.05, "quant": MOTOR_STEP}),
             note="the stand logger's irregular intervals; the motor's brushes are a harder "
                  "electro-graphite grade than the data sheet's: a contact drop of 0.5 V; "
                  "the user frees Jm and Tl (really 3.5 % lower and 3 % higher than "
                  "declared); 1/f noise on the motor's speed (50 mrad/s)"),
        spec("bi06", "catalog", "fast", True, (warmup(0.08, 0.12),),
             free={"k": -0.03, "Th": 0.04},
             noise={"current": {"white": 0.08, "ar1": [0.04, 0.6], "quant": STAND_STEP},
                    "speed": {"white": 0.25, "quant": MOTOR_STEP}},
             note="a jittered 20 kHz acquisition; the stand's leads' crimped lugs warm with "
                  "the start's current: the armature circuit's resistance rises by 8 % with "
                  "a time constant of 0.12 s; the user frees k and Th (really 3 % lower and "
                  "4 % higher than declared); Gauss-Markov noise on the current (40 mA, "
                  "correlation 0.6 over the interval)"),
        spec("bi07", "catalog", "fast", False, (cogging_rotor(14, 0.02, 1.1),),
             probes=("speed",), noise={"speed": {"white": 0.25, "quant": MOTOR_STEP}},
             free={"R": -0.025, "Jl": 0.04, "Ks": 0.03},
             note="a stand acquisition of the motor's speed alone, even 20 kHz; the motor "
                  "fitted for the test has the stronger sintered magnets: a detent torque of "
                  "20 mN m at its 14 slots (order 14 of the rotor), phase 1.1 rad; the user "
                  "frees R, Jl and Ks (really 2.5 % lower, 4 % higher and 3 % higher than "
                  "declared)"),
        spec("bi10", "catalog", "fast", False, (offset_hub(0.05),),
             marginal=lambda f: (offset_hub(f),), size=0.05,
             noise={"current": {"white": 0.08, "pink": 0.03, "quant": STAND_STEP},
                    "speed": {"white": 0.25, "quant": MOTOR_STEP}},
             free={"L": -0.03, "Bl": 0.04},
             note="an even 20 kHz acquisition; the gearhead's output shaft carries the "
                  "bender's manual handwheel, and its spring-loaded counterweight arm was left "
                  "latched against the frame's stop: a constant torque on the hub whichever "
                  "way it turns, scaled to a 25 sigma signature (marginal); the user frees L "
                  "and Bl (really 3 % lower and 4 % higher than declared); 1/f noise on the "
                  "current (30 mA)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """bi08, bi09: two catalog effects at once."""
    return [
        spec("bi08", "two", "fast", True,
             (emf_harmonic(2, 1.2e-3, -0.6), sensor("speed", "delay", 1.5e-4)),
             free={"Jh": 0.03, "Tl": -0.035, "Ks": 0.04},
             noise={"current": {"white": 0.08, "quant": STAND_STEP},
                    "speed": {"white": 0.25, "quant": MOTOR_STEP}},
             note="a jittered 20 kHz acquisition; the motor's two ferrite arcs were glued in "
                  "unevenly: the air gap, and the EMF with it, varies twice a turn (order 2), "
                  "1.2 mV s/rad (about 2 % of k), phase -0.6 rad; and the speed was taken "
                  "from the encoder's frequency-to-speed module, whose filter lags it by "
                  "150 us; the user frees Jh, Tl and Ks (really 3 % higher, 3.5 % lower and "
                  "4 % higher than declared)"),
        spec("bi09", "two", "slow", False,
             (backlash(0.03), sensor("load_speed", "offset", 0.02)),
             free={"R": -0.03, "Jm": 0.04, "Bl": 0.03},
             noise=slow_noise(speed={"white": 0.15, "ar1": [0.05, 0.7], "quant": MOTOR_STEP}),
             note="an even record; the cardan shaft's slip yoke has worn its splines: a play "
                  "of 30 mrad (1.7 degree) in the drive to the roll; and the roll encoder's "
                  "speed module was zeroed while the roll still crept: its reading is 20 "
                  "mrad/s high throughout; the user frees R, Jm and Bl (really 3 % lower, 4 % "
                  "higher and 3 % higher than declared); Gauss-Markov noise on the motor's "
                  "speed (50 mrad/s, correlation 0.7 over the interval)"),
    ]


#: the reversing contactor's pitted reverse contacts: their resistance [ohm] and the
#: command's width over which the contactor's sides change over [V]
PITTED = (0.3, 0.5)
#: the stand PC's update interval of the supply's set voltage [s]
HOLD = 0.1
#: the roll encoder's worn tongue coupling: its play [rad], the time constant it follows
#: the roll with once in contact [s], and the rounding of the contact [rad]
PLAY = (0.12, 0.002, 0.002)
#: the speed module's output stage: its slew limit [rad/s^2] and its small-signal lag [s]
SLEW = (6000.0, 5e-5)


def outside_records() -> list[dict[str, Any]]:
    """bi11-bi14: effects the catalog does not contain."""
    b_p, tau_p, eps_p = PLAY
    return [
        spec("bi11", "outside", "slow", True, (outside(
            "pitted-reverse-contacts-of-the-reversing-contactor", {"pitted": PITTED},
            {"Rp_ohm": PITTED[0], "u0_V": PITTED[1],
             "form": "the armature loop takes Rp i (1 - tanh(v/u0))/2 more, v(t) the supply's "
                     "output: a resistance in the loop only while the command is negative "
                     "(the contactor's reverse side closed)"}),),
            free={"k": -0.035, "Bl": 0.03}, noise=slow_noise(), note=NOTE_PITTED),
        spec("bi12", "outside", "slow", False, (outside(
            "supply-set-voltage-updated-only-every-tenth-of-a-second", {"hold": HOLD},
            {"Th_s": HOLD,
             "form": "the supply's output is v(t) = u(Th floor(t/Th)): the logged command "
                     "held between the stand PC's updates, a staircase through each ramp; "
                     "the record's u column is the command itself"}),),
            free={"R": 0.03, "Jl": -0.045},
            noise=slow_noise(current={"white": 0.02, "ar1": [0.01, 0.8],
                                      "quant": LOGGER_STEP}),
            note=NOTE_HOLD),
        spec("bi13", "outside", "slow", True, (outside(
            "roll-encoder-driven-through-a-worn-tongue-coupling", {"play": PLAY},
            {"b_rad": b_p, "tau_s": tau_p, "eps_rad": eps_p,
             "form": "load_speed reads dphi/dt, the encoder's angle phi following "
                     "dphi/dt = dz(thl - phi)/tau from 0, dz(x) = eps (ln(1 + exp((x - b/2)/"
                     "eps)) - ln(1 + exp((-x - b/2)/eps))): the encoder is dragged along only "
                     "once the play b is taken up; the roll itself is not touched"}),),
            free={"Jh": 0.035, "Tl": -0.03},
            noise=slow_noise(load_speed={"white": 0.004, "ar1": [0.002, 0.75],
                                         "quant": ROLL_STEP}),
            note=NOTE_PLAY),
        spec("bi14", "outside", "fast", False, (outside(
            "speed-module-output-stage-slew-limited", {"slew": SLEW},
            {"S_rad_s2": SLEW[0], "tau_s": SLEW[1],
             "form": "speed reads r, dr/dt = S tanh((w - r)/(S tau)) from 0: the speed "
                     "module's output follows the speed with a lag tau while it changes "
                     "slowly and at the slew rate S at most; the motor itself is not "
                     "touched"}),),
            free={"L": 0.04, "Th": -0.03},
            noise={"current": {"white": 0.08, "quant": STAND_STEP},
                   "speed": {"white": 0.25, "pink": 0.08, "quant": MOTOR_STEP}},
            note=NOTE_SLEW),
    ]


NOTE_PITTED = (
    "the stand logger's irregular intervals; the user frees k and Bl (really 3.5 % lower and "
    "3 % higher than declared); for this run the stand fed the motor through the bender's own "
    "reversing contactor (the supply's magnitude on the contactor's forward or reverse side "
    "by the command's sign), whose reverse contacts are pitted and burnt: 0.3 ohm more in "
    "the loop while the command is negative; a person sees everything as declared forwards "
    "and at rest, and the backward run {pt_w} rad/s slower at the motor ({pt_l} rad/s at "
    "the roll) on the same current; not a series or a source resistance, a brush drop or a "
    "drift: a resistance only in one direction of the command")
NOTE_HOLD = (
    "an even record; the user frees R and Jl (really 3 % higher and 4.5 % lower than "
    "declared); the stand's PC drove the programmable supply over a slow USB-serial link and "
    "updated its set voltage only every 0.1 s, while the logger recorded the program's "
    "intended command: through each ramp the supply's output climbs in steps (0.67 V in the "
    "entry ramp, 1.6 V in the ramp to 24 V, 3.4 V in the stop); a person sees the plateaus as declared, but in "
    "each ramp the current jumping at every step and decaying within the step (up to {hd_i} A "
    "off the declared at the logger's samples) and the motor's speed following a staircase "
    "(up to {hd_w} rad/s off, the roll {hd_l} rad/s); not a delay of a sensor, an inductance "
    "or an inertia: a supply voltage that moves in steps ten times a second")
NOTE_PLAY = (
    "the stand logger's irregular intervals; the user frees Jh and Tl (really 3.5 % higher "
    "and 3 % lower than declared); the roll encoder is driven by a tongue-and-slot coupling "
    "on the roll's shaft end whose slot has worn to a play of 0.12 rad (6.9 degree); the "
    "encoder's own drag keeps it where it was left: a person sees the current and the motor "
    "as declared, the roll's speed reading zero at the start until the roll has turned 0.06 "
    "rad ({p_t0} s), and after the stop reading zero through the first 0.12 rad of the "
    "backward run (until {p_t1} s) while the roll already turns backwards at up to "
    "{p_w} rad/s, then catching up with a jump; not a delay, a gain or an offset of the "
    "speed's reading, nor a play in the drive: a play between the roll and its encoder only")
NOTE_SLEW = (
    "an even 20 kHz acquisition; the user frees L and Th (really 4 % higher and 3 % lower than "
    "declared); the motor's speed was taken from the encoder's frequency-to-speed module, "
    "whose output stage slews at 6000 rad/s^2 at most (a lag of 50 us for small changes): "
    "a person sees the current as declared and the speed's reading falling behind in each "
    "fast change, up to {sl_w} rad/s behind at {sl_t} s, and catching up on each plateau; "
    "not a delay, a gain or an offset of the speed's reading: a reading limited in its rate")


def record_specs() -> list[dict[str, Any]]:
    """The 14 records in id order, each with its seed."""
    out = sorted(nulls() + singles() + pairs() + outside_records(), key=lambda s: s["id"])
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


def times(s: dict[str, Any]) -> np.ndarray:
    """The record's sample times [s] (even, or uneven from its seed), once."""
    return recordkit.record_times(s, sf.REGIMES, sf.grid, 57, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

def scalar_effects(p: dict[str, float]) -> tuple[tuple[str, dict], ...]:
    """Small catalog effects (label, fx) an imprint is compared with, linearised at the
    record's true null (``p``: its true values)."""
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
        ("inductor-saturation:30", {"lsat": (30.0, 0.999)}),
        ("inertia:Jr", {"p": {"Jm": p["Jm"] * 1.001}}),
        ("inertia:Jh", {"p": {"Jh": p["Jh"] * 1.001}}),
        ("inertia:Jl", {"p": {"Jl": p["Jl"] * 1.001}}),
        ("resistance-drift:linear", {"alpha": 1e-4}),
        ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
        ("resistance-drift:warmup-2", {"warmup": (1e-3, 2.0)}),
    )


#: angle-locked catalog effects (two columns each, sine and cosine): the rotor's order 14
#: (its 14 slots), the roll's order 2 (the cardan shaft's two joints)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:hub", lambda a, b: {"cog": {"hub": [(1, a, b)]}}),
    ("unbalance:roll", lambda a, b: {"cog": {"roll": [(1, a, b)]}}),
    ("cogging:rotor:14", lambda a, b: {"cog": {"rotor": [(14, a, b)]}}),
    ("cogging:roll:2", lambda a, b: {"cog": {"roll": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:14", lambda a, b: {"emf": [(14, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """An angle-locked column's size [N m, or 100 V s/rad for the EMF]."""
    return 1e-5 if (":rotor" in label or label.startswith("emf")) else 1e-4


PLACES = {"rotor": N, "hub": 1.0, "roll": 1.0}
INERTIAS = {"Jr": ("Jm", N), "Jh": ("Jh", 1.0), "Jl": ("Jl", 1.0)}
BEYOND = ("roll", "Jl")
LOOP_KINDS = ("series-resistance", "source-resistance", "brush-drop", "inductance",
              "inductor-saturation", "resistance-drift", "emf-harmonic")
INERTIA_BODY = {"Jr": "rotor", "Jh": "hub", "Jl": "roll"}


def place(kind: str, target: str | None) -> str:
    """Where a catalog effect acts: a body, a probe, ``loop`` or K."""
    if kind in LOOP_KINDS:
        return "loop"
    if kind == "inertia":
        return INERTIA_BODY[str(target)]
    return str(target)


def label_place(label: str) -> tuple[str, str]:
    """An alternative's label -> (kind, place)."""
    kind, _, rest = label.partition(":")
    return kind, place(kind, rest.split(":")[0] if rest else None)


@dataclass(frozen=True)
class BenderKit(recordkit.DeclaredOff):
    """recordkit.DeclaredOff, with each effect's own imprint against the freed parameters
    and, for a two-effect record, each effect's law separation."""

    def alone(self, s: dict[str, Any]) -> list[np.ndarray]:
        """Each truth effect's imprint run alone [white sigma], once."""
        if "alone" not in s:
            imp = self.imprints(s)
            s["alone"] = [imp.imprint(s["regime"], self.run(s, frag)) for frag, _ in s["parts"]]
        return s["alone"]

    def free_separation(self, s: dict[str, Any]) -> list[dict[str, Any]]:
        cols = np.column_stack(list(self.freed(s).values()))
        return [{"effect": e["effect"], "target": e["target"], "free": list(s["free"]),
                 "sigma": recordkit.left(y, cols), "imprint_sigma": float(np.linalg.norm(y))}
                for (_, e), y in zip(s["parts"], self.alone(s), strict=True)]

    def law_separation(self, s: dict[str, Any]) -> list[dict[str, Any]]:
        imp = self.imprints(s)
        y = imp.imprint(s["regime"], self.run(s, s["fx"]))
        freed = np.column_stack(list(self.freed(s).values()))
        mine = self.alone(s)
        alts = {**self.alternatives(s), **self.harmonic_alternatives(s)}
        out = []
        for j, (_, e) in enumerate(s["parts"]):
            others = [mine[m] for m in range(len(mine)) if m != j]
            beside = np.column_stack([freed, *others])
            here = place(e["effect"], e["target"])
            same = {e["effect"], *(a["effect"] for a in e.get("also_accept", []))}
            near: dict[str, float] = {}
            for label, cols in alts.items():
                kind, where = label_place(label)
                if where == here and kind not in same:
                    v = recordkit.left(y, np.column_stack([cols, beside]))
                    near[kind] = min(near.get(kind, math.inf), v)
            out.append({
                "effect": e["effect"], "target": e["target"], "place": here,
                "free": list(s["free"]),
                "beside": [x["effect"] for m, (_, x) in enumerate(s["parts"]) if m != j],
                "imprint_sigma": float(np.linalg.norm(y)),
                "own_sigma": recordkit.left(y, np.column_stack([mine[j], beside])),
                "without_sigma": recordkit.left(y, beside),
                "neighbours": near})
        return out

    def make(self, s: dict[str, Any], write: bool) -> dict:
        entry = super().make(s, write)
        if s["class"] == "two":
            entry["law_separation_sigma"] = self.law_separation(s)
        return entry


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor BF's clean probes at the DECLARED values (Plumbing's field)."""
    return sf.simulate(regime, t, fx)


KIT = BenderKit(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sf, sim=sim,
    times=times, scalar_effects=(), harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=harmonic_size, marginal_sigma=MARGINAL_SIGMA, declared=(),
    run=run, declared_run=declared_run, params=P, effects_of=scalar_effects,
    free_step=FREE_STEP, places=PLACES, inertias=INERTIAS, beyond=BEYOND)
imprints = KIT.imprints
scale_marginal = KIT.scale_marginal


def note_numbers(s: dict[str, Any]) -> None:
    """Fill an outside record's note with what its effect does on its own times (the
    record's true values, against its true null)."""
    if s["class"] != "outside" or "{" not in s["note"]:
        return
    t = times(s)
    base, eff = run(s, {}), run(s, s["fx"])
    di = eff["current"] - base["current"]
    dw = eff["speed"] - base["speed"]
    nums: dict[str, str] = {}
    if "pitted" in s["fx"]:
        m = (t >= 12.0) & (t <= 13.5)
        dl = eff["load_speed"] - base["load_speed"]
        nums = {"pt_w": f"{np.mean(np.abs(dw[m])):.2g}", "pt_l": f"{np.mean(np.abs(dl[m])):.2g}"}
    elif "hold" in s["fx"]:
        dl = eff["load_speed"] - base["load_speed"]
        nums = {"hd_i": f"{np.max(np.abs(di)):.2g}", "hd_w": f"{np.max(np.abs(dw)):.2g}",
                "hd_l": f"{np.max(np.abs(dl)):.2g}"}
    elif "play" in s["fx"]:
        ld = eff["load_speed"]
        true = base["load_speed"]
        on = np.flatnonzero((t < 5.0) & (ld > 0.5 * np.maximum(true, 1e-9)) & (true > 0.05))
        back = np.flatnonzero((t > 9.5) & (true < -0.05))
        caught = back[np.flatnonzero(ld[back] < 0.5 * true[back])]
        gone = back[back < (caught[0] if caught.size else back[-1])]
        nums = {"p_t0": f"{t[on[0]]:.2f}" if on.size else "?",
                "p_t1": f"{t[caught[0]]:.2f}" if caught.size else "?",
                "p_w": f"{-np.min(true[gone]):.2f}" if gone.size else "?"}
    elif "slew" in s["fx"]:
        j = int(np.argmax(np.abs(dw)))
        nums = {"sl_w": f"{abs(dw[j]):.0f}", "sl_t": f"{t[j]:.3f}"}
    s["note"] = s["note"].format(**nums)


def check_entry(e: dict[str, Any]) -> None:
    """Report what misses the set's thresholds (outside left, free separation, marginal and
    law separations)."""
    u = e.get("unexplained_sigma")
    if u and u["all_scalar_effects_jointly"] < OUTSIDE_LEFT * u["imprint"]:
        print(f"WARNING {e['id']}: the catalog's effects and the freed parameters jointly "
              f"leave {u['all_scalar_effects_jointly']:.3g} of its {u['imprint']:.3g} sigma")
    for f in e.get("free_separation_sigma", []):
        if f["sigma"] < FREE_SEPARATION:
            print(f"WARNING {e['id']}: {f['effect']} on {f['target']} lies {f['sigma']:.3g} "
                  f"sigma from the freed {', '.join(f['free'])}")
    for kind, v in (e.get("separation_sigma") or {}).items():
        if v < 2.0:
            print(f"WARNING {e['id']}: {kind} lies {v:.3g} sigma from its imprint")
    for f in e.get("law_separation_sigma", []):
        for kind, v in f["neighbours"].items():
            if v < 2.0:
                print(f"WARNING {e['id']}: {f['effect']} on {f['target']} lies {v:.3g} sigma "
                      f"from a {kind} there")


def checked_make(s: dict[str, Any], write: bool) -> dict:
    """``KIT.make``, the note's numbers, the checks, and a line of what it holds."""
    note_numbers(s)
    entry = KIT.make(s, write)
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
          + "; ".join(extra), flush=True)
    return entry


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, checked_make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
