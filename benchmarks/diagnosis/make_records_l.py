"""Generate the blind set ``fresh11`` of the diagnosis benchmark: records s01-s14 of motor L
(a 12 V brushed DC motor driving the spindle of a bench micro-lathe through a 2.5:1 poly-V
belt), sampled UNEVENLY as a real data logger writes them, and merge their truth into
truth.json.

    python benchmarks/diagnosis/make_records_l.py              # records/s*.csv + truth.json
    python benchmarks/diagnosis/make_records_l.py --only s03,s12
    python benchmarks/diagnosis/make_records_l.py --truth-only # rewrite the s entries only

Uses simulators_l.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe [SI] (and, in the slow regime, the command ``u``
[V] that motor_l_slow.yaml reads from its own table). The times are uneven: in the fast
regime a 25 kHz grid whose every sample is moved by a random jitter of up to 20-35 % of the
interval; in the slow regime a logger's irregular intervals (0.6-2.6 times the mean of
1/300 s) with a few samples dropped. Each record has its own times (from its seed), and the
motor is simulated at those very times (``t_eval``), never interpolated. truth.json is
merged under an exclusive lock (``.truth.lock``): every other entry is kept, an entry with
the same id is replaced, and the file is replaced atomically. Nobody ran the diagnosis on
these records.
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
import simulators_l as sl

RECORDS = HERE / "records"
SPLIT = "fresh11"
MOTOR = "L"
SEED0 = 11500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_l.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_l_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.02, "speed": 0.2},
         "slow": {"current": 0.02, "speed": 0.2, "load_speed": 0.08}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter: a fraction of the nominal interval drawn in this range, per record
JITTER = (0.20, 0.35)
#: the slow regime's dropped samples: a count drawn in this range, per record
DROPS = (3, 8)
P = sl.MOTOR_L
N = P["N"]
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_l, truth effect). ``expected`` is keyed by the
# catalog patch's parameter suffixes. The belt is rigid and lossless in the declared model:
# the spindle turns with the rotor at 1/N of its speed, so a torque on the spindle is one
# 1/N as large on the rotor, a viscous coefficient 1/N^2 (the same observation).

def _on_rotor(effect: str, node: str, key: str, value: float, power: int) -> list[dict]:
    """The physically identical label of an effect on the spindle, on the rotor."""
    if node == "rotor":
        return [{"effect": effect, "targets": ["spindle"], "expected": {key: value * N**power}}]
    return [{"effect": effect, "targets": ["rotor"], "expected": {key: value / N**power}}]


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def brush_drop(vb: float) -> Part:
    """A brush contact drop [V]."""
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


def series_resistance(r: float) -> Part:
    """A resistance [ohm] in series with the armature."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": ["Ra", "La", "M"],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": ["Vin", "U"],
                         "expected": {"R": r}}]}


def warmup(rise: float, tau: float) -> Part:
    """The winding warming up: a relative rise [1] with a time constant [s]."""
    return {"warmup": (rise, tau)}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + rise*(1 - exp(-t/tau)))", "rise": rise,
                       "tau_s": tau},
        "expected": {"rise": rise, "tau": tau}}


def harmonic(node: str, order: int, amp: float, phase: float) -> Part:
    """A torque amp sin(order angle + phase) [N m] on ``node``: an unbalance (order 1) or a
    cogging."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    effect = "unbalance" if order == 1 else "cogging"
    alts = [{"effect": "cogging" if order == 1 else "unbalance", "targets": [node],
             "order": order, "expected": {"a": a, "b": b}}] if order == 1 else []
    if node == "rotor" and float(order * N).is_integer():
        alts.append({"effect": "cogging", "targets": ["spindle"], "order": int(order * N),
                     "expected": {"a": a * N, "b": b * N}})
    return {"cog": {node: [(order, a, b)]}}, {
        "effect": effect, "target": node, "targets": [node], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"{node} receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b}, **({"also_accept": alts} if alts else {})}


def stribeck(node: str, s: float, ws: float) -> Part:
    """A breakaway peak s [N m] below the Stribeck speed ws [rad/s] on ``node``."""
    return {"stribeck": {node: (s, ws)}}, {
        "effect": "stribeck-friction", "target": node, "targets": [node],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": f"{node} takes s exp(-(w/ws)^2) tanh(w/0.01) over the "
                               "declared Ts tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def coulomb(node: str, c: float) -> Part:
    """An extra Coulomb friction [N m] on ``node``."""
    return {"coul": {node: c}}, {
        "effect": "coulomb-friction", "target": node, "targets": [node],
        "parameters": {"Fc_Nm": c, "form": f"c tanh(w_{node}/0.01) against the {node}"},
        "expected": {"c": c}, "also_accept": _on_rotor("coulomb-friction", node, "c", c, 1)}


def viscous(node: str, b: float) -> Part:
    """An extra viscous friction [N m s/rad] on ``node``."""
    return {"visc": {node: b}}, {
        "effect": "viscous-friction", "target": node, "targets": [node],
        "parameters": {"b_extra_Nms_rad": b, "form": f"b w_{node} against the {node}"},
        "expected": {"b": b}, "also_accept": _on_rotor("viscous-friction", node, "b", b, 2)}


outside = recordkit.outside


combine = recordkit.combine




def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor L's clean probes at the times ``t`` [s] with the effects ``fx``."""
    fx = dict(fx)
    p = {**P, **fx.pop("p", {})}
    return sl.simulate(regime, t, fx, p)


