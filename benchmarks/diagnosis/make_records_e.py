"""Generate the blind set ``fresh5`` of the diagnosis benchmark: records e01-e14 of motor E
(a 12 V brushed DC motor with brush friction, driving a turntable through a 3:1 belt), and
merge their truth into truth.json.

    python benchmarks/diagnosis/make_records_e.py              # records/e*.csv + truth.json
    python benchmarks/diagnosis/make_records_e.py --only e03,e11
    python benchmarks/diagnosis/make_records_e.py --truth-only # rewrite the e entries only

Uses simulators_e.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s], one column per probe [SI] (and the command ``u`` [V] in the slow
regime), written to records/<id>.csv (git-ignored). truth.json keeps every other entry as it
is; an entry with the same id is replaced. Nobody ran the diagnosis on these records while
they were written.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import recordkit
import simulators_e as se

RECORDS = HERE / "records"
TRUTH = HERE / "truth.json"
SPLIT = "fresh5"
MOTOR = "E"
NETLIST = {"fast": "benchmarks/diagnosis/netlists/motor_e.yaml",
           "slow": "benchmarks/diagnosis/netlists/motor_e_slow.yaml"}
#: the default white noise per probe [A, rad/s, rad/s]
WHITE = {"fast": {"current": 5e-3, "speed": 0.1},
         "slow": {"current": 5e-3, "speed": 0.1, "load_speed": 0.03}}
SOURCE = {"fast": "Vin", "slow": "U"}
#: [sigma] the best probe's signature of a marginal record
MARGINAL_SIGMA = 25.0
P = se.MOTOR_E
N = P["N"]
#: the turntable's inertia reflected to the rotor, over the rotor's own [1]: a relative
#: change dJ of Jo is dJ * JL_OVER_JM of Jr
JL_OVER_JM = P["Jl"] / N**2 / P["Jm"]

Fx = dict[str, Any]
Effect = tuple[Fx, dict[str, Any]]


# ---------------------------------------------------------------------- effect helpers
# Each returns (simulators_e fx fragment, truth entry). ``expected``: what the catalog patch's
# free parameters should come out as (matched by the suffix of their names). The belt is
# rigid and lossless: a torque on the turntable is 1/N of it on the rotor, a viscous
# coefficient 1/N^2 of it; both targets are accepted, each with its own expected value.

def loop() -> list[str]:
    """The armature loop's two-pins a series resistance may be put on."""
    return ["Ra", "La", "M"]


def source_resistance(regime: str, r: float) -> Effect:
    """An internal resistance ``r`` [ohm] of the supply (a long thin supply lead, a weak
    bench supply)."""
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[regime], "targets": [SOURCE[regime]],
        "parameters": {"R_source_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": loop(),
                         "expected": {"R": r}}]}


def brush_drop(vb: float) -> Effect:
    """Brush drop ``vb`` [V], smoothed over 1 mA as the catalog's."""
    return {"Vb": vb, "Vb_eps": 1e-3}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"V_brush_V": vb, "i_smoothing_A": 1e-3,
                       "form": "Vb tanh(i/i_smoothing)"}, "expected": {"Vb": vb}}


def saturation(ipar: float, ratio: float) -> Effect:
    """The armature inductance falling with current: knee ``ipar`` [A], saturated over
    unsaturated ``ratio`` [1] (the differential inductance of circuitsim's Lsat)."""
    return {"lsat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"Ipar_A": ipar, "ratio": ratio,
                       "form": "dpsi/di = La (ratio + (1 - ratio)/(1 + (i/Ipar)^2))"},
        "expected": {"Ipar": ipar, "ratio": ratio}}


def drift(alpha: float) -> Effect:
    """Ra drifting straight, R (1 + alpha t), ``alpha`` [1/s] (the winding warming up well
    within its thermal time constant)."""
    return {"alpha": alpha}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "Ra*(1 + alpha*t)", "alpha_per_s": alpha},
        "expected": {"alpha": alpha}}


