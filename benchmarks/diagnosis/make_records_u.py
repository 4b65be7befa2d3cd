"""Generate the blind set ``fresh20`` of the diagnosis benchmark: records j01-j14 of motor U
(a 36 V brushed DC motor driving the disc brush of a floor scrubber through a rigid 20:1
spur gearbox and a compliant rubber drive plate, against the floor's friction under the
brush and the detergent film's drag, with the motor's declared cogging of order 6), some
sampled evenly and some UNEVENLY, and merge their truth into truth.json.

    python benchmarks/diagnosis/make_records_u.py              # records/j*.csv + truth.json
    python benchmarks/diagnosis/make_records_u.py --only j03,j12
    python benchmarks/diagnosis/make_records_u.py --truth-only # rewrite the j entries only

Uses simulators_u.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe [SI] (and, in the slow regime, the command ``u``
[V] that motor_u_slow.yaml reads from its own table). Even records are sampled on the
regime's grid k/fs; uneven ones, in the fast regime, on a 25 kHz grid whose every sample is
moved by a random jitter of up to 10-30 % of the interval, and in the slow regime at a
logger's irregular intervals (0.6-1.4 times the mean of 4 ms) with a few samples dropped.
Each uneven record has its own times (from its seed), and the motor is simulated at those
very times (``t_eval``), never interpolated. truth.json is merged under an exclusive lock
(recordkit.merge). Nobody ran the diagnosis on these records.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import recordkit
import simulators_u as su

RECORDS = HERE / "records"
SPLIT = "fresh20"
MOTOR = "U"
SEED0 = 20500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_u.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_u_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.05, "speed": 0.4},
         "slow": {"current": 0.05, "speed": 0.4, "load_speed": 0.02}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = su.MOTOR_U
N = P["N"]
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_u, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gearbox is rigid and lossless: a torque on the
# rotor is N = 20 times as large on the hub (the gearbox's output), a viscous coefficient
# N^2 = 400 times; the brush sits behind the compliant drive plate and has no such equal.

def backlash(gap: float) -> Part:
    """A play of total width ``gap`` [rad of the hub against the brush] in the drive plate
    (ElastoBacklash)."""
    return {"gap": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap, "form": "no plate torque while |twist| < gap/2, "
                                               "c (twist -+ gap/2) + d w_rel in contact"},
        "expected": {"gap": gap}}


def stribeck_brush(s: float, ws: float) -> Part:
    """A breakaway peak s [N m] with Stribeck speed ws [rad/s] over the brush's declared
    floor friction."""
    return {"stribeck": {"brush": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "brush", "targets": ["brush"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "brush takes s exp(-(w/ws)^2) tanh(w/0.01) over the declared "
                               "Tf tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def brush_drop(vb: float) -> Part:
    """A brush contact drop Vb tanh(i / 1 mA) [V] in series with the armature."""
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def coulomb_rotor(c: float) -> Part:
    """An extra Coulomb friction c [N m] on the rotor (accepted on the hub at N times its
    size)."""
    return {"coul": {"rotor": c}}, {
        "effect": "coulomb-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"Fc_Nm": c, "form": "c tanh(w/0.01) against the rotor"},
        "expected": {"c": c},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["hub"],
                         "expected": {"c": c * N}}]}


def choke(dl: float) -> Part:
    """An inductance dl La [H] in series with the armature: the declared La off by a
    factor 1 + ``dl``, reported by the catalog as a correction of La."""
    return {"p": {"L": P["L"] * (1.0 + dl)}}, {
        "effect": "inductance", "target": "La", "targets": ["La"], "correction": True,
        "parameters": {"L_series_H": P["L"] * dl, "dL": dl}, "expected": {"dL": dl}}


def source_resistance(r: float, regime: str) -> Part:
    """A resistance [ohm] inside the supply (accepted in series with the armature)."""
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[regime], "targets": [SOURCE[regime]],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": ["Ra", "La", "M"],
                         "expected": {"R": r}}]}


def inertia_brush(dj: float) -> Part:
    """The brush's inertia off by a factor 1 + ``dj`` (a correction of Jb)."""
    return {"p": {"Jb": P["Jb"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jb", "targets": ["Jb"], "correction": True,
        "parameters": {"Jb_true_kgm2": P["Jb"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


def drift_linear(alpha: float) -> Part:
    """The armature's resistance drifting straight, R (1 + alpha t) [1/s]."""
    return {"alpha": alpha}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + alpha*t)", "alpha_per_s": alpha},
        "expected": {"alpha": alpha}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor U's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return su.simulate(regime, t, fx)


spec = recordkit.spec


# ---------------------------------------------------------------------- the records

#: a 12-bit ADC over +-40 A (19.5 mA steps) on the current
ADC_I = {"white": 0.05, "quant": 0.0195}


def nulls_and_singles() -> list[dict[str, Any]]:
    """j01-j07: the null and single catalog records."""
    return [
        spec("j01", "null", "fast", False, note="white noise"),
        spec("j02", "null", "slow", True,
             noise={"current": {"white": 0.03, "ar1": [0.04, 0.88], "quant": 0.0195},
                    "speed": {"white": 0.4, "pink": 0.4},
                    "load_speed": {"white": 0.02}},
             note="coloured noise: Gauss-Markov current noise (correlation 0.88 over the mean "
                  "interval, exp(-dt/tau) over an interval dt) and a 12-bit ADC over +-40 A "
                  "(19.5 mA steps) on the current, 1/f noise on the motor's speed (a sum of "
                  "Gauss-Markov processes an octave apart)"),
        spec("j03", "catalog", "fast", False, (backlash(0.03),),
             noise={"current": ADC_I, "speed": {"white": 0.4}},
             note="the brush's clip-in hub is worn: its three drive lugs sit loose in the "
                  "drive plate's slots, a total play of 0.03 rad of the brush (3 mm at the "
                  "lugs' radius) that opens whenever the plate's torque reverses (the step "
                  "down, the braking, the reversal); the current read by a 12-bit ADC"),
        spec("j04", "catalog", "slow", False, (stribeck_brush(2.5, 0.4),),
             note="the machine stood overnight on a floor where detergent dried under the "
                  "brush: the bristles are glued to the film and break away with 2.5 N m "
                  "more than the declared floor friction, which fades with the brush's speed "
                  "(Stribeck speed 0.4 rad/s): at the start and at the backward pass"),
        spec("j05", "catalog", "fast", True, (brush_drop(0.1),),
             marginal=lambda v: (brush_drop(v),), size=0.1,
             noise={"current": ADC_I, "speed": {"white": 0.4}},
             note="the motor's carbon brushes were just replaced and are not yet bedded in: "
                  "a contact drop of the sign of the current over the declared resistance, "
                  "scaled to a 25 sigma signature (marginal); the current read by a 12-bit "
                  "ADC"),
        spec("j06", "catalog", "slow", True, (sensor("load_speed", "gain", 20.0 / 21.0),),
             noise={"current": {"white": 0.03, "ar1": [0.03, 0.8]},
                    "speed": {"white": 0.4}, "load_speed": {"white": 0.02}},
             note="the brush's tachometer was refitted with a magnet ring of 20 poles while "
                  "its converter is still set for 21: it reads 20/21 of the brush's speed "
                  "(4.8 % low) at any speed; Gauss-Markov noise on the current"),
        spec("j07", "catalog", "fast", False, (coulomb_rotor(0.005),),
             marginal=lambda c: (coulomb_rotor(c),), size=0.005,
             note="the felt seal that keeps detergent splash off the motor's shaft was "
                  "pressed on too tight: an extra dry friction on the rotor, scaled to a 25 "
                  "sigma signature (marginal)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """j08, j09: two catalog effects at once."""
    return [
        spec("j08", "two", "fast", True, (choke(0.5), source_resistance(0.12, "fast")),
             noise={"current": ADC_I, "speed": {"white": 0.4}},
             note="the scrubber was refitted with an EMC kit: a 0.35 mH choke in the motor's "
                  "lead (the declared La 50 % low; a correction of La) and a longer, thinner "
                  "battery cable with the pack's own resistance, 0.12 ohm inside the supply; "
                  "the current read by a 12-bit ADC"),
        spec("j09", "two", "slow", False, (inertia_brush(0.4), drift_linear(0.006)),
             noise={"current": {"white": 0.05}, "speed": {"white": 0.4},
                    "load_speed": {"white": 0.015, "pink": 0.015}},
             note="a grit brush with a steel plate is fitted instead of the declared nylon "
                  "brush: its inertia is 40 % above Jb (a correction of Jb); and the record "
                  "starts right after a long scrub of a rough floor with a cold motor: the "
                  "winding heats at about 1.5 K/s through the record, its resistance rising "
                  "by 0.6 %/s; 1/f noise on the brush's speed"),
    ]


#: [ohm] the wet path across the motor's terminals
LEAK_R = 150.0
#: [1] the logger's clock running fast
CLOCK_EPS = 0.012
#: the bristles' presliding stiffness [N m/rad] and the smoothing of |wb| [rad/s]
DAHL = (60.0, 1e-3)
#: the vacuum motor: start [s], the bus's steady drop [V], its inrush's extra drop [V] and
#: decay [s], the bus's nominal voltage [V]
VAC = (2.6, 1.5, 3.0, 0.25, 36.0)


def outside_fast() -> list[dict[str, Any]]:
    """j10, j11: effects the catalog does not contain, fast regime."""
    return [
        spec("j10", "outside", "fast", False, (outside(
            "terminal-leakage-path", {"leak": LEAK_R},
            {"Rp_ohm": LEAK_R,
             "form": "the current reads i + v/Rp, v the bridge's output; the armature's "
                     "own current unchanged"}),),
            note="detergent water and carbon dust have bridged the motor's terminal block: "
                 "a 150 ohm path across the armature; the drive's current shunt sits in the "
                 "supply lead, so it reads the armature's current plus the path's v/150 ohm. "
                 "A person sees the current read 0.2 A high at 30 V, 0.13 A at 20 V, 0.23 A "
                 "at 34 V, 0.17 A LOW at -26 V and exactly right whenever the bridge applies "
                 "0 V (while braking and after the dynamic stop), the extra following the "
                 "applied voltage along the ramps; the speed untouched"),
        spec("j11", "outside", "fast", False, (outside(
            "logger-clock-fast", {"clock": CLOCK_EPS},
            {"eps": CLOCK_EPS, "form": "a sample stamped t was taken at the true time "
                                       "t/(1 + eps); the command's own timing is right"}),),
            note="the data logger runs on its microcontroller's internal RC oscillator, 1.2 % "
                 "fast: it samples every 39.5 us of true time and stamps each sample 40 us "
                 "after the last, so the record's clock runs ahead of the drive's. A person "
                 "sees every change of the record come later than the command says, by a "
                 "lag that grows along the record in proportion to the time (1.9 ms at the "
                 "end of the soft start, 3.6 ms at the step down, 8.6 ms at the dynamic "
                 "braking), and the record end 9.5 ms of true time early; every level and "
                 "gain as declared"),
    ]


def outside_slow() -> list[dict[str, Any]]:
    """j12-j14: effects the catalog does not contain, slow regime."""
    return [
        spec("j12", "outside", "slow", True, (outside(
            "direction-blind-tachometer", {"absread": "load_speed"},
            {"probe": "load_speed", "form": "reads |w_brush|"}),),
            noise={"current": {"white": 0.03, "ar1": [0.03, 0.85]}, "speed": {"white": 0.4},
                   "load_speed": {"white": 0.02}},
            note="the brush's tachometer is a single Hall switch over the magnet ring feeding "
                 "a frequency-to-voltage converter: it counts pulses but cannot tell the "
                 "direction, and reads the brush's speed without its sign. A person sees the "
                 "brush's speed as declared while it turns forwards, and during the backward "
                 "pass a positive brush speed of 13 rad/s while the motor's own encoder "
                 "shows -265 rad/s; it dips to zero at each reversal; Gauss-Markov noise on "
                 "the current"),
        spec("j13", "outside", "slow", False, (outside(
            "bristle-presliding-friction", {"dahl": DAHL},
            {"sigma_Nm_rad": DAHL[0], "eps_rad_s": DAHL[1], "Tf_Nm": P["Tf"],
             "form": "instead of the declared Tf tanh(w/0.01), the brush takes -F with "
                     "dF/dt = sigma (w - sqrt(w^2 + eps^2) F/Tf) (Dahl's model)"}),),
            noise={"current": {"white": 0.05}, "speed": {"white": 0.4, "pink": 0.3},
                   "load_speed": {"white": 0.02}},
            note="the floor's friction on the brush is the bristles' friction: before they "
                 "slide, the bristles bend like a spring (Dahl's presliding model), and the "
                 "friction builds up over about 0.1 rad of the brush's travel (21 mm at its "
                 "rim) instead of switching with the speed's sign; at steady speed it is the "
                 "declared 6 N m. A person sees each start and each reversal soften: the "
                 "brush first turns on the bent bristles as on a spring, with a short "
                 "wobble, then slides; after each stop the bent bristles push the brush a "
                 "little back; at steady speed nothing differs; 1/f noise on the motor's "
                 "speed"),
        spec("j14", "outside", "slow", True, (outside(
            "shared-battery-load-start", {"vac": VAC},
            {"t0_s": VAC[0], "dV_V": VAC[1], "dVin_V": VAC[2], "tau_in_s": VAC[3],
             "Vbus_V": VAC[4],
             "form": "the bridge's output is u (1 - drop(t)/Vbus), drop = dV + dVin "
                     "exp(-(t - t0)/tau_in) after t0, 0 before"}),),
            noise={"current": ADC_I, "speed": {"white": 0.4}, "load_speed": {"white": 0.02}},
            note="the operator lowers the squeegee 2.6 s into the pass: its vacuum motor "
                 "starts on the same 36 V battery and pulls the bus down by 4.5 V at its "
                 "inrush, settling to 1.5 V in a quarter of a second; the brush's bridge "
                 "applies its duty to the sagging bus. A person sees at 2.6 s, with no "
                 "change in the logged command, the current dip by 3 A for a few "
                 "milliseconds and the rotor's speed sag by 45 rad/s, then recover to about "
                 "17 rad/s (4.5 %) low and stay so for the rest of the record, the shortfall "
                 "in proportion to the command (9 rad/s in the eco pass, 12 rad/s in the "
                 "backward pass, none while the command is 0 V); the current read by a "
                 "12-bit ADC"),
    ]


def record_specs() -> list[dict[str, Any]]:
    """The 14 records in id order, each with its seed."""
    out = sorted(nulls_and_singles() + pairs() + outside_fast() + outside_slow(),
                 key=lambda s: s["id"])
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- sample times

def times(s: dict[str, Any]) -> np.ndarray:
    """The record's sample times [s] (even, or uneven from its seed), once; described in
    ``s["timestamps"]`` (``recordkit.record_times``)."""
    return recordkit.record_times(s, su.REGIMES, su.grid, 20, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
#: (the hub's frictions and offsets are the rotor's columns scaled)
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-3}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:brush", {"coul": {"brush": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-6}}),
    ("viscous-friction:brush", {"visc": {"brush": 1e-4}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:brush", {"offset": {"brush": 1e-3}}),
    ("stribeck-friction:brush:0.3", {"stribeck": {"brush": (1e-3, 0.3)}}),
    ("stribeck-friction:brush:3", {"stribeck": {"brush": (1e-3, 3.0)}}),
    ("backlash:K", {"gap": 1e-3}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:20", {"lsat": (20.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jh", {"p": {"Jg": P["Jg"] * 1.001}}),
    ("inertia:Jb", {"p": {"Jb": P["Jb"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder);
#: cogging:rotor:6 re-tunes the declared cogging
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:hub", lambda a, b: {"cog": {"hub": [(1, a, b)]}}),
    ("unbalance:brush", lambda a, b: {"cog": {"brush": [(1, a, b)]}}),
    ("cogging:rotor:6", lambda a, b: {"cog": {"rotor": [(6, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:6", lambda a, b: {"emf": [(6, a * 1e-2, b * 1e-2)]}),
)
#: the harmonic term the netlist declares (the motor's cogging)
DECLARED = ({"effect": "cogging", "target": "rotor", "order": su.COG_ORDER},)

#: the plumbing every later set shares (recordkit.Plumbing): truth entries, marginal
#: scaling, the catalog's imprints an outside or marginal record is compared with, the CSV;
#: each probe's sensor effects are its gain, its offset and its (pure) delay
KIT = recordkit.Plumbing(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=su, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=lambda label: 1e-4, marginal_sigma=MARGINAL_SIGMA, declared=DECLARED)
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
