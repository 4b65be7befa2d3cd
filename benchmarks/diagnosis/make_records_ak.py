"""Generate the blind set ``fresh36`` of the diagnosis benchmark: records an01-an14 of motor AK
(a 90 V brushed DC motor in a potter's wheel: a rigid 8:1 poly-V belt ratio, the belt's and
the long vertical shaft's compliance to the wheel head with its clay, the head meeting its
bearings' and the slurry's drag, the potter's steadying hands and the slurry film's soft
drag), some sampled evenly and some UNEVENLY, three of them giving the diagnosis ONE probe
only, and merge their truth into truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_ak.py                # records/an*.csv + truth.json
    python benchmarks/diagnosis/make_records_ak.py --only an03,an12
    python benchmarks/diagnosis/make_records_ak.py --truth-only   # rewrite the an entries only

Uses simulators_ak.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_ak_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the catalog imprints it is compared with are computed on that probe
alone (``OneProbe``). Even records are sampled on the regime's grid k/fs; uneven ones, in the
fast regime, on a 25 kHz grid whose every sample is moved by a random jitter of up to 10-30 %
of the interval, and in the slow regime at a logger's irregular intervals (0.6-1.4 times the
mean of 2 ms) with a few samples dropped. Each uneven record has its own times (from its
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
import simulators_ak as sa

RECORDS = HERE / "records"
SPLIT = "fresh36"
MOTOR = "AK"
SEED0 = 36500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_ak_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_ak_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.05, "speed": 0.5},
         "slow": {"current": 0.03, "speed": 0.4, "load_speed": 0.03}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AK
N = P["N"]
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_ak, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The belt's ratio is rigid and lossless as declared: a
# torque on the body ``hub`` (the shaft's pulley) is 1/N = 1/8 of it on the rotor, and the
# pulley turns with the rotor. The wheel head lies behind the belt and the shaft (compliant,
# 1:1): an effect on it has no exact equal on the pulley.

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


def saturation(ipar: float, ratio: float) -> Part:
    """The armature inductance saturating: La (ratio + (1 - ratio) / (1 + (i / Ipar)^2))."""
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


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF harmonic w slope sin(order th + phase) [V], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def cogging_rotor(order: int, amp: float, phase: float) -> Part:
    """A detent torque amp sin(order th + phase) [N m] on the rotor (accepted on the pulley
    at the order order N and the amplitude amp N)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["hub"], "order": round(order * N),
                         "expected": {"a": a * N, "b": b * N}}]}