# ---------------------------------------------------------------------- the records

def spec(rid: str, cls: str, regime: str, parts: Sequence[Part] = (),
         noise: dict | None = None, note: str = "",
         marginal: Callable[[float], Sequence[Part]] | None = None,
         size: float | None = None) -> dict[str, Any]:
    """One record's specification."""
    fx, effects = combine(parts)
    return {"id": rid, "class": cls, "regime": regime, "fx": fx, "effects": effects,
            "noise": noise, "note": note, "marginal": marginal, "size": size}


def null_and_catalog() -> list[dict[str, Any]]:
    """s01-s09: the null, catalog and two-effect records."""
    return [
        spec("s01", "null", "fast", note="white noise"),
        spec("s02", "null", "slow",
             noise={"current": {"ar1": [0.012, 0.85], "quant": 0.01},
                    "speed": {"white": 0.15, "pink": 0.15, "quant": 0.1},
                    "load_speed": {"white": 0.06, "quant": 0.05}},
             note="coloured noise: Gauss-Markov current noise (correlation 0.85 over the "
                  "mean interval, phi^(dt/mean) over an interval dt), 1/f speed noise; ADC "
                  "steps 10 mA, 0.1 rad/s, 0.05 rad/s"),
        spec("s03", "catalog", "fast", (brush_drop(0.7),),
             noise={"current": {"white": 0.02, "quant": 0.02}, "speed": {"white": 0.2}},
             note="the carbon brushes' contact drop: 0.7 V in all (both brushes), constant "
                  "with the current's size, reversing with its sign; the current read by a "
                  "12-bit ADC over +-40 A (20 mA steps)"),
        spec("s04", "catalog", "fast", (sensor("current", "delay", 5e-6),),
             marginal=lambda s: (sensor("current", "delay", s),), size=5e-6,
             note="the current amplifier's anti-alias filter lags the current by a few "
                  "microseconds (a sensor delay of the current), well below the 40 us "
                  "sample interval, scaled to a 25 sigma signature (marginal)"),
        spec("s05", "catalog", "slow", (stribeck("spindle", 0.05, 2.0),),
             noise={"current": {"ar1": [0.015, 0.7]}, "speed": {"white": 0.2},
                    "load_speed": {"white": 0.08}},
             note="the spindle's bearings have stood and their grease has set: a breakaway "
                  "peak of 0.05 N m over the declared 0.04 N m friction, gone above about "
                  "2 rad/s (Stribeck speed 2 rad/s); seen where the spindle starts, stops "
                  "and creeps through zero at the jog"),
        spec("s06", "catalog", "slow", (harmonic("spindle", 1, 0.012, 0.7),),
             note="an off-centre workpiece in the chuck (0.5 kg, its centre of mass 2.5 mm "
                  "off the axis): its weight pulls the spindle round once per spindle turn, "
                  "an unbalance of 12 mN m (0.4 times per rotor turn)"),
        spec("s07", "catalog", "slow", (viscous("spindle", 2e-4),),
             marginal=lambda s: (viscous("spindle", s),), size=2e-4,
             note="the spindle's bearings are greased more than declared (or run cold): "
                  "an extra viscous friction on the spindle, scaled to a 25 sigma signature "
                  "(marginal)"),
        spec("s08", "two", "fast", (series_resistance(0.12), harmonic("rotor", 10, 4e-3, 0.3)),
             noise={"current": {"white": 0.02}, "speed": {"white": 0.15, "pink": 0.15}},
             note="a corroded crimp in the motor lead (0.12 ohm in series with the armature), "
                  "and the motor's 2-pole, 5-slot iron cogs 10 times per turn (4 mN m on the "
                  "rotor)"),
        spec("s09", "two", "slow", (warmup(0.12, 3.0), coulomb("spindle", 0.03)),
             noise={"current": {"white": 0.02, "quant": 0.01}, "speed": {"white": 0.2},
                    "load_speed": {"white": 0.08}},
             note="the record starts from a cold motor whose winding warms up: its resistance "
                  "rises by 12 % with a 3 s time constant; and the belt is over-tensioned, "
                  "loading the spindle's bearings: an extra Coulomb friction of 0.03 N m on "
                  "the spindle"),
    ]


