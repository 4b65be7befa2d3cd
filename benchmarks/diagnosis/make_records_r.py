"""Generate the blind set ``fresh17`` of the diagnosis benchmark: records z01-z14 of motor R
(a 24 V brushed DC motor driving a sectional garage-door opener through a rigid 60:1 worm
gear and a compliant roller chain), some sampled evenly and some UNEVENLY, and merge their
truth into truth.json.

    python benchmarks/diagnosis/make_records_r.py              # records/z*.csv + truth.json
    python benchmarks/diagnosis/make_records_r.py --only z03,z12
    python benchmarks/diagnosis/make_records_r.py --truth-only # rewrite the z entries only

Uses simulators_r.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe [SI] (and, in the slow regime, the command ``u``
[V] that motor_r_slow.yaml reads from its own table). Even records are sampled on the
regime's grid k/fs; uneven ones, in the fast regime, on a 20 kHz grid whose every sample is
moved by a random jitter of up to 15-30 % of the interval, and in the slow regime at a
logger's irregular intervals (0.6-1.4 times the mean of 4 ms) with a few samples dropped.
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
import simulators_r as sr

RECORDS = HERE / "records"
SPLIT = "fresh17"
MOTOR = "R"
SEED0 = 17500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_r.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_r_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.03, "speed": 0.3},
         "slow": {"current": 0.03, "speed": 0.3, "load_speed": 0.01}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.15, 0.30), (2, 8)
P = sr.MOTOR_R
N = P["N"]
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_r, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The worm gear is rigid and lossless: a torque on the
# rotor is N = 60 times as large on the sprocket, a viscous coefficient N^2 = 3600 times;
# the door sits behind the compliant chain and has no such equal.

def cogging(order: int, amp: float, phase: float) -> Part:
    """The rotor's detent torque amp sin(order angle + phase) [N m] (accepted on the
    sprocket at order N times and N times the size)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["sprocket"],
                         "order": int(order * N), "expected": {"a": a * N, "b": b * N}}]}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def series_resistance(r: float, regime: str) -> Part:
    """A resistance [ohm] in series with the armature (a long, thin cable to the motor)."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": ["Ra", "La", "M"],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


def saturation(ipar: float, ratio: float) -> Part:
    """The armature's inductance saturating with the current (Modelica's SaturatingInductor:
    dpsi/di = L (ratio + (1 - ratio)/(1 + (i/Ipar)^2)))."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def coulomb_door(c: float) -> Part:
    """An extra dry friction c [N m] on the door (at the sprocket)."""
    return {"coul": {"door": c}}, {
        "effect": "coulomb-friction", "target": "door", "targets": ["door"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(w_door/0.01) against the door"},
        "expected": {"c": c}}


def viscous_rotor(b: float) -> Part:
    """An extra viscous friction [N m s/rad] on the rotor (accepted on the sprocket at N^2
    times)."""
    return {"visc": {"rotor": b}}, {
        "effect": "viscous-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b w against the rotor"},
        "expected": {"b": b},
        "also_accept": [{"effect": "viscous-friction", "targets": ["sprocket"],
                         "expected": {"b": b * N ** 2}}]}