def stribeck(s: float, ws: float) -> Effect:
    """A breakaway peak ``s`` [N*m] over the declared brush friction, fading over ``ws``
    [rad/s]: the rotor takes s exp(-(w/ws)^2) tanh(w/0.01) more (the catalog's law)."""
    return {"stribeck": (s, ws)}, {
        "effect": "stribeck-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"T_peak_Nm": s, "w_stribeck_rad_s": ws,
                       "form": "rotor takes s exp(-(w/ws)^2) tanh(w/0.01) over Tc tanh(w/0.01)"},
        "expected": {"s": s, "ws": ws}}


def viscous_load(bx: float) -> Effect:
    """Extra viscous friction ``bx`` [N*m*s/rad] on the turntable (a grease-packed
    bearing)."""
    return {"Bx_load": bx}, {
        "effect": "viscous-friction", "target": "load", "targets": ["load"],
        "parameters": {"B_extra_Nms_rad": bx}, "expected": {"b": bx},
        "also_accept": [{"effect": "viscous-friction", "targets": ["rotor"],
                         "expected": {"b": bx / N**2}}]}


def inertia_load(dj: float) -> Effect:
    """The turntable's inertia off by a factor 1 + ``dj`` [1] (a fixture the netlist lacks):
    the catalog reports it as a correction of Jo (or of Jr, dj Jl/(N^2 Jm))."""
    return {"p": {"Jl": P["Jl"] * (1.0 + dj)}}, {
        "effect": "inertia", "target": "Jo", "targets": ["Jo"], "correction": True,
        "parameters": {"Jl_true_kgm2": P["Jl"] * (1.0 + dj), "dJ": dj},
        "expected": {"dJ": dj},
        "also_accept": [{"effect": "inertia", "targets": ["Jr"],
                         "expected": {"dJ": dj * JL_OVER_JM}}]}


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


def split_fx(fx: Fx) -> tuple[Fx, dict[str, float]]:
    """(simulator effects, motor parameters) of a merged fx: a ``p`` entry overrides the
    declared values."""
    fx = dict(fx)
    return fx, {**P, **fx.pop("p", {})}


# ---------------------------------------------------------------------- the record list

def _rec(rid: str, cls: str, regime: str, parts: tuple[Effect, ...] = (),
         noise: dict[str, dict[str, Any]] | None = None, note: str = "",
         marginal: Callable[[float], tuple[Effect, ...]] | None = None) -> dict[str, Any]:
    """One record's spec (noise None: the regime's default white noise). ``marginal``: the
    record's effects as a function of their size, scaled in ``make`` until the best probe's
    signature is MARGINAL_SIGMA (``parts`` then holds them at a trial size)."""
    fx, effects = add(*parts)
    return {"id": rid, "class": cls, "regime": regime, "fx": fx, "effects": effects,
            "noise": noise, "note": note, "marginal": marginal}