def outside_records() -> list[dict[str, Any]]:
    """s10-s14: effects the catalog does not contain."""
    return [
        spec("s10", "outside", "fast", (outside(
            "raised-commutator-bar", {"bar": (0.6, 40.0, 0.4)},
            {"a": 0.6, "kappa": 40.0, "phase_rad": 0.4,
             "form": "R (1 + a exp(kappa (cos(2 (th - phase)) - 1))): the armature's "
                     "resistance pulses by a R over a narrow arc twice per rotor turn"}),),
            note="one commutator bar stands proud: each brush bounces as the bar passes "
                 "under it (twice per turn, over about 10 degrees), and the contact's "
                 "resistance rises by up to 0.42 ohm while it does. A person sees the current "
                 "dip twice per turn by an amount that follows the current itself (nothing "
                 "at the zero crossings, deepest at the reversal's -15 A), where an EMF "
                 "harmonic would follow the speed; many harmonics of order 2, 4, 6, ..."),
        spec("s11", "outside", "fast", (outside(
            "advanced-brush-timing", {"timing": (0.05, 5.0)},
            {"delta": 0.05, "w0_rad_s": 5.0,
             "form": "k becomes k (1 - delta tanh(w/w0)) in the EMF and the torque"}),),
            noise={"current": {"white": 0.02, "quant": 0.02}, "speed": {"white": 0.2}},
            note="the motor's brushes are advanced for forward running (a motor made for "
                 "one direction): the armature reaction weakens the field by 5 % forward "
                 "and strengthens it by 5 % backward. A person sees a motor that runs faster "
                 "and draws more current than declared forward, slower and with less "
                 "current backward (at 159 ms 322 instead of 317 rad/s and 3.2 instead of "
                 "2.7 A; at 360 ms -139.6 instead of -143.4 rad/s): a motor constant "
                 "that depends on the direction"),
        spec("s12", "outside", "slow", (outside(
            "cutting-load", {"cut": (0.12, 2.5, 3.3, 0.03)},
            {"T_Nm": 0.12, "t1_s": 2.5, "t2_s": 3.3, "tr_s": 0.03,
             "form": "the spindle receives -T g(t) tanh(ws/1 rad/s), g = (tanh((t - t1)/tr) "
                     "- tanh((t - t2)/tr))/2"}),),
            note="a facing cut: the tool is fed into the brass workpiece at 2.5 s and "
                 "withdrawn at 3.3 s, while the command holds 12 V. A person sees the "
                 "current rise by 1.5 A and the speeds sag by 9 % for 0.8 s with no change "
                 "in the command: a load that comes and goes, neither a friction nor an "
                 "offset present all through the record"),
        spec("s13", "outside", "slow", (outside(
            "belt-creep", {"creep": 0.05},
            {"c_Nms_rad": 0.05,
             "form": "the belt carries c (w/N - ws) to a spindle that is a body of its own "
                     "(the declared belt is rigid)"}),),
            note="the poly-V belt creeps on its pulleys in proportion to the torque it "
                 "carries (1.4 rad/s of slip at 12 V, 1 %; up to 5.7 rad/s in the "
                 "accelerations): the spindle lags the rotor's speed over N in every "
                 "acceleration and runs slower while loaded. A person sees load_speed "
                 "differ from speed/2.5 by an amount that follows the current, and the "
                 "spindle respond to the rotor with an 8 ms lag"),
        spec("s14", "outside", "slow", (outside(
            "speed-from-counts", {"counts": True},
            {"form": "speed(t_k) = (th(t_k) - th(t_k-1))/(t_k - t_k-1): the mean of the "
                     "rotor's speed over the logger's own (uneven) interval before each "
                     "sample"}),),
            noise={"current": {"white": 0.02}, "speed": {"white": 0.2},
                   "load_speed": {"white": 0.08}},
            note="the logger computes the motor's speed from the encoder's counts over its "
                 "own sample intervals (which vary from 2 to 8.7 ms, and to 10 ms across a "
                 "dropped sample): each speed sample is the mean over the interval before it. A "
                 "person sees the speed lag by half an interval, a lag that changes from "
                 "sample to sample with the interval: in the accelerations the speed's "
                 "residual jumps with the timestamps' spacing; not a fixed sensor delay"),
    ]


