"""Generate the blind set ``fresh13`` of the diagnosis benchmark: records v01-v14 of motor N
(a 24 V brushed DC motor driving the head drum of an inclined belt conveyor through a rigid
20:1 gearhead), some sampled evenly and some UNEVENLY, and merge their truth into
truth.json.

    python benchmarks/diagnosis/make_records_n.py              # records/v*.csv + truth.json
    python benchmarks/diagnosis/make_records_n.py --only v03,v12
    python benchmarks/diagnosis/make_records_n.py --truth-only # rewrite the v entries only

Uses simulators_n.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe [SI] (and, in the slow regime, the command ``u``
[V] that motor_n_slow.yaml reads from its own table). Even records are sampled on the
regime's grid k/fs; uneven ones, in the fast regime, on a 20 kHz grid whose every sample is
moved by a random jitter of up to 15-30 % of the interval, and in the slow regime at a
logger's irregular intervals (0.4-3 times the mean of 1/400 s) with a few samples dropped.
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
import simulators_n as sn

RECORDS = HERE / "records"
SPLIT = "fresh13"
MOTOR = "N"
SEED0 = 13500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_n.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_n_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.03, "speed": 0.2},
         "slow": {"current": 0.03, "speed": 0.2, "load_speed": 0.01}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter: a fraction of the interval drawn in this range, per record
JITTER = (0.15, 0.30)
#: the slow regime's dropped samples: a count drawn in this range, per record
DROPS = (2, 7)
P = sn.MOTOR_N
N = P["N"]
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_n, truth effect). ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearhead is rigid and lossless in the declared
# model: the drum turns with the rotor at 1/N of its speed, so a torque on the drum is one
# 1/N as large on the rotor and a viscous coefficient one 1/N^2 as large (the same
# observation); those labels are accepted too.

def _other_shaft(effect: str, node: str, key: str, value: float, power: int) -> list[dict]:
    """The physically identical label of a drum effect on the rotor, or the reverse."""
    if node == "rotor":
        return [{"effect": effect, "targets": ["drum"], "expected": {key: value * N**power}}]
    return [{"effect": effect, "targets": ["rotor"], "expected": {key: value / N**power}}]


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain or offset [1, probe unit]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def brush_drop(vb: float) -> Part:
    """A brush contact drop [V]."""
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


def source_resistance(r: float, regime: str) -> Part:
    """An internal resistance [ohm] of the supply (the regime's source)."""
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[regime], "targets": [SOURCE[regime]],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": ["Ra", "La", "M"],
                         "expected": {"R": r}}]}


def saturation(ipar: float, ratio: float) -> Part:
    """The armature's iron saturating: knee current [A], saturated inductance ratio [1]."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"I_knee_A": ipar, "L_ratio_saturated": ratio,
                       "form": "La(i) = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2)), the "
                               "differential inductance"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def warmup(rise: float, tau: float) -> Part:
    """The winding warming up: a relative rise [1] with a time constant [s]."""
    return {"warmup": (rise, tau)}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + rise*(1 - exp(-t/tau)))", "rise": rise,
                       "tau_s": tau},
        "expected": {"rise": rise, "tau": tau}}


def cogging(order: int, amp: float, phase: float) -> Part:
    """The rotor's detent torque amp sin(order angle + phase) [N m]."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    alts = [{"effect": "cogging", "targets": ["drum"], "order": int(order * N),
             "expected": {"a": a * N, "b": b * N}}]
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b}, "also_accept": alts}


def coulomb(node: str, c: float) -> Part:
    """An extra Coulomb friction [N m] on ``node``."""
    return {"coul": {node: c}}, {
        "effect": "coulomb-friction", "target": node, "targets": [node],
        "parameters": {"Fc_Nm": c, "form": f"c tanh(w_{node}/0.01) against the {node}"},
        "expected": {"c": c}, "also_accept": _other_shaft("coulomb-friction", node, "c", c, 1)}


def viscous(node: str, b: float) -> Part:
    """An extra viscous friction [N m s/rad] on ``node``."""
    return {"visc": {node: b}}, {
        "effect": "viscous-friction", "target": node, "targets": [node],
        "parameters": {"b_extra_Nms_rad": b, "form": f"b w_{node} against the {node}"},
        "expected": {"b": b}, "also_accept": _other_shaft("viscous-friction", node, "b", b, 2)}


outside = recordkit.outside


combine = recordkit.combine




def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor N's clean probes at the times ``t`` [s] with the effects ``fx``."""
    fx = dict(fx)
    p = {**P, **fx.pop("p", {})}
    return sn.simulate(regime, t, fx, p)


