"""Generate the blind set ``fresh12`` of the diagnosis benchmark: records u01-u14 of motor M
(a 48 V brushed DC motor driving the impeller of a centrifugal blower directly, through a
short elastomer jaw coupling), some sampled evenly and some UNEVENLY as a real data logger
writes them, and merge their truth into truth.json.

    python benchmarks/diagnosis/make_records_m.py              # records/u*.csv + truth.json
    python benchmarks/diagnosis/make_records_m.py --only u03,u12
    python benchmarks/diagnosis/make_records_m.py --truth-only # rewrite the u entries only

Uses simulators_m.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe [SI] (and, in the slow regime, the command ``u``
[V] that motor_m_slow.yaml reads from its own table). Even records are sampled on the
regime's grid k/fs; uneven ones, in the fast regime, on a 25 kHz grid whose every sample is
moved by a random jitter of up to 20-35 % of the interval, and in the slow regime at a
logger's irregular intervals (0.5-2 times the mean of 1/250 s) with a few samples dropped.
Each uneven record has its own times (from its seed), and the motor is simulated at those
very times (``t_eval``), never interpolated. truth.json is merged under an exclusive lock
(``.truth.lock``, recordkit.merge): every other entry is kept, an entry with the same id is
replaced, and the file is replaced atomically. Nobody ran the diagnosis on these records.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import recordkit
import simulators_m as sm

RECORDS = HERE / "records"
SPLIT = "fresh12"
MOTOR = "M"
SEED0 = 12500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_m.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_m_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.05, "speed": 0.3},
         "slow": {"current": 0.05, "speed": 0.3, "load_speed": 0.3}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: the fast regime's jitter: a fraction of the nominal interval drawn in this range, per record
JITTER = (0.20, 0.35)
#: the slow regime's dropped samples: a count drawn in this range, per record
DROPS = (3, 8)
#: the term the netlist declares (the motor's order-14 ripple, on M)
DECLARED = [{"effect": "emf-harmonic", "target": "M", "order": 14}]
#: the sensor effects an imprint is compared with (kind, size) [1, probe unit]
SENSORS = (("gain", 1.001), ("offset", 1e-3))
#: the two shafts an effect can sit on (either side of the jaw coupling)
SHAFTS = ("rotor", "fan")
P = sm.MOTOR_M
Part = tuple[dict, dict]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_m, truth effect). ``expected`` is keyed by the
# catalog patch's parameter suffixes. The jaw coupling is compliant in the declared model:
# an effect on the fan is not the same physics as one on the rotor, so no rotor label is
# accepted for it.

def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain or offset [1, probe unit]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def brush_drop(vb: float) -> Part:
    """A brush contact drop [V]."""
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i/1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


def series_resistance(r: float) -> Part:
    """A resistance [ohm] in series with the armature."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": ["Ra", "La", "M"],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": ["Vin", "U"],
                         "expected": {"R": r}}]}


def saturation(ipar: float, ratio: float) -> Part:
    """The armature's iron saturating: knee current [A], saturated inductance ratio [1]."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"I_knee_A": ipar, "L_ratio_saturated": ratio,
                       "form": "La(i) = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2)), the "
                               "differential inductance"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def warmup(rise: float, tau: float) -> Part:
    """The winding warming up: a relative rise [1] with a time constant [s]."""
    return {"warmup": (rise, tau)}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + rise*(1 - exp(-t/tau)))", "rise": rise,
                       "tau_s": tau},
        "expected": {"rise": rise, "tau": tau}}


def harmonic(node: str, order: int, amp: float, phase: float) -> Part:
    """A torque amp sin(order angle + phase) [N m] on ``node``: an unbalance (order 1) or a
    cogging."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    effect = "unbalance" if order == 1 else "cogging"
    alts = [{"effect": "cogging", "targets": [node], "order": 1,
             "expected": {"a": a, "b": b}}] if order == 1 else []
    return {"cog": {node: [(order, a, b)]}}, {
        "effect": effect, "target": node, "targets": [node], "order": order,
        "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                       "form": f"{node} receives T sin({order} angle + phase)"},
        "expected": {"a": a, "b": b}, **({"also_accept": alts} if alts else {})}


