"""Generate the blind set ``fresh8`` of the diagnosis benchmark: records p01-p14 of motor H
(a 36 V brushed DC servo motor driving the ball screw of a linear axis through a rigid
2.5:1 gear pair, the screw's friction declared), and merge their truth into truth.json.

    python benchmarks/diagnosis/make_records_h.py              # records/p*.csv + truth.json
    python benchmarks/diagnosis/make_records_h.py --only p03,p12
    python benchmarks/diagnosis/make_records_h.py --truth-only # rewrite the p entries only

Uses simulators_h.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s] and one column per probe [SI] (and, in the slow regime, the command ``u``
[V] that motor_h_slow.yaml reads from its own table). The p entries of truth.json are merged
under an exclusive lock on .truth.lock (other sets may be merged at the same time): every
other entry is kept, an entry with the same id is replaced, and the file is replaced
atomically. Nobody ran the diagnosis on these records.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

import numpy as np
from scipy.optimize import lsq_linear

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import recordkit
import simulators_h as sh

RECORDS = HERE / "records"
TRUTH = HERE / "truth.json"
LOCK = HERE / ".truth.lock"
SPLIT = "fresh8"
MOTOR = "H"
SEED0 = 9000
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_h.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_h_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s]: a Hall current sensor on a 50 A range,
#: the motor's encoder differenced per sample, the screw's encoder
WHITE = {"fast": {"current": 0.025, "speed": 0.3},
         "slow": {"current": 0.02, "speed": 0.2, "load_speed": 0.04}}
#: a marginal record's best probe signature [white sigma]
MARGINAL_SIGMA = 25.0
P = sh.MOTOR_H
N = P["N"]


# ---------------------------------------------------------------------- effects
# Each returns (fx fragment for simulators_h, truth effect). ``expected`` is keyed by the
# catalog patch's parameter suffixes. The gear is rigid and lossless: a torque T on the screw
# is T / N on the rotor, a Coulomb friction c on the rotor is c N on the screw (the same
# power; its sign smoothing differs by the ratio, 0.01 vs 0.025 rad/s of the screw).

def _other_node(effect: str, node: str, key: str, value: float) -> list[dict]:
    other, f = ("rotor", 1.0 / N) if node == "screw" else ("screw", N)
    return [{"effect": effect, "targets": [other], "expected": {key: value * f}}]


def stribeck(s: float, ws: float):
    return {"stribeck": {"screw": (s, ws)}}, {
        "effect": "stribeck-friction", "target": "screw", "targets": ["screw"],
        "parameters": {"T_breakaway_Nm": P["Fs"] + s, "T_coulomb_Nm": P["Fs"], "s_Nm": s,
                       "ws_rad_s": ws,
                       "form": "the screw's friction gains s exp(-(w_s/ws)^2) tanh(w_s/0.01) "
                               "over the declared Fs tanh(w_s/0.01)"},
        "expected": {"s": s, "ws": ws}}


def brush_drop(vb: float):
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"Vb_V": vb, "form": "Vb tanh(i / 1 mA) in series with the armature"},
        "expected": {"Vb": vb}}


def cogging(node: str, order: int, amp: float, phase: float):
    a, b = amp * math.cos(phase), amp * math.sin(phase)
    e = {"effect": "unbalance" if order == 1 else "cogging", "target": node, "targets": [node],
         "order": order,
         "parameters": {"order": order, "T_Nm": amp, "phase_rad": phase,
                        "form": f"{node} receives T sin({order} angle + phase)"},
         "expected": {"a": a, "b": b}}
    if node == "rotor" and float(order * N).is_integer():
        # the screw turns rigidly with the rotor (th = N th_s, both from 0): the same torque
        # is order N k of the screw's angle, N times as large there
        e["also_accept"] = [{"effect": "cogging", "targets": ["screw"], "order": int(order * N),
                             "expected": {"a": a * N, "b": b * N}}]
    return {"cog": {node: [(order, a, b)]}}, e


def sensor(probe: str, kind: str, value: float):
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value, **({"form": "the first-order Pade stage of the delay, "
                                                "as the catalog's patch"}
                                       if kind == "delay" else {})},
        "expected": {kind: value}}


def coulomb(node: str, c: float):
    return {"coul": {node: c}}, {
        "effect": "coulomb-friction", "target": node, "targets": [node],
        "parameters": {"Fc_Nm": c, "form": f"c tanh(w/0.01) against the {node}'s motion"},
        "expected": {"c": c}, "also_accept": _other_node("coulomb-friction", node, "c", c)}


def series_resistance(r: float, regime: str):
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": ["Ra", "La", "M"],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


def torque_offset(node: str, value: float):
    return {"offset": {node: value}}, {
        "effect": "force-offset", "target": node, "targets": [node],
        "parameters": {"T_Nm": value, "form": f"the {node} receives a constant T"},
        "expected": {"F": value}, "also_accept": _other_node("force-offset", node, "F", value)}


def drift(alpha: float):
    return {"alpha": alpha}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"alpha_per_s": alpha, "form": "Ra (1 + alpha t)"},
        "expected": {"alpha": alpha}}


outside = recordkit.outside


combine = recordkit.combine




def sim(regime: str, fx: dict) -> dict[str, np.ndarray]:
    fx = dict(fx)
    p = {**P, **fx.pop("p", {})}
    return sh.simulate(regime, None, fx, p)


# ---------------------------------------------------------------------- the records

def spec(rid, cls, regime, parts=(), noise=None, note="", marginal=None, size=None):
    fx, effects = combine(parts)
    return {"id": rid, "class": cls, "regime": regime, "fx": fx, "effects": effects,
            "noise": noise, "note": note, "marginal": marginal, "size": size}


CLUTCH = (1.5, 0.8, 1.0, 4e-5)  # fn [N m], mu, mu_s, Jw [kg m^2]
NUT = (4.35, 0.04, 0.3)  # order of the screw's angle, T [N m], phase [rad]
SPRING = (0.0, 120.0 * (sh.LEAD / (2 * math.pi)) ** 2)  # T0 [N m], Ks [N m/rad]
SHORTED = (1.5e-3, 0.015, 5e-6, 0.4)  # ks [V s/rad], Rs [ohm], Ls [H], phase [rad]
XTALK = 0.05  # [rad/s per A]


def record_specs() -> list[dict[str, Any]]:
    lead_mm = sh.LEAD * 1e3
    out = [
        spec("p01", "null", "fast", note="white noise"),
        spec("p02", "null", "slow",
             noise={"current": {"ar1": [0.015, 0.85], "quant": 0.025},
                    "speed": {"white": 0.15, "pink": 0.2, "quant": 0.25},
                    "load_speed": {"white": 0.03, "quant": 0.05}},
             note="coloured noise: AR(1) current noise (phi 0.85), 1/f speed noise; ADC steps "
                  "25 mA, 0.25 rad/s, 0.05 rad/s"),
        spec("p03", "catalog", "slow", (stribeck(0.1, 2.0),),
             note="the guides' breakaway: below a few rad/s of the screw (a few mm/s of the "
                  "carriage) the friction rises from the declared 0.08 N m towards 0.18 N m "
                  "(a Stribeck peak s 0.1 N m, ws 2 rad/s). A person sees the creep need more "
                  "current than declared and the slow reversal stick longer"),
        spec("p04", "catalog", "fast", (brush_drop(0.05),),
             marginal=lambda s: (brush_drop(s),), size=0.05,
             note="a small brush contact drop Vb sign(i) (the catalog's tanh(i/1 mA)), scaled "
                  "to a 25 sigma signature (marginal)"),
        spec("p05", "catalog", "fast", (cogging("rotor", 14, 0.015, 0.9),),
             noise={"current": {"white": 0.025, "quant": 0.04}, "speed": {"white": 0.3}},
             note="the motor's cogging torque: 7 slots and 2 poles, 14 detents per turn, "
                  "15 mN m (5 % of the torque at 5 A). A person sees a ripple at 14 per rotor "
                  "turn in the speed and, through the EMF, in the current, largest at low "
                  "speed"),
        spec("p06", "catalog", "slow", (sensor("load_speed", "gain", 1.0005),),
             marginal=lambda s: (sensor("load_speed", "gain", 1.0 + s),), size=5e-4,
             note="the screw's speed is computed with the nominal 10 mm lead and the screw's "
                  "real lead is a little longer: load_speed reads high by a constant factor, "
                  "scaled to a 25 sigma signature (marginal)"),
        spec("p07", "catalog", "slow", (coulomb("rotor", 0.03),),
             noise={"current": {"white": 0.02, "quant": 0.02}, "speed": {"white": 0.2},
                    "load_speed": {"white": 0.04, "quant": 0.05}},
             note="the motor's own brush and bearing friction, 0.03 N m at the rotor (0.46 A), "
                  "which the netlist lacks (it declares the screw's only). A person sees the "
                  "running current higher than declared by a constant step that changes sign "
                  "with the direction, and the motor stand still longer at the slow reversal"),
        spec("p08", "two", "fast", (series_resistance(0.12, "fast"),
                                    sensor("speed", "delay", 3e-4)),
             noise={"current": {"white": 0.025}, "speed": {"white": 0.3, "pink": 0.2}},
             note="a worn connector in the armature loop (0.12 ohm) and a 0.3 ms lag of the "
                  "speed measurement (the encoder's speed filter)"),
        spec("p09", "two", "slow", (torque_offset("screw", -0.05), drift(0.02)),
             noise={"current": {"white": 0.02}, "speed": {"white": 0.2, "pink": 0.15},
                    "load_speed": {"white": 0.04}},
             note="the axis slightly inclined (a constant 31 N pulling the carriage back, "
                  "-0.05 N m on the screw) and the armature warming through the run, Ra rising "
                  "2 %/s"),
        spec("p10", "outside", "fast", (outside(
            "slipping-overload-clutch", {"clutch": CLUTCH},
            {"fn_Nm": CLUTCH[0], "mu": CLUTCH[1], "mu_s": CLUTCH[2], "Jw_kgm2": CLUTCH[3],
             "form": "a friction clutch between the gear wheel (Jw, part of the declared Js) "
                     "and the screw: stuck below mu_s fn, slipping at mu fn sign(w_rel), "
                     "exact stick-slip (events)"}),),
            note="the axis's torque-limiting safety clutch is set too low: it holds 1.5 N m "
                 "at the screw and slips at 1.2 N m. During the hard run-up, the braking and "
                 "the reversal the screw and carriage lag the motor: the rotor accelerates "
                 "and brakes faster than the declared inertia allows (as if the load were "
                 "lighter), with a kink in the speed where the clutch breaks away and again "
                 "where it grips; in steady running nothing differs"),
        spec("p11", "outside", "fast", (outside(
            "tacho-ground-crosstalk", {"xtalk": XTALK},
            {"kappa_rad_s_per_A": XTALK,
             "form": "speed reads w + kappa i (a shared ground return of the tachogenerator "
                     "and the armature, 0.5 mohm at 10 mV per rad/s)"}),),
            noise={"current": {"white": 0.025, "quant": 0.04}, "speed": {"white": 0.3}},
            note="the speed is read from a DC tachogenerator whose ground return shares "
                 "0.5 mohm with the armature current: the speed reads 0.05 rad/s per ampere "
                 "too high (+1.7 rad/s in the 34 A run-up, -2.4 rad/s in the -47 A brake). A "
                 "person sees the speed lead the declared model's on every current pulse, as "
                 "a negative delay would, and the speed's steady values a little off where "
                 "the running current is not zero; the current fits"),
        spec("p12", "outside", "fast", (outside(
            "ball-nut-defect", {"nut": NUT},
            {"order_of_screw": NUT[0], "T_Nm": NUT[1], "phase_rad": NUT[2],
             "form": "the screw receives T sin(order th_s + phase), th_s = th / 2.5: "
                     "order 1.74 of the rotor"}),),
            note="a spalled ball in the ball nut: a torque of 40 mN m at the screw, locked to "
                 "the screw's angle at 4.35 per screw turn (1.74 per rotor turn), not an "
                 "integer order of either shaft. A person sees a ripple in speed and current "
                 "whose frequency follows the speed (152 Hz at 36 V) but sits between the "
                 "integer orders of the rotor and of the screw"),
        spec("p13", "outside", "slow", (outside(
            "return-spring", {"spring": SPRING},
            {"T0_Nm": SPRING[0], "Ks_Nm_per_rad": SPRING[1],
             "k_N_per_m": SPRING[1] * (2 * math.pi / sh.LEAD) ** 2,
             "form": "the screw receives -(T0 + Ks th_s), th_s = 0 at the start"}),),
            note=f"a return spring, relaxed with the carriage at home (where the record "
                 f"starts), pulls it back in proportion to its travel: 120 N/m at the "
                 f"carriage ({lead_mm:g} mm lead: {SPRING[1] * 1e3:.3g} mN m per rad of the "
                 f"screw), 32 N (0.051 N m on the screw) at the far end (265 mm). A person "
                 f"sees a load against moving out that looks like a constant offset but grows "
                 f"with the carriage's position, not with time or speed; at standstill "
                 f"the friction holds it"),
        spec("p14", "outside", "slow", (outside(
            "shorted-armature-turns", {"shorted": SHORTED},
            {"ks_V_s_per_rad": SHORTED[0], "Rs_ohm": SHORTED[1], "Ls_H": SHORTED[2],
             "phase_rad": SHORTED[3],
             "form": "Ls is' = ks w cos(th + phase) - Rs is; the rotor receives "
                     "-ks cos(th + phase) is"}),),
            noise={"current": {"ar1": [0.02, 0.7]}, "speed": {"white": 0.2},
                   "load_speed": {"white": 0.04}},
            note="a few armature turns shorted together (failed insulation): the magnets "
                 "drive a current round the shorted loop (ks 1.5 mV s/rad, 15 mohm, 5 uH), "
                 "which brakes the rotor: 34 mN m on average at 450 rad/s (15 W heating the "
                 "fault), proportional to the speed and rippling at twice per rotor turn with "
                 "a depth as large as the mean. A person sees an extra viscous drag whose "
                 "order-2 ripple grows with the speed instead of keeping one amplitude as "
                 "cogging would, in the speed and (through the drive) in the current"),
    ]
    for j, s in enumerate(out):
        s["seed"] = SEED0 + j
    return out


# ---------------------------------------------------------------------- signatures

IMPRINTS = recordkit.Imprints(sh.simulate, WHITE)
null, signature, imprint = IMPRINTS.null, IMPRINTS.signature, IMPRINTS.imprint


#: small catalog effects (label, fx) an imprint is compared with (linearised at the null)
SCALAR_EFFECTS = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-3}),
    ("coulomb-friction:rotor", {"coul": {"rotor": 1e-4}}),
    ("coulomb-friction:screw", {"coul": {"screw": 2.5e-4}}),
    ("viscous-friction:rotor", {"visc": {"rotor": 1e-6}}),
    ("viscous-friction:screw", {"visc": {"screw": 6.25e-6}}),
    ("force-offset:screw", {"offset": {"screw": 2.5e-4}}),
    ("force-offset:rotor", {"offset": {"rotor": 1e-4}}),
    ("stribeck-friction:screw-0.3", {"stribeck": {"screw": (1e-4, 0.3)}}),
    ("stribeck-friction:screw-1", {"stribeck": {"screw": (1e-4, 1.0)}}),
    ("stribeck-friction:screw-3", {"stribeck": {"screw": (1e-4, 3.0)}}),
    ("stribeck-friction:screw-10", {"stribeck": {"screw": (1e-4, 10.0)}}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:10", {"lsat": (10.0, 0.999)}),
    ("inductor-saturation:40", {"lsat": (40.0, 0.999)}),
    ("inertia:Js", {"p": {"Js": P["Js"] * 1.001}}),
    ("inertia:Jr", {"p": {"Jm": P["Jm"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.1", {"warmup": (1e-3, 0.1)}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
    ("resistance-drift:warmup-1", {"warmup": (1e-3, 1.0)}),
)


def alternatives(regime: str) -> dict[str, np.ndarray]:
    return IMPRINTS.of_effects(regime, lambda fx: sim(regime, fx), SCALAR_EFFECTS,
                               sh.PROBES[regime], sh.REGIMES[regime][1])


#: alternatives whose catalog parameter cannot go negative (a resistance, a brush drop, a
#: friction, a saturation, a delay): their stand-in is fitted with a coefficient >= 0
NONNEGATIVE = ("series-resistance", "brush-drop", "coulomb-friction", "viscous-friction",
               "stribeck-friction", "inductor-saturation", "sensor-delay")


def _lower(label: str) -> float:
    return 0.0 if label.split(":")[0] in NONNEGATIVE else -np.inf


def _left(y: np.ndarray, label: str, a: np.ndarray) -> float:
    """What the best-scaled stand-in ``a`` leaves of ``y`` (its sign as the catalog allows)."""
    c = max(float(y @ a / (a @ a)), _lower(label))
    return float(np.linalg.norm(y - c * a))


def unexplained(regime: str, clean: dict) -> dict:
    """What the catalog's scalar effects leave of an imprint [white sigma], linearised at the
    null: after the best single one, and after all of them at once (least squares), each with
    the sign its catalog parameter allows."""
    y = imprint(regime, clean)
    alts = alternatives(regime)
    left = {k: _left(y, k, a) for k, a in alts.items()}
    best = min(left, key=left.__getitem__)
    x = np.column_stack([a / np.linalg.norm(a) for a in alts.values()])
    lb = np.array([_lower(k) for k in alts])
    # unit columns (several are nearly parallel: the same torque on either side of the
    # rigid gear) and the bounded variable least squares
    fit = lsq_linear(x, y, bounds=(lb, np.full(lb.size, np.inf)), method="bvls", tol=1e-12)
    free, *_ = np.linalg.lstsq(x, y, rcond=None)
    return {"imprint": float(np.linalg.norm(y)), "best_single": [best, left[best]],
            "all_scalar_effects_jointly": float(np.linalg.norm(y - x @ fit.x)),
            "all_jointly_any_sign": float(np.linalg.norm(y - x @ free)),
            "note": "linearised, signs as the catalog allows (>= 0: "
                    + ", ".join(NONNEGATIVE) + "; all_jointly_any_sign lifts that); "
                    "alternatives: " + ", ".join(alts)}


def separation(regime: str, clean: dict, same: set) -> dict[str, float]:
    """Distance [white sigma] of the imprint from each other scalar effect's best-scaled one
    (its sign as the catalog allows)."""
    y = imprint(regime, clean)
    out: dict[str, float] = {}
    for label, a in alternatives(regime).items():
        kind = label.split(":")[0]
        if kind in same:
            continue
        out[kind] = min(out.get(kind, math.inf), _left(y, label, a))
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
    fs, dur = sh.REGIMES[regime]
    ns = recordkit.noise_or_white(s, WHITE)
    return {
        "id": s["id"], "class": s["class"], "split": SPLIT, "motor": MOTOR,
        "netlist": NETLIST[regime], "regime": regime, "sample_rate_Hz": fs,
        "duration_s": dur, "csv": f"benchmarks/diagnosis/records/{s['id']}.csv",
        "probes": list(sh.PROBES[regime]), "inputs": ["u"] if regime == "slow" else [],
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
        cols = {p: sh.add_noise(rng, clean[p], ns[p]) for p in sh.PROBES[regime]}
        if regime == "slow":
            cols["u"] = clean["u"]
        RECORDS.mkdir(exist_ok=True)
        recordkit.write_csv(RECORDS / f"{s['id']}.csv", sh.grid(regime), cols)
    return entry


def main(argv: list[str] | None = None) -> int:
    return recordkit.main(argv, __doc__, record_specs, make, "H")


if __name__ == "__main__":
    sys.exit(main())
