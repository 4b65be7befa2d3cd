"""Generate the blind set ``fresh23`` of the diagnosis benchmark: records aa01-aa14 of motor X
(a 12 V brushed DC motor in a car's power-window regulator: a 73:1 worm gear, a cable drum,
a steel cable to the glass carrier, a 4.5 kg pane in its glass-run seals against its
weight), some sampled evenly and some UNEVENLY, four of them giving the diagnosis ONE probe
only, and merge their truth into truth.json. The ids have two letters: every single letter
is taken by an earlier set.

    python benchmarks/diagnosis/make_records_x.py                # records/aa*.csv + truth.json
    python benchmarks/diagnosis/make_records_x.py --only aa03,aa12
    python benchmarks/diagnosis/make_records_x.py --truth-only   # rewrite the aa entries only

Uses simulators_x.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_x_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only, as a door module's
log of its current sense (what a ripple-counting module reads) or a tachometer's log would;
its signatures, its marginal scaling and the catalog imprints it is compared with are
computed on that probe alone. Even records are sampled on the regime's grid k/fs; uneven
ones, in the fast regime, on a 20 kHz grid whose every sample is moved by a random jitter of
up to 10-30 % of the interval, and in the slow regime at a logger's irregular intervals
(0.6-1.4 times the mean of 2 ms) with a few samples dropped. Each uneven record has its own
times (from its seed), and the motor is simulated at those very times (``t_eval``), never
interpolated. truth.json is merged under an exclusive lock (recordkit.merge). Nobody ran the
diagnosis on these records.
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
import simulators_x as sx

RECORDS = HERE / "records"
SPLIT = "fresh23"
MOTOR = "X"
SEED0 = 23500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_x_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_x_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.01, "speed": 0.3},
         "slow": {"current": 0.01, "speed": 0.3, "load_speed": 0.01}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sx.MOTOR_X
N = P["N"]
#: [m] the drum's radius, through which the pane is reflected (x = r thg)
R_DRUM = 0.02
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_x, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The worm gear is rigid and lossless as declared: a
# torque on the drum is 1/N = 1/73 of it on the rotor, a viscous coefficient 1/N^2; the pane
# sits behind the compliant cable, so an effect on it equals one on the drum only on
# average (``location_sigma``).

def series_resistance(r: float, regime: str) -> Part:
    """A resistance [ohm] in series with the armature (accepted inside the supply)."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": ["Ra", "La", "M"],
        "parameters": {"R_series_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad of the drum] in the cable ``K``."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap, "slack_mm": gap * R_DRUM * 1e3,
                       "form": "no cable torque while |twist| < gap/2, c (twist -+ gap/2) + "
                               "d w_rel in contact, the damping never pulling"},
        "expected": {"gap": gap}}


def offset_drum(f: float) -> Part:
    """A constant torque ``f`` [N m] the drum receives (accepted on the pane, and on the
    rotor at f / N)."""
    return {"offset": {"drum": f}}, {
        "effect": "force-offset", "target": "drum", "targets": ["drum"],
        "parameters": {"T_Nm": f, "force_at_pane_N": f / R_DRUM,
                       "form": "the drum receives a constant T (lifting the pane when T > 0)"},
        "expected": {"F": f},
        "also_accept": [{"effect": "force-offset", "targets": ["pane"], "expected": {"F": f}},
                        {"effect": "force-offset", "targets": ["rotor"],
                         "expected": {"F": f / N}}]}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF ripple w slope sin(order angle + phase) [V], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def unbalance_drum(amp: float, phase: float) -> Part:
    """A once-per-turn torque amp sin(angle + phase) [N m] on the drum (the worm wheel)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"drum": [(1, a, b)]}}, {
        "effect": "unbalance", "target": "drum", "targets": ["drum"], "order": 1,
        "parameters": {"order": 1, "T_Nm": amp, "phase_rad": phase,
                       "form": "drum receives T sin(1 angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["drum"], "order": 1,
                         "expected": {"a": a, "b": b}}]}


def inductance(dl: float) -> Part:
    """The armature's inductance off by a factor 1 + ``dl`` (a correction of La)."""
    return {"p": {"L": P["L"] * (1.0 + dl)}}, {
        "effect": "inductance", "target": "La", "targets": ["La"], "correction": True,
        "parameters": {"La_true_H": P["L"] * (1.0 + dl), "dL": dl}, "expected": {"dL": dl}}


