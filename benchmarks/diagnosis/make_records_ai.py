"""Generate the blind set ``fresh34`` of the diagnosis benchmark: records al01-al14 of motor AI
(a 12 V brushed DC motor in a motorised garden hose reel: a rigid 25:1 spur gearhead, a roller
chain's compliance to the reel, the reel with its hose meeting the swivel seal's drag, the
hose's drag over the lawn and a quadratic whipping drag), some sampled evenly and some
UNEVENLY, three of them giving the diagnosis ONE probe only, and merge their truth into
truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_ai.py                # records/al*.csv + truth.json
    python benchmarks/diagnosis/make_records_ai.py --only al03,al12
    python benchmarks/diagnosis/make_records_ai.py --truth-only   # rewrite the al entries only

Uses simulators_ai.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_ai_slow.yaml's pwl states). A single-probe record (truth's
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
import simulators_ai as sa

RECORDS = HERE / "records"
SPLIT = "fresh34"
MOTOR = "AI"
SEED0 = 34500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_ai_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_ai_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.04, "speed": 0.8},
         "slow": {"current": 0.03, "speed": 0.6, "load_speed": 0.03}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AI
N = P["N"]
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_ai, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearhead is rigid and lossless as declared: a torque
# on the body ``hub`` (the gearhead's output and the chain sprocket) is 1/N = 1/25 of it on the
# rotor, and the hub turns with the rotor. The reel lies behind the chain (compliant, 1:1): an
# effect on it has no exact equal on the hub.

def series_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] in series with the armature (a crimped terminal)."""
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


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad] in the chain K (a slack chain)."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap, "play_deg": math.degrees(gap),
                       "form": "no chain torque while |twist| < gap/2, Ks (twist -+ gap/2) "
                               "+ Ds w_rel in contact, the damping never pulling"},
        "expected": {"gap": gap}}


