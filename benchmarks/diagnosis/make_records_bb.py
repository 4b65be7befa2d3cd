"""Generate the blind set ``fresh53`` of the diagnosis benchmark: records be01-be14 of motor BB
(Kim & Kim 2024's small brushed DC motor, with the 8th-order ripple of its back-EMF, and the
paper's connector -- a varistor across the motor's input, a 0.22 uH rod-core inductor on each
pole -- behind one of three of the paper's SUPPLY FILTERS: case 3, a series R and a shunt C;
case 5, an LC low-pass; case 6, a series L with an RC snubber; on a bench with a 12 V supply
and an eddy-current brake on the shaft), sampled at 20-50 kHz, some evenly and some UNEVENLY,
three of them giving the diagnosis ONE probe only, and merge their truth into truth.json. The
ids have two letters.

    python benchmarks/diagnosis/make_records_bb.py                # records/be*.csv + truth.json
    python benchmarks/diagnosis/make_records_bb.py --only be03,be12
    python benchmarks/diagnosis/make_records_bb.py --truth-only   # rewrite the be entries only

Unlike the earlier sets (one geared DC motor, a compliance and a load), the netlists here are
the product's source paper's circuits (netlists/motor_bb_case3.yaml, motor_bb_case5.yaml,
motor_bb_case6.yaml: self-contained copies of netlists/kim2024's motor and connector with the
filter of each case and a bench program: start-up from rest at 12 V, a dip to 8 V, a brake
step, a reversal to -12 V; 0.3 s); each record names its netlist (truth's ``netlist`` and
``filter_case``). All records are in the fast regime, each at its own sample rate (truth's
``sample_rate_Hz``). The probes are the supply's current ``i_total`` and the rotor's ``speed``.

As in fresh45 to fresh50, the netlists declare the paper's values, and in every record two or
three of them are WRONG by 2-6 % (``FREE``: the record's relative errors, mixed signs): the
record is simulated with the TRUE values of those parameters (and the record's effects), and
the user frees exactly those parameters (truth's ``free``, the netlist's parameter names, and
``declared_error``: {name: {"declared": the netlist's value, "true": the record's}} [SI]). The
other parameters are declared exactly. A null record holds only the declared errors (the right
answer: nothing new, the freed parameters fitted).

A catalog effect that is the same thing as moving a freed parameter cannot be told from it (a
series resistance or a resistance drift when Ra is freed; a source resistance when the filter's
series Rf is freed -- it is in series with it --; an inertia correction when J is freed; a
viscous friction when B is freed; an inductance correction of La or Lf when that one is freed):
no record puts such an effect with its twin freed (``TWINS``, checked). The filter's shunt
element (Cf, or the snubber) stands between the supply and the armature: a source resistance is
NOT the same as a series resistance in the armature loop here (no ``also_accept`` between
them). Each catalog or two-effect record states, per effect, how far its own imprint (run alone
on the record's times and true values) lies from the freed parameters' imprints jointly,
best-scaled (``free_separation_sigma``; linearised: each freed parameter's column is its 1 %
step); a record below FREE_SEPARATION is reported. An outside record's imprint must keep
OUTSIDE_LEFT after the catalog's effects AND the freed parameters jointly (``unexplained_sigma``,
whose alternatives include the ``free:<name>`` columns). A marginal record's
``separation_sigma`` compares it with each other catalog effect with the freed parameters
beside that effect (as the diagnosis fits them).

As in fresh47 to fresh50, a two-effect record also states, per effect, whether the record tells
the effect's LAW from the other catalog kinds at the same place (``law_separation_sigma``): the
record's whole imprint against each neighbour kind at the effect's place (a viscous friction on
the rotor against a dry friction, a breakaway friction, a torque offset or an angle-locked
torque on the rotor; the armature's inductor saturation against the loop's other kinds; a
sensor's gain or offset against the same probe's other kinds), linearised, best-scaled, with
the freed parameters' columns and the record's OTHER effect (its own imprint run alone,
best-scaled) beside it; ``own_sigma`` is the same fit with the effect's own imprint in the
neighbour's place (what the linear fit leaves of the effects' interaction: the floor),
``without_sigma`` with nothing in its place.

Every imprint, signature and alternative is computed about the record's TRUE null (the true
values, no effect): ``signature_sigma`` is the effect's own; a null record's
``signature_sigma`` is its declared errors' (the true null against the declared one), and every
record's ``declared_error_signature_sigma`` is that. The netlists declare the EMF's 8th-order
harmonic (``declared_terms``): an accepted emf-harmonic of order 8 corrects it.

Uses simulators_bb.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI]. A single-probe record (truth's
``probes``: ["i_total"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the imprints it is compared with are computed on that probe alone. Even
records are sampled on k/fs; uneven ones on the record's nominal grid k/fs with every sample
moved by a random jitter of up to 6-22 % of the interval. Each uneven record has its own times
(from its seed), and the motor is simulated at those very times (``t_eval``), never
interpolated. truth.json is merged under an exclusive lock (recordkit.merge). The motor has one
body (the rotor): ``location_sigma`` is empty. Nobody ran the diagnosis on these records.
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
import simulators_bb as sy

RECORDS = HERE / "records"
SPLIT = "fresh53"
MOTOR = "BB"
SEED0 = 53500
NETLIST = {case: f"benchmarks/diagnosis/netlists/motor_bb_case{case}.yaml"
           for case in sy.CASES}
#: default white noise per probe [A, rad/s]
WHITE = {"fast": {"i_total": 0.01, "speed": 0.2}}
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
#: the jitter of an uneven record (a fraction of the interval, drawn per record in this
#: range); the slow regime's drops (unused: no slow regime here)
JITTER, DROPS = (0.06, 0.22), (2, 8)
Part = tuple[dict, dict]
#: the armature loop's elements (a series resistance anywhere in it is the same effect)
LOOP = ["Ra", "La", "Lc1", "Lc2", "M"]
#: the parameters a record may free, and the catalog effects (truth label, target; None: any
#: target) each one is the twin of (never in a record that frees it)
TWINS = {
    "Ra": {("series-resistance", None), ("resistance-drift", None)},
    "La": {("inductance", "La")},
    "Lf": {("inductance", "Lf")},
    "J": {("inertia", None)},
    "B": {("viscous-friction", None)},
    "k_t": set(),
    "Rf": {("source-resistance", None)},
    "Cf": set(),
    "Rs": set(),
    "Cs": set(),
}
#: the EMF harmonic every netlist declares (an accepted one of this order corrects it)
DECLARED = ({"effect": "emf-harmonic", "target": "M", "order": 8},)


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_bb, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The motor has one body, the rotor; no effect here
# changes a parameter a record frees.

def brush_drop(vb: float) -> Part:
    """A brush contact drop Vb tanh(i / 1 mA) [V] in series with the armature."""
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


def series_resistance(r: float) -> Part:
    """A resistance ``r`` [ohm] in series with the armature (after the filter's shunt: not a
    source resistance here; a marginal record scales it)."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": LOOP,
        "parameters": {"R_series_ohm": r,
                       "form": "r i in the armature loop (behind the filter's shunt element)"},
        "expected": {"R": r}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def stribeck_rotor(peak: float, ws: float) -> Part:
    """A breakaway peak s exp(-(w/ws)^2) tanh(w/0.01) [N m] against the rotor, ``ws``
    [rad/s] (the declared rotor has no dry friction)."""
    return {"stribeck": {"rotor": (peak, ws)}}, {
        "effect": "stribeck-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"T_peak_Nm": peak, "w_stribeck_rad_s": ws,
                       "form": "rotor takes s exp(-(w/ws)^2) tanh(w/0.01) against its motion"},
        "expected": {"s": peak, "ws": ws}}


