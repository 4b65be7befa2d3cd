"""Generate the blind set ``fresh33`` of the diagnosis benchmark: records ak01-ak14 of motor AH
(a 24 V brushed DC motor in a sliding-gate operator: a self-locking 36:1 worm gear whose mesh
friction grows with the torque it carries, an 18-tooth pinion on the leaf's rack, the rack and
the leaf's frame a compliance, a 300 kg gate on V-groove wheels along a level track), some
sampled evenly and some UNEVENLY, three of them giving the diagnosis ONE probe only, and merge
their truth into truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_ah.py                # records/ak*.csv + truth.json
    python benchmarks/diagnosis/make_records_ah.py --only ak03,ak12
    python benchmarks/diagnosis/make_records_ah.py --truth-only   # rewrite the ak entries only

Uses simulators_ah.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_ah_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the catalog imprints it is compared with are computed on that probe
alone (``OneProbe``). Even records are sampled on the regime's grid k/fs; uneven ones, in the
fast regime, on a 20 kHz grid whose every sample is moved by a random jitter of up to 10-30 %
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
import simulators_ah as sa

RECORDS = HERE / "records"
SPLIT = "fresh33"
MOTOR = "AH"
SEED0 = 33500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_ah_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_ah_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.05, "speed": 1.0},
         "slow": {"current": 0.04, "speed": 0.8, "load_speed": 0.02}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AH
N = P["N"]
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_ah, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The worm gear is rigid and lossless as declared (its
# mesh friction is the declared Worm torque on the wheel): a torque on the body ``hub`` (the
# worm wheel and the pinion) is 1/N = 1/36 of it on the rotor, and the wheel turns with the
# rotor. The gate lies behind the rack (compliant): an effect on it has no exact equal on the
# wheel.

def source_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] inside the source (the supply's leads and fuse)."""
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[regime], "targets": [SOURCE[regime]],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": LOOP,
                         "expected": {"R": r}}]}