def inertia_reel(dj: float) -> Part:
    """The reel's inertia off by a factor 1 + ``dj`` (a correction of Jl's J, the parameter
    Jl)."""
    return {"p": {"Jl": P["Jl"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jl", "targets": ["Jl"], "correction": True,
        "parameters": {"Jl_true_kgm2": P["Jl"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


def unbalance_reel(amp: float, phase: float) -> Part:
    """A once-per-turn torque amp sin(thl + phase) [N m] on the reel (accepted as a cogging
    of order 1 on the reel; behind the chain, it has no exact equal on the hub)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"reel": [(1, a, b)]}}, {
        "effect": "unbalance", "target": "reel", "targets": ["reel"], "order": 1,
        "parameters": {"order": 1, "T_Nm": amp, "phase_rad": phase,
                       "form": "reel receives T sin(1 angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["reel"], "order": 1,
                         "expected": {"a": a, "b": b}}]}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF harmonic w slope sin(order th + phase) [V], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def viscous_rotor(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the rotor (accepted on the hub at
    b N^2)."""
    return {"visc": {"rotor": b}}, {
        "effect": "viscous-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b w against the rotor"},
        "expected": {"b": b},
        "also_accept": [{"effect": "viscous-friction", "targets": ["hub"],
                         "expected": {"b": b * N ** 2}}]}


def coulomb_reel(c: float) -> Part:
    """An extra dry friction c tanh(wl / 0.01) [N m] on the reel (behind the chain)."""
    return {"coul": {"reel": c}}, {
        "effect": "coulomb-friction", "target": "reel", "targets": ["reel"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(wl/0.01) against the reel"},
        "expected": {"c": c}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AI's clean probes at the times ``t`` [s] with the effects ``fx``."""
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
#: the motor encoder's speed from an edge count: its resolution [rad/s]
SPEED_STEP = 0.5


def nulls() -> list[dict[str, Any]]:
    """al01, al02: the null records."""
    return [
        spec("al01", "null", "slow", True,
             noise={"current": {"white": 0.02, "ar1": [0.04, 0.85], "quant": ADC_STEP},
                    "speed": {"white": 0.5, "quant": SPEED_STEP},
                    "load_speed": {"white": 0.02, "ar1": [0.02, 0.9]}},
             note="a garden-tap data logger's irregular record; the current with Gauss-Markov "
                  "noise (correlation 0.85 over the interval, 40 mA: the PWM ripple through "
                  "the sense amplifier) on white noise, read by the controller's 10-bit ADC "
                  "(78 mA steps); the encoder's speed with white noise, read to 0.5 rad/s; "
                  "the reel's tachometer with Gauss-Markov noise (correlation 0.9, "
                  "0.02 rad/s) on white noise"),
        spec("al02", "null", "fast", False,
             noise={"current": {"white": 0.03, "pink": 0.05},
                    "speed": {"white": 0.6, "pink": 0.8, "quant": SPEED_STEP}},
             note="a bench acquisition's even 20 kHz record; the current with the sense "
                  "amplifier's 1/f noise (50 mA) on white noise; the encoder's speed with 1/f "
                  "noise (0.8 rad/s: the encoder disc's wobble) on white noise, read to "
                  "0.5 rad/s"),
    ]


def singles() -> list[dict[str, Any]]:
    """al03-al07, al10: one catalog effect each."""
    return [
        spec("al03", "catalog", "fast", True, (brush_drop(0.6),),
             note="a replacement motor with hard carbon brushes that have not bedded in: a "
                  "brush contact drop of 0.6 V (Vb tanh(i/1 mA)); the runs slower, the "
                  "braking currents smaller"),
        spec("al04", "catalog", "slow", False, (sensor("current", "offset", 0.02),),
             marginal=lambda o: (sensor("current", "offset", o),), size=0.02,
             note="the controller's current-sense amplifier has an input offset: the current "
                  "reads a constant amount high, scaled to a 25 sigma signature (marginal)"),
        spec("al05", "catalog", "fast", False, (backlash(0.08),),
             note="the roller chain has worn and stretched and its tensioner was never "
                  "adjusted: a slack of 0.08 rad (4.6 degrees of the sprocket, 1.6 mm of "
                  "chain) between the hub and the reel; the start and the reversals clack"),
        spec("al06", "catalog", "slow", True, (unbalance_reel(0.9, 0.5),),
             note="the hose was wound on in a lump on one side of the drum (the owner fed it "
                  "by hand in a heap), and it still holds water: a once-per-turn torque of "
                  "0.9 N m on the reel, phase 0.5 rad"),
        spec("al07", "catalog", "fast", False, (inertia_reel(0.45),),
             probes=("current",), noise={"current": {"white": 0.04, "quant": ADC_STEP}},
             note="a bench log of the current alone (the controller's 10-bit ADC); the hose is "
                  "full of water, the tap left on and the nozzle shut: the reel's inertia is "
                  "45 % above the declared (dJ = 0.45), its drags unchanged"),
        spec("al10", "catalog", "fast", True, (viscous_rotor(2e-5),),
             marginal=lambda b: (viscous_rotor(b),), size=2e-5,
             probes=("speed",),
             note="a bench log of the encoder's speed alone; the motor's front bearing's "
                  "grease has thickened in the cold: an extra viscous friction on the rotor, "
                  "scaled to a 25 sigma signature (marginal)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """al08, al09: two catalog effects at once."""
    return [
        spec("al08", "two", "slow", True, (warmup(0.25, 1.5), coulomb_reel(0.8)),
             note="the reel had been run in and out several times in the sun just before the "
                  "log: the winding, hot, keeps heating as it works, its resistance rising "
                  "towards 25 % above the declared with a time constant of 1.5 s (a warm-up); "
                  "and grit has got into the hose guide's rollers: an extra dry friction of "
                  "0.8 N m on the reel"),
        spec("al09", "two", "fast", False, (series_resistance(0.08, "fast"),
                                            emf_harmonic(1, 0.002, 1.1)),
             note="the motor's spade terminal was crimped badly: 0.08 Ohm in series with the "
                  "armature (a quarter of Ra); and one of the motor's two ferrite magnets "
                  "cracked and is weaker than the other: an EMF harmonic of order 1, "
                  "0.002 V s/rad, phase 1.1"),
    ]


#: the hose's drag over the lawn falling as it comes off the lawn: c [N m/rad] (Th r / l0:
#: the declared 2 N m with 15 m of hose out, the drum's 0.12 m radius)
LAWN = 0.016
#: the level-wind's reversals: the follower's drag F [N m], a reversal every P [rad] of the
#: reel (three turns of the drum a traverse), the first at th0 [rad], sharpness m
LEVELWIND = (1.5, 18.85, 9.4, 8)
#: the controller's current limit: Ilim [A], its fold-back G [ohm], softness d [A]
ILIM = (15.0, 0.3, 0.5)
#: the hose's end fitting jamming in the guide: stiffness Ke [N m/rad], from the [rad], d [rad]
NOZZLE = (25.0, 2.0, 0.05)


def outside_records() -> list[dict[str, Any]]:
    """al11-al14: effects the catalog does not contain."""
    return outside_slow() + outside_fast()


def outside_slow() -> list[dict[str, Any]]:
    """al11, al13: the hose coming off the lawn and the level-wind's reversals (slow)."""
    return [
        spec("al11", "outside", "slow", True, (outside(
            "hose-drag-falls-as-hose-comes-off-lawn", {"lawn": LAWN},
            {"c_Nm_per_rad": LAWN, "drum_radius_m": 0.12, "hose_out_m": 15.0,
             "form": "the reel receives + c thl tanh(wl/0.01): the hose's dry drag over the "
                     "lawn is proportional to the length still lying out, which shrinks by "
                     "the drum's radius per radian wound in (and grows again as it is paid "
                     "out); the declared Th is the drag with all of the hose out"}),),
            note="the declared drag of the hose over the grass, 2 N m, holds with the whole "
                 "15 m lying out; as the reel winds it in, less of it drags (0.016 N m less "
                 "per radian of the reel, 0.12 m of hose a radian): a person sees the start as "
                 "declared, then the winding current falling steadily below the declared "
                 "4.6 A (4.1 A by 2.5 s, after 28 rad), the motor and the reel a little "
                 "faster (334 instead of 329 rad/s), and the paying out starting light "
                 "(-4.1 instead of -4.7 A) and growing heavier back towards the declared as "
                 "the hose lies out again; close to a drift of the resistance or a change of "
                 "the dry friction, but one that follows the reel's angle, both ways"),
        spec("al13", "outside", "slow", False, (outside(
            "level-wind-reversal-drag", {"levelwind": LEVELWIND},
            {"F_Nm": LEVELWIND[0], "P_rad": LEVELWIND[1], "th0_rad": LEVELWIND[2],
             "m": LEVELWIND[3],
             "form": "the reel receives -F cos(pi (thl - th0)/P)^(2 m) tanh(wl/0.01): the "
                     "level-wind guide's diamond screw reverses at each end of its traverse "
                     "(every P of the reel's angle, from th0), its follower dragging through "
                     "the crossover"}),),
            note="the reel's level-wind guide lays the hose across the drum on a diamond "
                 "(double-helix) screw; at each end of its traverse, every three turns of the "
                 "drum (18.85 rad), its follower drags through the crossover, which is dry "
                 "and burred: a torque pulse of up to 1.5 N m on the reel, about 3 rad of the "
                 "reel wide; a person sees the winding current jump from 4.6 A to 6.2 A and "
                 "the motor slow from 329 to 313 rad/s for about a quarter of a second at "
                 "about 1.15 s and again at 2.6 s (9.4 rad and 28.3 rad of the reel), and the "
                 "paying out cross them back (about 3.9 s and 5.3-5.7 s), the rest as "
                 "declared; close to an unbalance or a cogging of the reel, but the pulses "
                 "come every three turns of the drum, not every turn"),
    ]


def outside_fast() -> list[dict[str, Any]]:
    """al12, al14: the controller's current limit and the hose's end fitting (fast)."""
    return [
        spec("al12", "outside", "fast", False, (outside(
            "controller-current-limit-foldback", {"ilim": ILIM},
            {"Ilim_A": ILIM[0], "G_ohm": ILIM[1], "d_A": ILIM[2],
             "form": "the loop takes G d (softplus((i - Ilim)/d) - softplus((-i - Ilim)/d)), "
                     "softplus(x) = ln(1 + exp(x)): the controller folds its output back "
                     "by G per ampere beyond its current limit Ilim, either way"}),),
            probes=("current",),
            noise={"current": {"white": 0.03, "ar1": [0.05, 0.7], "quant": ADC_STEP}},
            note="a bench log of the current alone (the controller's 10-bit ADC, the PWM "
                 "ripple as Gauss-Markov noise, correlation 0.7 over the interval, 50 mA, on "
                 "white noise); a replacement controller with a current limit of 15 A, "
                 "which folds its output back by 0.3 V per ampere beyond it: a person sees "
                 "the winding and paying-out runs as declared, but the soft start's inrush "
                 "held near 20 A (22.6 A declared), the braking at the stop held to -20 A "
                 "(-24.5 A declared) and the reversal's current flattened at -20 A (-26.6 A "
                 "declared), the speeds slower to build; close to a resistance in the loop, "
                 "but one that is there only above 15 A"),
        spec("al14", "outside", "fast", True, (outside(
            "hose-end-fitting-jams-in-guide", {"nozzle": NOZZLE},
            {"Ke_Nm_rad": NOZZLE[0], "the_rad": NOZZLE[1], "d_rad": NOZZLE[2],
             "form": "the reel receives -Ke d softplus((thl - the)/d): past the reel's angle "
                     "the the hose's end fitting, with its rubber sleeve, is pulled into the "
                     "guide's rollers and jams there, a stiff spring against winding further"}),),
            noise={"current": {"white": 0.04}, "speed": {"white": 0.8, "pink": 1.5}},
            note="the hose was nearly all wound in when the record began: after 2 rad of the "
                 "reel (0.24 m of hose) its end fitting is pulled into the guide's rollers, "
                 "and its rubber sleeve jams and compresses (25 N m a radian); the speed "
                 "column carries 1/f noise (1.5 rad/s) on white noise; a person sees the start "
                 "as declared, then from about 0.23 s the current rising (8 A instead of "
                 "4.8 A at 0.28 s) and the motor slowing (293 instead of 327 rad/s), the stop "
                 "braking far less (-8 A instead of -16 A) as the squeezed sleeve kicks the "
                 "reel back, and the paying out starting fast (-300 instead of -154 rad/s at "
                 "0.4 s); close to a spring or a force on the reel, but only past one angle "
                 "and only winding in"),
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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 34, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:hub", {"coul": {"hub": 1e-2}}),
    ("coulomb-friction:reel", {"coul": {"reel": 1e-2}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:reel", {"visc": {"reel": 1e-3}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:reel", {"offset": {"reel": 1e-2}}),
    ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-4, 10.0)}}),
    ("stribeck-friction:reel", {"stribeck": {"reel": (1e-2, 0.5)}}),
    ("backlash:K", {"gap": 1e-4}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:30", {"lsat": (30.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jl", {"p": {"Jl": P["Jl"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:reel", lambda a, b: {"cog": {"reel": [(1, a, b)]}}),
    ("cogging:rotor:10", lambda a, b: {"cog": {"rotor": [(10, a, b)]}}),
    ("cogging:reel:2", lambda a, b: {"cog": {"reel": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:10", lambda a, b: {"emf": [(10, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1 uV s/rad of EMF), 10 mN m on the reel."""
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


#: across the chain (a spring and a damper, 1:1): the body an effect on each is compared
#: with, and the factor its size takes there per kind (the hub and the reel turn at one mean
#: speed)
ACROSS = {"reel": ("hub", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0}),
          "hub": ("reel", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` across the chain
    (``recordkit.location_entry``), after a marginal record's scaling."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term of the catalog's kinds (the reel's quadratic whipping drag is a
#: behavioural torque of the declared model)
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
