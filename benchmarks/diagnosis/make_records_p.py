"""Generate the blind set ``fresh15`` of the diagnosis benchmark: records x01-x14 of motor P
(a 48 V brushed DC motor spinning a flywheel in a rough vacuum through a rigid 1:2 spur-gear
step-up and a compliant quill shaft), some sampled evenly and some UNEVENLY, and merge their
truth into truth.json.

    python benchmarks/diagnosis/make_records_p.py              # records/x*.csv + truth.json
    python benchmarks/diagnosis/make_records_p.py --only x03,x12
    python benchmarks/diagnosis/make_records_p.py --truth-only # rewrite the x entries only

Uses simulators_p.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe [SI] (and, in the slow regime, the command ``u``
[V] that motor_p_slow.yaml reads from its own table). Even records are sampled on the
regime's grid k/fs; uneven ones, in the fast regime, on a 40 kHz grid whose every sample is
moved by a random jitter of up to 15-30 % of the interval, and in the slow regime at a
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
import simulators_p as sp

RECORDS = HERE / "records"
SPLIT = "fresh15"
MOTOR = "P"
SEED0 = 15500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_p.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_p_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.04, "speed": 0.15},
         "slow": {"current": 0.04, "speed": 0.15, "load_speed": 0.3}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.15, 0.30), (2, 8)
P = sp.MOTOR_P
N = P["N"]
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_p, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The spur gear is rigid and lossless: a torque on the
# rotor is N = 0.5 times as large on the pinion's shaft (``pinion``), a viscous coefficient
# N^2 times; the flywheel sits behind the compliant quill and has no such equal.

def unbalance(node: str, amp: float, phase: float) -> Part:
    """A torque amp sin(angle + phase) [N m] once per turn of ``node`` (its weight)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {node: [(1, a, b)]}}, {
        "effect": "unbalance", "target": node, "targets": [node], "order": 1,
        "parameters": {"order": 1, "T_Nm": amp, "phase_rad": phase,
                       "form": f"{node} receives T sin(angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": [node], "order": 1,
                         "expected": {"a": a, "b": b}}]}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF harmonic w slope sin(order th + phase) [V], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"the EMF gains w k_h sin({order} th + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad] in the quill K."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap, "form": "0 while |phi_rel| < gap/2, else c (phi_rel "
                                               "-+ gap/2) + d w_rel, the damping never pulling"},
        "expected": {"gap": gap}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def source_resistance(r: float, regime: str) -> Part:
    """A resistance [ohm] inside the supply (the battery and its cable)."""
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[regime], "targets": [SOURCE[regime]],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": ["Ra", "La", "M"],
                         "expected": {"R": r}}]}


def saturation(ipar: float, ratio: float) -> Part:
    """The armature's inductance falling with the current (its teeth saturating)."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"I_knee_A": ipar, "L_ratio_saturated": ratio,
                       "form": "La(i) = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2)), the "
                               "differential inductance"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def inertia_fly(dj: float) -> Part:
    """The flywheel's inertia off by a factor 1 + ``dj`` (a correction of Jf)."""
    return {"p": {"Jf": P["Jf"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jf", "targets": ["Jf"], "correction": True,
        "parameters": {"Jf_true_kgm2": P["Jf"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


def warmup(rise: float, tau: float) -> Part:
    """The armature warming: R (1 + rise (1 - exp(-t / tau)))."""
    return {"warmup": (rise, tau)}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + rise*(1 - exp(-t/tau)))", "rise": rise, "tau_s": tau},
        "expected": {"rise": rise, "tau": tau}}


def coulomb_rotor(c: float) -> Part:
    """An extra Coulomb friction [N m] on the rotor (accepted on the pinion's shaft at N
    times its size)."""
    return {"coul": {"rotor": c}}, {
        "effect": "coulomb-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(w/0.01) against the rotor"},
        "expected": {"c": c},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["pinion"],
                         "expected": {"c": c * N}}]}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor P's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sp.simulate(regime, t, fx)


spec = recordkit.spec


# ---------------------------------------------------------------------- the records

#: a 12-bit ADC over +-40 A (20 mA steps) on the current
ADC_I = {"white": 0.035, "quant": 0.02}


