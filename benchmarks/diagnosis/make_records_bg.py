"""Generate the blind set ``fresh58`` of the diagnosis benchmark: records bj01-bj14 of motor BG
(a 12 V brushed DC gearmotor driving the three-roller head of a laboratory peristaltic pump on
the maker's test stand: a rigid 50:1 spur gearhead to the hub, turning in its output bearings,
the Oldham coupling's polymer centre disc a torsional compliance to the pump head, the head
meeting the dry friction of its rollers' and its own bearings and the viscous drag of the
silicone tubing the rollers squeeze), some sampled evenly and some UNEVENLY, three of them
giving the diagnosis ONE probe only, and merge their truth into truth.json. The ids have two
letters.

    python benchmarks/diagnosis/make_records_bg.py                # records/bj*.csv + truth.json
    python benchmarks/diagnosis/make_records_bg.py --only bj03,bj12
    python benchmarks/diagnosis/make_records_bg.py --truth-only   # rewrite the bj entries only

As in fresh45 to fresh57, the netlists (motor_bg_fast.yaml, motor_bg_slow.yaml) declare the
motor's parameters as the maker's data give them, and in every record two or three of them are
WRONG by 2-6 % (``FREE``, mixed signs): the record is simulated with the TRUE values of those
parameters (and its effects), and the user frees exactly those parameters (truth's ``free``
and ``declared_error``: {name: {"declared": the netlist's value, "true": the record's}}). The
other parameters are declared exactly. A null record holds only the declared errors.

A catalog effect that is the same thing as moving a freed parameter cannot be told from it (a
series or source resistance or a resistance drift when R is freed; an inertia correction on a
freed inertia -- the hub's inertia is the rotor's through the rigid gearhead --; a viscous
friction when the tubing's drag Bl is freed; a dry friction when the hub's Th or the head's
Tl is freed; a speed sensor's gain when k is freed; the inductance, or its saturation, when L
is freed): no record puts such an effect with its twin freed (``TWINS``, checked). Each
catalog or two-effect record states, per effect, how far its own imprint lies from the freed
parameters' imprints jointly, best-scaled (``free_separation_sigma``; each freed parameter's
column its 1 % step); an outside record's imprint must keep OUTSIDE_LEFT after the catalog's
effects AND the freed parameters jointly (``unexplained_sigma``, alternatives including
``free:<name>``); a marginal record's ``separation_sigma`` compares it with each other catalog
effect with the freed parameters beside it. A two-effect record states, per effect, whether it
tells the effect's LAW from the other catalog kinds at the same place
(``law_separation_sigma``: the record's whole imprint against each neighbour kind there, with
the freed parameters' columns and the record's other effect beside it; ``own_sigma`` with the
effect's own imprint in the neighbour's place, ``without_sigma`` with nothing there). Every
imprint, signature and alternative is computed about the record's TRUE null; a null record's
``signature_sigma`` is its declared errors' (``declared_error_signature_sigma`` on every
record).

Uses simulators_bg.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the command
``u`` [V] that motor_bg_slow.yaml's pwl states). A single-probe record holds that probe's column
only; its signatures, its marginal scaling and its comparisons use that probe alone. Even
records are sampled on the regime's grid k/fs; uneven ones, in the fast regime, on the 20 kHz
grid whose every sample is moved by a random jitter of up to 5-20 % of the interval, and in the
slow regime at a logger's irregular intervals (0.6-1.4 times the mean of 10 ms) with a few
samples dropped. The motor is simulated at the record's very times (``t_eval``), never
interpolated. truth.json is merged under an exclusive lock (recordkit.merge). A catalog or
two-effect record's ``location_sigma`` compares a torque effect on the rotor, the hub or the
head with its equal on each of the other two, an added inertia on Jr, Jh or Jl with its equal
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
import simulators_bg as sg

SPLIT = "fresh58"
MOTOR = "BG"
SEED0 = 58500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_bg_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_bg_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.012, "speed": 0.3},
         "slow": {"current": 0.004, "speed": 0.15, "load_speed": 0.003}}
MARGINAL_SIGMA = 25.0
OUTSIDE_LEFT = 0.2
FREE_SEPARATION = 10.0
FREE_STEP = 0.01
JITTER, DROPS = (0.05, 0.20), (3, 9)
P = sg.MOTOR_BG
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
# suffixes. The gearhead is rigid and lossless: a torque T on the hub is T / 50 on the rotor.
# The head lies behind the Oldham disc's compliance: no exact equal on the hub or the rotor.

def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def stribeck_head(peak: float, ws: float) -> Part:
    """A breakaway peak s exp(-(wl/ws)^2) tanh(wl/0.01) [N m] on the head, ``ws`` [rad/s]
    (behind the Oldham disc: no exact equal on the hub or the rotor; a marginal record scales
    it)."""
    return {"stribeck": {"head": (peak, ws)}}, {
        "effect": "stribeck-friction", "target": "head", "targets": ["head"],
        "parameters": {"T_peak_Nm": peak, "w_stribeck_rad_s": ws,
                       "form": "head takes s exp(-(w/ws)^2) tanh(w/0.01) over its declared "
                               "Tl tanh(w/0.01)"},
        "expected": {"s": peak, "ws": ws}}


def cogging_head(order: int, amp: float, phase: float) -> Part:
    """A torque amp sin(order angle + phase) [N m] on the head, locked to its angle (behind
    the Oldham disc: no exact equal on the hub or the rotor)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"head": [(order, a, b)]}}, {
        "effect": "cogging", "target": "head", "targets": ["head"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"head receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b}}


def series_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] in series with the armature (the supply is stiff: the same as
    a resistance inside the source)."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": LOOP,
        "parameters": {"R_series_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


def source_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] inside the supply (its output lead and its connector)."""
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[regime],
        "targets": [SOURCE[regime]], "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": LOOP,
                         "expected": {"R": r}}]}


def unbalance_rotor(amp: float, phase: float) -> Part:
    """A once-a-turn torque amp sin(th + phase) [N m] on the rotor (accepted as a cogging of
    order 1 on the rotor; at the hub it would be of order 50, no unbalance)."""
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


def coulomb_rotor(c: float) -> Part:
    """An extra dry friction c tanh(w / 0.01) [N m] on the rotor (accepted on the hub at
    c N; a marginal record scales it)."""
    return {"coul": {"rotor": c}}, {
        "effect": "coulomb-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(w/0.01) against the rotor"},
        "expected": {"c": c},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["hub"],
                         "expected": {"c": c * N}}]}


def viscous_rotor(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the rotor (accepted on the hub at
    b N^2)."""
    return {"visc": {"rotor": b}}, {
        "effect": "viscous-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b w against the rotor"},
        "expected": {"b": b},
        "also_accept": [{"effect": "viscous-friction", "targets": ["hub"],
                         "expected": {"b": b * N ** 2}}]}


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad] in the Oldham coupling K."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap,
                       "form": "no disc torque while |twist| < gap/2, Ks (twist -+ gap/2) "
                               "+ Ds w_rel in contact, the damping never pulling"},
        "expected": {"gap": gap}}


