"""Generate the blind set ``fresh24`` of the diagnosis benchmark: records ab01-ab14 of motor Y
(a 12 V brushed DC motor in a car's electronic throttle body: a rigid 20:1 two-stage spur
gear to the throttle shaft, the butterfly plate on a preloaded torsion return spring, the
shaft's grease drag and its seal's dry friction), some sampled evenly and some UNEVENLY,
three of them giving the diagnosis ONE probe only, and merge their truth into truth.json.
The ids have two letters: every single letter is taken by an earlier set.

    python benchmarks/diagnosis/make_records_y.py                # records/ab*.csv + truth.json
    python benchmarks/diagnosis/make_records_y.py --only ab03,ab12
    python benchmarks/diagnosis/make_records_y.py --truth-only   # rewrite the ab entries only

Uses simulators_y.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_y_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the catalog imprints it is compared with are computed on that probe
alone (``OneProbe``, as make_records_x.py has it). Even records are sampled on the regime's
grid k/fs; uneven ones, in the fast regime, on a 20 kHz grid whose every sample is moved by a
random jitter of up to 10-30 % of the interval, and in the slow regime at a logger's
irregular intervals (0.6-1.4 times the mean of 2 ms) with a few samples dropped. Each uneven
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
import simulators_y as sy

RECORDS = HERE / "records"
SPLIT = "fresh24"
MOTOR = "Y"
SEED0 = 24500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_y_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_y_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.01, "speed": 0.3},
         "slow": {"current": 0.01, "speed": 0.3, "load_speed": 0.015}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sy.MOTOR_Y
N = P["N"]
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_y, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The spur gear is rigid and lossless as declared: a
# torque on the plate is 1/N = 1/20 of it on the rotor, and the plate turns with the rotor.

def series_resistance(r: float, regime: str) -> Part:
    """A resistance [ohm] in series with the armature (accepted inside the supply)."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": ["Ra", "La", "M"],
        "parameters": {"R_series_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


def source_resistance(r: float, regime: str) -> Part:
    """A resistance [ohm] inside the supply (accepted in series with the armature)."""
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[regime],
        "targets": [SOURCE[regime]], "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": ["Ra", "La", "M"],
                         "expected": {"R": r}}]}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def saturation(ipar: float, ratio: float) -> Part:
    """The armature's inductance saturating: dpsi/di = La (ratio + (1 - ratio)/(1 +
    (i/Ipar)^2))."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def offset_plate(f: float) -> Part:
    """A constant torque ``f`` [N m] the plate receives (accepted on the rotor at f / N)."""
    return {"offset": {"plate": f}}, {
        "effect": "force-offset", "target": "plate", "targets": ["plate"],
        "parameters": {"T_Nm": f,
                       "form": "the plate receives a constant T (opening it when T > 0)"},
        "expected": {"F": f},
        "also_accept": [{"effect": "force-offset", "targets": ["rotor"],
                         "expected": {"F": f / N}}]}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF ripple w slope sin(order angle + phase) [V], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def cogging_rotor(order: int, amp: float, phase: float) -> Part:
    """A detent torque amp sin(order angle + phase) [N m] on the rotor."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b}}


