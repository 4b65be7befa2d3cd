"""Generate the blind set ``fresh25`` of the diagnosis benchmark: records ac01-ac14 of motor Z
(a 24 V brushed DC motor in a swimming-pool robot cleaner's track drive: a rigid 30:1 spur
gearhead to the drive sprocket, a rubber track, compliant, to the robot with the water it
drags along, the track's rolling and the scrubbing brush's dry drag, the water's linear and
form drag), some sampled evenly and some UNEVENLY, three of them giving the diagnosis ONE
probe only, and merge their truth into truth.json. The ids have two letters: every single
letter is taken by an earlier set.

    python benchmarks/diagnosis/make_records_z.py                # records/ac*.csv + truth.json
    python benchmarks/diagnosis/make_records_z.py --only ac03,ac12
    python benchmarks/diagnosis/make_records_z.py --truth-only   # rewrite the ac entries only

Uses simulators_z.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_z_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the catalog imprints it is compared with are computed on that probe
alone (``OneProbe``, as make_records_y.py has it). Even records are sampled on the regime's
grid k/fs; uneven ones, in the fast regime, on a 25 kHz grid whose every sample is moved by a
random jitter of up to 10-30 % of the interval, and in the slow regime at a logger's
irregular intervals (0.6-1.4 times the mean of 1 ms) with a few samples dropped. Each uneven
record has its own times (from its seed), and the motor is simulated at those very times
(``t_eval``), never interpolated. truth.json is merged under an exclusive lock
(recordkit.merge). Nobody ran the diagnosis on these records.
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
import simulators_z as sz

RECORDS = HERE / "records"
SPLIT = "fresh25"
MOTOR = "Z"
SEED0 = 25500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_z_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_z_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.02, "speed": 0.3},
         "slow": {"current": 0.02, "speed": 0.3, "load_speed": 0.02}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sz.MOTOR_Z
N = P["N"]
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_z, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearhead is rigid and lossless as declared: a torque
# on the sprocket is 1/N = 1/30 of it on the rotor, and the sprocket turns with the rotor. The
# robot lies behind the compliant track: an effect on it has no exact equal elsewhere.

def brush_drop(vb: float) -> Part:
    """A brush contact drop Vb tanh(i / 1 mA) [V] in series with the armature."""
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad of the sprocket] in the track ``K``."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap, "play_mm": gap * 32.0,
                       "form": "no track torque while |twist| < gap/2, Kt (twist -+ gap/2) + "
                               "Dt w_rel in contact, the damping never pulling"},
        "expected": {"gap": gap}}


def unbalance_rotor(amp: float, phase: float) -> Part:
    """A once-per-turn torque amp sin(angle + phase) [N m] on the rotor."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(1, a, b)]}}, {
        "effect": "unbalance", "target": "rotor", "targets": ["rotor"], "order": 1,
        "parameters": {"order": 1, "T_Nm": amp, "phase_rad": phase,
                       "form": "rotor receives T sin(1 angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["rotor"], "order": 1,
                         "expected": {"a": a, "b": b}}]}


def stribeck_robot(s: float, ws: float) -> Part:
    """A Stribeck peak s exp(-(wb / ws)^2) tanh(wb / 0.01) [N m] over the robot's declared
    dry drag."""
    return {"stribeck": {"robot": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "robot", "targets": ["robot"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "robot takes s exp(-(w/ws)^2) tanh(w/0.01) over the declared "
                               "Tr tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def viscous_robot(b: float) -> Part:
    """An extra viscous friction b [N m s/rad] on the robot (behind the compliant track: no
    equal on the rotor)."""
    return {"visc": {"robot": b}}, {
        "effect": "viscous-friction", "target": "robot", "targets": ["robot"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b w against the robot"},
        "expected": {"b": b}}


def warmup(rise: float, tau: float) -> Part:
    """The winding warming: R (1 + rise (1 - exp(-t / tau)))."""
    return {"warmup": (rise, tau)}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + rise*(1 - exp(-t/tau)))", "rise": rise,
                       "tau_s": tau},
        "expected": {"rise": rise, "tau": tau}}


def coulomb_spr(c: float) -> Part:
    """An extra dry friction c tanh(ws / 0.01) [N m] on the sprocket (accepted on the rotor
    at c / N)."""
    return {"coul": {"spr": c}}, {
        "effect": "coulomb-friction", "target": "spr", "targets": ["spr"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(ws/0.01) against the sprocket"},
        "expected": {"c": c},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["rotor"],
                         "expected": {"c": c / N}}]}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor Z's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sz.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sz.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the robot controller's current sense: a 12-bit ADC over +-20 A (9.8 mA steps)
