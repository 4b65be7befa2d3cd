"""Generate the blind set ``fresh29`` of the diagnosis benchmark: records ag01-ag14 of motor AD
(a 24 V brushed DC motor stirring a mixing tank: a rigid 10:1 planetary gearhead and a slender
stainless shaft, 1 m long, a torsional compliance, to a pitched-blade impeller; the impeller's
turbulent drag, the bottom steady bush's dry friction), some sampled evenly and some UNEVENLY,
three of them giving the diagnosis ONE probe only, and merge their truth into truth.json. The
ids have two letters.

    python benchmarks/diagnosis/make_records_ad.py                # records/ag*.csv + truth.json
    python benchmarks/diagnosis/make_records_ad.py --only ag03,ag12
    python benchmarks/diagnosis/make_records_ad.py --truth-only   # rewrite the ag entries only

Uses simulators_ad.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_ad_slow.yaml's pwl states). A single-probe record (truth's
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
import simulators_ad as sa

RECORDS = HERE / "records"
SPLIT = "fresh29"
MOTOR = "AD"
SEED0 = 29500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_ad_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_ad_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.03, "speed": 0.5},
         "slow": {"current": 0.02, "speed": 0.4, "load_speed": 0.08}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AD
N = P["N"]
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_ad, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearhead is rigid and lossless as declared: a torque
# on the body ``hub`` is 1/N = 1/10 of it on the rotor, and the hub turns with the rotor. The
# impeller lies behind the shaft (compliant): an effect on it has no exact equal on the rotor.

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


def warmup(rise: float, tau: float) -> Part:
    """The winding warming: R (1 + rise (1 - exp(-t / tau)))."""
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


def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad] in the shaft K."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap, "play_deg": math.degrees(gap),
                       "form": "no shaft torque while |twist| < gap/2, Kc (twist -+ gap/2) "
                               "+ Dc w_rel in contact, the damping never pulling"},
        "expected": {"gap": gap}}


def inertia_impeller(dj: float) -> Part:
    """The impeller's inertia off by a factor 1 + ``dj`` (a correction of Ji's J)."""
    return {"p": {"Ji": P["Ji"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Ji", "targets": ["Ji"], "correction": True,
        "parameters": {"Ji_true_kgm2": P["Ji"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


def coulomb_impeller(c: float) -> Part:
    """An extra dry friction c tanh(wi / 0.01) [N m] on the impeller (behind the shaft)."""
    return {"coul": {"impeller": c}}, {
        "effect": "coulomb-friction", "target": "impeller", "targets": ["impeller"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(wi/0.01) against the impeller"},
        "expected": {"c": c}}


def stribeck_impeller(s: float, ws: float) -> Part:
    """A breakaway peak s exp(-(wi/ws)^2) tanh(wi/0.01) [N m] over the impeller's declared
    dry friction, ``ws`` [rad/s]."""
    return {"stribeck": {"impeller": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "impeller", "targets": ["impeller"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "impeller takes s exp(-(w/ws)^2) tanh(w/0.01) over the "
                               "declared Tl tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def cogging_rotor(order: int, amp: float, phase: float) -> Part:
    """A detent torque amp sin(order th + phase) [N m] on the rotor (accepted on the hub at
    the order order N and the amplitude amp N)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["hub"], "order": round(order * N),
                         "expected": {"a": a * N, "b": b * N}}]}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AD's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sa.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sa.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the drive's current sense: a 12-bit ADC over +-40 A (19.5 mA steps)
ADC_STEP = 80.0 / 4096


def nulls() -> list[dict[str, Any]]:
    """ag01, ag02: the null records."""
    return [
        spec("ag01", "null", "slow", True,
             noise={"current": {"white": 0.01, "ar1": [0.03, 0.85], "quant": ADC_STEP},
                    "speed": {"white": 0.4, "pink": 1.0},
                    "load_speed": {"white": 0.08}},
             note="the agitator drive's log on its irregular clock; the current with "
                  "Gauss-Markov noise (correlation 0.85 over the mean interval, 30 mA) on "
                  "white noise, read by its 12-bit ADC (19.5 mA steps); the encoder speed "
                  "with 1/f noise (white noise shaped by 1/sqrt(f), 1 rad/s) on white noise; "
                  "the impeller's blade-pass speed with white noise"),
        spec("ag02", "null", "fast", False,
             note="a commissioning log of the current and the motor encoder's speed, white "
                  "noise"),
    ]