def inertia_rotor(dj: float) -> Part:
    """The rotor's inertia off by a factor 1 + ``dj`` (a correction of Jr's Jm)."""
    return {"p": {"Jm": P["Jm"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jr", "targets": ["Jr"], "correction": True,
        "parameters": {"Jr_true_kgm2": P["Jm"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


def coulomb_plate(c: float) -> Part:
    """An extra dry friction c tanh(wp / 0.01) [N m] on the plate (accepted on the rotor
    at c / N)."""
    return {"coul": {"plate": c}}, {
        "effect": "coulomb-friction", "target": "plate", "targets": ["plate"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(wp/0.01) against the plate"},
        "expected": {"c": c},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["rotor"],
                         "expected": {"c": c / N}}]}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor Y's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sy.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sy.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the ECU's current sense: a 12-bit ADC over +-10 A (4.9 mA steps)
ADC_STEP = 20.0 / 4096
ADC_I = {"white": 0.01, "quant": ADC_STEP}


def nulls_and_singles() -> list[dict[str, Any]]:
    """ab01-ab08: the null and single catalog records."""
    return [
        spec("ab01", "null", "fast", False, note="white noise; current and speed"),
        spec("ab02", "null", "slow", True,
             noise={"current": {"white": 0.005, "ar1": [0.01, 0.85], "quant": ADC_STEP},
                    "speed": {"white": 0.3, "pink": 0.4},
                    "load_speed": {"white": 0.015, "quant": 0.01}},
             note="a logger's irregular clock; the current with Gauss-Markov noise "
                  "(correlation 0.85 over the mean interval) on white noise, read by the "
                  "ECU's 12-bit ADC (4.9 mA steps); the speed with 1/f noise (white noise "
                  "shaped by 1/sqrt(f)) on white noise: the encoder's period counter beating "
                  "against the logger's clock; the plate's speed from the throttle position "
                  "sensor's differences, quantised to 0.01 rad/s"),
        spec("ab03", "null", "fast", True, probes=("speed",),
             noise={"speed": {"white": 0.2, "quant": 0.25}},
             note="a bench log of the motor's encoder speed alone, jittered: white noise, "
                  "read with a resolution of 0.25 rad/s"),
        spec("ab04", "catalog", "fast", True, (saturation(1.2, 0.6),),
             note="the replacement motor's armature stack is of a thinner, cheaper steel: its "
                  "inductance falls with the current, to 0.6 of La at large currents (Ipar "
                  "1.2 A). A person sees the current's steps rise faster: at the tip-in the "
                  "current leads by up to 0.08 A within the first milliseconds, and through the "
                  "closing kick's reversals it runs up to 0.15 A ahead"),
        spec("ab05", "catalog", "slow", False, (offset_plate(0.03),),
             noise={"current": ADC_I, "speed": {"white": 0.3},
                    "load_speed": {"white": 0.015}},
             note="the throttle body's return spring was replaced by a service part wound "
                  "with a quarter less preload: a constant 0.03 N m opening the plate that the "
                  "declared model lacks (T0 is 0.12 N m). A person sees the plate settle 0.06 rad "
                  "further open for the same command (the rotor up to 8 rad/s faster opening)"
                  "; the current read by a 12-bit ADC (4.9 mA steps)"),
        spec("ab06", "catalog", "fast", True, (emf_harmonic(12, 2e-4, -0.7),),
             probes=("current",), marginal=lambda sl: (emf_harmonic(12, sl, -0.7),),
             size=2e-4, noise={"current": ADC_I},
             note="the ECU's log of its current sense, the current alone: the commutator's "
                  "ripple in the EMF, twelve a turn (the six-slot armature's twelve "
                  "commutations), scaled to a 25 sigma signature (marginal): 1.2e-4 V s/rad, "
                  "a ripple of up to 8 mA at up to 370 Hz while the rotor runs; the current "
                  "read by a 12-bit ADC"),
        spec("ab07", "catalog", "fast", False, (cogging_rotor(6, 2e-3, 0.5),),
             marginal=lambda a: (cogging_rotor(6, a, 0.5),), size=2e-3,
             note="the motor's magnets pull its six-slot armature to six detents a turn: a "
                  "cogging torque sin(6 angle + 0.5) on the rotor, scaled to a 25 sigma "
                  "signature (marginal): 58 uN m, a ripple of up to 0.25 rad/s in the speed "
                  "and 2 mA in the current while the rotor runs"),
        spec("ab08", "catalog", "slow", True, (source_resistance(0.25, "slow"),),
             note="the ECU's bridge MOSFETs run hot and its harness connector is aged: 0.25 ohm "
                  "inside the supply the bridge presents to the motor (the bridge's on "
                  "resistances and the connector's). A person sees the plate open less for "
                  "every command (the current 12 % lower when holding), and the moves "
                  "slower"),
    ]


def pairs() -> list[dict[str, Any]]:
    """ab09, ab10: a declared parameter's correction with a catalog effect, and two catalog
    effects."""
    return [
        spec("ab09", "two", "fast", False,
             (inertia_rotor(0.3), series_resistance(0.15, "fast")),
             note="the declared Jm, from the motor's catalogue, is the bare armature's: with its"
                  " steel pinion pressed on and the encoder hub of the test bench the rotor's "
                  "inertia is 30 % higher (a correction of Jr: the rotor lags at every step "
                  "and the closing kick's reversal takes longer); and the motor's crimped "
                  "terminal has corroded: 0.15 ohm in series with the armature (the holding "
                  "currents 8 % lower)"),
        spec("ab10", "two", "slow", True,
             (coulomb_plate(0.03), sensor("load_speed", "delay", 4e-3)),
             note="a throttle body from a high-mileage engine: oily blow-by deposits have "
                  "coated the bore and the shaft, adding a dry friction of 0.03 N m on the "
                  "plate (the plate stops short of its settling points and moves in jerks when "
                  "it moves slowly), and the logger computes the plate's speed from the "
                  "throttle position sensor through its filter: 4 ms late (a delay of the "
                  "load_speed)"),
    ]


#: the limp-home (default) spring: its preload [N m], its rate [N m/rad], where its lever
#: meets the plate (15 mrad below limp-home) [rad] and the width of the contact's onset [rad]
LIMP = (0.2, 1.0, -0.015, 0.004)
#: the return spring's coil friction: a friction coefficient times its wind-up torque [1]
COIL = 0.08
#: the intake pulsation: [N m per rad of the plate's angle from closed], the limp-home
#: plate's angle from closed [rad], the firing frequency of a four-cylinder engine at 1200 rpm
#: [Hz] and the phase [rad]
PULSE = (0.05, 0.14, 40.0, 0.3)
#: the carbon ring: its extra friction [N m], its centre (20 mrad below limp-home, near the
#: idle position) [rad] and its half-width [rad]
COKE = (0.06, -0.02, 0.04)


def outside_records() -> list[dict[str, Any]]:
    """ab11-ab14: effects the catalog does not contain."""
    return [
        spec("ab11", "outside", "slow", True, (outside(
            "limp-home-spring", {"limp": LIMP},
            {"T1_Nm": LIMP[0], "c2_Nm_rad": LIMP[1], "thl_rad": LIMP[2], "wl_rad": LIMP[3],
             "form": "the plate receives (T1 - c2 (thp - thl)) (1 - tanh((thp - thl)/wl))/2: a "
                     "second, opposing spring that engages just below limp-home"}),),
            note="the throttle body has the usual limp-home mechanism the declared model "
                 "leaves out: below the limp-home position a second spring (the default "
                 "spring, preload 0.2 N m, 1 N m/rad) pushes the plate open against the "
                 "return spring, engaging 15 mrad below limp-home. A person sees the plate "
                 "stop at limp-home after each closing kick instead of sinking towards the "
                 "idle position: at the idle command it rests 13 mrad below limp-home instead "
                 "of 54, the rotor comes to rest at 2.49 s instead of 2.68 s after the first "
                 "kick, and the next opening starts from higher up"),
        spec("ab12", "outside", "fast", False, (outside(
            "return-spring-coil-friction", {"coil": COIL},
            {"mu": COIL,
             "form": "the plate takes -mu (T0 + c thp) tanh(wp/0.01): a dry friction in "
                     "proportion to the return spring's wind-up torque"}),),
            note="the torsion return spring's coils rub on each other and on their guide "
                 "sleeve, with a friction in proportion to the spring's torque (8 % of it): "
                 "10 mN m at limp-home, 50 mN m with the plate 1 rad open. A person sees "
                 "the plate lag its command, more the further it is open, more current to "
                 "open it and less to hold it closing, and a hysteresis between opening and "
                 "closing that widens with the opening"),
        spec("ab13", "outside", "fast", True, (outside(
            "intake-pulsation-torque", {"pulse": PULSE},
            {"A_Nm_rad": PULSE[0], "phc_rad": PULSE[1], "f_Hz": PULSE[2], "psi_rad": PULSE[3],
             "form": "the plate receives A (thp + phc) sin(2 pi f t + psi): the manifold's "
                     "pressure pulses at the firing frequency on the plate's off-centre shaft, "
                     "growing with its opening"}),),
            note="the engine runs at 1200 rpm while the bench logs the throttle: the intake "
                 "manifold's pressure pulses (two a crank turn, 40 Hz) push on the plate, "
                 "whose shaft is slightly off its centre line, with a torque that grows with "
                 "the opening (7 mN m at limp-home, 33 mN m at 0.5 rad). A person sees a "
                 "40 Hz wobble of a few rad/s in the speed, larger while the plate is open, "
                 "and a matching ripple of some tens of mA in the current"),
        spec("ab14", "outside", "slow", False, (outside(
            "carbon-ring-near-idle", {"coke": COKE},
            {"dT_Nm": COKE[0], "thc_rad": COKE[1], "wc_rad": COKE[2],
             "form": "the plate takes -dT exp(-((thp - thc)/wc)^2) tanh(wp/0.01): a dry "
                     "friction in a band of angles around the idle position"}),),
            probes=("current",), noise={"current": ADC_I},
            note="the ECU's log of its current sense, the current alone: a ring of carbon "
                 "(oil vapour and soot from the crankcase ventilation) has built up in the "
                 "bore where the plate spends its time, around the idle position: a dry "
                 "friction of up to 0.06 N m within some 40 mrad of it, none higher up. A "
                 "person sees the plate held back at the start of every opening near idle, "
                 "the current up to 0.1 A higher at the tip-in (0.4 s) and 0.16 A at the "
                 "opening from idle (3.3 s) while the rotor's back-EMF lags, and the closings "
                 "stop short of idle (3 mrad above limp-home instead of 54 mrad below it); "
                 "the current read by a 12-bit ADC"),
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
    return recordkit.record_times(s, sy.REGIMES, sy.grid, 24, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:plate", {"coul": {"plate": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:plate", {"visc": {"plate": 1e-4}}),
    ("force-offset:plate", {"offset": {"plate": 1e-3}}),
    ("stribeck-friction:rotor:10", {"stribeck": {"rotor": (1e-4, 10.0)}}),
    ("stribeck-friction:plate:0.1", {"stribeck": {"plate": (1e-3, 0.1)}}),
    ("stribeck-friction:plate:1", {"stribeck": {"plate": (1e-3, 1.0)}}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:2", {"lsat": (2.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jp", {"p": {"Jp": P["Jp"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:plate", lambda a, b: {"cog": {"plate": [(1, a, b)]}}),
    ("cogging:plate:2", lambda a, b: {"cog": {"plate": [(2, a, b)]}}),
    ("cogging:rotor:6", lambda a, b: {"cog": {"rotor": [(6, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:6", lambda a, b: {"emf": [(6, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:12", lambda a, b: {"emf": [(12, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1 uV s/rad of EMF), 1 mN m on the plate."""
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
#: no harmonic term; the gear is rigid, so no effect has another place across a compliance
KIT = OneProbe(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sy, sim=sim,
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
