"""Generate the blind set ``fresh4`` of the diagnosis benchmark: records d01-d12 of motor D
(a 24 V brushed DC gearmotor with a current shunt), and merge their truth into truth.json.

    python benchmarks/diagnosis/make_records_d.py              # records/d*.csv + truth.json
    python benchmarks/diagnosis/make_records_d.py --only d03,d10
    python benchmarks/diagnosis/make_records_d.py --truth-only # rewrite the d entries only

Uses simulators_d.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s], one column per probe [SI] (and the command ``u`` [V] in the slow
regime), written to records/<id>.csv (git-ignored). truth.json keeps every other entry as it
is; an entry with the same id is replaced. Nobody ran the diagnosis on these records while
they were written.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import recordkit
import simulators_d as sd

RECORDS = HERE / "records"
TRUTH = HERE / "truth.json"
SPLIT = "fresh4"
MOTOR = "D"
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_d.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_d_slow.yaml"}
#: the default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 0.01, "speed": 0.2},
         "slow": {"current": 0.01, "speed": 0.2, "load_speed": 0.02}}
SOURCE = {"fast": "Vin", "slow": "U"}
P = sd.MOTOR_D
N = P["N"]

Fx = dict[str, Any]
Effect = tuple[Fx, dict[str, Any]]


# ---------------------------------------------------------------------- effect helpers
# Each returns (simulators_d fx fragment, truth entry). ``expected``: what the catalog patch's
# free parameters should come out as (matched by the suffix of their names); a torque on the
# output is the same as 1/N of it on the rotor (the gear is rigid and lossless), a viscous
# coefficient 1/N^2 of it: both targets are accepted, each with its own expected value.

def loop(regime: str) -> list[str]:
    """Every element of the armature loop (a series resistance anywhere in it is one
    effect)."""
    return ["Rsh", "Ra", "La", "M", SOURCE[regime]]


def brush_drop(vb: float, eps: float = 0.01) -> Effect:
    """Brush drop ``vb`` [V], smoothed over ``eps`` [A] (the catalog's over 1 mA)."""
    return {"Vb": vb, "Vb_eps": eps}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"V_brush_V": vb, "i_smoothing_A": eps,
                       "form": "Vb tanh(i/i_smoothing)"}, "expected": {"Vb": vb}}


def coulomb_load(fc: float, wc: float = 0.01) -> Effect:
    """Coulomb friction ``fc`` [N*m] on the output, smoothed over ``wc`` [rad/s] (the
    catalog's friction law: tanh(w/0.01))."""
    return {"Fc_load": fc, "wc_load": wc}, {
        "effect": "coulomb-friction", "target": "load", "targets": ["load"],
        "parameters": {"T_coulomb_Nm": fc, "w_smoothing_rad_s": wc,
                       "form": "output receives -Fc tanh(w_load/wc)"},
        "expected": {"c": fc},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["rotor"],
                         "expected": {"c": fc / N}}]}


def load_torque(tl: float) -> Effect:
    """A constant load torque ``tl`` [N*m] on the output against positive rotation (the
    catalog's force-offset F = -tl on the output, -tl/N on the rotor)."""
    return {"T_load": tl}, {
        "effect": "force-offset", "target": "load", "targets": ["load"],
        "parameters": {"T_load_Nm": tl, "form": "output receives -T_load (a hoisted weight)"},
        "expected": {"F": -tl},
        "also_accept": [{"effect": "force-offset", "targets": ["rotor"],
                         "expected": {"F": -tl / N}}]}


def viscous_load(bx: float) -> Effect:
    """Extra viscous friction ``bx`` [N*m*s/rad] on the output (gear oil drag)."""
    return {"Bx_load": bx}, {
        "effect": "viscous-friction", "target": "load", "targets": ["load"],
        "parameters": {"B_extra_Nms_rad": bx}, "expected": {"b": bx},
        "also_accept": [{"effect": "viscous-friction", "targets": ["rotor"],
                         "expected": {"b": bx / N**2}}]}


def series_resistance(regime: str, r: float) -> Effect:
    """A resistance ``r`` [ohm] in the loop (a corroded connector)."""
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": loop(regime),
        "parameters": {"R_series_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


def supply_inductance(ls: float) -> Effect:
    """An inductance ``ls`` [H] between the supply and the drive: the declared La off by
    ls/La, reported by the catalog as a correction of La."""
    return {"Ls": ls}, {
        "effect": "inductance", "target": "La", "targets": ["La"], "correction": True,
        "parameters": {"L_supply_H": ls}, "expected": {"dL": ls / P["L"]}}


def warmup(rise: float, tau: float) -> Effect:
    """The armature's copper warming up: Ra (1 + rise (1 - exp(-t/tau))), tau [s]. The
    shunt carries the same current: a warm-up there is the same record (rise scaled by
    Ra/Rsh)."""
    return {"warmup": (rise, tau)}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "Ra*(1 + rise*(1 - exp(-t/tau)))", "rise": rise, "tau_s": tau},
        "expected": {"rise": rise, "tau": tau},
        "also_accept": [{"effect": "resistance-drift", "targets": ["Rsh"],
                         "expected": {"rise": rise * P["R"] / P["Rsh"], "tau": tau}}]}


