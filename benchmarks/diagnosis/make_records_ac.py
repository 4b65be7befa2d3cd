"""Generate the blind set ``fresh28`` of the diagnosis benchmark: records af01-af14 of motor AC
(a 12 V brushed DC motor moving a car seat's track: a rigid 5:1 spur gear and a flexible drive
shaft, its steel core a compliance, to the lead screw; the nut's dry friction and the grease's
drag), some sampled evenly and some UNEVENLY, three of them giving the diagnosis ONE probe
only, and merge their truth into truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_ac.py                # records/af*.csv + truth.json
    python benchmarks/diagnosis/make_records_ac.py --only af03,af12
    python benchmarks/diagnosis/make_records_ac.py --truth-only   # rewrite the af entries only

Uses simulators_ac.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_ac_slow.yaml's pwl states). A single-probe record (truth's
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
import simulators_ac as sa

RECORDS = HERE / "records"
SPLIT = "fresh28"
MOTOR = "AC"
SEED0 = 28500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_ac_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_ac_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.01, "speed": 0.2},
         "slow": {"current": 0.01, "speed": 0.2, "load_speed": 0.05}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AC
N = P["N"]
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_ac, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The spur gear is rigid and lossless as declared: a torque
# on the body ``hub`` is 1/N = 1/5 of it on the rotor, and the hub turns with the rotor. The
# screw lies behind the flexible shaft (compliant): an effect on it has no exact equal on the
# rotor.

def series_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] in series with the armature."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": LOOP,
        "parameters": {"R_series_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


def source_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] inside the supply."""
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[regime],
        "targets": [SOURCE[regime]], "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": LOOP,
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


def inductance(dl: float) -> Part:
    """The armature's inductance off by a factor 1 + ``dl`` (a correction of La's L)."""
    return {"p": {"L": P["L"] * (1.0 + dl)}}, {
        "effect": "inductance", "target": "La", "targets": ["La"], "correction": True,
        "parameters": {"L_true_H": P["L"] * (1.0 + dl), "dL": dl},
        "expected": {"dL": dl}}


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


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad] in the flexible shaft K."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap, "play_deg": math.degrees(gap),
                       "form": "no shaft torque while |twist| < gap/2, Kc (twist -+ gap/2) "
                               "+ Dc w_rel in contact, the damping never pulling"},
        "expected": {"gap": gap}}