# ---------------------------------------------------------------------- the records

def spec(rid: str, cls: str, regime: str, uneven: bool, parts: Sequence[Part] = (),
         noise: dict | None = None, note: str = "",
         marginal: Callable[[float], Sequence[Part]] | None = None,
         size: float | None = None) -> dict[str, Any]:
    """One record's specification."""
    fx, effects = combine(parts)
    return {"id": rid, "class": cls, "regime": regime, "uneven": uneven, "fx": fx,
            "effects": effects, "noise": noise, "note": note, "marginal": marginal,
            "size": size}


ADC_I = {"white": 0.03, "quant": 0.02}


def null_and_catalog() -> list[dict[str, Any]]:
    """v01-v09: the null, catalog and two-effect records."""
    return [
        spec("v01", "null", "fast", False, note="white noise"),
        spec("v02", "null", "slow", True,
             noise={"current": {"white": 0.02, "ar1": [0.03, 0.85], "quant": 0.02},
                    "speed": {"white": 0.15, "pink": 0.2},
                    "load_speed": {"white": 0.01, "quant": 0.005}},
             note="coloured noise: Gauss-Markov current noise (correlation 0.85 over the mean "
                  "interval, phi^(dt/mean) over an interval dt) and a 12-bit ADC over +-40 A "
                  "(20 mA steps) on the current, 1/f noise on the speed, 5 mrad/s steps on "
                  "the drum's speed"),
        spec("v03", "catalog", "fast", True, (source_resistance(0.12, "fast"),),
             noise={"current": ADC_I, "speed": {"white": 0.2}},
             note="the bench supply's output stage and its 3 m of thin leads: 0.12 ohm "
                  "inside the source, seen as the command sagging with the current; the "
                  "current read by a 12-bit ADC over +-40 A (20 mA steps)"),
        spec("v04", "catalog", "fast", False, (cogging(12, 0.02, 0.3),),
             note="the motor's 4-pole, 6-slot iron cogs 12 times per rotor turn: a detent "
                  "torque of 20 mN m on the rotor (5 % of the rated torque), seen where the "
                  "rotor turns slowly: the start, the braked creep back and the reversal"),
        spec("v05", "catalog", "slow", True, (coulomb("drum", 0.02),),
             marginal=lambda s: (coulomb("drum", s),), size=0.02,
             note="a belt scraper barely touching the return belt at the head drum: an extra "
                  "Coulomb drag on the drum, reversing with the belt, scaled to a 25 sigma "
                  "signature (marginal)"),
        spec("v06", "catalog", "slow", False, (brush_drop(0.6),),
             noise={"current": {"white": 0.03, "ar1": [0.02, 0.7]}, "speed": {"white": 0.2},
                    "load_speed": {"white": 0.01}},
             note="the carbon brushes' contact drop: 0.6 V in all (both brushes), constant "
                  "with the current's size, reversing with its sign; Gauss-Markov current "
                  "noise"),
        spec("v07", "catalog", "fast", True, (sensor("speed", "gain", 1.001),),
             marginal=lambda s: (sensor("speed", "gain", 1.0 + s),), size=1e-3,
             note="the encoder's speed scaling is a little off (a warm tachometer interface "
                  "whose reference has drifted): a gain on the speed reading, scaled to a "
                  "25 sigma signature (marginal)"),
        spec("v08", "two", "fast", False, (saturation(18.0, 0.5), sensor("current", "offset",
                                                                          0.12)),
             noise={"current": {"white": 0.03}, "speed": {"white": 0.15, "pink": 0.15}},
             note="the armature's iron saturates at the start-up, braking and plugging "
                  "currents (knee 18 A, the differential inductance falling towards half "
                  "the declared 0.8 mH); and the Hall current sensor's zero has drifted by "
                  "+0.12 A; 1/f noise on the speed"),
        spec("v09", "two", "slow", True, (warmup(0.12, 3.0), viscous("drum", 0.03)),
             noise={"current": ADC_I, "speed": {"white": 0.2}, "load_speed": {"white": 0.01}},
             note="the record starts from a cold motor whose winding warms up: its resistance "
                  "rises by 12 % with a 3 s time constant; and the idlers' grease is cold "
                  "and stiff: an extra viscous drag of 0.03 N m s/rad on the drum; the "
                  "current read by a 12-bit ADC (20 mA steps)"),
    ]


