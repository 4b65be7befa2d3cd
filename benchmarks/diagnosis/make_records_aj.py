"""Generate the blind set ``fresh35`` of the diagnosis benchmark: records am01-am14 of motor AJ
(a 24 V brushed DC motor in an observatory dome's rotation drive: a rigid 60:1 worm gearbox,
a polyurethane-tyred friction drive wheel's compliance to the dome's base ring, the dome on
its rollers meeting the bearings' drag, the rollers' rolling resistance and the weather
skirt's soft brush drag), some sampled evenly and some UNEVENLY, three of them giving the
diagnosis ONE probe only, and merge their truth into truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_aj.py                # records/am*.csv + truth.json
    python benchmarks/diagnosis/make_records_aj.py --only am03,am12
    python benchmarks/diagnosis/make_records_aj.py --truth-only   # rewrite the am entries only

Uses simulators_aj.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_aj_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the catalog imprints it is compared with are computed on that probe
alone (``OneProbe``). Even records are sampled on the regime's grid k/fs; uneven ones, in the
fast regime, on a 20 kHz grid whose every sample is moved by a random jitter of up to 10-30 %
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
import simulators_aj as sa

RECORDS = HERE / "records"
SPLIT = "fresh35"
MOTOR = "AJ"
SEED0 = 35500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_aj_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_aj_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.05, "speed": 1.0},
         "slow": {"current": 0.04, "speed": 0.8, "load_speed": 0.02}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AJ
N = P["N"]
#: [m] the drive wheel's radius: the dome's reflected angle is the ring's travel over it
R_WHEEL = 0.04
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_aj, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The worm gearbox is rigid and lossless as declared: a
# torque on the body ``hub`` (the gearbox's output and the drive wheel) is 1/N = 1/60 of it on
# the rotor, and the wheel turns with the rotor. The dome lies behind the tyre (compliant,
# 1:1 in its reflected frame): an effect on it has no exact equal on the wheel.

def source_resistance(r: float, regime: str) -> Part:
    """A resistance ``r`` [ohm] inside the source (the supply's leads, fuse and slip ring)."""
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


def drift(alpha: float) -> Part:
    """The winding's resistance rising linearly, R (1 + alpha t) [1/s]."""
    return {"alpha": alpha}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + alpha*t)", "alpha_per_s": alpha},
        "expected": {"alpha": alpha}}