outside = recordkit.outside


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None,
         free: dict[str, float] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.declared_spec``)."""
    return recordkit.declared_spec(rid, cls, regime, uneven, parts, noise, note, marginal,
                                   size, probes=probes or sg.PROBES[regime], free=free,
                                   params=P, twins=TWINS, mixed_signs=True)


def run(s: dict[str, Any], fx: dict, t: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """Motor BG's clean probes at the record's times (or ``t``) with its TRUE values."""
    return sg.simulate(s["regime"], times(s) if t is None else t, fx, s["ptrue"])


def declared_run(s: dict[str, Any]) -> dict[str, np.ndarray]:
    """Motor BG's clean probes at the record's times with the DECLARED values, no effect."""
    return sg.simulate(s["regime"], times(s), {})


# ---------------------------------------------------------------------- the records

#: the stand's fast acquisition's current channel: a 12-bit ADC over +-10 A (4.88 mA steps)
STAND_STEP = 20.0 / 4096
#: the stand's data logger's current channel: 16 bits over +-2.5 A (76 uA steps)
LOGGER_STEP = 5.0 / 65536
#: the tachogenerator's speed word: 0.01 rad/s steps
TACHO_STEP = 0.01
#: the head encoder's speed word: 1 mrad/s steps
HEAD_STEP = 0.001
FAST_PLAIN = {"current": {"white": 0.012, "quant": STAND_STEP},
              "speed": {"white": 0.3, "quant": TACHO_STEP}}
SLOW_PLAIN = {"current": {"white": 0.004, "quant": LOGGER_STEP},
              "speed": {"white": 0.15, "quant": TACHO_STEP},
              "load_speed": {"white": 0.003, "quant": HEAD_STEP}}


def fast_noise(**over: dict) -> dict[str, dict]:
    """The stand's fast noise per probe, with the probes in ``over`` replaced."""
    return {p: over.get(p, v) for p, v in FAST_PLAIN.items()}


