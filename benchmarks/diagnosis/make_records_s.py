"""Generate the blind set ``fresh18`` of the diagnosis benchmark: records a01-a14 of motor S
(a 12 V brushed DC motor driving a motorised camera slider through a rigid 12:1 planetary
gearhead, a GT2 pulley and a compliant timing belt; the carriage and an 8 kg camera on a
rail tilted 20 degrees), some sampled evenly and some UNEVENLY, and merge their truth into
truth.json.

    python benchmarks/diagnosis/make_records_s.py              # records/a*.csv + truth.json
    python benchmarks/diagnosis/make_records_s.py --only a03,a12
    python benchmarks/diagnosis/make_records_s.py --truth-only # rewrite the a entries only

Uses simulators_s.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe [SI] (and, in the slow regime, the command ``u``
[V] that motor_s_slow.yaml reads from its own table). Even records are sampled on the
regime's grid k/fs; uneven ones, in the fast regime, on a 25 kHz grid whose every sample is
moved by a random jitter of up to 10-30 % of the interval, and in the slow regime at a
logger's irregular intervals (0.6-1.4 times the mean of 5 ms) with a few samples dropped.
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
import simulators_s as ss

RECORDS = HERE / "records"
SPLIT = "fresh18"
MOTOR = "S"
SEED0 = 18500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_s.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_s_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.02, "speed": 0.25},
         "slow": {"current": 0.02, "speed": 0.25, "load_speed": 0.01}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = ss.MOTOR_S
N = P["N"]
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_s, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearhead is rigid and lossless: a torque on the
# rotor is N = 12 times as large on the pulley, a viscous coefficient N^2 = 144 times; the
# carriage sits behind the compliant belt and has no such equal.

def cogging(order: int, amp: float, phase: float) -> Part:
    """The rotor's detent torque amp sin(order angle + phase) [N m] (accepted on the pulley
    at order N times and N times the size)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["pulley"],
                         "order": int(order * N), "expected": {"a": a * N, "b": b * N}}]}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s] (a delay a pure transport
    delay)."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def source_resistance(r: float, regime: str) -> Part:
    """A resistance [ohm] inside the supply (accepted in series with the armature)."""
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[regime], "targets": [SOURCE[regime]],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": ["Ra", "La", "M"],
                         "expected": {"R": r}}]}


def brush_drop(vb: float) -> Part:
    """A brush contact drop Vb tanh(i / 1 mA) [V] in series with the armature."""
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


def warmup(rise: float, tau: float) -> Part:
    """The armature's resistance R (1 + rise (1 - exp(-t / tau))) [1, s]."""
    return {"warmup": (rise, tau)}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"rise": rise, "tau_s": tau,
                       "form": "Ra (1 + rise (1 - exp(-t/tau)))"},
        "expected": {"rise": rise, "tau": tau}}


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad of the pulley] in the belt (ElastoBacklash)."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap, "form": "no belt torque while |twist| < gap/2, "
                                               "c (twist -+ gap/2) + d w_rel in contact"},
        "expected": {"gap": gap}}


