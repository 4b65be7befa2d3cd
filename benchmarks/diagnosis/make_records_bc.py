"""Generate the blind set ``fresh54`` of the diagnosis benchmark: records bf01-bf14 of motor BC
(a 24 V brushed DC gearmotor driving the winch of a theatre's motorised fly-bar hoist on the
maker's test rig: a rigid 48:1 helical gearbox to the grooved wire-rope drum, turning in its
pillow-block bearings with the ropes bending onto it, the four lift lines' stretch over the
head block and the loft blocks a compliance to the test batten, which the counterweight arbor
balances, the batten and the arbor meeting the dry friction of the arbor's guide shoes and of
the blocks and the viscous drag of the sheaves' grease), some sampled evenly and some
UNEVENLY, three of them giving the diagnosis ONE probe only, and merge their truth into
truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_bc.py                # records/bf*.csv + truth.json
    python benchmarks/diagnosis/make_records_bc.py --only bf03,bf12
    python benchmarks/diagnosis/make_records_bc.py --truth-only   # rewrite the bf entries only

As in fresh45 to fresh52, the netlists (motor_bc_fast.yaml, motor_bc_slow.yaml) declare the
motor's parameters as the maker's data give them, and in every record two or three of them are
WRONG by 2-6 % (``FREE``: the record's relative errors, mixed signs): the record is simulated
with the TRUE values of those parameters (and the record's effects), and the user frees exactly
those parameters (truth's ``free``, the netlist's parameter names, and ``declared_error``:
{name: {"declared": the netlist's value, "true": the record's}}). The other parameters are
declared exactly. A null record holds only the declared errors (the right answer: nothing new,
the freed parameters fitted).

A catalog effect that is the same thing as moving a freed parameter cannot be told from it (a
series or source resistance, or a resistance drift, when R is freed; an inertia correction on
a freed inertia -- the drum's inertia is the rotor's through the rigid gearbox --; a viscous
friction when the sheaves' drag Bb is freed; a dry friction when the drum's Td or the
batten's Tb is freed; a speed sensor's gain when k is freed; the inductance when L is freed):
no record puts such an effect with its twin freed (``TWINS``, checked). Each catalog or
two-effect record states, per effect, how far its own imprint (run alone on the record's times
and true values) lies from the freed parameters' imprints jointly, best-scaled
(``free_separation_sigma``; linearised: each freed parameter's column is its 1 % step); a record
below FREE_SEPARATION is reported. An outside record's imprint must keep OUTSIDE_LEFT after the
catalog's effects AND the freed parameters jointly (``unexplained_sigma``, whose alternatives
include the ``free:<name>`` columns). A marginal record's ``separation_sigma`` compares it with
each other catalog effect with the freed parameters beside that effect (as the diagnosis fits
them).

As in fresh47 to fresh52, a two-effect record also states, per effect, whether the record
tells the effect's LAW from the other catalog kinds at the same place
(``law_separation_sigma``): the record's whole imprint against each neighbour kind at the
effect's place (a torque offset on the batten against the batten's dry, viscous or breakaway
friction and its angle-locked torque; a viscous drag on the drum against the drum's other
kinds and its inertia; a resistance in the armature loop against the loop's other kinds; a
sensor's delay against the same probe's gain and offset), linearised, best-scaled, with the
freed parameters' columns and the record's OTHER effect (its own imprint run alone,
best-scaled) beside it; ``own_sigma`` is the same fit with the effect's own imprint in the
neighbour's place (what the linear fit leaves of the effects' interaction: the floor),
``without_sigma`` with nothing in its place.

Every imprint, signature and alternative is computed about the record's TRUE null (the true
values, no effect): ``signature_sigma`` is the effect's own; a null record's
``signature_sigma`` is its declared errors' (the true null against the declared one), and
every record's ``declared_error_signature_sigma`` is that.

Uses simulators_bc.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_bc_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the imprints it is compared with are computed on that probe alone. Even
records are sampled on the regime's grid k/fs; uneven ones, in the fast regime, on the 25 kHz
grid whose every sample is moved by a random jitter of up to 5-20 % of the interval, and in
the slow regime at a logger's irregular intervals (0.6-1.4 times the mean of 10 ms) with a
few samples dropped. Each uneven record has its own times (from its seed), and the motor is
simulated at those very times (``t_eval``), never interpolated. truth.json is merged under an
exclusive lock (recordkit.merge). A catalog or two-effect record's ``location_sigma`` covers
every other place its effect has an equal at: a torque effect on the rotor, the drum or the
batten is compared with its equal on each of the other two (across the ropes for rotor-batten
and drum-batten, through the rigid gearbox for rotor-drum), an added inertia on Jr, Jd or Jb
with its equal on the other two (``PLACES``, ``INERTIAS``, recordkit.places_entry). Nobody ran
the diagnosis on these records.
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
import simulators_bc as sc

RECORDS = HERE / "records"
SPLIT = "fresh54"
MOTOR = "BC"
SEED0 = 54500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_bc_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_bc_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.12, "speed": 0.35},
         "slow": {"current": 0.04, "speed": 0.25, "load_speed": 0.004}}
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
P = sc.MOTOR_BC
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
    "Jm": {("inertia", "Jr"), ("inertia", "Jd")},
    "Jd": {("inertia", "Jr"), ("inertia", "Jd")},
    "Jb": {("inertia", "Jb")},
    "Bb": {("viscous-friction", None)},
    "Td": {("coulomb-friction", None)},
    "Tb": {("coulomb-friction", None)},
    "Ks": set(),
}


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_bc, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearbox is rigid and lossless as declared: a torque
# on the body ``drum`` is 1/N = 1/48 of it on the rotor, and the drum turns at 1/N of the
# rotor's speed (a dry friction c on the rotor is c N on the drum, a viscous friction b on the
# drum b / N^2 on the rotor). The batten lies behind the ropes' compliance (1:1): an effect on
# it has no exact equal on the drum or the rotor. No effect here changes a parameter a record
# frees.

def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def brush_drop(vb: float) -> Part:
    """A brush contact drop Vb tanh(i / 1 mA) [V] in series with the armature."""
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


def series_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] in series with the armature (the supply is stiff: the same as
    a resistance inside the source)."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": LOOP,
        "parameters": {"R_series_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


def unbalance_drum(amp: float, phase: float) -> Part:
    """A once-a-turn torque amp sin(drum angle + phase) [N m] on the drum (no whole order on
    the rotor; accepted as a cogging of order 1 on the drum; a marginal record scales it)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"drum": [(1, a, b)]}}, {
        "effect": "unbalance", "target": "drum", "targets": ["drum"], "order": 1,
        "parameters": {"order": 1, "T_Nm": amp, "phase_rad": phase,
                       "form": "drum receives T sin(1 angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["drum"], "order": 1,
                         "expected": {"a": a, "b": b}}]}


