"""Generate the blind set ``fresh45`` of the diagnosis benchmark: records aw01-aw14 of motor AT
(a 24 V brushed DC motor driving the evaporating flask of a laboratory rotary evaporator on the
service bench: a rigid 12:1 spur gear to the drive head's hollow shaft, the rubber collet with
the glass vapour duct a compliance to the flask, the flask meeting the bath water's drag, the
PTFE vapour seal's dry friction and the bath's wave drag), some sampled evenly and some
UNEVENLY, three of them giving the diagnosis ONE probe only, and merge their truth into
truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_at.py                # records/aw*.csv + truth.json
    python benchmarks/diagnosis/make_records_at.py --only aw03,aw12
    python benchmarks/diagnosis/make_records_at.py --truth-only   # rewrite the aw entries only

WHAT IS NEW IN THIS SET: the netlists (motor_at_fast.yaml, motor_at_slow.yaml) declare the
motor's parameters as the maker's data give them, and in every record two or three of them
are WRONG by 2-6 % (``FREE``: the record's relative errors, mixed signs): the record is
simulated with the TRUE values of those parameters (and the record's effects), and the user
frees exactly those parameters (truth's ``free``, the netlist's parameter names, and
``declared_error``: {name: {"declared": the netlist's value, "true": the record's}}). The
other parameters are declared exactly. A null record holds only the declared errors (the
right answer: nothing new, the freed parameters fitted).

A catalog effect that is the same thing as moving a freed parameter cannot be told from it
(a series or source resistance when R is freed, an inertia correction on a freed inertia --
the hub's inertia is the rotor's through the rigid gear --, a viscous friction when the
flask's declared viscous drag Bf is freed, a dry friction when the seal's Tf is freed, a
speed sensor's gain when k is freed): no record puts such an effect with its twin freed
(``TWINS``, checked). Each catalog or two-effect record states, per effect, how far its own
imprint (run alone on the record's times and true values) lies from the freed parameters'
imprints jointly, best-scaled (``free_separation_sigma``; linearised: each freed parameter's
column is its 1 % step); a record below FREE_SEPARATION is reported. An outside record's
imprint must keep OUTSIDE_LEFT after the catalog's effects AND the freed parameters jointly
(``unexplained_sigma``, whose alternatives include the ``free:<name>`` columns).

Every imprint, signature and alternative is computed about the record's TRUE null (the
true values, no effect): ``signature_sigma`` is the effect's own; a null record's
``signature_sigma`` is its declared errors' (the true null against the declared one, as the
held-out n03 and n06 state it), and every record's ``declared_error_signature_sigma`` is that.

Uses simulators_at.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_at_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the imprints it is compared with are computed on that probe alone. Even
records are sampled on the regime's grid k/fs; uneven ones, in the fast regime, on a 20 kHz
grid whose every sample is moved by a random jitter of up to 10-30 % of the interval, and in
the slow regime at a logger's irregular intervals (0.6-1.4 times the mean of 4 ms) with a few
samples dropped. Each uneven record has its own times (from its seed), and the motor is
simulated at those very times (``t_eval``), never interpolated. truth.json is merged under an
exclusive lock (recordkit.merge). A catalog or two-effect record's ``location_sigma`` covers
every other place its effect has an equal at: a torque effect on the rotor, the hub or the
flask is compared with its equal on each of the other two (across the collet for rotor-flask
and hub-flask, through the rigid gear for rotor-hub), an added inertia on Jr, Jh or Jf with
its equal on the other two (``PLACES``, ``INERTIAS``, recordkit.places_entry). Nobody ran the
diagnosis on these records.
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
import simulators_at as sa

RECORDS = HERE / "records"
SPLIT = "fresh45"
MOTOR = "AT"
SEED0 = 45500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_at_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_at_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.03, "speed": 0.4},
         "slow": {"current": 0.015, "speed": 0.3, "load_speed": 0.05}}
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
JITTER, DROPS = (0.10, 0.30), (2, 8)
#: the declared values (the netlists'): what the diagnosis starts from
P = sa.MOTOR_AT
N = P["N"]
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]
#: the parameters a record may free, and the catalog effects (truth label, target) each one
#: is the twin of (never in a record that frees it)
TWINS = {
    "R": {("series-resistance", None), ("source-resistance", None),
          ("resistance-drift", None)},
    "k": {("sensor-gain", "speed"), ("sensor-gain", "load_speed")},
    "Jm": {("inertia", "Jr"), ("inertia", "Jh")},
    "Jf": {("inertia", "Jf")},
    "Bf": {("viscous-friction", None)},
    "Tf": {("coulomb-friction", None)},
}


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_at, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The spur gear is rigid and lossless as declared: a
# torque on the body ``hub`` (the hollow shaft) is 1/N = 1/12 of it on the rotor, and the hub
# turns at 1/N of the rotor's speed (a viscous friction b on the hub is b / N^2 on the rotor).
# The flask lies behind the collet's compliance (1:1): an effect on it has no exact equal on
# the hub or the rotor. No effect here changes a parameter a record frees.

def source_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] inside the supply (its lead and its connector)."""
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[regime],
        "targets": [SOURCE[regime]], "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": LOOP,
                         "expected": {"R": r}}]}


