"""Generate the blind set ``fresh32`` of the diagnosis benchmark: records aj01-aj14 of motor AG
(a 12 V brushed DC motor in a car's electric parking brake, a motor-on-caliper actuator on an
end-of-line test bench: a rigid 100:1 belt and planetary gearbox, an elastomer coupling, a
torsional compliance, to a self-locking spindle that pushes the nut and the piston across the
pads' air gap into a progressive clamp, the thread's friction growing with the clamp), some
sampled evenly and some UNEVENLY, three of them giving the diagnosis ONE probe only, and merge
their truth into truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_ag.py                # records/aj*.csv + truth.json
    python benchmarks/diagnosis/make_records_ag.py --only aj03,aj12
    python benchmarks/diagnosis/make_records_ag.py --truth-only   # rewrite the aj entries only

Uses simulators_ag.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_ag_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the catalog imprints it is compared with are computed on that probe
alone (``OneProbe``). Even records are sampled on the regime's grid k/fs; uneven ones, in the
fast regime, on a 25 kHz grid whose every sample is moved by a random jitter of up to 10-30 %
of the interval, and in the slow regime at a logger's irregular intervals (0.6-1.4 times the
mean of 5 ms) with a few samples dropped. Each uneven record has its own times (from its
seed), and the motor is simulated at those very times (``t_eval``), never interpolated.
truth.json is merged under an exclusive lock (recordkit.merge). Nobody ran the diagnosis on
these records.
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
import simulators_ag as sa

RECORDS = HERE / "records"
SPLIT = "fresh32"
MOTOR = "AG"
SEED0 = 32500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_ag_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_ag_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.05, "speed": 1.0},
         "slow": {"current": 0.03, "speed": 0.8, "load_speed": 0.01}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AG
N = P["N"]
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_ag, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearbox is rigid and lossless as declared: a torque
# on the body ``hub`` (the output carrier) is 1/N = 1/100 of it on the rotor, and the carrier
# turns with the rotor. The spindle lies behind the elastomer coupling (compliant): an effect
# on it has no exact equal on the carrier.

def series_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] in series with the armature."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": LOOP,
        "parameters": {"R_series_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


def brush_drop(vb: float) -> Part:
    """A brush contact drop Vb tanh(i / 1 mA) [V] in series with the armature."""
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


def warmup(rise: float, tau: float) -> Part:
    """The winding's resistance settling: R (1 + rise (1 - exp(-t / tau))) (rise < 0: it
    cools)."""
    return {"warmup": (rise, tau)}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + rise*(1 - exp(-t/tau)))", "rise": rise,
                       "tau_s": tau},
        "expected": {"rise": rise, "tau": tau}}


def inductance(dl: float) -> Part:
    """The armature's inductance off by a factor 1 + ``dl`` (a correction of La's L)."""
    return {"p": {"L": P["L"] * (1.0 + dl)}}, {
        "effect": "inductance", "target": "La", "targets": ["La"], "correction": True,
        "parameters": {"L_true_H": P["L"] * (1.0 + dl), "dL": dl},
        "expected": {"dL": dl}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def cogging_rotor(order: int, amp: float, phase: float) -> Part:
    """A detent torque amp sin(order th + phase) [N m] on the rotor (accepted on the carrier
    at the order order N and the amplitude amp N)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["hub"], "order": round(order * N),
                         "expected": {"a": a * N, "b": b * N}}]}


def unbalance_rotor(amp: float, phase: float) -> Part:
    """A once-per-turn torque amp sin(th + phase) [N m] on the rotor (accepted as a cogging
    of order 1 on the rotor, and of order N on the carrier at amp N)."""
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