def singles() -> list[dict[str, Any]]:
    """ag03-ag07, ag10: one catalog effect each."""
    return [
        spec("ag03", "catalog", "fast", True, (inertia_impeller(0.4),),
             note="the impeller was replaced by a cast stainless one of the same blades "
                  "with a heavier hub: the impeller's inertia is 40 % above the declared "
                  "4e-3 kg m^2 (a correction of Ji); its drag is unchanged"),
        spec("ag04", "catalog", "slow", False, (coulomb_impeller(0.05),),
             marginal=lambda c: (coulomb_impeller(c),), size=0.05,
             note="the bottom steady bush's PTFE liner has worn and the shaft's end rubs on "
                  "its steel sleeve: a dry friction c tanh(wi/0.01) more against the "
                  "impeller, scaled to a 25 sigma signature (marginal)"),
        spec("ag05", "catalog", "fast", False, (cogging_rotor(6, 5e-3, 0.4),),
             marginal=lambda a: (cogging_rotor(6, a, 0.4),), size=5e-3,
             probes=("speed",),
             note="a bench log of the motor encoder's speed alone; a replacement motor "
                  "with unskewed slots: a detent torque of order 6 (6 slots, 2 poles) on "
                  "the rotor, phase 0.4, scaled to a 25 sigma signature (marginal)"),
        spec("ag06", "catalog", "slow", True, (warmup(0.2, 3.0),),
             note="a thick batch and a hot plant room: the small motor's winding, started "
                  "cold, warms quickly through the log (the copper's own time constant, "
                  "before the frame heats): its resistance rises by 20 % towards a plateau "
                  "with a 3 s time constant"),
        spec("ag07", "catalog", "fast", True, (series_resistance(0.3, "fast"),),
             probes=("current",),
             note="a bench log of the current alone; the motor lead's crimp at the terminal "
                  "block has corroded in the dairy's wash-down: 0.3 Ohm in series with the "
                  "armature"),
        spec("ag10", "catalog", "slow", False, (sensor("current", "offset", 0.15),),
             note="the drive's Hall current sensor has lost its zero after a power cycle "
                  "at a warm cabinet: an offset of 0.15 A on the current"),
    ]


def pairs() -> list[dict[str, Any]]:
    """ag08, ag09: two catalog effects at once."""
    return [
        spec("ag08", "two", "slow", True, (stribeck_impeller(0.4, 2.0),
                                           sensor("load_speed", "gain", 0.96)),
             note="solids settled around the impeller over the weekend: a breakaway torque "
                  "s exp(-(wi/ws)^2) tanh(wi/0.01) on the impeller, s 0.4 N m, ws 2 rad/s, "
                  "over its declared dry friction; and the blade-pass pickup's scaling was "
                  "entered wrongly: a sensor gain of 0.96 on load_speed"),
        spec("ag09", "two", "fast", False, (backlash(0.05), brush_drop(0.5)),
             note="the shaft's keyed coupling to the gearhead has worn: a play of 0.05 rad "
                  "(2.9 degrees) in the shaft; and the motor's brushes are glazed: a contact "
                  "drop 0.5 tanh(i/1 mA) V in series with the armature"),
    ]


#: the baffles left out: the liquid's spinning inertia Jf [kg m^2], the wall's drag
#: cw [N m s^2/rad^2]
SWIRL = (0.25, 6e-3)
#: an open armature coil: dR [ohm], kappa [1], phase [rad]
BAR = (0.3, 6.0, 0.7)
#: the surface vortex reaching the impeller: dv [1], wv [rad/s], dw [rad/s]
VORTEX = (0.35, 33.0, 1.5)
#: a worn overload slip clutch: Ts [N m], ws [rad/s], Jp [kg m^2]
CLUTCH = (3.0, 0.05, 2e-4)