def saturation(ipar: float, ratio: float) -> Part:
    """The armature inductance saturating: La (ratio + (1 - ratio) / (1 + (i / Ipar)^2))."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def drift(alpha: float) -> Part:
    """The winding's resistance rising linearly, R (1 + alpha t) [1/s]."""
    return {"alpha": alpha}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + alpha*t)", "alpha_per_s": alpha},
        "expected": {"alpha": alpha}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def cogging_rotor(order: int, amp: float, phase: float) -> Part:
    """A detent torque amp sin(order th + phase) [N m] on the rotor (accepted on the wheel
    at the order order N and the amplitude amp N)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["hub"], "order": round(order * N),
                         "expected": {"a": a * N, "b": b * N}}]}


def coulomb_rotor(c: float) -> Part:
    """An extra dry friction c tanh(w / 0.01) [N m] on the rotor (accepted on the wheel at
    c N)."""
    return {"coul": {"rotor": c}}, {
        "effect": "coulomb-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(w/0.01) against the rotor"},
        "expected": {"c": c},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["hub"],
                         "expected": {"c": c * N}}]}


def stribeck_gate(s: float, ws: float) -> Part:
    """A breakaway peak s exp(-(wg/ws)^2) tanh(wg/0.01) [N m] over the gate's declared rolling
    resistance, ``ws`` [rad/s]."""
    return {"stribeck": {"gate": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "gate", "targets": ["gate"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "gate takes s exp(-(w/ws)^2) tanh(w/0.01) over the declared "
                               "Tr tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def viscous_gate(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the gate (behind the rack)."""
    return {"visc": {"gate": b}}, {
        "effect": "viscous-friction", "target": "gate", "targets": ["gate"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b wg against the gate"},
        "expected": {"b": b}}


def offset_gate(f: float) -> Part:
    """A constant torque ``f`` [N m] on the gate (behind the rack; f < 0: towards closed)."""
    return {"offset": {"gate": f}}, {
        "effect": "force-offset", "target": "gate", "targets": ["gate"],
        "parameters": {"T_Nm": f, "F_N": f / 0.036,
                       "form": "the gate receives a constant T (T < 0: pushing it towards "
                               "closed)"},
        "expected": {"F": f}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AH's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sa.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sa.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the operator board's current sense: a 12-bit ADC over +-64 A (31.25 mA steps)
ADC_STEP = 128.0 / 4096
#: the Hall encoder's speed from a period count: its resolution [rad/s]
SPEED_STEP = 0.4


def nulls() -> list[dict[str, Any]]:
    """ak01, ak02: the null records."""
    return [
        spec("ak01", "null", "fast", True,
             noise={"current": {"white": 0.03, "ar1": [0.05, 0.9], "quant": ADC_STEP},
                    "speed": {"white": 0.8, "quant": SPEED_STEP}},
             note="a commissioning kit's acquisition on its jittered clock; the current with "
                  "Gauss-Markov noise (correlation 0.9 over the interval, 50 mA: the bridge's "
                  "switching hash through the shunt amplifier) on white noise, read by the "
                  "operator board's 12-bit ADC (31.25 mA steps); the Hall encoder's speed, "
                  "computed from a period count, with white noise and read to 0.4 rad/s"),
        spec("ak02", "null", "slow", False,
             noise={"current": {"white": 0.02, "pink": 0.05, "quant": ADC_STEP},
                    "speed": {"white": 0.6, "ar1": [1.0, 0.8]},
                    "load_speed": {"white": 0.015, "pink": 0.02}},
             note="the commissioning logger's even 200 Hz record; the current read by the "
                  "operator board's 12-bit ADC with the shunt amplifier's 1/f noise (50 mA) "
                  "on white noise; the Hall encoder's speed with Gauss-Markov noise "
                  "(correlation 0.8 over the interval, 1 rad/s: the encoder's speed filter) on "
                  "white noise; the measuring wheel's gate speed with 1/f noise (the wheel "
                  "slipping on the leaf's paint, 0.02 rad/s) on white noise"),
    ]


def singles() -> list[dict[str, Any]]:
    """ak03-ak07, ak10: one catalog effect each."""
    return [
        spec("ak03", "catalog", "fast", True, (source_resistance(0.15, "fast"),),
             note="a mains failure: the operator runs from its 24 V backup pack, whose leads "
                  "pass a corroded blade-fuse holder: 0.15 Ohm inside the source (a third of "
                  "the declared Ra); the inrush, the braking and the closing's currents are "
                  "lower, the runs slower"),
        spec("ak04", "catalog", "slow", False, (stribeck_gate(3.0, 0.3),),
             marginal=lambda s: (stribeck_gate(s, 0.3),), size=3.0,
             note="the gate stood through a wet summer and the V-groove wheels' bearings "
                  "rusted: a breakaway torque s exp(-(wg/0.3)^2) tanh(wg/0.01) on the gate "
                  "(0.3 rad/s: 11 mm/s of the leaf) over its declared rolling resistance, "
                  "scaled to a 25 sigma signature (marginal)"),
        spec("ak05", "catalog", "fast", False, (offset_gate(-2.0),),
             note="the track's foundation has settled towards the post: the track falls "
                  "2 % towards the closed end and the leaf's weight pulls it that way, "
                  "56 N (a constant torque of -2 N m on the gate); the opening is slower, "
                  "the closing faster, and the rack stays loaded towards closed in the "
                  "stops"),
        spec("ak06", "catalog", "slow", True, (coulomb_rotor(0.05),),
             note="the motor was re-brushed with a kit whose brush springs are stiffer and "
                  "whose rear sleeve bearing went in dry: an extra dry friction of 0.05 N m "
                  "on the rotor (2.5 times the declared Tm)"),
        spec("ak07", "catalog", "fast", False, (saturation(14.0, 0.5),),
             probes=("current",), noise={"current": {"white": 0.05, "quant": ADC_STEP}},
             note="a bench log of the current alone (the operator board's 12-bit ADC); a "
                  "replacement motor from another maker with a thin-walled yoke: its "
                  "armature inductance saturates, dpsi/di = La (0.5 + 0.5/(1 + (i/14 A)^2)); "
                  "the inrushes and the braking currents rise and fall faster"),
        spec("ak10", "catalog", "fast", True, (sensor("speed", "delay", 3e-4),),
             marginal=lambda d: (sensor("speed", "delay", d),), size=3e-4,
             probes=("speed",),
             note="a bench log of the Hall encoder's speed alone; the operator board "
                  "averages the Hall periods over a window: a delay on speed, scaled to a "
                  "25 sigma signature (marginal)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """ak08, ak09: two catalog effects at once."""
    return [
        spec("ak08", "two", "slow", True, (drift(0.012), viscous_gate(0.5)),
             note="the log began after the installer had cycled the gate a dozen times: the "
                  "winding, hot from the cycles, is still heating, its resistance rising "
                  "1.2 % a second (a linear resistance drift); and a brush seal was fitted "
                  "along the leaf's bottom edge to keep out leaves, its bristles dragging on "
                  "the track: an extra viscous friction of 0.5 N m s/rad on the gate "
                  "(139 N s/m, 2.7 times the declared Bg)"),
        spec("ak09", "two", "fast", False, (cogging_rotor(12, 0.03, -0.6),
                                            sensor("current", "gain", 1.06)),
             note="a replacement motor of another make (4 poles, 12 slots): a detent "
                  "torque of order 12 on the rotor, 0.03 N m, phase -0.6; and the operator "
                  "board's shunt is a 1 % part of the wrong value: the current reads 6 % high, "
                  "a sensor gain of 1.06"),
    ]


#: a snow drift against the post: its stiffness ks [N m/rad], where the leaf meets it th0
#: [rad] and the softening d [rad]
SNOW = (0.8, 6.0, 0.3)
#: the brake relay's contact burnt open: the bleed resistor Ro [ohm]
RELAY = 47.0
#: the sagging leaf's tail on the paving: F [N m] between th1 and th2 [rad], edges d [rad]
SCRAPE = (3.0, 5.0, 13.0, 0.4)
#: two rack segments' pitch error e [rad at the pinion], at thj [rad], over d [rad]
JOINT = (0.014, 0.9, 0.05)


def outside_records() -> list[dict[str, Any]]:
    """ak11-ak14: effects the catalog does not contain."""
    return outside_slow() + outside_fast()


def outside_slow() -> list[dict[str, Any]]:
    """ak11, ak13: the snow drift and the leaf's scraping tail (the slow regime)."""
    return [
        spec("ak11", "outside", "slow", True, (outside(
            "snow-drift-ploughing", {"snow": SNOW},
            {"ks_Nm_rad": SNOW[0], "th0_rad": SNOW[1], "d_rad": SNOW[2],
             "th0_mm": SNOW[1] * 36.0, "ks_N_per_m": SNOW[0] / 0.036 ** 2,
             "form": "the gate receives -ks d ln(1 + exp((thg - th0)/d)) (1 + tanh(wg/0.01))/2: "
                     "past th0 the leaf's end ploughs into a snow drift and packs it, a "
                     "resistance growing with the way it has pushed in, against the opening "
                     "only (the packed snow stays behind when the gate closes)"}),),
            note="a cold night after a snowfall: the wind has piled a drift against the post the "
                 "gate opens towards, and from 0.22 m of its travel (6 rad) the leaf's end ploughs"
                 " into it and packs it: a resistance growing by 6 N per cm pushed in (0.8 N m per"
                 " rad of the pinion), 250 N by the end of the opening, against the opening only; "
                 "a person sees the first second of the opening as declared, then the current "
                 "climbing steadily (13.1 A instead of 6.7 A when the slow-down begins, 12.8 A "
                 "instead of 5.0 A at its end) and the motor and the gate slowing (279 instead of "
                 "323 rad/s of the motor, 7.7 instead of 9.0 rad/s of the gate, half the declared "
                 "speeds in the slow-down), the stop without the gate's swing on the rack, and the"
                 " closing exactly as declared; close to a friction or a force on the gate, but "
                 "one that grows with the way the gate has pushed into the drift, and only while "
                 "it opens"),
        spec("ak13", "outside", "slow", False, (outside(
            "sagging-leaf-tail-scrape", {"scrape": SCRAPE},
            {"F_Nm": SCRAPE[0], "F_N": SCRAPE[0] / 0.036, "th1_rad": SCRAPE[1],
             "th2_rad": SCRAPE[2], "d_rad": SCRAPE[3],
             "form": "the gate receives -F (tanh((thg - th1)/d) - tanh((thg - th2)/d))/2 "
                     "tanh(wg/0.01): a dry friction only while the leaf's sagging tail is "
                     "over the raised paving between th1 and th2"}),),
            note="a worn V-groove wheel lets the leaf sag and its tail drags on a raised row of "
                 "the paving between 0.18 m and 0.47 m of its travel (5 to 13 rad): a dry "
                 "friction of 83 N (3 N m) there and nowhere else; a person sees the current "
                 "2.7 A higher (9.4 A instead of 6.7 A), the motor 18 rad/s and the gate "
                 "0.5 rad/s slower while the gate crosses that stretch, on the opening "
                 "(about 0.95 to 2.05 s) and again on the closing (about 4.05 to 5.05 s), and "
                 "the start, the slow-downs and the stops as declared; close to a dry "
                 "friction on the gate, but only over a stretch of its travel"),
    ]


def outside_fast() -> list[dict[str, Any]]:
    """ak12, ak14: the open brake relay and the rack's joint (the fast regime)."""
    return [
        spec("ak12", "outside", "fast", False, (outside(
            "open-brake-relay", {"relay": RELAY},
            {"Ro_ohm": RELAY,
             "form": "the loop takes Ro (1 - tanh(u/0.5 V)^2) i (u the bridge's command): "
                     "whenever the command is zero the motor is left across the board's bleed "
                     "resistor Ro instead of the bridge's short"}),),
            probes=("current",),
            noise={"current": {"white": 0.04, "ar1": [0.05, 0.7], "quant": ADC_STEP}},
            note="a bench log of the current alone (the operator board's 12-bit ADC, the "
                 "bridge's hash as Gauss-Markov noise, correlation 0.7 over the interval, "
                 "50 mA, on white noise); the board's brake relay, which shorts the motor "
                 "whenever the command is zero, has a burnt contact that no longer closes: in "
                 "the stops the motor is left across the board's 47 Ohm bleed resistor; a "
                 "person sees the opening, the slow-downs and the closing as declared, but no "
                 "braking current at the stops (0.13 A where the declared motor brakes with "
                 "-12.1 A after the opening, 0.12 A instead of +10.2 A after the closing), the "
                 "motor coasting down against its friction and the worm's, and the closing's "
                 "start a little different (the current up to 1.9 A off); close to a "
                 "resistance in the loop, but one that is there only while the command is "
                 "zero"),
        spec("ak14", "outside", "fast", True, (outside(
            "rack-joint-pitch-error", {"joint": JOINT},
            {"e_rad": JOINT[0], "e_mm": JOINT[0] * 36.0, "thj_rad": JOINT[1],
             "thj_mm": JOINT[1] * 36.0, "d_rad": JOINT[2],
             "form": "the mesh's twist is hub.phi - gate.phi - e (1 + tanh((thg - thj)/d))/2 "
                     "in the rack's spring and in the Worm's law: two rack segments butted "
                     "with a gap e too long, the pinion crossing the joint at thj"}),),
            noise={"current": {"white": 0.05}, "speed": {"white": 1.0, "pink": 2.0}},
            note="the rack is made of 1 m segments, and the installer butted two of them with a "
                 "gap 0.5 mm too long (0.014 rad at the pinion's radius) where the pinion stands "
                 "32 mm from closed (0.9 rad of the gate); the speed column carries 1/f noise (2 "
                 "rad/s) on white noise; a person sees the start as declared, then, as the pinion "
                 "crosses the joint (0.22 s), the mesh unloading for a moment: the current 3 A "
                 "lower and the motor lurching 21 rad/s ahead, the gate's swing on the rack at the"
                 " slow-down and the stop smaller, and a lurch of the other sign as the closing "
                 "crosses the joint back (0.53 s: the current up to 2 A more negative, the motor "
                 "up to 15 rad/s slower as it stops); close to a backlash in the rack or a torque "
                 "on the gate, but at one place of the travel only"),
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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 33, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:hub", {"coul": {"hub": 1e-2}}),
    ("coulomb-friction:gate", {"coul": {"gate": 1e-2}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:gate", {"visc": {"gate": 1e-3}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:gate", {"offset": {"gate": 1e-2}}),
    ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-4, 10.0)}}),
    ("stribeck-friction:gate", {"stribeck": {"gate": (1e-2, 0.3)}}),
    ("backlash:K", {"gap": 1e-4}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:30", {"lsat": (30.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jg", {"p": {"Jg": P["Jg"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("cogging:rotor:12", lambda a, b: {"cog": {"rotor": [(12, a, b)]}}),
    ("cogging:hub:18", lambda a, b: {"cog": {"hub": [(18, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:12", lambda a, b: {"emf": [(12, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1 uV s/rad of EMF), 10 mN m on the wheel."""
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
        eight) until within 1 % of it (a breakaway's imprint is not linear in its size)."""
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


#: across the rack (a spring and a damper, 1:1): the body an effect on each is compared with,
#: and the factor its size takes there per kind (the wheel and the gate turn at one mean
#: speed)
ACROSS = {"gate": ("hub", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0}),
          "hub": ("gate", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` across the rack
    (``recordkit.location_entry``), after a marginal record's scaling."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term of the catalog's kinds (the worm's mesh friction, a law of the rack's
#: torque and the wheel's speed, is a behavioural torque of the declared model)
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