def slow_noise(**over: dict) -> dict[str, dict]:
    """The logger's noise per probe, with the probes in ``over`` replaced."""
    return {p: over.get(p, v) for p, v in SLOW_PLAIN.items()}


def nulls() -> list[dict[str, Any]]:
    """bj01, bj02: the null records (the declared errors only)."""
    return [
        spec("bj01", "null", "fast", False, free={"R": 0.03, "Jl": -0.04},
             noise=fast_noise(speed={"white": 0.3, "pink": 0.1, "quant": TACHO_STEP}),
             note="an even 20 kHz acquisition of the stand's test program; the user frees R "
                  "and the pump head's inertia Jl (the stand's leads are longer than the "
                  "data sheet's; the head fitted has the lighter moulded rotor): R is really "
                  "3 % higher, Jl 4 % lower; nothing else; 1/f noise on the tachogenerator's "
                  "speed (0.1 rad/s: its ripple filter's drift)"),
        spec("bj02", "null", "slow", True, free={"k": -0.025, "Bl": 0.04, "Ks": 0.035},
             noise=slow_noise(current={"white": 0.004, "ar1": [0.0015, 0.8],
                                       "quant": LOGGER_STEP},
                              speed={"white": 0.15, "pink": 0.04, "quant": TACHO_STEP}),
             note="the stand logger's irregular intervals; the user frees k, the tubing's "
                  "drag Bl and the Oldham disc's stiffness Ks (a motor of the weaker magnet "
                  "batch; a tube of a thicker wall; a new, stiffer disc): k is really 2.5 % "
                  "lower, Bl 4 % higher, Ks 3.5 % higher; nothing else; Gauss-Markov noise "
                  "on the current (1.5 mA, correlation 0.8 over the interval: the shunt "
                  "amplifier's drift) and 1/f noise on the speed (40 mrad/s)"),
    ]


