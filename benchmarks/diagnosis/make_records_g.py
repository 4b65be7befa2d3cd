"""Generate the blind set ``fresh7`` of the diagnosis benchmark: records m01-m14 of motor G
(a 24 V brushed DC hoist motor driving a winch drum through a flexible coupling and a rigid
10:1 gearbox, a hanging load's gravity torque declared), and merge their truth into
truth.json.

    python benchmarks/diagnosis/make_records_g.py              # records/m*.csv + truth.json
    python benchmarks/diagnosis/make_records_g.py --only m03,m12
    python benchmarks/diagnosis/make_records_g.py --truth-only # rewrite the m entries only

Uses simulators_g.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe [SI] (and, in the slow regime, the command ``u``
[V] that motor_g_slow.yaml reads from its own table). Every other entry of truth.json is
kept; an entry with the same id is replaced. Nobody ran the diagnosis on these records.
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
import simulators_g as sg

RECORDS = HERE / "records"
TRUTH = HERE / "truth.json"
SPLIT = "fresh7"
MOTOR = "G"
SEED0 = 8000
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_g.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_g_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.02, "speed": 0.2},
         "slow": {"current": 0.02, "speed": 0.2, "load_speed": 0.02}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
P = sg.MOTOR_G
N = P["N"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_g, truth effect). ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gear is rigid and lossless: a torque on the drum is
# a torque 1/N as large on the pinion (and, through the stiff coupling, on the rotor).

def saturation(ipar: float, ratio: float):
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def angle_torque(node: str, order: int, amp: float, phase: float):
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    e = {"effect": "unbalance" if order == 1 else "cogging", "target": node,
         "targets": [node], "order": order,
         "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                        "form": f"{node} receives T sin({order} angle + phase)"},
         "expected": {"a": a, "b": b}}
    if order == 1:
        e["also_accept"] = [{"effect": "cogging", "targets": [node], "order": 1,
                             "expected": {"a": a, "b": b}}]
    elif node == "rotor":
        # the pinion behind the stiff coupling turns with the rotor (a twist of a few
        # mrad): a torque of the same order on it is the same observation
        e["also_accept"] = [{"effect": "cogging", "targets": ["hub"], "order": order,
                             "expected": {"a": a, "b": b}}]
    return {"cog": {node: [(order, a, b)]}}, e


def warmup(rise: float, tau: float):
    return {"warmup": (rise, tau)}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "Ra*(1 + rise*(1 - exp(-t/tau)))", "rise": rise,
                       "tau_s": tau},
        "expected": {"rise": rise, "tau": tau}}


def _drum_alternatives(effect: str, key: str, value: float) -> list[dict]:
    return [{"effect": effect, "targets": [n], "expected": {key: value / N}}
            for n in ("hub", "rotor")]


def torque_offset(value: float):
    return {"offset": {"drum": value}}, {
        "effect": "force-offset", "target": "drum", "targets": ["drum"],
        "parameters": {"T_Nm": value, "form": "the drum receives a constant T (the load "
                                              "heavier than declared when T < 0)"},
        "expected": {"F": value},
        "also_accept": _drum_alternatives("force-offset", "F", value)}


def coulomb_drum(fc: float):
    return {"coul": {"drum": fc}}, {
        "effect": "coulomb-friction", "target": "drum", "targets": ["drum"],
        "parameters": {"Fc_Nm": fc, "form": "Fc tanh(w_d/0.01) against the drum"},
        "expected": {"c": fc},
        "also_accept": _drum_alternatives("coulomb-friction", "c", fc)}


def source_resistance(r: float, regime: str):
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[regime], "targets": [SOURCE[regime]],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": ["Ra", "La", "M"],
                         "expected": {"R": r}}]}


def emf_harmonic(order: int, slope: float, phase: float):
    a, b = slope * math.cos(phase), slope * math.sin(phase)
    return {"emf_h": (order, a, b)}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": phase,
                       "form": f"e + w slope sin({order} theta + phase), voltage only"},
        "expected": {"a": a, "b": b}}


def sensor(probe: str, kind: str, value: float):
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


outside = recordkit.outside


NESTED = ("sensor", "p", "cog", "coul", "visc", "offset")


def combine(parts) -> tuple[dict, list]:
    """The simulator's fx of several effects (this set's nested keys), and their truth
    entries."""
    return recordkit.combine(parts, NESTED)




def sim(regime: str, fx: dict) -> dict[str, np.ndarray]:
    fx = dict(fx)
    p = {**P, **fx.pop("p", {})}
    return sg.simulate(regime, None, fx, p)


# ---------------------------------------------------------------------- the records

def spec(rid, cls, regime, parts=(), noise=None, note="", marginal=None, size=None):
    fx, effects = combine(parts)
    return {"id": rid, "class": cls, "regime": regime, "fx": fx, "effects": effects,
            "noise": noise, "note": note, "marginal": marginal, "size": size}


def record_specs() -> list[dict[str, Any]]:
    reel = (12.0, 0.025, 0.3e-3, 0.0045)  # J0 = Jd - m r0^2: the drum alone
    out = [
        spec("m01", "null", "fast", note="white noise"),
        spec("m02", "null", "slow",
             noise={"current": {"ar1": [0.015, 0.8], "quant": 0.02},
                    "speed": {"white": 0.15, "pink": 0.2, "quant": 0.25},
                    "load_speed": {"white": 0.02, "quant": 0.02}},
             note="coloured noise: AR(1) current noise (phi 0.8), 1/f speed noise; ADC steps "
                  "20 mA, 0.25 rad/s, 0.02 rad/s"),
        spec("m03", "catalog", "fast", (saturation(20.0, 0.55),),
             noise={"current": {"white": 0.02, "quant": 0.025}, "speed": {"white": 0.2}},
             note="the armature's iron saturates: the differential inductance falls to 55 % "
                  "at high current, half way down at 20 A"),
        spec("m04", "catalog", "fast", (angle_torque("rotor", 4, 5e-3, 0.6),),
             marginal=lambda s: (angle_torque("rotor", 4, s, 0.6),), size=5e-3,
             note="a 4-pole motor's cogging torque (order 4 of the rotor angle), scaled to a "
                  "25 sigma signature (marginal)"),
        spec("m05", "catalog", "slow", (warmup(0.15, 1.5),),
             note="the armature warming up through the run: Ra rising by 15 % with a 1.5 s "
                  "time constant"),
        spec("m06", "catalog", "slow", (angle_torque("drum", 1, 0.12, -1.0),),
             note="the winch drum out of balance (a clamp on its rim): 0.12 N m once per drum "
                  "revolution"),
        spec("m07", "catalog", "slow", (torque_offset(-0.02),),
             marginal=lambda s: (torque_offset(s),), size=-0.02,
             note="the load a little heavier than declared: a constant torque against lifting "
                  "on the drum, scaled to a 25 sigma signature (marginal)"),
        spec("m08", "two", "fast", (emf_harmonic(6, 1.5e-3, 0.4),
                                    sensor("current", "delay", 40e-6)),
             note="a back-EMF ripple of order 6 (2.5 % of k) and a 40 us lag of the current "
                  "measurement (its anti-aliasing filter)"),
        spec("m09", "two", "slow", (source_resistance(0.08, "slow"), coulomb_drum(0.15)),
             noise={"current": {"white": 0.02}, "speed": {"white": 0.2, "pink": 0.15},
                    "load_speed": {"white": 0.02}},
             note="a long supply cable (80 mohm) and a dry rope sheave (0.15 N m of Coulomb "
                  "friction on the drum)"),
        spec("m10", "outside", "fast", (outside(
            "hall-sensor-saturation", {"hall_sat": 100.0},
            {"Is_A": 100.0, "form": "the current probe reads Is tanh(i/Is)"}),),
            note="the Hall current sensor's core saturating: it reads Is tanh(i/Is) with "
                 "Is = 100 A (-2.3 % at 27 A, -7.0 % at the 48 A start). A person sees the "
                 "current's peaks short of what the speed's accelerations need, by a share "
                 "growing with the square of the current; small currents read true"),
        spec("m11", "outside", "fast", (outside(
            "rdc-tracking-loop", {"rdc": (120.0, 0.35)},
            {"fn_Hz": 120.0, "zeta": 0.35,
             "form": "speed reads the velocity integrator of a type-II tracking loop on the "
                     "rotor angle: w_hat = wn^2/(s^2 + 2 zeta wn s + wn^2) w"}),),
            note="the speed comes from a resolver-to-digital converter whose tracking loop "
                 "(120 Hz, damping 0.35) filters it to second order: the speed overshoots "
                 "after each step and the coupling's 100 Hz ringing reads amplified and late; "
                 "the current fits the declared model exactly"),
        spec("m12", "outside", "fast", (outside(
            "regenerative-bus-pumping", {"bus": (24.0, 0.03, 3.3e-3, 27.0, 0.2)},
            {"Vs_V": 24.0, "Rs_ohm": 0.03, "Cbus_F": 3.3e-3, "Vclamp_V": 27.0,
             "Rbrake_ohm": 0.2,
             "form": "a diode-fed bus: Cbus dV/dt = diode((Vs - V)/Rs) - (V - Vclamp)+/Rbrake "
                     "- d i, armature voltage d V, d = u/Vs"}),),
            noise={"current": {"white": 0.02, "quant": 0.025}, "speed": {"white": 0.2}},
            note="the drive's DC bus is fed through a diode and held by a capacitor bank with "
                 "a brake chopper at 27 V: whenever the motor regenerates (braking at 150 ms, "
                 "lowering the load at -6 V, braking the descent) the bus pumps up to 27-28.7 V "
                 "and the armature gets up to a fifth more voltage than commanded; while "
                 "motoring it sags through the diode's 30 mohm (1.4 V at the 48 A start). A "
                 "person sees the braking currents and the lowering speed larger than "
                 "declared, the lift close to it"),
        spec("m13", "outside", "slow", (outside(
            "cable-reel", {"reel": reel},
            {"m_kg": reel[0], "r0_m": reel[1], "delta_m_per_turn": reel[2],
             "J0_kgm2": reel[3],
             "form": "r = r0 + delta theta_d/(2 pi); drum receives -m g r - m r r' w_d^2, "
                     "inertia J0 + m r^2"}),),
            note="the rope winds on itself (a cable reel): the radius grows 0.3 mm per drum "
                 "turn, so the load's pull grows as it is lifted (+7 % after the first "
                 "lift, +10 % at the top) and falls back as it is lowered. A person sees the "
                 "holding current follow the load's height, not time"),
        spec("m14", "outside", "slow", (outside(
            "log-brush-contact", {"logbrush": (0.25, 1.5)},
            {"V1_V": 0.25, "I1_A": 1.5,
             "form": "the brushes take V1 ln(1 + |i|/I1) sign(i)"}),),
            noise={"current": {"ar1": [0.02, 0.7]}, "speed": {"white": 0.2},
                   "load_speed": {"white": 0.02}},
            note="the carbon brushes' contact voltage grows with the current as a logarithm "
                 "(0.25 V ln(1 + |i|/1.5 A): 0.13 V at 1 A, 0.37 V at 5 A, 0.6 V at 15 A). A "
                 "person sees a loss in the loop that is neither a constant drop nor a "
                 "resistance: relatively largest at small currents, growing slower than "
                 "linearly"),
    ]
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- signatures

IMPRINTS = recordkit.Imprints(sg.simulate, WHITE)
null, signature, imprint = IMPRINTS.null, IMPRINTS.signature, IMPRINTS.imprint


#: small catalog effects (label, fx) an imprint is compared with (linearised at the null)
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-3}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:drum", {"coul": {"drum": 1e-3}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-6}}),
    ("viscous-friction:drum", {"visc": {"drum": 1e-4}}),
    ("force-offset:drum", {"offset": {"drum": 1e-3}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:10", {"lsat": (10.0, 0.999)}),
    ("inductor-saturation:40", {"lsat": (40.0, 0.999)}),
    ("inertia:Jd", {"p": {"Jd": P["Jd"] * 1.001}}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.1", {"warmup": (1e-3, 0.1)}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
    ("resistance-drift:warmup-1", {"warmup": (1e-3, 1.0)}),
)


def alternatives(regime: str) -> dict[str, np.ndarray]:
    return IMPRINTS.of_effects(regime, lambda fx: sim(regime, fx), SCALAR_EFFECTS,
                               sg.PROBES[regime], sg.REGIMES[regime][1])


def unexplained(regime: str, clean: dict) -> dict:
    """What the catalog's scalar effects leave of an imprint [white sigma], linearised at the
    null: after the best single one, and after all of them at once (least squares)."""
    y = imprint(regime, clean)
    alts = alternatives(regime)
    left = {k: float(np.linalg.norm(y - (y @ a / (a @ a)) * a)) for k, a in alts.items()}
    best = min(left, key=left.__getitem__)
    x = np.column_stack(list(alts.values()))
    coef, *_ = np.linalg.lstsq(x, y, rcond=None)
    return {"imprint": float(np.linalg.norm(y)), "best_single": [best, left[best]],
            "all_scalar_effects_jointly": float(np.linalg.norm(y - x @ coef)),
            "note": "linearised; alternatives: " + ", ".join(alts)}


def separation(regime: str, clean: dict, same: set) -> dict[str, float]:
    """Distance [white sigma] of the imprint from each other scalar effect's best-scaled one."""
    y = imprint(regime, clean)
    out: dict[str, float] = {}
    for label, a in alternatives(regime).items():
        kind = label.split(":")[0]
        if kind in same:
            continue
        out[kind] = min(out.get(kind, math.inf), float(np.linalg.norm(y - (y @ a / (a @ a)) * a)))
    return out


