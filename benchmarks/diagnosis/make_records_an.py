"""Generate the blind set ``fresh39`` of the diagnosis benchmark: records aq01-aq14 of motor AN
(a 48 V brushed DC motor in a rear geared e-bike hub on the workshop's end-of-line test rig: a
rigid 5:1 planetary gear to the wheel, the tyre's compliance on the fluid turbo trainer's
roller, the roller meeting its bearings' drag, the tyre's rolling resistance and the fluid
unit's quadratic drag), some sampled evenly and some UNEVENLY, three of them giving the
diagnosis ONE probe only, and merge their truth into truth.json. The ids have two letters.

    python benchmarks/diagnosis/make_records_an.py                # records/aq*.csv + truth.json
    python benchmarks/diagnosis/make_records_an.py --only aq03,aq12
    python benchmarks/diagnosis/make_records_an.py --truth-only   # rewrite the aq entries only

Uses simulators_an.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe it gives [SI] (and, in the slow regime, the
command ``u`` [V] that motor_an_slow.yaml's pwl states). A single-probe record (truth's
``probes``: ["current"] or ["speed"]) holds that probe's column only; its signatures, its
marginal scaling and the catalog imprints it is compared with are computed on that probe
alone (``OneProbe``). Even records are sampled on the regime's grid k/fs; uneven ones, in the
fast regime, on a 20 kHz grid whose every sample is moved by a random jitter of up to 10-30 %
of the interval, and in the slow regime at a logger's irregular intervals (0.6-1.4 times the
mean of 4 ms) with a few samples dropped. Each uneven record has its own times (from its
seed), and the motor is simulated at those very times (``t_eval``), never interpolated.
truth.json is merged under an exclusive lock (recordkit.merge). An outside record whose
imprint the catalog's effects jointly leave less than OUTSIDE_LEFT of is reported (it would
not be outside in effect). A catalog or two-effect record's ``location_sigma`` covers every
pair of places an effect has an equal at: rotor, hub and roller for a torque effect, Jr,
Jw and Jf for an inertia (``PLACES``, ``INERTIAS``; first only across the tyre). Nobody
ran the diagnosis on these records.
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
import simulators_an as sa

RECORDS = HERE / "records"
SPLIT = "fresh39"
MOTOR = "AN"
SEED0 = 39500
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_an_fast.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_an_slow.yaml"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.1, "speed": 0.4},
         "slow": {"current": 0.06, "speed": 0.3, "load_speed": 0.05}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
#: an outside record's imprint must keep at least this fraction after all the catalog's
#: effects jointly (linearised)
OUTSIDE_LEFT = 0.2
#: the fast regime's jitter (a fraction of the interval, drawn per record in this range) and
#: the slow regime's dropped samples (a count drawn in this range)
JITTER, DROPS = (0.10, 0.30), (2, 8)
P = sa.MOTOR_AN
N = P["N"]
Part = tuple[dict, dict]
#: the source per regime, and the armature loop's elements
SOURCE = {"fast": "Vin", "slow": "U"}
LOOP = ["Ra", "La", "M"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_an, truth effect); ``expected`` is keyed by the
# catalog patch's parameter suffixes. The planetary gear is rigid and lossless as declared: a
# torque on the body ``hub`` (the wheel) is 1/N = 1/5 of it on the rotor, and the wheel turns
# with the rotor. The roller lies behind the tyre's compliance (1:1 in the reflected frame):
# an effect on it has no exact equal on the wheel.

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


def saturation(ipar: float, ratio: float) -> Part:
    """The armature inductance saturating: La (ratio + (1 - ratio) / (1 + (i / Ipar)^2))."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def sensor(probe: str, kind: str, value: float) -> Part:
    """A sensor's gain, offset or delay [1, probe unit, s]."""
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def emf_harmonic(order: int, slope: float, phase: float) -> Part:
    """An EMF harmonic w slope sin(order th + phase) [V], voltage only."""
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf": [(order, a, b)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


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


def cogging_36(amp: float) -> Part:
    """The armature's detent torque of order 36 at the phase 1.1 rad (a marginal record
    scales its amplitude [N m])."""
    return cogging_rotor(36, amp, 1.1)


def drift(alpha: float) -> Part:
    """The winding's resistance rising linearly, R (1 + alpha t) [1/s] (a marginal record
    scales alpha)."""
    return {"alpha": alpha}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + alpha*t)", "alpha_per_s": alpha},
        "expected": {"alpha": alpha}}