#: the holding brake's spans released [s]: the drive energises its coil with the command
#: (0.2 s, 4.6 s, 6.5 s) and drops it with the stops (4.0 s, 6.1 s); the brake releases
#: 120 ms late and is applied 150 ms after each stop
BRAKE_SPANS = ((0.32, 4.15), (4.72, 6.25), (6.62, 9.0))
#: the dropped parcel: m [kg], mu, slope [rad], drum radius [m], t_drop [s], tr [s], eps [m/s]
PARCEL = (12.0, 0.5, math.radians(10.0), 0.05, 2.0, 0.005, 1e-3)


def outside_fast() -> list[dict[str, Any]]:
    """v10-v11: effects the catalog does not contain, fast regime."""
    return [
        spec("v10", "outside", "fast", True, (outside(
            "brush-bounce", {"bounce": (0.25, 330.0, 20.0)},
            {"Rb_ohm": 0.25, "w1_rad_s": 330.0, "dw_rad_s": 20.0,
             "form": "the loop takes Rb (1 + tanh((|w| - w1)/dw))/2 i more: the brushes "
                     "lose contact part of the time above about w1"}),),
            note="the brush springs are weak and the commutator slightly out of round: "
                 "above about 330 rad/s the brushes bounce, and the contact's mean "
                 "resistance rises by up to 0.25 ohm. A person sees a loop resistance that "
                 "is the declared one at low and moderate speed and larger at full speed "
                 "only (the run at 24 V, the first moments of the step down): a resistance "
                 "that follows the speed, neither constant nor drifting in time"),
        spec("v11", "outside", "fast", False, (outside(
            "current-sensor-bandwidth", {"csensor": (1500.0, 0.35)},
            {"fn_Hz": 1500.0, "zeta": 0.35,
             "form": "the current reads y, y'' = (2 pi fn)^2 (i - y) - 2 zeta (2 pi fn) y', "
                     "from rest"}),),
            note="the current is read through the drive's Hall sensor and a second-order "
                 "anti-alias filter of too low a corner (1.5 kHz, damping ratio 0.35: a "
                 "30 % overshoot on a step). A person sees the current reading lag the "
                 "current's fast changes and ring after the command's corners at about "
                 "1.4 kHz, with an overshoot no delay gives, while the speed agrees"),
    ]


def outside_slow() -> list[dict[str, Any]]:
    """v12-v14: effects the catalog does not contain, slow regime."""
    return [
        spec("v12", "outside", "slow", True, (outside(
            "parcel-pitch-load", {"items": (0.085, 0.8, 0.05, 4.0, 0.6)},
            {"dT_Nm": 0.085, "pitch_m": 0.8, "drum_radius_m": 0.05, "kappa": 4.0,
             "phase_rad": 0.6,
             "form": "the drum receives -dT tanh(kappa sin(2 pi r thd/pitch + phase)) about "
                     "the declared gravity torque; thd the drum's angle"}),),
            noise={"current": {"white": 0.03}, "speed": {"white": 0.2},
                   "load_speed": {"white": 0.01}},
            note="2 kg parcels are placed on the belt every 0.8 m; as one arrives at the "
                 "foot of the incline and another tips off at its head, the number on the "
                 "incline alternates between n and n + 1, and the gravity torque at the drum "
                 "swings by +-85 mN m (about +-0.07 A at the motor) about the declared mean, "
                 "periodic in the belt's travel: once per 16 rad of the drum, 2.55 drum "
                 "turns, a non-integer order of both shafts (0.39 of the drum, 7.85 of the "
                 "rotor). A person sees a square-ish load wave whose period follows the "
                 "belt's travel, not a shaft's turn"),
        spec("v13", "outside", "slow", False, (outside(
            "late-holding-brake", {"brake": (0.3, 0.01, BRAKE_SPANS)},
            {"Tb_Nm": 0.3, "tr_s": 0.01,
             "released_s": [list(x) for x in BRAKE_SPANS],
             "form": "the rotor receives -Tb g(t) tanh(w/0.01), g = 1 - sum over the "
                     "released spans (a, b) of (tanh((t - a)/tr) - tanh((t - b)/tr))/2"}),),
            note="a spring-applied holding brake on the motor's rear shaft (0.3 N m), not "
                 "in the netlist, whose coil the drive energises with each move: it "
                 "releases 120 ms after the command starts (the motor pushes against it "
                 "meanwhile: the current rises with the command while the rotor stands) and "
                 "is applied 150 ms after each stop, holding the belt where the declared "
                 "model lets the parcels pull it back. A person sees the rotor stand still "
                 "at the start, then lurch, and stand still again during the pauses with "
                 "the current at zero"),
        spec("v14", "outside", "slow", True, (outside(
            "parcel-drop", {"parcel": PARCEL},
            {"m_kg": PARCEL[0], "mu": PARCEL[1], "slope_rad": PARCEL[2], "r_m": PARCEL[3],
             "t_drop_s": PARCEL[4], "tr_s": PARCEL[5], "eps_m_s": PARCEL[6],
             "form": "m dvp/dt = h(t) (F - m g sin(slope)), F = mu m g cos(slope) "
                     "tanh((r wd - vp)/eps), h = (1 + tanh((t - t_drop)/tr))/2; the drum "
                     "receives -F r"}),),
            noise={"current": {"white": 0.03, "quant": 0.02}, "speed": {"white": 0.2},
                   "load_speed": {"white": 0.01}},
            note="a 12 kg parcel is dropped from a side chute onto the running belt at 2.0 s "
                 "(while the command holds 24 V): it slides for about 0.3 s, the belt's "
                 "kinetic friction (mu 0.5, 58 N) dragging it up to speed, then rides up the "
                 "incline with the belt for the rest of the record. A person sees the current "
                 "jump by about 2.4 A with a dip in both speeds while it slides, then settle "
                 "0.85 A above the declared model (its weight on the incline), and every "
                 "later acceleration take longer (the belt's load 40 % heavier): a load and "
                 "an inertia that change once during the record, with a slipping transient"),
    ]


