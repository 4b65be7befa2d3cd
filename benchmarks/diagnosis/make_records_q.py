"""Generate the blind set ``fresh16`` of the diagnosis benchmark: records y01-y14 of motor Q
(a 60 V brushed DC traction motor driving a 350 kg utility cart through a rigid 12:1
reduction and compliant half-shafts), some sampled evenly and some UNEVENLY, and merge their
truth into truth.json.

    python benchmarks/diagnosis/make_records_q.py              # records/y*.csv + truth.json
    python benchmarks/diagnosis/make_records_q.py --only y03,y12
    python benchmarks/diagnosis/make_records_q.py --truth-only # rewrite the y entries only

Uses simulators_q.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe [SI] (and, in the slow regime, the command ``u``
[V] that motor_q_slow.yaml reads from its own table). Even records are sampled on the
regime's grid k/fs; uneven ones, in the fast regime, on a 25 kHz grid whose every sample is
moved by a random jitter of up to 15-30 % of the interval, and in the slow regime at a
logger's irregular intervals (0.6-1.4 times the mean of 2.5 ms) with a few samples dropped.
Each uneven record has its own times (from its seed), and the motor is simulated at those
very times (``t_eval``), never interpolated. truth.json is merged under an exclusive lock
(recordkit.merge). Nobody ran the diagnosis on these records.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import recordkit
import simulators_q as sp

RECORDS = HERE / "records"
SPLIT = "fresh16"
MOTOR = "Q"
SEED0 = 16500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_q.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_q_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.08, "speed": 0.1},
         "slow": {"current": 0.08, "speed": 0.1, "load_speed": 0.03}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.15, 0.30), (2, 8)
P = sp.MOTOR_Q
N = P["N"]
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_q, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The reduction is rigid and lossless: a torque on the
# rotor is N = 12 times as large on the hub, a viscous coefficient N^2 = 144 times; the
# wheels and the cart sit behind the compliant half-shafts and have no such equal.

def cogging(order: int, amp: float, phase: float) -> Part:
    """The rotor's detent torque amp sin(order angle + phase) [N m] (accepted on the hub at
    order N times and N times the size)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"rotor": [(order, a, b)]}}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"rotor receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["hub"], "order": int(order * N),
                         "expected": {"a": a * N, "b": b * N}}]}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def series_resistance(r: float, regime: str) -> Part:
    """A resistance [ohm] in series with the armature (a corroded cable lug)."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": ["Ra", "La", "M"],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


def brush_drop(vb: float) -> Part:
    """A brush contact drop [V]."""
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


def viscous_hub(b: float) -> Part:
    """An extra viscous friction [N m s/rad] on the hub (accepted on the rotor at 1/N^2)."""
    return {"visc": {"hub": b}}, {
        "effect": "viscous-friction", "target": "hub", "targets": ["hub"],
        "parameters": {"b_extra_Nms_rad": b, "form": "b w_hub against the hub"},
        "expected": {"b": b},
        "also_accept": [{"effect": "viscous-friction", "targets": ["rotor"],
                         "expected": {"b": b / N ** 2}}]}


def stribeck_wheel(s: float, ws: float) -> Part:
    """A breakaway peak s [N m] with Stribeck speed ws [rad/s] over the wheels' rolling
    resistance."""
    return {"stribeck": {"wheel": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "wheel", "targets": ["wheel"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "wheel takes s exp(-(w/ws)^2) tanh(w/0.01) over the declared "
                               "Tf tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def offset_wheel(value: float) -> Part:
    """A constant torque [N m] on the wheels (a slope of the floor; negative: uphill)."""
    return {"offset": {"wheel": value}}, {
        "effect": "force-offset", "target": "wheel", "targets": ["wheel"],
        "parameters": {"T_Nm": value, "form": "the wheels receive a constant T (uphill when "
                                              "T < 0)"},
        "expected": {"F": value}}


def inertia_cart(dj: float) -> Part:
    """The cart's reflected inertia off by a factor 1 + ``dj`` (a correction of Jv)."""
    return {"p": {"Jv": P["Jv"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jv", "targets": ["Jv"], "correction": True,
        "parameters": {"Jv_true_kgm2": P["Jv"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


def drift_linear(alpha: float) -> Part:
    """The armature's resistance drifting straight, R (1 + alpha t)."""
    return {"alpha": alpha}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + alpha*t)", "alpha_per_s": alpha},
        "expected": {"alpha": alpha}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor Q's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sp.simulate(regime, t, fx)


spec = recordkit.spec


# ---------------------------------------------------------------------- the records

#: a 12-bit ADC over +-160 A (80 mA steps) on the current
ADC_I = {"white": 0.08, "quant": 0.08}


def null_and_catalog() -> list[dict[str, Any]]:
    """y01-y09: the null, catalog and two-effect records."""
    return [
        spec("y01", "null", "fast", False, note="white noise"),
        spec("y02", "null", "slow", True,
             noise={"current": {"white": 0.05, "ar1": [0.08, 0.9], "quant": 0.08},
                    "speed": {"white": 0.1, "pink": 0.12},
                    "load_speed": {"white": 0.03}},
             note="coloured noise: Gauss-Markov current noise (correlation 0.9 over the mean "
                  "interval, exp(-dt/tau) over an interval dt) and a 12-bit ADC over +-160 A "
                  "(80 mA steps) on the current, 1/f noise on the motor's speed (a sum of "
                  "Gauss-Markov processes an octave apart)"),
        spec("y03", "catalog", "fast", True, (brush_drop(1.1),),
             noise={"current": ADC_I, "speed": {"white": 0.15}},
             note="the traction motor's carbon brushes (a hard grade fitted at the last "
                  "service) drop 1.1 V across the two brush contacts whatever the current's "
                  "size, against its sign; the current read by a 12-bit ADC"),
        spec("y04", "catalog", "fast", False, (viscous_hub(0.9),),
             note="the differential was overfilled with a heavy gear oil on a cold morning: "
                  "its churning drags the hub with 0.9 N m s/rad (1/144 of it on the rotor)"),
        spec("y05", "catalog", "fast", True, (cogging(28, 0.12, 1.2),),
             note="the motor's 28 armature slots under its 4 magnets lock the rotor 28 times a "
                  "turn: a detent torque of 0.12 N m (2.4 % of the rated torque), phase "
                  "1.2 rad"),
        spec("y06", "catalog", "slow", False, (stribeck_wheel(6.0, 0.6),),
             marginal=lambda s: (stribeck_wheel(s, 0.6),), size=6.0,
             note="the cart stood overnight on the tyres' flat spots: a breakaway peak over the "
                  "rolling resistance at the wheels, fading over 0.6 rad/s of the wheels, "
                  "scaled to a 25 sigma signature (marginal)"),
        spec("y07", "catalog", "slow", True, (sensor("load_speed", "gain", 1.03),),
             marginal=lambda s: (sensor("load_speed", "gain", 1.0 + s),), size=0.03,
             note="the wheel-speed sensor's tone ring was replaced by one with more teeth than "
                  "the controller's setting: the wheels' speed reads a few per cent high, "
                  "scaled to a 25 sigma signature (marginal)"),
        spec("y08", "two", "fast", False, (series_resistance(0.035, "fast"),
                                           offset_wheel(-6.0)),
             noise={"current": {"white": 0.06}, "speed": {"white": 0.1, "pink": 0.1}},
             note="a corroded cable lug on the motor's lead adds 35 mohm in series with the "
                  "armature; and the bay's floor is not level: a 0.9 % rise in the direction "
                  "of travel, -6 N m on the wheels; 1/f noise on the speed"),
        spec("y09", "two", "slow", True, (drift_linear(0.012), inertia_cart(0.17)),
             noise={"current": ADC_I, "speed": {"white": 0.15}, "load_speed": {"white": 0.03}},
             note="the armature warms through the trip well within its thermal time "
                  "constant: its resistance rises 1.2 % a second (24 % by the end); and a "
                  "60 kg crate the declared load lacks: the cart's reflected inertia 17 % "
                  "above Jv (a correction); the current read by a 12-bit ADC"),
    ]


#: the battery's polarisation branch: [ohm], [F] (a 50 ms time constant)
POLAR = (0.06, 0.8)
#: the tyres' traction: the wheels' own inertia [kg m^2], the peak traction torque [N m]
#: (0.25 x the drive axle's 175 kg x 9.81 x 0.2 m) and the creep's slope [N m s/rad]
TRACTION = (0.4, 86.0, 400.0)
#: [V] the throttle's dead zone
DEADBAND = 2.5
#: the liquid payload's sloshing mode: [kg m^2] (40 kg x (0.2 m)^2), [N m/rad] (1.1 Hz),
#: [N m s/rad] (damping ratio 0.05)
SLOSH = (1.6, 76.4, 1.1)
#: the ramp: the uphill torque [N m] (4 % grade), where its foot is [rad of the wheels]
#: and how long the transition [rad]
GRADE = (27.5, 178.0, 2.0)


def outside_fast() -> list[dict[str, Any]]:
    """y10-y12: effects the catalog does not contain, fast regime."""
    return [
        spec("y10", "outside", "fast", True, (outside(
            "battery-polarisation", {"polar": POLAR},
            {"Rp_ohm": POLAR[0], "Cp_F": POLAR[1],
             "form": "the source gives u - vp, Cp dvp/dt = i - vp/Rp, vp(0) = 0"}),),
            noise={"current": ADC_I, "speed": {"white": 0.15}},
            note="the cart's lead-acid traction battery is cold and half discharged: besides "
                 "its ohmic resistance (part of the drive's declared source) its voltage sags "
                 "with the diffusion polarisation of its plates, an RC branch of 60 mohm and "
                 "0.8 F (48 ms) in series with the supply. A person sees a source resistance "
                 "that acts on the current's slow part and not on its quick changes, and a "
                 "voltage that recovers after each current pulse; the current read by a "
                 "12-bit ADC"),
        spec("y11", "outside", "fast", False, (outside(
            "tyre-traction-slip", {"traction": TRACTION},
            {"Jw_kgm2": TRACTION[0], "T_max_Nm": TRACTION[1], "ks_Nms_rad": TRACTION[2],
             "form": "the wheels (Jw, with the declared losses) push the cart body (Jv - Jw) "
                     "with Tmax tanh(ks (wv - wb)/Tmax)"}),),
            note="the floor is dusty and the drive wheels carry half the laden weight: the "
                 "tyres' traction saturates at 86 N m (a friction coefficient of 0.25); the "
                 "launch and the regenerative step down ask for more, and the wheels spin up "
                 "ahead of the cart (or lock behind it). A person sees the inertia seen by the "
                 "motor collapse while the torque is high, and come back below it"),
        spec("y12", "outside", "fast", True, (outside(
            "throttle-dead-zone", {"deadband": DEADBAND},
            {"db_V": DEADBAND,
             "form": "the armature gets u - clamp(u, -db, db): nothing while |u| < db"}),),
            noise={"current": ADC_I, "speed": {"white": 0.15}},
            note="the drive's throttle input has a dead zone of +-2.5 V around neutral that "
                 "the logged command does not show: the armature gets nothing until the "
                 "command passes 2.5 V, then the command less 2.5 V. A person sees the launch "
                 "start late, a voltage deficit like a brush drop's that follows the "
                 "command's sign rather than the current's (it is the other way round in the "
                 "regenerative step down), and the armature held at zero volts (only the "
                 "short circuit's braking) while the command is within the zone; the current read by a 12-bit ADC"),
    ]


def outside_slow() -> list[dict[str, Any]]:
    """y13-y14: effects the catalog does not contain, slow regime."""
    return [
        spec("y13", "outside", "slow", False, (outside(
            "liquid-payload-slosh", {"slosh": SLOSH},
            {"Js_kgm2": SLOSH[0], "cs_Nm_rad": SLOSH[1], "ds_Nms_rad": SLOSH[2],
             "form": "Jv keeps Jv - Js; an inertia Js hangs on the wheels through cs and ds"}),),
            noise={"current": {"white": 0.04}, "speed": {"white": 0.15},
                   "load_speed": {"white": 0.02, "pink": 0.02}},
            note="the cart carries a half-full 80 l water tank: 40 kg of the laden mass is "
                 "liquid and sloshes fore and aft in the tank's first mode (1.1 Hz, damping "
                 "ratio 0.05) instead of moving with the cart. A person sees a lightly damped "
                 "1.1 Hz oscillation of the wheels' speed and the current after every change "
                 "of the acceleration, and a slightly smaller inertia in between; 1/f noise on "
                 "the wheels' speed"),
        spec("y14", "outside", "slow", True, (outside(
            "floor-ramp-by-position", {"grade": GRADE},
            {"T_grade_Nm": GRADE[0], "th0_rad": GRADE[1], "dth_rad": GRADE[2],
             "form": "the wheels take -Tg (1 + tanh((thv - th0)/dth))/2, thv their angle "
                     "from the start"}),),
            note="35.6 m from the start (178 rad of the wheels) the cart reaches the foot of "
                 "a 4 % loading ramp: gravity pulls it back with 27.5 N m at the wheels while "
                 "it stands on the ramp (from about 12.9 s, during the braking) until it has "
                 "backed off again at about 17.7 s. A person sees a constant load that "
                 "appears and disappears "
                 "with where the cart is, not with when or how fast"),
    ]


def record_specs() -> list[dict[str, Any]]:
    """The 14 records, each with its seed."""
    out = null_and_catalog() + outside_fast() + outside_slow()
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- sample times

def logger_times(rng: np.random.Generator, fs: float, duration: float, drops: int
                 ) -> tuple[np.ndarray, np.ndarray]:
    """A logger's times [s] and the times it dropped [s]: intervals of 0.6 + 0.8 Beta(3, 3)
    [1] times the mean 1/fs [Hz] (0.6-1.4 times it), from 0 to at most ``duration`` [s],
    rounded to 1 us; ``drops`` interior samples removed, at least seven apart."""
    gaps = (0.6 + 0.8 * rng.beta(3.0, 3.0, int(1.2 * duration * fs))) / fs
    t = np.round(np.concatenate([[0.0], np.cumsum(gaps)]) * 1e6) / 1e6
    t = t[t <= duration]
    pick = np.sort(rng.choice(np.arange(7, t.size - 7, 7), drops, replace=False))
    return np.delete(t, pick), t[pick]


def _tidy(t: np.ndarray) -> np.ndarray:
    """The times exactly as the CSV holds them (10 significant digits) [s]."""
    return np.array([float(f"{x:.10g}") for x in t])


def times(s: dict[str, Any]) -> np.ndarray:
    """The record's sample times [s] (even, or uneven from its seed), once; described in
    ``s["timestamps"]``."""
    if "t" in s:
        return s["t"]
    fs, dur = sp.REGIMES[s["regime"]]
    rng = np.random.default_rng([s["seed"], 16])
    if not s["uneven"]:
        t = sp.grid(s["regime"])
        s["timestamps"] = f"even: k/fs, fs = {fs:g} Hz"
    elif s["regime"] == "fast":
        jitter = round(float(rng.uniform(*JITTER)), 3)
        t = recordkit.jittered_times(rng, fs, dur, jitter)
        s["timestamps"] = (
            f"jittered: the nominal {fs / 1e3:g} kHz grid k/fs, every sample time but the "
            f"first moved by a uniform random jitter within +-{jitter:.1%} of the "
            f"{1e6 / fs:g} us interval (the last one only earlier), rounded to 1 ns; "
            f"intervals {np.diff(t).min() * 1e6:.2f}-{np.diff(t).max() * 1e6:.2f} us")
    else:
        drops = int(rng.integers(DROPS[0], DROPS[1] + 1))
        t, gone = logger_times(rng, fs, dur, drops)
        s["timestamps"] = (
            f"jittered: a data logger's irregular intervals, 0.6 + 0.8 Beta(3, 3) times the "
            f"mean {1e3 / fs:.3g} ms, from 0 to {t[-1]:.4f} s, rounded to 1 us; {drops} "
            "samples dropped (at " + ", ".join(f"{x:.4f}" for x in gone)
            + f" s); intervals {np.diff(t).min() * 1e3:.3f}-{np.diff(t).max() * 1e3:.3f} ms")
    s["t"] = _tidy(t)
    return s["t"]


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-3}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:wheel", {"coul": {"wheel": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-6}}),
    ("viscous-friction:wheel", {"visc": {"wheel": 1e-4}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:wheel", {"offset": {"wheel": 1e-3}}),
    ("stribeck-friction:wheel:0.3", {"stribeck": {"wheel": (1e-2, 0.3)}}),
    ("stribeck-friction:wheel:3", {"stribeck": {"wheel": (1e-2, 3.0)}}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:30", {"lsat": (30.0, 0.999)}),
    ("inertia:Jv", {"p": {"Jv": P["Jv"] * 1.001}}),
    ("inertia:Jm", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
    ("sensor-delay:current", {"sensor": {"current": {"delay": 1e-6}}}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:wheel", lambda a, b: {"cog": {"wheel": [(1, a, b)]}}),
    ("unbalance:hub", lambda a, b: {"cog": {"hub": [(1, a, b)]}}),
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("cogging:rotor:28", lambda a, b: {"cog": {"rotor": [(28, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:28", lambda a, b: {"emf": [(28, a * 1e-2, b * 1e-2)]}),
)
#: each probe's sensor effects (the delay only on the current, above)
SENSOR_STEPS = (("gain", 1.001), ("offset", 1e-3))

#: across the half-shafts: the shaft an effect on each is compared with, and the factor its
#: size takes there per kind (a torque on the rotor is N times its size on the wheels' side,
#: which turns 1/N times as fast; a viscous coefficient N^2 times; an angle-locked torque on
#: the wheels is the same on the hub, which turns with them)
ACROSS = {"rotor": ("wheel", {"coul": N, "offset": N, "visc": N * N}),
          "hub": ("wheel", {"coul": 1.0, "offset": 1.0, "visc": 1.0}),
          "wheel": ("hub", {"coul": 1.0, "offset": 1.0, "visc": 1.0, "cog": 1.0})}


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` across the half-shafts
    (``recordkit.location_entry``), after a marginal record's scaling (its parts are then
    the scaled ones)."""
    return recordkit.location_entry(s, ACROSS, times(s), imprints(s), sim)


#: the plumbing every later set shares (recordkit.Plumbing): truth entries, marginal
#: scaling, the catalog's imprints an outside or marginal record is compared with, the CSV
KIT = recordkit.Plumbing(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sp, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=lambda label: 1e-3,
    marginal_sigma=MARGINAL_SIGMA, sensor_steps=SENSOR_STEPS, extra=_location_entry)
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
