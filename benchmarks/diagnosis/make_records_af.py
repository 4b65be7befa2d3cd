"""Generate the blind set ``fresh31`` of the diagnosis benchmark: records ai01-ai14 of motor AF
(a 24 V brushed DC motor in a quarter-turn electric valve actuator on a buried butterfly valve
of a water main: a rigid 600:1 worm gearbox, a 1.5 m steel extension spindle, a torsional
compliance, to the valve's stem and disc; the stem packing's dry friction, the liner's seat
gripping the disc near closed, the flow's hydrodynamic torque pulling it towards closed), some
sampled evenly and some UNEVENLY, three of them giving the diagnosis ONE probe only, and merge
their truth into truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_af.py                # records/ai*.csv + truth.json
    python benchmarks/diagnosis/make_records_af.py --only ai03,ai12
    python benchmarks/diagnosis/make_records_af.py --truth-only   # rewrite the ai entries only

Uses simulators_af.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_af_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the catalog imprints it is compared with are computed on that probe
alone (``OneProbe``). Even records are sampled on the regime's grid k/fs; uneven ones, in the
fast regime, on a 20 kHz grid whose every sample is moved by a random jitter of up to 10-30 %
of the interval, and in the slow regime at a logger's irregular intervals (0.6-1.4 times the
mean of 4 ms) with a few samples dropped. Each uneven record has its own times (from its
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
import simulators_af as sa

RECORDS = HERE / "records"
SPLIT = "fresh31"
MOTOR = "AF"
SEED0 = 31500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_af_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_af_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.04, "speed": 0.4},
         "slow": {"current": 0.02, "speed": 0.3, "load_speed": 0.004}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AF
N = P["N"]
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_af, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearbox is rigid and lossless as declared: a torque
# on the body ``hub`` (the sleeve) is 1/N = 1/600 of it on the rotor, and the sleeve turns with
# the rotor. The disc lies behind the spindle (compliant): an effect on it has no exact equal
# on the sleeve.

def source_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] inside the source (the feed cable)."""
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


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad] in the spindle K."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap, "play_deg": math.degrees(gap),
                       "form": "no spindle torque while |twist| < gap/2, Ks (twist -+ gap/2) "
                               "+ Ds w_rel in contact, the damping never pulling"},
        "expected": {"gap": gap}}