def null_and_catalog() -> list[dict[str, Any]]:
    """x01-x09: the null, catalog and two-effect records."""
    return [
        spec("x01", "null", "fast", False, note="white noise"),
        spec("x02", "null", "slow", True,
             noise={"current": {"white": 0.025, "ar1": [0.035, 0.85], "quant": 0.02},
                    "speed": {"white": 0.1, "pink": 0.15},
                    "load_speed": {"white": 0.3}},
             note="coloured noise: Gauss-Markov current noise (correlation 0.85 over the mean "
                  "interval, exp(-dt/tau) over an interval dt) and a 12-bit ADC over +-40 A "
                  "(20 mA steps) on the current, 1/f noise on the motor's speed (a sum of "
                  "Gauss-Markov processes an octave apart)"),
        spec("x03", "catalog", "fast", True, (source_resistance(0.08, "fast"),),
             noise={"current": ADC_I, "speed": {"white": 0.15}},
             note="the demonstrator runs from a 48 V battery through 3 m of thin cable: the "
                  "battery's internal resistance and the cable's, 80 mohm in all, inside the "
                  "source; the current read by a 12-bit ADC"),
        spec("x04", "catalog", "fast", False, (saturation(12.0, 0.4),),
             note="the armature's teeth saturate: the differential inductance falls to half "
                  "at 12 A and towards 40 % of La at high current (the soft start's and the "
                  "braking's 25-32 A)"),
        spec("x05", "catalog", "fast", True, (inertia_fly(0.125),),
             note="the flywheel fitted is the 18 mm thick disc, not the declared 16 mm one: "
                  "its inertia is 12.5 % above Jf (a correction of Jf; the quill keeps it "
                  "apart from the rotor's and the pinion's inertia)"),
        spec("x06", "catalog", "slow", False, (unbalance("fly", 0.002, 0.7),),
             marginal=lambda s: (unbalance("fly", s, 0.7),), size=0.002,
             note="a balancing hole drilled on the wrong side of the flywheel (its axis is "
                  "horizontal): its weight pulls the flywheel once per turn, scaled to a 25 "
                  "sigma signature (marginal)"),
        spec("x07", "catalog", "slow", True, (sensor("load_speed", "offset", 0.1),),
             marginal=lambda s: (sensor("load_speed", "offset", s),), size=0.1,
             note="the flywheel's optical pickup feeds a frequency-to-voltage converter whose "
                  "output amplifier has an offset: the flywheel's speed reads a constant "
                  "amount high, scaled to a 25 sigma signature (marginal)"),
        spec("x08", "two", "fast", False, (backlash(0.012), emf_harmonic(14, 1.3e-3, 2.1)),
             noise={"current": {"white": 0.04}, "speed": {"white": 0.1, "pink": 0.12}},
             note="the quill's splined end has worn: a play of 12 mrad (0.7 degree) in the "
                  "quill, crossed wherever its torque reverses (the regenerative ramp down, "
                  "the braking); and the armature's 7 commutator bars under two brushes make "
                  "the EMF ripple 14 times per rotor turn, 1.2 % of k (1.3e-3 V s/rad), with "
                  "no torque ripple of its own worth stating; 1/f noise on the speed"),
        spec("x09", "two", "slow", True, (warmup(0.15, 2.5), coulomb_rotor(0.02)),
             noise={"current": ADC_I, "speed": {"white": 0.15}, "load_speed": {"white": 0.3}},
             note="the armature's brush contact film warming from a cold start (the loop's "
                  "resistance settling 15 % higher with a 2.5 s time constant) and a lip "
                  "seal on the motor's shaft, fitted to keep the housing's vacuum, dragging "
                  "with 20 mN m of Coulomb friction; the current read by a 12-bit ADC"),
    ]


#: high mica: the contact resistance's peak [ohm], its order (two brushes passing 7 bar
#: gaps per turn), the pulse's sharpness [1] and its angle [rad]
MICA = (0.4, 14, 30.0, 0.3)
#: the magnetic bearing's eddy drag: peak torque [N m] and the critical speed [rad/s]
EDDY = (0.025, 250.0)
#: [s] the drive's current-loop sampling period, 5 kHz
HOLD = 2e-4
#: [s] the housing's leak: the windage doubles every tau_l of the record
LEAK = 0.5
#: the drive's slew-rate limiter: [V/s] and its small-signal lag [s]
SLEW = (50.0, 0.01)