def inertia_rotor(dj: float) -> Part:
    """The rotor's inertia off by a factor 1 + ``dj`` (a correction of Jr's Jm)."""
    return {"p": {"Jm": P["Jm"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jr", "targets": ["Jr"], "correction": True,
        "parameters": {"Jr_true_kgm2": P["Jm"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


def coulomb_rotor(c: float) -> Part:
    """An extra dry friction c tanh(w / 0.01) [N m] on the rotor (accepted on the drum at
    N c)."""
    return {"coul": {"rotor": c}}, {
        "effect": "coulomb-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(w/0.01) against the rotor"},
        "expected": {"c": c},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["drum"],
                         "expected": {"c": c * N}}]}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor X's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sx.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sx.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the door module's current sense: a 12-bit ADC over +-25 A (12.2 mA steps)
ADC_STEP = 50.0 / 4096
ADC_I = {"white": 0.01, "quant": ADC_STEP}


def nulls_and_singles() -> list[dict[str, Any]]:
    """aa01-aa08: the null and single catalog records."""
    return [
        spec("aa01", "null", "fast", False, note="white noise; current and speed"),
        spec("aa02", "null", "slow", True,
             noise={"current": {"white": 0.005, "ar1": [0.01, 0.85], "quant": ADC_STEP},
                    "speed": {"white": 0.3, "pink": 0.4},
                    "load_speed": {"white": 0.01, "quant": 0.005}},
             note="a logger's irregular clock; the current with Gauss-Markov noise "
                  "(correlation 0.85 over the mean interval) on white noise, read by the "
                  "module's 12-bit ADC (12.2 mA steps); the speed with 1/f noise (white noise "
                  "shaped by 1/sqrt(f)) on white noise: the Hall period counter beating against "
                  "the logger's clock; the pane's speed from a draw-wire encoder, quantised to "
                  "0.005 rad/s (0.1 mm/s)"),
        spec("aa03", "null", "fast", True, probes=("current",),
             noise={"current": {"white": 0.005, "ar1": [0.01, 0.9], "quant": ADC_STEP}},
             note="a door module's log of its current sense, the current alone (the signal a "
                  "ripple-counting module reads): Gauss-Markov noise (correlation 0.9 over the "
                  "mean interval) on white noise, read by a 12-bit ADC over +-25 A (12.2 mA "
                  "steps)"),
        spec("aa04", "catalog", "fast", True, (backlash(0.3),),
             note="the cable's tensioner spring has lost its preload and 6 mm of cable hang "
                  "slack in the regulator: a play of 0.3 rad of the drum (22 rad of the rotor). "
                  "The pane, lying mid-slack at the start, sinks 3 mm onto the lifting run (its "
                  "weight beats the seals' grip) before the motor starts. A person sees the "
                  "start 0.34 A lighter and the rotor 12 rad/s faster at 70 ms, and at the "
                  "reversal the rotor run through the slack unloaded, 8 rad/s faster on 0.24 A "
                  "less current for 40 ms, while the pane lags behind it"),
        spec("aa05", "catalog", "slow", False, (offset_drum(0.3),),
             noise={"current": ADC_I, "speed": {"white": 0.3},
                    "load_speed": {"white": 0.01}},
             note="the regulator carries a constant-force (negator) spring on its drum that "
                  "lifts 15 N of the pane's 44 N weight, and the declared model lacks it: a "
                  "constant 0.3 N m on the drum. A person sees the current 0.2 A lower going up"
                  " and 0.2 A higher going down, the rotor 7 rad/s faster up and slower down; "
                  "the current read by a 12-bit ADC (12.2 mA steps)"),
        spec("aa06", "catalog", "fast", False, (sensor("speed", "delay", 5e-4),),
             probes=("speed",), noise={"speed": {"white": 0.3}},
             note="a tachometer-only log, the speed alone: the module computes the speed from "
                  "its Hall sensor and sends it on the LIN bus, where the logger reads it "
                  "0.5 ms late (a delay of 0.5 ms). A person sees the speed follow every step "
                  "late, 9 rad/s behind while the rotor reverses"),
        spec("aa07", "catalog", "fast", True, (emf_harmonic(10, 2e-4, 0.4),),
             probes=("current",), marginal=lambda sl: (emf_harmonic(10, sl, 0.4),),
             size=2e-4, noise={"current": ADC_I},
             note="a door module's log of its current sense, the current alone: the ten "
                  "commutator bars' ripple in the EMF, ten a turn (the ripple a ripple-counting"
                  " module counts), scaled to a 25 sigma signature (marginal): 2.1e-5 V s/rad, "
                  "a ripple of 3.7 mA at 820 Hz while the pane goes up; the current read by a "
                  "12-bit ADC"),
        spec("aa08", "catalog", "slow", True, (unbalance_drum(0.02, 1.1),),
             marginal=lambda a: (unbalance_drum(a, 1.1),), size=0.02,
             note="the worm wheel was moulded with a sink mark on one side, and the drum, "
                  "whose axis lies across the door, carries the heavy side round once a turn "
                  "(about once a second): a torque sin(angle + 1.1) on the drum, scaled to a 25 "
                  "sigma signature (marginal): 8 mN m, a ripple of 6 mA and 0.2 rad/s"),
    ]


def pairs() -> list[dict[str, Any]]:
    """aa09, aa10: a declared parameter's correction with a catalog effect."""
    return [
        spec("aa09", "two", "fast", False, (inductance(0.4), series_resistance(0.1, "fast")),
             note="the door got a replacement motor of another make: its armature's inductance"
                  " is 40 % above the declared La (a correction of La: the current's steps "
                  "are slower, by up to 1.35 A at the step at 0.5 s), and the door's connector, "
                  "under the hinge-side grommet, has a corroded pin: 0.1 ohm in series with the"
                  " armature (the rotor 12 rad/s slower going up)"),
        spec("aa10", "two", "slow", True, (inertia_rotor(0.35), coulomb_rotor(0.006)),
             note="the declared Jm, the armature's and the worm's from the supplier's drawing,"
                  " misses the Hall sensor's ring magnet and the worm's steel thrust collar: the"
                  " rotor's inertia is 35 % higher (a "
                  "correction of Jr: every start and stop takes longer, the rotor 41 rad/s "
                  "behind at the end of the 0.1 s soft start); and new brushes bed in, "
                  "rubbing 6 mN m more (a dry friction on the rotor: 0.3 A more current in both"
                  " directions)"),
    ]


#: the worm's efficiencies: lead angle 8 deg, friction coefficient 0.07 (friction angle 4
#: deg): driving tan(8)/tan(12), driven back tan(4)/tan(8), blended over 1 mW
LEAD, FRICTION = math.radians(8.0), math.atan(0.07)
WORM = (math.tan(LEAD) / math.tan(LEAD + FRICTION),
        math.tan(LEAD - FRICTION) / math.tan(LEAD), 1e-3)
#: the upper frame seal: its extra friction [N m] (40 N), where the pane enters it (0.35 m
#: up) [rad] and the width of the entry (15 mm) [rad]
HEADER = (0.8, 0.35 / R_DRUM, 0.015 / R_DRUM)
#: the alternator's ripple: the bus [V], the fundamental's amplitude [V], its frequency (six
#: pulses a turn of a 6-pole-pair alternator at 2100 rpm) [Hz], the second harmonic's
#: amplitude [V] and phase [rad]
RIPPLE = (13.5, 0.15, 6 * 6 * 2100 / 60, 0.05, 0.9)
#: the seals' aging: the extra breakaway [N m] (50 N after a night), the aging time [s], the
#: slide that renews the contact (2 mm) [rad]
DWELL = (1.0, 1.5, 0.002 / R_DRUM)


def outside_records() -> list[dict[str, Any]]:
    """aa11-aa14: effects the catalog does not contain."""
    return [
        spec("aa11", "outside", "slow", True, (outside(
            "worm-mesh-efficiency-by-power-flow", {"worm": WORM},
            {"lead_angle_deg": 8.0, "mesh_friction_coefficient": 0.07,
             "eta_driving": WORM[0], "eta_driven": WORM[1], "P0_W": WORM[2],
             "form": "the wheel receives eta_f N T_in while the rotor drives the worm (T_in w "
                     "> 0), N T_in = eta_b T_out while the wheel drives it back; blended by "
                     "(1 + tanh(P/P0))/2 of the transmitted power P"}),),
            note="the worm gear is not lossless as declared: its mesh friction (lead angle 8 "
                 "deg, friction coefficient 0.07) passes 66 % of the power while the motor "
                 "drives the pane and 50 % while the pane's weight drives the worm back. A "
                 "person sees the current 0.64 A higher going up (3.07 instead of 2.43 A), the "
                 "rotor 22 rad/s slower; going down only 0.04 A higher, at full speed, where "
                 "the motor still drives the seals' small excess over the weight, as in the "
                 "slow approach at -3 V, where the weight drives the worm back and its help "
                 "comes through at half strength"),
        spec("aa12", "outside", "slow", False, (outside(
            "upper-frame-seal-by-height", {"header": HEADER},
            {"dT_Nm": HEADER[0], "force_N": HEADER[0] / R_DRUM, "th1_rad": HEADER[1],
             "height_m": 0.35, "wth_rad": HEADER[2], "width_m": 0.015,
             "form": "the pane takes -dT (1 + tanh((thg - th1)/wth))/2 tanh(wg/0.01): a dry "
                     "friction switched on by its height"}),), probes=("current",),
            noise={"current": ADC_I},
            note="a door module's log of its current sense, the current alone: the pane's top "
                 "edge enters the upper frame's seal 0.35 m up, which grips it with 40 N more "
                 "friction over the last 60 mm of its travel (and again as it leaves the seal "
                 "going down). A person sees the current climb by 0.35 A from 2.8 to 2.95 s, the "
                 "slow approach at 6 V drawing 2.77 A instead of 2.23 A, after the stop the "
                 "cable, stretched the more, turn the rotor back (0.46 A at 3.8 s), and the "
                 "first 0.5 s of the way down 0.5 A above the rest of it; the current read by "
                 "a 12-bit ADC"),
        spec("aa13", "outside", "fast", True, (outside(
            "alternator-ripple-through-duty", {"ripple": RIPPLE},
            {"U_bus_V": RIPPLE[0], "a1_V": RIPPLE[1], "f_Hz": RIPPLE[2], "a2_V": RIPPLE[3],
             "psi2_rad": RIPPLE[4],
             "form": "the motor sees u (1 + (a1 sin(2 pi f t) + a2 sin(4 pi f t + psi2))/U)"}),),
            note="the engine idles and the alternator's six-pulse ripple (0.4 V peak to peak "
                 "at 1260 Hz on the 13.5 V bus) passes through the door module's bridge in "
                 "proportion to its duty: the motor sees the command times (1 + ripple/13.5 V)."
                 " A person sees a 1.26 kHz ripple of up to 35 mA in the current while the "
                 "motor is driven, none while the bridge shorts it, and nothing in the speed"),
        spec("aa14", "outside", "slow", False, (outside(
            "seal-dwell-stiction", {"dwell": DWELL},
            {"dT_Nm": DWELL[0], "force_N": DWELL[0] / R_DRUM, "tau_age_s": DWELL[1],
             "D_rad": DWELL[2], "D_mm": 2.0,
             "form": "the pane takes -dT (1 - u) tanh(wg/0.01), du/dt = -u/tau + (1 - u) "
                     "|wg|/D, u(0) = 0: a rate-and-state aging of the seals' grip"}),),
            note="the car stood overnight in the cold and the seals' rubber crept into the "
                 "glass: the pane breaks away only with 50 N more than its sliding friction, "
                 "which the first 2 mm of slide wear off; standing 0.9 s at the top, the seals "
                 "regrow 45 % of that grip (an aging time of 1.5 s). A person sees the start "
                 "held back, the current 0.5 A higher at 0.43 s, then the pane jump (13.4 "
                 "instead of 7.2 rad/s at 0.45 s) and ring on its cable, and at the start "
                 "down a jolt of 0.1 rad/s"),
    ]


def record_specs() -> list[dict[str, Any]]:
    """The 14 records in id order, each with its seed."""
    out = sorted(nulls_and_singles() + pairs() + outside_records(), key=lambda s: s["id"])
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- sample times

def times(s: dict[str, Any]) -> np.ndarray:
    """The record's sample times [s] (even, or uneven from its seed), once; described in
    ``s["timestamps"]`` (``recordkit.record_times``)."""
    return recordkit.record_times(s, sx.REGIMES, sx.grid, 23, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
#: (the drum's frictions and offsets are the rotor's columns scaled by the rigid gear)
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:pane", {"coul": {"pane": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:pane", {"visc": {"pane": 1e-3}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:pane", {"offset": {"pane": 1e-3}}),
    ("stribeck-friction:rotor:10", {"stribeck": {"rotor": (1e-4, 10.0)}}),
    ("stribeck-friction:pane:0.3", {"stribeck": {"pane": (1e-3, 0.3)}}),
    ("stribeck-friction:pane:3", {"stribeck": {"pane": (1e-3, 3.0)}}),
    ("backlash:K", {"gap": 1e-4}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:20", {"lsat": (20.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jd", {"p": {"Jd": P["Jd"] * 1.001}}),
    ("inertia:Jg", {"p": {"Jg": P["Jg"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: the scalar effects compared in the fast regime only (none: the cable's play runs in both)
FAST_ONLY: tuple[str, ...] = ()
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:drum", lambda a, b: {"cog": {"drum": [(1, a, b)]}}),
    ("unbalance:pane", lambda a, b: {"cog": {"pane": [(1, a, b)]}}),
    ("cogging:rotor:10", lambda a, b: {"cog": {"rotor": [(10, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:10", lambda a, b: {"emf": [(10, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1 uV s/rad of EMF), 1 mN m on the drum and the pane."""
    return 1e-4 if (":rotor" in label or label.startswith("emf")) else 1e-3


#: across the cable: a body -> (the body an effect on it is compared with, the factor its
#: size takes there per simulator key: the drum turns with the pane on average)
ACROSS = {"drum": ("pane", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0}),
          "pane": ("drum", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


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
        effects = [(k, fx) for k, fx in self.scalar_effects
                   if regime == "fast" or k not in FAST_ONLY]
        return self.imprints(s).of_effects(
            regime, lambda fx: self.sim(regime, t, fx), effects, s["probes"],
            self.simulator.REGIMES[regime][1], self.sensor_steps, columns=True)

    def truth_entry(self, s: dict[str, Any], sig: dict) -> dict:
        """The record's entry of truth.json: its probes and their noise only."""
        entry = super().truth_entry(s, sig)
        ns = {p: v for p, v in recordkit.noise_or_white(s, self.white).items()
              if p in s["probes"]}
        entry.update(probes=list(s["probes"]), noise=ns,
                     noise_text=recordkit.noise_text(ns))
        return entry

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


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` across the cable
    (``recordkit.location_entry``) on the record's probes, after a marginal record's
    scaling."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term
KIT = OneProbe(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sx, sim=sim,
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
