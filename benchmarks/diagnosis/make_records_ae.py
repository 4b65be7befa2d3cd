"""Generate the blind set ``fresh30`` of the diagnosis benchmark: records ah01-ah14 of motor AE
(a 24 V brushed DC motor in a car park's barrier gate: a rigid 300:1 worm gearbox, a compliant
crank drive (its rubber-bushed rods and the boom's bending, one torsional compliance) to a
3.5 m aluminium boom that swings up against its weight, -Tg cos(angle), helped by a balance
spring; the pivot's dry friction, the boom's air drag), some sampled evenly and some
UNEVENLY, three of them giving the diagnosis ONE probe only, and merge their truth into
truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_ae.py                # records/ah*.csv + truth.json
    python benchmarks/diagnosis/make_records_ae.py --only ah03,ah12
    python benchmarks/diagnosis/make_records_ae.py --truth-only   # rewrite the ah entries only

Uses simulators_ae.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_ae_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the catalog imprints it is compared with are computed on that probe
alone (``OneProbe``). Even records are sampled on the regime's grid k/fs; uneven ones, in the
fast regime, on a 25 kHz grid whose every sample is moved by a random jitter of up to 10-30 %
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
import simulators_ae as sa

RECORDS = HERE / "records"
SPLIT = "fresh30"
MOTOR = "AE"
SEED0 = 30500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_ae_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_ae_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.05, "speed": 0.5},
         "slow": {"current": 0.03, "speed": 0.4, "load_speed": 0.01}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AE
N = P["N"]
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_ae, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearbox is rigid and lossless as declared: a torque
# on the body ``hub`` is 1/N = 1/300 of it on the rotor, and the hub turns with the rotor.
# The boom lies behind the drive (compliant): an effect on it has no exact equal on the hub.

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


def saturation(ipar: float, ratio: float) -> Part:
    """The armature inductance saturating: La (ratio + (1 - ratio) / (1 + (i / Ipar)^2))."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def drift(alpha: float) -> Part:
    """The armature's resistance drifting linearly, R (1 + alpha t) [1/s]."""
    return {"alpha": alpha}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + alpha*t)", "alpha_per_s": alpha},
        "expected": {"alpha": alpha}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def offset_boom(f: float) -> Part:
    """A constant torque ``f`` [N m] on the boom (behind the drive; f < 0: heavier)."""
    return {"offset": {"boom": f}}, {
        "effect": "force-offset", "target": "boom", "targets": ["boom"],
        "parameters": {"T_Nm": f, "form": "the boom receives a constant T (T < 0: pulling it "
                                          "down)"},
        "expected": {"F": f}}


