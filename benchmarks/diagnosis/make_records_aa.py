"""Generate the blind set ``fresh26`` of the diagnosis benchmark: records ad01-ad14 of motor AA
(a 36 V brushed DC motor driving an industrial lockstitch sewing machine's head through a
1.5:1 toothed belt whose stretch is a compliance; the head's oil drag and its mechanisms' dry
friction), some sampled evenly and some UNEVENLY, three of them giving the diagnosis ONE
probe only, and merge their truth into truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_aa.py                # records/ad*.csv + truth.json
    python benchmarks/diagnosis/make_records_aa.py --only ad03,ad12
    python benchmarks/diagnosis/make_records_aa.py --truth-only   # rewrite the ad entries only

Uses simulators_aa.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_aa_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the catalog imprints it is compared with are computed on that probe
alone (``OneProbe``, as make_records_z.py has it). Even records are sampled on the regime's
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
import simulators_aa as sa

RECORDS = HERE / "records"
SPLIT = "fresh26"
MOTOR = "AA"
SEED0 = 26500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_aa_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_aa_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.03, "speed": 0.2},
         "slow": {"current": 0.03, "speed": 0.2, "load_speed": 0.1}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AA
N = P["N"]
Part = tuple[dict, dict]
LOOP = ["Ra", "La", "M"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_aa, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The belt's tooth engagement is rigid and lossless as
# declared: a torque on the body ``belt`` is 1/N = 1/1.5 of it on the rotor, and the belt
# turns with the rotor. The head lies behind the belt's stretch (compliant): an effect on it
# has no exact equal on the rotor.

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


def cogging_rotor(order: int, amp: float, phase: float) -> Part:
    """A detent torque amp sin(order th + phase) [N m] on the rotor (accepted on the belt at
    the order order N and the amplitude amp N)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["belt"], "order": round(order * N),
                         "expected": {"a": a * N, "b": b * N}}]}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF harmonic w slope sin(order th + phase) [V], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def drift(alpha: float) -> Part:
    """The armature's resistance drifting linearly, R (1 + alpha t) [1/s]."""
    return {"alpha": alpha}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + alpha*t)", "alpha_per_s": alpha},
        "expected": {"alpha": alpha}}


def coulomb_head(c: float) -> Part:
    """An extra dry friction c tanh(wh / 0.01) [N m] on the head (behind the belt)."""
    return {"coul": {"head": c}}, {
        "effect": "coulomb-friction", "target": "head", "targets": ["head"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(wh/0.01) against the head"},
        "expected": {"c": c}}


def viscous_rotor(b: float) -> Part:
    """An extra viscous friction b [N m s/rad] on the rotor (accepted on the belt at b N^2)."""
    return {"visc": {"rotor": b}}, {
        "effect": "viscous-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b w against the rotor"},
        "expected": {"b": b},
        "also_accept": [{"effect": "viscous-friction", "targets": ["belt"],
                         "expected": {"b": b * N * N}}]}