def coulomb_wheel(c: float) -> Part:
    """An extra dry friction c tanh(ww / 0.01) [N m] on the wheel head (behind the belt)."""
    return {"coul": {"wheel": c}}, {
        "effect": "coulomb-friction", "target": "wheel", "targets": ["wheel"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(ww/0.01) against the wheel head"},
        "expected": {"c": c}}


def viscous_wheel(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the wheel head (behind the belt)."""
    return {"visc": {"wheel": b}}, {
        "effect": "viscous-friction", "target": "wheel", "targets": ["wheel"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b ww against the wheel head"},
        "expected": {"b": b}}


def inertia_wheel(dj: float) -> Part:
    """The wheel head's inertia (with its bat and clay) off by a factor 1 + ``dj`` (a
    correction of Jw's J, the parameter Jw)."""
    return {"p": {"Jw": P["Jw"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jw", "targets": ["Jw"], "correction": True,
        "parameters": {"Jw_true_kgm2": P["Jw"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AK's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sa.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sa.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the controller's current sense: a 10-bit ADC over +-40 A (78.1 mA steps)
ADC_STEP = 80.0 / 1024
#: the tachometer's voltage read by a 12-bit ADC over +-300 rad/s (0.146 rad/s steps)
SPEED_STEP = 600.0 / 4096


def nulls() -> list[dict[str, Any]]:
    """an01, an02: the null records."""
    return [
        spec("an01", "null", "slow", True,
             noise={"current": {"white": 0.015, "ar1": [0.04, 0.8], "quant": ADC_STEP},
                    "speed": {"white": 0.3, "quant": SPEED_STEP},
                    "load_speed": {"white": 0.02, "ar1": [0.03, 0.9]}},
             note="the studio's data logger's irregular record; the current with "
                  "Gauss-Markov noise (correlation 0.8 over the interval, 40 mA: the SCR "
                  "bridge's ripple through the sense amplifier) on white noise, read by the "
                  "controller's 10-bit ADC (78 mA steps); the tachometer's speed with white "
                  "noise, read by a 12-bit ADC (0.146 rad/s steps); the wheel head's optical "
                  "speed with Gauss-Markov noise (correlation 0.9, 0.03 rad/s: slurry "
                  "smeared on the rim's marks) on white noise"),
        spec("an02", "null", "fast", False, probes=("speed",),
             noise={"speed": {"white": 0.3, "pink": 0.5, "quant": SPEED_STEP}},
             note="a bench log of the tachometer's speed alone, an even 25 kHz record; the "
                  "speed with 1/f noise (0.5 rad/s: the tachometer's brushes) on white noise, "
                  "read by a 12-bit ADC (0.146 rad/s steps)"),
    ]


def singles() -> list[dict[str, Any]]:
    """an03-an07, an10: one catalog effect each."""
    return [
        spec("an03", "catalog", "fast", True, (emf_harmonic(1, 0.009, 0.4),),
             note="the wheel was dropped in a move and one of the motor's two ceramic magnet "
                  "arcs cracked, a piece of it lost: the back EMF varies once a turn of the "
                  "rotor, 0.009 V s/rad (2 % of k), phase 0.4 rad"),
        spec("an04", "catalog", "slow", False, (coulomb_wheel(0.3),),
             marginal=lambda c: (coulomb_wheel(c),), size=0.3,
             note="the wheel head's lower bearing got a new lip seal that has not run in: "
                  "an extra dry friction on the wheel head (behind the belt), scaled to a "
                  "25 sigma signature (marginal)"),
        spec("an05", "catalog", "fast", False, (cogging_rotor(10, 0.1, -1.0),),
             note="a replacement motor with stronger magnets and a 5-slot armature without "
                  "skew: a detent torque of 0.1 N m, 10 periods a turn of the rotor, phase "
                  "-1.0 rad"),
        spec("an06", "catalog", "slow", True, (warmup(0.35, 1.8),),
             note="the record began straight after a long session of centring heavy lumps: "
                  "the armature's winding is still heating (the motor runs hot at low speed "
                  "and high torque), its resistance settling 35 % above the declared with a "
                  "time constant of 1.8 s"),
        spec("an07", "catalog", "fast", False, (brush_drop(1.5),),
             probes=("current",), noise={"current": {"white": 0.05, "quant": ADC_STEP}},
             note="a bench log of the current alone (the controller's 10-bit ADC); the motor "
                  "was re-brushed with hard electrographitic brushes whose contact drop is "
                  "not in the declared Ra: 1.5 V"),
        spec("an10", "catalog", "fast", True, (inertia_wheel(0.1),),
             marginal=lambda dj: (inertia_wheel(dj),), size=0.1, probes=("speed",),
             note="a bench log of the tachometer's speed alone; the potter put a heavier "
                  "bat and a bigger lump of clay on the head than the declared: the wheel "
                  "head's inertia is above the declared, scaled to a 25 sigma signature "
                  "(marginal)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """an08, an09: two catalog effects at once."""
    return [
        spec("an08", "two", "slow", True,
             (viscous_wheel(0.06), sensor("current", "offset", 0.12)),
             note="slip ran down the shaft into the wheel head's upper bearing: an extra "
                  "viscous drag of 0.06 N m s/rad on the wheel head; and the current-sense "
                  "amplifier's zero has drifted: the current reads 0.12 A high"),
        spec("an09", "two", "fast", False,
             (saturation(8.0, 0.55), sensor("current", "delay", 1.5e-4)),
             note="the motor's armature iron saturates at the start's and the braking's "
                  "currents, La (0.55 + 0.45/(1 + (i/8 A)^2)); and the current is read "
                  "through the controller's isolation amplifier and its filter, 0.15 ms "
                  "late"),
    ]


#: the splash pan's rub: drag F [N m], at the wheel head's angle a [rad], width d [rad]
RUB = (2.5, 2.0, 0.25)
#: the potter's centring: extra drag F [N m] from t1 to t2 [s], edges dt [s]
HANDS = (3.0, 0.9, 1.6, 0.05)
#: the SCR bridge's ripple: the fraction m of the mean, at f [Hz] (50 Hz mains, full wave)
RIPPLE = (0.08, 100.0)
#: the commutator's flat: the resistance Rf [ohm] at the rotor's angle a [rad], width d [rad]
FLAT = (0.8, 1.0, 0.15)


def outside_records() -> list[dict[str, Any]]:
    """an11-an14: effects the catalog does not contain."""
    return outside_slow() + outside_fast()


def outside_slow() -> list[dict[str, Any]]:
    """an11, an13: the splash pan's rub and the potter's centring (slow)."""
    return [
        spec("an11", "outside", "slow", True, (outside(
            "splash-pan-rubs-wheel-head-once-a-turn", {"rub": RUB},
            {"F_Nm": RUB[0], "a_rad": RUB[1], "d_rad": RUB[2],
             "form": "the wheel head receives -F exp((cos(thw - a) - 1)/d^2) tanh(ww/0.01): "
                     "the splash pan, seated askew on the tray, touches the wheel head's rim "
                     "at one point of its turn (the head's angle a from where the record "
                     "starts), a dry drag once a turn of the head, about d wide"}),),
            note="the two-piece splash pan was put back askew after cleaning and its rim "
                 "touches the wheel head's edge at one point of the head's turn (2.0 rad from "
                 "where the record starts, over about 0.25 rad): a dry drag of up to 2.5 N m "
                 "once a turn of the head; a person sees, each time the head passes it (about "
                 "twice a second at 60 V, four times at 90 V), the current kick up by about "
                 "0.4 A for some 50 ms (1.51 to 1.94 A at 2.15 s) and the motor's speed dip "
                 "by about 2.3 rad/s, the head's speed with it; on the reversed trim the "
                 "same kicks, the other way; close to an unbalance or a cogging of the wheel "
                 "head, but a narrow drag that always opposes the motion"),
        spec("an13", "outside", "slow", False, (outside(
            "potter-leans-in-to-centre-the-clay", {"hands": HANDS},
            {"F_Nm": HANDS[0], "t1_s": HANDS[1], "t2_s": HANDS[2], "dt_s": HANDS[3],
             "form": "the wheel head receives -F s((t - t1)/dt) s((t2 - t)/dt) "
                     "tanh(ww/0.01), s(x) = 1/(1 + exp(-x)): the potter braces the elbows "
                     "and leans into the clay to centre it between the times t1 and t2, a "
                     "dry drag F over the declared hands' Tw while pressing"}),),
            note="while the wheel runs at the centring speed the potter braces and leans "
                 "into the lump from 0.9 s to 1.6 s (edges of about 50 ms), pressing 3 N m "
                 "of extra drag on the wheel head; a person sees the current climb from "
                 "1.36 A to 2.0-2.2 A and the motor slow from 126 to 122 rad/s (the head "
                 "from 15.8 to 15.2 rad/s) over those 0.7 s, then all as declared again; "
                 "close to a dry friction on the wheel head, but only for a while in the "
                 "middle of the record"),
    ]


def outside_fast() -> list[dict[str, Any]]:
    """an12, an14: the SCR bridge's ripple and the commutator's flat spot (fast)."""
    return [
        spec("an12", "outside", "fast", False, (outside(
            "scr-bridge-100-hz-ripple", {"ripple": RIPPLE},
            {"m": RIPPLE[0], "f_Hz": RIPPLE[1],
             "form": "the motor sees u(t) (1 + m cos(2 pi f t)) instead of the mean u(t) "
                     "(the pwl): the phase-controlled SCR bridge on 50 Hz mains, full wave, "
                     "its smoothing capacitor dried out, so its output carries a 100 Hz "
                     "ripple in proportion to the mean it gives"}),),
            noise={"current": {"white": 0.03, "ar1": [0.05, 0.7], "quant": ADC_STEP},
                   "speed": {"white": 0.5}},
            note="a bench acquisition of the current (the controller's 10-bit ADC, the "
                 "sense amplifier's own noise as Gauss-Markov noise, correlation 0.7 over the "
                 "interval, 50 mA, on white noise) and the tachometer's speed; the "
                 "controller's smoothing capacitor has dried out and the SCR bridge's output "
                 "carries a 100 Hz ripple of 8 % of its mean (7.2 V at 90 V); a person sees "
                 "a 100 Hz wave on the current, about 1.9 A peak to peak while running at "
                 "90 V, smaller at -60 V and gone at 0 V, and a faint one (0.9 rad/s peak to "
                 "peak) on the speed; close to nothing in the catalog (not locked to the "
                 "rotor's angle; a harmonic of the EMF at the running speed's order 3.3 at "
                 "best, while the speed holds)"),
        spec("an14", "outside", "fast", True, (outside(
            "commutator-flat-spot", {"flat": FLAT},
            {"Rf_ohm": FLAT[0], "a_rad": FLAT[1], "d_rad": FLAT[2],
             "form": "the loop takes Rf exp((cos(th - a) - 1)/d^2) i: a flat spot burnt into "
                     "the commutator (the motor was held stalled on a heavy lump while "
                     "centring), the brushes riding over it once a turn of the rotor, at its "
                     "angle a, their contact resistance rising by up to Rf there"}),),
            noise={"current": {"white": 0.05}, "speed": {"white": 0.4, "pink": 0.6}},
            note="the motor has been stalled often under heavy lumps and a bar of the "
                 "commutator burnt flat; the brushes bounce over it once a turn of the rotor "
                 "(at 1.0 rad from where the record starts, over about 0.15 rad), adding up "
                 "to 0.8 Ohm; the speed column carries 1/f noise (0.6 rad/s) on white noise; "
                 "a person sees, once a turn, a notch in the current: up to 2.3 A deep in the "
                 "soft start's 16 A, 0.2 A in the running current, and the reversal's "
                 "braking current notched the other way; the motor a little slower in the "
                 "start (up to 4.9 rad/s) and the braking weaker; close to a resistance in "
                 "series, or a harmonic of the EMF, but one that acts on the current once a "
                 "turn of the rotor, in proportion to the current, not the speed"),
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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 36, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:hub", {"coul": {"hub": 1e-3}}),
    ("coulomb-friction:wheel", {"coul": {"wheel": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-6}}),
    ("viscous-friction:wheel", {"visc": {"wheel": 1e-4}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:wheel", {"offset": {"wheel": 1e-3}}),
    ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-4, 10.0)}}),
    ("stribeck-friction:wheel", {"stribeck": {"wheel": (1e-3, 1.0)}}),
    ("backlash:K", {"gap": 1e-4}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:20", {"lsat": (20.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jw", {"p": {"Jw": P["Jw"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:wheel", lambda a, b: {"cog": {"wheel": [(1, a, b)]}}),
    ("cogging:rotor:10", lambda a, b: {"cog": {"rotor": [(10, a, b)]}}),
    ("cogging:wheel:2", lambda a, b: {"cog": {"wheel": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:10", lambda a, b: {"emf": [(10, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1 uV s/rad of EMF), 1 mN m on the wheel head."""
    return 1e-4 if (":rotor" in label or label.startswith("emf")) else 1e-3


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


#: across the belt (a spring and a damper, 1:1): the body an effect on each is compared
#: with, and the factor its size takes there per kind (the pulley and the wheel head turn at
#: one mean speed)
ACROSS = {"wheel": ("hub", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0}),
          "hub": ("wheel", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` across the belt
    (``recordkit.location_entry``), after a marginal record's scaling."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term of the catalog's kinds (the slurry film's soft dry drag is a behavioural
#: torque of the declared model)
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