def coulomb_rotor(c: float) -> Part:
    """An extra dry friction c tanh(w / 0.01) [N m] on the rotor (accepted on the drum at
    c N; a marginal record scales it)."""
    return {"coul": {"rotor": c}}, {
        "effect": "coulomb-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(w/0.01) against the rotor"},
        "expected": {"c": c},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["drum"],
                         "expected": {"c": c * N}}]}


def stribeck_batten(peak: float, ws: float) -> Part:
    """A breakaway peak s exp(-(wb/ws)^2) tanh(wb/0.01) [N m] on the batten, ``ws`` [rad/s]
    (behind the ropes: no exact equal on the drum or the rotor)."""
    return {"stribeck": {"batten": (peak, ws)}}, {
        "effect": "stribeck-friction", "target": "batten", "targets": ["batten"],
        "parameters": {"T_peak_Nm": peak, "w_stribeck_rad_s": ws,
                       "form": "batten takes s exp(-(w/ws)^2) tanh(w/0.01) over its declared "
                               "Tb tanh(w/0.01)"},
        "expected": {"s": peak, "ws": ws}}


def inertia_batten(dj: float) -> Part:
    """The batten's inertia off by a factor 1 + ``dj`` (a correction of Jb's J, the parameter
    Jb; behind the ropes)."""
    return {"p": {"Jb": P["Jb"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jb", "targets": ["Jb"], "correction": True,
        "parameters": {"Jb_true_kgm2": P["Jb"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


def offset_batten(torque: float) -> Part:
    """A constant torque ``torque`` [N m] the batten receives (behind the ropes: no exact
    equal on the drum or the rotor)."""
    return {"offset": {"batten": torque}}, {
        "effect": "force-offset", "target": "batten", "targets": ["batten"],
        "parameters": {"T_Nm": torque,
                       "form": "the batten receives a constant T (T > 0: raising it)"},
        "expected": {"F": torque}}


def viscous_drum(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the drum (accepted on the rotor at
    b / N^2)."""
    return {"visc": {"drum": b}}, {
        "effect": "viscous-friction", "target": "drum", "targets": ["drum"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b wd against the drum"},
        "expected": {"b": b},
        "also_accept": [{"effect": "viscous-friction", "targets": ["rotor"],
                         "expected": {"b": b / N ** 2}}]}


outside = recordkit.outside


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None,
         free: dict[str, float] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.declared_spec``): the probes it gives the
    diagnosis (default: all of its regime's) and the declared parameters it frees
    (``free``: name -> relative error of the true value over the declared)."""
    return recordkit.declared_spec(rid, cls, regime, uneven, parts, noise, note, marginal,
                                   size, probes=probes or sc.PROBES[regime], free=free,
                                   params=P, twins=TWINS, mixed_signs=True)


def run(s: dict[str, Any], fx: dict, t: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """Motor BC's clean probes at the record's times (or ``t``) [s] with its TRUE values and
    the effects ``fx``."""
    return sc.simulate(s["regime"], times(s) if t is None else t, fx, s["ptrue"])


def declared_run(s: dict[str, Any]) -> dict[str, np.ndarray]:
    """Motor BC's clean probes at the record's times with the DECLARED values, no effect."""
    return sc.simulate(s["regime"], times(s), {})


# ---------------------------------------------------------------------- the records

#: the rig's fast acquisition's current channel: a 14-bit ADC over +-200 A (24.4 mA steps)
RIG_STEP = 400.0 / 16384
#: the rig's data logger's current channel: 16 bits over +-50 A (1.53 mA steps)
LOGGER_STEP = 100.0 / 65536
#: the tachogenerator's channel: 16 bits over +-600 rad/s (0.0183 rad/s steps)
TACHO_STEP = 1200.0 / 65536
#: the speed word of the encoder on the head block's sheave, over the drum's radius:
#: 0.8 mrad/s steps
SHEAVE_STEP = 0.0008


def nulls() -> list[dict[str, Any]]:
    """bf01, bf02: the null records (the declared errors only)."""
    return [
        spec("bf01", "null", "fast", False, free={"k": -0.03, "Jb": 0.045},
             noise={"current": {"white": 0.12, "ar1": [0.07, 0.85], "quant": RIG_STEP},
                    "speed": {"white": 0.35, "quant": TACHO_STEP}},
             note="an even 25 kHz acquisition of the rig's test program; the user frees the "
                  "motor's constant (a gearmotor from a new magnet supplier) and the batten's "
                  "inertia (the test load and the arbor's weights were made up from the "
                  "rig's own stock, not weighed): k is really 3 % lower, Jb 4.5 % higher; "
                  "nothing else; the current with Gauss-Markov noise (70 mA, correlation "
                  "0.85 over the interval: the shunt amplifier's chopper ripple, smeared) on "
                  "white noise, in the 14-bit ADC's 24.4 mA steps; the tachogenerator's speed "
                  "in 0.0183 rad/s steps"),
        spec("bf02", "null", "slow", True, probes=("speed",),
             free={"R": 0.04, "Tb": -0.035, "Ks": 0.05},
             noise={"speed": {"white": 0.25, "pink": 0.1, "quant": TACHO_STEP}},
             note="the rig logger's record of the tachogenerator alone, at its irregular "
                  "intervals; the user frees R, the batten's dry friction Tb and the ropes' "
                  "stiffness Ks (the rig's motor leads are longer than a theatre's "
                  "installation's; the arbor's guide shoes were new and run in; the rig's "
                  "lift lines are of a stiffer, compacted-strand rope): R is really 4 % "
                  "higher, Tb 3.5 % lower, Ks 5 % higher; nothing else; 1/f noise (0.1 "
                  "rad/s, the tachogenerator's brush noise) on white noise, in 0.0183 rad/s "
                  "steps"),
    ]


def singles() -> list[dict[str, Any]]:
    """bf03-bf07, bf10: one catalog effect each."""
    return [
        spec("bf03", "catalog", "fast", True, (brush_drop(0.9),), probes=("current",),
             noise={"current": {"white": 0.12, "quant": RIG_STEP}},
             free={"Jm": 0.03, "Bb": -0.04},
             note="a rig acquisition of the current alone (the 14-bit ADC), jittered 25 kHz; "
                  "the gearmotor was fitted with a hard electrographitic brush grade for a "
                  "long service life: a contact drop of 0.9 V across the brushes whichever "
                  "way the current flows; the user frees Jm and Bb (really 3 % higher and 4 % "
                  "lower than declared)"),
        spec("bf04", "catalog", "slow", False, (unbalance_drum(6.0, 1.1),),
             marginal=lambda a: (unbalance_drum(a, 1.1),), size=6.0,
             free={"R": -0.03, "Jb": 0.04},
             note="an even record; the drum's four rope-anchor clamps were fitted on one side "
                  "of the drum with their heavy wedge sockets: a once-a-turn gravity torque on "
                  "the drum, phase 1.1 rad, scaled to a 25 sigma signature (marginal); the "
                  "user frees R and Jb (really 3 % lower and 4 % higher than declared)"),
        spec("bf05", "catalog", "fast", False, (coulomb_rotor(0.05),),
             marginal=lambda c: (coulomb_rotor(c),), size=0.05,
             noise={"current": {"white": 0.12, "quant": RIG_STEP},
                    "speed": {"white": 0.35, "quant": TACHO_STEP}},
             free={"Jd": -0.035, "Bb": 0.03},
             note="an even 25 kHz acquisition; the motor's rear shaft seal (fitted for the "
                  "orchestra pit's damp) rubs the shaft: an extra dry friction on the rotor, "
                  "scaled to a 25 sigma signature (marginal); the user frees Jd and Bb "
                  "(really 3.5 % lower and 3 % higher than declared)"),
        spec("bf06", "catalog", "slow", True, (stribeck_batten(14.0, 0.25),),
             free={"k": 0.025, "Jd": -0.04},
             noise={"current": {"white": 0.04, "quant": LOGGER_STEP},
                    "speed": {"white": 0.25, "quant": TACHO_STEP},
                    "load_speed": {"white": 0.004, "ar1": [0.002, 0.8],
                                   "quant": SHEAVE_STEP}},
             note="the rig logger's irregular intervals; the arbor stood overnight with its "
                  "UHMW guide shoes pressed into the T-track's fresh paint: the batten breaks "
                  "away with a peak of 14 N m over its declared dry friction, fading by about "
                  "0.25 rad/s (2 cm/s at the rope); the user frees k and Jd (really 2.5 % "
                  "higher and 4 % lower than declared); Gauss-Markov noise on the batten's "
                  "speed (2 mrad/s, correlation 0.8 over the mean interval: the sheave "
                  "encoder's eccentricity, smeared)"),
        spec("bf07", "catalog", "fast", False, (inertia_batten(0.15),), probes=("speed",),
             noise={"speed": {"white": 0.35, "quant": TACHO_STEP}},
             free={"R": 0.03, "Tb": -0.04},
             note="a rig acquisition of the speed alone, even 25 kHz; the test batten carried "
                  "a lighting bar 78 kg heavier than the build sheet's test load, balanced by "
                  "as much more weight in the arbor: the batten's inertia (the batten, its "
                  "load and the arbor) is 15 % more than declared; the user frees R and Tb "
                  "(really 3 % higher and 4 % lower than declared)"),
        spec("bf10", "catalog", "slow", False, (sensor("current", "gain", 0.965),),
             free={"Jm": -0.03, "Tb": 0.035, "Ks": 0.04},
             noise={"current": {"white": 0.04, "quant": LOGGER_STEP},
                    "speed": {"white": 0.25, "quant": TACHO_STEP},
                    "load_speed": {"white": 0.004, "pink": 0.002, "quant": SHEAVE_STEP}},
             note="an even record; the logger's current channel was set up for a 75 mV shunt "
                  "while the rig's is a 72.4 mV one at the same current: the current reads "
                  "0.965 times the true; the user frees Jm, Tb and Ks (really 3 % lower, "
                  "3.5 % higher and 4 % higher than declared); 1/f noise on the batten's "
                  "speed (2 mrad/s: the sheave encoder's magnet)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """bf08, bf09: two catalog effects at once."""
    return [
        spec("bf08", "two", "fast", True,
             (offset_batten(9.0), sensor("current", "delay", 4e-4)),
             free={"R": -0.025, "Jm": 0.04, "Ks": 0.03},
             noise={"current": {"white": 0.12, "quant": RIG_STEP},
                    "speed": {"white": 0.35, "quant": TACHO_STEP}},
             note="a jittered 25 kHz acquisition; the arbor was loaded 11.5 kg heavy (one "
                  "spare weight left on it): the line set is out of trim, arbor-heavy, the "
                  "batten receiving a constant 9 N m (113 N at the rope) upwards; and the "
                  "current was read through the rig's spare isolation amplifier, whose output "
                  "filter lags it by 0.4 ms; the user frees R, Jm and Ks (really 2.5 % lower, "
                  "4 % higher and 3 % higher than declared)"),
        spec("bf09", "two", "slow", False,
             (viscous_drum(1.5), series_resistance(0.045, "slow")),
             free={"k": -0.035, "Jb": 0.03, "Ks": 0.04},
             note="an even record; the gearbox was filled with an ISO VG 460 oil meant for "
                  "the winches of the fly tower's cold loading gallery: an extra viscous drag "
                  "of 1.5 N m s/rad on the drum (the gearbox's output); and a crimp in the "
                  "rig's motor lead was corroded: 45 mohm more in the armature circuit; the "
                  "user frees k, Jb and Ks (really 3.5 % lower, 3 % higher and 4 % higher "
                  "than declared)"),
    ]


#: the lift lines climbing onto a second layer: the working radius's rise [1] (a 6 mm rope
#: on the 80 mm pitch radius), the drum's angle where they climb [rad] and the climb's width
#: [rad]
LAYER = (0.065, 30.0, 0.6)
#: the holding brake: its coil's resistance [ohm] and inductance [H], its release current and
#: the release's width [A], its torque on the rotor [N m] and the bridge's knee [V]
BRAKE = (48.0, 1.0, 0.12, 0.01, 1.5, 1.0)
#: the shunt's thermoelectric offset at full heat [A], the current of unit heat [A] and the
#: junctions' thermal time constant [s]
THERMO = (0.3, 20.0, 1.0)
#: the new lift lines' bedding-in: the permanent set per unit pull [rad / N m], its creep time
#: [s] and the smoothing of its one-way law [rad]
BEDDING = (0.003, 0.8, 1e-3)


def outside_records() -> list[dict[str, Any]]:
    """bf11-bf14: effects the catalog does not contain."""
    delta, th1, wd = LAYER
    rc, lc, ir, di, tb, ve = BRAKE
    io, i0, tau = THERMO
    cb, taub, eb = BEDDING
    return [
        spec("bf11", "outside", "slow", False, (outside(
            "lift-lines-climb-onto-a-second-layer-on-the-drum", {"layer": LAYER},
            {"delta": delta, "theta1_rad": th1, "width_rad": wd,
             "form": "the drum's working radius is r (1 + delta sig((thd - th1)/wd)), "
                     "sig(x) = 1/(1 + exp(-x)), thd the drum's angle from the start: the "
                     "ropes' stretch is S(thd) - thb with S(thd) = thd + delta wd "
                     "(sp((thd - th1)/wd) - sp(-th1/wd)), sp(x) = ln(1 + exp(x)), its rate "
                     "rho wd_dot - wb with rho = dS/dthd, and the drum takes rho times the "
                     "ropes' pull (the batten the pull itself)"}),),
            free={"Jm": 0.04, "Bb": -0.03}, note=NOTE_LAYER),
        spec("bf12", "outside", "fast", True, (outside(
            "holding-brake-coil-fed-from-the-motor-terminals", {"brake": BRAKE},
            {"Rc_ohm": rc, "Lc_H": lc, "Ir_A": ir, "dI_A": di, "Tb_Nm": tb, "Ve_V": ve,
             "form": "the brake's coil, fed through a bridge rectifier from the motor's "
                     "terminals (the supply's output u): Lc dic/dt = sqrt(u^2 + Ve^2) - Ve "
                     "- Rc ic, ic = 0 at rest; the supply's shunt carries i + tanh(u/Ve) ic; "
                     "the rotor receives -Tb (1 - sig((ic - Ir)/dI)) tanh(w/0.01), "
                     "sig(x) = 1/(1 + exp(-x)): the spring-applied brake holds until its "
                     "coil's current pulls the armature plate off"}),),
            free={"R": 0.03, "Jb": -0.045},
            noise={"current": {"white": 0.12, "quant": RIG_STEP},
                   "speed": {"white": 0.35}},
            note=NOTE_BRAKE),
        spec("bf13", "outside", "slow", True, (outside(
            "shunt-thermoelectric-offset-follows-its-heating", {"thermo": THERMO},
            {"Io_A": io, "I0_A": i0, "tau_s": tau,
             "form": "the current reads i + Io h, dh/dt = ((i/I0)^2 - h)/tau, h = 0 at "
                     "rest: the shunt's manganin-to-copper junctions heat unevenly with its "
                     "loss, a thermoelectric voltage that follows the recent square of the "
                     "current; the motor itself is not touched"}),),
            free={"k": 0.03, "Td": -0.04},
            noise={"current": {"white": 0.04, "ar1": [0.02, 0.8], "quant": LOGGER_STEP},
                   "speed": {"white": 0.25, "quant": TACHO_STEP},
                   "load_speed": {"white": 0.004, "quant": SHEAVE_STEP}},
            note=NOTE_THERMO),
        spec("bf14", "outside", "slow", True, (outside(
            "new-lift-lines-bed-in-under-their-peak-pull", {"bedding": BEDDING},
            {"c_rad_per_Nm": cb, "tau_s": taub, "e_rad": eb,
             "form": "the ropes' pull is Ks (th/N - thb - z) + Ds (w/N - wb), z their "
                     "permanent set (0 at the start) creeping towards c times the pull "
                     "whenever the pull exceeds what set it: dz/dt = e sp((c Tk - z)/e)/tau, "
                     "sp(x) = ln(1 + exp(x)); it never recovers"}),),
            free={"Jd": 0.035, "Tb": -0.03},
            noise={"current": {"white": 0.04, "quant": LOGGER_STEP},
                   "speed": {"white": 0.25, "quant": TACHO_STEP},
                   "load_speed": {"white": 0.004, "pink": 0.0015, "quant": SHEAVE_STEP}},
            note=NOTE_BEDDING),
    ]


NOTE_LAYER = (
    "the rig logger's record, an even record; the user frees Jm and Bb (really 4 % higher "
    "and 3 % lower than declared); the rig was fitted with the short drum of the hoist's "
    "compact version, and the test's travel ran the lift lines out of its grooves: past 30 "
    "rad of the drum's turn from the start (4.8 turns, 2.4 m of the batten's travel) they "
    "climb onto a second layer, the drum's working radius 6.5 % larger; a person sees "
    "everything as declared while raising at trim speed and through the first 1.5 s at full "
    "speed, then from about 7.0 s the batten up to 0.41 rad/s faster on the drum's same "
    "turning and the motor up to 7.1 rad/s slower on a current up to 2.1 A higher (at 7.25 "
    "s), still 4.8 rad/s slow and 1.4 A high when the stop begins at 8.0 s, the stop itself "
    "braking on a current up to 1.4 A more negative; lowering, the batten up to 0.33 rad/s "
    "faster downwards while the motor runs up to 6.5 rad/s slower backwards on a current up "
    "to 1.9 A more negative, until the lines have come off the second layer at about 11.3 s; "
    "as declared after that; not a sensor's gain, an inertia or a friction: a change of the "
    "drum's ratio at one place of its travel")
NOTE_BRAKE = (
    "a jittered 25 kHz acquisition; the user frees R and Jb (really 3 % higher and 4.5 % "
    "lower than declared); the gearmotor came with its spring-applied holding brake (1.5 N m "
    "on the motor's rear shaft, not in the netlist), whose 48 ohm, 1 H coil the rig wired "
    "through a bridge rectifier across the motor's terminals as the hoist's own panel does; "
    "its air gap set tight, the brake lets go once the coil carries 0.12 A (a quarter of its "
    "0.48 A at 24 V) and drops in again below it; a person sees the motor held back from the "
    "start of the ramp (up to 40 rad/s slow at 0.05 s on a current up to 11 A higher), "
    "overshooting once the brake lets go at 0.067 s (up to 27 rad/s fast), then up to 23 "
    "rad/s slow and 7 A high through the rest of the ramp and within 6 rad/s and 2.2 A at "
    "full speed, the current carrying the coil's 0.48 A besides (its sign the supply's); as "
    "the reversal passes through 0 V the brake drops in from 0.287 s to 0.302 s against the "
    "still-fast rotor (the motor up to 37 rad/s slow, the current up to 9.9 A high at 0.30 "
    "s), and at the stop it sets again from 0.445 s (the motor up to 20 rad/s less fast "
    "backwards at the end); not a dry friction or an offset: a brake whose grip follows the "
    "lagging current of a coil fed from the supply's own voltage")
NOTE_THERMO = (
    "the rig logger's irregular intervals; the user frees k and Td (really 3 % higher and 4 % "
    "lower than declared); the rig's current shunt (a manganin shunt with one end bolted to "
    "the supply's busbar and the other hanging on the motor lead's lug) heats unevenly with "
    "its loss: its manganin-to-copper junctions give a thermoelectric voltage that follows "
    "the recent square of the current within about 1 s, 0.3 A of reading at the heat of a "
    "steady 20 A; a person sees the motor and the batten exactly as declared and the current "
    "reading high: by 0.09 A while raising at trim speed, 0.17-0.18 A through the "
    "accelerations, 0.14-0.15 A at full speed, falling off to 0.04 A through the rest, "
    "0.13-0.18 A while lowering, and 0.016 A at the end; high whichever way the current "
    "flows; not an offset, a gain or a resistance: an offset that follows the shunt's "
    "heating")
NOTE_BEDDING = (
    "the rig logger's irregular intervals; the user frees Jd and Tb (really 3.5 % higher and "
    "3 % lower than declared); the rig had just been re-roped with new lift lines, which bed "
    "in (their strands settling onto the core) under their first pulls: a permanent stretch "
    "of 3 mrad of the batten's travel over the drum's radius (0.24 mm at the rope) per N m of "
    "pull, reached within about 0.8 s whenever the pull exceeds what set it, never given "
    "back; a person sees the batten lag as it starts to rise (up to 74 mrad/s slow at 0.88 s; "
    "the motor up to 2.4 rad/s fast on a current 0.71 A lower at 0.61 s) and again as it "
    "speeds up to full speed (the batten up to 56 mrad/s slow, the current up to 0.36 A lower "
    "at 4.6 s and 0.34 A higher at 5.3 s), the lines set by 0.117 rad (9.3 mm at the rope) in "
    "all; as declared from about 6.5 s on, the stop, the lowering and the end included; not a "
    "play, a stiffness or an inertia: a stretch that stays once taken, growing only when the "
    "pull reaches a new peak")


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
    return recordkit.record_times(s, sc.REGIMES, sc.grid, 54, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

def scalar_effects(p: dict[str, float]) -> tuple[tuple[str, dict], ...]:
    """Small catalog effects (label, fx) an imprint is compared with, linearised at the
    record's true null (``p``: its true values, the inertias' steps relative to them)."""
    return (
        ("series-resistance", {"Rser": 1e-4}),
        ("brush-drop", {"Vb": 1e-2}),
        ("coulomb-friction:rotor", {"coul": {"rotor": 1e-5}}),
        ("coulomb-friction:drum", {"coul": {"drum": 1e-3}}),
        ("coulomb-friction:batten", {"coul": {"batten": 1e-3}}),
        ("viscous-friction:rotor", {"visc": {"rotor": 1e-8}}),
        ("viscous-friction:drum", {"visc": {"drum": 1e-4}}),
        ("viscous-friction:batten", {"visc": {"batten": 1e-4}}),
        ("force-offset:rotor", {"offset": {"rotor": 1e-5}}),
        ("force-offset:drum", {"offset": {"drum": 1e-3}}),
        ("force-offset:batten", {"offset": {"batten": 1e-3}}),
        ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-5, 5.0)}}),
        ("stribeck-friction:drum", {"stribeck": {"drum": (1e-3, 0.1)}}),
        ("stribeck-friction:batten", {"stribeck": {"batten": (1e-3, 0.1)}}),
        ("backlash:K", {"gap": 1e-5}),
        ("inductance", {"p": {"L": p["L"] * 1.001}}),
        ("inductor-saturation:50", {"lsat": (50.0, 0.999)}),
        ("inertia:Jr", {"p": {"Jm": p["Jm"] * 1.001}}),
        ("inertia:Jd", {"p": {"Jd": p["Jd"] * 1.001}}),
        ("inertia:Jb", {"p": {"Jb": p["Jb"] * 1.001}}),
        ("resistance-drift:linear", {"alpha": 1e-4}),
        ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
        ("resistance-drift:warmup-2", {"warmup": (1e-3, 2.0)}),
    )


#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder); the
#: rotor's order 36 (its 4 poles against its 18 slots), the drum's order 4 (the four lift
#: lines' anchor clamps round it)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:drum", lambda a, b: {"cog": {"drum": [(1, a, b)]}}),
    ("unbalance:batten", lambda a, b: {"cog": {"batten": [(1, a, b)]}}),
    ("cogging:rotor:36", lambda a, b: {"cog": {"rotor": [(36, a, b)]}}),
    ("cogging:drum:4", lambda a, b: {"cog": {"drum": [(4, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:36", lambda a, b: {"emf": [(36, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 10 uN m on the
    rotor (and 1e-7 V s/rad of EMF), 1 mN m on the drum and the batten."""
    return 1e-5 if (":rotor" in label or label.startswith("emf")) else 1e-3


#: the places a torque effect may sit at, each with its gear factor (its speed over the
#: drum's: the rotor turns N times the drum, the batten at the drum's mean speed across the
#: 1:1 ropes); rotor-drum is exact (the rigid gearbox), rotor-batten and drum-batten lie
#: across the compliance
PLACES = {"rotor": N, "drum": 1.0, "batten": 1.0}
#: the same for an inertia (component: (parameter, gear factor)); Jr is the rotor's, the
#: parameter Jm
INERTIAS = {"Jr": ("Jm", N), "Jd": ("Jd", 1.0), "Jb": ("Jb", 1.0)}
#: the places behind the ropes
BEYOND = ("batten", "Jb")
#: the catalog's kinds of the armature loop (one place: the loop)
LOOP_KINDS = ("series-resistance", "source-resistance", "brush-drop", "inductance",
              "inductor-saturation", "resistance-drift", "emf-harmonic")
#: an inertia component's body
INERTIA_BODY = {"Jr": "rotor", "Jd": "drum", "Jb": "batten"}


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
    """Motor BC's clean probes at the DECLARED values (Plumbing's field; every record's own
    runs go through ``run``, at its true values)."""
    return sc.simulate(regime, t, fx)


#: the plumbing of this set; each probe's sensor effects are its gain, its offset and its
#: delay; the netlist declares no harmonic term of the catalog's kinds
KIT = LawSeparated(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sc, sim=sim,
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