def _outside_records() -> list[dict[str, Any]]:
    """The four records whose effect the catalog cannot name."""
    return [
        _rec("e11", "outside", "slow", (outside(
            "magnet-heating", {"magnet_heating": (0.05, 2.5)},
            {"delta": 0.05, "tau_s": 2.5,
             "form": "k(t) = k (1 - delta (1 - exp(-t/tau))) in the EMF and the torque"}),),
            note="the magnets warm up: the motor constant falls by 5 % with a 2.5 s time "
                 "constant. A person sees the speed creep up at a fixed voltage and the no-load "
                 "current rise, growing through the record; a resistance warm-up would slow the "
                 "motor instead, and a constant change of k does not grow"),
        _rec("e12", "outside", "fast", (outside(
            "belt-efficiency", {"belt_eta": 0.85},
            {"eta": 0.85, "form": "the motor supplies Q/(eta N) while it drives the "
                                  "turntable, eta Q/N while the turntable drives it; Q the "
                                  "turntable's demand Jl dw_l/dt + bl w_l"}),),
            noise={"current": {"white": 5e-3, "quant": 0.01}, "speed": {"white": 0.1}},
            note="a belt of 85 % efficiency: a friction proportional to the torque it "
                 "carries. A person sees the run-up slower (an inertia 18 % too high, a "
                 "viscous friction too), but the braking after 150 ms faster than either would "
                 "allow: the turntable looks heavier when driven and lighter when it drives"),
        _rec("e13", "outside", "slow", (outside(
            "inertia-step", {"inertia_step": (5.0, 0.6 * P["Jl"])},
            {"t_s": 5.0, "dJ_kgm2": 0.6 * P["Jl"],
             "form": "Jl -> 1.6 Jl from t = 5 s (the turntable stands still from 4.7 s)"}),),
            noise={"current": {"ar1": [5e-3, 0.8]}, "speed": {"white": 0.1},
                   "load_speed": {"white": 0.03}},
            note="a part (+60 % of the turntable's inertia) is set on the turntable while "
                 "it stands still at 5 s: only the last run-up (5.32 s) is slower. A person "
                 "sees every run-up and braking before 5 s fit the declared inertia and the "
                 "last run-up lag it"),
        _rec("e14", "outside", "fast", (outside(
            "iron-loss", {"iron_loss": 1e-6},
            {"c_Nm_per_rad_s_1_5": 1e-6,
             "form": "rotor takes c |w|^1.5 sign(w) (eddy currents and hysteresis)"}),),
            note="iron loss in the rotor growing as w^1.5 (8 mN m at 400 rad/s, four times "
                 "the brush friction). A person sees the current at the end of the 12 V run-up "
                 "0.68 A instead of 0.45 A, the speed 13 rad/s lower, and the loss bending "
                 "with speed: a viscous plus a Coulomb friction fit it to within a few per "
                 "cent, not exactly"),
    ]


def record_specs() -> list[dict[str, Any]]:
    """The records of fresh5: id, class, regime, fx, truth effects, noise, note, seed."""
    S = [
        _rec("e01", "null", "fast", note="white noise"),
        _rec("e02", "null", "slow",
             noise={"current": {"ar1": [4e-3, 0.9], "quant": 5e-3},
                    "speed": {"pink": 0.15, "quant": 0.2},
                    "load_speed": {"white": 0.03, "quant": 0.05}},
             note="AR(1) current noise (phi 0.9), 1/f motor-speed noise; ADC steps 5 mA, "
                  "0.2 rad/s, 0.05 rad/s"),
        _rec("e03", "catalog", "slow", (stribeck(3e-3, 3.0),),
             note="a breakaway peak of the brush friction: 3 mN m over the declared 2 mN m, "
                  "fading over 3 rad/s (the creep at 0.25 V and the slow reversal)"),
        _rec("e04", "catalog", "fast", (saturation(2.5, 0.45),),
             noise={"current": {"white": 5e-3, "quant": 0.01}, "speed": {"white": 0.1}},
             note="the armature inductance saturating: half way down at 2.5 A, to 45 %"),
        _rec("e05", "catalog", "fast", (source_resistance("fast", 0.01),),
             marginal=lambda a: (source_resistance("fast", a),),
             note="a weak supply: internal resistance scaled to a 25 sigma signature "
                  "(marginal)"),
        _rec("e06", "catalog", "slow", (sensor("current", "offset", 0.012),),
             noise={"current": {"white": 5e-3}, "speed": {"pink": 0.1},
                    "load_speed": {"white": 0.03}},
             note="a current-sense amplifier offset of 12 mA"),
        _rec("e07", "catalog", "slow", (drift(0.012),),
             noise={"current": {"white": 5e-3, "quant": 0.01}, "speed": {"white": 0.1},
                    "load_speed": {"white": 0.03, "quant": 0.05}},
             note="the armature warming: Ra + 1.2 %/s, straight (+7.2 % at 6 s)"),
        _rec("e08", "catalog", "fast", (inertia_load(0.01),),
             marginal=lambda a: (inertia_load(a),),
             note="the turntable's inertia a little off (a fixture the netlist lacks), scaled "
                  "to a 25 sigma signature (marginal); a correction of Jo"),
        _rec("e09", "two", "slow", (brush_drop(0.3), viscous_load(6e-5)),
             note="carbon brushes 0.3 V and a grease-packed turntable bearing 6e-5 N m s/rad "
                  "(+150 % of bl)"),
        _rec("e10", "two", "fast", (inertia_load(0.4), sensor("current", "offset", 0.015)),
             noise={"current": {"white": 5e-3}, "speed": {"white": 0.05, "pink": 0.1}},
             note="a fixture on the turntable (+40 % of its inertia, a correction of Jo) and "
                  "a current-sense offset of 15 mA"),
        *_outside_records(),
    ]
    for j, s in enumerate(S):
        s["seed"] = 6000 + j
    return S


