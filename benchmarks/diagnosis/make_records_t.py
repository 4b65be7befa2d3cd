"""Generate the blind set ``fresh19`` of the diagnosis benchmark: records b01-b14 of motor T
(a 24 V brushed DC motor driving a three-roller peristaltic hose pump through a rigid 16:1
spur gearhead, against the hose's rolling loss, the delivery line's laminar loss and its
static pressure, with the rollers' declared occlusion ripple of order 3), some sampled evenly
and some UNEVENLY, and merge their truth into truth.json.

    python benchmarks/diagnosis/make_records_t.py              # records/b*.csv + truth.json
    python benchmarks/diagnosis/make_records_t.py --only b03,b12
    python benchmarks/diagnosis/make_records_t.py --truth-only # rewrite the b entries only

Uses simulators_t.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe [SI] (and, in the slow regime, the command ``u``
[V] that motor_t_slow.yaml reads from its own table). Even records are sampled on the
regime's grid k/fs; uneven ones, in the fast regime, on a 40 kHz grid whose every sample is
moved by a random jitter of up to 10-30 % of the interval, and in the slow regime at a
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
import simulators_t as st

RECORDS = HERE / "records"
SPLIT = "fresh19"
MOTOR = "T"
SEED0 = 19500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_t.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_t_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.03, "speed": 0.3},
         "slow": {"current": 0.03, "speed": 0.3, "load_speed": 0.02}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = st.MOTOR_T
N = P["N"]
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_t, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearhead is rigid and lossless: a torque on the
# pump is 1/N = 1/16 of it on the rotor, a viscous coefficient 1/N^2 = 1/256 of it; a
# harmonic of the pump's angle has no integer order on the rotor.

def saturation(ipar: float, ratio: float) -> Part:
    """The armature's inductance saturating with the current: Ipar [A], ratio [1]."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def viscous_pump(b: float) -> Part:
    """An extra viscous loss b [N m s/rad] on the pump shaft (accepted on the rotor at
    b / N^2)."""
    return {"visc": {"pump": b}}, {
        "effect": "viscous-friction", "target": "pump", "targets": ["pump"],
        "parameters": {"B_extra_Nms_rad": b, "form": "pump receives -b w_pump"},
        "expected": {"b": b},
        "also_accept": [{"effect": "viscous-friction", "targets": ["rotor"],
                         "expected": {"b": b / N ** 2}}]}


def offset_pump(torque: float) -> Part:
    """A constant torque [N m] the pump shaft receives (negative: a load; accepted on the
    rotor at 1/N of it)."""
    return {"offset": {"pump": torque}}, {
        "effect": "force-offset", "target": "pump", "targets": ["pump"],
        "parameters": {"T_Nm": torque, "form": "pump receives T (negative: against pumping, "
                                               "in either direction of turning)"},
        "expected": {"F": torque},
        "also_accept": [{"effect": "force-offset", "targets": ["rotor"],
                         "expected": {"F": torque / N}}]}


