"""Generate the blind set ``fresh14`` of the diagnosis benchmark: records w01-w14 of motor O
(a 36 V brushed DC motor with a heated winding driving a triplex plunger pump through a
rigid 3:1 gearhead and a tyre coupling), some sampled evenly and some UNEVENLY, and merge
their truth into truth.json.

    python benchmarks/diagnosis/make_records_o.py              # records/w*.csv + truth.json
    python benchmarks/diagnosis/make_records_o.py --only w03,w12
    python benchmarks/diagnosis/make_records_o.py --truth-only # rewrite the w entries only

Uses simulators_o.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe [SI] (and, in the slow regime, the command ``u``
[V] that motor_o_slow.yaml reads from its own table). Even records are sampled on the
regime's grid k/fs; uneven ones, in the fast regime, on a 50 kHz grid whose every sample is
moved by a random jitter of up to 20-35 % of the interval, and in the slow regime at a
logger's irregular intervals (0.5-2 times the mean of 1 ms) with a few samples dropped.
Each uneven record has its own times (from its seed), and the motor is simulated at those
very times (``t_eval``), never interpolated. truth.json is merged under an exclusive lock
(recordkit.merge). Nobody ran the diagnosis on these records.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import recordkit
import simulators_o as so

RECORDS = HERE / "records"
SPLIT = "fresh14"
MOTOR = "O"
SEED0 = 14500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_o.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_o_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.05, "speed": 0.3},
         "slow": {"current": 0.05, "speed": 0.3, "load_speed": 0.05}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.20, 0.35), (3, 9)
P = so.MOTOR_O
N = P["N"]
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_o, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearhead is rigid and lossless: a torque on the
# rotor is one N times as large on the gearhead's output (``out``), a viscous coefficient
# N^2 times; the crank sits behind the compliant coupling and has no such equal.

def angle_torque(node: str, order: int, amp: float, phase: float, effect: str) -> Part:
    """A torque amp sin(order angle + phase) [N m] locked to ``node``'s angle."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    alts = [{"effect": "cogging", "targets": [node], "order": 1, "expected": {"a": a, "b": b}}]
    return {"cog": {node: [(order, a, b)]}}, {
        "effect": effect, "target": node, "targets": [node], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"{node} receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b}, **({"also_accept": alts} if order == 1 else {})}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF harmonic w slope sin(order th + phase) [V], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"the EMF gains w k_h sin({order} th + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad] in the tyre coupling K."""
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


def stribeck(node: str, s: float, ws: float) -> Part:
    """A breakaway peak s [N m] with Stribeck speed ws [rad/s] over ``node``'s friction."""
    return {"stribeck": {node: (s, ws)}}, {
        "effect": "stribeck-friction", "target": node, "targets": [node],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": f"{node} takes s exp(-(w/ws)^2) tanh(w/0.01) over the declared "
                               "Tf tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def series_resistance(r: float, regime: str) -> Part:
    """A resistance [ohm] in series with the armature (a corroded connector)."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": ["Ra", "La", "M"],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


def coulomb_rotor(c: float) -> Part:
    """An extra Coulomb friction [N m] on the rotor (accepted on the gearhead's output at
    N times its size)."""
    return {"coul": {"rotor": c}}, {
        "effect": "coulomb-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(w/0.01) against the rotor"},
        "expected": {"c": c},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["out"],
                         "expected": {"c": c * N}}]}


def brush_drop(vb: float) -> Part:
    """A brush contact drop [V]."""
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor O's clean probes at the times ``t`` [s] with the effects ``fx``."""
    fx = dict(fx)
    p = {**P, **fx.pop("p", {})}
    return so.simulate(regime, t, fx, p)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts: Sequence[Part] = (),
         noise: dict | None = None, note: str = "",
         marginal: Callable[[float], Sequence[Part]] | None = None,
         size: float | None = None) -> dict[str, Any]:
    """One record's specification."""
    fx, effects = recordkit.combine(parts)
    return {"id": rid, "class": cls, "regime": regime, "uneven": uneven, "fx": fx,
            "effects": effects, "noise": noise, "note": note, "marginal": marginal,
            "size": size}


# ---------------------------------------------------------------------- the records

ADC_I = {"white": 0.04, "quant": 0.025}


def null_and_catalog() -> list[dict[str, Any]]:
    """w01-w09: the null, catalog and two-effect records."""
    return [
        spec("w01", "null", "fast", False, note="white noise"),
        spec("w02", "null", "slow", True,
             noise={"current": {"white": 0.03, "ar1": [0.04, 0.9], "quant": 0.025},
                    "speed": {"white": 0.2, "pink": 0.25},
                    "load_speed": {"white": 0.04, "quant": 0.02}},
             note="coloured noise: Gauss-Markov current noise (correlation 0.9 over the mean "
                  "interval, exp(-dt/tau) over an interval dt) and a 12-bit ADC over +-50 A "
                  "(25 mA steps) on the current, 1/f noise on the speed (a sum of "
                  "Gauss-Markov processes an octave apart), 20 mrad/s steps on the crank's "
                  "speed"),
        spec("w03", "catalog", "fast", True, (backlash(0.02),),
             noise={"current": ADC_I, "speed": {"white": 0.3}},
             note="the tyre coupling's rubber element has torn free of one flange's "
                  "clamping ring: a play of 20 mrad (1.15 degrees) opens in the coupling, "
                  "crossed at every reversal of its torque (the step down, the braking, the "
                  "reversal, the plugging restart); the current read by a 12-bit ADC"),
        spec("w04", "catalog", "fast", False, (emf_harmonic(22, 1.2e-3, 0.9),),
             note="the armature's 11 commutator bars under two brushes: the EMF ripples 22 "
                  "times per rotor turn, 1.6 % of k (1.2e-3 V s/rad, 0.52 V at 433 rad/s), "
                  "with no torque ripple of its own worth stating"),
        spec("w05", "catalog", "fast", True, (sensor("current", "delay", 5e-6),),
             marginal=lambda s: (sensor("current", "delay", s),), size=5e-6,
             note="the current is read through the drive's isolated sigma-delta modulator "
                  "and its decimation filter: a pure lag of a few microseconds, scaled to a "
                  "25 sigma signature (marginal)"),
        spec("w06", "catalog", "slow", True, (stribeck("crank", 0.5, 2.0),),
             note="the plungers' packings have dried while the pump stood: a breakaway peak "
                  "of 0.5 N m over the declared 0.4 N m packing friction, fading by about "
                  "2 rad/s of the crank; seen at the stops, the backward turn's start and the "
                  "inching move"),
        spec("w07", "catalog", "slow", False, (angle_torque("crank", 1, 0.05, 1.3,
                                                            "unbalance"),),
             marginal=lambda s: (angle_torque("crank", 1, s, 1.3, "unbalance"),), size=0.05,
             note="one balance weight is missing from the crankshaft's web: its weight pulls "
                  "the crank once per turn, scaled to a 25 sigma signature (marginal)"),
        spec("w08", "two", "fast", False, (series_resistance(0.05, "fast"),
                                           coulomb_rotor(0.03)),
             noise={"current": {"white": 0.05}, "speed": {"white": 0.2, "pink": 0.2}},
             note="a corroded spade connector in the armature lead (50 mohm) and a dragging "
                  "rear bearing seal on the motor (30 mN m of Coulomb friction on the "
                  "rotor); 1/f noise on the speed"),
        spec("w09", "two", "slow", True, (brush_drop(0.5),
                                          sensor("load_speed", "gain", 33.0 / 34.0)),
             noise={"current": ADC_I, "speed": {"white": 0.3}, "load_speed": {"white": 0.05}},
             note="the carbon brushes' contact drop, 0.5 V in all, reversing with the "
                  "current; and the crank's speed is counted from a pickup on the pump's "
                  "33-tooth drive gear by a logger configured for 34 teeth (a gain of 33/34 "
                  "on the crank's speed); the current read by a 12-bit ADC"),
    ]


#: the missing tooth: the gap's centre on the rotor [rad], one pitch of a 36-tooth wheel
#: [rad], the edges' sharpness [1]
TOOTH = (1.2, 2.0 * math.pi / 36.0, 3000.0)
#: the relief valve: cracking torque [N m] (9.4 bar), override slope [1], knee [N m]
RELIEF = (1.5, 0.2, 0.05)
#: the battery: V0 [V], the voltage lost per coulomb drawn [V/C], the drive's nominal [V]
BATTERY = (36.0, 4e-3, 36.0)
#: the air-bound start: the load's fraction air-bound, the crank angle at which the pump
#: primes [rad] (24 turns: the suction line's air pushed out) and its width [rad]
PRIME = (0.15, 150.0, 20.0)


def outside_fast() -> list[dict[str, Any]]:
    """w10-w12: effects the catalog does not contain, fast regime."""
    return [
        spec("w10", "outside", "fast", True, (outside(
            "plunger-flow-pulsation", {"pulse": 0.7},
            {"kappa": 0.7, "S3_mean": so.S3_MEAN,
             "form": "the pressure load cq wp|wp| becomes cq wp|wp| (1 + kappa (S(thp)^3/"
                     "<S^3> - 1)), S(thp) = sum_j max(0, sin(thp - 2 pi j/3)); thp the "
                     "crank's angle"}),),
            note="the discharge hose's pulsation damper has lost its gas charge: the nozzles' "
                 "pressure follows the three plungers' instantaneous flow, so the crank's "
                 "load pulsates six times per crank turn with a cusped shape (the flow's "
                 "cube), by 70 % of the undamped swing, its size growing with the square of "
                 "the speed. A person sees a torque ripple locked to the crank's angle whose "
                 "amplitude follows the pressure: large at 36 V, a quarter of it at 24 V, "
                 "none at rest"),
        spec("w11", "outside", "fast", False, (outside(
            "missing-tooth-speed-sensor", {"tooth": TOOTH},
            {"gap_centre_rad": TOOTH[0], "width_rad": TOOTH[1], "kappa": TOOTH[2],
             "form": "speed reads w (1 - G/2), G = (1 + tanh(kappa (cos(th - thc) - "
                     "cos(width/2))))/2; th the rotor's angle"}),),
            note="the motor's speed is measured on a 36-1 toothed wheel (a reference gap of "
                 "one missing tooth) by a drive that divides the tooth pitch by the last "
                 "edge interval and does not handle the gap: once per rotor turn, for one "
                 "pitch, the interval is twice as long and the speed reads half. A person "
                 "sees the speed reading dip to half for a tenth of a millisecond once per "
                 "turn while the current shows nothing"),
        spec("w12", "outside", "fast", True, (outside(
            "pressure-relief-valve", {"relief": RELIEF},
            {"T_crack_Nm": RELIEF[0], "override": RELIEF[1], "knee_Nm": RELIEF[2],
             "form": "the load q = cq wp|wp| becomes q - (1 - s)(sp(q - Tc) - sp(-q - Tc)), "
                     "sp(y) = delta log(1 + exp(y/delta))"}),),
            noise={"current": ADC_I, "speed": {"white": 0.3}},
            note="the boom's pressure-relief valve is set too low (9.4 bar): above about "
                 "130 rad/s of the crank it opens and bypasses the excess flow, and the "
                 "pressure then rises only a fifth as fast as the nozzles alone would make "
                 "it. A person sees a load that follows the declared square law up to a "
                 "speed and saturates above it (the run at 36 V only); the current read by "
                 "a 12-bit ADC"),
    ]


def outside_slow() -> list[dict[str, Any]]:
    """w13-w14: effects the catalog does not contain, slow regime."""
    return [
        spec("w13", "outside", "slow", False, (outside(
            "weak-battery-charge-droop", {"battery": BATTERY},
            {"V0_V": BATTERY[0], "kq_V_per_C": BATTERY[1], "Vnom_V": BATTERY[2],
             "form": "the armature gets u (V0 - kq q)/Vnom, dq/dt = u i/Vnom (q the charge "
                     "drawn from the battery, u the logged command)"}),),
            note="the sprayer's 36 V battery is nearly empty: on the steep end of its "
                 "discharge curve its voltage falls by 4 mV per coulomb drawn (14 V/Ah), "
                 "while the drive's duty is logged as if the bus held 36 V. A person sees "
                 "the speed sag further below the declared model the longer the pump runs "
                 "(0.15 V lost by the end), recovering a little while the motor "
                 "regenerates: neither a resistance nor a drift in time"),
        spec("w14", "outside", "slow", True, (outside(
            "pump-priming", {"prime": PRIME},
            {"a0": PRIME[0], "th1_rad": PRIME[1], "dth_rad": PRIME[2],
             "form": "the pressure load cq wp|wp| is scaled by a0 + (1 - a0)(1 + "
                     "tanh((thp - th1)/dth))/2; thp the crank's angle (it never turns back "
                     "below th1 in this record)"}),),
            noise={"current": {"white": 0.05, "quant": 0.025}, "speed": {"white": 0.3},
                   "load_speed": {"white": 0.05}},
            note="the pump starts air-bound: the suction hose holds air that the plungers "
                 "compress instead of water, and the nozzles' pressure builds only once the "
                 "air has been pushed out, after about 24 crank turns (1.8 s into the "
                 "record). A person sees the load at 15 % of the declared square law during "
                 "the start, then rising to it within a few turns: a load that changes "
                 "once, with the pumped volume"),
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
    """A logger's times [s] and the times it dropped [s]: intervals of 0.5 + 1.5 Beta(2, 4)
    [1] times the mean 1/fs [Hz] (0.5-2 times it), from 0 to at most ``duration`` [s],
    rounded to 1 us; ``drops`` interior samples removed, at least five apart."""
    gaps = (0.5 + 1.5 * rng.beta(2.0, 4.0, int(1.4 * duration * fs))) / fs
    t = np.round(np.concatenate([[0.0], np.cumsum(gaps)]) * 1e6) / 1e6
    t = t[t <= duration]
    pick = np.sort(rng.choice(np.arange(5, t.size - 5, 5), drops, replace=False))
    return np.delete(t, pick), t[pick]


def _tidy(t: np.ndarray) -> np.ndarray:
    """The times exactly as the CSV holds them (10 significant digits) [s]."""
    return np.array([float(f"{x:.10g}") for x in t])


def times(s: dict[str, Any]) -> np.ndarray:
    """The record's sample times [s] (even, or uneven from its seed), once; described in
    ``s["timestamps"]``."""
    if "t" in s:
        return s["t"]
    fs, dur = so.REGIMES[s["regime"]]
    if not s["uneven"]:
        t = so.grid(s["regime"])
        s["timestamps"] = f"even: k/fs, fs = {fs:g} Hz"
    elif s["regime"] == "fast":
        rng = np.random.default_rng([s["seed"], 14])
        jitter = round(float(rng.uniform(*JITTER)), 3)
        t = recordkit.jittered_times(rng, fs, dur, jitter)
        s["timestamps"] = (
            f"jittered: the nominal {fs / 1e3:g} kHz grid k/fs, every sample time but the "
            f"first moved by a uniform random jitter within +-{jitter:.1%} of the "
            f"{1e6 / fs:g} us interval (the last one only earlier), rounded to 1 ns; "
            f"intervals {np.diff(t).min() * 1e6:.2f}-{np.diff(t).max() * 1e6:.2f} us")
    else:
        rng = np.random.default_rng([s["seed"], 14])
        drops = int(rng.integers(DROPS[0], DROPS[1] + 1))
        t, gone = logger_times(rng, fs, dur, drops)
        s["timestamps"] = (
            f"jittered: a data logger's irregular intervals, 0.5 + 1.5 Beta(2, 4) times the "
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
    ("coulomb-friction:crank", {"coul": {"crank": 1e-4}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-6}}),
    ("viscous-friction:crank", {"visc": {"crank": 1e-5}}),
    ("stribeck-friction:crank:1", {"stribeck": {"crank": (1e-3, 1.0)}}),
    ("stribeck-friction:crank:10", {"stribeck": {"crank": (1e-3, 10.0)}}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inertia:Jp", {"p": {"Jp": P["Jp"] * 1.001}}),
    ("inertia:Jm", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("sensor-delay:current", {"sensor": {"current": {"delay": 1e-6}}}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:crank", lambda a, b: {"cog": {"crank": [(1, a, b)]}}),
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("cogging:crank:6", lambda a, b: {"cog": {"crank": [(6, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
)
#: each probe's sensor effects (the delay only on the current, above)
SENSOR_STEPS = (("gain", 1.001), ("offset", 1e-3))


#: the plumbing every later set shares (recordkit.Plumbing): truth entries, marginal
#: scaling, the catalog's imprints an outside or marginal record is compared with, the CSV
KIT = recordkit.Plumbing(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=so, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=lambda label: 1e-3,
    marginal_sigma=MARGINAL_SIGMA, sensor_steps=SENSOR_STEPS)
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