def coulomb_carriage(c: float) -> Part:
    """An extra dry friction c [N m] on the carriage (at the pulley)."""
    return {"coul": {"carriage": c}}, {
        "effect": "coulomb-friction", "target": "carriage", "targets": ["carriage"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(w_carriage/0.01) against the carriage"},
        "expected": {"c": c}}


def stribeck_carriage(s: float, ws: float) -> Part:
    """A breakaway peak s [N m] with Stribeck speed ws [rad/s] over the carriage's dry
    friction."""
    return {"stribeck": {"carriage": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "carriage", "targets": ["carriage"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "carriage takes s exp(-(w/ws)^2) tanh(w/0.01) over the "
                               "declared Tf tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor S's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return ss.simulate(regime, t, fx)


spec = recordkit.spec


# ---------------------------------------------------------------------- the records

#: a 12-bit ADC over +-25 A (12.2 mA steps) on the current
ADC_I = {"white": 0.02, "quant": 0.0122}


def null_and_catalog() -> list[dict[str, Any]]:
    """a01-a09: the null, catalog and two-effect records."""
    return [
        spec("a01", "null", "fast", False, note="white noise"),
        spec("a02", "null", "slow", True,
             noise={"current": {"white": 0.012, "ar1": [0.02, 0.9], "quant": 0.0122},
                    "speed": {"white": 0.25, "pink": 0.3},
                    "load_speed": {"white": 0.01}},
             note="coloured noise: Gauss-Markov current noise (correlation 0.9 over the mean "
                  "interval, exp(-dt/tau) over an interval dt) and a 12-bit ADC over +-25 A "
                  "(12.2 mA steps) on the current, 1/f noise on the motor's speed (a sum of "
                  "Gauss-Markov processes an octave apart)"),
        spec("a03", "catalog", "fast", True, (sensor("speed", "delay", 6e-4),),
             note="the motor's speed reaches the logger over the slider controller's CAN "
                  "bus: a pure transport latency of 600 us (the encoder's sample is queued "
                  "and sent a fixed 15 frames later), the reading y(t - 600 us), unfiltered"),
        spec("a04", "catalog", "fast", False, (backlash(0.02),),
             noise={"current": ADC_I, "speed": {"white": 0.25}},
             note="the belt was fitted slack: its teeth sit loose in the pulley's grooves, a "
                  "total play of 0.02 rad of the pulley (0.25 mm of the belt) that opens when "
                  "the belt's torque reverses (the braking and the run back down); the "
                  "current read by a 12-bit ADC"),
        spec("a05", "catalog", "slow", False, (coulomb_carriage(0.02),),
             marginal=lambda c: (coulomb_carriage(c),), size=0.02,
             note="grit from the location's sand in the carriage's linear bearings: an extra "
                  "dry friction on the carriage, scaled to a 25 sigma signature (marginal)"),
        spec("a06", "catalog", "fast", False, (brush_drop(0.1),),
             marginal=lambda v: (brush_drop(v),), size=0.1,
             noise={"current": ADC_I, "speed": {"white": 0.25}},
             note="the motor's brushes were just replaced and are not yet bedded in: a "
                  "contact drop of the sign of the current over the declared resistance, "
                  "scaled to a 25 sigma signature (marginal: a few mV); the current read by "
                  "a 12-bit ADC"),
        spec("a07", "catalog", "slow", True, (warmup(-0.15, 6.0),),
             noise={"current": {"white": 0.015, "ar1": [0.012, 0.8]},
                    "speed": {"white": 0.25}, "load_speed": {"white": 0.01}},
             note="the declared Ra was measured hot, right after a stall test; this move too "
                  "starts right after the carriage was held stalled against the end stop, "
                  "the winding about 45 K above the housing, and the winding cools into the "
                  "housing as the carriage moves: its resistance falls by 15 % with the "
                  "winding's 6 s thermal time constant; Gauss-Markov noise on the current"),
        spec("a08", "two", "fast", False, (cogging(10, 0.004, 1.1),
                                           sensor("current", "gain", 1.03)),
             note="the cheap motor's 5 slots under its 2 magnets lock the rotor 10 times a "
                  "turn: a detent torque of 4 mN m (11 % of the running torque), phase "
                  "1.1 rad; and the Hall current sensor reads 3 % high (its gain not "
                  "trimmed)"),
        spec("a09", "two", "slow", True, (source_resistance(0.15, "slow"),
                                          stribeck_carriage(0.12, 0.5)),
             noise={"current": ADC_I, "speed": {"white": 0.25},
                    "load_speed": {"white": 0.006, "pink": 0.006}},
             note="the slider is fed from a camera V-mount battery through a 3 m coiled "
                  "cable: 0.15 ohm in the supply; and the linear bearings' grease has "
                  "stiffened on a cold night shoot: a breakaway peak of 0.12 N m over the "
                  "carriage's dry friction, fading over 0.5 rad/s (6 mm/s) of the carriage; "
                  "the current read by a 12-bit ADC, 1/f noise on the carriage's speed"),
    ]


#: the current-sense amplifier's Sallen-Key anti-alias filter: corner [Hz], damping [1]
AA = (800.0, 0.7071)
#: the gearhead's two planetary stages' efficiency [1]
ETA = 0.85
#: an aged 10-cell NiMH pack: EMF [V], resistance [ohm], polarisation [ohm] || [F] (3 s)
BATT = (12.0, 0.35, 0.25, 12.0)
#: the rubber end stop: where [rad of the pulley's travel, 0.99 m], its stiffness
#: [N m/rad, 40 N/mm at the belt], its Hunt-Crossley damping [N m s/rad^2]
BUMPER = (78.0, 6.45, 3.0)
#: [s] the encoder speed estimate's window
MAVG = 2e-3


def outside_fast() -> list[dict[str, Any]]:
    """a10, a11, a14: effects the catalog does not contain, fast regime."""
    return [
        spec("a10", "outside", "fast", False, (outside(
            "current-antialias-filter", {"aa": AA},
            {"fc_Hz": AA[0], "zeta": AA[1],
             "form": "reads i through 1/(s^2/wn^2 + 2 zeta s/wn + 1), wn = 2 pi fc"}),),
            note="the drive's current-sense amplifier has a second-order Butterworth "
                 "(Sallen-Key) anti-alias filter at 800 Hz ahead of its ADC: the current is "
                 "read through it (damping 0.707, 4.3 % overshoot to a step). A person sees "
                 "a current that lags the declared one by about 0.28 ms at low frequency, "
                 "its fast edges after the command's 1 ms steps rounded off and overshooting, "
                 "and the speed untouched: a sensor lag that is not a pure delay"),
        spec("a11", "outside", "fast", True, (outside(
            "gearhead-efficiency", {"eta": ETA},
            {"eta": ETA,
             "form": "the pulley receives eta N tau_a while the motor drives the gearhead "
                     "(tau_a w >= 0), N tau_a / eta while it is driven back; tau_a the "
                     "torque the rotor puts into it"}),),
            noise={"current": ADC_I, "speed": {"white": 0.25}},
            note="the two-stage planetary gearhead is declared lossless but passes only 85 % "
                 "of the power: its teeth's sliding friction grows with the torque they "
                 "carry. A person sees a loss that scales with the load, not with the speed "
                 "or its sign: more current than declared while the motor lifts the camera, "
                 "a weaker regenerative braking while the camera drives the motor back, and "
                 "the gear's loss switching side where the power reverses; the current read "
                 "by a 12-bit ADC"),
        spec("a14", "outside", "fast", False, (outside(
            "windowed-speed-estimate", {"mavg": MAVG},
            {"T_s": MAVG, "form": "reads (th(t) - th(t - T))/T, th the rotor's angle"}),),
            note="the logged speed is not the encoder's instantaneous speed but the drive's "
                 "M-method estimate: the angle counted over a sliding 2 ms window divided by "
                 "the window (a high-resolution encoder, so no count steps). A person sees a "
                 "speed that lags by about 1 ms and whose corners are cut to straight "
                 "2 ms ramps (the belt's 23 Hz ringing all but unchanged): a boxcar filter, "
                 "neither a pure delay nor a first-order lag; the current untouched"),
    ]


def outside_slow() -> list[dict[str, Any]]:
    """a12, a13: effects the catalog does not contain, slow regime."""
    return [
        spec("a12", "outside", "slow", False, (outside(
            "battery-sag-through-duty", {"batt": BATT},
            {"E0_V": BATT[0], "R0_ohm": BATT[1], "R1_ohm": BATT[2], "C1_F": BATT[3],
             "form": "armature gets d (E0 - R0 d i - v1), d = u/E0, "
                     "C1 dv1/dt = d i - v1/R1"}),),
            noise={"current": {"white": 0.02}, "speed": {"white": 0.25, "pink": 0.2},
                   "load_speed": {"white": 0.01}},
            note="the bridge runs from an aged 10-cell NiMH pack (12 V) and the logged command "
                 "is its duty times 12 V: the pack's 0.35 ohm and its polarisation (0.25 ohm "
                 "|| 12 F, 3 s) sag the bus under load, and the armature gets the duty times "
                 "the sagging bus. A person sees a supply resistance whose drop grows with the "
                 "square of the duty and keeps a 3 s memory of the current (the speed "
                 "recovering slowly after the load falls); 1/f noise on the motor's speed"),
        spec("a13", "outside", "slow", True, (outside(
            "rubber-end-stop", {"bumper": BUMPER},
            {"th0_rad": BUMPER[0], "kb_Nm_rad": BUMPER[1], "db_Nms_rad2": BUMPER[2],
             "form": "the carriage takes -max(0, (thc - th0)(kb + db wc)) while thc > th0, "
                     "thc its travel from the start"}),),
            noise={"current": ADC_I, "speed": {"white": 0.25}, "load_speed": {"white": 0.01}},
            note="the slider's top end stop, a rubber bumper, was set 4 cm lower than the "
                 "operator's move assumed: during the 2.5 V creep the carriage runs into it "
                 "(at about 6.43 s, 65 mm/s) and is pressed 2.6 mm into the rubber until the "
                 "command falls (Hunt-Crossley contact: 40 N/mm, damping growing with the "
                 "indentation). A person sees the carriage and the motor stall, the current "
                 "rise to the 2.5 V stall current of 5 A, and the carriage pushed back off "
                 "the stop when the command ends (at about 7.07 s); the declared motor "
                 "everywhere else; the current read by a 12-bit ADC"),
    ]


def record_specs() -> list[dict[str, Any]]:
    """The 14 records in id order, each with its seed."""
    out = sorted(null_and_catalog() + outside_fast() + outside_slow(),
                 key=lambda s: s["id"])
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- sample times

def times(s: dict[str, Any]) -> np.ndarray:
    """The record's sample times [s] (even, or uneven from its seed), once; described in
    ``s["timestamps"]`` (``recordkit.record_times``)."""
    return recordkit.record_times(s, ss.REGIMES, ss.grid, 18, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-3}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-5}}),
    ("coulomb-friction:carriage", {"coul": {"carriage": 1e-4}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:carriage", {"visc": {"carriage": 1e-5}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-5}}),
    ("force-offset:carriage", {"offset": {"carriage": 1e-4}}),
    ("stribeck-friction:carriage:0.3", {"stribeck": {"carriage": (1e-4, 0.3)}}),
    ("stribeck-friction:carriage:3", {"stribeck": {"carriage": (1e-4, 3.0)}}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:10", {"lsat": (10.0, 0.999)}),
    ("inertia:Jc", {"p": {"Jc": P["Jc"] * 1.001}}),
    ("inertia:Jm", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jg", {"p": {"Jg": P["Jg"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:carriage", lambda a, b: {"cog": {"carriage": [(1, a, b)]}}),
    ("unbalance:pulley", lambda a, b: {"cog": {"pulley": [(1, a, b)]}}),
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("cogging:rotor:10", lambda a, b: {"cog": {"rotor": [(10, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:10", lambda a, b: {"emf": [(10, a * 1e-2, b * 1e-2)]}),
)

#: across the belt: the shaft an effect on each is compared with, and the factor its size
#: takes there per kind (a torque on the rotor is N times its size on the carriage's side,
#: which turns 1/N times as fast; a viscous coefficient N^2 times; an angle-locked torque on
#: the carriage is the same on the pulley, which turns with it on average)
ACROSS = {"rotor": ("carriage", {"coul": N, "offset": N, "visc": N * N}),
          "pulley": ("carriage", {"coul": 1.0, "offset": 1.0, "visc": 1.0}),
          "carriage": ("pulley", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` across the belt
    (``recordkit.location_entry``), after a marginal record's scaling (its parts are then
    the scaled ones)."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing every later set shares (recordkit.Plumbing): truth entries, marginal
#: scaling, the catalog's imprints an outside or marginal record is compared with, the CSV;
#: each probe's sensor effects are its gain, its offset and its (pure) delay
KIT = recordkit.Plumbing(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=ss, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=lambda label: 1e-4,
    marginal_sigma=MARGINAL_SIGMA, extra=_location_entry)
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