def unbalance_pump(amp: float, phase: float) -> Part:
    """A once-a-turn torque amp sin(angle + phase) [N m] on the pump shaft."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"pump": [(1, a, b)]}}, {
        "effect": "unbalance", "target": "pump", "targets": ["pump"], "order": 1,
        "parameters": {"order": 1, "T_Nm": amp, "phase_rad": phase,
                       "form": "pump receives T sin(1 angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["pump"], "order": 1,
                         "expected": {"a": a, "b": b}}]}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An undeclared EMF harmonic w slope sin(order th + phase) [V s/rad], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def series_resistance(r: float, regime: str) -> Part:
    """A resistance [ohm] in series with the armature (accepted inside the supply)."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": ["Ra", "La", "M"],
        "parameters": {"R_series_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor T's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return st.simulate(regime, t, fx)


spec = recordkit.spec


# ---------------------------------------------------------------------- the records

#: a 12-bit ADC over +-30 A (14.6 mA steps) on the current
ADC_I = {"white": 0.03, "quant": 0.0146}


def nulls_and_singles() -> list[dict[str, Any]]:
    """b01-b07: the null and single catalog records."""
    return [
        spec("b01", "null", "fast", False, note="white noise"),
        spec("b02", "null", "slow", True,
             noise={"current": {"white": 0.02, "ar1": [0.025, 0.85], "quant": 0.0146},
                    "speed": {"white": 0.3, "pink": 0.35},
                    "load_speed": {"white": 0.02}},
             note="coloured noise: Gauss-Markov current noise (correlation 0.85 over the mean "
                  "interval, exp(-dt/tau) over an interval dt) and a 12-bit ADC over +-30 A "
                  "(14.6 mA steps) on the current, 1/f noise on the motor's speed"),
        spec("b03", "catalog", "fast", False, (saturation(7.0, 0.5),),
             noise={"current": ADC_I, "speed": {"white": 0.3}},
             note="a motor from a cheaper batch whose stator ring is thinner: the armature's "
                  "inductance falls to half its declared value at 7 A and further beyond "
                  "(the soft start, the step down and the dynamic braking reach 9-14 A); "
                  "the current read by a 12-bit ADC"),
        spec("b04", "catalog", "slow", True, (sensor("current", "offset", 0.1),),
             note="the Hall current sensor's zero has drifted with the cabinet's "
                  "temperature: it reads 0.1 A high at any current"),
        spec("b05", "catalog", "fast", True, (viscous_pump(0.002),),
             marginal=lambda b: (viscous_pump(b),), size=0.002,
             note="the liquid is colder and a little more viscous than the delivery line's "
                  "declared laminar loss assumes (by under 2 %): an extra viscous loss on the "
                  "pump shaft, scaled to a 25 sigma signature (marginal)"),
        spec("b06", "catalog", "slow", False, (offset_pump(-0.02),),
             marginal=lambda c: (offset_pump(c),), size=-0.02,
             noise={"current": {"white": 0.03}, "speed": {"white": 0.3, "pink": 0.3},
                    "load_speed": {"white": 0.02}},
             note="the receiving tank stands higher than when the line was declared (by "
                  "about 10 cm of water, 1 kPa): a constant extra static pressure on the "
                  "pump's displacement, a torque against pumping that also pushes the "
                  "suck-back, scaled to a 25 sigma signature (marginal); 1/f noise on the "
                  "motor's speed"),
        spec("b07", "catalog", "slow", False, (unbalance_pump(0.15, 0.9),),
             noise={"current": {"white": 0.02, "ar1": [0.02, 0.8]},
                    "speed": {"white": 0.3}, "load_speed": {"white": 0.02}},
             note="one plastic roller was replaced by a steel one with a heavier bracket "
                  "(0.3 kg more at 50 mm) on the horizontal pump shaft: a gravity torque "
                  "of 0.15 N m once a turn of the pump, phase 0.9 rad; Gauss-Markov noise "
                  "on the current"),
    ]


def pairs() -> list[dict[str, Any]]:
    """b08, b09: two catalog effects at once."""
    return [
        spec("b08", "two", "fast", True, (emf_harmonic(18, 1.0e-3, 0.5),
                                          series_resistance(0.18, "fast")),
             noise={"current": ADC_I, "speed": {"white": 0.3}},
             note="the armature's 9 slots and commutator bars ripple the back-EMF 18 times a "
                  "turn (slope 1 mV s/rad, 0.4 V at full speed, phase 0.5 rad), undeclared; "
                  "and a corroded crimp terminal on the motor lead adds 0.18 ohm in series "
                  "with the armature; the current read by a 12-bit ADC"),
        spec("b09", "two", "slow", False, (viscous_pump(0.015),
                                           sensor("load_speed", "offset", 0.35)),
             noise={"current": {"white": 0.03}, "speed": {"white": 0.3},
                    "load_speed": {"white": 0.015, "pink": 0.015}},
             note="the pump now doses a 40 % glycol mix: the delivery line's laminar loss is "
                  "more than doubled (+0.015 N m s/rad on the pump shaft); and the pump "
                  "head's tachometer (a frequency-to-voltage converter) reads 0.35 rad/s high "
                  "at any speed; 1/f noise on the pump head's speed"),
    ]


#: the armature's slot-modulated inductance: depth [1], order [1 / turn], phase [rad]
LRIP = (0.06, 18, 0.3)
#: [V] the bridge's DC link the current's shunt sits on
VBUS = 24.0
#: the seized roller: extra drag [N m], its window's centre on the pump's angle [rad], the
#: window's half-width [rad] (75 degrees, the track's wrap), the window's edge [1]
SEIZED = (0.3, 1.0, 1.309, 0.08)
#: [V] the duty register's step: 24 V in 64 steps (6 bits)
DUTY_Q = 0.375
#: the bottle: displacement [m^3/rad], the headspace's pressure [Pa] and volume [m^3]
VESSEL = (3.18e-6, 101325.0, 0.8e-3)


def outside_fast() -> list[dict[str, Any]]:
    """b10, b11: effects the catalog does not contain, fast regime."""
    return [
        spec("b10", "outside", "fast", False, (outside(
            "slot-modulated-inductance", {"lrip": LRIP},
            {"eps": LRIP[0], "order": LRIP[1], "phase_rad": LRIP[2],
             "form": "L(th) = La (1 + eps cos(order th + phase)); the loop takes "
                     "d(L(th) i)/dt, the rotor the torque i^2/2 dL/dth"}),),
            note="the armature's inductance is not constant: the rotor's 9 slots change the "
                 "magnetic path as the commutator switches coils, 18 times a turn, by +-6 % "
                 "of the declared 1.1 mH (the energy-consistent reluctance torque with it). A "
                 "person sees a current ripple at 18 times the rotor's speed whose size grows "
                 "with the current times the speed, largest at full speed under load and in "
                 "the braking spikes, and none when either is zero; the speed all but "
                 "untouched"),
        spec("b11", "outside", "fast", True, (outside(
            "dc-link-shunt-current", {"busread": VBUS},
            {"Vbus_V": VBUS, "form": "reads i u / Vbus, u the bridge's mean output"}),),
            noise={"current": ADC_I, "speed": {"white": 0.3}},
            note="the drive's current is measured on its DC-link shunt, not in the motor's "
                 "lead: averaged over the PWM period the reading is the bus current, the "
                 "armature current times the duty u/24 V. A person sees the declared current "
                 "at 24 V, half of it at 12 V, nothing at 0 V while the armature brakes, and "
                 "a positive reading while the motor runs backwards; the speed untouched; the "
                 "current read by a 12-bit ADC"),
    ]


def outside_slow() -> list[dict[str, Any]]:
    """b12-b14: effects the catalog does not contain, slow regime."""
    return [
        spec("b12", "outside", "slow", True, (outside(
            "seized-roller-bearing", {"seized": SEIZED},
            {"Ts_Nm": SEIZED[0], "centre_rad": SEIZED[1], "half_width_rad": SEIZED[2],
             "edge": SEIZED[3],
             "form": "pump takes -Ts tanh(w/0.01) 0.5 (1 + tanh((cos(th - centre) - "
                     "cos(half))/edge)), th the pump's angle"}),),
            noise={"current": {"white": 0.02, "ar1": [0.02, 0.85]}, "speed": {"white": 0.3},
                   "load_speed": {"white": 0.02}},
            note="one roller's needle bearing has seized: while that roller presses the hose "
                 "(150 degrees of each turn of the pump) it skids instead of rolling and "
                 "drags the pump with 0.3 N m more, against the pump's motion. A person sees "
                 "a friction that comes and goes once a turn of the pump, on for 150 degrees "
                 "and off for 210, whose sign follows the direction of turning (the suck-back "
                 "too); Gauss-Markov noise on the current"),
        spec("b13", "outside", "slow", False, (outside(
            "coarse-duty-register", {"duty_q": DUTY_Q},
            {"q_V": DUTY_Q, "form": "the armature gets q round(u/q), u the logged command"}),),
            noise={"current": {"white": 0.03}, "speed": {"white": 0.3, "pink": 0.3},
                   "load_speed": {"white": 0.02}},
            note="the pump driver takes its duty through a 6-bit register: the armature gets "
                 "the logged command rounded to 24 V/64 = 0.375 V steps. A person sees the "
                 "current step by 0.42 A and relax every 11-23 ms along the ramps (a "
                 "staircase), and the speed held about 2.2 rad/s off at each level: 19.875 V "
                 "for 20 V, 8.625 V for 8.5 V, -13.125 V for -13 V; 1/f noise on the motor's "
                 "speed"),
        spec("b14", "outside", "slow", False, (outside(
            "blocked-bottle-vent", {"vessel": VESSEL},
            {"D_m3_rad": VESSEL[0], "p0_Pa": VESSEL[1], "V0_m3": VESSEL[2],
             "form": "pump takes -D p0 D th / (V0 - D th), th the pump's angle from the "
                     "start"}),),
            note="the receiving bottle's vent filter is blocked: the 0.8 L of air above the "
                 "liquid is compressed as the pump fills it (isothermal, 20 mL a turn), so "
                 "the delivery pressure rises with the volume pumped, by 0.46 bar at the end "
                 "of the dose (250 mL), and falls back to 0.31 bar with the suck-back. A person sees "
                 "a load that grows with the pump's travel, not with time or speed, and stays "
                 "while the pump stands"),
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
    return recordkit.record_times(s, st.REGIMES, st.grid, 19, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
#: (the rotor's copies of the pump's frictions and offsets are the same columns scaled)
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-3}),
    ("coulomb-friction:pump", {"coul": {"pump": 1e-3}}),
    ("viscous-friction:pump", {"visc": {"pump": 1e-4}}),
    ("force-offset:pump", {"offset": {"pump": 1e-3}}),
    ("stribeck-friction:pump:0.3", {"stribeck": {"pump": (1e-3, 0.3)}}),
    ("stribeck-friction:pump:3", {"stribeck": {"pump": (1e-3, 3.0)}}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:10", {"lsat": (10.0, 0.999)}),
    ("inertia:Jm", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jp", {"p": {"Jp": P["Jp"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder);
#: cogging:pump:3 re-tunes the declared occlusion ripple
HARMONIC_EFFECTS = (
    ("unbalance:pump", lambda a, b: {"cog": {"pump": [(1, a, b)]}}),
    ("cogging:pump:3", lambda a, b: {"cog": {"pump": [(3, a, b)]}}),
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("cogging:rotor:18", lambda a, b: {"cog": {"rotor": [(18, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:18", lambda a, b: {"emf": [(18, a * 1e-2, b * 1e-2)]}),
)
#: the harmonic term the netlist declares (the rollers' occlusion ripple)
DECLARED = ({"effect": "cogging", "target": "pump", "order": 3},)

#: the plumbing every later set shares (recordkit.Plumbing): truth entries, marginal
#: scaling, the catalog's imprints an outside or marginal record is compared with, the CSV;
#: each probe's sensor effects are its gain, its offset and its (pure) delay
KIT = recordkit.Plumbing(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=st, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=lambda label: 1e-4, marginal_sigma=MARGINAL_SIGMA, declared=DECLARED)
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
