"""Generate the blind set ``fresh27`` of the diagnosis benchmark: records ae01-ae14 of motor AB
(a 24 V brushed DC motor turning a parts-finishing barrel tumbler's hexagonal barrel through a
rigid 80:1 helical gearhead and a jaw coupling whose spider is a compliance; the media bed's
dry lift torque and the slurry's drag), some sampled evenly and some UNEVENLY, three of them
giving the diagnosis ONE probe only, and merge their truth into truth.json. The ids have two
letters.

    python benchmarks/diagnosis/make_records_ab.py                # records/ae*.csv + truth.json
    python benchmarks/diagnosis/make_records_ab.py --only ae03,ae12
    python benchmarks/diagnosis/make_records_ab.py --truth-only   # rewrite the ae entries only

Uses simulators_ab.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_ab_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the catalog imprints it is compared with are computed on that probe
alone (``OneProbe``). Even records are sampled on the regime's grid k/fs; uneven ones, in the
fast regime, on a 25 kHz grid whose every sample is moved by a random jitter of up to 10-30 %
of the interval, and in the slow regime at a logger's irregular intervals (0.6-1.4 times the
mean of 2 ms) with a few samples dropped. Each uneven record has its own times (from its
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
import simulators_ab as sb

RECORDS = HERE / "records"
SPLIT = "fresh27"
MOTOR = "AB"
SEED0 = 27500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_ab_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_ab_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.02, "speed": 0.15},
         "slow": {"current": 0.02, "speed": 0.15, "load_speed": 0.01}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sb.MOTOR_AB
N = P["N"]
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_ab, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearhead is rigid and lossless as declared: a torque
# on the body ``hub`` is 1/N = 1/80 of it on the rotor, and the hub turns with the rotor. The
# barrel lies behind the spider (compliant): an effect on it has no exact equal on the rotor.

def harmonic(effect: str, body: str, order: int, amp: float, phase: float) -> Part:
    """An angle-locked torque amp sin(order angle + phase) [N m] on ``body`` (the catalog's
    cogging or, at order 1, unbalance)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    entry = {"effect": effect, "target": body, "targets": [body], "order": order,
             "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                            "form": f"{body} receives T sin({order} angle + phase)"},
             "expected": {"a": a, "b": b}}
    if effect == "unbalance":
        entry["also_accept"] = [{"effect": "cogging", "targets": [body], "order": 1,
                                 "expected": {"a": a, "b": b}}]
    return {"cog": {body: [(order, a, b)]}}, entry


def stribeck_barrel(s: float, ws: float) -> Part:
    """A breakaway peak s exp(-(wb/ws)^2) tanh(wb/0.01) [N m] over the barrel's declared
    friction, ``ws`` [rad/s]."""
    return {"stribeck": {"barrel": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "barrel", "targets": ["barrel"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "barrel takes s exp(-(w/ws)^2) tanh(w/0.01) over the declared "
                               "Tl tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad] in the spider K."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap, "play_deg": math.degrees(gap),
                       "form": "no spider torque while |twist| < gap/2, Kc (twist -+ gap/2) "
                               "+ Dc w_rel in contact, the damping never pulling"},
        "expected": {"gap": gap}}


def viscous_barrel(b: float) -> Part:
    """An extra viscous friction ``b`` [N m s/rad] on the barrel."""
    return {"visc": {"barrel": b}}, {
        "effect": "viscous-friction", "target": "barrel", "targets": ["barrel"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b wb against the barrel"},
        "expected": {"b": b}}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF harmonic w slope sin(order th + phase) [V], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def coulomb_rotor(c: float) -> Part:
    """An extra dry friction c tanh(w / 0.01) [N m] on the rotor (accepted on the hub at
    c N)."""
    return {"coul": {"rotor": c}}, {
        "effect": "coulomb-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(w/0.01) against the rotor"},
        "expected": {"c": c},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["hub"],
                         "expected": {"c": c * N}}]}