def brush_drop(vb: float) -> Part:
    """A brush contact drop Vb tanh(i / 1 mA) [V] in series with the armature (a marginal
    record scales it)."""
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


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad] in the collet K (the duct loose in a worn
    collet)."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap,
                       "form": "no collet torque while |twist| < gap/2, Ks (twist -+ gap/2) "
                               "+ Ds w_rel in contact, the damping never pulling"},
        "expected": {"gap": gap}}


def stribeck_flask(s: float, ws: float) -> Part:
    """A breakaway peak s exp(-(wf/ws)^2) tanh(wf/0.01) [N m] on the flask, ``ws`` [rad/s]
    (behind the collet)."""
    return {"stribeck": {"flask": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "flask", "targets": ["flask"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "flask takes s exp(-(w/ws)^2) tanh(w/0.01) over its declared "
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


def inertia_flask(dj: float) -> Part:
    """The flask's inertia off by a factor 1 + ``dj`` (a correction of Jf's J, the parameter
    Jf; behind the collet)."""
    return {"p": {"Jf": P["Jf"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jf", "targets": ["Jf"], "correction": True,
        "parameters": {"Jf_true_kgm2": P["Jf"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


outside = recordkit.outside


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None,
         free: dict[str, float] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.declared_spec``): the probes it gives the
    diagnosis (default: all of its regime's) and the declared parameters it frees
    (``free``: name -> relative error of the true value over the declared)."""
    return recordkit.declared_spec(rid, cls, regime, uneven, parts, noise, note, marginal,
                                   size, probes=probes or sa.PROBES[regime], free=free,
                                   params=P, twins=TWINS)


def run(s: dict[str, Any], fx: dict, t: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """Motor AT's clean probes at the record's times (or ``t``) [s] with its TRUE values and
    the effects ``fx``."""
    return sa.simulate(s["regime"], times(s) if t is None else t, fx, s["ptrue"])


def declared_run(s: dict[str, Any]) -> dict[str, np.ndarray]:
    """Motor AT's clean probes at the record's times with the DECLARED values, no effect."""
    return sa.simulate(s["regime"], times(s), {})


# ---------------------------------------------------------------------- the records

#: the bench's shunt amplifier: a 12-bit ADC over +-10 A (4.9 mA steps)
BENCH_STEP = 20.0 / 4096
#: the rotavap controller's current sense: a 12-bit ADC over +-2.5 A (1.2 mA steps)
CONTROLLER_STEP = 5.0 / 4096
#: the motor's encoder's speed report: 0.1 rad/s steps at the rotor
SPEED_STEP = 0.1
#: the controller's flask speed from the duct's slotted ring: 0.01 rad/s steps
FLASK_STEP = 0.01


def nulls() -> list[dict[str, Any]]:
    """aw01, aw02: the null records (the declared errors only)."""
    return [
        spec("aw01", "null", "slow", False, free={"R": 0.04, "Jf": -0.03},
             noise={"current": {"white": 0.008, "pink": 0.006, "quant": CONTROLLER_STEP},
                    "speed": {"white": 0.25, "ar1": [0.15, 0.85], "quant": SPEED_STEP},
                    "load_speed": {"white": 0.04, "quant": FLASK_STEP}},
             note="the rotavap controller's log of the service program, an even record; the "
                  "user frees the armature's resistance (the data sheet's 1.2 Ohm at 20 C; "
                  "the motor is warm) and the flask's inertia (a different flask and fill "
                  "than the manual's): R is really 4 % higher, Jf 3 % lower; nothing else; "
                  "the current with 1/f noise (6 mA: the brushes) on white noise, read by "
                  "the controller's 12-bit ADC (1.2 mA steps); the encoder's speed with "
                  "Gauss-Markov noise (0.15 rad/s, correlation 0.85 over the interval) on "
                  "white noise, in 0.1 rad/s steps; the flask's speed in 0.01 rad/s steps"),
        spec("aw02", "null", "fast", True, probes=("current",),
             free={"k": 0.03, "Jm": -0.05, "Bf": 0.04},
             noise={"current": {"white": 0.025, "ar1": [0.015, 0.7], "quant": BENCH_STEP}},
             note="a bench log of the current alone, a jittered 20 kHz acquisition; the user "
                  "frees the motor constant, the rotor's inertia and the bath's viscous drag "
                  "(a replacement motor of another batch, a bath at another temperature): k "
                  "is really 3 % higher, Jm 5 % lower, Bf 4 % higher; nothing else; "
                  "Gauss-Markov noise (15 mA, correlation 0.7 over the interval) on white "
                  "noise, read by the 12-bit ADC (4.9 mA steps)"),
    ]


def singles() -> list[dict[str, Any]]:
    """aw03-aw07, aw10: one catalog effect each."""
    return [
        spec("aw03", "catalog", "fast", True, (inductance(0.35),),
             free={"R": -0.03, "Jf": 0.04},
             note="the declared armature inductance was measured at 1 kHz with the rotor "
                  "turned to a low-inductance position; the armature has 35 % more "
                  "inductance than declared; the user frees R and Jf (really 3 % lower and "
                  "4 % higher than declared)"),
        spec("aw04", "catalog", "slow", False, (brush_drop(0.05),),
             marginal=lambda v: (brush_drop(v),), size=0.05,
             free={"Jf": -0.035, "Bf": 0.05},
             note="the motor's brushes were replaced with a harder grade: a contact drop "
                  "across the pair whichever the current's direction, scaled to a 25 sigma "
                  "signature (marginal); the user frees Jf and Bf (really 3.5 % lower and 5 % "
                  "higher than declared)"),
        spec("aw05", "catalog", "fast", False, (backlash(0.03),),
             free={"Jm": -0.04, "Tf": 0.05},
             note="the rubber collet has hardened and shrunk with the bath's heat: the duct "
                  "turns 30 mrad (1.7 degrees) freely in it before it takes the flask along; "
                  "the user frees Jm and Tf (really 4 % lower and 5 % higher than declared)"),
        spec("aw06", "catalog", "slow", True, (stribeck_flask(0.1, 2.0),),
             free={"R": 0.03, "k": -0.02, "Jf": 0.05},
             note="the PTFE vapour seal ran dry and glazed: a breakaway of 0.1 N m on the "
                  "flask fading above about 2 rad/s, over the seal's declared friction; the "
                  "user frees R, k and Jf (really 3 % higher, 2 % lower and 5 % higher than "
                  "declared)"),
        spec("aw07", "catalog", "fast", False, (emf_harmonic(1, 4e-4, 0.9),),
             probes=("current",), noise={"current": {"white": 0.025, "quant": BENCH_STEP}},
             free={"R": -0.05, "Bf": 0.04},
             note="a bench log of the current alone (the 12-bit ADC); one of the motor's two "
                  "magnets came unglued and sits askew in the can: the EMF swings by 0.7 % of "
                  "k (0.4 mV s/rad) once a turn of the rotor; the user frees R and Bf (really "
                  "5 % lower and 4 % higher than declared)"),
        spec("aw10", "catalog", "fast", True, (viscous_hub(5e-4),),
             marginal=lambda b: (viscous_hub(b),), size=5e-4, probes=("speed",),
             free={"R": 0.03, "Jm": -0.05},
             note="a bench log of the motor's encoder speed alone; the drive head's hollow "
                  "shaft bearings were regreased with a stiff grease: an extra viscous drag "
                  "on the hub, scaled to a 25 sigma signature (marginal); the user frees R and "
                  "Jm (really 3 % higher and 5 % lower than declared)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """aw08, aw09: two catalog effects at once."""
    return [
        spec("aw08", "two", "slow", True,
             (inertia_flask(0.3), source_resistance(0.4, "slow")),
             free={"k": -0.03, "Bf": 0.05},
             note="the service program ran with the 2 L flask instead of the 1 L one the "
                  "manual states: 30 % more inertia on the flask than declared; and the "
                  "rotavap is fed from a bench supply through a long thin cable: 0.4 Ohm "
                  "inside the source; the user frees k and Bf (really 3 % lower and 5 % "
                  "higher than declared)"),
        spec("aw09", "two", "fast", False,
             (cogging_rotor(12, 5e-3, 0.4), sensor("speed", "offset", 1.2)),
             free={"R": 0.05, "Jf": -0.04, "Tf": 0.03},
             note="the replacement motor has 12 unskewed slots: a cogging of 5 mN m, twelve "
                  "times a turn of the rotor; and the bench's speed channel reads 1.2 rad/s "
                  "high (its converter's zero shifted); the user frees R, Jf and Tf (really "
                  "5 % higher, 4 % lower and 3 % higher than declared)"),
    ]


#: the water's spin-up: its share Jl [kg m^2] of the declared Jf and the wall's viscous
#: coupling c [N m s/rad]
SPINUP = (1.6e-3, 2.5e-3)
#: the vacuum let in: the seal's extra dry friction Tv [N m], the time t0 [s] the pressure
#: is half-way down and the fall's time scale tr [s]
VACUUM = (0.05, 4.2, 0.4)
#: the suppression varistor across the motor's terminals: its current I0 [A] at V0 [V] and
#: its exponent n (odd)
VARISTOR = (0.15, 16.0, 15)
#: the centrifugal governor: its resistor Rg [ohm], its set speed wg [rad/s] and the width
#: dw [rad/s] over which its contacts open
GOVERNOR = (2.5, 230.0, 6.0)


def outside_records() -> list[dict[str, Any]]:
    """aw11-aw14: effects the catalog does not contain."""
    jl, c = SPINUP
    tv, t0, tr = VACUUM
    i0, v0, power = VARISTOR
    rg, wg, dw = GOVERNOR
    return [
        spec("aw11", "outside", "slow", True, (outside(
            "water-in-the-flask-spins-up-behind-the-glass", {"spinup": SPINUP},
            {"Jl_kgm2": jl, "c_Nms_rad": c,
             "form": "the water's share Jl of the declared Jf is a body of its own, dragged "
                     "by the flask's wall: the flask takes -c (wf - wl) (its rigid inertia "
                     "Jf - Jl), Jl dwl/dt = c (wf - wl), wl = 0 at rest"}),),
            free={"R": -0.04, "Bf": 0.03}, note=NOTE_SPINUP),
        spec("aw12", "outside", "fast", False, (outside(
            "suppression-varistor-across-the-motor-terminals", {"varistor": VARISTOR},
            {"I0_A": i0, "V0_V": v0, "n": power,
             "form": "the current (the shunt in the supply's lead) reads i + I0 (u/V0)^n, u "
                     "the supply's output across the varistor; the motor itself is not "
                     "touched (the supply is stiff)"}),),
            free={"k": 0.04, "Jm": -0.03},
            noise={"current": {"white": 0.03, "pink": 0.015, "quant": BENCH_STEP},
                   "speed": {"white": 0.4}},
            note=NOTE_VARISTOR),
        spec("aw13", "outside", "slow", False, (outside(
            "vacuum-draws-the-duct-into-its-seal", {"vacuum": VACUUM},
            {"Tv_Nm": tv, "t0_s": t0, "tr_s": tr,
             "form": "the flask takes an extra dry friction Tv s(t) tanh(wf/0.01), s(t) = "
                     "(1 + tanh((t - t0)/tr))/2: the seal's friction grows as the pressure "
                     "falls"}),),
            free={"R": 0.025, "Jm": 0.04},
            noise={"current": {"white": 0.015, "quant": CONTROLLER_STEP},
                   "speed": {"white": 0.3, "quant": SPEED_STEP},
                   "load_speed": {"white": 0.05, "ar1": [0.03, 0.8], "quant": FLASK_STEP}},
            note=NOTE_VACUUM),
        spec("aw14", "outside", "fast", True, (outside(
            "centrifugal-governor-opens-above-a-speed", {"governor": GOVERNOR},
            {"Rg_ohm": rg, "wg_rad_s": wg, "dw_rad_s": dw,
             "form": "the armature's loop takes Rg i s, s = (1 + tanh((a - wg)/dw))/2, a = "
                     "sqrt(w^2 + (1 rad/s)^2): the governor's resistor switched in as its "
                     "contacts open above wg, in either direction"}),),
            free={"k": -0.04, "Jf": 0.05, "Bf": -0.03},
            noise={"current": {"white": 0.03}, "speed": {"white": 0.4, "pink": 0.2}},
            note=NOTE_GOVERNOR),
    ]


NOTE_SPINUP = (
    "the rotavap controller's log, a logger's uneven times; the user frees R and Bf (really 4 % "
    "lower and 3 % higher than declared); the flask's 0.4 L of water does not turn with the "
    "glass at once: only the wall's boundary layer drags it along, within about 0.6 s; a "
    "person sees every change of the flask's speed start faster than declared and then "
    "labour on while the water catches up: the flask's speed up to 0.47 rad/s, the motor's "
    "up to 3.9 rad/s and the current up to 0.19 A off after the corners (most at the end of "
    "the reversal), next to nothing in the steady runs; not more inertia and not more drag: "
    "an inertia that follows the flask with a lag")
NOTE_VARISTOR = (
    "a bench acquisition of the current (the shunt in the supply's lead, 1/f noise of 15 mA "
    "on white noise) and the motor's encoder speed; the user frees k and Jm (really 4 % "
    "higher and 3 % lower than declared); against the brushes' radio noise the service "
    "shop soldered a disc varistor across the motor's terminals, a part meant for a 12 V "
    "motor: it conducts steeply above about 13 V (0.15 A at 16 V, a tenth of that at "
    "13.5 V, nothing at 10 V); a person sees the current 0.15 A higher on the 16 V run "
    "and the top of the ramp, and as declared everywhere else, the speed as declared "
    "throughout; not a sensor offset nor a gain, and not a load: current that bypasses "
    "the motor, only at a high voltage")
NOTE_VACUUM = (
    "the rotavap controller's log, an even record; the user frees R and Jm (really 2.5 % and "
    "4 % higher than declared); the operator opened the vacuum valve during the 12 V run: as "
    "the pressure falls (half-way at 4.2 s, over about a second), the air pushes the glass "
    "duct into the PTFE vapour seal and the seal's dry friction doubles (50 mN m more on the "
    "flask); a person sees nothing at 6 V nor in the first half of the 12 V run, then the "
    "current 72 mA higher (0.435 A to 0.507 A at 12 V, 0.55 A to 0.63 A at 20 V), the motor "
    "1.7 rad/s and the flask 0.13 rad/s slower for the rest of the record, in the reversal "
    "too, and the stops quicker; not the seal's declared friction off: a friction that "
    "appears during the record")
NOTE_GOVERNOR = (
    "a bench acquisition of the current and the motor's encoder speed (1/f noise of 0.2 "
    "rad/s on white noise); the service shop fitted a replacement motor from a toy maker's "
    "range whose built-in centrifugal governor opens its contacts above 230 rad/s (2200 "
    "rpm) and puts its 2.5 Ohm resistor in series with the armature; a person sees the "
    "ramp's speed bend off above 230 rad/s and the 16 V run end near 258 rad/s instead of "
    "292 rad/s (the flask 21.4 instead of 23.8 rad/s), the current there 0.16 A higher, and "
    "in the drop to 6 V the braking current up to 2.3 A smaller; nothing at 6 V nor in the "
    "reversal (the rotor below 175 rad/s); the user frees k, Jf and Bf (really 4 % lower, "
    "5 % higher and 3 % lower than declared); not a series resistance: one only above a "
    "speed")


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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 45, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

def scalar_effects(p: dict[str, float]) -> tuple[tuple[str, dict], ...]:
    """Small catalog effects (label, fx) an imprint is compared with, linearised at the
    record's true null (``p``: its true values, the inertias' steps relative to them)."""
    return (
        ("series-resistance", {"Rser": 1e-3}),
        ("brush-drop", {"Vb": 1e-2}),
        ("coulomb-friction:rotor", {"coul": {"rotor": 1e-5}}),
        ("coulomb-friction:hub", {"coul": {"hub": 1e-4}}),
        ("coulomb-friction:flask", {"coul": {"flask": 1e-4}}),
        ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
        ("viscous-friction:flask", {"visc": {"flask": 1e-6}}),
        ("force-offset:rotor", {"offset": {"rotor": 1e-5}}),
        ("force-offset:flask", {"offset": {"flask": 1e-4}}),
        ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-5, 20.0)}}),
        ("stribeck-friction:hub", {"stribeck": {"hub": (1e-4, 2.0)}}),
        ("stribeck-friction:flask", {"stribeck": {"flask": (1e-4, 2.0)}}),
        ("backlash:K", {"gap": 1e-5}),
        ("inductance", {"p": {"L": p["L"] * 1.001}}),
        ("inductor-saturation:2", {"lsat": (2.0, 0.999)}),
        ("inertia:Jr", {"p": {"Jm": p["Jm"] * 1.001}}),
        ("inertia:Jh", {"p": {"Jh": p["Jh"] * 1.001}}),
        ("inertia:Jf", {"p": {"Jf": p["Jf"] * 1.001}}),
        ("resistance-drift:linear", {"alpha": 1e-4}),
        ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
        ("resistance-drift:warmup-2", {"warmup": (1e-3, 2.0)}),
    )


#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:hub", lambda a, b: {"cog": {"hub": [(1, a, b)]}}),
    ("unbalance:flask", lambda a, b: {"cog": {"flask": [(1, a, b)]}}),
    ("cogging:rotor:12", lambda a, b: {"cog": {"rotor": [(12, a, b)]}}),
    ("cogging:hub:4", lambda a, b: {"cog": {"hub": [(4, a, b)]}}),
    ("cogging:flask:2", lambda a, b: {"cog": {"flask": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:12", lambda a, b: {"emf": [(12, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 10 uN m on the
    rotor (and 1e-7 V s/rad of EMF), 0.1 mN m on the hub and the flask."""
    return 1e-5 if (":rotor" in label or label.startswith("emf")) else 1e-4


#: the places a torque effect may sit at, each with its gear factor (its speed over the
#: hub's: the rotor turns N times the hub, the flask at the hub's mean speed across the 1:1
#: collet); rotor-hub is exact (the rigid gear), rotor-flask and hub-flask lie across the
#: collet's compliance
PLACES = {"rotor": N, "hub": 1.0, "flask": 1.0}
#: the same for an inertia (component: (parameter, gear factor)); Jr is the rotor's, the
#: parameter Jm
INERTIAS = {"Jr": ("Jm", N), "Jh": ("Jh", 1.0), "Jf": ("Jf", 1.0)}
#: the places behind the collet
BEYOND = ("flask", "Jf")


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AT's clean probes at the DECLARED values (Plumbing's field; every record's own
    runs go through ``run``, at its true values)."""
    return sa.simulate(regime, t, fx)


#: the plumbing of this set; each probe's sensor effects are its gain, its offset and its
#: delay; the netlist declares no harmonic term of the catalog's kinds (the bath's wave drag
#: is a behavioural torque of the declared model)
KIT = recordkit.DeclaredOff(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sa, sim=sim,
    times=times, scalar_effects=(), harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=harmonic_size, marginal_sigma=MARGINAL_SIGMA, declared=(),
    run=run, declared_run=declared_run, params=P, effects_of=scalar_effects,
    free_step=FREE_STEP, places=PLACES, inertias=INERTIAS, beyond=BEYOND)
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def check_entry(e: dict[str, Any]) -> None:
    """Report an outside record that the catalog's effects and the freed parameters jointly
    (linearised) leave less than OUTSIDE_LEFT of its imprint, and a catalog effect nearer
    than FREE_SEPARATION to the freed parameters jointly."""
    u = e.get("unexplained_sigma")
    if u and u["all_scalar_effects_jointly"] < OUTSIDE_LEFT * u["imprint"]:
        print(f"WARNING {e['id']}: the catalog's effects and the freed parameters jointly "
              f"leave {u['all_scalar_effects_jointly']:.3g} of its {u['imprint']:.3g} sigma")
    for f in e.get("free_separation_sigma", []):
        if f["sigma"] < FREE_SEPARATION:
            print(f"WARNING {e['id']}: {f['effect']} on {f['target']} lies {f['sigma']:.3g} "
                  f"sigma from the freed {', '.join(f['free'])}")


def checked_make(s: dict[str, Any], write: bool) -> dict:
    """``make``, its checks, and a line of what it holds."""
    entry = make(s, write)
    check_entry(entry)
    extra = []
    if "free_separation_sigma" in entry:
        extra.append("from the freed " + ", ".join(
            f"{f['effect']} {f['sigma']:.3g} of {f['imprint_sigma']:.3g}"
            for f in entry["free_separation_sigma"]))
    u = entry.get("unexplained_sigma")
    if u:
        extra.append(f"left {u['all_scalar_effects_jointly'] / u['imprint']:.2f} of it")
    dec = ", ".join(f"{k} {v:.3g}" for k, v in entry["declared_error_signature_sigma"].items())
    print(f"   {entry['id']} declared errors {dec}; " + "; ".join(extra))
    return entry


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, checked_make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