# ---------------------------------------------------------------------- generation

#: scalar catalog effects a record's imprint is compared with (label, fx, parameter
#: overrides), each small enough for its imprint to be linear in it. A torque on the rotor is
#: one on the turntable (the belt is rigid), so the rotor's stand for both.
ALTERNATIVES: tuple[tuple[str, Fx, dict[str, float]], ...] = (
    ("series-resistance", {"Rser": 1e-3}, {}),
    ("brush-drop", {"Vb": 1e-3, "Vb_eps": 1e-3}, {}),
    ("coulomb-friction", {}, {"Tc": P["Tc"] + 1e-5}),
    ("viscous-friction", {}, {"bm": P["bm"] + 1e-7}),
    ("force-offset", {"T_load": 3e-5}, {}),
    ("stribeck-friction:0.3", {"stribeck": (1e-5, 0.3)}, {}),
    ("stribeck-friction:1", {"stribeck": (1e-5, 1.0)}, {}),
    ("stribeck-friction:3", {"stribeck": (1e-5, 3.0)}, {}),
    ("stribeck-friction:10", {"stribeck": (1e-5, 10.0)}, {}),
    ("inductance", {}, {"L": P["L"] * 1.001}),
    ("inductor-saturation:1", {"lsat": (1.0, 0.999)}, {}),
    ("inductor-saturation:3", {"lsat": (3.0, 0.999)}, {}),
    ("inertia", {}, {"Jl": P["Jl"] * 1.001}),
    ("resistance-drift:linear", {"alpha": 1e-4}, {}),
)
#: warm-ups Ra (1 + rise (1 - exp(-t/tau))) with tau these fractions of the record
WARMUP_FRACTIONS = (0.1, 0.3, 1.0)

IMPRINTS = recordkit.Imprints(se.simulate, WHITE)
null, signature, imprint = IMPRINTS.null, IMPRINTS.signature, IMPRINTS.imprint
_ALTS: dict[str, dict[str, np.ndarray]] = {}


def alternative_imprints(regime: str) -> dict[str, np.ndarray]:
    """Imprints of ALTERNATIVES, of Ra's warm-ups and of each probe's sensor gain, offset and
    delay (cached per regime)."""
    if regime in _ALTS:
        return _ALTS[regime]
    dur = se.REGIMES[regime][1]
    out = {}
    for label, fx, over in ALTERNATIVES:
        out[label] = imprint(regime, se.simulate(regime, None, fx, {**P, **over}))
    for f in WARMUP_FRACTIONS:
        fx = {"warmup": (1e-3, f * dur)}
        out[f"resistance-drift:warmup-{f:g}"] = imprint(regime, se.simulate(regime, None, fx))
    for probe in se.PROBES[regime]:
        for kind, val in (("gain", 1.001), ("offset", 1e-3), ("delay", 1e-6)):
            fx = {"sensor": {probe: {kind: val}}}
            out[f"sensor-{kind}:{probe}"] = imprint(regime, se.simulate(regime, None, fx))
    _ALTS[regime] = out
    return out


def _effect_kind(label: str) -> str:
    """The catalog id of an alternative's label."""
    return label.split(":")[0]


def unexplained(regime: str, clean: dict[str, np.ndarray]) -> dict[str, Any]:
    """How much of an outside record's imprint the catalog's scalar effects leave, in white
    sigmas (linearised at the null): after the best single one, and after the least-squares
    combination of all of them together (a lower bound of what any catalog fit leaves)."""
    tr = imprint(regime, clean)
    alts = alternative_imprints(regime)
    single = {k: float(np.linalg.norm(tr - (tr @ a / (a @ a)) * a)) for k, a in alts.items()}
    best = min(single, key=single.__getitem__)
    x = np.column_stack(list(alts.values()))
    coef, *_ = np.linalg.lstsq(x, tr, rcond=None)
    return {"imprint": float(np.linalg.norm(tr)), "best_single": [best, single[best]],
            "all_scalar_effects_jointly": float(np.linalg.norm(tr - x @ coef))}