def singles() -> list[dict[str, Any]]:
    """bj03-bj07, bj10: one catalog effect each."""
    return [
        spec("bj03", "catalog", "fast", True, (sensor("current", "offset", 0.03),),
             probes=("current",), noise={"current": {"white": 0.012, "quant": STAND_STEP}},
             free={"L": 0.04, "Tl": -0.03},
             note="a stand acquisition of the current alone (the 12-bit ADC), jittered 20 "
                  "kHz; the current was taken this time from the stand's Hall-effect clamp "
                  "instead of its shunt, zeroed before it had warmed: it reads 30 mA high "
                  "throughout; the user frees L and the head's dry friction Tl (really 4 % "
                  "higher and 3 % lower than declared)"),
        spec("bj04", "catalog", "slow", False, (stribeck_head(0.05, 0.5),),
             marginal=lambda s: (stribeck_head(s, 0.5),), size=0.05, noise=slow_noise(),
             free={"R": -0.03, "Ks": 0.045},
             note="an even record; the tube had lain occluded under the rollers overnight and "
                  "its flattened section sticks to the bed: a breakaway peak on the head "
                  "fading within 0.5 rad/s, scaled to a 25 sigma signature (marginal); the "
                  "user frees R and Ks (really 3 % lower and 4.5 % higher than declared)"),
        spec("bj05", "catalog", "slow", True, (cogging_head(3, 0.03, 0.7),),
             free={"Jm": 0.04, "Bl": -0.03},
             noise=slow_noise(speed={"white": 0.15, "pink": 0.05, "quant": TACHO_STEP}),
             note="the stand logger's irregular intervals; the occlusion bed was set a notch "
                  "tighter than the build sheet's: each of the three rollers pinches the tube "
                  "harder as it enters the bed and is pushed on as it leaves, a torque ripple "
                  "of 30 mN m three times a head turn (order 3 of the head), phase 0.7 rad; "
                  "the user frees Jm and Bl (really 4 % higher and 3 % lower than declared); "
                  "1/f noise on the motor's speed (50 mrad/s)"),
        spec("bj06", "catalog", "fast", True, (series_resistance(0.2, "fast"),),
             free={"k": 0.035, "Th": -0.04},
             noise=fast_noise(current={"white": 0.012, "ar1": [0.006, 0.6],
                                       "quant": STAND_STEP}),
             note="a jittered 20 kHz acquisition; the motor's leads were extended for the "
                  "stand with a crimped splice that was not fully pressed: 0.2 ohm more in "
                  "the armature's loop; the user frees k and Th (really 3.5 % higher and 4 % "
                  "lower than declared); Gauss-Markov noise on the current (6 mA, "
                  "correlation 0.6 over the interval)"),
        spec("bj07", "catalog", "fast", False, (unbalance_rotor(6e-4, -1.2),),
             probes=("speed",), noise={"speed": {"white": 0.3, "quant": TACHO_STEP}},
             free={"R": 0.025, "Jl": -0.035, "Ks": 0.03},
             note="a stand acquisition of the motor's speed alone, even 20 kHz; the motor's "
                  "rear shaft carries the stand's tachogenerator coupling, whose clamp collar "
                  "lost its counter-screw: a once-a-turn torque of 0.6 mN m on the rotor "
                  "(order 1), phase -1.2 rad; the user frees R, Jl and Ks (really 2.5 % "
                  "higher, 3.5 % lower and 3 % higher than declared)"),
        spec("bj10", "catalog", "fast", False, (coulomb_rotor(1e-3),),
             marginal=lambda c: (coulomb_rotor(c),), size=1e-3,
             noise=fast_noise(current={"white": 0.012, "pink": 0.005, "quant": STAND_STEP}),
             free={"L": -0.03, "Bl": 0.04},
             note="an even 20 kHz acquisition; the motor was fitted with the stiffer brush "
                  "springs of the 24 V variant: more dry friction on the rotor, scaled to a "
                  "25 sigma signature (marginal); the user frees L and Bl (really 3 % lower "
                  "and 4 % higher than declared); 1/f noise on the current (5 mA)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """bj08, bj09: two catalog effects at once."""
    return [
        spec("bj08", "two", "fast", True,
             (source_resistance(0.3, "fast"), sensor("speed", "gain", 0.985)),
             free={"Jl": 0.04, "Tl": -0.03, "Ks": -0.035}, noise=fast_noise(),
             note="a jittered 20 kHz acquisition; the stand's supply was replaced for this "
                  "run by a bench supply without remote sensing, on thin leads: 0.3 ohm "
                  "inside the source; and the tachogenerator fitted has the 1.5 % lower "
                  "constant of a later batch (its reading 0.985 of the speed); the user frees "
                  "Jl, Tl and Ks (really 4 % higher, 3 % lower and 3.5 % lower than "
                  "declared)"),
        spec("bj09", "two", "slow", False, (backlash(0.05), viscous_rotor(3e-6)),
             free={"R": 0.03, "Jh": -0.04, "Tl": 0.025},
             noise=slow_noise(speed={"white": 0.15, "ar1": [0.05, 0.7], "quant": TACHO_STEP}),
             note="an even record; the Oldham coupling's acetal disc has worn in its slots: "
                  "a play of 50 mrad (2.9 degree) between the hub and the head; and the "
                  "motor was fitted with a lip seal on its output shaft (a splash-proof "
                  "variant): an extra viscous drag of 3 uN m s/rad on the rotor; the user "
                  "frees R, Jh and Tl (really 3 % higher, 4 % lower and 2.5 % higher than "
                  "declared); Gauss-Markov noise on the motor's speed (50 mrad/s, "
                  "correlation 0.7 over the interval)"),
    ]


#: the seized roller: its extra drag while in the occlusion bed [N m], the bed's half
#: width [rad], the head's angle at the bed's middle for that roller [rad], the gate's
#: smoothing
SEIZED = (0.1, math.pi / 3, 0.5, 0.02)
#: the tachogenerator's burnt bar: the reading's dip, the gate's half width [rad], its centre
#: [rad], its smoothing
TACHO = (0.6, 0.22, 1.0, 0.004)
#: the Oldham drive hub's set screw: the torque it holds and the torque it slides at [N m],
#: the speed over which it changes between them [rad/s], the drive hub's inertia (a part of
#: the declared Jh) [kg m^2]
SLIP = (0.35, 0.28, 0.05, 2e-4)
#: the bench supply's current limit: its setting and where it sags to [A], the time constant
#: of the sag [s], its fold-back [V/A], the rounding of its threshold [A]
CLIMIT = (0.6, 0.38, 8.0, 100.0, 0.003)

NOTE_SEIZED = (
    "the stand logger's irregular intervals; the user frees k and Th (really 3 % lower and "
    "3.5 % higher than declared); one of the head's three rollers has a seized bearing: "
    "while it is in the occlusion bed (a third of each head turn) it skids along the tube "
    "instead of rolling, 0.1 N m more drag on the head; a person sees the current pulse up "
    "once a head turn (by {sz_i} A in the dosing run, 1.6 times a second) and the head's "
    "speed dip with it (by {sz_l} rad/s), a steady drag besides; not an unbalance of the "
    "head, the rollers' occlusion ripple or a dry friction: a drag over one third of each "
    "head turn only")
NOTE_TACHO = (
    "a stand acquisition of the motor's speed alone, even 20 kHz; the user frees R and Jm "
    "(really 3 % higher and 3.5 % lower than declared); one commutator bar of the rear-shaft "
    "tachogenerator is burnt: over 25 degree of each rotor turn its brushes lose the bar and "
    "the reading falls to 0.4 of the speed; a person sees the speed as declared between the "
    "dips and, once a turn, a notch {tc_w} rad/s deep at full speed (80 notches a second), "
    "its width shrinking as the motor speeds up; not a sensor's gain, offset or delay, nor "
    "a cogging or an unbalance: a reading that drops out at one angle of the rotor")
NOTE_SLIP = (
    "the stand logger's irregular intervals; the user frees k and Ks (really 3 % higher and "
    "3.5 % lower than declared); the Oldham coupling's drive-side hub is held on the "
    "gearhead's shaft by a set screw that was tightened on the round of the shaft, not on "
    "its flat: it holds 0.35 N m and slides at 0.28 N m; a person sees the priming run and "
    "the backward run nearly as declared, but in the dosing run, once the load passes the "
    "screw's hold, the hub lets go of the head: the head falls back to {sl_l} rad/s while "
    "the motor runs {sl_w} rad/s faster than declared on {sl_i} A less current, until the stop, where "
    "the screw bites again ({sl_p} rad slipped in all); not a gain of the head's encoder, a "
    "play, a friction or an offset: a torque-limited slip in the coupling's hub")
NOTE_CLIMIT = (
    "an even record; the user frees R and Jl (really 2.5 % lower and 4 % higher than "
    "declared); the stand's supply was a bench supply whose current limit had been left at "
    "0.6 A and whose limit sags as its pass transistor warms (towards 0.38 A, time constant "
    "8 s); in limit its output folds back 100 V per ampere over it; a person sees the "
    "priming run as declared, then the dosing run's current held flat on the falling limit "
    "(up to {cl_i} A below the declared) and the motor slowing through it (down to {cl_w} "
    "rad/s below, the head {cl_l} rad/s), and the backward run clipped too; not a source "
    "resistance or a drift: a supply that will not give more than its sagging limit")


def outside_records() -> list[dict[str, Any]]:
    """bj11-bj14: effects the catalog does not contain."""
    return [
        spec("bj11", "outside", "slow", True, (outside(
            "seized-roller-skidding-on-the-tube", {"seized": SEIZED},
            {"Tp_Nm": SEIZED[0], "half_width_rad": SEIZED[1], "theta0_rad": SEIZED[2],
             "delta": SEIZED[3],
             "form": "the head takes Tp g(thl) tanh(wl/0.01) more against it, g = 1/(1 + "
                     "exp(-(cos(thl - theta0) - cos(half_width))/delta)): a dry drag over "
                     "+-half_width about theta0 of each head turn"}),),
            free={"k": -0.03, "Th": 0.035},
            noise=slow_noise(load_speed={"white": 0.003, "pink": 0.001, "quant": HEAD_STEP}),
            note=NOTE_SEIZED),
        spec("bj12", "outside", "fast", False, (outside(
            "tachogenerator-with-a-burnt-commutator-bar", {"tacho": TACHO},
            {"m": TACHO[0], "half_width_rad": TACHO[1], "theta0_rad": TACHO[2],
             "delta": TACHO[3],
             "form": "speed reads w (1 - m g(th)), g = 1/(1 + exp(-(cos(th - theta0) - "
                     "cos(half_width))/delta)): once a rotor turn, over +-half_width about "
                     "theta0, the reading falls by the fraction m; the motor itself is not "
                     "touched"}),),
            probes=("speed",), free={"R": 0.03, "Jm": -0.035},
            noise={"speed": {"white": 0.3, "quant": TACHO_STEP}}, note=NOTE_TACHO),
        spec("bj13", "outside", "slow", True, (outside(
            "oldham-hub-set-screw-slipping-on-the-gearhead-shaft", {"slip": SLIP},
            {"Ts_Nm": SLIP[0], "Tc_Nm": SLIP[1], "vs_rad_s": SLIP[2], "Jo_kgm2": SLIP[3],
             "form": "the disc's drive hub (inertia Jo, part of Jh) slips on the gearhead's "
                     "shaft: slip angle phi (shaft minus hub), slip speed s, Jo (dw/dt/N - "
                     "ds/dt) = F(s) - Tk, the shaft taking -F(s) in place of -Tk, F(s) = (Tc "
                     "+ (Ts - Tc) exp(-(s/vs)^2)) tanh(s/0.01); the twist th/N - phi - thl, "
                     "Tk = Ks twist + Ds (w/N - s - wl)"}),),
            free={"k": 0.03, "Ks": -0.035},
            noise=slow_noise(speed={"white": 0.15, "ar1": [0.04, 0.75], "quant": TACHO_STEP}),
            note=NOTE_SLIP),
        spec("bj14", "outside", "slow", False, (outside(
            "bench-supply-with-a-sagging-current-limit", {"climit": CLIMIT},
            {"I0_A": CLIMIT[0], "I1_A": CLIMIT[1], "tau_s": CLIMIT[2], "Rf_V_A": CLIMIT[3],
             "eps_A": CLIMIT[4],
             "form": "the supply's output is u - Rf dz(i), dz(i) = eps (ln(1 + exp((i - "
                     "Ilim)/eps)) - ln(1 + exp((-i - Ilim)/eps))), the limit Ilim(t) = I1 + "
                     "(I0 - I1) exp(-t/tau); the record's u column is the command"}),),
            free={"R": -0.025, "Jl": 0.04},
            noise=slow_noise(current={"white": 0.004, "ar1": [0.002, 0.75],
                                      "quant": LOGGER_STEP}),
            note=NOTE_CLIMIT),
    ]


def record_specs() -> list[dict[str, Any]]:
    """The 14 records in id order, each with its seed."""
    out = sorted(nulls() + singles() + pairs() + outside_records(), key=lambda s: s["id"])
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


def times(s: dict[str, Any]) -> np.ndarray:
    """The record's sample times [s] (even, or uneven from its seed), once."""
    return recordkit.record_times(s, sg.REGIMES, sg.grid, 58, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

def scalar_effects(p: dict[str, float]) -> tuple[tuple[str, dict], ...]:
    """Small catalog effects (label, fx) an imprint is compared with, linearised at the
    record's true null (``p``: its true values)."""
    return (
        ("series-resistance", {"Rser": 1e-3}),
        ("brush-drop", {"Vb": 1e-2}),
        ("coulomb-friction:rotor", {"coul": {"rotor": 1e-5}}),
        ("coulomb-friction:hub", {"coul": {"hub": 1e-4}}),
        ("coulomb-friction:head", {"coul": {"head": 1e-4}}),
        ("viscous-friction:rotor", {"visc": {"rotor": 1e-9}}),
        ("viscous-friction:hub", {"visc": {"hub": 1e-5}}),
        ("viscous-friction:head", {"visc": {"head": 1e-5}}),
        ("force-offset:rotor", {"offset": {"rotor": 1e-5}}),
        ("force-offset:hub", {"offset": {"hub": 1e-4}}),
        ("force-offset:head", {"offset": {"head": 1e-4}}),
        ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-5, 10.0)}}),
        ("stribeck-friction:hub", {"stribeck": {"hub": (1e-4, 0.3)}}),
        ("stribeck-friction:head", {"stribeck": {"head": (1e-4, 0.3)}}),
        ("backlash:K", {"gap": 1e-5}),
        ("inductance", {"p": {"L": p["L"] * 1.001}}),
        ("inductor-saturation:3", {"lsat": (3.0, 0.999)}),
        ("inertia:Jr", {"p": {"Jm": p["Jm"] * 1.001}}),
        ("inertia:Jh", {"p": {"Jh": p["Jh"] * 1.001}}),
        ("inertia:Jl", {"p": {"Jl": p["Jl"] * 1.001}}),
        ("resistance-drift:linear", {"alpha": 1e-4}),
        ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
        ("resistance-drift:warmup-2", {"warmup": (1e-3, 2.0)}),
    )