def inertia_barrel(dj: float) -> Part:
    """The barrel's inertia off by a factor 1 + ``dj`` (a correction of Jb's J)."""
    return {"p": {"Jb": P["Jb"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jb", "targets": ["Jb"], "correction": True,
        "parameters": {"Jb_true_kgm2": P["Jb"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AB's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sb.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sb.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the controller's current sense: a 12-bit ADC over +-20 A (9.77 mA steps)
ADC_STEP = 40.0 / 4096
#: the flat-spotted support roller turns 330 / 70 times a barrel turn
ROLLER_ORDER = round(330.0 / 70.0, 4)


def nulls() -> list[dict[str, Any]]:
    """ae01, ae02: the null records."""
    return [
        spec("ae01", "null", "slow", True,
             noise={"current": {"white": 0.01, "ar1": [0.03, 0.9], "quant": ADC_STEP},
                    "speed": {"white": 0.15, "pink": 0.5},
                    "load_speed": {"white": 0.01}},
             note="the tumbler controller's log on its irregular clock; the current with "
                  "Gauss-Markov noise (correlation 0.9 over the mean interval, 0.03 A) on "
                  "white noise, read by its 12-bit ADC (9.77 mA steps); the encoder speed "
                  "with 1/f noise (white noise shaped by 1/sqrt(f), 0.5 rad/s) on white "
                  "noise; the barrel pickup's speed with white noise"),
        spec("ae02", "null", "fast", False, probes=("speed",),
             note="a bench log of the motor encoder's speed alone, white noise"),
    ]


def singles() -> list[dict[str, Any]]:
    """ae03-ae07: one catalog effect each."""
    return [
        spec("ae03", "catalog", "slow", False, (harmonic("unbalance", "barrel", 1, 0.4, 0.6),),
             note="a lump of wet media and parts (about 0.5 kg) has packed into one corner "
                  "of the hexagonal barrel, 80 mm off its axis: an unbalance of 0.4 N m on "
                  "the barrel, sin(angle + 0.6), once per barrel turn. A person sees a slow "
                  "swing once a barrel turn of up to 0.09 A in the current, 1.6 rad/s in the "
                  "motor's speed and 0.03 rad/s in the barrel's"),
        spec("ae04", "catalog", "slow", True, (harmonic("cogging", "barrel", 6, 0.1, -0.3),),
             marginal=lambda a: (harmonic("cogging", "barrel", 6, a, -0.3),), size=0.1,
             note="the media bed slides over each of the hexagonal barrel's six flats in turn: "
                  "a load-torque ripple locked to the barrel's angle at order 6 (a cogging "
                  "of the barrel in the catalog's terms), sin(6 angle - 0.3), scaled to a "
                  "25 sigma signature (marginal): about 26 mN m, a ripple at six times the "
                  "barrel's turn rate of up to 0.12 rad/s in the motor's speed"),
        spec("ae05", "catalog", "fast", False, (sensor("current", "offset", 0.04),),
             probes=("current",),
             note="a bench log of the current alone; the controller's Hall-effect current "
                  "sensor has drifted off its zero: a sensor offset of 40 mA on the current"),
        spec("ae06", "catalog", "slow", False, (stribeck_barrel(0.5, 0.3),),
             marginal=lambda s: (stribeck_barrel(s, 0.3),), size=0.5,
             note="the media bed's static angle of repose exceeds its sliding one: the barrel "
                  "breaks away with a Stribeck peak over its declared dry torque, s "
                  "exp(-(wb/0.3)^2) tanh(wb/0.01), scaled to a 25 sigma signature (marginal): "
                  "about 0.18 N m (7 % of the declared 2.5 N m); visible only as the barrel "
                  "starts and reverses, up to 0.6 rad/s in the motor's speed"),
        spec("ae07", "catalog", "slow", False, (sensor("load_speed", "gain", 0.9375),),
             note="the barrel's pickup ring was replaced by one of 64 teeth, but the "
                  "controller still divides by 60: the barrel's speed reads 60/64 = 0.9375 "
                  "of the truth, up to 0.35 rad/s low at full speed; the current and the "
                  "motor's speed are unchanged"),
    ]


def pairs() -> list[dict[str, Any]]:
    """ae08-ae10: two catalog effects at once."""
    return [
        spec("ae08", "two", "slow", True, (backlash(0.04), viscous_barrel(0.12)),
             note="the jaw coupling's polyurethane spider is worn: a play of 0.04 rad (2.3 "
                  "degrees) in the coupling; and the batch was run with a thicker compound: "
                  "a viscous drag of 0.12 N m s/rad more on the barrel (40 % above the "
                  "declared 0.3). A person sees the barrel up to 0.65 rad/s slower, a knock "
                  "in the motor's speed (up to 18 rad/s) where the coupling's sides part and "
                  "meet again at the stop and the reversal, and the current up to 1 A off"),
        spec("ae09", "two", "fast", True,
             (emf_harmonic(9, 1.2e-3, -0.5), sensor("speed", "gain", 0.9766)),
             note="the motor's magnets are unevenly magnetised: an EMF harmonic of order 9 "
                  "(the 9-slot armature), slope 1.2e-3 V s/rad (2.3 % of k), phase -0.5, "
                  "voltage only; and the controller assumes a 512-line encoder where the "
                  "motor has 500 lines: a sensor gain of 500/512 = 0.9766 on the speed. A "
                  "person sees the speed up to 10 rad/s low at full speed and a ripple at "
                  "nine times the rotor's turn rate in the current (up to 0.12 A)"),
        spec("ae10", "two", "fast", False, (coulomb_rotor(0.012), inertia_barrel(0.3)),
             note="the motor's spring-applied holding brake does not fully release: a dry "
                  "drag of 12 mN m more on the rotor (twice the brushes' declared 6); and the "
                  "barrel was overfilled with media: its inertia is 30 % above the declared "
                  "(a correction of Jb). A person sees the current up to 1.7 A off and the "
                  "speed up to 30 rad/s off, the barrel's ringing on the coupling slower"),
    ]


#: the shear-thinning compound: c [N m (s/rad)^n], n [1], eps [rad/s]
SHEAR = (0.27, 0.5, 0.05)
#: the flat-spotted support roller: its torque's amplitude [N m], order [1], phase [rad]
ROLLER = (0.25, ROLLER_ORDER, 1.1)
#: the lossy EMI choke in the motor lead: Lc [H], its core loss as a parallel Rp [ohm]
CHOKE = (4e-4, 1.5)
#: the spider's viscoelastic relaxation: a Maxwell branch K2 [N m/rad], D2 [N m s/rad]
SPIDER = (300.0, 3.0)


def outside_records() -> list[dict[str, Any]]:
    """ae11-ae14: effects the catalog does not contain."""
    return [
        spec("ae11", "outside", "slow", True, (outside(
            "shear-thinning-compound", {"shear": SHEAR},
            {"c_Nm_per_sqrt_rad_s": SHEAR[0], "n": SHEAR[1], "eps_rad_s": SHEAR[2],
             "form": "the barrel takes -c wb (wb^2 + eps^2)^((n - 1)/2), about c "
                     "sqrt(|wb|) sign(wb): a power-law (shear-thinning) slurry's drag"}),),
            note="a new burnishing compound mixed too rich makes a shear-thinning slurry: its "
                 "drag on the barrel grows with the square root of the barrel's speed, "
                 "neither a constant dry torque nor a viscous one: 0.27 N m at 1 rad/s, 0.6 "
                 "N m at full speed. A person sees the motor up to 2.6 rad/s slower, the "
                 "barrel up to 0.03 rad/s, and the current up to 0.15 A higher"),
        spec("ae12", "outside", "slow", False, (outside(
            "flat-spotted-support-roller", {"roller": ROLLER},
            {"T_Nm": ROLLER[0], "order": ROLLER[1], "phase_rad": ROLLER[2],
             "form": "the barrel receives T sin(order thb + phase), order = 330/70 = "
                     "4.7143: a torque locked to a support roller's angle, not the "
                     "barrel's"}),),
            note="the barrel's far end rides on two 70 mm support rollers on a 330 mm track; "
                 "one roller's polyurethane tyre has a flat spot from standing under the "
                 "loaded barrel: a torque of 0.25 N m (its fundamental) on the barrel at "
                 "4.714 times the barrel's turn rate, locked to the roller's angle, at no "
                 "whole order of the barrel's. A person sees a ripple of up to 0.07 A in the "
                 "current, 1.2 rad/s in the motor's speed and 0.026 rad/s in the barrel's"),
        spec("ae13", "outside", "fast", True, (outside(
            "lossy-emi-choke", {"choke": CHOKE},
            {"Lc_H": CHOKE[0], "Rp_ohm": CHOKE[1],
             "form": "an inductance Lc in parallel with a resistance Rp, in series with "
                     "the armature: Lc dic/dt = Rp (i - ic), the loop takes Rp (i - ic)"}),),
            probes=("current",), noise={"current": {"white": 0.02, "quant": ADC_STEP}},
            note="a bench log of the current alone (12-bit ADC): an EMI suppression choke "
                 "was fitted in the motor lead for a compliance test; its ferrite core is "
                 "lossy: 0.4 mH in parallel with 1.5 Ohm (corner 600 Hz), added inductance "
                 "for slow changes, a resistance for fast ones. A person sees the current up "
                 "to 1.7 A off the declared model's at the steps"),
        spec("ae14", "outside", "fast", False, (outside(
            "viscoelastic-spider", {"spider": SPIDER},
            {"K2_Nm_rad": SPIDER[0], "D2_Nms_rad": SPIDER[1],
             "form": "a Maxwell branch across the coupling: the spider's torque gains K2 x, "
                     "dx/dt = (w/N - wb) - K2 x / D2 from 0 (relaxation time D2/K2 = 10 "
                     "ms)"}),),
            note="the jaw coupling was refitted with a softer, more damping grade of spider "
                 "whose polyurethane relaxes: besides its declared stiffness and damping, a "
                 "spring of 300 N m/rad in series with a damper of 3 N m s/rad (a 10 ms "
                 "relaxation), so that the spider is stiffer and more damped at the barrel's "
                 "ringing than at rest. A person sees the barrel's ringing on the coupling "
                 "faster and damped sooner, the speed up to 18 rad/s and the current up to "
                 "1 A off"),
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
    return recordkit.record_times(s, sb.REGIMES, sb.grid, 27, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:barrel", {"coul": {"barrel": 1e-2}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:barrel", {"visc": {"barrel": 1e-3}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:barrel", {"offset": {"barrel": 1e-2}}),
    ("stribeck-friction:barrel", {"stribeck": {"barrel": (1e-2, 0.5)}}),
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
    ("unbalance:barrel", lambda a, b: {"cog": {"barrel": [(1, a, b)]}}),
    ("cogging:barrel:5", lambda a, b: {"cog": {"barrel": [(5, a, b)]}}),
    ("cogging:barrel:6", lambda a, b: {"cog": {"barrel": [(6, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:9", lambda a, b: {"emf": [(9, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1 uV s/rad of EMF), 10 mN m on the barrel."""
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


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term
KIT = OneProbe(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sb, sim=sim,
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