ADC_STEP = 40.0 / 4096
ADC_I = {"white": 0.02, "quant": ADC_STEP}


def nulls() -> list[dict[str, Any]]:
    """ac01-ac03: the null records."""
    return [
        spec("ac01", "null", "fast", False, note="white noise; current and speed"),
        spec("ac02", "null", "slow", True,
             noise={"current": {"white": 0.01, "ar1": [0.02, 0.9], "quant": ADC_STEP},
                    "speed": {"white": 0.3, "pink": 0.5},
                    "load_speed": {"white": 0.02, "quant": 0.02}},
             note="the robot controller's log on its irregular clock; the current with "
                  "Gauss-Markov noise (correlation 0.9 over the mean interval) on white noise, "
                  "read by its 12-bit ADC (9.8 mA steps); the encoder speed with 1/f noise "
                  "(white noise shaped by 1/sqrt(f)) on white noise; the robot's ground speed "
                  "from its optical floor sensor, quantised to 0.02 rad/s"),
        spec("ac03", "null", "fast", False, probes=("current",), noise={"current": ADC_I},
             note="the drive module's own log of its current sense, the current alone: white "
                  "noise read by the 12-bit ADC (9.8 mA steps)"),
    ]


def singles() -> list[dict[str, Any]]:
    """ac04-ac08: one catalog effect each."""
    return [
        spec("ac04", "catalog", "fast", True, (brush_drop(0.8),),
             note="the motor's carbon brushes have worn onto a glazed commutator: a contact "
                  "drop of 0.8 V in the armature loop that the declared model lacks. A person "
                  "sees the rotor run 16 rad/s slower at 14 V (280 instead of 295 rad/s), up to "
                  "20 rad/s in the transients, and the current up to 1.6 A off"),
        spec("ac05", "catalog", "slow", False, (backlash(0.05),), noise={
            "current": ADC_I, "speed": {"white": 0.3}, "load_speed": {"white": 0.02}},
             note="the sprocket's teeth are worn and the track has stretched: a play of 0.05 "
                  "rad of the sprocket (1.6 mm of track) between the teeth and the track's lugs. "
                  "A person sees the rotor run free through the play at every start and "
                  "reversal, then jerk the robot: the speed up to 15 rad/s off the declared "
                  "model's, the robot's speed 2.3 rad/s off at the reversal, and the track's "
                  "10 Hz ringing chopped; the current read by a 12-bit ADC"),
        spec("ac06", "catalog", "fast", False, (unbalance_rotor(1e-3, 0.9),),
             marginal=lambda a: (unbalance_rotor(a, 0.9),), size=1e-3,
             note="the armature lost a balancing weight: the motor lies on its side in the "
                  "module, so the armature's heavy side is lifted once a turn, a torque "
                  "sin(angle + 0.9) on the rotor, scaled to a 25 sigma signature (marginal): "
                  "0.49 mN m, a ripple once a turn, up to 50 Hz, of up to 0.16 rad/s in the "
                  "speed and 8 mA in the current"),
        spec("ac07", "catalog", "slow", True, (stribeck_robot(0.1, 2.0),),
             marginal=lambda s: (stribeck_robot(s, 2.0),), size=0.1,
             note="the scrubbing brush's bristles stick to the tiles when the robot stands: a "
                  "Stribeck peak over the declared dry drag of the track and the brush "
                  "(Stribeck speed 2 rad/s, 6 cm/s of the robot), scaled to a 25 sigma "
                  "signature (marginal): a peak of 31 mN m; at every start, stop and reversal "
                  "the robot is held back a little longer (the robot's speed up to 0.05 "
                  "rad/s off, the rotor's 0.48 rad/s, the current 24 mA)"),
        spec("ac08", "catalog", "fast", False, (sensor("speed", "gain", 0.97),),
             probes=("speed",),
             note="a bench log of the motor's encoder speed alone, through a frequency-to-"
                  "voltage converter calibrated 3 % low (a sensor gain of 0.97): a person sees "
                  "every speed 3 % smaller (286 instead of 295 rad/s at 14 V)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """ac09, ac10: two catalog effects at once."""
    return [
        spec("ac09", "two", "fast", False,
             (viscous_robot(0.015), sensor("current", "offset", 0.05)),
             note="the robot's filter bag is clogged and bulges into the flow under it: an "
                  "extra linear drag of 0.015 N m s/rad on the robot (2.5 times the declared "
                  "0.01; the rotor up to 3.6 rad/s slower and the running current "
                  "higher); and the current sensor's offset has drifted to +0.05 A "
                  "(a sensor offset)"),
        spec("ac10", "two", "slow", True, (warmup(0.08, 2.0), coulomb_spr(0.15)),
             note="the robot has just finished a wall climb that heated the motor's "
                  "commutator: its heat spreads into the winding, whose resistance rises by 8 % "
                  "with a time constant of 2 s (a warm-up of Ra); and the gearhead's new output "
                  "shaft lip seal grips the shaft: a dry friction of 0.15 N m on the sprocket "
                  "(5 mN m at the rotor). A person sees the rotor run up to 7.4 rad/s slower"),
    ]


#: the resettable fuse: its cold resistance [ohm], its temperature coefficient near its trip
#: point [1/K], its heat capacity [J/K] and its conductance to the water-cooled housing [W/K]
FUSE = (0.05, 0.08, 0.005, 0.01)
#: the chipped tooth: the binding's peak torque at the sprocket [N m], the sharpness of its
#: once-per-turn pulse [1] (about 0.18 rad wide) and its angle [rad]
TOOTH = (0.15, 30.0, 1.0)
#: the commutation's reactance drop: [ohm per rad/s of the rotor]
ARC = 4e-4
#: the floating cable: its drag per rad of the robot's travel [N m s/rad^2] and the length
#: paid out at the start [rad of the sprocket, 16 cm]
CABLE = (1e-3, 5.0)


def outside_records() -> list[dict[str, Any]]:
    """ac11-ac14: effects the catalog does not contain."""
    return [
        spec("ac11", "outside", "slow", True, (outside(
            "resettable-fuse-heating", {"fuse": FUSE},
            {"R0_ohm": FUSE[0], "a_per_K": FUSE[1], "C_J_K": FUSE[2], "G_W_K": FUSE[3],
             "form": "R0 (1 + a dT) in the loop, C ddT/dt = R0 (1 + a dT) i^2 - G dT from "
                     "dT = 0: a PTC fuse heated by its own loss"}),),
            probes=("current",), noise={"current": ADC_I},
            note="the controller's log of its current sense, the current alone: the power "
                 "supply's floating cable feeds the robot through a resettable (PTC) fuse the "
                 "declared model leaves out, 50 mOhm cold, close to its trip point: every "
                 "start and reversal heats it (a time constant of 0.5 s to the housing), and "
                 "its resistance rises by 8 % a kelvin: up to 30 K and 0.17 Ohm after the "
                 "reversal at 4.3 s. A person sees the current's peaks at each start and "
                 "reversal lower than the declared model's, more so the later and the closer "
                 "together they come, up to 0.19 A; the current read by a 12-bit ADC"),
        spec("ac12", "outside", "slow", False, (outside(
            "chipped-output-gear-tooth", {"tooth": TOOTH},
            {"A_Nm": TOOTH[0], "kappa": TOOTH[1], "th0_rad": TOOTH[2],
             "form": "the sprocket takes -A exp(kappa (cos(ths - th0) - 1)) tanh(ws/0.01): "
                     "a binding pulse once per turn of the gearhead's output"}),),
            note="a tooth of the gearhead's output gear is chipped and its burr binds in the "
                 "mesh once per output turn: a braking pulse of up to 0.15 N m at the sprocket "
                 "(5 mN m at the rotor), some 0.18 rad of the sprocket wide. A person sees a "
                 "short dip of up to 1.9 rad/s in the speed and a spike of up to 0.09 A in the "
                 "current once per sprocket turn, 1.8 times a second at 16 V, more apart at "
                 "10 V, and none while the robot stands"),
        spec("ac13", "outside", "fast", True, (outside(
            "commutation-reactance-drop", {"arc": ARC},
            {"ka_ohm_s_rad": ARC,
             "form": "a voltage ka sqrt(w^2 + 1) i against the current: a resistance growing "
                     "in proportion to the rotor's speed"}),),
            note="the motor's commutation is poor (its brushes sit off the neutral after a "
                 "repair): the reactance voltage of the coils being commutated is not "
                 "cancelled and the brushes spark, a drop that grows with the current and the "
                 "speed: 0.12 Ohm more in the loop at 300 rad/s, none at rest. A person sees "
                 "the speed 1.7 rad/s lower at 14 V and up to 6.7 rad/s off in the "
                 "transients, and the current up to 1.1 A off where a large current meets a "
                 "fast rotor (the reversal, the braking)"),
        spec("ac14", "outside", "slow", False, (outside(
            "floating-cable-drag", {"cable": CABLE},
            {"cb_Nms_rad2": CABLE[0], "x0_rad": CABLE[1],
             "form": "the robot takes -cb sqrt(thb^2 + x0^2) wb: a linear drag growing with "
                     "the length of cable paid out"}),),
            note="the robot's floating power cable, dragged through the water behind it, pulls "
                 "back with a drag in proportion to its speed and to the length of cable it "
                 "has paid out from its start: 5 mN m s/rad at the start, 19 mN m s/rad after "
                 "the 0.6 m run, nearly twice the declared linear drag. A person sees the "
                 "robot slow down along its run (the speed 1.8 rad/s lower and the current "
                 "0.09 A higher at the end of the run; up to 3 rad/s and 0.15 A), less so "
                 "backing towards its start"),
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
    return recordkit.record_times(s, sz.REGIMES, sz.grid, 25, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:spr", {"coul": {"spr": 1e-3}}),
    ("coulomb-friction:robot", {"coul": {"robot": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:spr", {"visc": {"spr": 1e-4}}),
    ("viscous-friction:robot", {"visc": {"robot": 1e-4}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:robot", {"offset": {"robot": 1e-3}}),
    ("stribeck-friction:rotor:10", {"stribeck": {"rotor": (1e-4, 10.0)}}),
    ("stribeck-friction:robot:0.3", {"stribeck": {"robot": (1e-3, 0.3)}}),
    ("stribeck-friction:robot:3", {"stribeck": {"robot": (1e-3, 3.0)}}),
    ("backlash:K", {"gap": 1e-4}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:10", {"lsat": (10.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Js", {"p": {"Js": P["Js"] * 1.001}}),
    ("inertia:Jb", {"p": {"Jb": P["Jb"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:spr", lambda a, b: {"cog": {"spr": [(1, a, b)]}}),
    ("unbalance:robot", lambda a, b: {"cog": {"robot": [(1, a, b)]}}),
    ("cogging:rotor:10", lambda a, b: {"cog": {"rotor": [(10, a, b)]}}),
    ("cogging:spr:12", lambda a, b: {"cog": {"spr": [(12, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:10", lambda a, b: {"emf": [(10, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:20", lambda a, b: {"emf": [(20, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1 uV s/rad of EMF), 1 mN m on the sprocket and the robot."""
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


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term
KIT = OneProbe(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sz, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=harmonic_size, marginal_sigma=MARGINAL_SIGMA, declared=())
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