def scale_marginal(s: dict) -> None:
    """Scale a marginal record's size so that its best probe's signature is MARGINAL_SIGMA
    (the effects here are linear in their size at this scale; two passes)."""
    size = s["size"]
    for _ in range(2):
        best = max(signature(s["regime"], sim(s["regime"], s["fx"])).values())
        size = float(f"{size * MARGINAL_SIGMA / best:.4g}")
        s["fx"], s["effects"] = combine(s["marginal"](size))
    s["size"] = size


def truth_entry(s: dict, sig: dict) -> dict:
    regime = s["regime"]
    fs, dur = sg.REGIMES[regime]
    ns = recordkit.noise_or_white(s, WHITE)
    return {
        "id": s["id"], "class": s["class"], "split": SPLIT, "motor": MOTOR,
        "netlist": NETLIST[regime], "regime": regime, "sample_rate_Hz": fs,
        "duration_s": dur, "csv": f"benchmarks/diagnosis/records/{s['id']}.csv",
        "probes": list(sg.PROBES[regime]), "inputs": ["u"] if regime == "slow" else [],
        "free": [], "declared_error": {}, "noise": ns, "noise_text": recordkit.noise_text(ns),
        "seed": s["seed"], "effects": s["effects"], "declared_terms": [],
        "signature_sigma": sig, "marginal": s["marginal"] is not None, "note": s["note"],
    }


def make(s: dict, write: bool) -> dict:
    regime = s["regime"]
    if s["marginal"] is not None:
        scale_marginal(s)
    clean = sim(regime, s["fx"])
    entry = truth_entry(s, signature(regime, clean))
    if s["class"] == "outside":
        entry["unexplained_sigma"] = unexplained(regime, clean)
    if s["marginal"] is not None:
        e = s["effects"][0]
        same = {e["effect"], *(a["effect"] for a in e.get("also_accept", []))}
        entry["separation_sigma"] = separation(regime, clean, same)
    if write:
        rng = np.random.default_rng(s["seed"])
        ns = recordkit.noise_or_white(s, WHITE)
        cols = {p: sg.add_noise(rng, clean[p], ns[p]) for p in sg.PROBES[regime]}
        if regime == "slow":
            cols["u"] = clean["u"]
        RECORDS.mkdir(exist_ok=True)
        recordkit.write_csv(RECORDS / f"{s['id']}.csv", sg.grid(regime), cols)
    return entry


def main(argv: list[str] | None = None) -> int:
    return recordkit.main(argv, __doc__, record_specs, make, "G")


if __name__ == "__main__":
    sys.exit(main())