def inertia_rotor(dj: float) -> Part:
    """The rotor's inertia off by a factor 1 + ``dj`` (a correction of Jr's J, the
    parameter Jm)."""
    return {"p": {"Jm": P["Jm"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jr", "targets": ["Jr"], "correction": True,
        "parameters": {"Jr_true_kgm2": P["Jm"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


def coulomb_disc(c: float) -> Part:
    """An extra dry friction c tanh(wd / 0.01) [N m] on the disc (behind the spindle)."""
    return {"coul": {"disc": c}}, {
        "effect": "coulomb-friction", "target": "disc", "targets": ["disc"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(wd/0.01) against the disc"},
        "expected": {"c": c}}


def stribeck_disc(s: float, ws: float) -> Part:
    """A breakaway peak s exp(-(wd/ws)^2) tanh(wd/0.01) [N m] over the disc's declared dry
    friction, ``ws`` [rad/s]."""
    return {"stribeck": {"disc": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "disc", "targets": ["disc"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "disc takes s exp(-(w/ws)^2) tanh(w/0.01) over the declared "
                               "Td tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def viscous_rotor(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the rotor (accepted on the sleeve at
    b N^2)."""
    return {"visc": {"rotor": b}}, {
        "effect": "viscous-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b w against the rotor"},
        "expected": {"b": b},
        "also_accept": [{"effect": "viscous-friction", "targets": ["hub"],
                         "expected": {"b": b * N ** 2}}]}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """The EMF's constant modulated, e + w slope sin(order th + phase) [V s/rad]."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AF's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sa.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sa.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the actuator controller's current sense: a 12-bit ADC over +-30 A (14.6 mA steps)
ADC_STEP = 60.0 / 4096


def nulls() -> list[dict[str, Any]]:
    """ai01, ai02: the null records."""
    return [
        spec("ai01", "null", "slow", True,
             noise={"current": {"white": 0.01, "ar1": [0.02, 0.85], "quant": ADC_STEP},
                    "speed": {"white": 0.3, "pink": 0.6},
                    "load_speed": {"white": 0.004}},
             note="the actuator controller's log on its irregular clock; the current with "
                  "Gauss-Markov noise (correlation 0.85 over the mean interval, 20 mA: the "
                  "bridge's switching hash through the shunt amplifier) on white noise, read "
                  "by its 12-bit ADC (14.6 mA steps); the motor encoder's speed with 1/f noise "
                  "(white noise shaped by 1/sqrt(f), 0.6 rad/s) on white noise; the stem "
                  "encoder's speed with white noise"),
        spec("ai02", "null", "fast", False,
             note="a commissioning engineer's even acquisition of the current and the motor "
                  "encoder's speed, white noise"),
    ]


def singles() -> list[dict[str, Any]]:
    """ai03-ai07, ai10: one catalog effect each."""
    return [
        spec("ai03", "catalog", "fast", True, (inertia_rotor(0.3),),
             note="a spring-applied brake was fitted to the motor's tail shaft to hold the "
                  "valve against the flow; released while the bridge drives, its steel "
                  "armature plate (50 mm across, 3 mm thick) still turns with the rotor: the "
                  "rotor's inertia is 30 % above the declared 5e-5 kg m^2 (a correction of "
                  "Jr); the starts, the braking and the reversal take longer"),
        spec("ai04", "catalog", "slow", False, (coulomb_disc(2.0),),
             marginal=lambda c: (coulomb_disc(c),), size=2.0,
             note="the stem's packing gland was tightened to stop a weep: an extra dry "
                  "friction c tanh(wd/0.01) on the disc, scaled to a 25 sigma signature "
                  "(marginal)"),
        spec("ai05", "catalog", "fast", False, (emf_harmonic(2, 4e-4, -0.6),),
             marginal=lambda s: (emf_harmonic(2, s, -0.6),), size=4e-4,
             probes=("speed",),
             note="a bench log of the motor encoder's speed alone; the rewound armature's "
                  "lamination stack was turned oval between worn centres: the air gap under "
                  "the two poles narrows twice a turn and the EMF's constant with it, an "
                  "EMF harmonic of order 2, phase -0.6, scaled to a 25 sigma signature "
                  "(marginal)"),
        spec("ai06", "catalog", "slow", True, (backlash(0.04),),
             note="the square drive at the foot of the extension spindle has worn in the "
                  "valve's stem cap: a play of 0.04 rad (2.3 degrees) in the spindle; the "
                  "sleeve turns through it before each start and at the reversal, and the "
                  "flow pulls the disc across it towards closed while the valve is held"),
        spec("ai07", "catalog", "fast", True, (source_resistance(0.4, "fast"),),
             probes=("current",), noise={"current": {"white": 0.04, "quant": ADC_STEP}},
             note="a bench log of the current alone (the controller's 12-bit ADC); the "
                  "actuator was moved to a chamber 80 m from its control panel and fed "
                  "through the old 1.5 mm^2 cable: 0.4 Ohm in the source"),
        spec("ai10", "catalog", "slow", False, (sensor("current", "gain", 0.93),),
             note="the controller's current amplifier was repaired with a gain resistor "
                  "of the wrong tolerance: the current reads 7 % low, a sensor gain of 0.93"),
    ]


def pairs() -> list[dict[str, Any]]:
    """ai08, ai09: two catalog effects at once."""
    return [
        spec("ai08", "two", "slow", True, (stribeck_disc(5.0, 0.05),
                                           viscous_rotor(3e-5)),
             note="the valve stood closed for a year and scale has grown on the disc's edge "
                  "and the stem: a breakaway torque s exp(-(wd/ws)^2) tanh(wd/0.01) on the "
                  "disc, s 5 N m, ws 0.05 rad/s, over its declared dry friction (the disc "
                  "jerks on the spindle, sticking and slipping, as it gets going after each "
                  "start and as it stops); and the "
                  "chamber is cold, the worm gear's grease stiff: an extra viscous friction "
                  "of 3e-5 N m s/rad on the rotor (four times the declared one)"),
        spec("ai09", "two", "fast", False, (saturation(3.0, 0.5),
                                            sensor("speed", "delay", 4e-4)),
             note="a replacement motor from another maker with a short, thin-walled yoke: "
                  "its armature inductance saturates, dpsi/di = La (0.5 + 0.5/(1 + (i/3 A)^2)) "
                  "(the inrush and the braking currents rise and fall faster); and the "
                  "encoder's speed comes through the drive's moving-average filter, a delay "
                  "of 0.4 ms on speed"),
    ]


#: vortices shed from the open disc: Tv [N m] at f [Hz]
FLUTTER = (4.0, 11.0)
#: reaction brushes angled for opening: the contact drop forward and back [V]
BRUSHES = (0.3, 1.2)
#: a displaced lip of the liner: Tl [N m], its centre th1 [rad] and its width wl [rad]
LIP = (12.0, 0.6, 0.06)


def outside_records() -> list[dict[str, Any]]:
    """ai11-ai14: effects the catalog does not contain."""
    return [
        spec("ai11", "outside", "slow", True, (outside(
            "vortex-shedding-disc-flutter", {"flutter": FLUTTER},
            {"Tv_Nm": FLUTTER[0], "f_Hz": FLUTTER[1],
             "form": "the disc receives Tv sin(thd)^2 sin(2 pi f t): vortices shed from the "
                     "open disc's edges at a fixed frequency (the flow's, not the disc's "
                     "angle), their torque growing with the opening, nothing closed"}),),
            note="a pump upstream now runs at a higher duty and the flow sheds vortices from "
                 "the open disc's edges: an 11 Hz torque on the disc, up to 4 N m wide open, "
                 "nothing closed; a person sees an 11 Hz ripple in the stem's speed, the "
                 "motor's speed and the current that grows as the valve opens (0.06 A, "
                 "0.9 rad/s), carries on in the stem's speed alone while the valve is held "
                 "open and the motor stands still, and fades as the disc closes; close to a harmonic of the disc's angle "
                 "(cogging), but locked to time, not to the angle"),
        spec("ai12", "outside", "fast", False, (outside(
            "one-way-angled-brushes", {"brushes": BRUSHES},
            {"Vf_V": BRUSHES[0], "Vr_V": BRUSHES[1],
             "form": "the loop takes tanh(i/1 mA) ((Vf + Vr)/2 + (Vf - Vr)/2 tanh(i/1 mA)): "
                     "a contact drop Vf while the current flows forward (opening), Vr while "
                     "it flows back (closing, braking from the opening)"}),),
            probes=("current",),
            noise={"current": {"white": 0.03, "ar1": [0.04, 0.7], "quant": ADC_STEP}},
            note="a bench log of the current alone (the controller's 12-bit ADC, the "
                 "bridge's hash as Gauss-Markov noise, correlation 0.7 over the interval, "
                 "40 mA, on white noise); the motor was re-brushed with reaction brushes "
                 "angled for a one-way motor: they ride well forward (0.3 V of contact drop "
                 "while opening) and chatter on their heels backwards (1.2 V while the current "
                 "flows back); a person sees the opening as declared with a small brush drop, "
                 "but the braking current smaller and the closing's current and transients "
                 "as if the loop lost 0.9 V more; close to a brush drop, but a different one "
                 "for each direction of the current"),
        spec("ai13", "outside", "slow", False, (outside(
            "displaced-liner-lip", {"lip": LIP},
            {"Tl_Nm": LIP[0], "th1_rad": LIP[1], "wl_rad": LIP[2],
             "form": "the disc takes Tl exp(-((thd - th1)/wl)^2) tanh(wd/0.01) against its "
                     "motion: a lip of the liner, pushed out of its groove, rubs the disc's "
                     "edge around th1 = 34 degrees"}),),
            note="a lip of the elastomer liner was pushed out of its groove by a pressure "
                 "surge and now stands into the bore: the disc's edge rubs it over a few "
                 "degrees around 34 degrees open, up to 12 N m against the motion; a person "
                 "sees a hump of current (0.33 A) and a dip in the stem's and the motor's "
                 "speeds as the disc passes 0.6 rad on the opening, and a hump of the "
                 "opposite sign as it passes back on the closing; close to a dry friction on the disc or the "
                 "sleeve, but only at one angle"),
        spec("ai14", "outside", "fast", True, (outside(
            "speed-from-emf-estimate", {"emf_speed": True},
            {"R_ohm": P["R"], "k_V_s_rad": P["k"],
             "form": "speed reads (u - R i)/k, u the bridge's command, R and k the declared "
                     "values: the controller's back-EMF estimate, which is w + (L/k) di/dt"}),),
            noise={"current": {"white": 0.04}, "speed": {"white": 0.4, "pink": 0.8}},
            note="the retrofitted actuator has no motor encoder: the column logged as the "
                 "speed is the controller's back-EMF estimate (u - R i)/k, which leaves out "
                 "the inductance's drop, so it reads w + (L/k) di/dt (20 ms times di/dt); the "
                 "speed column carries 1/f noise (0.8 rad/s) on white noise; a person sees "
                 "the speed leap ahead of the motor at each change of the command (up to "
                 "about 70 rad/s at the stop after the closing, 37 rad/s at the braking) and dip with every fall "
                 "of the current, ripple with the disc's 58 Hz ringing through the current, "
                 "and agree with the current's model in the steady parts; close to a delay "
                 "or a lead on the speed, but shaped by the current's slope"),
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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 31, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:hub", {"coul": {"hub": 1e-2}}),
    ("coulomb-friction:disc", {"coul": {"disc": 1e-2}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:disc", {"visc": {"disc": 1e-3}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:disc", {"offset": {"disc": 1e-2}}),
    ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-4, 10.0)}}),
    ("stribeck-friction:disc", {"stribeck": {"disc": (1e-2, 0.1)}}),
    ("backlash:K", {"gap": 1e-4}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:30", {"lsat": (30.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jd", {"p": {"Jd": P["Jd"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:disc", lambda a, b: {"cog": {"disc": [(1, a, b)]}}),
    ("cogging:rotor:12", lambda a, b: {"cog": {"rotor": [(12, a, b)]}}),
    ("cogging:disc:2", lambda a, b: {"cog": {"disc": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:12", lambda a, b: {"emf": [(12, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1 uV s/rad of EMF), 10 mN m on the disc."""
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


#: across the spindle (a spring and a damper, 1:1): the body an effect on each is compared
#: with, and the factor its size takes there per kind (the sleeve and the disc turn at one
#: mean speed)
ACROSS = {"disc": ("hub", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0}),
          "hub": ("disc", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` across the spindle
    (``recordkit.location_entry``), after a marginal record's scaling."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term of the catalog's kinds (the seat's grip and the flow's torque,
#: -Th sin(angle)^2 sin(2 angle), are behavioural torques of the declared model)
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
