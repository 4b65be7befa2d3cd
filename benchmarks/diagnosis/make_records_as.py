"""Generate the blind set ``fresh44`` of the diagnosis benchmark: records av01-av14 of motor AS
(a 48 V brushed DC motor turning the open-array antenna of a marine radar scanner on a service
bench: a rigid 60:1 spur train to the pedestal's output shaft, the array's mounting bracket and
its long fibreglass radiator a compliance to the array, the array meeting its main bearing's
grease drag, the lip seal's and rotary joint's dry friction and its own air drag), some sampled
evenly and some UNEVENLY, three of them giving the diagnosis ONE probe only, and merge their
truth into truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_as.py                # records/av*.csv + truth.json
    python benchmarks/diagnosis/make_records_as.py --only av03,av12
    python benchmarks/diagnosis/make_records_as.py --truth-only   # rewrite the av entries only

Uses simulators_as.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_as_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the catalog imprints it is compared with are computed on that probe
alone (``OneProbe``). Even records are sampled on the regime's grid k/fs; uneven ones, in the
fast regime, on a 20 kHz grid whose every sample is moved by a random jitter of up to 10-30 %
of the interval, and in the slow regime at a logger's irregular intervals (0.6-1.4 times the
mean of 4 ms) with a few samples dropped. Each uneven record has its own times (from its
seed), and the motor is simulated at those very times (``t_eval``), never interpolated.
truth.json is merged under an exclusive lock (recordkit.merge). An outside record whose
imprint the catalog's effects jointly leave less than OUTSIDE_LEFT of is reported (it would
not be outside in effect). A catalog or two-effect record's ``location_sigma`` covers every
other place its effect has an equal at: a torque effect on the rotor, the hub or the array is
compared with its equal on each of the other two (across the bracket for rotor-array and
hub-array, through the rigid spur train for rotor-hub), an added inertia on Jr, Jh or Ja with
its equal on the other two (``PLACES``, ``INERTIAS``). Nobody ran the diagnosis on these
records.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import recordkit
import simulators_as as sa

RECORDS = HERE / "records"
SPLIT = "fresh44"
MOTOR = "AS"
SEED0 = 44500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_as_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_as_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.03, "speed": 0.5},
         "slow": {"current": 0.01, "speed": 0.3, "load_speed": 0.015}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: an outside record's imprint must keep at least this fraction after all the catalog's
#: effects jointly (linearised)
OUTSIDE_LEFT = 0.2
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AS
N = P["N"]
#: [m] the radius of the bracket's clamp bolts on the turntable flange
R_CLAMP = 0.03
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_as, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The spur train is rigid and lossless as declared: a
# torque on the body ``hub`` (the pedestal's output shaft) is 1/N = 1/60 of it on the rotor,
# and the hub turns at 1/N of the rotor's speed (a dry friction c on the hub is c / N on the
# rotor, a viscous friction b on the rotor is b N^2 on the hub). The array lies behind the
# bracket's compliance (1:1): an effect on it has no exact equal on the hub or the rotor.

def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad] in the bracket K (its clamp bolts worked loose)."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap, "play_mm": gap * R_CLAMP * 1e3,
                       "form": "no bracket torque while |twist| < gap/2, Ks (twist -+ gap/2) "
                               "+ Ds w_rel in contact, the damping never pulling"},
        "expected": {"gap": gap}}


def coulomb_array(c: float) -> Part:
    """An extra dry friction c tanh(wa / 0.01) [N m] on the array (behind the bracket; a
    marginal record scales it)."""
    return {"coul": {"array": c}}, {
        "effect": "coulomb-friction", "target": "array", "targets": ["array"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(wa/0.01) against the array"},
        "expected": {"c": c}}


def coulomb_hub(c: float) -> Part:
    """An extra dry friction c tanh(wh / 0.01) [N m] on the hub (accepted on the rotor at
    c / N)."""
    return {"coul": {"hub": c}}, {
        "effect": "coulomb-friction", "target": "hub", "targets": ["hub"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(wh/0.01) against the hub"},
        "expected": {"c": c},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["rotor"],
                         "expected": {"c": c / N}}]}


def viscous_rotor(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the rotor (accepted on the hub at
    b N^2; a marginal record scales it)."""
    return {"visc": {"rotor": b}}, {
        "effect": "viscous-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b w against the rotor"},
        "expected": {"b": b},
        "also_accept": [{"effect": "viscous-friction", "targets": ["hub"],
                         "expected": {"b": b * N ** 2}}]}