def separation(regime: str, clean: dict[str, np.ndarray], same: set[str]) -> dict[str, float]:
    """A marginal record's distance from each other catalog effect (not in ``same``: the
    truth's id and its also_accept labels): ||truth's imprint - the best-scaled
    alternative's|| in white sigmas, the smallest per catalog id."""
    tr = imprint(regime, clean)
    out: dict[str, float] = {}
    for label, a in alternative_imprints(regime).items():
        kind = _effect_kind(label)
        if kind in same:
            continue
        d = float(np.linalg.norm(tr - (tr @ a / (a @ a)) * a))
        out[kind] = min(out.get(kind, np.inf), d)
    return out


def truth_entry(spec: dict[str, Any], sig: dict[str, float]) -> dict[str, Any]:
    """The record's truth.json entry (the schema of the other splits)."""
    regime = spec["regime"]
    fs, dur = se.REGIMES[regime]
    ns = recordkit.noise_or_white(spec, WHITE)
    return {
        "id": spec["id"], "class": spec["class"], "split": SPLIT, "motor": MOTOR,
        "netlist": NETLIST[regime], "regime": regime, "sample_rate_Hz": fs,
        "duration_s": dur, "csv": f"benchmarks/diagnosis/records/{spec['id']}.csv",
        "probes": list(se.PROBES[regime]), "inputs": ["u"] if regime == "slow" else [],
        "free": [], "declared_error": {}, "noise": ns, "noise_text": recordkit.noise_text(ns),
        "seed": spec["seed"], "effects": spec["effects"], "declared_terms": [],
        "signature_sigma": sig, "marginal": spec["marginal"] is not None,
        "note": spec["note"],
    }


def clean_of(regime: str, fx: Fx) -> dict[str, np.ndarray]:
    """Noise-free probes of the model with the merged effects ``fx``."""
    sim_fx, p = split_fx(fx)
    return se.simulate(regime, None, sim_fx, p)


def scale_marginal(spec: dict[str, Any]) -> None:
    """Scale a marginal record's effects until the best probe's signature is MARGINAL_SIGMA
    (the imprint is linear at these sizes; one correction step)."""
    regime = spec["regime"]
    trial = next(iter(spec["effects"][0]["expected"].values()))
    for _ in range(2):
        best = max(signature(regime, clean_of(regime, spec["fx"])).values())
        trial *= MARGINAL_SIGMA / best
        spec["fx"], spec["effects"] = add(*spec["marginal"](float(f"{trial:.4g}")))


def make(spec: dict[str, Any], write: bool) -> dict[str, Any]:
    """Simulate one record, write its CSV (``write``), return its truth entry."""
    regime = spec["regime"]
    if spec["marginal"] is not None:
        scale_marginal(spec)
    t = se.grid(regime)
    clean = clean_of(regime, spec["fx"])
    entry = truth_entry(spec, signature(regime, clean))
    if spec["class"] == "outside":
        entry["unexplained_sigma"] = unexplained(regime, clean)
    if spec["marginal"] is not None:
        truth = spec["effects"][0]
        same = {truth["effect"], *(a["effect"] for a in truth.get("also_accept", []))}
        entry["separation_sigma"] = separation(regime, clean, same)
    if write:
        rng = np.random.default_rng(spec["seed"])
        ns = recordkit.noise_or_white(spec, WHITE)
        cols = {p: se.add_noise(rng, clean[p], ns[p]) for p in se.PROBES[regime]}
        if "u" in clean:
            cols["u"] = clean["u"]
        RECORDS.mkdir(exist_ok=True)
        recordkit.write_csv(RECORDS / f"{spec['id']}.csv", t, cols)
    return entry


def main(argv: list[str] | None = None) -> int:
    return recordkit.main(argv, __doc__, record_specs, make, "E")


if __name__ == "__main__":
    sys.exit(main())