def inductance(dl: float) -> Part:
    """The armature's inductance off by a factor 1 + ``dl`` (a correction of La's L)."""
    return {"p": {"L": P["L"] * (1.0 + dl)}}, {
        "effect": "inductance", "target": "La", "targets": ["La"], "correction": True,
        "parameters": {"L_true_H": P["L"] * (1.0 + dl), "dL": dl},
        "expected": {"dL": dl}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def cogging_rotor(order: int, amp: float, phase: float) -> Part:
    """A detent torque amp sin(order th + phase) [N m] on the rotor (accepted on the wheel
    at the order order N and the amplitude amp N)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["hub"], "order": round(order * N),
                         "expected": {"a": a * N, "b": b * N}}]}


def stribeck_dome(s: float, ws: float) -> Part:
    """A breakaway peak s exp(-(wd/ws)^2) tanh(wd/0.01) [N m] over the dome's declared rolling
    resistance, ``ws`` [rad/s] (behind the tyre)."""
    return {"stribeck": {"dome": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "dome", "targets": ["dome"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "dome takes s exp(-(w/ws)^2) tanh(w/0.01) over the declared "
                               "Td tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def offset_dome(f: float) -> Part:
    """A constant torque ``f`` [N m] on the dome (behind the tyre; f < 0: turning it
    anticlockwise)."""
    return {"offset": {"dome": f}}, {
        "effect": "force-offset", "target": "dome", "targets": ["dome"],
        "parameters": {"T_Nm": f, "F_N": f / R_WHEEL,
                       "form": "the dome receives a constant T (T < 0: turning it "
                               "anticlockwise); F the force on the ring"},
        "expected": {"F": f}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AJ's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sa.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sa.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the controller's current sense: a 10-bit ADC over +-50 A (97.7 mA steps)
ADC_STEP = 100.0 / 1024
#: the motor encoder's speed from an edge count: its resolution [rad/s]
SPEED_STEP = 0.5


def nulls() -> list[dict[str, Any]]:
    """am01, am02: the null records."""
    return [
        spec("am01", "null", "slow", True,
             noise={"current": {"white": 0.02, "ar1": [0.05, 0.8], "quant": ADC_STEP},
                    "speed": {"white": 0.6, "quant": SPEED_STEP},
                    "load_speed": {"white": 0.01, "ar1": [0.02, 0.9]}},
             note="the observatory's data logger's irregular record; the current with "
                  "Gauss-Markov noise (correlation 0.8 over the interval, 50 mA: the PWM "
                  "ripple through the sense amplifier) on white noise, read by the "
                  "controller's 10-bit ADC (98 mA steps); the encoder's speed with white "
                  "noise, read to 0.5 rad/s; the ring encoder's speed with Gauss-Markov "
                  "noise (correlation 0.9, 0.02 rad/s: its wheel rolling over the ring's "
                  "joints and grit) on white noise"),
        spec("am02", "null", "fast", False, probes=("current",),
             noise={"current": {"white": 0.04, "pink": 0.06}},
             note="a bench log of the current alone, an even 20 kHz record; the current with "
                  "the sense amplifier's 1/f noise (60 mA) on white noise"),
    ]


def singles() -> list[dict[str, Any]]:
    """am03-am07, am10: one catalog effect each."""
    return [
        spec("am03", "catalog", "fast", True, (saturation(10.0, 0.4),),
             note="a replacement motor of another make with a small, highly loaded iron "
                  "circuit: its armature inductance saturates, La (0.4 + 0.6/(1 + (i/10 A)^2)), "
                  "so the soft start's and the reversal's currents (above 20 A) rise and fall "
                  "faster than declared"),
        spec("am04", "catalog", "slow", False, (offset_dome(-0.3),),
             marginal=lambda f: (offset_dome(f),), size=-0.3,
             note="the shutter was open and a steady breeze presses on the slit, turning the "
                  "dome anticlockwise: a constant torque on the dome (reflected to the drive "
                  "wheel), scaled to a 25 sigma signature (marginal)"),
        spec("am05", "catalog", "fast", False, (cogging_rotor(6, 0.015, 0.7),),
             note="a replacement motor with stronger neodymium magnets and a 6-slot "
                  "armature without skew: a detent torque of 0.015 N m, 6 periods a turn of "
                  "the rotor, phase 0.7 rad"),
        spec("am06", "catalog", "slow", True, (stribeck_dome(2.0, 0.4),),
             note="the support rollers' bearings have rusted over the winter (the dome stood "
                  "unturned for months): a breakaway of 2 N m (reflected to the wheel) over "
                  "the declared rolling resistance, fading by 0.4 rad/s of the dome"),
        spec("am07", "catalog", "fast", False, (source_resistance(0.2, "fast"),),
             probes=("current",), noise={"current": {"white": 0.05, "quant": ADC_STEP}},
             note="a bench log of the current alone (the controller's 10-bit ADC); the supply "
                  "reaches the motor through the dome's slip ring and 20 m of thin cable: "
                  "0.2 Ohm inside the source"),
        spec("am10", "catalog", "fast", True, (sensor("speed", "delay", 2e-4),),
             marginal=lambda d: (sensor("speed", "delay", d),), size=2e-4,
             probes=("speed",),
             note="a bench log of the encoder's speed alone; the speed is computed by the "
                  "controller's firmware from a window of encoder edges and comes late: a "
                  "delay of the speed, scaled to a 25 sigma signature (marginal)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """am08, am09: two catalog effects at once."""
    return [
        spec("am08", "two", "slow", True, (drift(0.04), sensor("load_speed", "gain", 1.06)),
             note="a cold winter night: the motor was heated by a previous long slew and its "
                  "winding's resistance is still climbing through the record, R (1 + 0.04 t) "
                  "(24 % above the declared by 6 s); and the ring encoder's rubber wheel has "
                  "worn to a smaller radius: the dome's speed reads 6 % high"),
        spec("am09", "two", "fast", False, (inductance(0.6), sensor("current", "gain", 0.95)),
             note="the motor's datasheet inductance was measured at 1 kHz with the rotor "
                  "free; the winding's true inductance is 60 % above the declared "
                  "(dL = 0.6); and the current-sense amplifier's gain resistor has drifted: "
                  "the current reads 5 % low"),
    ]


#: the ice patch on the ring: extra drag F [N m], from a to b [rad] (the dome's angle
#: reflected to the wheel), edge d [rad]
ICE = (3.0, 6.0, 9.0, 0.3)
#: the shutter's charging contacts at home: stiffness Kh [N m/rad], half-width wh [rad]
DETENT = (6.0, 1.2)
#: the lead-acid bank's polarisation: Rp [ohm], Cp [F] (60 ms)
BATTERY = (0.15, 0.4)
#: the ring's splice plate: the energy E [J] of the wheel's climb, at a [rad], width wd [rad]
SPLICE = (2.0, 0.9, 0.06)


def outside_records() -> list[dict[str, Any]]:
    """am11-am14: effects the catalog does not contain."""
    return outside_slow() + outside_fast()


def outside_slow() -> list[dict[str, Any]]:
    """am11, am13: the ice patch on the ring and the home position's contacts (slow)."""
    return [
        spec("am11", "outside", "slow", True, (outside(
            "ice-patch-on-base-ring", {"ice": ICE},
            {"F_Nm": ICE[0], "a_rad": ICE[1], "b_rad": ICE[2], "d_rad": ICE[3],
             "form": "the dome receives -F s((thd - a)/d) s((b - thd)/d) tanh(wd/0.01), "
                     "s(x) = 1/(1 + exp(-x)): melt water froze on the base ring between the "
                     "dome's angles a and b (reflected to the wheel: 1 rad = 40 mm of the "
                     "ring), and the rollers and the wheel drag more over it"}),),
            note="melt water from the dome's seams froze on one stretch of the base ring, "
                 "120 mm long (6 to 9 rad of the dome reflected to the wheel, 9.2 to 13.8 "
                 "degrees from home): over it the rollers and the drive wheel drag 3 N m "
                 "more; a person sees the slew out as declared until about 1.45 s, then the "
                 "current rising from 2.1 A to 3.0 A and the motor slowing from 415 to "
                 "407 rad/s for about 0.45 s, then as declared again; on the way back the same "
                 "from about 4.5 s to 5.0 s; close to a change of the rolling resistance, but "
                 "only over one stretch of the dome's angle, both ways"),
        spec("am13", "outside", "slow", False, (outside(
            "home-position-charging-contacts", {"detent": DETENT},
            {"Kh_Nm_per_rad": DETENT[0], "wh_rad": DETENT[1],
             "form": "the dome receives -Kh thd exp(-(thd/wh)^2): at the home position (where "
                     "the record starts, thd = 0) the shutter's battery-charging contacts, "
                     "sprung wipers on the ring, hold the dome in a detent that pulls it back "
                     "home, strongest at wh/sqrt(2) either side and gone a few wh away"}),),
            note="the shutter's battery is charged through sprung contacts that meet at the "
                 "home position, where the record starts; their wipers pull the dome back "
                 "towards home (up to 3.1 N m, 0.85 rad either side, reflected to the wheel); "
                 "a person sees the soft start as declared at first, then the current higher "
                 "(8.1 A instead of 7.2 A at 0.8 s) and the motor slower (355 instead of "
                 "364 rad/s) while the dome leaves home, then as declared; on the way back "
                 "the dome's last stop near home (at 1.9 rad) pulled further in; close to a "
                 "spring or an offset on the dome, but only near the start's angle"),
    ]


def outside_fast() -> list[dict[str, Any]]:
    """am12, am14: the battery bank's polarisation and the ring's splice plate (fast)."""
    return [
        spec("am12", "outside", "fast", False, (outside(
            "battery-bank-polarisation", {"battery": BATTERY},
            {"Rp_ohm": BATTERY[0], "Cp_F": BATTERY[1],
             "tau_s": BATTERY[0] * BATTERY[1],
             "form": "the loop takes vp, dvp/dt = i/Cp - vp/(Rp Cp), vp(0) = 0: the off-grid "
                     "observatory's 24 V lead-acid bank's polarisation (an R-C pair in series "
                     "with its terminal), its voltage sagging behind the current drawn over "
                     "tau = Rp Cp and recovering after"}),),
            noise={"current": {"white": 0.03, "ar1": [0.06, 0.7], "quant": ADC_STEP},
                   "speed": {"white": 1.0}},
            note="a bench acquisition of the current (the controller's 10-bit ADC, the PWM "
                 "ripple as Gauss-Markov noise, correlation 0.7 over the interval, 60 mA, on "
                 "white noise) and the encoder's speed; the observatory runs off a solar-charged 24 V lead-acid bank "
                 "whose polarisation (0.15 Ohm behind 0.4 F, 60 ms) sags the supply after "
                 "every surge of current: a person sees the soft start's inrush lower "
                 "(21.5 A instead of 23.3 A), the running current settling higher (3.6 A "
                 "instead of 2.7 A at 0.3 s, the motor slower: 385 instead of 410 rad/s), the soft stop's braking "
                 "smaller (-18.1 instead of -20.2 A) and the reversal's current smaller; "
                 "close to a resistance in the source, but one that lags the current by "
                 "60 ms"),
        spec("am14", "outside", "fast", True, (outside(
            "base-ring-splice-bump", {"splice": SPLICE},
            {"E_J": SPLICE[0], "a_rad": SPLICE[1], "wd_rad": SPLICE[2],
             "form": "the dome receives -dU/dthd, U = E exp(-((thd - a)/wd)^2): "
                     "2 E (thd - a)/wd^2 exp(-((thd - a)/wd)^2); the base ring's splice "
                     "plate stands proud at the dome's angle a (reflected to the wheel: "
                     "1 rad = 40 mm of the ring), and the sprung drive wheel climbs over it "
                     "(its bracket's spring storing E) and drops off it (giving E back)"}),),
            noise={"current": {"white": 0.05}, "speed": {"white": 1.0, "pink": 1.5}},
            note="the base ring is rolled in segments bolted together with splice plates; one "
                 "plate stands proud, 0.9 rad (36 mm of the ring) from where the record "
                 "starts, and the sprung drive wheel climbs over it and drops off it (2 J, "
                 "over about 0.06 rad: up to 24 N m against and then with the dome, "
                 "reflected to the wheel); the speed column carries 1/f noise (1.5 rad/s) on "
                 "white noise; a person sees the start and the slew as declared until about "
                 "0.25 s, then a kick as the wheel crosses it (the current 3.4 A instead of "
                 "2.8 A at 0.278 s, the motor 402 instead of 409 rad/s at 0.276 s) and a "
                 "ringing of the wheel against the dome on the tyre after it, the rest close "
                 "to declared (the dome does not come back over it); close to a cogging or an "
                 "unbalance of the dome, but one kick at one angle, not a periodic torque"),
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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 35, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:hub", {"coul": {"hub": 1e-2}}),
    ("coulomb-friction:dome", {"coul": {"dome": 1e-2}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:dome", {"visc": {"dome": 1e-3}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:dome", {"offset": {"dome": 1e-2}}),
    ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-4, 10.0)}}),
    ("stribeck-friction:dome", {"stribeck": {"dome": (1e-2, 0.5)}}),
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
    ("unbalance:dome", lambda a, b: {"cog": {"dome": [(1, a, b)]}}),
    ("cogging:rotor:6", lambda a, b: {"cog": {"rotor": [(6, a, b)]}}),
    ("cogging:dome:2", lambda a, b: {"cog": {"dome": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:6", lambda a, b: {"emf": [(6, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1 uV s/rad of EMF), 10 mN m on the dome."""
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

    def scale_marginal(self, s: dict[str, Any]) -> None:
        """Scale a marginal record's size so that its best probe's signature is the set's
        marginal size on its own times: recordkit's proportional passes, repeated (up to
        eight) until within 1 % of it (a breakaway's imprint is not linear in its size)."""
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


#: across the tyre (a spring and a damper, 1:1): the body an effect on each is compared
#: with, and the factor its size takes there per kind (the wheel and the dome, reflected to
#: it, turn at one mean speed)
ACROSS = {"dome": ("hub", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0}),
          "hub": ("dome", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` across the tyre
    (``recordkit.location_entry``), after a marginal record's scaling."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term of the catalog's kinds (the skirt's soft dry drag is a behavioural
#: torque of the declared model)
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