def outside_fast() -> list[dict[str, Any]]:
    """x10-x12: effects the catalog does not contain, fast regime."""
    return [
        spec("x10", "outside", "fast", True, (outside(
            "high-mica-commutator", {"mica": MICA},
            {"Rm_ohm": MICA[0], "order": MICA[1], "kappa": MICA[2], "phase_rad": MICA[3],
             "form": "the loop gains Rm exp(kappa (cos(order th - phase) - 1)) in series "
                     "(th the rotor's angle)"}),),
            note="the commutator's mica insulation stands proud of the worn copper bars: "
                 "each brush rides up at every bar gap, its contact resistance rising to "
                 "0.4 ohm for about 7 % of a bar pitch, 14 times per rotor turn. A person "
                 "sees narrow dips in the current, 14 per turn, whose depth follows the "
                 "current (none while it is near zero), and a resistance's slight extra "
                 "drop on average"),
        spec("x11", "outside", "fast", False, (outside(
            "eddy-current-drag-peak", {"eddy": EDDY},
            {"T_peak_Nm": EDDY[0], "w_critical_rad_s": EDDY[1],
             "form": "the flywheel takes 2 Tp (wf/wc)/(1 + (wf/wc)^2) against its motion"}),),
            note="the passive magnetic bearing that carries the flywheel's weight has ring "
                 "magnets facing the solid steel disc: eddy currents drag it with the law of "
                 "an eddy-current brake, rising in proportion to the speed, peaking at 25 "
                 "mN m at 250 rad/s of the flywheel (where the skin effect starts to expel "
                 "the field) and falling as 1/w above. A person sees a drag that a viscous "
                 "friction fits at low speed and overestimates at the top speed"),
        spec("x12", "outside", "fast", True, (outside(
            "current-sample-hold", {"hold": HOLD},
            {"T_hold_s": HOLD,
             "form": "the current reads i(floor(t/T) T): the value the drive's controller "
                     "last sampled, every T"}),),
            noise={"current": ADC_I, "speed": {"white": 0.15}},
            note="the current is not read by the data acquisition's own ADC but taken from "
                 "the drive's controller, which samples it once per PWM period (5 kHz) and "
                 "holds it: the 40 kHz record shows the current as a staircase of 8 samples "
                 "a step. A person sees a lag of half a period on average whose error is a "
                 "sawtooth wherever the current changes, and nothing at a steady current; "
                 "the current read by a 12-bit ADC"),
    ]


def outside_slow() -> list[dict[str, Any]]:
    """x13-x14: effects the catalog does not contain, slow regime."""
    return [
        spec("x13", "outside", "slow", False, (outside(
            "vacuum-leak-windage", {"leak": LEAK},
            {"tau_leak_s": LEAK,
             "form": "the flywheel's windage bf wf becomes bf (1 + t/tau_l) wf"}),),
            noise={"current": {"white": 0.04}, "speed": {"white": 0.15},
                   "load_speed": {"white": 0.2, "pink": 0.2}},
            note="the housing's vacuum pump was switched off at the start of the test and "
                 "the housing leaks: its pressure rises linearly, and in molecular flow the "
                 "windage drag grows with it, 21 times the declared bf by the end (0.06 N m "
                 "at the flywheel's 870 rad/s). A person sees a viscous drag that grows "
                 "steadily through the record; 1/f noise on the flywheel's speed"),
        spec("x14", "outside", "slow", True, (outside(
            "drive-slew-rate-limit", {"slew": SLEW},
            {"S_V_per_s": SLEW[0], "tau_s": SLEW[1],
             "form": "the armature gets v, dv/dt = S tanh((u - v)/(S tau)), v(0) = 0; u the "
                     "logged command"}),),
            note="the drive's acceleration ramp is set to 50 V/s, but the logger records "
                 "the command before it: the armature voltage follows the logged u with a "
                 "10 ms lag, and the command's steps (36 to 48 V, 16 to 0 V, -24 to -10 V) "
                 "become ramps of a quarter to a third of a second. A person sees the "
                 "current's peaks at the steps lower and longer than the declared model's, "
                 "while the slow ramps agree"),
    ]


def record_specs() -> list[dict[str, Any]]:
    """The 14 records, each with its seed."""
    out = null_and_catalog() + outside_fast() + outside_slow()
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- sample times

def logger_times(rng: np.random.Generator, fs: float, duration: float, drops: int
                 ) -> tuple[np.ndarray, np.ndarray]:
    """A logger's times [s] and the times it dropped [s]: intervals of 0.6 + 0.8 Beta(3, 3)
    [1] times the mean 1/fs [Hz] (0.6-1.4 times it), from 0 to at most ``duration`` [s],
    rounded to 1 us; ``drops`` interior samples removed, at least seven apart."""
    gaps = (0.6 + 0.8 * rng.beta(3.0, 3.0, int(1.2 * duration * fs))) / fs
    t = np.round(np.concatenate([[0.0], np.cumsum(gaps)]) * 1e6) / 1e6
    t = t[t <= duration]
    pick = np.sort(rng.choice(np.arange(7, t.size - 7, 7), drops, replace=False))
    return np.delete(t, pick), t[pick]