def stribeck_door(s: float, ws: float) -> Part:
    """A breakaway peak s [N m] with Stribeck speed ws [rad/s] over the door's dry
    friction."""
    return {"stribeck": {"door": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "door", "targets": ["door"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "door takes s exp(-(w/ws)^2) tanh(w/0.01) over the declared "
                               "Tf tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def offset_door(value: float) -> Part:
    """A constant torque [N m] on the door (negative: the door heavier, pulling it shut);
    accepted on the sprocket at its size and on the rotor at 1/N of it (a constant torque
    passes the chain unchanged once it has stretched)."""
    return {"offset": {"door": value}}, {
        "effect": "force-offset", "target": "door", "targets": ["door"],
        "parameters": {"T_Nm": value, "form": "the door receives a constant T (pulling it "
                                              "shut when T < 0)"},
        "expected": {"F": value},
        "also_accept": [{"effect": "force-offset", "targets": ["sprocket"],
                         "expected": {"F": value}},
                        {"effect": "force-offset", "targets": ["rotor"],
                         "expected": {"F": value / N}}]}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor R's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sr.simulate(regime, t, fx)


spec = recordkit.spec


# ---------------------------------------------------------------------- the records

#: a 12-bit ADC over +-40 A (19.5 mA steps) on the current
ADC_I = {"white": 0.03, "quant": 0.0195}


def null_and_catalog() -> list[dict[str, Any]]:
    """z01-z09: the null, catalog and two-effect records."""
    return [
        spec("z01", "null", "fast", False, note="white noise"),
        spec("z02", "null", "slow", True,
             noise={"current": {"white": 0.02, "ar1": [0.03, 0.85], "quant": 0.0195},
                    "speed": {"white": 0.3, "pink": 0.4},
                    "load_speed": {"white": 0.01}},
             note="coloured noise: Gauss-Markov current noise (correlation 0.85 over the mean "
                  "interval, exp(-dt/tau) over an interval dt) and a 12-bit ADC over +-40 A "
                  "(19.5 mA steps) on the current, 1/f noise on the motor's speed (a sum of "
                  "Gauss-Markov processes an octave apart)"),
        spec("z03", "catalog", "fast", False, (coulomb_door(1.2),),
             noise={"current": ADC_I, "speed": {"white": 0.3}},
             note="a section of the door's track is bent where a car touched it: the rollers "
                  "bind and the door's dry friction is 1.2 N m (40 N at the trolley) above "
                  "the declared one; the current read by a 12-bit ADC"),
        spec("z04", "catalog", "fast", False, (saturation(8.0, 0.5),),
             note="the motor's thin stator ring saturates under the armature's field: its "
                  "inductance falls with the current, to 75 % of La at 8 A and to 57 % at "
                  "the braking's 19.6 A peak (Ipar 8 A, ratio 0.5)"),
        spec("z05", "catalog", "fast", True, (sensor("current", "delay", 8e-5),),
             note="the drive's current is read through an RC filter on the shunt amplifier "
                  "that lags it by 80 us (the first-order Pade stage of the delay, as the "
                  "catalog's patch)"),
        spec("z06", "catalog", "fast", False, (viscous_rotor(2e-5),),
             marginal=lambda b: (viscous_rotor(b),), size=2e-5,
             note="the worm's grease has thickened (an unheated garage in winter): an extra "
                  "viscous drag on the rotor and the worm, scaled to a 25 sigma signature "
                  "(marginal); N^2 = 3600 times it on the sprocket accepted"),
        spec("z07", "catalog", "slow", False, (offset_door(-0.3),),
             marginal=lambda f: (offset_door(f),), size=-0.3,
             note="one of the door's torsion springs has lost some of its wind: the door is "
                  "heavier than declared by a constant torque pulling it shut, scaled to a "
                  "25 sigma signature (marginal)"),
        spec("z08", "two", "fast", False, (series_resistance(0.25, "fast"),
                                           stribeck_door(1.5, 0.3)),
             noise={"current": ADC_I, "speed": {"white": 0.25, "pink": 0.25}},
             note="the opener is fed through a 2 x 7 m run of thin lamp cord to the motor "
                  "head: 0.25 ohm in series with the armature; and the rollers' grease has "
                  "stiffened in the cold: a breakaway peak of 1.5 N m over the door's dry "
                  "friction, fading over 0.3 rad/s of the door (9 mm/s); the current read "
                  "by a 12-bit ADC, 1/f noise on the speed"),
        spec("z09", "two", "fast", False, (cogging(12, 0.006, 0.7),
                                           sensor("current", "offset", 0.12)),
             note="the motor's 12 slots under its 2 magnets lock the rotor 12 times a turn: "
                  "a detent torque of 6 mN m (6 % of the running torque), phase 0.7 rad; and "
                  "the Hall current sensor's zero has drifted: it reads 0.12 A high"),
    ]


#: the frozen bottom seal: the bond's stiffness [N m/rad] and damping [N m s/rad] at the
#: sprocket, and the torque [N m] that breaks it (1000 N at the trolley)
ICE = (3000.0, 5.0, 30.0)
#: the current-sense trace: [ohm], [K/W], [J/K] (0.24 s), copper's coefficient [1/K]
SHUNT = (3e-3, 60.0, 4e-3, 3.93e-3)
#: the yoke's eddy currents: [H] of the armature's 1.2 mH behind them, [ohm] (0.75 ms)
EDDY = (0.6e-3, 0.8)
#: [V] the bridge's largest output (an 80 % duty of the 24 V bus)
CLIP = 19.2
#: the rail's misaligned splice: the peak drag [N m], where [rad of the sprocket's travel,
#: 0.9 m], how wide [rad, 12 mm]
SPLICE = (3.0, 30.0, 0.4)


def outside_fast() -> list[dict[str, Any]]:
    """z10-z12: effects the catalog does not contain, fast regime."""
    return [
        spec("z10", "outside", "fast", False, (outside(
            "frozen-bottom-seal", {"ice": ICE},
            {"kb_Nm_rad": ICE[0], "db_Nms_rad": ICE[1], "Tb_Nm": ICE[2],
             "form": "the door takes -(kb thd + db wd) while |kb thd + db wd| < Tb (thd its "
                     "travel from the start), nothing once the bond has broken"}),),
            note="a winter morning: the door's rubber bottom seal is frozen to the floor. The "
                 "bond holds the door at its start like a stiff spring (3000 N m/rad at the "
                 "sprocket) until the torque on it reaches 30 N m (1000 N at the trolley), "
                 "then breaks for good, at about 78 ms. A person sees the door held through "
                 "the soft start while the chain stretches to 2.5 times the declared run's "
                 "stretch: the motor's speed falls behind (252 instead of 304 rad/s at 80 ms) "
                 "and the current stays up to 5 A above the declared run's; then the seal "
                 "tears free, the door leaps ahead and the chain rings (the motor's speed "
                 "overshooting to 440 rad/s); after that the motor is the declared one. A "
                 "breakaway, but of the door's travel and its history, not of its speed"),
        spec("z11", "outside", "fast", False, (outside(
            "self-heating-current-shunt", {"shunt": SHUNT},
            {"Rsh_ohm": SHUNT[0], "Rth_K_W": SHUNT[1], "Cth_J_K": SHUNT[2],
             "a_per_K": SHUNT[3],
             "form": "reads i (1 + a T), Cth dT/dt = i^2 Rsh - T/Rth, T(0) = 0"}),),
            noise={"current": ADC_I, "speed": {"white": 0.3}},
            note="the opener's cheap controller board reads the current across a 3 mohm "
                 "copper trace instead of a manganin shunt: the trace warms by its own loss "
                 "(4 mJ/K, 60 K/W: 0.24 s) and copper's resistance rises 0.39 % per kelvin, "
                 "so the reading grows with the trace's temperature. A person sees a current "
                 "sensor gain that is not constant: a few per cent high after the soft "
                 "start's and the braking's large currents, relaxing as the trace cools; the "
                 "current read by a 12-bit ADC"),
        spec("z12", "outside", "fast", True, (outside(
            "yoke-eddy-currents", {"eddy": EDDY},
            {"L2_H": EDDY[0], "Re_ohm": EDDY[1],
             "form": "the armature's inductance is La - L2 in series with L2 || Re"}),),
            note="the motor's stator yoke is a solid steel tube, not laminated: eddy currents "
                 "in it screen part of the armature's flux from fast changes. The armature "
                 "is 0.6 mH in series with 0.6 mH shunted by 0.8 ohm (0.75 ms): the declared "
                 "1.2 mH for slow changes, 0.6 mH for fast ones. A person sees the current "
                 "jump faster than the declared inductance allows at each step of the "
                 "command and then settle with the declared time constant: an inductance "
                 "that depends on how fast the current changes"),
    ]


def outside_slow() -> list[dict[str, Any]]:
    """z13-z14: effects the catalog does not contain, slow regime."""
    return [
        spec("z13", "outside", "slow", True, (outside(
            "bridge-duty-limit", {"clip": CLIP},
            {"Umax_V": CLIP,
             "form": "the armature gets clamp(u, -Umax, Umax)"}),),
            noise={"current": ADC_I, "speed": {"white": 0.3}, "load_speed": {"white": 0.01}},
            note="the H-bridge's bootstrap gate drivers need a minimum off-time each PWM "
                 "period: its duty tops out at 80 %, 19.2 V of the 24 V bus, while the "
                 "logged command asks for up to 22 V. A person sees the motor short of the "
                 "commanded speed only while the command is above 19.2 V (by 2.8 V worth, "
                 "60 rad/s, through the opening run; by 0.8 V through the closing run), "
                 "and the declared motor everywhere else: a loss that is neither a "
                 "resistance nor a drop; the current read by a 12-bit ADC"),
        spec("z14", "outside", "slow", False, (outside(
            "rail-splice-bump", {"splice": SPLICE},
            {"Tb_Nm": SPLICE[0], "th0_rad": SPLICE[1], "wb_rad": SPLICE[2],
             "form": "the door takes -Tb exp(-((thd - th0)/wb)^2) tanh(wd/0.01), thd its "
                     "travel from the start"}),),
            noise={"current": {"white": 0.03}, "speed": {"white": 0.3},
                   "load_speed": {"white": 0.006, "pink": 0.008}},
            note="the two sections of the opener's rail are spliced 0.9 m from the closed "
                 "position with a step of a millimetre: the trolley drags over it with up to "
                 "3 N m at the sprocket (100 N) over about 2 cm of its travel, once on the "
                 "way up (about 5.0 s) and once on the way down (about 13.3 s). A person "
                 "sees a short dip of the door's and the motor's speed and a current pulse "
                 "at the same place of the travel in both directions, and the declared "
                 "motor everywhere else; 1/f noise on the door's speed"),
    ]


def record_specs() -> list[dict[str, Any]]:
    """The 14 records, each with its seed."""
    out = null_and_catalog() + outside_fast() + outside_slow()
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- sample times

def times(s: dict[str, Any]) -> np.ndarray:
    """The record's sample times [s] (even, or uneven from its seed), once; described in
    ``s["timestamps"]`` (``recordkit.record_times``)."""
    return recordkit.record_times(s, sr.REGIMES, sr.grid, 17, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-3}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-5}}),
    ("coulomb-friction:door", {"coul": {"door": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:door", {"visc": {"door": 1e-4}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-5}}),
    ("force-offset:door", {"offset": {"door": 1e-3}}),
    ("stribeck-friction:door:0.3", {"stribeck": {"door": (1e-3, 0.3)}}),
    ("stribeck-friction:door:3", {"stribeck": {"door": (1e-3, 3.0)}}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:10", {"lsat": (10.0, 0.999)}),
    ("inertia:Jd", {"p": {"Jd": P["Jd"] * 1.001}}),
    ("inertia:Jm", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jw", {"p": {"Jw": P["Jw"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
    ("sensor-delay:current", {"sensor": {"current": {"delay": 1e-6}}}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:door", lambda a, b: {"cog": {"door": [(1, a, b)]}}),
    ("unbalance:sprocket", lambda a, b: {"cog": {"sprocket": [(1, a, b)]}}),
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("cogging:rotor:12", lambda a, b: {"cog": {"rotor": [(12, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:12", lambda a, b: {"emf": [(12, a * 1e-2, b * 1e-2)]}),
)
#: each probe's sensor effects (the delay only on the current, above)
SENSOR_STEPS = (("gain", 1.001), ("offset", 1e-3))

#: across the chain: the shaft an effect on each is compared with, and the factor its size
#: takes there per kind (a torque on the rotor is N times its size on the door's side, which
#: turns 1/N times as fast; a viscous coefficient N^2 times; an angle-locked torque on the
#: door is the same on the sprocket, which turns with it on average)
ACROSS = {"rotor": ("door", {"coul": N, "offset": N, "visc": N * N}),
          "sprocket": ("door", {"coul": 1.0, "offset": 1.0, "visc": 1.0}),
          "door": ("sprocket", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` across the chain
    (``recordkit.location_entry``), after a marginal record's scaling (its parts are then
    the scaled ones)."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing every later set shares (recordkit.Plumbing): truth entries, marginal
#: scaling, the catalog's imprints an outside or marginal record is compared with, the CSV
KIT = recordkit.Plumbing(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sr, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=lambda label: 1e-4,
    marginal_sigma=MARGINAL_SIGMA, sensor_steps=SENSOR_STEPS, extra=_location_entry)
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