def stribeck_hub(s: float, ws: float) -> Part:
    """A breakaway peak s exp(-(wh/ws)^2) tanh(wh/0.01) [N m] on the wheel, ``ws`` [rad/s]
    (accepted on the rotor at s / N and ws N)."""
    return {"stribeck": {"hub": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "hub", "targets": ["hub"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "hub takes s exp(-(w/ws)^2) tanh(w/0.01) (the wheel declares "
                               "no dry friction of its own)"},
        "expected": {"s": s, "ws": ws},
        "also_accept": [{"effect": "stribeck-friction", "targets": ["rotor"],
                         "expected": {"s": s / N, "ws": ws * N}}]}


def unbalance_hub(amp: float, phase: float) -> Part:
    """A once-per-turn torque amp sin(thh + phase) [N m] on the wheel (accepted as a cogging
    of order 1 on the wheel; at the rotor it would be of order 1/N, no catalog order)."""
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    return {"cog": {"hub": [(1, a, b)]}}, {
        "effect": "unbalance", "target": "hub", "targets": ["hub"], "order": 1,
        "parameters": {"order": 1, "T_Nm": amp, "phase_rad": phase,
                       "form": "hub receives T sin(1 angle + phase)"},
        "expected": {"a": a, "b": b},
        "also_accept": [{"effect": "cogging", "targets": ["hub"], "order": 1,
                         "expected": {"a": a, "b": b}}]}


def inertia_roller(dj: float) -> Part:
    """The roller's inertia (with the trainer's flywheel) off by a factor 1 + ``dj`` (a
    correction of Jf's J, the parameter Jf)."""
    return {"p": {"Jf": P["Jf"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jf", "targets": ["Jf"], "correction": True,
        "parameters": {"Jf_true_kgm2": P["Jf"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj}}


outside = recordkit.outside


def sim(regime: str, t: np.ndarray, fx: dict) -> dict[str, np.ndarray]:
    """Motor AN's clean probes at the times ``t`` [s] with the effects ``fx``."""
    return sa.simulate(regime, t, fx)


def spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None, note="",
         marginal=None, size=None, probes: tuple[str, ...] | None = None) -> dict[str, Any]:
    """One record's specification (``recordkit.spec``) and the probes it gives the diagnosis
    (default: all of its regime's)."""
    s = recordkit.spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes or sa.PROBES[regime])
    return s


# ---------------------------------------------------------------------- the records

#: the rig's shunt amplifier: a 12-bit ADC over +-80 A (39.1 mA steps)
ADC_STEP = 160.0 / 4096
#: the controller's speed report of the hub's Hall sensor: 0.1 rad/s steps at the rotor
SPEED_STEP = 0.1
#: the trainer's head unit: the roller's speed as the wheel's, in 0.05 rad/s steps
ROLLER_STEP = 0.05


def nulls() -> list[dict[str, Any]]:
    """aq01, aq02: the null records."""
    return [
        spec("aq01", "null", "slow", False,
             noise={"current": {"white": 0.05, "pink": 0.04, "quant": ADC_STEP},
                    "speed": {"white": 0.25, "ar1": [0.2, 0.85], "quant": SPEED_STEP},
                    "load_speed": {"white": 0.04, "quant": ROLLER_STEP}},
             note="the controller's log of the rig's test program, an even record; the "
                  "current with 1/f noise (40 mA: the brushes on the commutator) on white "
                  "noise, read by the rig's 12-bit ADC (39.1 mA steps); the hub's Hall speed "
                  "with Gauss-Markov noise (correlation 0.85 over the interval, 0.2 rad/s: "
                  "the magnet ring's uneven poles) on white noise, reported in 0.1 rad/s "
                  "steps; the trainer's roller speed on white noise, reported in 0.05 rad/s "
                  "steps"),
        spec("aq02", "null", "fast", True, probes=("current",),
             noise={"current": {"white": 0.08, "ar1": [0.06, 0.7], "quant": ADC_STEP}},
             note="a bench log of the current alone, a jittered 20 kHz acquisition; the "
                  "current with Gauss-Markov noise (correlation 0.7 over the interval, 60 mA: "
                  "the shunt amplifier's own noise) on white noise, read by the 12-bit ADC "
                  "(39.1 mA steps)"),
    ]


def singles() -> list[dict[str, Any]]:
    """aq03-aq07, aq10: one catalog effect each."""
    return [
        spec("aq03", "catalog", "fast", True, (brush_drop(0.9),),
             note="the hub was serviced and its worn brushes replaced by a harder "
                  "electrographite grade: a contact drop of 0.9 V at the commutator whichever "
                  "way the current flows"),
        spec("aq04", "catalog", "slow", False, (drift(2e-3),),
             marginal=lambda a: (drift(a),), size=2e-3,
             note="the hub had stood in the unheated store overnight and its winding warms "
                  "through the test: the armature's resistance rises linearly with the time, "
                  "scaled to a 25 sigma signature (marginal)"),
        spec("aq05", "catalog", "fast", False, (emf_harmonic(1, 6e-3, 2.4),),
             note="the armature was rewound by a repair shop and one of its 18 coils has two "
                  "turns fewer than the others: the back EMF varies once a turn of the rotor, "
                  "6e-3 V s/rad (2.5 % of k), phase 2.4 rad"),
        spec("aq06", "catalog", "slow", True, (unbalance_hub(0.14, 0.7),),
             note="a puncture was mended with a thick tyre plug and a 25 g spoke magnet for "
                  "the bike's speedometer was clipped on beside it: about 45 g at the rim's "
                  "0.31 m, a once-a-turn gravity torque of 0.14 N m on the wheel, phase "
                  "0.7 rad"),
        spec("aq07", "catalog", "fast", False, (series_resistance(0.12, "fast"),),
             probes=("current",), noise={"current": {"white": 0.1, "quant": ADC_STEP}},
             note="a bench log of the current alone (the 12-bit ADC); the hub's cable "
                  "connector has corroded pins after a winter of wet rides: 0.12 Ohm in series "
                  "with the armature"),
        spec("aq10", "catalog", "fast", True, (cogging_36(0.02),),
             marginal=lambda a: (cogging_36(a),), size=0.02, probes=("speed",),
             note="a bench log of the hub's Hall speed alone; the armature was replaced by a "
                  "cheaper one whose 18 slots are not skewed: a detent torque 36 times a turn "
                  "of the rotor, phase 1.1 rad, scaled to a 25 sigma signature (marginal)"),
    ]


def pairs() -> list[dict[str, Any]]:
    """aq08, aq09: two catalog effects at once."""
    return [
        spec("aq08", "two", "slow", True,
             (inertia_roller(0.35), sensor("current", "offset", 0.25)),
             note="the trainer was fitted with its heavier \"road feel\" flywheel: the roller "
                  "with the flywheel has 35 % more inertia than the declared; and the rig's "
                  "shunt amplifier was not zeroed after its replacement: the current reads "
                  "0.25 A high"),
        spec("aq09", "two", "fast", False,
             (saturation(18.0, 0.55), stribeck_hub(0.6, 2.0)),
             note="the hub's motor is a replacement with a thinner magnet can, which saturates "
                  "under the armature's field at the ramp's and the reversal's high currents: "
                  "the armature inductance falls to 55 % of the declared, half way at 18 A; "
                  "and the wheel's axle bearings lost their grease to a pressure washer: a "
                  "breakaway of 0.6 N m on the wheel (1.8 N at the tread), fading above about "
                  "2 rad/s"),
    ]


#: the clutched hub: the carrier with the clutch's inner race Jk [kg m^2] (part of the
#: declared Jw), the engaged rollers' stiff damping Dl [N m s/rad], their smoothing e [rad/s]
CLUTCH = (0.004, 2000.0, 1e-4)
#: ghost pedalling: the cranks, chainring, chain and sprockets at the sprocket's speed Jc
#: [kg m^2], the gummed freewheel's viscous drag Df [N m s/rad] and pawls' drag Tp [N m], its
#: lock Dl [N m s/rad] and smoothing e [rad/s], the bottom bracket's and the chain's friction
#: Tb [N m] at the sprocket, the one pedal's weight G [N m] at the sprocket (0.36 kg at the
#: 170 mm crank, times rho) and the cranks' turns per sprocket turn rho (16/44)
PEDAL = (0.0035, 0.03, 0.02, 50.0, 1e-3, 0.06, 0.36 * 9.81 * 0.17 * 16.0 / 44.0, 16.0 / 44.0)
#: the radially laced wheel: the hub shell's inertia Jsh [kg m^2] (part of the declared Jw),
#: the spokes' torsional stiffness Kw [N m/rad] and damping Dw [N m s/rad]
WINDUP = (0.02, 800.0, 0.5)
#: the fluid unit's magnetic drive, at the wheel's radius (the roller turning Q = r /
#: r_roller = 11.6 times as fast): the impeller's inertia Ji [kg m^2] (1.5e-4 kg m^2 times
#: Q^2, part of the declared Jf), the coupling's pull-out torque Tmax [N m] (0.6 N m times Q)
#: and its angle factor P (4 pole pairs times Q)
Q_ROLLER = sa.R_WHEEL / sa.R_ROLLER
MAGDRIVE = (1.5e-4 * Q_ROLLER ** 2, 0.6 * Q_ROLLER, 4.0 * Q_ROLLER)


def outside_records() -> list[dict[str, Any]]:
    """aq11-aq14: effects the catalog does not contain."""
    return outside_slow() + outside_fast()


def outside_slow() -> list[dict[str, Any]]:
    """aq11, aq13: a clutched hub overrunning and ghost pedalling (slow)."""
    jk, dl, e = CLUTCH
    jc, df, tp, dlc, ec, tb, g, rho = PEDAL
    return [
        spec("aq11", "outside", "slow", True, (outside(
            "clutched-hub-overruns", {"clutch": CLUTCH},
            {"Jk_kgm2": jk, "Dl_Nms_rad": dl, "e_rad_s": e,
             "form": "a one-way roller clutch between the planetary's carrier (Jk, part of "
                     "the declared Jw, turning at w/N with the rotor) and the hub shell "
                     "(Jw - Jk, its own speed wh): the shell receives Dl (x + sqrt(x^2 + "
                     "e^2))/2, x = w/N - wh, the carrier the opposite; the tyre K lies "
                     "between the shell and the roller: the motor drives the wheel forward "
                     "only, and the wheel overruns it freely"}),),
            note="the stores sent the common clutched (freewheeling) version of the hub "
                 "instead of the declared clutchless regen one: the motor drives the wheel "
                 "forward but cannot hold it back; a person sees the record as declared up to "
                 "the slow-down, the wheel overrunning the motor briefly at 8.47-8.51 s, then "
                 "from 9.14 s, as the controller's output falls to 0 and shorts the motor, a "
                 "braking current of at most 0.67 A instead of 5.2 A, the rotor stopping on "
                 "its own while the wheel coasts on (9.2 rad/s instead of 1.8 at 9.5 s, 4.8 "
                 "rad/s instead of rest at the end); close to a smaller inertia of the wheel "
                 "or a lag of the roller's sensor, but only while the motor would brake"),
        spec("aq13", "outside", "slow", False, (outside(
            "ghost-pedalling-with-one-pedal", {"pedal": PEDAL},
            {"Jc_kgm2": jc, "Df_Nms_rad": df, "Tp_Nm": tp, "Dl_Nms_rad": dlc, "e_rad_s": ec,
             "Tb_Nm": tb, "G_Nm": g, "rho": rho,
             "form": "the cranks, chainring, chain and sprockets (Jc at the sprocket's speed "
                     "wc, angle thc) receive Tg = Df x + Tp tanh(x/0.01) + Dl (x - sqrt(x^2 + "
                     "e^2))/2, x = wh - wc, from the wheel (the wheel the opposite), "
                     "-Tb tanh(wc/0.01) from the bottom bracket and the chain, and "
                     "-G sin(rho thc) from the one pedal's weight (hanging at thc = 0): the "
                     "gummed freewheel drags the cranks round while the wheel overruns them "
                     "and locks if the cranks overrun the wheel"}),),
            noise={"current": {"white": 0.06, "quant": ADC_STEP},
                   "speed": {"white": 0.3, "quant": SPEED_STEP},
                   "load_speed": {"white": 0.05, "ar1": [0.03, 0.8], "quant": ROLLER_STEP}},
            note="the bike came in with its left pedal removed (its thread stripped) and a "
                 "screw-on freewheel gummed with old grease: the cranks turn with the wheel "
                 "(ghost pedalling), 16/44 of a turn of the sprocket, the one pedal lifted "
                 "and dropped once a crank turn; a person sees the pedal dragged up towards "
                 "the horizontal and held there in the easy step (the current 0.13-0.22 A "
                 "above the declared, the rotor 0.4 rad/s slower), going over the top at 3.7 "
                 "s (the wheel at 20 rad/s) and the cranks then turning in lurches, eight "
                 "turns in all, the current swinging by about 0.1-0.15 A and the rotor by "
                 "0.2-0.3 rad/s once a crank turn; close to a dry or viscous drag on the wheel "
                 "with an unbalance, but at no whole order of any body's turn (the cranks "
                 "slip behind the wheel)"),
    ]


def outside_fast() -> list[dict[str, Any]]:
    """aq12, aq14: the fluid unit's weak magnetic drive and a radially laced wheel (fast)."""
    ji, tmax, pp = MAGDRIVE
    jsh, kw, dw = WINDUP
    return [
        spec("aq12", "outside", "fast", False, (outside(
            "trainer-impeller-on-weak-magnetic-drive", {"magdrive": MAGDRIVE},
            {"Ji_kgm2": ji, "Tmax_Nm": tmax, "P": pp, "Q": Q_ROLLER,
             "form": "the fluid unit's impeller (Ji at the wheel's radius, part of the "
                     "declared Jf, its own speed wi and angle thi) receives Tmax sin(P (thr - "
                     "thi)) from the roller through the sealed unit's magnetic coupling (the "
                     "roller the opposite) and the fluid's drag -Cf wi sqrt(wi^2 + 1) (not "
                     "the roller); Tmax = 0.6 N m Q and P = 4 Q, Q = r/r_roller"}),),
            noise={"current": {"white": 0.1, "pink": 0.05, "quant": ADC_STEP},
                   "speed": {"white": 0.4}},
            note="a bench acquisition of the current (the 12-bit ADC, with 1/f noise of "
                 "50 mA on white noise) and the hub's Hall speed; the rig's fluid unit is a "
                 "sealed one whose impeller is driven through a magnetic coupling, and its "
                 "magnets were weakened when the unit overheated (a pull-out torque of 0.6 N "
                 "m left, 4 pole pairs): the impeller lags the roller by up to 15 degrees "
                 "and rings on the coupling at about 21 Hz; a person sees the current ring "
                 "by up to 0.06 A in the ramp and 0.5 A after the drop to 15 V, the reversal "
                 "and the stop, and the rotor's speed by up to 1 rad/s; close to a larger "
                 "inertia or drag of the roller, but ringing at a frequency of its own"),
        spec("aq14", "outside", "fast", True, (outside(
            "radially-laced-wheel-winds-up", {"windup": WINDUP},
            {"Jsh_kgm2": jsh, "Kw_Nm_rad": kw, "Dw_Nms_rad": dw,
             "form": "the spokes are a torsional spring and damper between the hub shell "
                     "(Jsh, part of the declared Jw, turning at w/N with the rotor) and the rim "
                     "with the tyre (Jw - Jsh, its own angle thm): the rim receives Kw (th/N - "
                     "thm) + Dw (w/N - wm), the shell the opposite; the tyre K lies between "
                     "the rim and the roller"}),),
            noise={"current": {"white": 0.1}, "speed": {"white": 0.4, "pink": 0.2}},
            note="a bench acquisition of the current and the hub's Hall speed (1/f noise "
                 "of 0.2 rad/s on white noise); the wheel was rebuilt by a shop with radially "
                 "laced spokes, which twist under the motor's torque: the rim winds up on the "
                 "hub shell by up to 0.038 rad (12 mm at the rim) and swings against it at "
                 "about 26 Hz; a person sees the current ring by up to 5 A after the drop to "
                 "15 V and 2 A after the reversal, and the rotor's speed by up to 8.5 rad/s; "
                 "close to the tyre's resonance on the roller, but at a frequency of its own "
                 "(26 Hz, not 65 Hz) and far stronger"),
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
    return recordkit.record_times(s, sa.REGIMES, sa.grid, 39, JITTER, DROPS)


# ---------------------------------------------------------------------- signatures

#: small catalog effects (label, fx) an imprint is compared with, linearised at the null
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-2}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:hub", {"coul": {"hub": 1e-3}}),
    ("coulomb-friction:roller", {"coul": {"roller": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-6}}),
    ("viscous-friction:roller", {"visc": {"roller": 1e-4}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("force-offset:roller", {"offset": {"roller": 1e-3}}),
    ("stribeck-friction:rotor", {"stribeck": {"rotor": (1e-4, 20.0)}}),
    ("stribeck-friction:hub", {"stribeck": {"hub": (1e-3, 2.0)}}),
    ("stribeck-friction:roller", {"stribeck": {"roller": (1e-3, 2.0)}}),
    ("backlash:K", {"gap": 1e-5}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:40", {"lsat": (40.0, 0.999)}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("inertia:Jw", {"p": {"Jw": P["Jw"] * 1.001}}),
    ("inertia:Jf", {"p": {"Jf": P["Jf"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
)
#: angle-locked catalog effects, two columns each (sine and cosine): (label, fx builder)
HARMONIC_EFFECTS = (
    ("unbalance:rotor", lambda a, b: {"cog": {"rotor": [(1, a, b)]}}),
    ("unbalance:hub", lambda a, b: {"cog": {"hub": [(1, a, b)]}}),
    ("unbalance:roller", lambda a, b: {"cog": {"roller": [(1, a, b)]}}),
    ("cogging:rotor:36", lambda a, b: {"cog": {"rotor": [(36, a, b)]}}),
    ("cogging:hub:2", lambda a, b: {"cog": {"hub": [(2, a, b)]}}),
    ("emf-harmonic:M:1", lambda a, b: {"emf": [(1, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:2", lambda a, b: {"emf": [(2, a * 1e-2, b * 1e-2)]}),
    ("emf-harmonic:M:36", lambda a, b: {"emf": [(36, a * 1e-2, b * 1e-2)]}),
)


def harmonic_size(label: str) -> float:
    """The size [N m, or 100 V s/rad for the EMF] of an angle-locked column: 0.1 mN m on the
    rotor (and 1e-6 V s/rad of EMF), 1 mN m on the wheel and the roller."""
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

    def scale_marginal(self, s: dict[str, Any]) -> None:
        """Scale a marginal record's size so that its best probe's signature is the set's
        marginal size on its own times: recordkit's proportional passes, repeated (up to
        eight) until within 1 % of it (a dry friction's imprint is not linear in its
        size)."""
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


#: every place a torque effect may sit at, with its gear factor (its speed over the hub's:
#: the rotor turns N times the wheel, the roller at the wheel's mean speed across the tyre,
#: 1:1 in the reflected frame), and every inertia with its parameter and factor
#: (``recordkit.places_moved``). Rotor-hub is exact (the rigid planetary gear); a pair with
#: the roller (or Jf) lies across the tyre's compliance. The truth first compared each torque
#: effect only across the tyre; after the set had been run, every pair is compared, inertias
#: too, as for fresh42 (the README says which verdicts this moved).
PLACES = {"rotor": N, "hub": 1.0, "roller": 1.0}
INERTIAS = {"Jr": ("Jm", N), "Jw": ("Jw", 1.0), "Jf": ("Jf", 1.0)}


def _location_entry(s: dict[str, Any]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` over every pair of places, after
    a marginal record's scaling (``recordkit.places_entry``)."""
    return recordkit.places_entry(s, times(s), imprints(s), sim, PLACES, INERTIAS, P,
                                  ("roller", "Jf"))


#: the plumbing of this set: truth entries, marginal scaling, the catalog's imprints an
#: outside or marginal record is compared with, the CSV, each on the record's own probes;
#: each probe's sensor effects are its gain, its offset and its delay; the netlist declares
#: no harmonic term of the catalog's kinds (the fluid unit's drag is a behavioural torque of
#: the declared model)
KIT = OneProbe(
    split=SPLIT, motor=MOTOR, netlist=NETLIST, white=WHITE, simulator=sa, sim=sim,
    times=times, scalar_effects=SCALAR_EFFECTS, harmonic_effects=HARMONIC_EFFECTS,
    harmonic_size=harmonic_size, marginal_sigma=MARGINAL_SIGMA, declared=(),
    extra=_location_entry)
imprints = KIT.imprints
make = KIT.make
scale_marginal = KIT.scale_marginal


def check_outside(entries: list[dict[str, Any]]) -> None:
    """Report an outside record that the catalog's effects jointly (linearised) leave less
    than OUTSIDE_LEFT of its imprint: it would not be outside in effect."""
    for e in entries:
        u = e.get("unexplained_sigma")
        if u and u["all_scalar_effects_jointly"] < OUTSIDE_LEFT * u["imprint"]:
            print(f"WARNING {e['id']}: the catalog's effects jointly leave "
                  f"{u['all_scalar_effects_jointly']:.3g} of its {u['imprint']:.3g} sigma")


def checked_make(s: dict[str, Any], write: bool) -> dict:
    """``make``, and the outside check of its entry."""
    entry = make(s, write)
    check_outside([entry])
    return entry


def main(argv: list[str] | None = None) -> int:
    """The command line (recordkit.main)."""
    return recordkit.main(argv, __doc__, record_specs, checked_make, MOTOR)


if __name__ == "__main__":
    sys.exit(main())