def sensor(probe: str, kind: str, value: float) -> Effect:
    """A sensor effect on ``probe``: gain [1], offset [probe unit] or delay [s]."""
    key = {"gain": "sensor-gain", "offset": "sensor-offset", "delay": "sensor-delay"}[kind]
    return {"sensor": {probe: {kind: value}}}, {
        "effect": key, "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def outside(kind: str, fx: Fx, params: dict[str, Any]) -> Effect:
    """An effect the catalog has no entry for."""
    return fx, {"effect": f"outside:{kind}", "target": None, "targets": None,
                "parameters": params, "expected": {}}


def add(*parts: Effect) -> tuple[Fx, list[dict[str, Any]]]:
    """Merge effects into one fx (sensor entries merged per probe) and a truth list."""
    fx: Fx = {}
    effects = []
    for f, e in parts:
        for k, v in f.items():
            fx[k] = {**fx.get(k, {}), **v} if k == "sensor" else v
        effects.append(e)
    return fx, effects


# ---------------------------------------------------------------------- the record list

def _rec(rid: str, cls: str, regime: str, parts: tuple[Effect, ...] = (),
         noise: dict[str, dict[str, Any]] | None = None, note: str = "") -> dict[str, Any]:
    """One record's spec (noise None: the regime's default white noise)."""
    fx, effects = add(*parts)
    return {"id": rid, "class": cls, "regime": regime, "fx": fx, "effects": effects,
            "noise": noise, "note": note}


def _outside_records() -> list[dict[str, Any]]:
    """The three records whose effect the catalog cannot name."""
    return [
        _rec("d10", "outside", "fast", (outside(
            "supply-current-limit", {"current_limit": (6.0, 20.0, 0.05)},
            {"I_limit_A": 6.0, "foldback_V_per_A": 20.0, "smoothing_A": 0.05,
             "form": "u = u_cmd - 20 (sp(i - 6) - sp(-i - 6)), sp a softplus over 50 mA"}),),
            note="the bipolar supply's current limit (6 A, a regulator of finite gain 20 V/A) "
                 "clips the soft-start, the braking and the reversal currents"),
        _rec("d11", "outside", "slow", (outside(
            "armature-reaction", {"armature_reaction": 30.0},
            {"I_ar_A": 30.0, "form": "k(i) = k/(1 + (i/I_ar)^2) in the EMF and the torque"}),),
            note="armature reaction: the field weakens with current (-10 % of k at 10 A), "
                 "energy-consistent"),
        _rec("d12", "outside", "slow", (outside(
            "battery-fed-bridge", {"dc_link": (24.0, 0.25, 0.15, 2.0)},
            {"E_V": 24.0, "R0_ohm": 0.25, "R1_ohm": 0.15, "C1_F": 2.0,
             "form": "duty d = u/E; armature sees d (E - R0 d i - v1); "
                     "C1 dv1/dt = d i - v1/R1"}),),
            note="the PWM bridge is fed by a battery (R0 0.25 ohm, polarisation 0.15 ohm || "
                 "2 F, 0.3 s): the sag seen by the motor scales with the duty"),
    ]


def record_specs() -> list[dict[str, Any]]:
    """The records of fresh4: id, class, regime, fx, truth effects, noise, note, seed."""
    S = [
        _rec("d01", "null", "fast", note="white noise"),
        _rec("d02", "null", "slow",
             noise={"current": {"ar1": [8e-3, 0.85], "quant": 0.02},
                    "speed": {"pink": 0.2, "quant": 0.25},
                    "load_speed": {"white": 0.02, "quant": 0.02}},
             note="AR(1) current noise (phi 0.85), 1/f motor-speed noise; ADC steps 20 mA, "
                  "0.25 rad/s, 0.02 rad/s"),
        _rec("d03", "catalog", "fast", (brush_drop(0.8),), note="carbon brushes, 0.8 V"),
        _rec("d04", "catalog", "slow", (coulomb_load(0.12),),
             note="output shaft seal: 0.12 N m of Coulomb friction on the output (8 mN m at "
                  "the rotor); the output reverses"),
        _rec("d05", "catalog", "fast", (sensor("current", "delay", 50e-6),),
             note="current sense delayed by 50 us (one sample: filter and ADC pipeline)"),
        _rec("d06", "catalog", "fast", (supply_inductance(0.3e-3),),
             note="a 0.3 mH choke between the supply and the drive (dL = 1/3)"),
        _rec("d07", "catalog", "slow", (warmup(0.10, 2.0),),
             note="armature copper warming up: +10 % with a 2 s time constant"),
        _rec("d08", "two", "slow", (load_torque(0.15), sensor("load_speed", "gain", 0.98)),
             note="a constant 0.15 N m load torque on the output (a hoist) and a 2 % low "
                  "output encoder"),
        _rec("d09", "two", "fast", (series_resistance("fast", 0.15), viscous_load(3e-3)),
             note="a 0.15 ohm connector and gear-oil drag of 3e-3 N m s/rad on the output"),
        *_outside_records(),
    ]
    for j, s in enumerate(S):
        s["seed"] = 5000 + j
    return S


# ---------------------------------------------------------------------- generation

#: scalar catalog effects an outside record's imprint is projected on, each small enough for
#: its imprint to be linear in it (label, fx, parameter overrides)
ALTERNATIVES: tuple[tuple[str, Fx, dict[str, float]], ...] = (
    ("series-resistance", {"Rser": 1e-3}, {}), ("brush-drop", {"Vb": 1e-3, "Vb_eps": 1e-3}, {}),
    ("coulomb-friction", {"Fc_load": 1e-3}, {}), ("viscous-friction", {"Bx_load": 1e-4}, {}),
    ("force-offset", {"T_load": 1e-3}, {}), ("inductance", {"Ls": 1e-6}, {}),
    ("inertia", {}, {"Jl": P["Jl"] * 1.001}),
    ("resistance-drift:linear", {"warmup": (1.0, 1e4)}, {}),
    ("resistance-drift:warmup-0.1", {"warmup": (1e-3, 0.1)}, {}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}, {}),
    ("resistance-drift:warmup-1", {"warmup": (1e-3, 1.0)}, {}),
)