def stribeck(node: str, s: float, ws: float) -> Part:
    """A breakaway peak s [N m] below the Stribeck speed ws [rad/s] on ``node``."""
    declared = "Tf" if node == "fan" else "Tc"
    return {"stribeck": {node: (s, ws)}}, {
        "effect": "stribeck-friction", "target": node, "targets": [node],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": f"{node} takes s exp(-(w/ws)^2) tanh(w/0.01) over the "
                               f"declared {declared} tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def coulomb(node: str, c: float) -> Part:
    """An extra Coulomb friction [N m] on ``node``."""
    return {"coul": {node: c}}, {
        "effect": "coulomb-friction", "target": node, "targets": [node],
        "parameters": {"Fc_Nm": c, "form": f"c tanh(w_{node}/0.01) against the {node}"},
        "expected": {"c": c}}


def viscous(node: str, b: float) -> Part:
    """An extra viscous friction [N m s/rad] on ``node``."""
    return {"visc": {node: b}}, {
        "effect": "viscous-friction", "target": node, "targets": [node],
        "parameters": {"b_extra_Nms_rad": b, "form": f"b w_{node} against the {node}"},
        "expected": {"b": b}}


outside = recordkit.outside


combine = recordkit.combine




def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor M's clean probes at the times ``t`` [s] with the effects ``fx``."""
    fx = dict(fx)
    p = {**P, **fx.pop("p", {})}
    return sm.simulate(regime, t, fx, p)


# ---------------------------------------------------------------------- the records

def spec(rid: str, cls: str, regime: str, uneven: bool, parts: Sequence[Part] = (),
         noise: dict | None = None, note: str = "",
         marginal: Callable[[float], Sequence[Part]] | None = None,
         size: float | None = None) -> dict[str, Any]:
    """One record's specification."""
    fx, effects = combine(parts)
    return {"id": rid, "class": cls, "regime": regime, "uneven": uneven, "fx": fx,
            "effects": effects, "parts": tuple(parts), "noise": noise, "note": note,
            "marginal": marginal, "size": size}


def null_and_catalog() -> list[dict[str, Any]]:
    """u01-u09: the null, catalog and two-effect records."""
    return [
        spec("u01", "null", "fast", False, note="white noise"),
        spec("u02", "null", "slow", True,
             noise={"current": {"white": 0.03, "ar1": [0.04, 0.8], "quant": 0.025},
                    "speed": {"white": 0.2, "pink": 0.25},
                    "load_speed": {"white": 0.3}},
             note="coloured noise: Gauss-Markov current noise (correlation 0.8 over the mean "
                  "interval, phi^(dt/mean) over an interval dt) and a 12-bit ADC over "
                  "+-50 A (25 mA steps) on the current, 1/f noise on the speed"),
        spec("u03", "catalog", "fast", True, (series_resistance(0.15),),
             noise={"current": {"white": 0.05, "quant": 0.025}, "speed": {"white": 0.3}},
             note="a loose, oxidised spade terminal on the motor lead: 0.15 ohm in series with "
                  "the armature; the current read by a 12-bit ADC over +-50 A (25 mA steps)"),
        spec("u04", "catalog", "fast", False, (sensor("current", "offset", 0.02),),
             marginal=lambda s: (sensor("current", "offset", s),), size=0.02,
             note="the Hall current sensor's zero has drifted: a constant offset on the "
                  "current reading, scaled to a 25 sigma signature (marginal)"),
        spec("u05", "catalog", "slow", True, (stribeck("fan", 0.1, 3.0),),
             noise={"current": {"white": 0.03, "ar1": [0.03, 0.7]}, "speed": {"white": 0.3},
                    "load_speed": {"white": 0.3}},
             note="the impeller's bearings have stood in a damp duct and their grease has "
                  "set: a breakaway peak of 0.1 N m over the declared 10 mN m bearing "
                  "friction, gone above about 3 rad/s (Stribeck speed 3 rad/s); seen where "
                  "the blower stops and reverses for the purge and stops again"),
        spec("u06", "catalog", "slow", False, (harmonic("fan", 1, 0.025, 1.1),),
             note="the impeller is fouled: about 40 g of dust and grease caked on a few "
                  "blades 6 cm from the axis; on the horizontal shaft its weight pulls the "
                  "impeller round once per turn, an unbalance of 25 mN m on the fan"),
        spec("u07", "catalog", "slow", True, (viscous("fan", 2e-5),),
             marginal=lambda s: (viscous("fan", s),), size=2e-5,
             note="the impeller's bearings run cold, their grease stiff: an extra viscous "
                  "friction on the fan, scaled to a 25 sigma signature (marginal)"),
        spec("u08", "two", "fast", True, (brush_drop(0.8), saturation(25.0, 0.55)),
             noise={"current": {"white": 0.05}, "speed": {"white": 0.2, "pink": 0.2}},
             note="worn carbon brushes with a 0.8 V contact drop in all (both brushes), "
                  "reversing with the current's sign; and the armature's iron saturates at "
                  "the start-up and braking currents (knee 25 A, the differential inductance "
                  "falling towards 55 % of the declared 0.9 mH); 1/f noise on the speed"),
        spec("u09", "two", "slow", False, (warmup(0.15, 2.5), coulomb("fan", 0.05)),
             noise={"current": {"white": 0.05, "quant": 0.025}, "speed": {"white": 0.3},
                    "load_speed": {"white": 0.3}},
             note="the record starts from a cold motor whose winding warms up: its resistance "
                  "rises by 15 % with a 2.5 s time constant; and the shaft seal of the "
                  "blower's housing is dry: an extra Coulomb friction of 0.05 N m on the fan; "
                  "the current read by a 12-bit ADC (25 mA steps)"),
    ]


def outside_records() -> list[dict[str, Any]]:
    """u10-u14: effects the catalog does not contain."""
    return [
        spec("u10", "outside", "fast", True, (outside(
            "ntc-inrush-limiter", {"ntc": (0.4, 3000.0, 1.0, 30.0)},
            {"R25_ohm": 0.4, "B_K": 3000.0, "Cth_J_K": 1.0, "Rth_K_W": 30.0,
             "form": "R_ntc = R25 exp(B (1/(298.15 K + dT) - 1/298.15 K)) in the supply "
                     "lead, Cth d(dT)/dt = i^2 R_ntc - dT/Rth, cold at t = 0"}),),
            note="an NTC inrush limiter (0.4 ohm cold) sits in the supply lead and heats up "
                 "by its own loss: its resistance falls from 0.4 ohm to about 0.13 ohm as "
                 "the start-up current warms it (by about 37 K within the record). A person "
                 "sees a loop resistance that is large at the start and shrinks as the "
                 "current has flowed, faster while the current is large: neither a constant "
                 "series resistance nor a winding that warms and rises"),
        spec("u11", "outside", "fast", False, (outside(
            "one-quadrant-chopper", {"chopper": (500.0, 0.01)},
            {"Roff_ohm": 500.0, "i0_A": 0.01,
             "form": "the loop takes Roff (1 - tanh(i/i0))/2 i more: the freewheeling diode "
                     "blocks a negative current"}),),
            noise={"current": {"white": 0.05, "quant": 0.025}, "speed": {"white": 0.3}},
            note="the blower is driven by a one-quadrant chopper (a switch and a freewheeling "
                 "diode) where the netlist declares a four-quadrant bridge: the current "
                 "cannot reverse. A person sees the current fall to zero and stay there at "
                 "the step down to 24 V (instead of the regenerative braking current of "
                 "down to -34 A) while the blower coasts down on its own load, more slowly "
                 "than declared, until the back-EMF falls below the command"),
        spec("u12", "outside", "fast", True, (outside(
            "impeller-rub", {"rub": (0.12, 20.0, 1.0)},
            {"T_Nm": 0.12, "kappa": 20.0, "phase_rad": 1.0,
             "form": "the fan receives -T exp(kappa (cos(thf - phase) - 1)) tanh(wf/0.01): "
                     "a friction pulse over a narrow arc once per impeller turn"}),),
            note="the impeller has shifted on its hub and one blade's shroud touches the "
                 "inlet cone over about 30 degrees of each turn, dragging it with up to "
                 "0.12 N m there (a mean drag of about 11 mN m). A person sees a drag that "
                 "comes in short pulses once per turn, with many harmonics of the shaft "
                 "order: partly like an unbalance and partly like a friction, neither alone"),
        spec("u13", "outside", "slow", False, (outside(
            "duct-damper-closing", {"damper": (0.4, 3.9, 0.1)},
            {"drop": 0.4, "t1_s": 3.9, "tr_s": 0.1,
             "form": "the fan's load becomes cf (1 - drop g(t)) wf |wf|, g = (1 + "
                     "tanh((t - t1)/tr))/2"}),),
            note="a motorised damper in the duct closes at 3.9 s while the command holds "
                 "48 V: the blower moves less air and its aerodynamic load falls by 40 % "
                 "within about 0.2 s. A person sees the current drop and both speeds rise "
                 "with no change in the command, and every later part of the cycle loaded "
                 "less than declared: a load that changes once during the record"),
        spec("u14", "outside", "slow", True, (outside(
            "eccentric-encoder-disk", {"encoder": (0.01, 0.6)},
            {"e": 0.01, "phase_rad": 0.6,
             "form": "speed reads w (1 + e cos(th + phase)): the encoder disk sits 1 % of "
                     "its track radius off the axis"}),),
            noise={"current": {"white": 0.05}, "speed": {"white": 0.3},
                   "load_speed": {"white": 0.3}},
            note="the motor's encoder disk was fitted off-centre (0.2 mm on a 20 mm track "
                 "radius): the angle it reports runs ahead and behind the rotor's once per "
                 "turn, and the speed it reports swings by +-1 % once per turn. A person "
                 "sees the speed alone carry a ripple at the rotor's turn whose size follows "
                 "the speed, seen in neither the current nor the impeller's tachometer"),
    ]


def record_specs() -> list[dict[str, Any]]:
    """The 14 records, each with its seed."""
    out = null_and_catalog() + outside_records()
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- sample times

def times(s: dict[str, Any]) -> np.ndarray:
    """The record's sample times [s] (even, or uneven from its seed), once; an uneven
    record's are described in ``s["timestamps"]``."""
    if "t" in s:
        return s["t"]
    fs, dur = sm.REGIMES[s["regime"]]
    if not s["uneven"]:
        s["t"] = np.array([float(f"{x:.10g}") for x in sm.grid(s["regime"])])
        return s["t"]
    rng = np.random.default_rng([s["seed"], 7])
    if s["regime"] == "fast":
        jitter = round(float(rng.uniform(*JITTER)), 3)
        t = recordkit.jittered_times(rng, fs, dur, jitter)
        s["timestamps"] = (
            f"jittered: the nominal {fs / 1e3:g} kHz grid k/fs, every sample time but the "
            f"first moved by a uniform random jitter within +-{jitter:.0%} of the "
            f"{1e6 / fs:g} us interval (the last one only earlier), rounded to 1 ns; "
            f"intervals {np.diff(t).min() * 1e6:.1f}-{np.diff(t).max() * 1e6:.1f} us, "
            f"monotonic")
    else:
        drops = int(rng.integers(DROPS[0], DROPS[1] + 1))
        t, dropped = sm.logger_times(rng, fs, dur, drops)
        dt = np.diff(t)
        s["timestamps"] = (
            f"jittered: a data logger's irregular intervals, 0.5-2 times the mean "
            f"{1e3 / fs:.3g} ms (0.5 + 1.5 Beta(2, 4) of it), from 0 to {t[-1]:.4f} s, "
            f"rounded to 1 us; {drops} samples dropped (at "
            + ", ".join(f"{x:.3f}" for x in dropped)
            + f" s); intervals {dt.min() * 1e3:.2f}-{dt.max() * 1e3:.2f} ms")
    # the times exactly as the CSV holds them (10 significant digits)
    s["t"] = np.array([float(f"{x:.10g}") for x in t])
    return s["t"]


def mean_rate(t: np.ndarray) -> float:
    """The mean sample rate [Hz] of the times ``t`` [s]."""
    return float((t.size - 1) / (t[-1] - t[0]))


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-3}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:fan", {"coul": {"fan": 1e-4}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-6}}),
    ("viscous-friction:fan", {"visc": {"fan": 1e-6}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:fan", {"offset": {"fan": 1e-4}}),
    ("stribeck-friction:rotor:3", {"stribeck": {"rotor": (1e-3, 3.0)}}),
    ("stribeck-friction:fan:1", {"stribeck": {"fan": (1e-3, 1.0)}}),
    ("stribeck-friction:fan:3", {"stribeck": {"fan": (1e-3, 3.0)}}),
    ("stribeck-friction:fan:10", {"stribeck": {"fan": (1e-3, 10.0)}}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:10", {"lsat": (10.0, 0.999)}),
    ("inductor-saturation:30", {"lsat": (30.0, 0.999)}),
    ("inertia:Jf", {"p": {"Jf": P["Jf"] * 1.001}}),
    ("inertia:Jm", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.1", {"warmup": (1e-3, 0.1)}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
    ("resistance-drift:warmup-1", {"warmup": (1e-3, 1.0)}),
)
#: angle-locked catalog effects (two columns each: the sine and the cosine), for what the
#: outside records leave: (label, builder of the fx for one column)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:fan", lambda a, b: {"cog": {"fan": [(1, a, b)]}}),
    ("cogging:fan:2", lambda a, b: {"cog": {"fan": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf_h": (1, a, b)}),
    ("emf-harmonic:M:2", lambda a, b: {"emf_h": (2, a, b)}),
)


#: the plumbing every later set shares (recordkit.Plumbing): truth entries, marginal
#: scaling, the catalog's imprints an outside or marginal record is compared with, the CSV
KIT = recordkit.Plumbing(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sm, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=lambda label: 1e-5 if "emf" in label else 1e-4,
    marginal_sigma=MARGINAL_SIGMA, sensor_steps=SENSORS,
    declared=DECLARED, extra=lambda s: _location_entry(s))
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def moved(frag: dict, target: str, other: str) -> list[dict]:
    """The columns' fx of one effect ``frag`` moved from shaft ``target`` to ``other`` at
    its own size: one for a scalar effect; two for an angle-locked one (its amplitude as a
    sine and as a cosine, so that the phase is fitted). The same size, not the catalog's
    small steps (SCALAR_EFFECTS): near the slow regime's stops, where the friction sticks, an
    imprint does not scale with its effect's size (a 1e-6 N m s/rad friction's, times 20,
    misses a 2e-5 one's by four times its norm, between 5.6 and 6.3 s), so a small step
    leaves 105 of a 2e-5 friction's 115 sigma on u07's times where the same size leaves 0.02."""
    (kind, where), = frag.items()
    value = where[target]
    if kind != "cog":
        return [{kind: {other: value}}]
    return [{kind: {other: [(k, math.hypot(a, b) * c, math.hypot(a, b) * d)
                            for k, a, b in value]}} for c, d in ((1.0, 0.0), (0.0, 1.0))]


def location(s: dict[str, Any]) -> list[dict[str, Any]]:
    """For each truth effect on a shaft (rotor or fan), the distance [white sigma] of its own
    clean imprint, run alone on the record's times and regime (so a two-effect record's other
    effect does not count), from the same effect at the same size on the other shaft,
    best-scaled; and that imprint's norm [white sigma]. ``separation_sigma`` never compares
    the same effect across the coupling."""
    regime, t, imp = s["regime"], times(s), imprints(s)
    out = []
    for frag, e in s["parts"]:
        if e["target"] not in SHAFTS:
            continue
        other = next(x for x in SHAFTS if x != e["target"])
        cols = np.column_stack([imp.imprint(regime, sim(regime, t, fx))
                                for fx in moved(frag, e["target"], other)])
        y = imp.imprint(regime, sim(regime, t, frag))
        out.append({"effect": e["effect"], "target": e["target"], "other": other,
                    "sigma": recordkit.left(y, cols), "imprint_sigma": float(np.linalg.norm(y))})
    return out


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` (``location``)."""
    return {"location_sigma": location(s)} if s["class"] in ("catalog", "two") else {}


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
