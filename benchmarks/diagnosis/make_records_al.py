"""Generate the blind set ``fresh37`` of the diagnosis benchmark: records ao01-ao14 of motor AL
(an 18 V brushed DC motor with a brass flywheel in a G-scale garden-railway locomotive: a
rigid 28:1 worm gear to the driving axles, which carry the locomotive's own mass, the sprung
drawbar coupler's compliance to the rake of coaches, the rake meeting its bushes' drag, its
rolling resistance and its lighting skates' soft drag), some sampled evenly and some
UNEVENLY, three of them giving the diagnosis ONE probe only, and merge their truth into
truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_al.py                # records/ao*.csv + truth.json
    python benchmarks/diagnosis/make_records_al.py --only ao03,ao12
    python benchmarks/diagnosis/make_records_al.py --truth-only   # rewrite the ao entries only

Uses simulators_al.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_al_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the catalog imprints it is compared with are computed on that probe
alone (``OneProbe``). Even records are sampled on the regime's grid k/fs; uneven ones, in the
fast regime, on a 20 kHz grid whose every sample is moved by a random jitter of up to 10-30 %
of the interval, and in the slow regime at a logger's irregular intervals (0.6-1.4 times the
mean of 4 ms) with a few samples dropped. Each uneven record has its own times (from its
seed), and the motor is simulated at those very times (``t_eval``), never interpolated.
truth.json is merged under an exclusive lock (recordkit.merge). An outside record whose
imprint the catalog's effects jointly leave less than OUTSIDE_LEFT of is reported (it would
not be outside in effect). Nobody ran the diagnosis on these records.
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
import simulators_al as sa

RECORDS = HERE / "records"
SPLIT = "fresh37"
MOTOR = "AL"
SEED0 = 37500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_al_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_al_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.01, "speed": 0.4},
         "slow": {"current": 0.008, "speed": 0.3, "load_speed": 0.02}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: an outside record's imprint must keep at least this fraction after all the catalog's
#: effects jointly (linearised)
OUTSIDE_LEFT = 0.2
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AL
N = P["N"]
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_al, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The worm gear is rigid and lossless as declared: a
# torque on the body ``hub`` (the driving axles with the locomotive) is 1/N = 1/28 of it on
# the rotor, and the axles turn with the rotor. The rake of coaches lies behind the coupler
# (compliant, 1:1 in the reflected frame): an effect on it has no exact equal on the axles.

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


def speed_gain(excess: float) -> Part:
    """The speed encoder's gain 1 + ``excess`` (a marginal record scales the excess)."""
    return sensor("speed", "gain", 1.0 + excess)


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF harmonic w slope sin(order th + phase) [V], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad] in the coupler K (a worn coupler's slack)."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap, "play_mm": gap * sa.R_WHEEL * 1e3,
                       "form": "no coupler torque while |twist| < gap/2, Ks (twist -+ gap/2) "
                               "+ Ds w_rel in contact, the damping never pulling"},
        "expected": {"gap": gap}}