def record_specs() -> list[dict[str, Any]]:
    """The 14 records, each with its seed."""
    out = null_and_catalog() + outside_records()
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- sample times

def times(s: dict[str, Any]) -> np.ndarray:
    """The record's own uneven sample times [s] (from its seed), once; their description in
    ``s["timestamps"]``."""
    if "t" in s:
        return s["t"]
    rng = np.random.default_rng([s["seed"], 7])
    fs, dur = sl.REGIMES[s["regime"]]
    if s["regime"] == "fast":
        jitter = round(float(rng.uniform(*JITTER)), 3)
        t = recordkit.jittered_times(rng, fs, dur, jitter)
        s["timestamps"] = (
            f"jittered: the nominal {fs / 1e3:g} kHz grid k/fs, every sample time but the "
            f"first moved by a uniform random jitter within +-{jitter:.0%} of the "
            f"{1e6 / fs:g} us interval (the last one only earlier), rounded to 1 ns; "
            f"intervals {np.diff(t).min() * 1e6:.1f}-{np.diff(t).max() * 1e6:.1f} us, "
            f"monotonic")
    else:
        drops = int(rng.integers(DROPS[0], DROPS[1] + 1))
        t, dropped = sl.logger_times(rng, fs, dur, drops)
        dt = np.diff(t)
        s["timestamps"] = (
            f"jittered: a data logger's irregular intervals, 0.6-2.6 times the mean "
            f"{1e3 / fs:.3g} ms (0.6 + 2 Beta(1, 4) of it), from 0 to {t[-1]:.4f} s, rounded "
            f"to 1 us; {drops} samples dropped (at "
            + ", ".join(f"{x:.3f}" for x in dropped)
            + f" s); intervals {dt.min() * 1e3:.2f}-{dt.max() * 1e3:.2f} ms")
    # the times exactly as the CSV holds them (10 significant digits)
    s["t"] = np.array([float(f"{x:.10g}") for x in t])
    return s["t"]


def mean_rate(t: np.ndarray) -> float:
    """The mean sample rate [Hz] of the times ``t`` [s]."""
    return float((t.size - 1) / (t[-1] - t[0]))


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-3}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:spindle", {"coul": {"spindle": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-6}}),
    ("viscous-friction:spindle", {"visc": {"spindle": 1e-5}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:spindle", {"offset": {"spindle": 1e-3}}),
    ("stribeck-friction:spindle:1", {"stribeck": {"spindle": (1e-3, 1.0)}}),
    ("stribeck-friction:spindle:3", {"stribeck": {"spindle": (1e-3, 3.0)}}),
    ("stribeck-friction:spindle:10", {"stribeck": {"spindle": (1e-3, 10.0)}}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:3", {"lsat": (3.0, 0.999)}),
    ("inductor-saturation:10", {"lsat": (10.0, 0.999)}),
    ("inertia:Js", {"p": {"Js": P["Js"] * 1.001}}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.1", {"warmup": (1e-3, 0.1)}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
    ("resistance-drift:warmup-1", {"warmup": (1e-3, 1.0)}),
)
#: angle-locked catalog effects (two columns each: the sine and the cosine), for what the
#: outside records leave: (label, builder of the fx for one column)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("cogging:rotor:2", lambda a, b: {"cog": {"rotor": [(2, a, b)]}}),
    ("unbalance:spindle", lambda a, b: {"cog": {"spindle": [(1, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf_h": (1, a, b)}),
    ("emf-harmonic:M:2", lambda a, b: {"emf_h": (2, a, b)}),
)


#: the plumbing every later set shares (recordkit.Plumbing): truth entries, marginal
#: scaling, the catalog's imprints an outside or marginal record is compared with, the CSV
KIT = recordkit.Plumbing(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sl, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=lambda label: 1e-4 if "emf" in label else (1e-3 if "spindle" in label else 1e-4),
    marginal_sigma=MARGINAL_SIGMA)
imprints = KIT.imprints
make = KIT.make


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