def saturation(ipar: float, ratio: float) -> Part:
    """The armature inductance saturating: La (ratio + (1 - ratio) / (1 + (i / Ipar)^2))."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def warmup(rise: float, tau: float) -> Part:
    """The winding's resistance settling: R (1 + rise (1 - exp(-t / tau)))."""
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


def inertia_array(dj: float) -> Part:
    """The array's inertia off by a factor 1 + ``dj`` (a correction of Ja's J, the parameter
    Ja; behind the bracket)."""
    return {"p": {"Ja": P["Ja"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Ja", "targets": ["Ja"], "correction": True,
        "parameters": {"Ja_true_kgm2": P["Ja"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AS's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sa.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sa.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the bench's shunt amplifier: a 12-bit ADC over +-20 A (9.8 mA steps)
BENCH_STEP = 40.0 / 4096
#: the scanner driver's current sensor: a 12-bit ADC over +-5 A (2.4 mA steps)
DRIVER_STEP = 10.0 / 4096
#: the motor's magnetic encoder's speed report: 0.1 rad/s steps at the rotor
SPEED_STEP = 0.1
#: the pedestal's bearing encoder's speed report: 5 mrad/s steps
ARRAY_STEP = 0.005


def nulls() -> list[dict[str, Any]]:
    """av01, av02: the null records."""
    return [
        spec("av01", "null", "slow", False,
             noise={"current": {"white": 0.006, "pink": 0.005, "quant": DRIVER_STEP},
                    "speed": {"white": 0.25, "ar1": [0.2, 0.9], "quant": SPEED_STEP},
                    "load_speed": {"white": 0.012, "quant": ARRAY_STEP}},
             note="the scanner driver's log of the service bench's test program, an even "
                  "record; the current with 1/f noise (5 mA: the brushes on the commutator) "
                  "on white noise, read by the driver's 12-bit ADC (2.4 mA steps); the motor "
                  "encoder's speed with Gauss-Markov noise (correlation 0.9 over the "
                  "interval, 0.2 rad/s: the encoder magnet's uneven field) on white noise, "
                  "reported in 0.1 rad/s steps; the array's speed from the pedestal's "
                  "bearing encoder on white noise, reported in 5 mrad/s steps"),
        spec("av02", "null", "fast", True,
             noise={"current": {"white": 0.025, "ar1": [0.015, 0.8], "quant": BENCH_STEP},
                    "speed": {"white": 0.4, "pink": 0.2, "quant": SPEED_STEP}},
             note="a bench acquisition of the current and the motor encoder's speed, a "
                  "jittered 20 kHz acquisition; the current with Gauss-Markov noise "
                  "(correlation 0.8 over the interval, 15 mA: the shunt amplifier's drift) "
                  "on white noise, read by the 12-bit ADC (9.8 mA steps); the speed with 1/f "
                  "noise (0.2 rad/s) on white noise, reported in 0.1 rad/s steps"),
    ]


def singles() -> list[dict[str, Any]]:
    """av03-av07, av10: one catalog effect each."""
    return [
        spec("av03", "catalog", "fast", True, (backlash(0.012),),
             note="the array's mounting bracket was refitted after a repaint and its two "
                  "clamp bolts on the turntable flange have worked loose in their slotted "
                  "holes: 0.012 rad (0.7 degrees, 0.36 mm at the bolts) of play between the "
                  "pedestal's output shaft and the array"),
        spec("av04", "catalog", "slow", False, (coulomb_array(0.05),),
             marginal=lambda c: (coulomb_array(c),), size=0.05,
             note="salt crystals have crept under the lip of the pedestal's main seal on the "
                  "array's side after a season at sea: an extra dry friction on the array, "
                  "scaled to a 25 sigma signature (marginal)"),
        spec("av05", "catalog", "fast", False, (saturation(3.0, 0.45),),
             probes=("current",), noise={"current": {"white": 0.03, "quant": BENCH_STEP}},
             note="a bench log of the current alone (the 12-bit ADC); the motor is a "
                  "pattern replacement whose armature stack is shorter and whose teeth "
                  "saturate: the armature's inductance falls to 45 % by about 3 A"),
        spec("av06", "catalog", "slow", True, (warmup(0.2, 2.5),),
             note="the motor had been held stalled for the bench's torque check just before "
                  "this log: the heat of the commutator and the brush holders soaks into the "
                  "armature's winding, whose resistance rises by 20 % with a 2.5 s time "
                  "constant over the log"),
        spec("av07", "catalog", "fast", False, (sensor("speed", "delay", 2.5e-3),),
             note="the bench's speed channel now takes the driver board's speed estimate, "
                  "which averages the encoder's count over its last 5 ms: the speed reads "
                  "about 2.5 ms late"),
        spec("av10", "catalog", "fast", True, (viscous_rotor(2e-5),),
             marginal=lambda b: (viscous_rotor(b),), size=2e-5, probes=("speed",),
             note="a bench log of the motor encoder's speed alone; the motor's ball "
                  "bearings were regreased with a stiff low-temperature grease: an extra "
                  "viscous drag on the rotor, scaled to a 25 sigma signature (marginal)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """av08, av09: two catalog effects at once."""
    return [
        spec("av08", "two", "slow", True,
             (inertia_array(0.3), sensor("load_speed", "gain", 0.95)),
             note="the owner had a stainless bird-deterrent spike strip and a second "
                  "radome end cap bolted onto the radiator: 30 % more inertia on the array "
                  "than the declared; and the pedestal was fitted with a replacement bearing "
                  "encoder whose disc has 5 % more counts than the driver's firmware "
                  "assumes: the array's speed reads 5 % low"),
        spec("av09", "two", "fast", False,
             (coulomb_hub(0.25), sensor("current", "gain", 1.06)),
             note="the pedestal's output shaft got a new lip seal where it leaves the gear "
                  "case, fitted dry: a dry friction of 0.25 N m on the hub; and the bench's "
                  "shunt amplifier was recalibrated against a meter reading 6 % low: the "
                  "current reads 6 % high"),
    ]


#: the unworn lip seal: its extra dry friction T1 [N m] at the start and the angle s0 [rad]
#: of the array's travel over which it fades
RUNIN = (0.6, 6.0)
#: the Hall current sensor beside the encoder magnet: the field's reading Ip [A] and its
#: phase [rad] to the rotor's angle
PICKUP = (0.12, 0.9)
#: the logger's AC-coupled current input: its time constant tau [s]
ACCOUPLE = (0.25,)
#: the driver's speed limiter: the rotor speed w0 [rad/s] above which it acts, its gain Kg
#: [V s/rad] and the rounding eps [rad/s] of its corner
GOVERNOR = (180.0, 0.4, 2.0)


def outside_records() -> list[dict[str, Any]]:
    """av11-av14: effects the catalog does not contain."""
    return outside_slow() + outside_fast()


def outside_slow() -> list[dict[str, Any]]:
    """av11, av13: a seal running in and an AC-coupled current input (slow)."""
    t1, s0 = RUNIN
    tau, = ACCOUPLE
    return [
        spec("av11", "outside", "slow", True, (outside(
            "new-seal-running-in-with-the-turns", {"runin": RUNIN},
            {"T1_Nm": t1, "s0_rad": s0,
             "form": "the array takes an extra dry friction T1 exp(-s/s0) tanh(wa/0.01), "
                     "ds/dt = sqrt(wa^2 + (0.01 rad/s)^2), s = 0 at the start: it fades with "
                     "the angle the array has travelled, not with the time"}),),
            note=NOTE_RUNIN),
        spec("av13", "outside", "slow", False, (outside(
            "ac-coupled-current-input", {"accouple": ACCOUPLE},
            {"tau_s": tau,
             "form": "the current reads i - q, dq/dt = (i - q)/tau, q = 0 at rest: a "
                     "coupling capacitor's high-pass on the reading; the motor itself is not "
                     "touched"}),),
            noise={"current": {"white": 0.01, "quant": DRIVER_STEP},
                   "speed": {"white": 0.3, "quant": SPEED_STEP},
                   "load_speed": {"white": 0.015, "ar1": [0.008, 0.8], "quant": ARRAY_STEP}},
            note=NOTE_ACCOUPLE),
    ]


def outside_fast() -> list[dict[str, Any]]:
    """av12, av14: a current sensor reading the encoder magnet and a speed limiter (fast)."""
    ip, phase = PICKUP
    w0, kg, eps = GOVERNOR
    return [
        spec("av12", "outside", "fast", False, (outside(
            "current-sensor-reads-the-encoder-magnet", {"pickup": PICKUP},
            {"Ip_A": ip, "phase_rad": phase,
             "form": "the current reads i + Ip sin(th + phase), th the rotor's angle: the "
                     "rotating field of the encoder's diametric magnet in an open-loop Hall "
                     "current sensor; the motor itself is not touched"}),),
            probes=("current",),
            noise={"current": {"white": 0.03, "pink": 0.015, "quant": BENCH_STEP}},
            note=NOTE_PICKUP),
        spec("av14", "outside", "fast", True, (outside(
            "driver-speed-limiter-in-harbour-mode", {"governor": GOVERNOR},
            {"w0_rad_s": w0, "Kg_V_s_rad": kg, "eps_rad_s": eps,
             "form": "the motor receives u - Kg (x + sqrt(x^2 + eps^2))/2, x = w - w0: the "
                     "driver takes back Kg volts per rad/s of rotor speed above w0, forward "
                     "only"}),),
            noise={"current": {"white": 0.03}, "speed": {"white": 0.5, "pink": 0.2}},
            note=NOTE_GOVERNOR),
    ]


NOTE_RUNIN = (
    "the scanner driver's log; the pedestal's main lip seal was replaced just before this log "
    "and is not yet run in: a dry friction of 0.6 N m on the array over the declared at the "
    "start, fading as the seal's lip polishes itself, to a third of it after about 6 rad "
    "(one turn) of the array's travel; a person sees the current 0.10 A higher as the array "
    "breaks away at the start, 0.06 A higher early on the first speed (16 V) and 0.04 A at "
    "its end, 0.01 A at 32 V and nothing from 44 V on nor in the reverse run (the array has "
    "travelled 11 rad by 5 s and 21 rad by 7 s), the motor 1.1 rad/s and the array 0.03 "
    "rad/s slower at most; close to more dry friction on the array, but one that wears off "
    "with the turns, not with the time")
NOTE_ACCOUPLE = (
    "the scanner driver's log; the logger's current input was left in its AC-coupled "
    "setting (a series capacitor, a 0.25 s time constant) while the two speeds' inputs are "
    "DC-coupled: a person sees each change of the current as declared and then its reading "
    "sag back to zero within about a second: 0.03 A at 1.0 s instead of 0.41 A, about 0 on "
    "each steady speed (0.16, 0.23 and 0.31 A declared), -0.40 A at 7.4 s in the stop "
    "instead of -1.31 A, 1.15 A off at most (8.3 s, the reversal), while the two speeds are "
    "as declared; not an offset nor a gain: the reading forgets its level")
NOTE_PICKUP = (
    "a bench acquisition of the current alone (the 12-bit ADC, with 1/f noise of 15 mA on "
    "white noise); the current now comes from the driver board's open-loop Hall current "
    "sensor, which sits 2 cm from the motor's encoder magnet (a diametric magnet on the "
    "rotor's tail shaft) and reads its rotating field: a ripple of +-0.12 A once a turn of "
    "the rotor at any speed and any current (38 Hz at 240 rad/s, slowing through each "
    "reversal, a steady 0.09 A before the motor starts); the motor itself is untouched; "
    "locked to the rotor's angle like an EMF harmonic, but not growing with the speed")
NOTE_GOVERNOR = (
    "a bench acquisition of the current and the motor encoder's speed (1/f noise of 0.2 "
    "rad/s on white noise); for this run the bench fed the motor through the scanner's own "
    "driver board, whose 'harbour mode' speed limiter was left jumpered on: above 180 rad/s "
    "of the motor (3 rad/s, 29 rpm of the array) it takes back 0.4 V of its output per "
    "rad/s of excess, forward only; a person sees the ramp as declared up to 180 rad/s, then "
    "the speed held at about 204 rad/s instead of 258 rad/s on 36 V (57 rad/s lower at "
    "most) and the current up to 2.9 A off (0.32 s) as the array's swing on its bracket "
    "changes, then the drop to 20 V from the lower speed, and the reversal 6.6 rad/s "
    "slower backwards at 0.52 s; close to a resistance in the source, but only above "
    "a speed")


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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 44, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-5}}),
    ("coulomb-friction:hub", {"coul": {"hub": 1e-3}}),
    ("coulomb-friction:array", {"coul": {"array": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:array", {"visc": {"array": 1e-4}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-5}}),
    ("force-offset:array", {"offset": {"array": 1e-3}}),
    ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-5, 30.0)}}),
    ("stribeck-friction:hub", {"stribeck": {"hub": (1e-3, 0.5)}}),
    ("stribeck-friction:array", {"stribeck": {"array": (1e-3, 0.5)}}),
    ("backlash:K", {"gap": 1e-5}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:3", {"lsat": (3.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jh", {"p": {"Jh": P["Jh"] * 1.001}}),
    ("inertia:Ja", {"p": {"Ja": P["Ja"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
    ("resistance-drift:warmup-2", {"warmup": (1e-3, 2.0)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:hub", lambda a, b: {"cog": {"hub": [(1, a, b)]}}),
    ("unbalance:array", lambda a, b: {"cog": {"array": [(1, a, b)]}}),
    ("cogging:rotor:16", lambda a, b: {"cog": {"rotor": [(16, a, b)]}}),
    ("cogging:hub:3", lambda a, b: {"cog": {"hub": [(3, a, b)]}}),
    ("cogging:array:2", lambda a, b: {"cog": {"array": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:16", lambda a, b: {"emf": [(16, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 10 uN m on the
    rotor (and 1e-7 V s/rad of EMF), 1 mN m on the hub and the array."""
    return 1e-5 if (":rotor" in label or label.startswith("emf")) else 1e-3


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
        eight) until within 1 % of it (an imprint need not be linear in its size)."""
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


#: the places a torque effect may sit at, each with its gear factor g (its speed over the
#: hub's: the rotor turns N times the hub, the array at the hub's mean speed across the 1:1
#: bracket). A torque effect of kind k on a place of factor ga equals, on a place of factor
#: gb, a dry friction or an offset of ga/gb of it, a viscous friction of (ga/gb)^2, a Stribeck
#: peak of ga/gb at gb/ga times the speed scale, a cogging (or unbalance) of order k ga/gb
#: (when whole) at ga/gb of the amplitude. Rotor-hub is exact (the rigid gear); rotor-array
#: and hub-array lie across the bracket's compliance, where a record at these sample rates
#: may not tell the two apart: every other place is listed.
PLACES = {"rotor": N, "hub": 1.0, "array": 1.0}
#: the same for an inertia (component: (parameter, gear factor)): an added inertia dJ on a
#: place of factor ga is dJ (ga/gb)^2 on a place of factor gb (Jr is the rotor's, the
#: parameter Jm)
INERTIAS = {"Jr": ("Jm", N), "Jh": ("Jh", 1.0), "Ja": ("Ja", 1.0)}
#: the places on the far side of the train's compliance: a pair with one of them is ``across``
BEYOND = ("array", "Ja")


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma``, after a marginal record's
    scaling: recordkit.places_entry over PLACES and INERTIAS (each truth effect's own clean
    imprint, run alone on the record's times, against the same effect at its equivalent size
    at each other place, best-scaled)."""
    return recordkit.places_entry(s, times(s), imprints(s), sim, PLACES, INERTIAS, P, BEYOND)


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term of the catalog's kinds (the radiator's air drag is a behavioural torque of
#: the declared model)
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