def _tidy(t: np.ndarray) -> np.ndarray:
    """The times exactly as the CSV holds them (10 significant digits) [s]."""
    return np.array([float(f"{x:.10g}") for x in t])


def times(s: dict[str, Any]) -> np.ndarray:
    """The record's sample times [s] (even, or uneven from its seed), once; described in
    ``s["timestamps"]``."""
    if "t" in s:
        return s["t"]
    fs, dur = sp.REGIMES[s["regime"]]
    rng = np.random.default_rng([s["seed"], 15])
    if not s["uneven"]:
        t = sp.grid(s["regime"])
        s["timestamps"] = f"even: k/fs, fs = {fs:g} Hz"
    elif s["regime"] == "fast":
        jitter = round(float(rng.uniform(*JITTER)), 3)
        t = recordkit.jittered_times(rng, fs, dur, jitter)
        s["timestamps"] = (
            f"jittered: the nominal {fs / 1e3:g} kHz grid k/fs, every sample time but the "
            f"first moved by a uniform random jitter within +-{jitter:.1%} of the "
            f"{1e6 / fs:g} us interval (the last one only earlier), rounded to 1 ns; "
            f"intervals {np.diff(t).min() * 1e6:.2f}-{np.diff(t).max() * 1e6:.2f} us")
    else:
        drops = int(rng.integers(DROPS[0], DROPS[1] + 1))
        t, gone = logger_times(rng, fs, dur, drops)
        s["timestamps"] = (
            f"jittered: a data logger's irregular intervals, 0.6 + 0.8 Beta(3, 3) times the "
            f"mean {1e3 / fs:.3g} ms, from 0 to {t[-1]:.4f} s, rounded to 1 us; {drops} "
            "samples dropped (at " + ", ".join(f"{x:.4f}" for x in gone)
            + f" s); intervals {np.diff(t).min() * 1e3:.3f}-{np.diff(t).max() * 1e3:.3f} ms")
    s["t"] = _tidy(t)
    return s["t"]


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-3}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:fly", {"coul": {"fly": 1e-4}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-6}}),
    ("viscous-friction:fly", {"visc": {"fly": 1e-7}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:fly", {"offset": {"fly": 1e-4}}),
    ("stribeck-friction:fly:1", {"stribeck": {"fly": (1e-3, 1.0)}}),
    ("stribeck-friction:fly:10", {"stribeck": {"fly": (1e-3, 10.0)}}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:10", {"lsat": (10.0, 0.999)}),
    ("inertia:Jf", {"p": {"Jf": P["Jf"] * 1.001}}),
    ("inertia:Jm", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
    ("sensor-delay:current", {"sensor": {"current": {"delay": 1e-6}}}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:fly", lambda a, b: {"cog": {"fly": [(1, a, b)]}}),
    ("unbalance:pinion", lambda a, b: {"cog": {"pinion": [(1, a, b)]}}),
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("cogging:rotor:14", lambda a, b: {"cog": {"rotor": [(14, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:14", lambda a, b: {"emf": [(14, a * 1e-2, b * 1e-2)]}),
)
#: each probe's sensor effects (the delay only on the current, above)
SENSOR_STEPS = (("gain", 1.001), ("offset", 1e-3))

#: across the quill: the shaft an effect on each is compared with, and the factor its size
#: takes there per kind (a torque on the rotor is N times its size on the flywheel's side,
#: which turns 1/N times as fast; a viscous coefficient N^2 times; an angle-locked torque on
#: the flywheel is the same on the pinion, which turns with it)
ACROSS = {"rotor": ("fly", {"coul": N, "offset": N, "visc": N * N}),
          "pinion": ("fly", {"coul": 1.0, "offset": 1.0, "visc": 1.0}),
          "fly": ("pinion", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` across the quill
    (``recordkit.location_entry``), after a marginal record's scaling (its parts are then
    the scaled ones)."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing every later set shares (recordkit.Plumbing): truth entries, marginal
#: scaling, the catalog's imprints an outside or marginal record is compared with, the CSV
KIT = recordkit.Plumbing(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sp, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=lambda label: 1e-3,
    marginal_sigma=MARGINAL_SIGMA, sensor_steps=SENSOR_STEPS, extra=_location_entry)
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