def viscous_boom(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the boom (behind the drive)."""
    return {"visc": {"boom": b}}, {
        "effect": "viscous-friction", "target": "boom", "targets": ["boom"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b wb against the boom"},
        "expected": {"b": b}}


def stribeck_boom(s: float, ws: float) -> Part:
    """A breakaway peak s exp(-(wb/ws)^2) tanh(wb/0.01) [N m] over the boom's declared dry
    friction, ``ws`` [rad/s]."""
    return {"stribeck": {"boom": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "boom", "targets": ["boom"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "boom takes s exp(-(w/ws)^2) tanh(w/0.01) over the declared "
                               "Tb tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def cogging_rotor(order: int, amp: float, phase: float) -> Part:
    """A detent torque amp sin(order th + phase) [N m] on the rotor."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AE's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sa.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sa.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the controller's current sense: a 12-bit ADC over +-50 A (24.4 mA steps)
ADC_STEP = 100.0 / 4096


def nulls() -> list[dict[str, Any]]:
    """ah01, ah02: the null records."""
    return [
        spec("ah01", "null", "fast", True,
             noise={"current": {"white": 0.03, "ar1": [0.06, 0.8], "quant": ADC_STEP},
                    "speed": {"white": 0.5}},
             note="a service engineer's jittered acquisition of the current and the motor "
                  "encoder's speed; the current with Gauss-Markov noise (correlation 0.8 over "
                  "the mean interval, 60 mA: the bridge's switching hash through the shunt "
                  "amplifier) on white noise, read by the controller's 12-bit ADC (24.4 mA "
                  "steps); the speed with white noise"),
        spec("ah02", "null", "slow", False,
             note="the barrier controller's even log of the current, the motor encoder's "
                  "speed and the boom gyroscope's speed, white noise"),
    ]


def singles() -> list[dict[str, Any]]:
    """ah03-ah07, ah10: one catalog effect each."""
    return [
        spec("ah03", "catalog", "fast", True, (saturation(8.0, 0.45),),
             note="a replacement motor from another maker with a thinner yoke: its armature "
                  "inductance saturates, dpsi/di = La (0.45 + 0.55/(1 + (i/8 A)^2)); the "
                  "inrush and the braking currents (up to 21 A) rise and fall faster"),
        spec("ah04", "catalog", "slow", False, (offset_boom(-4.0),),
             marginal=lambda f: (offset_boom(f),), size=-4.0,
             note="a light strip and its cable were fitted along the boom without re-setting "
                  "the balance spring: a constant torque F pulling the boom down (taken as "
                  "constant over the stroke), scaled to a 25 sigma signature (marginal)"),
        spec("ah05", "catalog", "fast", False, (cogging_rotor(20, 0.01, 0.7),),
             marginal=lambda a: (cogging_rotor(20, a, 0.7),), size=0.01,
             probes=("speed",),
             note="a bench log of the motor encoder's speed alone; a replacement motor with "
                  "unskewed slots (4 magnets over 10 slots): a detent torque of order 20 on "
                  "the rotor, phase 0.7, scaled to a 25 sigma signature (marginal)"),
        spec("ah06", "catalog", "slow", True, (drift(0.02),),
             note="the barrier has been cycling all afternoon in the sun and the motor, its "
                  "housing hot, keeps warming through the log: its armature's resistance "
                  "rises linearly by 2 % a second (16 % over the 8 s)"),
        spec("ah07", "catalog", "fast", True, (brush_drop(0.6),),
             probes=("current",),
             note="a bench log of the current alone; the motor's brushes are glazed after a "
                  "winter of short, cold runs: a contact drop 0.6 tanh(i/1 mA) V in series "
                  "with the armature"),
        spec("ah10", "catalog", "slow", False, (sensor("load_speed", "gain", 0.94),),
             note="the boom's MEMS gyroscope was set up with its datasheet's typical "
                  "sensitivity, and this part reads 6 % low: a sensor gain of 0.94 on "
                  "load_speed"),
    ]


def pairs() -> list[dict[str, Any]]:
    """ah08, ah09: two catalog effects at once."""
    return [
        spec("ah08", "two", "slow", True, (stribeck_boom(6.0, 0.05),
                                           sensor("current", "offset", 0.12)),
             note="the boom's pivot bearings have rusted over a wet winter: a breakaway "
                  "torque s exp(-(wb/ws)^2) tanh(wb/0.01) on the boom, s 6 N m, ws 0.05 rad/s, "
                  "over its declared dry friction; and the controller's current amplifier "
                  "has lost its zero: an offset of 0.12 A on the current"),
        spec("ah09", "two", "fast", False, (viscous_boom(2.0), series_resistance(0.25, "fast")),
             note="a hinged aluminium skirt (an apron against pedestrians) was hung under the "
                  "boom: it drags the air, an extra viscous friction of 2 N m s/rad on the "
                  "boom; and the motor's lead runs through a corroded connector in the "
                  "cabinet: 0.25 Ohm in series with the armature"),
    ]


#: a steady wind along the road on the raised boom's face: Tw [N m]
WIND = 20.0
#: the braking relay's resistor: Rb [ohm], the command's width u0 [V] around 0 V
BRAKE_R = (2.0, 0.5)
#: the gyroscope's full scale [rad/s] (+-50 degrees/s)
CLIP = 0.8727
#: the boom root's crack: the drive's stiffness lost under tension [1]
CRACK = 0.5


def outside_records() -> list[dict[str, Any]]:
    """ah11-ah14: effects the catalog does not contain."""
    return [
        spec("ah11", "outside", "slow", True, (outside(
            "wind-on-raised-boom", {"wind": WIND},
            {"Tw_Nm": WIND,
             "form": "the boom receives -Tw sin(thb)|sin(thb)|: a steady wind along the road "
                     "presses on the boom's face, the face's projection across the wind "
                     "growing as sin(thb), the pressure's torque with its square"}),),
            note="a steady wind of about 8 m/s along the road presses on the boom as it "
                 "rises: nothing with the boom down, 20 N m pushing it back down upright; a "
                 "person sees the opening draw more current and slow towards the top, the "
                 "boom sag further back while held up, the closing run faster near the top; "
                 "close to a heavier boom (a force offset or an unbalance on it), but "
                 "growing with the square of the boom's lift"),
        spec("ah12", "outside", "fast", False, (outside(
            "relay-brake-resistor", {"brake_r": BRAKE_R},
            {"Rb_ohm": BRAKE_R[0], "u0_V": BRAKE_R[1],
             "form": "the loop takes Rb exp(-(u/u0)^2) i more, u the bridge's command: near "
                     "0 V the controller's braking relay drops the motor onto a braking "
                     "resistor instead of shorting it"}),),
            probes=("current",), noise={"current": {"white": 0.05, "quant": ADC_STEP}},
            note="a bench log of the current alone (12-bit ADC); an older controller brakes "
                 "through a relay and a 2 Ohm resistor instead of shorting the motor through "
                 "its bridge: while the command is at 0 V the braking current is about a third of "
                 "the declared one's and decays slowly, the motor coasting on; while driving, "
                 "nothing changes; close to a series resistance, but only while braking"),
        spec("ah13", "outside", "slow", False, (outside(
            "gyro-full-scale-clipping", {"clip": CLIP},
            {"ws_rad_s": CLIP,
             "form": "load_speed reads clip(wb, -ws, ws): the boom's gyroscope left at its "
                     "+-50 degrees/s full scale"}),),
            note="the boom's new gyroscope was left at its most sensitive range, +-50 "
                 "degrees/s (0.87 rad/s): the boom's speed reads flat at 0.87 rad/s through "
                 "the fast part of the opening and at -0.87 rad/s through the fast part of "
                 "the closing, while the current and the motor's speed carry on as declared; "
                 "close to a lower sensor gain on load_speed, but only above the full scale"),
        spec("ah14", "outside", "fast", True, (outside(
            "cracked-boom-root", {"crack": CRACK},
            {"dk": CRACK,
             "form": "the drive's torque takes -dk Kc max(twist, 0) more, twist = th/N - thb: a "
                     "fatigue crack at the boom's root opens under tension, halving its "
                     "stiffness while the hub leads the boom"}),),
            note="a fatigue crack has grown at the boom's root where it is clamped: it opens "
                 "whenever the drive leads the boom (the boom lagging as it is lifted, or "
                 "swinging down after a stop) and closes the other way, so the boom is half "
                 "as stiff one way as the other; a person sees a slower, lopsided ringing of "
                 "the boom through the motor's current and speed after each change of the "
                 "command; close to a softer drive or a backlash, but one-sided"),
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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 30, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:hub", {"coul": {"hub": 1e-2}}),
    ("coulomb-friction:boom", {"coul": {"boom": 1e-2}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:boom", {"visc": {"boom": 1e-3}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:boom", {"offset": {"boom": 1e-2}}),
    ("stribeck-friction:boom", {"stribeck": {"boom": (1e-2, 0.1)}}),
    ("backlash:K", {"gap": 1e-4}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:30", {"lsat": (30.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jb", {"p": {"Jb": P["Jb"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:boom", lambda a, b: {"cog": {"boom": [(1, a, b)]}}),
    ("cogging:rotor:20", lambda a, b: {"cog": {"rotor": [(20, a, b)]}}),
    ("cogging:boom:2", lambda a, b: {"cog": {"boom": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:20", lambda a, b: {"emf": [(20, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1 uV s/rad of EMF), 10 mN m on the boom."""
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


#: across the drive (a spring and a damper, 1:1): the body an effect on each is compared
#: with, and the factor its size takes there per kind (the hub and the boom turn at one mean
#: speed)
ACROSS = {"boom": ("hub", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0}),
          "hub": ("boom", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` across the drive
    (``recordkit.location_entry``), after a marginal record's scaling."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term of the catalog's kinds (the boom's weight, -Tg cos(angle), is a
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