IMPRINTS = recordkit.Imprints(sd.simulate, WHITE)
null, signature, imprint = IMPRINTS.null, IMPRINTS.signature, IMPRINTS.imprint


def _alternative_imprints(regime: str) -> dict[str, np.ndarray]:
    """Imprints of ALTERNATIVES and of each probe's sensor gain, offset and delay."""
    dur = sd.REGIMES[regime][1]
    out = {}
    for label, fx, over in ALTERNATIVES:
        fx = dict(fx)
        if label.startswith("resistance-drift:warmup"):
            fx["warmup"] = (fx["warmup"][0], fx["warmup"][1] * dur)
        out[label] = imprint(regime, sd.simulate(regime, None, fx, {**P, **over}))
    for probe in sd.PROBES[regime]:
        for kind, val in (("gain", 1.001), ("offset", 1e-3), ("delay", 1e-6)):
            fx = {"sensor": {probe: {kind: val}}}
            out[f"sensor-{kind}:{probe}"] = imprint(regime, sd.simulate(regime, None, fx))
    return out


def unexplained(regime: str, clean: dict[str, np.ndarray]) -> dict[str, Any]:
    """How much of an outside record's imprint the catalog's scalar effects leave, in white
    sigmas (linearised at the null): after the best single one, and after the least-squares
    combination of all of them together (a lower bound of what any catalog fit leaves)."""
    tr = imprint(regime, clean)
    alts = _alternative_imprints(regime)
    single = {k: float(np.linalg.norm(tr - (tr @ a / (a @ a)) * a)) for k, a in alts.items()}
    best = min(single, key=single.__getitem__)
    x = np.column_stack(list(alts.values()))
    coef, *_ = np.linalg.lstsq(x, tr, rcond=None)
    return {"imprint": float(np.linalg.norm(tr)), "best_single": [best, single[best]],
            "all_scalar_effects_jointly": float(np.linalg.norm(tr - x @ coef))}


def truth_entry(spec: dict[str, Any], sig: dict[str, float]) -> dict[str, Any]:
    """The record's truth.json entry (the schema of the other splits)."""
    regime = spec["regime"]
    fs, dur = sd.REGIMES[regime]
    ns = recordkit.noise_or_white(spec, WHITE)
    return {
        "id": spec["id"], "class": spec["class"], "split": SPLIT, "motor": MOTOR,
        "netlist": NETLIST[regime], "regime": regime, "sample_rate_Hz": fs,
        "duration_s": dur, "csv": f"benchmarks/diagnosis/records/{spec['id']}.csv",
        "probes": list(sd.PROBES[regime]), "inputs": ["u"] if regime == "slow" else [],
        "free": [], "declared_error": {}, "noise": ns, "noise_text": recordkit.noise_text(ns),
        "seed": spec["seed"], "effects": spec["effects"], "declared_terms": [],
        "signature_sigma": sig, "marginal": False, "note": spec["note"],
    }


def make(spec: dict[str, Any], write: bool) -> dict[str, Any]:
    """Simulate one record, write its CSV (``write``), return its truth entry."""
    regime = spec["regime"]
    t = sd.grid(regime)
    clean = sd.simulate(regime, t, spec["fx"])
    entry = truth_entry(spec, signature(regime, clean))
    if spec["class"] == "outside":
        entry["unexplained_sigma"] = unexplained(regime, clean)
    if write:
        rng = np.random.default_rng(spec["seed"])
        ns = recordkit.noise_or_white(spec, WHITE)
        cols = {p: sd.add_noise(rng, clean[p], ns[p]) for p in sd.PROBES[regime]}
        if "u" in clean:
            cols["u"] = clean["u"]
        RECORDS.mkdir(exist_ok=True)
        recordkit.write_csv(RECORDS / f"{spec['id']}.csv", t, cols)
    return entry


def main(argv: list[str] | None = None) -> int:
    return recordkit.main(argv, __doc__, record_specs, make, "D")


if __name__ == "__main__":
    sys.exit(main())