def viscous_screw(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the screw."""
    return {"visc": {"screw": b}}, {
        "effect": "viscous-friction", "target": "screw", "targets": ["screw"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b ws against the screw"},
        "expected": {"b": b}}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF harmonic w slope sin(order th + phase) [V], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AC's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sa.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sa.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the seat module's current sense: a 12-bit ADC over +-10 A (4.88 mA steps)
ADC_STEP = 20.0 / 4096


def nulls() -> list[dict[str, Any]]:
    """af01, af02: the null records."""
    return [
        spec("af01", "null", "slow", True,
             noise={"current": {"white": 0.005, "ar1": [0.015, 0.9], "quant": ADC_STEP},
                    "speed": {"white": 0.2, "pink": 0.6},
                    "load_speed": {"white": 0.05}},
             note="the seat module's log on its irregular clock; the current with "
                  "Gauss-Markov noise (correlation 0.9 over the mean interval, 15 mA) on "
                  "white noise, read by its 12-bit ADC (4.88 mA steps); the encoder speed "
                  "with 1/f noise (white noise shaped by 1/sqrt(f), 0.6 rad/s) on white "
                  "noise; the screw's Hall speed with white noise"),
        spec("af02", "null", "fast", False,
             note="a bench log of the current and the motor encoder's speed, white noise"),
    ]


def singles() -> list[dict[str, Any]]:
    """af03-af07: one catalog effect each."""
    return [
        spec("af03", "catalog", "fast", True, (inductance(0.35),),
             note="the motor was replaced by a service part wound with more, finer turns "
                  "(the same torque constant through a different magnet grade): its "
                  "armature inductance is 35 % above the declared 0.9 mH (a correction of "
                  "La); the current's rise at each step is slower"),
        spec("af04", "catalog", "slow", False, (brush_drop(0.3),),
             marginal=lambda v: (brush_drop(v),), size=0.3,
             note="the motor's carbon brushes have glazed: a contact drop Vb tanh(i/1 mA) "
                  "in series with the armature, scaled to a 25 sigma signature (marginal)"),
        spec("af05", "catalog", "fast", False, (sensor("speed", "delay", 5e-5),),
             marginal=lambda d: (sensor("speed", "delay", d),), size=5e-5,
             probes=("speed",),
             note="a bench log of the motor encoder's speed alone; the speed is computed "
                  "from counts over a window that lags it: a sensor delay of the speed, "
                  "scaled to a 25 sigma signature (marginal)"),
        spec("af06", "catalog", "slow", False, (drift(0.02),),
             note="the seat was run end to end several times before the log: the armature "
                  "copper keeps heating during it, its resistance rising linearly by 2 % a "
                  "second (10 % over the record)"),
        spec("af07", "catalog", "fast", True, (saturation(4.0, 0.5),), probes=("current",),
             note="a bench log of the current alone; the armature's iron saturates at the "
                  "start and reversal currents: dpsi/di = La (0.5 + 0.5/(1 + (i/4 A)^2))"),
    ]


def pairs() -> list[dict[str, Any]]:
    """af08-af10: two catalog effects at once."""
    return [
        spec("af08", "two", "slow", True, (series_resistance(0.25, "slow"),
                                           viscous_screw(1e-4)),
             note="the motor's connector has corroded: 0.25 Ohm more in series with the "
                  "armature; and the track's grease has hardened: a viscous drag of 1e-4 "
                  "N m s/rad more on the screw (50 % above the declared 2e-4)"),
        spec("af09", "two", "slow", False, (source_resistance(0.3, "slow"),
                                            sensor("load_speed", "gain", 0.95)),
             note="the seat module is fed through a long, thin harness from a tired battery: "
                  "0.3 Ohm inside the supply; and the screw's Hall speed is scaled with a "
                  "wrong constant: a sensor gain of 0.95 on load_speed"),
        spec("af10", "two", "fast", False, (backlash(0.06), emf_harmonic(5, 4e-4, 0.8)),
             note="the flexible shaft's square end has worn in its socket: a play of 0.06 "
                  "rad (3.4 degrees) in the shaft; and the motor's magnets are unevenly "
                  "magnetised: an EMF harmonic of order 5, slope 4e-4 V s/rad (2 % of k), "
                  "phase 0.8, voltage only"),
    ]


#: the nut's friction growing with the thrust: mu [1] of the shaft's torque
NUTLOAD = 0.3
#: cold grease thinning: b1 [N m s/rad], tau [s]
GREASE = (4e-4, 1.5)
#: the seat heater on the shared harness: Rh [ohm], Ih [A], t1 [s], tr [s]
HEATER = (0.06, 8.0, 0.08, 0.005)
#: the bent track's tight stretch: Tb [N m], th0 [rad], wd [rad]
TIGHT = (0.04, 60.0, 8.0)


def outside_records() -> list[dict[str, Any]]:
    """af11-af14: effects the catalog does not contain."""
    return [
        spec("af11", "outside", "slow", True, (outside(
            "thrust-dependent-nut-friction", {"nutload": NUTLOAD},
            {"mu": NUTLOAD,
             "form": "the screw takes -mu |Tk| tanh(ws/0.01) more, Tk the flexible shaft's "
                     "torque Kc (th/N - ths) + Dc (w/N - ws): the nut's flank friction "
                     "grows with the thrust it carries"}),),
            note="the seat's occupant leans on the backrest: the nut's flanks carry the "
                 "thrust, their dry friction growing with it: 0.3 of the torque the "
                 "flexible shaft delivers, against the screw's turn; close to a dry friction "
                 "on the screw, but larger where the drive pushes harder (at the starts and "
                 "at the reversal)"),
        spec("af12", "outside", "slow", False, (outside(
            "cold-grease-thinning", {"grease": GREASE},
            {"b1_Nms_rad": GREASE[0], "tau_s": GREASE[1],
             "form": "the screw takes -b1 exp(-t/tau) ws more: the track's grease, cold at "
                     "the start, thinning as the screw churns it"}),),
            note="a winter morning: the track's grease is stiff at first and thins as the "
                 "screw churns it: a viscous drag on the screw of 4e-4 N m s/rad more at "
                 "the start (three times the declared 2e-4), decaying with a 1.5 s time "
                 "constant; close to a viscous friction on the screw, but fading"),
        spec("af13", "outside", "fast", True, (outside(
            "seat-heater-on-shared-harness", {"heater": HEATER},
            {"Rh_ohm": HEATER[0], "Ih_A": HEATER[1], "t1_s": HEATER[2], "tr_s": HEATER[3],
             "form": "the motor's terminal sees v - Rh (i + Ih h(t)), h(t) = (1 + tanh((t - "
                     "t1)/tr))/2: a harness resistance shared with the seat heater, which "
                     "switches on at t1"}),),
            probes=("current",), noise={"current": {"white": 0.01, "quant": ADC_STEP}},
            note="a bench log of the current alone (12-bit ADC); the motor shares 0.06 Ohm "
                 "of harness with the seat heater, which switches on at 80 ms drawing 8 A: "
                 "the motor loses 0.06 Ohm times its own current throughout and 0.48 V "
                 "more once the heater is on"),
        spec("af14", "outside", "slow", False, (outside(
            "bent-track-tight-stretch", {"tight": TIGHT},
            {"Tb_Nm": TIGHT[0], "th0_rad": TIGHT[1], "wd_rad": TIGHT[2],
             "form": "the screw takes -Tb exp(-((ths - th0)/wd)^2) tanh(ws/0.01) more: a "
                     "dry friction bump over a stretch of the track (th0 60 rad: 9.5 mm "
                     "of travel from the start, wd 8 rad: 1.3 mm)"}),),
            note="one seat rail was bent when a heavy load was dropped on it: the track "
                 "binds over a short stretch, a dry drag of up to 40 mN m on the screw "
                 "(above the declared 30) around 9.5 mm of travel from the seat's start "
                 "position, felt going forward and coming back"),
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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 28, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:screw", {"coul": {"screw": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:screw", {"visc": {"screw": 1e-5}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:screw", {"offset": {"screw": 1e-3}}),
    ("stribeck-friction:screw", {"stribeck": {"screw": (1e-3, 5.0)}}),
    ("backlash:K", {"gap": 1e-4}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:30", {"lsat": (30.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Js", {"p": {"Js": P["Js"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:screw", lambda a, b: {"cog": {"screw": [(1, a, b)]}}),
    ("cogging:rotor:5", lambda a, b: {"cog": {"rotor": [(5, a, b)]}}),
    ("cogging:screw:2", lambda a, b: {"cog": {"screw": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:5", lambda a, b: {"emf": [(5, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1 uV s/rad of EMF), 1 mN m on the screw."""
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
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sa, sim=sim,
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

