"""Generate the blind set ``fresh42`` of the diagnosis benchmark: records at01-at14 of motor AQ
(a 24 V brushed DC motor driving the burr of a flat-burr coffee grinder on the test bench: a
rigid 5:1 spur gear to the output shaft, the jaw coupling's elastomer spider a compliance to the
burr carrier, the burr meeting its bearings' drag, the felt dust seal's dry friction and the
sweeper's air drag), some sampled evenly and some UNEVENLY, three of them giving the diagnosis
ONE probe only, and merge their truth into truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_aq.py                # records/at*.csv + truth.json
    python benchmarks/diagnosis/make_records_aq.py --only at03,at12
    python benchmarks/diagnosis/make_records_aq.py --truth-only   # rewrite the at entries only

Uses simulators_aq.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_aq_slow.yaml's pwl states). A single-probe record (truth's
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
other place its effect has an equal at: a torque effect on the rotor, the hub or the burr is
compared with its equal on each of the other two (across the spider for rotor-burr and
hub-burr, through the rigid gear for rotor-hub), an added inertia on Jr, Jh or Jc with its
equal on the other two (``PLACES``, ``INERTIAS``). Nobody ran the diagnosis on these records.
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
import simulators_aq as sa

RECORDS = HERE / "records"
SPLIT = "fresh42"
MOTOR = "AQ"
SEED0 = 42500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_aq_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_aq_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.03, "speed": 0.5},
         "slow": {"current": 0.02, "speed": 0.4, "load_speed": 0.1}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: an outside record's imprint must keep at least this fraction after all the catalog's
#: effects jointly (linearised)
OUTSIDE_LEFT = 0.2
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AQ
N = P["N"]
#: [m] the spider's mean lobe radius (the jaw coupling, 30 mm across)
R_SPIDER = 0.0075
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]



# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_aq, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The spur gear is rigid and lossless as declared: a
# torque on the body ``hub`` (the output shaft) is 1/N = 1/5 of it on the rotor, and the hub
# turns at 1/N of the rotor's speed (a viscous friction b on the rotor is b N^2 on the hub, a
# Stribeck breakaway s, ws on the rotor is s N, ws / N on the hub). The burr lies behind the
# spider's compliance (1:1): an effect on it has no exact equal on the hub or the rotor.

def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad] in the coupling K (a worn, shrunken spider)."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap, "play_mm": gap * R_SPIDER * 1e3,
                       "form": "no coupling torque while |twist| < gap/2, Ks (twist -+ gap/2) "
                               "+ Ds w_rel in contact, the damping never pulling"},
        "expected": {"gap": gap}}


def saturation(ipar: float, ratio: float) -> Part:
    """The armature inductance saturating: La (ratio + (1 - ratio) / (1 + (i / Ipar)^2))."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def viscous_burr(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the burr (behind the spider; a marginal
    record scales it)."""
    return {"visc": {"burr": b}}, {
        "effect": "viscous-friction", "target": "burr", "targets": ["burr"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b wc against the burr"},
        "expected": {"b": b}}


def coulomb_hub(c: float) -> Part:
    """An extra dry friction c tanh(wh / 0.01) [N m] on the hub (accepted on the rotor at
    c / N)."""
    return {"coul": {"hub": c}}, {
        "effect": "coulomb-friction", "target": "hub", "targets": ["hub"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(wh/0.01) against the hub"},
        "expected": {"c": c},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["rotor"],
                         "expected": {"c": c / N}}]}


def coulomb_rotor(c: float) -> Part:
    """An extra dry friction c tanh(w / 0.01) [N m] on the rotor (accepted on the hub at
    c N; a marginal record scales it)."""
    return {"coul": {"rotor": c}}, {
        "effect": "coulomb-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(w/0.01) against the rotor"},
        "expected": {"c": c},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["hub"],
                         "expected": {"c": c * N}}]}


def stribeck_rotor(s: float, ws: float) -> Part:
    """A breakaway peak s exp(-(w/ws)^2) tanh(w/0.01) [N m] on the rotor, ``ws`` [rad/s]
    (accepted on the hub at s N, ws / N)."""
    return {"stribeck": {"rotor": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "rotor takes s exp(-(w/ws)^2) tanh(w/0.01) over its declared "
                               "dry friction"},
        "expected": {"s": s, "ws": ws},
        "also_accept": [{"effect": "stribeck-friction", "targets": ["hub"],
                         "expected": {"s": s * N, "ws": ws / N}}]}


def inertia_hub(dj: float) -> Part:
    """The hub's inertia off by a factor 1 + ``dj`` (a correction of Jh's J, the parameter
    Jh; accepted on the rotor's Jr as the same added inertia over N^2)."""
    added = P["Jh"] * dj
    return {"p": {"Jh": P["Jh"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jh", "targets": ["Jh"], "correction": True,
        "parameters": {"Jh_true_kgm2": P["Jh"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj},
        "also_accept": [{"effect": "inertia", "targets": ["Jr"], "correction": True,
                         "expected": {"dJ": added / N ** 2 / P["Jm"]}}]}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AQ's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sa.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sa.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records


# ---------------------------------------------------------------------- the records

#: the bench's shunt amplifier: a 12-bit ADC over +-20 A (9.8 mA steps)
BENCH_STEP = 40.0 / 4096
#: the grinder controller's current sense: a 12-bit ADC over +-5 A (2.4 mA steps)
CONTROLLER_STEP = 10.0 / 4096
#: the motor's Hall encoder's speed report: 0.1 rad/s steps at the rotor
SPEED_STEP = 0.1
#: the controller's burr speed from its Hall switch: 0.05 rad/s steps
BURR_STEP = 0.05


def nulls() -> list[dict[str, Any]]:
    """at01, at02: the null records."""
    return [
        spec("at01", "null", "slow", False,
             noise={"current": {"white": 0.012, "pink": 0.008, "quant": CONTROLLER_STEP},
                    "speed": {"white": 0.3, "ar1": [0.25, 0.85], "quant": SPEED_STEP},
                    "load_speed": {"white": 0.08, "quant": BURR_STEP}},
             note="the grinder controller's log of the bench test program, an even record; "
                  "the current with 1/f noise (8 mA: the brushes on the commutator) on white "
                  "noise, read by the controller's 12-bit ADC (2.4 mA steps); the motor's Hall "
                  "speed with Gauss-Markov noise (correlation 0.85 over the interval, 0.25 "
                  "rad/s: the magnet ring's uneven poles) on white noise, reported in 0.1 "
                  "rad/s steps; the burr's speed from the Hall switch on white noise, "
                  "reported in 0.05 rad/s steps"),
        spec("at02", "null", "fast", True, probes=("current",),
             noise={"current": {"white": 0.025, "ar1": [0.015, 0.7], "quant": BENCH_STEP}},
             note="a bench log of the current alone, a jittered 20 kHz acquisition; "
                  "Gauss-Markov noise (correlation 0.7 over the interval, 15 mA: the shunt "
                  "amplifier's drift) on white noise, read by the 12-bit ADC (9.8 mA steps)"),
    ]


def singles() -> list[dict[str, Any]]:
    """at03-at07, at10: one catalog effect each."""
    return [
        spec("at03", "catalog", "fast", True, (backlash(0.02),),
             note="the coupling's polyurethane spider has hardened and shrunk after years "
                  "next to the grinder's warm motor: 0.02 rad (1.1 degrees, 0.15 mm at the "
                  "lobes) of play between the jaws"),
        spec("at04", "catalog", "slow", False, (viscous_burr(2e-5),),
             marginal=lambda b: (viscous_burr(b),), size=2e-5,
             note="the burr shaft's lower bearing was repacked with a stiff food-grade "
                  "grease instead of the light one: an extra viscous drag on the burr, scaled "
                  "to a 25 sigma signature (marginal)"),
        spec("at05", "catalog", "fast", False, (sensor("current", "gain", 1.08),),
             note="the bench's 10 mOhm shunt burnt out and was replaced by a 10.8 mOhm one "
                  "from the spares drawer while the amplifier kept its calibration: the "
                  "current reads 8 % high"),
        spec("at06", "catalog", "slow", True, (coulomb_hub(0.015),),
             note="a new nitrile lip seal was fitted on the output shaft where it leaves the "
                  "gearbox, dry: a dry friction of 15 mN m on the hub"),
        spec("at07", "catalog", "fast", False, (saturation(3.0, 0.5),),
             probes=("current",), noise={"current": {"white": 0.03, "quant": BENCH_STEP}},
             note="a bench log of the current alone (the 12-bit ADC); the motor is a "
                  "cheaper replacement whose thin armature teeth saturate: the armature's "
                  "inductance falls to half by about 3 A"),
        spec("at10", "catalog", "fast", True, (coulomb_rotor(1e-3),),
             marginal=lambda c: (coulomb_rotor(c),), size=1e-3, probes=("speed",),
             note="a bench log of the motor's Hall speed alone; the motor's brushes were "
                  "replaced with ones on stiffer springs: an extra dry friction on the "
                  "rotor, scaled to a 25 sigma signature (marginal)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """at08, at09: two catalog effects at once."""
    return [
        spec("at08", "two", "slow", True,
             (inertia_hub(0.8), sensor("load_speed", "delay", 0.015)),
             note="the acetal 50-tooth gear was replaced by a brass one after a jam stripped "
                  "its teeth: 80 % more inertia on the hub than the declared; and the "
                  "controller's firmware was updated to time the burr's Hall pulses over a "
                  "whole turn: the burr's speed reads about 15 ms late"),
        spec("at09", "two", "fast", False,
             (stribeck_rotor(4e-3, 25.0), sensor("speed", "gain", 1.03)),
             note="the motor's sintered sleeve bearings ran dry after a summer in a hot "
                  "cafe window: a breakaway of 4 mN m on the rotor fading above about 25 "
                  "rad/s; and the bench's speed channel is now the motor driver's Hall "
                  "estimate, clocked by its RC oscillator: the speed reads 3 % high"),
    ]


#: the polyfuse (PPTC) in the motor's lead: its resistance Rh [ohm] at full heating, the
#: current I0 [A] that heats it fully, its thermal time constant tau [s]
PPTC = (1.5, 1.0, 0.25)
#: the off-centre magnet ring of the speed probe: the relative error e [1] and its phase
#: [rad]
RING = (0.01, 0.7)
#: the controller's rectified rail: the ripple r [1] and its frequency f [Hz]
RIPPLE = (0.06, 100.0)
#: the spider's hardening: the twist x0 [rad] at which its stiffness has doubled
HARDEN = (0.05,)


def outside_records() -> list[dict[str, Any]]:
    """at11-at14: effects the catalog does not contain."""
    return outside_slow() + outside_fast()


def outside_slow() -> list[dict[str, Any]]:
    """at11, at13: a polyfuse heating in the lead and a rippling rail (slow)."""
    rh, i0, tau = PPTC
    r, f = RIPPLE
    return [
        spec("at11", "outside", "slow", True, (outside(
            "polyfuse-heating-in-the-motor-lead", {"pptc": PPTC},
            {"Rh_ohm": rh, "I0_A": i0, "tau_s": tau,
             "form": "Rh h in series with the armature, dh/dt = ((i/I0)^2 - h)/tau, h = 0 "
                     "at rest: a resistance that follows the recent square of the current "
                     "(its own heating), not the time"}),),
            note=NOTE_PPTC),
        spec("at13", "outside", "slow", False, (outside(
            "mains-ripple-on-the-controller-rail", {"ripple": RIPPLE},
            {"r": r, "f_Hz": f,
             "form": "the motor receives u(t) (1 + r sin(2 pi f t)) while the logged "
                     "command is u(t): the PWM duty times a rail with a full-wave ripple"}),),
            noise={"current": {"white": 0.02, "quant": CONTROLLER_STEP},
                   "speed": {"white": 0.4, "quant": SPEED_STEP},
                   "load_speed": {"white": 0.1, "ar1": [0.05, 0.8], "quant": BURR_STEP}},
            note=NOTE_RIPPLE),
    ]


def outside_fast() -> list[dict[str, Any]]:
    """at12, at14: an off-centre magnet ring and a hardening spider (fast)."""
    e, phase = RING
    x0, = HARDEN
    return [
        spec("at12", "outside", "fast", False, (outside(
            "off-centre-speed-magnet-ring", {"ring": RING},
            {"e": e, "phase_rad": phase,
             "form": "the speed reads w (1 + e sin(th + phase)), th the rotor's angle: a "
                     "once-a-turn error of the measurement in proportion to the speed; the "
                     "motor itself is not touched"}),),
            noise={"current": {"white": 0.03, "pink": 0.015, "quant": BENCH_STEP},
                   "speed": {"white": 0.5}},
            note=NOTE_RING),
        spec("at14", "outside", "fast", True, (outside(
            "hardening-coupling-spider", {"harden": HARDEN},
            {"x0_rad": x0,
             "form": "the coupling's torque is Ks x (1 + (x/x0)^2) + Ds v, x = th/N - thc, "
                     "v = w/N - wc: stiffer the more it is twisted, either way"}),),
            noise={"current": {"white": 0.03}, "speed": {"white": 0.5, "pink": 0.2}},
            note=NOTE_HARDEN),
    ]


NOTE_PPTC = (
    "the grinder's controller log; the maker added a resettable polyfuse (PPTC, held at 1 A) "
    "in the motor's lead after a jammed burr burnt a motor: its resistance climbs with its "
    "own temperature, 1.5 Ohm at the heating of a steady 1 A, with a 0.25 s thermal lag; a "
    "person sees the current and the speed fall below the declared in each speed-up, most "
    "in the start and the reverse run where the current is highest, and recover as the "
    "current settles; close to a series "
    "resistance or the armature warming, but it follows the current's recent square, not "
    "the time")
NOTE_RIPPLE = (
    "the bench log of the controller; the controller's bulk capacitor has dried out and its "
    "rail carries the mains' full-wave ripple, 6 % at 100 Hz, while its log keeps the "
    "commanded voltage: a person sees a 100 Hz ripple in the current growing with the "
    "command (about 0.3 A at 22 V), hardly any in the speeds; locked to the mains, not to "
    "any angle of the motor, the gear or the burr")
NOTE_RING = (
    "a bench acquisition of the current (the 12-bit ADC, with 1/f noise of 15 mA on white "
    "noise) and the motor's Hall speed; the speed probe's magnet ring was re-glued off-centre "
    "on the rotor's shaft after it came loose: the speed reads 1 % high and low once a turn "
    "of the rotor, a ripple of up to 4 rad/s at full speed sweeping with the speed, the "
    "current showing nothing of it")
NOTE_HARDEN = (
    "a bench acquisition of the current and the motor's Hall speed (1/f noise of 0.2 rad/s "
    "on white noise); the coupling's soft spider was replaced by a harder, over-size one that "
    "is squeezed between the jaws: its stiffness doubles by 0.05 rad of twist; a person sees "
    "the coupling's ringing after the ramp, the drop and the reversal quicker and shorter "
    "where the spider carries most torque, the same once the ringing has died out; close to "
    "a stiffer spider, but only at large twist")


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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 42, JITTER, DROPS)
# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-5}}),
    ("coulomb-friction:hub", {"coul": {"hub": 1e-4}}),
    ("coulomb-friction:burr", {"coul": {"burr": 1e-4}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:burr", {"visc": {"burr": 1e-6}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-5}}),
    ("force-offset:burr", {"offset": {"burr": 1e-4}}),
    ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-5, 20.0)}}),
    ("stribeck-friction:hub", {"stribeck": {"hub": (1e-4, 4.0)}}),
    ("stribeck-friction:burr", {"stribeck": {"burr": (1e-4, 4.0)}}),
    ("backlash:K", {"gap": 1e-5}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:3", {"lsat": (3.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jh", {"p": {"Jh": P["Jh"] * 1.001}}),
    ("inertia:Jc", {"p": {"Jc": P["Jc"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
    ("resistance-drift:warmup-2", {"warmup": (1e-3, 2.0)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:hub", lambda a, b: {"cog": {"hub": [(1, a, b)]}}),
    ("unbalance:burr", lambda a, b: {"cog": {"burr": [(1, a, b)]}}),
    ("cogging:rotor:12", lambda a, b: {"cog": {"rotor": [(12, a, b)]}}),
    ("cogging:hub:6", lambda a, b: {"cog": {"hub": [(6, a, b)]}}),
    ("cogging:burr:2", lambda a, b: {"cog": {"burr": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:12", lambda a, b: {"emf": [(12, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 10 uN m on the
    rotor (and 1e-7 V s/rad of EMF), 0.1 mN m on the hub and the burr."""
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
        eight) until within 1 % of it (a dry friction's imprint is not linear in its
        size)."""
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
#: hub's: the rotor turns N times the hub, the burr at the hub's mean speed across the 1:1
#: spider). A torque effect of kind k on a place of factor ga equals, on a place of factor gb,
#: a dry friction or an offset of ga/gb of it, a viscous friction of (ga/gb)^2, a Stribeck
#: peak of ga/gb at gb/ga times the speed scale, a cogging (or unbalance) of order k ga/gb
#: (when whole) at ga/gb of the amplitude. Rotor-hub is exact (the rigid gear); rotor-burr
#: and hub-burr lie across the spider's compliance, where a record at these sample rates may
#: not tell the two apart: every other place is listed.
PLACES = {"rotor": N, "hub": 1.0, "burr": 1.0}
#: the same for an inertia (component: (parameter, gear factor)): an added inertia dJ on a
#: place of factor ga is dJ (ga/gb)^2 on a place of factor gb (Jr is the rotor's, the
#: parameter Jm)
INERTIAS = {"Jr": ("Jm", N), "Jh": ("Jh", 1.0), "Jc": ("Jc", 1.0)}
#: the places on the far side of the train's compliance: a pair with one of them is ``across``
BEYOND = ("burr", "Jc")


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma``, after a marginal record's
    scaling: recordkit.places_entry over PLACES and INERTIAS (each truth effect's own clean
    imprint, run alone on the record's times, against the same effect at its equivalent size
    at each other place, best-scaled)."""
    return recordkit.places_entry(s, times(s), imprints(s), sim, PLACES, INERTIAS, P, BEYOND)


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term of the catalog's kinds (the burr's windage is a behavioural torque of
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