def record_specs() -> list[dict[str, Any]]:
    """The 14 records, each with its seed."""
    out = null_and_catalog() + outside_fast() + outside_slow()
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- sample times

def _tidy(t: np.ndarray) -> np.ndarray:
    """The times exactly as the CSV holds them (10 significant digits) [s]."""
    return np.array([float(f"{x:.10g}") for x in t])


def times(s: dict[str, Any]) -> np.ndarray:
    """The record's sample times [s] (even, or uneven from its seed), once; an uneven
    record's are described in ``s["timestamps"]``."""
    if "t" in s:
        return s["t"]
    fs, dur = sn.REGIMES[s["regime"]]
    if not s["uneven"]:
        s["t"] = _tidy(sn.grid(s["regime"]))
        s["timestamps"] = f"even: k/fs, fs = {fs:g} Hz"
        return s["t"]
    rng = np.random.default_rng([s["seed"], 11])
    if s["regime"] == "fast":
        jitter = round(float(rng.uniform(*JITTER)), 3)
        t = recordkit.jittered_times(rng, fs, dur, jitter)
        s["timestamps"] = (
            f"jittered: the nominal {fs / 1e3:g} kHz grid k/fs, every sample time but the "
            f"first moved by a uniform random jitter within +-{jitter:.1%} of the "
            f"{1e6 / fs:g} us interval (the last one only earlier), rounded to 1 ns; "
            f"intervals {np.diff(t).min() * 1e6:.1f}-{np.diff(t).max() * 1e6:.1f} us")
    else:
        drops = int(rng.integers(DROPS[0], DROPS[1] + 1))
        t, dropped = sn.logger_times(rng, fs, dur, drops)
        dt = np.diff(t)
        s["timestamps"] = (
            f"jittered: a data logger's irregular intervals, 0.4 + 0.6 Gamma(3, 1/3) times "
            f"the mean {1e3 / fs:.3g} ms (at most 3 times), from 0 to {t[-1]:.4f} s, "
            f"rounded to 1 us; {drops} samples dropped (at "
            + ", ".join(f"{x:.4f}" for x in dropped)
            + f" s); intervals {dt.min() * 1e3:.2f}-{dt.max() * 1e3:.2f} ms")
    s["t"] = _tidy(t)
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
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-6}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("stribeck-friction:drum:1", {"stribeck": {"drum": (1e-3, 1.0)}}),
    ("stribeck-friction:drum:10", {"stribeck": {"drum": (1e-3, 10.0)}}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:10", {"lsat": (10.0, 0.999)}),
    ("inductor-saturation:30", {"lsat": (30.0, 0.999)}),
    ("inertia:Jd", {"p": {"Jd": P["Jd"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.1", {"warmup": (1e-3, 0.1)}),
    ("resistance-drift:warmup-1", {"warmup": (1e-3, 1.0)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:drum", lambda a, b: {"cog": {"drum": [(1, a, b)]}}),
    ("cogging:rotor:8", lambda a, b: {"cog": {"rotor": [(8, a, b)]}}),
    ("cogging:rotor:12", lambda a, b: {"cog": {"rotor": [(12, a, b)]}}),
)


#: the plumbing every later set shares (recordkit.Plumbing): truth entries, marginal
#: scaling, the catalog's imprints an outside or marginal record is compared with, the CSV
KIT = recordkit.Plumbing(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sn, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=lambda label: 1e-3,
    marginal_sigma=MARGINAL_SIGMA)
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