def inertia_head(dj: float) -> Part:
    """The head's inertia off by a factor 1 + ``dj`` (a correction of Jh's J)."""
    return {"p": {"Jh": P["Jh"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jh", "targets": ["Jh"], "correction": True,
        "parameters": {"Jh_true_kgm2": P["Jh"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AA's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sa.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sa.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the control box's current sense: a 12-bit ADC over +-40 A (19.5 mA steps)
ADC_STEP = 80.0 / 4096
ADC_I = {"white": 0.03, "quant": ADC_STEP}


def nulls() -> list[dict[str, Any]]:
    """ad01, ad02: the null records."""
    return [
        spec("ad01", "null", "slow", True,
             noise={"current": {"white": 0.01, "ar1": [0.04, 0.95], "quant": ADC_STEP},
                    "speed": {"white": 0.2, "pink": 0.6},
                    "load_speed": {"white": 0.1, "quant": 0.05}},
             note="the control box's log on its irregular clock; the current with "
                  "Gauss-Markov noise (correlation 0.95 over the mean interval, 0.04 A) on "
                  "white noise, read by its 12-bit ADC (19.5 mA steps); the encoder speed "
                  "with 1/f noise (white noise shaped by 1/sqrt(f), 0.6 rad/s) on white "
                  "noise; the handwheel synchroniser's speed quantised to 0.05 rad/s"),
        spec("ad02", "null", "fast", False, probes=("current",),
             note="a bench log of the current alone, white noise"),
    ]


def singles() -> list[dict[str, Any]]:
    """ad03-ad07: one catalog effect each."""
    return [
        spec("ad03", "catalog", "fast", True, (saturation(8.0, 0.55),),
             note="the motor was rewound on a cheaper lamination stack: the armature's "
                  "inductance falls with the current, to 55 % of the declared 1.8 mH deep in "
                  "saturation (Ipar 8 A). A person sees the current rise faster at every step "
                  "and reversal, up to 1.9 A off the declared model's, and the speed up to 3.3 "
                  "rad/s off"),
        spec("ad04", "catalog", "fast", False, (cogging_rotor(12, 1e-3, -0.4),),
             marginal=lambda a: (cogging_rotor(12, a, -0.4),), size=1e-3,
             note="the motor (12 slots, 4 poles) had a magnet glued back slightly out of "
                  "place after a repair: a detent torque at the slot order 12 on the rotor, "
                  "sin(12 angle - 0.4), scaled to a 25 sigma signature (marginal): 4.9 mN m, a "
                  "ripple at 12 times the rotor's turn rate (up to 640 Hz) of up to 0.31 rad/s "
                  "in the speed and 18 mA in the current"),
        spec("ad05", "catalog", "fast", False, (sensor("speed", "delay", 1e-4),),
             marginal=lambda d: (sensor("speed", "delay", d),), size=1e-4,
             probes=("speed",), note="a bench log of the motor encoder's speed alone, which the drive's "
                  "firmware reports a fraction of a control cycle late: a sensor delay, scaled "
                  "to a 25 sigma signature (marginal): 19.8 us; the speed up to 0.19 rad/s off "
                  "where it changes fastest"),
        spec("ad06", "catalog", "slow", True, (drift(5e-3),),
             marginal=lambda a: (drift(a),), size=5e-3, note="the motor is still warming from an earlier run: its winding's resistance "
                  "rises linearly over the record, R (1 + alpha t), scaled to a 25 sigma "
                  "signature (marginal): alpha 4.5e-4 1/s, +0.27 % over the 6 s; the head's "
                  "speed up to 0.18 rad/s lower late in the record, the current up to 22 mA "
                  "off"),
        spec("ad07", "catalog", "slow", False, (source_resistance(0.15, "slow"),),
             noise={"current": ADC_I, "speed": {"white": 0.2},
                    "load_speed": {"white": 0.1}},
             note="the control box is fed from the 36 V supply over a long, thin extension "
                  "lead: 0.15 Ohm inside the source. A person sees the rotor up to 17 rad/s "
                  "slower at 36 V (the head 11 rad/s) and the current up to 1.2 A off in the "
                  "transients; the current read by a 12-bit ADC"),
    ]


def pairs() -> list[dict[str, Any]]:
    """ad08-ad10: two catalog effects at once."""
    return [
        spec("ad08", "two", "fast", True,
             (series_resistance(0.05, "fast"), brush_drop(0.15)), note="the motor's terminal block has a loose screw (0.05 Ohm in series with "
                  "the armature) and its brushes were replaced by a harder grade with a contact "
                  "drop of 0.15 V: both take voltage from the armature, one in proportion to "
                  "the current, one constant. A person sees the rotor up to 9.4 rad/s slower "
                  "and the current up to 1.4 A off"),
        spec("ad09", "two", "slow", True, (coulomb_head(0.03), viscous_rotor(3e-5)),
             note="the rotary hook's race is under-oiled: a dry friction of 0.03 N m "
                  "more on the head (half the declared 0.06); and the motor's front bearing's "
                  "grease has stiffened in a cold workshop: a viscous friction of 3e-5 N m "
                  "s/rad more on the rotor (2.5 times the declared 2e-5). A person sees the "
                  "head up to 3.8 rad/s slower, the rotor 5.6, the current up to 0.42 A "
                  "higher"),
        spec("ad10", "two", "fast", False, (inertia_head(0.35), emf_harmonic(5, 1.5e-3, 0.8)),
             note="the owner fitted a heavier cast-iron handwheel: the head's inertia "
                  "is 35 % above the declared (a correction of Jh); and the motor's magnets are "
                  "unevenly magnetised: an EMF harmonic of order 5, slope 1.5e-3 V s/rad (2 % of "
                  "k), phase 0.8, voltage only. A person sees the starts and stops take longer "
                  "(the speed up to 37 rad/s off, the current up to 2.9 A) and a ripple at five "
                  "times the rotor's turn rate in the current (up to 0.16 A)"),
    ]


#: the speed converter's RC filter on the synchroniser's speed: (probe, tau [s])
LAG = ("load_speed", 3e-3)
#: the connector's tarnish film: a [V/A^0.5], the smoothing current eps [A]
FILM = (0.08, 0.05)
#: the bent rotor shaft: the air gap's modulation e [1] and its phase [rad]
ECC = (0.02, 0.7)
#: the dry needle-bar bushing: its cold friction [N m], its friction's growth [1/K], its
#: heat capacity [J/K] and its conductance to the head's casting [W/K]
BUSHING = (0.02, 0.05, 1.5, 0.05)


def outside_records() -> list[dict[str, Any]]:
    """ad11-ad14: effects the catalog does not contain."""
    return [
        spec("ad11", "outside", "slow", False, (outside(
            "synchroniser-rc-lag", {"lag": LAG},
            {"probe": LAG[0], "tau_s": LAG[1],
             "form": "load_speed reads yf, dyf/dt = (wh - yf)/tau from 0: a first-order "
                     "RC low-pass"}),), note="the handwheel synchroniser's pulses are turned into a speed by a "
                  "frequency-to-voltage converter whose RC output filter (3 ms) the declared "
                  "model lacks: the head's speed read smoothed and behind (a first-order lag, "
                  "not a delay). A person sees the head's speed up to 5.2 rad/s behind at the "
                  "starts and stops; the current and the motor's speed are unchanged"),
        spec("ad12", "outside", "fast", True, (outside(
            "tarnished-connector-film", {"film": FILM},
            {"a_V_per_sqrtA": FILM[0], "eps_A": FILM[1],
             "form": "the loop takes a i (i^2 + eps^2)^(-1/4), about a sqrt(|i|) sign(i)"}),),
            probes=("current",), noise={"current": ADC_I}, note="a bench log of the current alone (12-bit ADC): the motor's crimped "
                  "connector has tarnished, and its oxide film conducts like a varistor, a drop "
                  "growing with the square root of the current: 0.08 V at 1 A, 0.32 V at 16 A. "
                  "A person sees the current up to 0.5 A off the declared model's"),
        spec("ad13", "outside", "fast", False, (outside(
            "bent-rotor-shaft-airgap", {"ecc": ECC},
            {"e": ECC[0], "phase_rad": ECC[1],
             "form": "k(th) = k (1 + e sin(th + phase)) in the EMF and in the torque"}),),
            note="the motor's shaft was bent when the machine was dropped: the rotor runs "
                  "eccentric in its air gap, and the EMF and the torque constant swing by 2 % "
                  "once a turn, k (1 + 0.02 sin(angle + 0.7)). A person sees a ripple once per "
                  "rotor turn (up to 53 Hz) of up to 0.4 A in the current and 2.5 rad/s in the "
                  "speed"),
        spec("ad14", "outside", "slow", True, (outside(
            "dry-needle-bar-bushing", {"bushing": BUSHING},
            {"T0_Nm": BUSHING[0], "beta_per_K": BUSHING[1], "C_J_K": BUSHING[2],
             "G_W_K": BUSHING[3],
             "form": "the head takes -T0 (1 + beta dT) tanh(wh/0.01), C ddT/dt = T0 (1 + beta "
                     "dT) tanh(wh/0.01) wh - G dT from dT = 0: a friction heated by its own "
                     "loss"}),), note="the needle bar's bushing runs nearly dry: its friction, 0.02 N m cold, "
                  "grows by 5 % a kelvin as it heats from its own loss (1.5 J/K, 0.05 W/K to "
                  "the head's casting): 14 K and +70 % by the end of the second seam. A person "
                  "sees the head slow down along the seams, up to 2.6 rad/s lower (the rotor "
                  "3.8), and the current up to 0.29 A higher"),
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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 26, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:head", {"coul": {"head": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:head", {"visc": {"head": 1e-5}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:head", {"offset": {"head": 1e-3}}),
    ("backlash:K", {"gap": 1e-4}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:20", {"lsat": (20.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jh", {"p": {"Jh": P["Jh"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:head", lambda a, b: {"cog": {"head": [(1, a, b)]}}),
    ("cogging:rotor:12", lambda a, b: {"cog": {"rotor": [(12, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:5", lambda a, b: {"emf": [(5, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1 uV s/rad of EMF), 1 mN m on the head."""
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
