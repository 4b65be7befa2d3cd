"""Generate the blind set ``fresh21`` of the diagnosis benchmark: records i01-i14 of motor V
(a 24 V brushed DC motor in an auto-steer kit: a rigid 18:1 gearhead on the steering column,
the intermediate shaft's compliance down to the rack-and-pinion gear, the rack and the road
wheels reflected to the pinion against the tyres' aligning moment, a spring to the frame),
some sampled evenly and some UNEVENLY, and merge their truth into truth.json.

    python benchmarks/diagnosis/make_records_v.py              # records/i*.csv + truth.json
    python benchmarks/diagnosis/make_records_v.py --only i03,i12
    python benchmarks/diagnosis/make_records_v.py --truth-only # rewrite the i entries only

Uses simulators_v.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe [SI] (and, in the slow regime, the command ``u``
[V] that motor_v_slow.yaml reads from its own table). Even records are sampled on the
regime's grid k/fs; uneven ones, in the fast regime, on a 20 kHz grid whose every sample is
moved by a random jitter of up to 10-30 % of the interval, and in the slow regime at a
logger's irregular intervals (0.6-1.4 times the mean of 2 ms) with a few samples dropped.
Each uneven record has its own times (from its seed), and the motor is simulated at those
very times (``t_eval``), never interpolated. truth.json is merged under an exclusive lock
(recordkit.merge). Nobody ran the diagnosis on these records.
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
import simulators_v as sv

RECORDS = HERE / "records"
SPLIT = "fresh21"
MOTOR = "V"
SEED0 = 21500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_v.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_v_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.03, "speed": 0.3},
         "slow": {"current": 0.03, "speed": 0.3, "load_speed": 0.01}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sv.MOTOR_V
N = P["N"]
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_v, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearhead is rigid and lossless: a torque on the
# rotor is N = 18 times as large on the column, a viscous coefficient N^2 = 324 times, a
# harmonic of order n of the rotor's angle is of order 18 n of the column's; the pinion sits
# behind the compliant intermediate shaft and has no such equal.

def saturation(ipar: float, ratio: float) -> Part:
    """The armature's inductance saturating with the current (Modelica's SaturatingInductor:
    dpsi/di = L (ratio + (1 - ratio)/(1 + (i/Ipar)^2)))."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def series_resistance(r: float, regime: str) -> Part:
    """A resistance [ohm] in series with the armature (accepted inside the supply)."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": ["Ra", "La", "M"],
        "parameters": {"R_series_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def viscous_pinion(b: float) -> Part:
    """An extra viscous friction b [N m s/rad] on the pinion's side (behind the compliant
    intermediate shaft: no equal on the rotor)."""
    return {"visc": {"pinion": b}}, {
        "effect": "viscous-friction", "target": "pinion", "targets": ["pinion"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b w against the pinion"},
        "expected": {"b": b}}


def cogging_rotor(order: int, amp: float, phase: float) -> Part:
    """The rotor's detent torque amp sin(order angle + phase) [N m] (accepted on the column
    at order 18 times and 18 times the size)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["column"], "order": int(order * N),
                         "expected": {"a": a * N, "b": b * N}}]}


def inductance(dl: float) -> Part:
    """The armature's inductance off by a factor 1 + ``dl`` (a correction of La)."""
    return {"p": {"L": P["L"] * (1.0 + dl)}}, {
        "effect": "inductance", "target": "La", "targets": ["La"], "correction": True,
        "parameters": {"La_true_H": P["L"] * (1.0 + dl), "dL": dl}, "expected": {"dL": dl}}


def brush_drop(vb: float) -> Part:
    """A brush contact drop Vb tanh(i / 1 mA) [V] in series with the armature."""
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


