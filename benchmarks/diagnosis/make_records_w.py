"""Generate the blind set ``fresh22`` of the diagnosis benchmark: records l01-l14 of motor W
(a 48 V brushed DC motor in a small electric outboard: a rigid 2:1 bevel gear, the
propeller's rubber cushion hub, the propeller working against the water by its open-water
law and driving a 320 kg dinghy through it), some sampled evenly and some UNEVENLY, six of
them giving the diagnosis ONE probe only, and merge their truth into truth.json.

    python benchmarks/diagnosis/make_records_w.py              # records/l*.csv + truth.json
    python benchmarks/diagnosis/make_records_w.py --only l03,l12
    python benchmarks/diagnosis/make_records_w.py --truth-only # rewrite the l entries only

Uses simulators_w.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_w_slow.yaml reads from its own table). A single-probe record
(truth's ``probes``: ["current"] or ["speed"]) holds that probe's column only, as a
sensorless controller's log (its current) or a tachometer's log (the speed) would; its
signatures, its marginal scaling and the catalog imprints it is compared with are computed
on that probe alone. Even records are sampled on the regime's grid k/fs; uneven ones, in the
fast regime, on a 25 kHz grid whose every sample is moved by a random jitter of up to 10-30 %
of the interval, and in the slow regime at a logger's irregular intervals (0.6-1.4 times the
mean of 2.5 ms) with a few samples dropped. Each uneven record has its own times (from its
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
import simulators_w as sw

RECORDS = HERE / "records"
SPLIT = "fresh22"
MOTOR = "W"
SEED0 = 22500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_w.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_w_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.1, "speed": 0.5},
         "slow": {"current": 0.1, "speed": 0.5, "load_speed": 0.25}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sw.MOTOR_W
N = P["N"]
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_w, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The bevel gear is rigid and lossless: a torque on the
# rotor is N = 2 times as large on the shaft, a viscous coefficient N^2 = 4 times, a harmonic
# of order n of the rotor's angle is of order n / N of the shaft's; the propeller sits behind
# the compliant rubber hub and the hull behind the water: neither has such an equal.

def source_resistance(r: float, regime: str) -> Part:
    """A resistance [ohm] inside the supply (accepted in series with the armature)."""
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[regime], "targets": [SOURCE[regime]],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": ["Ra", "La", "M"],
                         "expected": {"R": r}}]}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def coulomb_shaft(c: float) -> Part:
    """An extra dry friction c tanh(ws / 0.01) [N m] against the propeller shaft (accepted on
    the rotor at c / N)."""
    return {"coul": {"shaft": c}}, {
        "effect": "coulomb-friction", "target": "shaft", "targets": ["shaft"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(w/0.01) against the propeller shaft"},
        "expected": {"c": c},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["rotor"],
                         "expected": {"c": c / N}}]}


def stribeck_shaft(s: float, ws: float) -> Part:
    """A Stribeck peak s exp(-(ws_shaft / ws)^2) tanh(ws_shaft / 0.01) [N m] over the shaft
    seals' declared friction."""
    return {"stribeck": {"shaft": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "shaft", "targets": ["shaft"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "shaft takes s exp(-(w/ws)^2) tanh(w/0.01) over the declared "
                               "Ts tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def unbalance_prop(amp: float, phase: float) -> Part:
    """A once-per-turn torque amp sin(angle + phase) [N m] on the propeller."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"prop": [(1, a, b)]}}, {
        "effect": "unbalance", "target": "prop", "targets": ["prop"], "order": 1,
        "parameters": {"order": 1, "T_Nm": amp, "phase_rad": phase,
                       "form": "prop receives T sin(1 angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["prop"], "order": 1,
                         "expected": {"a": a, "b": b}}]}


def inductance(dl: float) -> Part:
    """The armature's inductance off by a factor 1 + ``dl`` (a correction of La)."""
    return {"p": {"L": P["L"] * (1.0 + dl)}}, {
        "effect": "inductance", "target": "La", "targets": ["La"], "correction": True,
        "parameters": {"La_true_H": P["L"] * (1.0 + dl), "dL": dl}, "expected": {"dL": dl}}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF ripple w slope sin(order angle + phase) [V], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def inertia_hull(dj: float) -> Part:
    """The hull's reflected inertia off by a factor 1 + ``dj`` (a correction of Jh)."""
    return {"p": {"Jh": P["Jh"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jh", "targets": ["Jh"], "correction": True,
        "parameters": {"Jh_true_kgm2": P["Jh"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


def drift(alpha: float) -> Part:
    """The armature's resistance drifting linearly: R (1 + alpha t)."""
    return {"alpha": alpha}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + alpha*t)", "alpha_per_s": alpha},
        "expected": {"alpha": alpha}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor W's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sw.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sw.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: a 12-bit ADC over +-200 A (97.7 mA steps) on the current
ADC_STEP = 400.0 / 4096
ADC_I = {"white": 0.1, "quant": ADC_STEP}


def nulls_and_singles() -> list[dict[str, Any]]:
    """l01-l08: the null and single catalog records."""
    return [
        spec("l01", "null", "fast", False, note="white noise; current and speed"),
        spec("l02", "null", "slow", True, probes=("speed",),
             noise={"speed": {"white": 0.3, "pink": 0.5}},
             note="a tachometer-only log: the speed alone, with 1/f noise (white noise shaped"
                  " by 1/sqrt(f)) on white noise: the Hall sensor's period counter beating "
                  "against the logger's irregular clock"),
        spec("l03", "null", "fast", True, probes=("current",),
             noise={"current": {"white": 0.05, "ar1": [0.1, 0.9], "quant": ADC_STEP}},
             note="a sensorless controller's log: the current alone, with Gauss-Markov noise "
                  "(correlation 0.9 over the mean interval) on white noise, read by a 12-bit "
                  "ADC over +-200 A (97.7 mA steps)"),
        spec("l04", "catalog", "slow", True, (source_resistance(0.03, "slow"),),
             note="the outboard runs from four old 12 V lead-acid batteries in series and 5 m "
                  "of cable to the transom: 30 mohm inside the supply (30 % of Ra). A person "
                  "sees the terminals sag by 1.5 V at the step to full throttle: the current "
                  "2.7 A and the rotor 12 rad/s lower there, the boat 0.08 m/s slower at the end "
                  "of the full-throttle run (2.49 instead of 2.57 m/s), the current 1.5 A "
                  "smaller backing hard"),
        spec("l05", "catalog", "fast", True, (sensor("current", "gain", 1.01),),
             probes=("current",), marginal=lambda dg: (sensor("current", "gain", 1.0 + dg),),
             size=0.01, noise={"current": ADC_I},
             note="a sensorless controller's log, the current alone: its 0.25 mohm current "
                  "shunt, warmed by the first minutes' current, reads a few hundredths of a "
                  "percent high (its manganin's temperature coefficient), scaled to a 25 sigma "
                  "signature (marginal): at most 54 mA at 116 A; the current read by a 12-bit "
                  "ADC (97.7 mA steps)"),
        spec("l06", "catalog", "fast", False, (coulomb_shaft(0.15),), probes=("speed",),
             noise={"speed": {"white": 0.5}},
             note="a tachometer-only log, the speed alone: a fishing line wound round the "
                  "propeller shaft between the propeller's hub and the gear case rubs on the "
                  "shaft: an extra dry friction of 0.15 N m on it (2.5 times the seals'). A "
                  "person sees the rotor run 0.65 rad/s slower at every hold, ahead and astern "
                  "alike, and the propeller stop sooner at the end"),
        spec("l07", "catalog", "slow", False, (stribeck_shaft(0.8, 1.0),),
             note="the boat lay on its mooring for a winter and the shaft seals' lips have "
                  "dried and stick: below about 1 rad/s of the shaft they hold up to 0.9 N m "
                  "instead of the declared 0.1 N m. A person sees nothing while the propeller "
                  "turns; the start from the jetty 2 rad/s late at the propeller, and as the "
                  "tiller is pulled slowly through zero into astern the rotor stays stuck for "
                  "a moment (-0.13 instead of -3.8 rad/s at 8.94 s) and the current goes 3.5 A "
                  "further negative to break it away"),
        spec("l08", "catalog", "fast", False, (unbalance_prop(0.2, 0.7),),
             marginal=lambda a: (unbalance_prop(a, 0.7),), size=0.2,
             note="a blade's tip nicked on a rock and bent a little: in the gear case's wake the "
                  "propeller takes a torque once a turn, scaled to a 25 sigma signature "
                  "(marginal): a few mN m, 35 Hz at full throttle, a ripple of 0.03 A in the "
                  "current and 0.03 rad/s in the speed"),
    ]


def pairs() -> list[dict[str, Any]]:
    """l09, l10: two catalog effects at once."""
    return [
        spec("l09", "two", "fast", True, (inductance(0.45), emf_harmonic(14, 1e-3, 0.8)),
             note="the leg got a replacement motor of another make: its armature's inductance "
                  "is 45 % above the declared La (a correction of La), so that the current "
                  "moves slower at every step (14 A less at the end of the 5 ms step at 0.5 "
                  "s, 8 A at the end of the step down at 0.29 s), and its seven-slot armature's commutation ripples "
                  "its EMF 14 times a turn (1 mV s/rad: 0.43 V at 950 Hz at full speed)"),
        spec("l10", "two", "slow", True, (inertia_hull(0.45), drift(0.004)),
             note="the declared Jh was entered from the brochure's weight of the boat with one "
                  "person, while the drag was measured by towing the boat loaded as on this trip:"
                  " two more people and a cool box aboard, the boat's inertia 45 % above Jh (a "
                  "correction of Jh): it gathers way slower (1.80 instead of 2.22 m/s at 5.6 s) "
                  "and carries it longer (0.73 instead of 0.41 m/s at the end); and the winding "
                  "warms through the record: its resistance rises by 0.4 % a second (4.8 % at "
                  "the end), the speeds a little lower"),
    ]


#: ventilation: its start and end [s], its edges' duration [s], the torque's and thrust's
#: loss [1]
VENT = (0.195, 0.245, 0.012, 0.55)
#: [N m s^2/rad^2] the churning water's drag on the rotor
CHURN = 1.4e-6
#: the tender: its inertia (90 kg r^2) [kg m^2], the rope's stiffness (3 kN/m r^2)
#: [N m/rad], the slack (0.5 m / r) [rad], the onset's width (5 cm / r) [rad], its drag
#: coefficient (50 N at 2.5 m/s, times r^3) [N m s^2/rad^2]
R_PITCH = 0.04
TENDER = (90.0 * R_PITCH ** 2, 3000.0 * R_PITCH ** 2, 0.5 / R_PITCH, 0.05 / R_PITCH,
          50.0 / 2.5 ** 2 * R_PITCH ** 3)
#: the head sea: the orbital velocity's amplitude at the propeller (0.25 m/s / r) [rad/s],
#: the waves' frequency [Hz], their wave number times r (a 3.2 m wavelength) [1/rad], phase
WAVE = (0.25 / R_PITCH, 0.7, 2.0 * math.pi * R_PITCH / 3.2, 0.3)


def outside_records() -> list[dict[str, Any]]:
    """l11-l14: effects the catalog does not contain."""
    return [
        spec("l11", "outside", "fast", True, (outside(
            "propeller-ventilation", {"vent": VENT},
            {"t0_s": VENT[0], "t1_s": VENT[1], "te_s": VENT[2], "depth": VENT[3],
             "form": "the propeller's torque and thrust times 1 - depth s(t), s rising as "
                     "sin^2 over [t0, t0 + te], 1 to t1, falling as cos^2 over [t1, t1 + te]"}),
        ), probes=("current",), noise={"current": ADC_I},
            note="a sensorless controller's log, the current alone: in a tight turn at full "
                 "throttle the propeller draws air down from the surface (ventilates) for 50 ms:"
                 " its torque and its thrust fall by 55 % with 12 ms edges. A person sees the "
                 "current fall from 56 A to 28 A at 0.21 s and come back at 0.26 s, the rotor "
                 "race by 29 rad/s meanwhile, the boat lose 0.03 m/s of way; the current read by a "
                 "12-bit ADC"),
        spec("l12", "outside", "fast", False, (outside(
            "flooded-motor-churning", {"churn": CHURN},
            {"cw_Nms2_rad2": CHURN, "form": "the rotor takes -cw w |w|"}),),
            note="the leg's lower seal has let water into the motor's can: the rotor churns it, "
                 "a drag growing with the square of its speed, 0.25 N m at 425 rad/s (a "
                 "twentieth of the propeller's load seen at the rotor). A person sees the current 2 A "
                 "higher and the rotor 2 rad/s slower at full throttle, 0.6 A and 0.6 rad/s at "
                 "24 V, 0.9 A backing at -30 V: a loss that grows faster than any viscous "
                 "friction"),
        spec("l13", "outside", "slow", True, (outside(
            "towed-tender-on-slack-rope", {"tender": TENDER},
            {"m_tender_kg": 90.0, "k_rope_N_m": 3000.0, "slack_m": 0.5, "onset_m": 0.05,
             "drag_N_at_2.5_m_s": 50.0, "r_m_rad": R_PITCH,
             "form": "a body Jt = m r^2 with drag -cht wt |wt|, pulled by kr s softplus((thh - "
                     "tht - L0)/s), the hull taking the reaction"}),),
            note="the dinghy tows a 90 kg tender on a nylon painter (3 kN/m) with 0.5 m of "
                 "slack, the tender lying 2 m astern at the start. A person sees nothing until "
                 "the boat has made 0.5 m: at 2.5 s the rope snatches taut and the boat's speed "
                 "falls back from 0.66 to 0.58 m/s by 3 s, where it would make 0.88 m/s; "
                 "the current 1.1 A higher from then on, 2.8 A higher and the boat 0.51 m/s "
                 "slower at full throttle (tension up to 370 N); when the boat slows and backs, "
                 "the rope slackens and the tender glides on (to within 0.9 m of the "
                 "transom)"),
        spec("l14", "outside", "slow", False, (outside(
            "head-sea-orbital-inflow", {"wave": WAVE},
            {"Wo_rad_s": WAVE[0], "orbital_m_s": 0.25, "f0_Hz": WAVE[1], "wavelength_m": 3.2,
             "kx_per_rad": WAVE[2], "psi_rad": WAVE[3],
             "form": "the propeller's inflow wh + Wo sin(2 pi f0 t + kx thh + psi) in its "
                     "torque and thrust laws"}),), probes=("speed",),
            noise={"speed": {"white": 0.5}},
            note="a tachometer-only log, the speed alone: the boat heads into a short chop "
                 "(0.7 Hz, 3.2 m waves): the waves' orbital velocity at the propeller, 0.25 m/s, "
                 "adds to and takes from its inflow, met the faster the faster the boat goes "
                 "(1.5 Hz at full throttle). A person sees the rotor's speed swing by 0.9 "
                 "rad/s at the cruise, 1.4 rad/s at full throttle and backing, at a rate that "
                 "follows the boat's speed, the command steady"),
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
    return recordkit.record_times(s, sw.REGIMES, sw.grid, 22, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
#: (the shaft's frictions and offsets are the rotor's columns scaled)
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-3}}),
    ("coulomb-friction:prop", {"coul": {"prop": 1e-3}}),
    ("coulomb-friction:hull", {"coul": {"hull": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-6}}),
    ("viscous-friction:prop", {"visc": {"prop": 1e-5}}),
    ("viscous-friction:hull", {"visc": {"hull": 1e-4}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-3}}),
    ("force-offset:prop", {"offset": {"prop": 1e-3}}),
    ("force-offset:hull", {"offset": {"hull": 1e-3}}),
    ("stribeck-friction:shaft:0.3", {"stribeck": {"shaft": (1e-3, 0.3)}}),
    ("stribeck-friction:shaft:3", {"stribeck": {"shaft": (1e-3, 3.0)}}),
    ("backlash:K", {"gap": 1e-4}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:150", {"lsat": (150.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jp", {"p": {"Jp": P["Jp"] * 1.001}}),
    ("inertia:Jh", {"p": {"Jh": P["Jh"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: the scalar effects compared in the fast regime only: at the end of the slow record the
#: propeller, which the boat's way still turns, rests on the shaft, which the seals hold,
#: at the edge of a play, and this simulator's contact law (clipped, with no event location)
#: switches its damping on and off there without end (circuitsim's held relations get
#: through it: 5 s)
FAST_ONLY = ("backlash:K",)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:shaft", lambda a, b: {"cog": {"shaft": [(1, a, b)]}}),
    ("unbalance:prop", lambda a, b: {"cog": {"prop": [(1, a, b)]}}),
    ("cogging:prop:3", lambda a, b: {"cog": {"prop": [(3, a, b)]}}),
    ("cogging:rotor:14", lambda a, b: {"cog": {"rotor": [(14, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:14", lambda a, b: {"emf": [(14, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column."""
    return 1e-3


#: across the rubber hub: a body -> (the body an effect on it is compared with, the factor
#: its size takes there per simulator key: the shaft turns with the propeller on average)
ACROSS = {"shaft": ("prop", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0}),
          "prop": ("shaft", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


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
    """A catalog or two-effect record's ``location_sigma`` across the rubber hub
    (``recordkit.location_entry``) on the record's probes, after a marginal record's
    scaling."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term
KIT = OneProbe(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sw, sim=sim,
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