def outside_records() -> list[dict[str, Any]]:
    """ag11-ag14: effects the catalog does not contain."""
    return [
        spec("ag11", "outside", "slow", True, (outside(
            "unbaffled-tank-swirl", {"swirl": SWIRL},
            {"Jf_kgm2": SWIRL[0], "cw_Nms2_rad2": SWIRL[1],
             "form": "the liquid's bulk spins up as a body of inertia Jf, its speed wf from "
                     "0: the impeller's turbulent drag becomes cq (wi - wf)|wi - wf| instead "
                     "of cq wi|wi|, and Jf dwf/dt = cq (wi - wf)|wi - wf| - cw wf|wf| (the "
                     "wall's drag on the liquid)"}),),
            note="the tank's four wall baffles were taken out for cleaning and not refitted: "
                 "the liquid swirls with the impeller, spinning up over seconds, so the "
                 "impeller's drag falls as the liquid follows it (by about a third at full "
                 "speed); close to a smaller viscous friction or a larger inertia on the "
                 "impeller, but growing with the liquid's own slow spin-up and lingering "
                 "after a stop"),
        spec("ag12", "outside", "fast", False, (outside(
            "open-armature-coil", {"bar": BAR},
            {"dR_ohm": BAR[0], "kappa": BAR[1], "phase_rad": BAR[2],
             "form": "the loop takes dR (1 - exp(kappa (cos(2 (th - phase)) - 1))) i more: "
                     "one of the armature's two parallel paths broken, bridged only while a "
                     "brush spans the open coil's two commutator bars (twice a turn)"}),),
            probes=("current",), noise={"current": {"white": 0.03, "quant": ADC_STEP}},
            note="a bench log of the current alone (12-bit ADC); one armature coil's lead "
                 "has broken off its commutator riser: the armature's resistance is 0.3 Ohm "
                 "higher but for the short moments a brush bridges the open coil's bars, "
                 "twice a turn; close to a series resistance with an EMF harmonic of order "
                 "2, but a resistance that pulses with the rotor's angle"),
        spec("ag13", "outside", "slow", False, (outside(
            "surface-vortex-aeration", {"vortex": VORTEX},
            {"dv": VORTEX[0], "wv_rad_s": VORTEX[1], "dw_rad_s": VORTEX[2],
             "form": "the impeller receives dv cq wi|wi| (1 + tanh((|wi| - wv)/dw))/2: a "
                     "fraction dv of its turbulent drag lost above the critical speed wv, "
                     "the impeller drawing air from the surface vortex"}),),
            note="the tank was drawn down to a low level before the log: above 33 rad/s "
                 "(315 rpm) the surface vortex reaches the impeller, which draws air and "
                 "loses 35 % of its drag; below, it stirs as declared (the 12 V and the "
                 "-20 V stretches run under the critical speed); close to a smaller viscous "
                 "friction on the impeller, but only at the top speed"),
        spec("ag14", "outside", "fast", True, (outside(
            "slipping-overload-clutch", {"clutch": CLUTCH},
            {"Ts_Nm": CLUTCH[0], "ws_rad_s": CLUTCH[1], "Jp_kgm2": CLUTCH[2],
             "form": "a friction clutch between the hub and the shaft: its driven plate "
                     "(inertia Jp) takes Ts tanh((w/N - wp)/ws) from the hub and drives the "
                     "shaft K, which twists by thp - thi"}),),
            note="the overload slip clutch between the gearhead and the shaft, set for 6 N "
                 "m, has worn linings and slips at 3 N m: it holds while the agitator runs "
                 "steadily (1.5 N m) but slips through the start, the braking and the "
                 "reversal, when the impeller's inertia asks for more; close to a backlash "
                 "or a softer shaft, but a torque limit"),
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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 29, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:impeller", {"coul": {"impeller": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-7}}),
    ("viscous-friction:impeller", {"visc": {"impeller": 1e-5}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:impeller", {"offset": {"impeller": 1e-3}}),
    ("stribeck-friction:impeller", {"stribeck": {"impeller": (1e-3, 2.0)}}),
    ("backlash:K", {"gap": 1e-4}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:30", {"lsat": (30.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Ji", {"p": {"Ji": P["Ji"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:impeller", lambda a, b: {"cog": {"impeller": [(1, a, b)]}}),
    ("cogging:rotor:6", lambda a, b: {"cog": {"rotor": [(6, a, b)]}}),
    ("cogging:impeller:3", lambda a, b: {"cog": {"impeller": [(3, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:6", lambda a, b: {"emf": [(6, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1 uV s/rad of EMF), 1 mN m on the impeller."""
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


#: across the shaft (a spring and a damper, 1:1): the body an effect on each is compared with,
#: and the factor its size takes there per kind (the hub and the impeller turn at one mean
#: speed). Added after fresh29 was run once, as motors M, P and Q have it: ag04's dry friction
#: on the impeller was named on the hub, 0.80 sigma from it
ACROSS = {"impeller": ("hub", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0}),
          "hub": ("impeller", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` across the shaft
    (``recordkit.location_entry``), after a marginal record's scaling."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term
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