def inertia_pinion(dj: float) -> Part:
    """The pinion side's inertia off by a factor 1 + ``dj`` (a correction of Jp)."""
    return {"p": {"Jp": P["Jp"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jp", "targets": ["Jp"], "correction": True,
        "parameters": {"Jp_true_kgm2": P["Jp"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


def warmup(rise: float, tau: float) -> Part:
    """The winding warming: R (1 + rise (1 - exp(-t / tau)))."""
    return {"warmup": (rise, tau)}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + rise*(1 - exp(-t/tau)))", "rise": rise,
                       "tau_s": tau},
        "expected": {"rise": rise, "tau": tau}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor V's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sv.simulate(regime, t, fx)


spec = recordkit.spec


# ---------------------------------------------------------------------- the records

#: a 12-bit ADC over +-30 A (14.6 mA steps) on the current
ADC_I = {"white": 0.03, "quant": 0.0146}


def nulls_and_singles() -> list[dict[str, Any]]:
    """i01-i07: the null and single catalog records."""
    return [
        spec("i01", "null", "fast", False, note="white noise"),
        spec("i02", "null", "slow", True,
             noise={"current": {"white": 0.02, "ar1": [0.03, 0.9], "quant": 0.0146},
                    "speed": {"white": 0.3, "pink": 0.3},
                    "load_speed": {"white": 0.01}},
             note="coloured noise: Gauss-Markov current noise (correlation 0.9 over the mean "
                  "interval, exp(-dt/tau) over an interval dt) and a 12-bit ADC over +-30 A "
                  "(14.6 mA steps) on the current, 1/f noise on the motor's speed (a sum of "
                  "Gauss-Markov processes an octave apart)"),
        spec("i03", "catalog", "fast", False, (saturation(10.0, 0.5),),
             noise={"current": ADC_I, "speed": {"white": 0.3}},
             note="a motor from a batch whose stator ring is thinner: the armature's inductance "
                  "falls to three quarters of its declared value at 10 A and towards half of it "
                  "beyond (the turn-in, the step up and the steer through the centre reach 17-20 "
                  "A): the current jumps faster at each step, 1.8 A more 0.4 ms after the step "
                  "up; the current read by a 12-bit ADC"),
        spec("i04", "catalog", "slow", False, (series_resistance(0.08, "slow"),),
             note="the motor's plug on the chassis harness sits behind the front wheel and its "
                  "pins have corroded in the spray: 0.08 ohm more in the armature's loop (20 % of"
                  " Ra); every hold draws a sixth less current (14.6 A instead of 17.5 A at 7 V) "
                  "and the wheels steer a sixth less far"),
        spec("i05", "catalog", "fast", True, (sensor("current", "offset", 0.01),),
             marginal=lambda o: (sensor("current", "offset", o),), size=0.01,
             noise={"current": ADC_I, "speed": {"white": 0.3}},
             note="the bridge's Hall current sensor was zeroed on a cold morning: it reads a few "
                  "milliamperes high at any current, scaled to a 25 sigma signature (marginal); "
                  "the current read by a 12-bit ADC"),
        spec("i06", "catalog", "slow", True, (viscous_pinion(0.02),),
             marginal=lambda b: (viscous_pinion(b),), size=0.02,
             noise={"current": {"white": 0.03, "ar1": [0.02, 0.8]},
                    "speed": {"white": 0.3}, "load_speed": {"white": 0.01}},
             note="the rack's rubber gaiters tore on a field track and took in muddy water that "
                  "thickens the rack's grease: an extra viscous drag on the pinion's side, scaled"
                  " to a 25 sigma signature (marginal); Gauss-Markov noise on the current"),
        spec("i07", "catalog", "fast", False, (cogging_rotor(10, 0.008, 1.1),),
             note="a replacement motor of a cheaper make whose ten armature slots are not skewed:"
                  " a detent torque of order 10 (8 mN m, a fifth of an ampere's torque) that "
                  "ripples the current and the speed ten times a rotor turn while the rotor turns"
                  " (up to 300 Hz in the steer through the centre) and nudges it at rest"),
    ]


def pairs() -> list[dict[str, Any]]:
    """i08, i09: two catalog effects at once."""
    return [
        spec("i08", "two", "fast", True, (inductance(-0.35), brush_drop(0.2)),
             noise={"current": ADC_I, "speed": {"white": 0.3}},
             note="the actuator got a replacement motor of another make: its armature's "
                  "inductance is 35 % below the declared La (a correction of La) and its harder, "
                  "copper-free carbon brushes take a contact drop of 0.2 V of the current's sign;"
                  " the current read by a 12-bit ADC"),
        spec("i09", "two", "slow", False, (inertia_pinion(0.4), warmup(0.12, 3.0)),
             noise={"current": {"white": 0.03}, "speed": {"white": 0.3},
                    "load_speed": {"white": 0.008, "pink": 0.008}},
             note="the front wheels were changed from aluminium to steel rims with the same "
                  "tyres: the road wheels' steer inertia, and with it the pinion side's, is 40 % "
                  "above Jp (a correction of Jp); and the auto-steer was engaged with a cold "
                  "motor that warms through the record from its holding currents: the winding's "
                  "resistance rises by 12 % with a time constant of 3 s; 1/f noise on the "
                  "pinion's speed"),
    ]


#: the universal joints' added transmission error [rad] and its phase [rad]
CARDAN = (0.05, 0.6)
#: the encoder hub: its inertia [kg m^2], the set screw's slipping torque [N m] and the
#: smoothing of the slip speed [rad/s]
SLIP = (8e-6, 0.03, 0.05)
#: the kerb stone: the start [s], the peak torque at the pinion [N m] and the duration [s]
KERB = (5.0, -10.0, 0.04)
#: [s] the tyres' relaxation: 0.45 m of travel at 40 km/h
RELAX = 0.04
#: [rad] the pinion's angle at which the aligning moment's growth bends over
ALSAT = 0.6


def outside_fast() -> list[dict[str, Any]]:
    """i10, i11: effects the catalog does not contain, fast regime."""
    return [
        spec("i10", "outside", "fast", False, (outside(
            "cardan-joint-phasing", {"cardan": CARDAN},
            {"e_rad": CARDAN[0], "psi_rad": CARDAN[1],
             "form": "the shaft's lower end stands at phi = thc + e (sin(2 thc + psi) - "
                     "sin(psi)), thc the column's angle; the intermediate shaft's torque "
                     "c (phi - thp) + d (phi' - wp), the column takes it times "
                     "dphi/dthc = 1 + 2 e cos(2 thc + psi)"}),),
            note="the intermediate shaft was refitted after a repair with its two universal "
                 "joints (each bent by 18 degrees) a quarter turn out of phase: instead of "
                 "cancelling, their speed fluctuations add, and the shaft's lower end runs ahead "
                 "of or behind the column by up to 0.05 rad, the ratio between them 1.08 at "
                 "straight ahead, 1.0 at half a radian to the left and 1.09 at half a radian to "
                 "the right. A person sees the moves to the right fall short (at -7 V the column "
                 "holds 0.42 instead of 0.49 rad and the pinion 0.38 instead of 0.40 rad; to the "
                 "left at 8 V 0.49 instead of 0.52 and 0.42 instead of 0.43 rad), the steer "
                 "through the centre 9 rad/s slower at the rotor with the current 1 A more "
                 "negative, the current and the speed off by up to 1.5 A and 14 rad/s, nothing "
                 "while the column stands near the centre"),
        spec("i11", "outside", "fast", False, (outside(
            "slipping-encoder-hub", {"slip": SLIP},
            {"Jenc_kgm2": SLIP[0], "Tc_Nm": SLIP[1], "eps_rad_s": SLIP[2],
             "form": "the encoder's hub (Jenc, part of the declared Jm) is dragged by "
                     "Tc tanh((w - wc)/eps), the rotor takes the reaction; the speed probe "
                     "reads wc"}),),
            note="the set screw of the motor encoder's clamping hub has worked loose: the hub "
                 "(8e-6 kg m^2 of the rotor's inertia) is carried by the screw's friction, at "
                 "most 0.03 N m, so it slips whenever the rotor accelerates faster than 3750 "
                 "rad/s^2. A person sees the encoder's speed lag the motor's through the sharp "
                 "changes only, each time for 20-100 ms until the two meet and lock again: 2 "
                 "rad/s after the step down, 17.6 rad/s low 9 ms after the step up, 20 rad/s "
                 "short of the motor's speed as it swings to -187 rad/s through the centre, 13 "
                 "rad/s low after the step at 0.62 s; the turn-in and the release read right; the"
                 " current almost untouched (0.16 A)"),
    ]


def outside_slow() -> list[dict[str, Any]]:
    """i12-i14: effects the catalog does not contain, slow regime."""
    return [
        spec("i12", "outside", "slow", True, (outside(
            "kerb-strike", {"kerb": KERB},
            {"t0_s": KERB[0], "T_peak_Nm": KERB[1], "Tw_s": KERB[2],
             "form": "the pinion receives T sin(pi (t - t0)/Tw)^2 for t0 <= t <= t0 + Tw"}),),
            noise={"current": {"white": 0.03, "ar1": [0.02, 0.85]}, "speed": {"white": 0.3},
                   "load_speed": {"white": 0.01}},
            note="the vehicle's front wheel strikes a kerb stone 5 s into the record, in the "
                 "middle of the curve: a torque pulse of -10 N m at the pinion over 40 ms "
                 "(half-sine squared) pushes the wheels back towards straight ahead. A person "
                 "sees, with no change of the command, the pinion's speed swing to -5 rad/s and "
                 "back to +2.7 rad/s, the rotor's speed to -55 rad/s, the current jump by 5.9 A "
                 "(the motor pushed backwards) and ring at the intermediate shaft's mode for "
                 "about 50 ms, the steering recover over 0.3 s and hold 0.005 rad short of where "
                 "it was (the rack's friction); Gauss-Markov noise on the current"),
        spec("i13", "outside", "slow", False, (outside(
            "tyre-relaxation-lag", {"relax": RELAX},
            {"tau_s": RELAX, "Ka_Nm_rad": P["Ka"],
             "form": "instead of the declared Ka thp, the pinion takes Mz with "
                     "dMz/dt = (Ka thp - Mz)/tau"}),),
            noise={"current": {"white": 0.03}, "speed": {"white": 0.3, "pink": 0.25},
                   "load_speed": {"white": 0.01}},
            note="at 40 km/h the tyres' aligning moment does not follow the steer angle at once: "
                 "it builds up over their relaxation length (0.45 m of travel, 40 ms). A person "
                 "sees the steering, whose declared response is critically damped, overshoot and "
                 "swing back at about 2.4 Hz after every quick move: after the 0.1 s turn into "
                 "the curve the pinion goes 0.054 rad past its hold and back (the rotor's speed "
                 "reverses to -7.8 rad/s), after the 0.2 s turn-in 0.014 rad; the holds end "
                 "within the rack's friction dead band but on its far side (0.329 instead of "
                 "0.315 rad at 5 V); 1/f noise on the motor's speed"),
        spec("i14", "outside", "slow", True, (outside(
            "aligning-moment-saturation", {"alsat": ALSAT},
            {"theta0_rad": ALSAT, "Ka_Nm_rad": P["Ka"],
             "form": "instead of the declared Ka thp, the pinion takes "
                     "Ka theta0 tanh(thp/theta0)"}),),
            noise={"current": ADC_I, "speed": {"white": 0.3}, "load_speed": {"white": 0.01}},
            note="at 40 km/h the front tyres' aligning moment grows less than in proportion to "
                 "the steer angle: the pneumatic trail shrinks as the slip grows, Ka theta0 "
                 "tanh(thp/theta0) with theta0 = 0.6 rad at the pinion. A person sees the holds' "
                 "currents as declared (u/R), but the steering goes further and the more so the "
                 "harder it is held: 10 % further at 5 V, 26 % at 7 V (0.557 instead of 0.442 rad"
                 " of the pinion), 17 % at -6 V; and the moves into them faster, the rotor's "
                 "speed 8 rad/s higher in the turn into the curve; the current read by a 12-bit "
                 "ADC"),
    ]


def record_specs() -> list[dict[str, Any]]:
    """The 14 records in id order, each with its seed."""
    out = sorted(nulls_and_singles() + pairs() + outside_fast() + outside_slow(),
                 key=lambda s: s["id"])
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- sample times

def times(s: dict[str, Any]) -> np.ndarray:
    """The record's sample times [s] (even, or uneven from its seed), once; described in
    ``s["timestamps"]`` (``recordkit.record_times``)."""
    return recordkit.record_times(s, sv.REGIMES, sv.grid, 21, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
#: (the column's frictions and offsets are the rotor's columns scaled)
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-3}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:pinion", {"coul": {"pinion": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-6}}),
    ("viscous-friction:pinion", {"visc": {"pinion": 1e-4}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:pinion", {"offset": {"pinion": 1e-3}}),
    ("stribeck-friction:pinion:0.3", {"stribeck": {"pinion": (1e-3, 0.3)}}),
    ("stribeck-friction:pinion:3", {"stribeck": {"pinion": (1e-3, 3.0)}}),
    ("backlash:K", {"gap": 1e-3}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:20", {"lsat": (20.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jc", {"p": {"Jc": P["Jc"] * 1.001}}),
    ("inertia:Jp", {"p": {"Jp": P["Jp"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:column", lambda a, b: {"cog": {"column": [(1, a, b)]}}),
    ("unbalance:pinion", lambda a, b: {"cog": {"pinion": [(1, a, b)]}}),
    ("cogging:column:2", lambda a, b: {"cog": {"column": [(2, a, b)]}}),
    ("cogging:pinion:2", lambda a, b: {"cog": {"pinion": [(2, a, b)]}}),
    ("cogging:rotor:10", lambda a, b: {"cog": {"rotor": [(10, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:10", lambda a, b: {"emf": [(10, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 1e-4 on the
    rotor and the EMF, 1e-3 behind the gearhead."""
    return 1e-3 if (":column" in label or ":pinion" in label) else 1e-4


#: the plumbing every later set shares (recordkit.Plumbing): truth entries, marginal
#: scaling, the catalog's imprints an outside or marginal record is compared with, the CSV;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term
KIT = recordkit.Plumbing(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sv, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=harmonic_size, marginal_sigma=MARGINAL_SIGMA, declared=())
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