def viscous_rotor(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the rotor."""
    return {"visc": {"rotor": b}}, {
        "effect": "viscous-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"B_extra_Nms_rad": b}, "expected": {"b": b}}


def cogging_rotor(order: int, amp: float, phase: float) -> Part:
    """A detent torque amp sin(order phi + phase) [N m] on the rotor (a marginal record
    scales it)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b}}


def unbalance_rotor(amp: float, phase: float) -> Part:
    """A once-a-turn torque amp sin(phi + phase) [N m] on the rotor (accepted as a cogging of
    order 1)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(1, a, b)]}}, {
        "effect": "unbalance", "target": "rotor", "targets": ["rotor"], "order": 1,
        "parameters": {"order": 1, "T_Nm": amp, "phase_rad": phase,
                       "form": "rotor receives T sin(1 angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["rotor"], "order": 1,
                         "expected": {"a": a, "b": b}}]}


def saturation_la(ipar: float, ratio: float) -> Part:
    """La saturating: dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "La's dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2)): "
                               "psi = La (ratio i + (1 - ratio) Ipar atan(i/Ipar))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


outside = recordkit.outside


def spec(rid: str, cls: str, case: int, fs: float, uneven: bool, parts=(), noise=None,
         note="", marginal=None, size=None, probes: tuple[str, ...] | None = None,
         free: dict[str, float] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.declared_spec``) on filter ``case`` sampled
    at ``fs`` [Hz]: the probes it gives the diagnosis (default: both) and the declared
    parameters it frees (``free``: name -> relative error of the true value over the
    declared)."""
    s = recordkit.declared_spec(rid, cls, "fast", uneven, parts, noise, note, marginal,
                                size, probes=probes or sy.PROBES["fast"], free=free,
                                params=sy.params(case), twins=TWINS, mixed_signs=True)
    s["case"], s["fs"] = case, fs
    return s


def run(s: dict[str, Any], fx: dict, t: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """Motor BB's clean probes at the record's times (or ``t``) [s] with its TRUE values and
    the effects ``fx``."""
    return sy.simulate(s["case"], times(s) if t is None else t, fx, s["ptrue"])


def declared_run(s: dict[str, Any]) -> dict[str, np.ndarray]:
    """Motor BB's clean probes at the record's times with the DECLARED values, no effect."""
    return sy.simulate(s["case"], times(s), {})


# ---------------------------------------------------------------------- the records

#: the current probe's acquisition: a 14-bit ADC over +-20 A (2.44 mA steps)
CURRENT_STEP = 40.0 / 16384
#: the encoder's speed word: 0.05 rad/s steps
SPEED_STEP = 0.05


def nulls() -> list[dict[str, Any]]:
    """be01, be02: the null records (the declared errors only)."""
    return [
        spec("be01", "null", 3, 20e3, False, free={"J": 0.04, "B": -0.05},
             noise={"i_total": {"white": 0.009, "ar1": [0.005, 0.8], "quant": CURRENT_STEP},
                    "speed": {"white": 0.2, "quant": SPEED_STEP}},
             note="an even 20 kHz acquisition, filter case 3; the user frees the rotor's "
                  "inertia and viscous friction (the paper's rolling-incline and coast-down "
                  "estimates; this motor carries a slightly heavier pinion and is run in): J "
                  "is really 4 % higher, B 5 % lower; nothing else; the current with "
                  "Gauss-Markov noise (5 mA, correlation 0.8 over the interval) on white "
                  "noise, in the ADC's 2.44 mA steps; the speed in 0.05 rad/s steps"),
        spec("be02", "null", 6, 25e3, True, probes=("speed",),
             free={"Ra": 0.03, "La": -0.04, "k_t": 0.045},
             noise={"speed": {"white": 0.22, "ar1": [0.15, 0.7], "quant": SPEED_STEP}},
             note="an acquisition of the speed alone, a jittered 25 kHz acquisition, filter "
                  "case 6; the user frees the armature's resistance and inductance and the "
                  "torque constant (the paper estimated La and k_t by matching its model): Ra "
                  "is really 3 % higher, La 4 % lower, k_t 4.5 % higher; nothing else; "
                  "Gauss-Markov noise (0.15 rad/s, correlation 0.7 over the interval) on "
                  "white noise, in 0.05 rad/s steps"),
    ]


def singles() -> list[dict[str, Any]]:
    """be03-be08: one catalog effect each."""
    return [
        spec("be03", "catalog", 3, 40e3, True, (brush_drop(0.12),),
             free={"J": 0.03, "La": -0.04},
             noise={"i_total": {"white": 0.01, "quant": CURRENT_STEP},
                    "speed": {"white": 0.2}},
             note="a jittered 40 kHz acquisition, filter case 3; the motor was rebuilt with "
                  "brushes of a metal-graphite grade: a contact drop of 0.12 V across the pair "
                  "whichever the current's direction; the user frees J and La (really 3 % "
                  "higher and 4 % lower than declared)"),
        spec("be04", "catalog", 5, 30e3, False, (series_resistance(0.02),),
             marginal=lambda r: (series_resistance(r),), size=0.02,
             free={"J": -0.035, "B": 0.03},
             note="an even 30 kHz acquisition, filter case 5; the motor's lead was extended "
                  "through a crimped splice between the connector and the motor: a resistance "
                  "in series with the armature, scaled to a 25 sigma signature (marginal); the "
                  "user frees J and B (really 3.5 % lower and 3 % higher than declared)"),
        spec("be05", "catalog", 5, 20e3, True, (stribeck_rotor(0.02, 40.0),),
             probes=("speed",), noise={"speed": {"white": 0.2, "quant": SPEED_STEP}},
             free={"Ra": 0.04, "Cf": -0.05},
             note="an acquisition of the speed alone, jittered 20 kHz, filter case 5; the "
                  "motor's sintered bronze bearings have dried out: a breakaway friction of "
                  "20 mN m at rest, fading by about 40 rad/s (felt at the start and through "
                  "the reversal); the user frees Ra and the filter's Cf (really 4 % higher and "
                  "5 % lower than declared)"),
        spec("be06", "catalog", 6, 50e3, False, (sensor("i_total", "delay", 3e-5),),
             probes=("i_total",), noise={"i_total": {"white": 0.01, "quant": CURRENT_STEP}},
             free={"Lf": 0.05, "B": -0.03},
             note="an even 50 kHz acquisition of the supply's current alone (the 14-bit ADC), "
                  "filter case 6; the current probe's amplifier was left on its 'low noise' "
                  "setting: its output lags the current by 30 us; the user frees the filter's "
                  "Lf and B (really 5 % higher and 3 % lower than declared)"),
        spec("be07", "catalog", 3, 25e3, False, (cogging_rotor(8, 1e-3, 2.2),),
             marginal=lambda a: (cogging_rotor(8, a, 2.2),), size=1e-3,
             noise={"i_total": {"white": 0.01, "quant": CURRENT_STEP},
                    "speed": {"white": 0.2}},
             free={"Ra": -0.03, "Cf": 0.04},
             note="an even 25 kHz acquisition, filter case 3; the replacement motor's magnets "
                  "are unskewed against its 8 slots: a detent torque 8 times a turn of the "
                  "rotor, scaled to a 25 sigma signature (marginal), phase 2.2 rad; the user "
                  "frees Ra and Cf (really 3 % lower and 4 % higher than declared)"),
        spec("be08", "catalog", 6, 30e3, True, (unbalance_rotor(1.5e-3, 0.8),),
             free={"La": 0.03, "Cs": -0.05, "k_t": -0.025},
             note="a jittered 30 kHz acquisition, filter case 6; the motor lies on its side "
                  "with a balancing weight lost from its rotor: a once-a-turn gravity torque "
                  "of 1.5 mN m, phase 0.8 rad; the user frees La, the snubber's Cs and k_t "
                  "(really 3 % higher, 5 % lower and 2.5 % lower than declared)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """be09, be10: two catalog effects at once."""
    return [
        spec("be09", "two", 3, 40e3, False,
             (viscous_rotor(4e-6), sensor("i_total", "offset", 0.03)),
             free={"Ra": 0.035, "J": -0.04},
             noise={"i_total": {"white": 0.01, "pink": 0.004, "quant": CURRENT_STEP},
                    "speed": {"white": 0.2, "quant": SPEED_STEP}},
             note="an even 40 kHz acquisition, filter case 3; the motor's shaft was fitted "
                  "with a small cooling fan, whose drag is about proportional to the speed "
                  "here: an extra viscous friction of 4e-6 N m s/rad; and the current probe "
                  "was zeroed with its jaw open near the bench's magnet: it reads 30 mA high; "
                  "the user frees Ra and J (really 3.5 % higher and 4 % lower than declared); "
                  "1/f noise (4 mA) on the current"),
        spec("be10", "two", 6, 20e3, True,
             (saturation_la(3.0, 0.5), sensor("speed", "gain", 0.975)),
             free={"Ra": -0.04, "J": 0.03, "Lf": 0.025},
             noise={"i_total": {"white": 0.01, "quant": CURRENT_STEP},
                    "speed": {"white": 0.2, "quant": SPEED_STEP}},
             note="a jittered 20 kHz acquisition, filter case 6; the armature's teeth "
                  "saturate under the start-up and reversal currents: La's incremental "
                  "inductance falls to half by 3 A (knee 3 A, ratio 0.5); and the encoder's "
                  "speed scaling was set for a 40-line disc on a 39-line one: the speed reads "
                  "2.5 % low; the user frees Ra, J and Lf (really 4 % lower, 3 % higher and "
                  "2.5 % higher than declared)"),
    ]


#: the MLCC bank: its capacitance ratio at a high bias r [1] and its knee V0 [V]
CAPBIAS = (0.25, 6.0)
#: the electrolytic Cf's diode-like reverse conduction: Ir [A], Vr [V]
REVCAP = (1e-3, 2.0)
#: the connector pin's oxide film: R0 [ohm], r1 [ohm] (fritted), Vf [V], n [1], tau [s]
FRITT = (0.25, 0.005, 0.8, 4.0, 2e-3)
#: the torque constant's slot ripple: depth m [1], phase psi [rad]
KTRIP = (0.05, 0.6)


def outside_records() -> list[dict[str, Any]]:
    """be11-be14: effects the catalog does not contain."""
    r, v0 = CAPBIAS
    ir, vr = REVCAP
    m, psi = KTRIP
    r0, r1, vf, n, tau = FRITT
    return [
        spec("be11", "outside", 3, 25e3, False, (outside(
            "ceramic-filter-capacitor-bank-loses-capacitance-under-dc-bias",
            {"capbias": CAPBIAS},
            {"r": r, "V0_V": v0,
             "form": "Cf's differential capacitance dq/dv = Cf (r + (1 - r)/(1 + (va/V0)^2)) "
                     "at its voltage va (class-II ceramic: 40 % of Cf left at 12 V)"}),),
            free={"J": 0.04, "B": -0.03},
            noise={"i_total": {"white": 0.01, "quant": CURRENT_STEP},
                   "speed": {"white": 0.2, "quant": SPEED_STEP}},
            note=NOTE_CAPBIAS),
        spec("be12", "outside", 5, 30e3, False, (outside(
            "polarised-filter-capacitor-conducts-when-reverse-biased", {"revcap": REVCAP},
            {"Ir_A": ir, "Vr_V": vr,
             "form": "Cf carries besides Cf dva/dt the current -Ir (exp(-va/Vr) - 1) from a "
                     "to gnd: Ir of leakage forward-biased, a diode-like reverse current "
                     "when va < 0"}),),
            free={"La": -0.03, "Rf": 0.05},
            noise={"i_total": {"white": 0.01, "ar1": [0.004, 0.8], "quant": CURRENT_STEP},
                   "speed": {"white": 0.2}},
            note=NOTE_REVCAP),
        spec("be13", "outside", 6, 20e3, True, (outside(
            "tarnished-connector-pin-film-punctures-at-start-up", {"fritt": FRITT},
            {"R0_ohm": r0, "r1_ohm": r1, "Vf_V": vf, "n": n, "tau_s": tau,
             "form": "the loop takes Rc i, Rc = r1 + (R0 - r1) h, dh/dt = -h (|Rc i|/Vf)^n "
                     "/ tau, h = 1 at the start: an oxide film on the connector's + pin "
                     "that breaks down (A-fritting) once the voltage across it nears Vf, and "
                     "never heals"}),),
            free={"Ra": 0.03, "B": -0.04},
            noise={"i_total": {"white": 0.01, "quant": CURRENT_STEP},
                   "speed": {"white": 0.2, "pink": 0.08, "quant": SPEED_STEP}},
            note=NOTE_FRITT),
        spec("be14", "outside", 5, 40e3, False, (outside(
            "torque-constant-ripples-with-the-slots", {"ktrip": KTRIP},
            {"m": m, "psi_rad": psi,
             "form": "the rotor receives k_t i (1 + m sin(8 phi + psi)) (phi the rotor's "
                     "angle); the back-EMF unchanged"}),),
            free={"J": -0.03, "Lf": 0.04},
            noise={"i_total": {"white": 0.01, "quant": CURRENT_STEP},
                   "speed": {"white": 0.2, "quant": SPEED_STEP}},
            note=NOTE_KTRIP),
    ]


NOTE_CAPBIAS = (
    "an even 25 kHz acquisition, filter case 3; the user frees J and B (really 4 % higher and "
    "3 % lower than declared); the filter's 1000 uF was built from ten 100 uF 16 V X5R "
    "ceramic capacitors instead of an electrolytic: their capacitance falls with the DC bias "
    "(to 40 % of the nominal at 12 V, knee 6 V); nothing else; not a resistance, an "
    "inductance or a sensor's fault: a shunt capacitance that depends on its own voltage")
NOTE_REVCAP = (
    "an even 30 kHz acquisition, filter case 5; the user frees La and the filter's Rf (really "
    "3 % lower and 5 % higher than declared); the filter's Cf is a polarised aluminium "
    "electrolytic (1000 uF): forward-biased it leaks 1 mA, and when the bench program "
    "reverses the supply it is reverse-biased and conducts like a diode (1 mA x (exp(|va|/2 "
    "V) - 1)); nothing else; not a resistance, an offset or a sensor's fault: a leak across "
    "the filter's output that grows exponentially with the reverse voltage")
NOTE_FRITT = (
    "a jittered 20 kHz acquisition, filter case 6; the user frees Ra and B (really 3 % higher "
    "and 4 % lower than declared); the connector's + pin had tarnished in storage: an oxide "
    "film of 0.25 ohm that breaks down (fritting) once about 0.8 V stands across it, which "
    "the start-up's inrush current does within the first milliseconds, leaving a metallic "
    "contact of 5 mohm for the rest of the record; nothing else; not a resistance, a brush "
    "drop or a resistance drift: a contact resistance that collapses under its own voltage "
    "and stays low; 1/f noise (0.08 rad/s) on the speed")
NOTE_KTRIP = (
    "an even 40 kHz acquisition, filter case 5; the user frees J and Lf (really 3 % lower and "
    "4 % higher than declared); the motor's torque constant ripples 8 times a turn with the "
    "slots (5 %, phase 0.6 rad): the rotor receives k_t i (1 + 0.05 sin(8 phi + 0.6)); the "
    "back-EMF as declared; nothing else; not a detent torque (it follows the current, and "
    "reverses with it) nor an EMF harmonic: a torque ripple proportional to the current")


def record_specs() -> list[dict[str, Any]]:
    """The 14 records in id order, each with its seed."""
    out = sorted(nulls() + singles() + pairs() + outside_records(), key=lambda s: s["id"])
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- sample times

def times(s: dict[str, Any]) -> np.ndarray:
    """The record's sample times [s] (even, or jittered from its seed), once; described in
    ``s["timestamps"]`` (``recordkit.record_times`` on the record's own rate)."""
    return recordkit.record_times(s, {"fast": (s["fs"], sy.DURATION)},
                                  lambda regime: sy.grid(s["fs"]), 53, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

def scalar_effects(p: dict[str, float]) -> tuple[tuple[str, dict], ...]:
    """Small catalog effects (label, fx) an imprint is compared with, linearised at the
    record's true null (``p``: its true values, the corrections' steps relative to them); the
    filter inductor's inductance and saturation where the case has one."""
    out = [
        ("series-resistance", {"Rser": 1e-3}),
        ("source-resistance", {"Rs": 1e-3}),
        ("brush-drop", {"Vb": 1e-2}),
        ("coulomb-friction:rotor", {"coul": {"rotor": 1e-5}}),
        ("viscous-friction:rotor", {"visc": {"rotor": 1e-8}}),
        ("force-offset:rotor", {"offset": {"rotor": 1e-5}}),
        ("stribeck-friction:rotor:10", {"stribeck": {"rotor": (1e-5, 10.0)}}),
        ("stribeck-friction:rotor:100", {"stribeck": {"rotor": (1e-5, 100.0)}}),
        ("inductance:La", {"p": {"La": p["La"] * 1.001}}),
        ("inductor-saturation:La:5", {"lsat": (5.0, 0.999)}),
        ("inertia:Jr", {"p": {"J": p["J"] * 1.001}}),
        ("resistance-drift:linear", {"alpha": 1e-4}),
        ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
        ("resistance-drift:warmup-2", {"warmup": (1e-3, 2.0)}),
    ]
    if "Lf" in p:
        out += [("inductance:Lf", {"p": {"Lf": p["Lf"] * 1.001}}),
                ("inductor-saturation:Lf:5", {"lsat_f": (5.0, 0.999)})]
    return tuple(out)


#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder); the
#: rotor's unbalance and its detent orders 2 and 8 (the 8 slots), the EMF's orders 1, 2, 8 (the
#: declared term's correction) and 16
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("cogging:rotor:2", lambda a, b: {"cog": {"rotor": [(2, a, b)]}}),
    ("cogging:rotor:8", lambda a, b: {"cog": {"rotor": [(8, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:8", lambda a, b: {"emf": [(8, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:16", lambda a, b: {"emf": [(16, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 10 uN m on the
    rotor (and 1e-7 V s/rad of EMF)."""
    return 1e-5


#: the places a torque effect may sit at (one body: the rotor), and the inertias
PLACES = {"rotor": 1.0}
INERTIAS = {"Jr": ("J", 1.0)}
BEYOND: tuple[str, ...] = ()
#: the catalog's kinds of the electrical circuit (one place: the loop)
LOOP_KINDS = ("series-resistance", "source-resistance", "brush-drop", "inductance",
              "inductor-saturation", "resistance-drift", "emf-harmonic")
#: an inertia component's body
INERTIA_BODY = {"Jr": "rotor"}


def place(kind: str, target: str | None) -> str:
    """Where a catalog effect of ``kind`` on ``target`` acts: the rotor for a torque effect
    or the inertia, a probe for a sensor effect, ``loop`` for the circuit's kinds."""
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
    other catalog kinds at its place (``law_separation_sigma``, ``law_separation``); the
    record's netlist is its filter case's."""

    case: int = 3

    def truth_entry(self, s: dict[str, Any], sig: dict) -> dict:
        """recordkit.DeclaredOff's entry, with the filter case's netlist."""
        entry = super().truth_entry(s, sig)
        entry["netlist"] = NETLIST[s["case"]]
        entry["filter_case"] = s["case"]
        return entry

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


def kit(case: int) -> LawSeparated:
    """The plumbing of this set for filter ``case``; each probe's sensor effects are its
    gain, its offset and its delay; the netlist declares the EMF's 8th harmonic."""
    return LawSeparated(
        split=SPLIT, motor=MOTOR, netlist={"fast": NETLIST[case]}, white=WHITE, simulator=sy,
        sim=lambda regime, t, fx: sy.simulate(case, t, fx), times=times, scalar_effects=(),
        harmonic_effects=HARMONIC_EFFECTS, harmonic_size=harmonic_size,
        marginal_sigma=MARGINAL_SIGMA, declared=DECLARED, run=run,
        declared_run=declared_run, params=sy.params(case), effects_of=scalar_effects,
        free_step=FREE_STEP, places=PLACES, inertias=INERTIAS, beyond=BEYOND, case=case)


KITS = {case: kit(case) for case in sy.CASES}


def imprints(s: dict[str, Any]) -> recordkit.Imprints:
    """The record's true null and imprints (its case's plumbing)."""
    return KITS[s["case"]].imprints(s)


def make(s: dict[str, Any], write: bool) -> dict:
    """One record (its case's plumbing)."""
    return KITS[s["case"]].make(s, write)


def scale_marginal(s: dict[str, Any]) -> None:
    """Scale a marginal record to MARGINAL_SIGMA (its case's plumbing)."""
    KITS[s["case"]].scale_marginal(s)


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
    for f in entry.get("law_separation_sigma", []):
        near = sorted(f["neighbours"].items(), key=lambda kv: kv[1])
        extra.append(f"law of {f['effect']}: own {f['own_sigma']:.3g}, without "
                     f"{f['without_sigma']:.3g}, " + ", ".join(f"{k} {v:.3g}" for k, v in near))
    u = entry.get("unexplained_sigma")
    if u:
        extra.append(f"best single {u['best_single'][0]} leaves {u['best_single'][1]:.3g}; "
                     f"left {u['all_scalar_effects_jointly'] / u['imprint']:.2f} of it")
    dec = ", ".join(f"{k} {v:.3g}" for k, v in entry["declared_error_signature_sigma"].items())
    print(f"   {entry['id']} case {entry['filter_case']}, "
          f"{entry.get('timestamps', '')[:40]}; declared errors {dec}; " + "; ".join(extra))
    return entry


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, checked_make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