def viscous_spindle(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the spindle (behind the coupling)."""
    return {"visc": {"spindle": b}}, {
        "effect": "viscous-friction", "target": "spindle", "targets": ["spindle"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b ws against the spindle"},
        "expected": {"b": b}}


def offset_spindle(f: float) -> Part:
    """A constant torque ``f`` [N m] on the spindle (behind the coupling; f < 0: towards
    the release)."""
    return {"offset": {"spindle": f}}, {
        "effect": "force-offset", "target": "spindle", "targets": ["spindle"],
        "parameters": {"T_Nm": f, "form": "the spindle receives a constant T (T < 0: turning "
                                          "it towards the release)"},
        "expected": {"F": f}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AG's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sa.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sa.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the actuator ECU's current sense: a 12-bit ADC over +-50 A (24.4 mA steps)
ADC_STEP = 100.0 / 4096


def nulls() -> list[dict[str, Any]]:
    """aj01, aj02: the null records."""
    return [
        spec("aj01", "null", "slow", True,
             noise={"current": {"white": 0.015, "ar1": [0.03, 0.85], "quant": ADC_STEP},
                    "speed": {"white": 0.8, "pink": 1.5},
                    "load_speed": {"white": 0.01}},
             note="the bench logger's record on its irregular clock; the current with "
                  "Gauss-Markov noise (correlation 0.85 over the mean interval, 30 mA: the "
                  "bridge's switching hash through the shunt amplifier) on white noise, read "
                  "by the ECU's 12-bit ADC (24.4 mA steps); the motor encoder's speed with 1/f "
                  "noise (white noise shaped by 1/sqrt(f), 1.5 rad/s) on white noise; the "
                  "spindle encoder's speed with white noise"),
        spec("aj02", "null", "fast", False,
             noise={"current": {"white": 0.04, "pink": 0.06, "quant": ADC_STEP},
                    "speed": {"white": 1.0, "ar1": [1.5, 0.95]}},
             note="the bench's even 25 kHz acquisition of the current and the motor encoder's "
                  "speed; the current read by the ECU's 12-bit ADC with the shunt amplifier's "
                  "1/f noise (60 mA) on white noise, the speed with Gauss-Markov noise "
                  "(correlation 0.95 over the interval, 1.5 rad/s: the encoder's speed "
                  "filter) on white noise"),
    ]


def singles() -> list[dict[str, Any]]:
    """aj03-aj07, aj10: one catalog effect each."""
    return [
        spec("aj03", "catalog", "fast", True, (series_resistance(0.06, "fast"),),
             note="a fretted, tin-plated terminal in the actuator's two-pin connector (the "
                  "caliper shakes on the axle): 60 mOhm in series with the armature, 17 % of "
                  "the declared Ra; the inrush, the stall current and the braking current are "
                  "lower, the run slower"),
        spec("aj04", "catalog", "slow", False, (brush_drop(0.3),),
             marginal=lambda v: (brush_drop(v),), size=0.3,
             note="the motor's brushes from a batch with a harder carbon grade: a contact "
                  "drop Vb tanh(i/1 mA) in series with the armature, scaled to a 25 sigma "
                  "signature (marginal)"),
        spec("aj05", "catalog", "fast", False, (cogging_rotor(10, 2e-3, 0.9),),
             marginal=lambda a: (cogging_rotor(10, a, 0.9),), size=2e-3,
             probes=("speed",),
             note="a bench log of the motor encoder's speed alone; a replacement motor from "
                  "a second source (2 poles, 10 slots) whose ferrite arcs were ground shorter: "
                  "a detent torque of order 10 on the rotor, phase 0.9, scaled to a 25 sigma "
                  "signature (marginal)"),
        spec("aj06", "catalog", "slow", True, (viscous_spindle(0.15),),
             note="a winter test: the actuator soaked at -30 C in the bench's climate chamber, "
                  "the spindle's and the nut's grease stiff: an extra viscous friction of "
                  "0.15 N m s/rad on the spindle (three times the declared Bs); every run of "
                  "the nut is slower and draws more current"),
        spec("aj07", "catalog", "fast", True, (sensor("current", "offset", 0.15),),
             probes=("current",), noise={"current": {"white": 0.05, "quant": ADC_STEP}},
             note="a bench log of the current alone (the ECU's 12-bit ADC); the ECU's "
                  "current-sense amplifier was not zeroed at the start of the test: the "
                  "current reads 0.15 A high, a sensor offset"),
        spec("aj10", "catalog", "slow", False, (offset_spindle(-0.4),),
             note="the bench's manual-release adaptor was left on the spindle's back end: its "
                  "spiral spring, pre-wound many turns, turns the spindle towards the release "
                  "with a nearly constant 0.4 N m over the nut's 0.36 turn (a constant torque "
                  "of -0.4 N m on the spindle); the apply is slower, the release faster, the "
                  "hold's creep back quicker"),
    ]


def pairs() -> list[dict[str, Any]]:
    """aj08, aj09: two catalog effects at once."""
    return [
        spec("aj08", "two", "slow", True, (warmup(-0.12, 4.0), unbalance_rotor(3e-3, 1.1)),
             note="the log began right after a series of stalled applies: the winding, hot, "
                  "cools into the stator, its resistance R (1 - 0.12 (1 - exp(-t/4 s))) (a "
                  "resistance drift, 12 % down to the housing's temperature); and the motor's "
                  "belt pulley was pressed on 0.2 mm off centre: the belt's tension gives the "
                  "rotor a once-per-turn torque of 3 mN m (an unbalance, phase 1.1)"),
        spec("aj09", "two", "fast", False, (inductance(-0.3), sensor("speed", "gain", 0.96)),
             note="a replacement motor from a second source with a shorter armature stack: its "
                  "inductance is 30 % below the declared La (0.14 mH); and the bench's encoder "
                  "input was set for 500 lines while the encoder has 480: the speed reads 4 % "
                  "low, a sensor gain of 0.96"),
    ]


#: hot pads creeping under the clamp: the creep's viscosity Dc [N m s/rad, spindle angle]
CREEP = 250.0
#: the bridge's reverse-polarity FET left off, its body diode: n Vt [V] and Is [A]
DIODE = (0.067, 6e-5)
#: a turning disc's thickness variation in a dynamic apply: the gap's swing d [rad of the
#: spindle] at the wheel's turning frequency f [Hz]
DTV = (0.04, 3.0)
#: the piston knocked back into its bore: the nut's extra travel to it [rad of the spindle]
KNOCK = 0.5


def outside_records() -> list[dict[str, Any]]:
    """aj11-aj14: effects the catalog does not contain."""
    return outside_pads() + outside_drive()


def outside_pads() -> list[dict[str, Any]]:
    """aj11, aj13: the pads' creep and the disc's thickness variation (the slow regime)."""
    return [
        spec("aj11", "outside", "slow", True, (outside(
            "hot-pad-creep", {"creep": CREEP},
            {"Dc_Nms_rad": CREEP,
             "form": "the clamp's law is Tc (exp((ths - z - thg)/thc) - exp(-thg/thc)), the "
                     "pads' set z (in the spindle's angle, from 0) flowing at dz/dt = "
                     "Tcl/Dc under the clamp and staying when the clamp is released: the hot "
                     "friction material creeps"}),),
            note="the test followed a series of hot stops on the bench's dynamometer and the "
                 "pads' friction material creeps under the clamp: the clamp relaxes 10 % over "
                 "the first hold (5.0 to 4.5 N m of the clamp's torque, 21 to 19 kN) where "
                 "the declared model loses 2.5 % (the thread's regularised creep), and the pads keep their set after the "
                 "release; a person sees the first apply as declared, the re-clamp turning "
                 "the nut further (the spindle up to 4 rad/s faster than declared, the "
                 "current 0.4 A lower as it breaks away), and the second apply meeting the "
                 "pads later (its current 0.64 A lower at its cut, the motor 19 rad/s "
                 "faster); close to a weaker clamp or a friction on the spindle, but one that "
                 "grows with the time spent clamped"),
        spec("aj13", "outside", "slow", False, (outside(
            "disc-thickness-variation-dynamic-apply", {"dtv": DTV},
            {"d_rad": DTV[0], "f_Hz": DTV[1], "gap_swing_um": DTV[0] * 1.5e3 / (2 * math.pi),
             "form": "the pads' gap is thg + d sin(2 pi f t) in the clamp's law and in the "
                     "thread's friction: a disc whose thickness varies once a turn, turning "
                     "at f (the wheel's, not the spindle's angle)"}),),
            note="a dynamic apply on the bench's dynamometer, the disc turning at 3 Hz (the "
                 "wheel at about 22 km/h), and the disc has worn unevenly: its thickness "
                 "varies once a turn, the pads' gap by +-9.6 um (0.04 rad of the spindle); a "
                 "person sees nothing before the pads touch, then the current's rise and the "
                 "speeds' fall in each apply wobbling at 3 Hz (up to 0.55 A, 16 rad/s of the "
                 "motor), the re-clamp breaking away early or late, the clamp breathing by "
                 "+-12 % while the nut holds; close to a torque ripple locked to time, but "
                 "only while the pads bear, and scaled by the clamp"),
    ]


def outside_drive() -> list[dict[str, Any]]:
    """aj12, aj14: the bridge's body diode and the piston's knock-back (the fast regime)."""
    return [
        spec("aj12", "outside", "fast", False, (outside(
            "reverse-polarity-body-diode", {"diode": DIODE},
            {"nVt_V": DIODE[0], "Is_A": DIODE[1],
             "form": "the loop takes tanh(u/0.05 V) nVt ln(1 + (sqrt(i^2 + 1 mA^2) - 1 mA)/Is) "
                     "(u the bridge's command): the forward drop of the body diode of the "
                     "ECU's reverse-polarity FET, which is left off, whenever the bridge "
                     "drives, none while its low sides short the motor"}),),
            probes=("current",),
            noise={"current": {"white": 0.04, "ar1": [0.05, 0.7], "quant": ADC_STEP}},
            note="a bench log of the current alone (the ECU's 12-bit ADC, the bridge's hash "
                 "as Gauss-Markov noise, correlation 0.7 over the interval, 50 mA, on white "
                 "noise); the ECU's reverse-polarity MOSFET is not switched on (its gate "
                 "driver's charge pump failed) and the supply reaches the bridge through its "
                 "body diode: 0.55 V at 1 A, 0.8 V at 20 A, whenever the bridge drives; a "
                 "person sees the inrush 1.9 A lower, the clamp built later and the current at "
                 "the cut 1.4 A lower, the release's breakaway current lower, and the "
                 "braking currents at the cuts as declared from a motor that ran about 55 "
                 "rad/s slower; close to a brush drop or a series resistance, but a drop "
                 "that grows with the logarithm of the current and vanishes when the "
                 "command is zero"),
        spec("aj14", "outside", "fast", True, (outside(
            "piston-knock-back", {"knock": KNOCK},
            {"dg_rad": KNOCK, "knock_back_mm": KNOCK * 1.5 / (2 * math.pi),
             "form": "the pads' gap is thg + dg in the clamp's law and in the thread's "
                     "friction: the piston was pushed back into its bore, away from the "
                     "EPB's nut, so the nut travels dg further before it meets it"}),),
            noise={"current": {"white": 0.05}, "speed": {"white": 1.0, "pink": 2.0}},
            note="the apply followed a hard cornering test on the bench's hub rig: the "
                 "disc's runout knocked the piston back into its bore by 0.12 mm (0.5 rad of "
                 "the spindle) away from the EPB's nut; the speed column carries 1/f noise "
                 "(2 rad/s) on white noise; a person sees the start and the run across the "
                 "gap as declared, then the clamp's load arriving about 50 ms late: the "
                 "current's rise late (3.7 A below the declared at the cut, the motor "
                 "110 rad/s faster), the clamp reaching 1.8 N m (7.7 kN) instead of 4.4 N m "
                 "at the cut, the braking and the coupling's unwinding smaller, and the "
                 "release's breakaway lighter and shorter; close to a weaker load or a "
                 "lighter friction, but the declared clamp law shifted along the nut's "
                 "travel"),
    ]


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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 32, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:hub", {"coul": {"hub": 1e-2}}),
    ("coulomb-friction:spindle", {"coul": {"spindle": 1e-2}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 2e-8}}),
    ("viscous-friction:spindle", {"visc": {"spindle": 5e-4}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:spindle", {"offset": {"spindle": 1e-2}}),
    ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-4, 10.0)}}),
    ("stribeck-friction:spindle", {"stribeck": {"spindle": (1e-2, 0.1)}}),
    ("backlash:K", {"gap": 1e-4}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:60", {"lsat": (60.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Js", {"p": {"Js": P["Js"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:spindle", lambda a, b: {"cog": {"spindle": [(1, a, b)]}}),
    ("cogging:rotor:10", lambda a, b: {"cog": {"rotor": [(10, a, b)]}}),
    ("cogging:spindle:2", lambda a, b: {"cog": {"spindle": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:10", lambda a, b: {"emf": [(10, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1 uV s/rad of EMF), 10 mN m on the spindle."""
    return 1e-4 if (":rotor" in label or label.startswith("emf")) else 1e-2


@dataclass(frozen=True)
class OneProbe(recordkit.Plumbing):
    """recordkit.Plumbing for records that may give the diagnosis fewer probes than their
    regime has: the signatures, the marginal scaling, the imprints of the catalog's effects
    (and of the sensors of the probes given only) and the CSV are those of the record's own
    ``probes``."""

    def white_of(self, s: dict[str, Any]) -> dict[str, dict[str, float]]:
        """The white sigma [probe unit] of the record's probes, in its regime."""
        return {s["regime"]: {p: self.white[s["regime"]][p] for p in s["probes"]}}

    def imprints(self, s: dict[str, Any]) -> recordkit.Imprints:
        """The null run and the imprints on the record's own times and probes, once."""
        if "imprints" not in s:
            t = self.times(s)
            s["imprints"] = recordkit.Imprints(lambda regime: self.sim(regime, t, {}),
                                               self.white_of(s))
        return s["imprints"]

    def alternatives(self, s: dict[str, Any]) -> dict[str, np.ndarray]:
        """Label -> (n, 1) imprint of each scalar catalog effect, per unit size, linearised
        (the sensor effects of the record's probes only)."""
        regime, t = s["regime"], self.times(s)
        return self.imprints(s).of_effects(
            regime, lambda fx: self.sim(regime, t, fx), self.scalar_effects, s["probes"],
            self.simulator.REGIMES[regime][1], self.sensor_steps, columns=True)

    def truth_entry(self, s: dict[str, Any], sig: dict) -> dict:
        """The record's entry of truth.json: its probes and their noise only."""
        entry = super().truth_entry(s, sig)
        ns = {p: v for p, v in recordkit.noise_or_white(s, self.white).items()
              if p in s["probes"]}
        entry.update(probes=list(s["probes"]), noise=ns,
                     noise_text=recordkit.noise_text(ns))
        return entry

    def scale_marginal(self, s: dict[str, Any]) -> None:
        """Scale a marginal record's size so that its best probe's signature is the set's
        marginal size on its own times: recordkit's proportional passes, repeated (up to
        eight) until within 1 % of it (a brush drop's imprint is not linear in its size)."""
        for _ in range(4):
            super().scale_marginal(s)
            clean = self.sim(s["regime"], self.times(s), s["fx"])
            best = max(self.imprints(s).signature(s["regime"], clean).values())
            if abs(best / self.marginal_sigma - 1.0) < 0.01:
                return

    def make(self, s: dict[str, Any], write: bool) -> dict:
        """One record: its truth entry, and its CSV (the record's probes, the command in
        the slow regime) when ``write``."""
        entry = super().make(s, False)
        if write:
            regime, t = s["regime"], self.times(s)
            clean = self.sim(regime, t, s["fx"])
            rng = np.random.default_rng(s["seed"])
            ns = recordkit.noise_or_white(s, self.white)
            cols = {p: self.simulator.add_noise(rng, t, clean[p], ns[p]) for p in s["probes"]}
            if regime == "slow":
                cols["u"] = clean["u"]
            RECORDS.mkdir(exist_ok=True)
            recordkit.write_csv(RECORDS / f"{s['id']}.csv", t, cols)
        return entry


#: across the coupling (a spring and a damper, 1:1): the body an effect on each is compared
#: with, and the factor its size takes there per kind (the carrier and the spindle turn at
#: one mean speed)
ACROSS = {"spindle": ("hub", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0}),
          "hub": ("spindle", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` across the coupling
    (``recordkit.location_entry``), after a marginal record's scaling."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term of the catalog's kinds (the clamp and the thread's friction, laws of the
#: spindle's angle and speed, are behavioural torques of the declared model)
KIT = OneProbe(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sa, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=harmonic_size, marginal_sigma=MARGINAL_SIGMA, declared=(),
    extra=_location_entry)
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