#: angle-locked catalog effects (two columns each, sine and cosine): the rotor's order 10
#: (its 5 slots and 2 poles; its 10 commutator bars for the EMF), the head's order 3 (its
#: three rollers)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:hub", lambda a, b: {"cog": {"hub": [(1, a, b)]}}),
    ("unbalance:head", lambda a, b: {"cog": {"head": [(1, a, b)]}}),
    ("cogging:rotor:10", lambda a, b: {"cog": {"rotor": [(10, a, b)]}}),
    ("cogging:head:3", lambda a, b: {"cog": {"head": [(3, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:10", lambda a, b: {"emf": [(10, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """An angle-locked column's size [N m, or 100 V s/rad for the EMF]."""
    return 1e-5 if (":rotor" in label or label.startswith("emf")) else 1e-4


PLACES = {"rotor": N, "hub": 1.0, "head": 1.0}
INERTIAS = {"Jr": ("Jm", N), "Jh": ("Jh", 1.0), "Jl": ("Jl", 1.0)}
BEYOND = ("head", "Jl")
LOOP_KINDS = ("series-resistance", "source-resistance", "brush-drop", "inductance",
              "inductor-saturation", "resistance-drift", "emf-harmonic")
INERTIA_BODY = {"Jr": "rotor", "Jh": "hub", "Jl": "head"}


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
class PumpKit(recordkit.DeclaredOff):
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
    """Motor BG's clean probes at the DECLARED values (Plumbing's field)."""
    return sg.simulate(regime, t, fx)


KIT = PumpKit(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sg, sim=sim,
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
    base = sg.simulate(s["regime"], t, {}, s["ptrue"], states=True)
    eff = sg.simulate(s["regime"], t, s["fx"], s["ptrue"], states=True)
    di = eff["current"] - base["current"]
    dw = eff["speed"] - base["speed"]
    nums: dict[str, str] = {}
    if "seized" in s["fx"]:
        m = (t > 7.0) & (t < 10.0)
        dl = eff["load_speed"] - base["load_speed"]
        nums = {"sz_i": f"{np.ptp(di[m]):.2g}", "sz_l": f"{np.ptp(dl[m]):.2g}"}
    elif "tacho" in s["fx"]:
        m = t > 0.12
        nums = {"tc_w": f"{np.max(-dw[m & (t < 0.19)]):.0f}"}
    elif "slip" in s["fx"]:
        j = int(np.searchsorted(t, 9.9))
        dl = eff["load_speed"] - base["load_speed"]
        nums = {"sl_l": f"{eff['load_speed'][j]:.2g}", "sl_w": f"{dw[j]:.2g}",
                "sl_i": f"{-di[j]:.2g}", "sl_p": f"{eff['slip_angle'][-1]:.3g}"}
    elif "climit" in s["fx"]:
        dl = eff["load_speed"] - base["load_speed"]
        nums = {"cl_i": f"{-np.min(di):.2g}", "cl_w": f"{-np.min(dw):.0f}",
                "cl_l": f"{-np.min(dl):.2g}"}
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