def stribeck_rotor(s: float, ws: float) -> Part:
    """A breakaway peak s exp(-(w/ws)^2) tanh(w/0.01) [N m] over the rotor's declared dry
    friction, ``ws`` [rad/s] (accepted on the axles at s N and ws / N)."""
    return {"stribeck": {"rotor": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "rotor takes s exp(-(w/ws)^2) tanh(w/0.01) over the declared "
                               "Tm tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws},
        "also_accept": [{"effect": "stribeck-friction", "targets": ["hub"],
                         "expected": {"s": s * N, "ws": ws / N}}]}


def unbalance_train(amp: float, phase: float) -> Part:
    """A once-per-turn torque amp sin(thc + phase) [N m] on the rake (accepted as a cogging
    of order 1 on the rake; behind the coupler, it has no exact equal on the axles)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"train": [(1, a, b)]}}, {
        "effect": "unbalance", "target": "train", "targets": ["train"], "order": 1,
        "parameters": {"order": 1, "T_Nm": amp, "phase_rad": phase,
                       "form": "train receives T sin(1 angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["train"], "order": 1,
                         "expected": {"a": a, "b": b}}]}


def viscous_train(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the rake (behind the coupler)."""
    return {"visc": {"train": b}}, {
        "effect": "viscous-friction", "target": "train", "targets": ["train"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b wc against the rake"},
        "expected": {"b": b}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AL's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sa.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sa.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the power pack's current sense: a 10-bit ADC over +-6 A (11.7 mA steps)
ADC_STEP = 12.0 / 1024
#: the flywheel encoder's speed, 12-bit over +-600 rad/s (0.293 rad/s steps)
SPEED_STEP = 1200.0 / 4096


def nulls() -> list[dict[str, Any]]:
    """ao01, ao02: the null records."""
    return [
        spec("ao01", "null", "fast", True, probes=("current",),
             noise={"current": {"white": 0.006, "ar1": [0.012, 0.85], "quant": ADC_STEP}},
             note="a bench log of the current alone, a jittered 20 kHz acquisition; the "
                  "current with Gauss-Markov noise (correlation 0.85 over the interval, 12 mA: "
                  "the rails' contact noise through the sense amplifier) on white noise, read "
                  "by the power pack's 10-bit ADC (11.7 mA steps)"),
        spec("ao02", "null", "slow", False,
             noise={"current": {"white": 0.006, "pink": 0.01, "quant": ADC_STEP},
                    "speed": {"white": 0.2, "pink": 0.4, "quant": SPEED_STEP},
                    "load_speed": {"white": 0.015, "ar1": [0.02, 0.9]}},
             note="the layout's data logger, an even record; the current with 1/f noise "
                  "(10 mA: the pickups' wiping contact on the outdoor rails) on white noise, "
                  "read by the 10-bit ADC (11.7 mA steps); the flywheel encoder's speed with "
                  "1/f noise (0.4 rad/s) on white noise, read as 12 bits (0.293 rad/s steps); "
                  "the rake's axle sensor with Gauss-Markov noise (correlation 0.9, 0.02 "
                  "rad/s) on white noise"),
    ]


def singles() -> list[dict[str, Any]]:
    """ao03-ao07, ao10: one catalog effect each."""
    return [
        spec("ao03", "catalog", "fast", True, (emf_harmonic(2, 5e-4, 0.9),),
             note="one of the motor's two ferrite magnet arcs came unglued and slid in the "
                  "can: the flux is no longer symmetric and the back EMF varies twice a turn "
                  "of the rotor, 5e-4 V s/rad (1.4 % of k), phase 0.9 rad"),
        spec("ao04", "catalog", "slow", False, (stribeck_rotor(2e-3, 30.0),),
             marginal=lambda s: (stribeck_rotor(s, 30.0),), size=2e-3,
             note="the locomotive stood in the shed all winter and the motor's sintered "
                  "bronze bearings have dried out: a breakaway over the rotor's declared dry "
                  "friction, fading above about 30 rad/s, scaled to a 25 sigma signature "
                  "(marginal)"),
        spec("ao05", "catalog", "fast", False, (backlash(0.13),),
             note="the locomotive's drawbar coupler is worn: a slack of 0.13 rad of the "
                  "wheels (2.9 mm at the rail) before the coupler's spring takes up, on "
                  "starting, on braking and on reversing"),
        spec("ao06", "catalog", "slow", True, (warmup(-0.2, 2.5),),
             note="the record began straight after the locomotive had stood in the summer "
                  "sun on the layout (its black boiler hot): running, the winding cools in "
                  "the draught of the flywheel and the open cab, its resistance settling "
                  "20 % below the declared with a time constant of 2.5 s"),
        spec("ao07", "catalog", "fast", False, (inductance(0.5),),
             probes=("current",), noise={"current": {"white": 0.01, "quant": ADC_STEP}},
             note="a bench log of the current alone (the 10-bit ADC); the motor is a "
                  "replacement of another winding (more turns of finer wire): its armature "
                  "inductance is 50 % above the declared"),
        spec("ao10", "catalog", "fast", True, (speed_gain(0.005),),
             marginal=lambda g: (speed_gain(g),), size=0.005, probes=("speed",),
             note="a bench log of the flywheel encoder's speed alone; the encoder's disc was "
                  "replaced by one whose slot count differs from the one the logger's "
                  "scaling assumes: the speed reads high by a constant factor, scaled to a "
                  "25 sigma signature (marginal)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """ao08, ao09: two catalog effects at once."""
    return [
        spec("ao08", "two", "slow", True,
             (unbalance_train(0.015, 1.2), sensor("speed", "offset", 1.5)),
             note="a coach's wheelset was re-pressed off centre on its axle after a "
                  "derailment: the coach rises and falls once a turn of its wheels (the same "
                  "45 mm as the locomotive's), a torque of 0.015 N m on the rake, phase "
                  "1.2 rad; and the encoder's interface has a zero error: the speed reads "
                  "1.5 rad/s high"),
        spec("ao09", "two", "fast", False, (brush_drop(0.4), viscous_train(3e-3)),
             note="the motor was fitted with harder carbon brushes whose contact drop is not "
                  "in the declared Ra: 0.4 V; and the coaches' axle bushes were oiled with a "
                  "thick gear oil: an extra viscous drag of 3e-3 N m s/rad on the rake"),
    ]


#: the ramp up to the bridge: gravity's torque Tg [N m] on the rake while its angle is
#: between a1 and a2 [rad], edges d [rad] (a 3.5 % ramp for the 8 kg rake: 2.7 N)
GRADE = (0.06, 24.0, 40.0, 2.0)
#: the dirty rail: a contact resistance Rd [ohm] while the axles' angle is between x1 and
#: x2 [rad], edges dx [rad]
DIRT = (3.0, 53.0, 57.0, 0.3)
#: the power pack's current limiter: Ilim [A], the fold-back Rc [ohm], the knee e [A]
LIMIT = (3.0, 1.5, 0.05)
#: the loose flywheel: its inertia Jf [kg m^2], its set screw's slip torque Tc [N m], the
#: slip's speed scale ws [rad/s]
SLIP = (3e-5, 0.1, 0.5)


def outside_records() -> list[dict[str, Any]]:
    """ao11-ao14: effects the catalog does not contain."""
    return outside_slow() + outside_fast()


def outside_slow() -> list[dict[str, Any]]:
    """ao11, ao13: the ramp up to the bridge and the dirty stretch of rail (slow)."""
    return [
        spec("ao11", "outside", "slow", True, (outside(
            "rake-climbs-ramp-to-bridge", {"grade": GRADE},
            {"Tg_Nm": GRADE[0], "a1_rad": GRADE[1], "a2_rad": GRADE[2], "d_rad": GRADE[3],
             "form": "the rake receives -Tg s((thc - a1)/d) s((a2 - thc)/d), "
                     "s(x) = 1/(1 + exp(-x)), thc the rake's angle (its travel over the "
                     "wheels' 22.5 mm radius from where the record starts): the track climbs "
                     "a 3.5 % ramp up to a level bridge over the garden pond between a1 and "
                     "a2, gravity along the ramp pulling the rake back whichever way it "
                     "runs, the rake's length spreading each end over about d"}),),
            note="the layout was rebuilt with a bridge over the pond, reached by a 3.5 % "
                 "ramp from 0.54 m to 0.90 m along the track from where the record starts "
                 "(the rake's angle 24 to 40 rad): gravity pulls the 8 kg rake back with "
                 "0.06 N m at its wheels while it climbs; a person sees, from about 3.1 s to "
                 "4.4 s, the current up from 0.22 A to 0.28 A and the motor slower by up to "
                 "4.3 rad/s (of 498), the rake by 0.15 rad/s, then all as declared again; "
                 "close to a force offset or a dry friction on the rake, but only over a "
                 "stretch of the track, and the same whichever way it runs"),
        spec("ao13", "outside", "slow", False, (outside(
            "dirty-rail-stretch", {"dirt": DIRT},
            {"Rd_ohm": DIRT[0], "x1_rad": DIRT[1], "x2_rad": DIRT[2], "dx_rad": DIRT[3],
             "form": "the loop takes Rd s((th/N - x1)/dx) s((x2 - th/N)/dx) i, "
                     "s(x) = 1/(1 + exp(-x)), th/N the axles' angle (the locomotive's travel "
                     "over the wheels' radius from where the record starts): a stretch of "
                     "rail dulled by oxide and leaf litter between x1 and x2, the pickups' "
                     "contact resistance rising by Rd while the locomotive runs over it"}),),
            note="a 90 mm stretch of rail under the hedge is dull with oxide and leaf "
                 "litter, 1.19 m to 1.28 m along the track (the axles' angle 53 to 57 rad): "
                 "the pickups' contact resistance rises by 3 Ohm while the locomotive is on "
                 "it; a person sees the locomotive cross it while slowing (4.8 to 5.1 s): the "
                 "braking current weakened from -0.57 A to -0.43 A and the motor up to 33 "
                 "rad/s faster than declared (the rake 1.2 rad/s), so it stops a little "
                 "further on; backing, it crosses it again (7.1 to 7.6 s); close to a "
                 "resistance in series for a while, but one that acts at a place of the "
                 "track, not a time"),
    ]


def outside_fast() -> list[dict[str, Any]]:
    """ao12, ao14: the power pack's current limiter and the loose flywheel (fast)."""
    return [
        spec("ao12", "outside", "fast", False, (outside(
            "power-pack-current-limit", {"limit": LIMIT},
            {"Ilim_A": LIMIT[0], "Rc_ohm": LIMIT[1], "e_A": LIMIT[2],
             "form": "the loop takes Rc e softplus((|i|_s - Ilim)/e) tanh(i/1 mA), "
                     "|i|_s = sqrt(i^2 + (1 mA)^2), softplus(x) = ln(1 + exp(x)): the hobby "
                     "power pack's electronic current limiter folds its output back by Rc "
                     "per ampere above Ilim (a knee e wide), in either direction"}),),
            noise={"current": {"white": 0.008, "ar1": [0.01, 0.7], "quant": ADC_STEP},
                   "speed": {"white": 0.4}},
            note="a bench acquisition of the current (the 10-bit ADC, the sense amplifier's "
                 "own noise as Gauss-Markov noise, correlation 0.7 over the interval, 10 mA, "
                 "on white noise) and the flywheel encoder's speed, the locomotive fed by a "
                 "3 A hobby power pack whose current limiter folds its output back by 1.5 V "
                 "per ampere over 3 A; a person sees the start's current peak held at 4.2 A "
                 "(declared 4.8 A), the reversal's braking current at -4.9 A (declared "
                 "-5.6 A), the motor starting a little slower and the reversal's braking "
                 "weaker (the rotor up to 35 rad/s off), and nothing while the current stays "
                 "under 3 A; close to a resistance in series or a brush drop, but one that "
                 "acts only above a current"),
        spec("ao14", "outside", "fast", True, (outside(
            "flywheel-slipping-on-motor-shaft", {"slip": SLIP},
            {"Jf_kgm2": SLIP[0], "Tc_Nm": SLIP[1], "ws_rad_s": SLIP[2],
             "form": "the brass flywheel (Jf of the declared Jm) is loose on the motor's "
                     "shaft, held by its set screw's friction only: the rotor carries "
                     "Jm - Jf and receives -Tc tanh((w - wf)/ws); the flywheel, at its own "
                     "speed wf, receives +Tc tanh((w - wf)/ws)"}),),
            noise={"current": {"white": 0.01}, "speed": {"white": 0.3, "pink": 0.5}},
            note="the brass flywheel's set screw has worked loose and the flywheel (3e-5 "
                 "kg m^2 of the declared 4e-5) is held on the motor's shaft by friction "
                 "only, up to 0.1 N m; the speed column carries 1/f noise (0.5 rad/s) on "
                 "white noise; a person sees the armature run ahead of the flywheel late in "
                 "the start (slipping from 0.093 s to 0.108 s) and behind it in the stop "
                 "(0.33 s to 0.38 s) and the reversal (0.40 s to 0.47 s), up to 43 rad/s "
                 "apart: the motor's speed up to 22 rad/s off the declared, the reversal's "
                 "braking current 0.3 A weaker; close to a smaller rotor inertia, but only "
                 "while the acceleration is high"),
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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 37, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-5}}),
    ("coulomb-friction:hub", {"coul": {"hub": 1e-4}}),
    ("coulomb-friction:train", {"coul": {"train": 1e-4}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-8}}),
    ("viscous-friction:train", {"visc": {"train": 1e-5}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-5}}),
    ("force-offset:train", {"offset": {"train": 1e-4}}),
    ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-5, 30.0)}}),
    ("stribeck-friction:train", {"stribeck": {"train": (1e-4, 1.0)}}),
    ("backlash:K", {"gap": 1e-4}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:8", {"lsat": (8.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jt", {"p": {"Jt": P["Jt"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:train", lambda a, b: {"cog": {"train": [(1, a, b)]}}),
    ("cogging:rotor:10", lambda a, b: {"cog": {"rotor": [(10, a, b)]}}),
    ("cogging:train:2", lambda a, b: {"cog": {"train": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:10", lambda a, b: {"emf": [(10, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.01 mN m on the
    rotor (and 1e-7 V s/rad of EMF), 0.1 mN m on the rake."""
    return 1e-5 if (":rotor" in label or label.startswith("emf")) else 1e-4


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


#: across the coupler (a spring and a damper, 1:1 in the reflected frame): the body an
#: effect on each is compared with, and the factor its size takes there per kind (the axles
#: and the rake turn at one mean speed)
ACROSS = {"train": ("hub", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0}),
          "hub": ("train", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` across the coupler
    (``recordkit.location_entry``), after a marginal record's scaling."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term of the catalog's kinds (the lighting skates' soft dry drag is a
#: behavioural torque of the declared model)
KIT = OneProbe(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sa, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=harmonic_size, marginal_sigma=MARGINAL_SIGMA, declared=(),
    extra=_location_entry)
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def check_outside(entries: list[dict[str, Any]]) -> None:
    """Report an outside record that the catalog's effects jointly (linearised) leave less
    than OUTSIDE_LEFT of its imprint: it would not be outside in effect."""
    for e in entries:
        u = e.get("unexplained_sigma")
        if u and u["all_scalar_effects_jointly"] < OUTSIDE_LEFT * u["imprint"]:
            print(f"WARNING {e['id']}: the catalog's effects jointly leave "
                  f"{u['all_scalar_effects_jointly']:.3g} of its {u['imprint']:.3g} sigma")


def checked_make(s: dict[str, Any], write: bool) -> dict:
    """``make``, and the outside check of its entry."""
    entry = make(s, write)
    check_outside([entry])
    return entry


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, checked_make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
