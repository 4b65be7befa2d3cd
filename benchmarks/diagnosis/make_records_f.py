"""Generate the blind set ``fresh6`` of the diagnosis benchmark: records k01-k14 of motor F
(a 48 V brushed DC motor with brush friction, driving a fan with a declared quadratic load
through a rigid 5:1 gearbox), and merge their truth into truth.json.

    python benchmarks/diagnosis/make_records_f.py              # records/k*.csv + truth.json
    python benchmarks/diagnosis/make_records_f.py --only k03,k11
    python benchmarks/diagnosis/make_records_f.py --truth-only # rewrite the k entries only

Uses simulators_f.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s], one column per probe [SI] (and the command ``u`` [V] in the slow regime,
which motor_f_slow.yaml reads from its own table). truth.json keeps every other entry; an
entry with the same id is replaced. Nobody ran the diagnosis on these records.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import recordkit
import simulators_f as sf

RECORDS = HERE / "records"
TRUTH = HERE / "truth.json"
SPLIT = "fresh6"
MOTOR = "F"
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_f.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_f_slow.yaml"}
SOURCE = {"fast": "Vin", "slow": "U"}
#: default white noise per probe [A, rad/s, rad/s] (about 1e-3 of each signal's range)
WHITE = {"fast": {"current": 0.02, "speed": 0.3},
         "slow": {"current": 0.02, "speed": 0.3, "load_speed": 0.06}}
MARGINAL_SIGMA = 25.0
P = sf.MOTOR_F
N = P["N"]
#: the fan's inertia reflected to the rotor over the rotor's own: dJ of Jf is dJ*this of Jr
JF_OVER_JM = P["Jf"] / N**2 / P["Jm"]


# ---------------------------------------------------------------------- truth of one effect
# (fx fragment for simulators_f, truth effect). ``expected`` keys are the catalog patch's
# parameter suffixes (gain: the factor). The gearbox is rigid and lossless: a torque on the
# fan is 1/N of it on the rotor, a viscous coefficient 1/N^2.

def series_resistance(r: float, regime: str) -> tuple[dict, dict]:
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": ["Ra", "La", "M"],
        "parameters": {"R_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[regime]],
                         "expected": {"R": r}}]}


def brush_drop(vb: float) -> tuple[dict, dict]:
    return {"Vb": vb}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"V_brush_V": vb, "form": "Vb tanh(i/1 mA)"}, "expected": {"Vb": vb}}


def coulomb_fan(fc: float) -> tuple[dict, dict]:
    return {"Fc_fan": fc}, {
        "effect": "coulomb-friction", "target": "fan", "targets": ["fan"],
        "parameters": {"Fc_Nm": fc, "form": "Fc tanh(w_f/0.01) on the fan shaft"},
        "expected": {"c": fc},
        "also_accept": [{"effect": "coulomb-friction", "targets": ["rotor"],
                         "expected": {"c": fc / N}}]}


def viscous(node: str, b: float) -> tuple[dict, dict]:
    other = "rotor" if node == "fan" else "fan"
    bo = b / N**2 if node == "fan" else b * N**2
    return {f"b_{node}": b}, {
        "effect": "viscous-friction", "target": node, "targets": [node],
        "parameters": {"b_extra_Nms_rad": b}, "expected": {"b": b},
        "also_accept": [{"effect": "viscous-friction", "targets": [other],
                         "expected": {"b": bo}}]}


def inertia_fan(dj: float) -> tuple[dict, dict]:
    return {"p": {"Jf": P["Jf"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jf", "targets": ["Jf"], "correction": True,
        "parameters": {"Jf_true_kgm2": P["Jf"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj},
        "also_accept": [{"effect": "inertia", "targets": ["Jr"],
                         "expected": {"dJ": dj * JF_OVER_JM}}]}


def drift(alpha: float) -> tuple[dict, dict]:
    return {"alpha": alpha}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "Ra*(1 + alpha*t)", "alpha_per_s": alpha},
        "expected": {"alpha": alpha}}


def sensor(probe: str, kind: str, value: float) -> tuple[dict, dict]:
    return {"sensor": {probe: {kind: value}}}, {
        "effect": f"sensor-{kind}", "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def outside(kind: str, fx: dict, params: dict) -> tuple[dict, dict]:
    return fx, {"effect": f"outside:{kind}", "target": None, "targets": None,
                "parameters": params, "expected": {}}


def merge_fx(parts) -> tuple[dict, list]:
    fx: dict = {}
    effects = []
    for f, e in parts:
        for k, v in f.items():
            fx[k] = {**fx.get(k, {}), **v} if k in ("sensor", "p") else v
        effects.append(e)
    return fx, effects


def sim(regime: str, fx: dict) -> dict[str, np.ndarray]:
    fx = dict(fx)
    p = {**P, **fx.pop("p", {})}
    return sf.simulate(regime, None, fx, p)


# ---------------------------------------------------------------------- the records

def rec(rid, cls, regime, parts=(), noise=None, note="", marginal=None):
    fx, effects = merge_fx(parts)
    return {"id": rid, "class": cls, "regime": regime, "fx": fx, "effects": effects,
            "noise": noise, "note": note, "marginal": marginal}


def record_specs() -> list[dict[str, Any]]:
    S = [
        rec("k01", "null", "fast", note="white noise"),
        rec("k02", "null", "slow",
            noise={"current": {"ar1": [0.015, 0.85], "quant": 0.02},
                   "speed": {"white": 0.2, "pink": 0.25, "quant": 0.25},
                   "load_speed": {"white": 0.06, "quant": 0.05}},
            note="AR(1) current noise (phi 0.85) and 1/f motor-speed noise; ADC steps 20 mA, "
                 "0.25 rad/s, 0.05 rad/s"),
        rec("k03", "catalog", "slow", (coulomb_fan(0.12),),
            note="a dry shaft seal on the fan: Coulomb friction 0.12 N m on the fan shaft "
                 "(24 mN m at the rotor, beside the declared 20 mN m brush friction)"),
        rec("k04", "catalog", "fast", (brush_drop(0.8),),
            noise={"current": {"white": 0.02, "quant": 0.025}, "speed": {"white": 0.3}},
            note="carbon brushes: a contact drop of 0.8 V"),
        rec("k05", "catalog", "fast", (inertia_fan(0.01),),
            marginal=lambda a: (inertia_fan(a),),
            note="the fan's inertia a little off (a larger impeller than the datasheet's), "
                 "scaled to a 25 sigma signature (marginal); a correction of Jf"),
        rec("k06", "catalog", "slow", (viscous("rotor", 1e-6),),
            marginal=lambda a: (viscous("rotor", a),),
            note="extra viscous drag in the motor (a tighter bearing), scaled to a 25 sigma "
                 "signature (marginal)"),
        rec("k07", "catalog", "slow", (drift(0.02),),
            noise={"current": {"white": 0.02, "quant": 0.02}, "speed": {"white": 0.3},
                   "load_speed": {"white": 0.06, "quant": 0.05}},
            note="the armature warming: Ra + 2 %/s, straight (+10 % at 5 s)"),
        rec("k08", "two", "fast", (series_resistance(0.12, "fast"),
                                   sensor("current", "offset", 0.06)),
            note="a corroded connector 0.12 ohm in the armature loop and a current-sense "
                 "offset of 60 mA"),
        rec("k09", "two", "slow", (viscous("fan", 2e-3), sensor("speed", "gain", 1.015)),
            noise={"current": {"white": 0.02}, "speed": {"white": 0.3, "pink": 0.2},
                   "load_speed": {"white": 0.06}},
            note="a grease-packed fan bearing (+2e-3 N m s/rad on the fan, three times bf) "
                 "and the motor encoder's speed reading 1.5 % high"),
        rec("k10", "outside", "fast", (outside(
            "deadtime-duty", {"deadtime": (1.2, 0.3, 48.0)},
            {"Vdt_V": 1.2, "i0_A": 0.3, "Vdc_V": 48.0,
             "form": "the armature sees u - Vdt tanh(i/i0) (1 - (u/Vdc)^2)"}),),
            note="the bridge's dead time: a voltage error against the current, 1.2 V at 50 % "
                 "duty (u = 0) and vanishing at full duty. A person sees a brush-drop-like "
                 "loss that is large while the command is small (the ramp through zero, the "
                 "pause) and almost absent at 48 V; a constant brush drop cannot fit both"),
        rec("k11", "outside", "slow", (outside(
            "fan-exponent", {"fan_exp": (2.3, 40.0)},
            {"n": 2.3, "w_ref_rad_s": 40.0,
             "form": "fan torque cf w_ref^(2-n) |w_f|^n sign(w_f), equal to the declared "
                     "cf w_f|w_f| at w_f = 40 rad/s"}),),
            note="the fan's torque grows as speed^2.3, not the declared speed^2 (equal at "
                 "40 rad/s of the fan). A person sees the steady current at 48 V higher and "
                 "the speed lower than declared (+12 % of fan torque at 59 rad/s), at 30 V and "
                 "40 V close to it and at the 2 V creep a little lower: a friction that grows "
                 "with speed faster than any viscous term"),
        rec("k12", "outside", "fast", (outside(
            "input-lc-filter", {"lc_in": (40e-6, 0.03, 1000e-6)},
            {"Lf_H": 40e-6, "Rf_ohm": 0.03, "Cf_F": 1000e-6,
             "form": "Lf diL/dt = u - Rf iL - vC, Cf dvC/dt = iL - i; the armature sees vC "
                     "(f0 = 796 Hz)"}),),
            noise={"current": {"white": 0.02, "quant": 0.025}, "speed": {"white": 0.3}},
            note="an LC filter on the drive's supply (40 uH, 1000 uF, 30 mohm): each fast "
                 "step of the command rings at about 0.8 kHz, damped over a few ms. A person "
                 "sees a decaying 0.8 kHz oscillation in the current after every step, "
                 "which no resistance or inductance of the loop gives"),
        rec("k13", "outside", "slow", (outside(
            "bearing-warming", {"bearing_warm": (0.25, 2.0)},
            {"F1_Nm": 0.25, "tau_s": 2.0,
             "form": "fan shaft takes F1 (1 - exp(-t/tau)) tanh(w_f/0.01) more"}),),
            noise={"current": {"ar1": [0.02, 0.7]}, "speed": {"white": 0.3},
                   "load_speed": {"white": 0.06}},
            note="the fan bearing's friction rises as it warms: 0 at the start, 0.16 N m at "
                 "2 s, 0.23 N m at 5 s on the fan shaft. A person sees the current at a "
                 "fixed speed creep up through the record and the creep at 2 V slower than a "
                 "constant friction allows, while the first run-up fits the declared model"),
        rec("k14", "outside", "fast", (outside(
            "tacho-lag-ripple", {"tacho": (1.5e-3, 0.01)},
            {"tau_s": 1.5e-3, "a3": 0.01,
             "form": "speed reads y (1 + a3 sin(3 theta)), y' = (w - y)/tau"}),),
            note="the speed probe is a tachometer: a 1.5 ms first-order lag and a 1 % ripple "
                 "at three times the shaft's frequency (its three poles). A person sees the "
                 "speed lag the current's steps and a ripple proportional to speed whose "
                 "frequency follows it (0 Hz at rest, 140 Hz at 294 rad/s); the current "
                 "fits the declared model exactly"),
    ]
    for j, s in enumerate(S):
        s["seed"] = 7000 + j
    return S


# ---------------------------------------------------------------------- sizes

IMPRINTS = recordkit.Imprints(sf.simulate, WHITE)
null, signature, imprint = IMPRINTS.null, IMPRINTS.signature, IMPRINTS.imprint


#: small catalog effects (label, fx) whose imprints an outside record's is compared with
ALTERNATIVES = (
    ("series-resistance", {"Rser": 1e-3}),
    ("brush-drop", {"Vb": 1e-3}),
    ("coulomb-friction", {"Fc_rotor": 1e-4}),
    ("viscous-friction", {"b_rotor": 1e-7}),
    ("force-offset", {"T_rotor": 1e-4}),
    ("stribeck-friction:1", {"stribeck": (1e-4, 1.0)}),
    ("stribeck-friction:10", {"stribeck": (1e-4, 10.0)}),
    ("inductance", {"p": {"L": P["L"] * 1.001}}),
    ("inductor-saturation:3", {"lsat": (3.0, 0.999)}),
    ("inductor-saturation:30", {"lsat": (30.0, 0.999)}),
    ("inertia", {"p": {"Jf": P["Jf"] * 1.001}}),
    ("resistance-drift:linear", {"alpha": 1e-4}),
    ("resistance-drift:warmup-0.3", {"warmup": (1e-3, 0.3)}),
    ("resistance-drift:warmup-1", {"warmup": (1e-3, 1.0)}),
)


def alternatives(regime: str) -> dict[str, np.ndarray]:
    return IMPRINTS.of_effects(regime, lambda fx: sim(regime, fx), ALTERNATIVES,
                               sf.PROBES[regime], sf.REGIMES[regime][1],
                               sensors=recordkit.SENSOR_STEPS[:2])  # no delay in this set


def unexplained(regime, clean):
    """What the catalog's scalar effects leave of an imprint (white sigmas, linearised at the
    null): after the best single one, and after all of them jointly (least squares)."""
    tr = imprint(regime, clean)
    alts = alternatives(regime)
    single = {k: float(np.linalg.norm(tr - (tr @ a / (a @ a)) * a)) for k, a in alts.items()}
    best = min(single, key=single.__getitem__)
    x = np.column_stack(list(alts.values()))
    coef, *_ = np.linalg.lstsq(x, tr, rcond=None)
    return {"imprint": float(np.linalg.norm(tr)), "best_single": [best, single[best]],
            "all_scalar_effects_jointly": float(np.linalg.norm(tr - x @ coef)),
            "note": "linearised; alternatives: " + ", ".join(alts)}


def separation(regime, clean, same):
    tr = imprint(regime, clean)
    out: dict[str, float] = {}
    for label, a in alternatives(regime).items():
        kind = label.split(":")[0]
        if kind in same:
            continue
        d = float(np.linalg.norm(tr - (tr @ a / (a @ a)) * a))
        out[kind] = min(out.get(kind, np.inf), d)
    return out


def scale_marginal(spec):
    regime = spec["regime"]
    trial = next(iter(spec["effects"][0]["expected"].values()))
    for _ in range(2):
        best = max(signature(regime, sim(regime, spec["fx"])).values())
        trial *= MARGINAL_SIGMA / best
        spec["fx"], spec["effects"] = merge_fx(spec["marginal"](float(f"{trial:.4g}")))


def truth_entry(spec, sig):
    regime = spec["regime"]
    fs, dur = sf.REGIMES[regime]
    ns = recordkit.noise_or_white(spec, WHITE)
    return {
        "id": spec["id"], "class": spec["class"], "split": SPLIT, "motor": MOTOR,
        "netlist": NETLIST[regime], "regime": regime, "sample_rate_Hz": fs,
        "duration_s": dur, "csv": f"benchmarks/diagnosis/records/{spec['id']}.csv",
        "probes": list(sf.PROBES[regime]), "inputs": ["u"] if regime == "slow" else [],
        "free": [], "declared_error": {}, "noise": ns, "noise_text": recordkit.noise_text(ns),
        "seed": spec["seed"], "effects": spec["effects"], "declared_terms": [],
        "signature_sigma": sig, "marginal": spec["marginal"] is not None,
        "note": spec["note"],
    }


def make(spec, write):
    regime = spec["regime"]
    if spec["marginal"] is not None:
        scale_marginal(spec)
    clean = sim(regime, spec["fx"])
    entry = truth_entry(spec, signature(regime, clean))
    if spec["class"] == "outside":
        entry["unexplained_sigma"] = unexplained(regime, clean)
    if spec["marginal"] is not None:
        e = spec["effects"][0]
        same = {e["effect"], *(a["effect"] for a in e.get("also_accept", []))}
        entry["separation_sigma"] = separation(regime, clean, same)
    if write:
        rng = np.random.default_rng(spec["seed"])
        ns = recordkit.noise_or_white(spec, WHITE)
        cols = {p: sf.add_noise(rng, clean[p], ns[p]) for p in sf.PROBES[regime]}
        if regime == "slow":
            cols["u"] = clean["u"]
        RECORDS.mkdir(exist_ok=True)
        recordkit.write_csv(RECORDS / f"{spec['id']}.csv", sf.grid(regime), cols)
    return entry


def main(argv: list[str] | None = None) -> int:
    return recordkit.main(argv, __doc__, record_specs, make, "F")


if __name__ == "__main__":
    sys.exit(main())
