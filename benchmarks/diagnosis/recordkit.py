"""What the record generators of the later sets share (``make_records_d.py`` ...
``make_records_n.py``): the noise's text, the merging of effects' simulator keys
(``combine``), a jittered acquisition's sample times, an effect's imprint on a set's null run
(``Imprints``), the writers of a record's CSV and of truth.json, and the command line. Each
set's simulator and its records stay in its own modules, written independently; nothing here
imports circuitsim, and nothing is simulated here but by a set's own simulator.

truth.json is merged under an exclusive lock (``.truth.lock``: several generators may merge
their own ids at once): every other entry is kept, an entry with the same id is replaced in
place, a new one is appended, and the file is replaced atomically. A CSV is written to a
temporary name and moved into place, so an interrupted run leaves no half-written record.
"""

from __future__ import annotations

import argparse
import fcntl
import json
import math
import os
import tempfile
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
RECORDS = HERE / "records"
TRUTH = HERE / "truth.json"
LOCK = HERE / ".truth.lock"


#: the simulator keys whose values several effects' fragments merge per target (a sensor's
#: settings per probe, cogging orders appended to a shaft's list, a friction per shaft)
NESTED = ("sensor", "p", "cog", "coul", "visc", "offset", "stribeck")


def combine(parts: Iterable[tuple[dict, dict]], nested: tuple[str, ...] = NESTED
            ) -> tuple[dict, list]:
    """The simulator's fx of several effects (each part a fragment of simulator keys and its
    truth entry), the ``nested`` keys merged per target, and their truth entries."""
    fx: dict = {}
    effects = []
    for frag, eff in parts:
        for key, val in frag.items():
            if key not in nested:
                fx[key] = val
                continue
            merged = dict(fx.get(key, {}))
            for sub, v in val.items():
                if key == "sensor":
                    merged[sub] = {**merged.get(sub, {}), **v}
                elif key == "cog":
                    merged[sub] = [*merged.get(sub, []), *v]
                else:
                    merged[sub] = v
            fx[key] = merged
        effects.append(eff)
    return fx, effects


def outside(kind: str, fx: dict, params: dict) -> tuple[dict, dict]:
    """An effect outside the catalog: its simulator keys ``fx`` and its truth entry (its
    ``params`` and its law in words), which no catalog label matches."""
    return fx, {"effect": f"outside:{kind}", "target": None, "targets": None,
                "parameters": params, "expected": {}}


def spec(rid: str, cls: str, regime: str, uneven: bool,
         parts: Sequence[tuple[dict, dict]] = (), noise: dict | None = None, note: str = "",
         marginal: Callable[[float], Sequence[tuple[dict, dict]]] | None = None,
         size: float | None = None) -> dict[str, Any]:
    """One record's specification (the generators of motors P to T): its effects' parts
    combined (``combine``), the noise, the note, and for a marginal record the function
    that makes its parts at a size."""
    fx, effects = combine(parts)
    return {"id": rid, "class": cls, "regime": regime, "uneven": uneven, "fx": fx,
            "parts": tuple(parts), "effects": effects, "noise": noise, "note": note,
            "marginal": marginal, "size": size}


def declared_spec(rid: str, cls: str, regime: str, uneven: bool, parts=(), noise=None,
                  note: str = "", marginal=None, size=None, *, probes: Sequence[str],
                  free: Mapping[str, float] | None, params: Mapping[str, float],
                  twins: Mapping[str, Iterable[tuple[str, str | None]]],
                  mixed_signs: bool = False) -> dict[str, Any]:
    """A record's specification (``spec``) for a set whose netlist declares some values
    wrong: the probes it gives the diagnosis and the declared parameters it frees with their
    true values (``free``: name -> relative error of the true value over the declared
    ``params``, 2-6 %, two or three of them, of both signs when ``mixed_signs``, to four
    significant digits). Refused: an effect that is a freed parameter's twin (``twins``:
    name -> (effect, target or None)) or that changes a freed parameter."""
    s = spec(rid, cls, regime, uneven, parts, noise, note, marginal, size)
    s["probes"] = tuple(probes)
    free = dict(free or {})
    if not 2 <= len(free) <= 3 or not all(0.02 <= abs(e) <= 0.06 for e in free.values()):
        raise ValueError(f"{rid}: frees {free}")
    if mixed_signs and len({e > 0 for e in free.values()}) < 2:
        raise ValueError(f"{rid}: the declared errors all have one sign")
    s["free"] = free
    s["ptrue"] = {name: float(f"{params[name] * (1.0 + e):.4g}") for name, e in free.items()}
    for name in free:
        for _, e in s["parts"]:
            if (e["effect"], e["target"]) in twins[name] or \
                    (e["effect"], None) in twins[name]:
                raise ValueError(f"{rid}: {e['effect']} on {e['target']} twins freed {name}")
        for frag, _ in s["parts"]:
            if name in frag.get("p", {}):
                raise ValueError(f"{rid}: an effect changes the freed {name}")
    return s


def jittered_times(rng: np.random.Generator, fs: float, duration: float, jitter: float,
                   step: float = 1e-9) -> np.ndarray:
    """A fast acquisition's times [s]: the grid k/fs [Hz], each time but the first moved by
    a uniform random jitter within +-``jitter`` [1] of the interval (the last one only
    earlier), rounded to ``step`` [s]. Monotonic for ``jitter`` < 0.5. Sampling, not
    physics: each set's simulator is run at these times."""
    n = round(fs * duration) + 1
    dt = 1.0 / fs
    move = rng.uniform(-jitter, jitter, n) * dt
    move[0] = 0.0
    move[-1] = -abs(move[-1])
    t = np.round((np.arange(n) * dt + move) / step) * step
    if np.any(np.diff(t) <= 0.0):
        raise ValueError("jittered times are not increasing")
    return t


def logger_times(rng: np.random.Generator, fs: float, duration: float, drops: int
                 ) -> tuple[np.ndarray, np.ndarray]:
    """A logger's times [s] and the times it dropped [s]: intervals of 0.6 + 0.8 Beta(3, 3)
    [1] times the mean 1/fs [Hz] (0.6-1.4 times it), from 0 to at most ``duration`` [s],
    rounded to 1 us; ``drops`` interior samples removed, at least seven apart (as motor Q's
    generator writes it; motor R's uses this one)."""
    gaps = (0.6 + 0.8 * rng.beta(3.0, 3.0, int(1.2 * duration * fs))) / fs
    t = np.round(np.concatenate([[0.0], np.cumsum(gaps)]) * 1e6) / 1e6
    t = t[t <= duration]
    pick = np.sort(rng.choice(np.arange(7, t.size - 7, 7), drops, replace=False))
    return np.delete(t, pick), t[pick]


def tidy_times(t: np.ndarray) -> np.ndarray:
    """The times exactly as the CSV holds them (10 significant digits) [s]."""
    return np.array([float(f"{x:.10g}") for x in t])


def record_times(s: dict[str, Any], regimes: Mapping[str, tuple[float, float]],
                 grid: Callable[[str], np.ndarray], salt: int,
                 jitter_range: tuple[float, float], drop_range: tuple[int, int]
                 ) -> np.ndarray:
    """Record ``s``'s sample times [s], once (kept in ``s["t"]``, described in
    ``s["timestamps"]``): the regime's even ``grid``; or, uneven, from the seed and ``salt``,
    a jittered fast grid (a jitter drawn in ``jitter_range`` of the interval) or a logger's
    slow times with a count drawn in ``drop_range`` dropped. ``regimes``: (fs [Hz],
    duration [s]) per regime."""
    if "t" in s:
        return s["t"]
    fs, dur = regimes[s["regime"]]
    rng = np.random.default_rng([s["seed"], salt])
    if not s["uneven"]:
        t = grid(s["regime"])
        s["timestamps"] = f"even: k/fs, fs = {fs:g} Hz"
    elif s["regime"] == "fast":
        jitter = round(float(rng.uniform(*jitter_range)), 3)
        t = jittered_times(rng, fs, dur, jitter)
        s["timestamps"] = (
            f"jittered: the nominal {fs / 1e3:g} kHz grid k/fs, every sample time but the "
            f"first moved by a uniform random jitter within +-{jitter:.1%} of the "
            f"{1e6 / fs:g} us interval (the last one only earlier), rounded to 1 ns; "
            f"intervals {np.diff(t).min() * 1e6:.2f}-{np.diff(t).max() * 1e6:.2f} us")
    else:
        drops = int(rng.integers(drop_range[0], drop_range[1] + 1))
        t, gone = logger_times(rng, fs, dur, drops)
        s["timestamps"] = (
            f"jittered: a data logger's irregular intervals, 0.6 + 0.8 Beta(3, 3) times the "
            f"mean {1e3 / fs:.3g} ms, from 0 to {t[-1]:.4f} s, rounded to 1 us; {drops} "
            "samples dropped (at " + ", ".join(f"{x:.4f}" for x in gone)
            + f" s); intervals {np.diff(t).min() * 1e3:.3f}-{np.diff(t).max() * 1e3:.3f} ms")
    s["t"] = tidy_times(t)
    return s["t"]


def noise_text(ns: Mapping[str, Mapping[str, Any]]) -> str:
    """The record's noise in words, per probe (white, AR(1), 1/f, ADC step)."""
    words = []
    for probe, d in ns.items():
        bits = []
        if d.get("white"):
            bits.append(f"white sigma {d['white']:g}")
        if d.get("ar1"):
            bits.append(f"AR(1) sigma {d['ar1'][0]:g} phi {d['ar1'][1]:g}")
        if d.get("pink"):
            bits.append(f"1/f sigma {d['pink']:g}")
        if d.get("quant"):
            bits.append(f"ADC step {d['quant']:g}")
        words.append(f"{probe}: " + ", ".join(bits))
    return "; ".join(words)


def noise_or_white(spec: Mapping[str, Any], white: Mapping[str, Mapping[str, float]]
                   ) -> dict[str, dict[str, Any]]:
    """The record's noise per probe: its own, else white noise of the regime's ``white``
    sigma [probe unit] on each probe."""
    if spec["noise"] is not None:
        return spec["noise"]
    return {p: {"white": s} for p, s in white[spec["regime"]].items()}


#: each probe's sensor effects an imprint is compared with: (kind, size) [1, probe unit, s]
SENSOR_STEPS = (("gain", 1.001), ("offset", 1e-3), ("delay", 1e-5))


class Imprints:
    """One set's null runs and what an effect changes in them, per regime: in each probe, in
    units of that probe's white noise sigma (the effect's *imprint*). ``simulate(regime)``
    gives the declared model's clean probes; ``white`` per regime, per probe, the sigma
    [probe unit]. The set's own simulator makes every run; nothing here changes a number."""

    def __init__(self, simulate: Callable[[str], Mapping[str, np.ndarray]],
                 white: Mapping[str, Mapping[str, float]]):
        self._simulate, self.white = simulate, white
        self._held: dict[tuple[str, str], Any] = {}

    def null(self, regime: str) -> Mapping[str, np.ndarray]:
        """The declared model's clean probes (one run a regime)."""
        if ("null", regime) not in self._held:
            self._held["null", regime] = self._simulate(regime)
        return self._held["null", regime]

    def signature(self, regime: str, clean: Mapping[str, np.ndarray]) -> dict[str, float]:
        """||effect - null|| / white sigma, per probe [1]."""
        return {p: float(np.linalg.norm(clean[p] - self.null(regime)[p]) / s)
                for p, s in self.white[regime].items()}

    def imprint(self, regime: str, clean: Mapping[str, np.ndarray]) -> np.ndarray:
        """The probes' difference from the null in white-noise sigmas, concatenated [1]."""
        return np.concatenate([(clean[p] - self.null(regime)[p]) / s
                               for p, s in self.white[regime].items()])

    def of_effects(self, regime: str, run: Callable[[dict], Mapping[str, np.ndarray]],
                   effects: Iterable[tuple[str, dict]], probes: Iterable[str],
                   duration: float, sensors: Iterable[tuple[str, float]] = SENSOR_STEPS,
                   columns: bool = False) -> dict[str, np.ndarray]:
        """Label -> imprint of each small catalog effect ``(label, fx)`` run by ``run(fx)``
        (a warm-up's time constant given as a fraction of the record's ``duration`` [s]), then
        of each probe's sensor effects; as (n, 1) columns with ``columns``. Once a regime."""
        if ("effects", regime) not in self._held:
            out = {}
            for label, fx in effects:
                if "warmup" in fx:
                    fx = {**fx, "warmup": (fx["warmup"][0], fx["warmup"][1] * duration)}
                out[label] = self.imprint(regime, run(fx))
            for probe in probes:
                for kind, v in sensors:
                    out[f"sensor-{kind}:{probe}"] = self.imprint(
                        regime, run({"sensor": {probe: {kind: v}}}))
            self._held["effects", regime] = {k: v[:, None] for k, v in out.items()} \
                if columns else out
        return self._held["effects", regime]

    def of_harmonics(self, regime: str, run: Callable[[dict], Mapping[str, np.ndarray]],
                     effects: Iterable[tuple[str, Callable[[float, float], dict]]],
                     size: Callable[[str], float]) -> dict[str, np.ndarray]:
        """Label -> (n, 2) imprints of each angle-locked effect ``(label, build)``: its sine
        and its cosine of ``size(label)`` each (``build(a, b)`` gives the fx). Once a regime."""
        if ("harmonics", regime) not in self._held:
            self._held["harmonics", regime] = {
                label: np.column_stack([self.imprint(regime, run(build(size(label), 0.0))),
                                        self.imprint(regime, run(build(0.0, size(label))))])
                for label, build in effects}
        return self._held["harmonics", regime]

    def unexplained(self, regime: str, clean: Mapping[str, np.ndarray],
                    alts: Mapping[str, np.ndarray]) -> dict[str, Any]:
        """What the effects ``alts`` (label -> their imprints' columns) leave of the
        imprint of ``clean`` [white sigma], linearised at the null: after the best single
        one, and after all of them at once (least squares)."""
        y = self.imprint(regime, clean)
        rest = {k: left(y, a) for k, a in alts.items()}
        best = min(rest, key=rest.__getitem__)
        return {"imprint": float(np.linalg.norm(y)), "best_single": [best, rest[best]],
                "all_scalar_effects_jointly": left(y, np.column_stack(list(alts.values()))),
                "note": "linearised; alternatives: " + ", ".join(alts)}

    def separation(self, regime: str, clean: Mapping[str, np.ndarray],
                   alts: Mapping[str, np.ndarray], same: set[str]) -> dict[str, float]:
        """Distance [white sigma] of the imprint of ``clean`` from each kind of effect in
        ``alts`` but those ``same`` (the record's own), best-scaled."""
        y = self.imprint(regime, clean)
        out: dict[str, float] = {}
        for label, a in alts.items():
            kind = label.split(":")[0]
            if kind not in same:
                out[kind] = min(out.get(kind, math.inf), left(y, a))
        return out


@dataclass(frozen=True)
class Plumbing:
    """What the later sets' generators share beyond their physics (``make_records_l.py``
    ... ``make_records_o.py``): a record's truth entry, its marginal scaling, the catalog's
    imprints it is compared with, its noisy CSV. A set gives its own names, netlists and
    default white noise [probe unit], its simulator module (``REGIMES``, ``PROBES``,
    ``add_noise``), its clean run ``sim(regime, t, fx)`` at times ``t`` [s], a record's times
    ``times(spec)`` [s], the small catalog effects an imprint is compared with (the sizes of
    the angle-locked ones by label), and the size of a marginal record's signature [white
    sigma]."""

    split: str
    motor: str
    netlist: Mapping[str, str]
    white: Mapping[str, Mapping[str, float]]
    simulator: Any
    sim: Callable[[str, np.ndarray, dict], dict[str, np.ndarray]]
    times: Callable[[dict[str, Any]], np.ndarray]
    scalar_effects: Sequence[tuple[str, dict]]
    harmonic_effects: Sequence[tuple[str, Callable[[float, float], dict]]]
    harmonic_size: Callable[[str], float]
    marginal_sigma: float
    sensor_steps: Sequence[tuple[str, float]] = SENSOR_STEPS
    #: the harmonic terms the set's netlist declares (truth's ``declared_terms``)
    declared: Sequence[dict[str, Any]] = ()
    #: what else a record's entry holds, from its spec (e.g. motor M's ``location_sigma``)
    extra: Callable[[dict[str, Any]], dict[str, Any]] | None = None

    def imprints(self, s: dict[str, Any]) -> Imprints:
        """The null run and the imprints on the record's own times, once a record."""
        if "imprints" not in s:
            t = self.times(s)
            s["imprints"] = Imprints(lambda regime: self.sim(regime, t, {}), self.white)
        return s["imprints"]

    def alternatives(self, s: dict[str, Any]) -> dict[str, np.ndarray]:
        """Label -> (n, 1) imprint of each scalar catalog effect, per unit size, linearised."""
        regime, t = s["regime"], self.times(s)
        return self.imprints(s).of_effects(
            regime, lambda fx: self.sim(regime, t, fx), self.scalar_effects,
            self.simulator.PROBES[regime], self.simulator.REGIMES[regime][1],
            self.sensor_steps, columns=True)

    def harmonic_alternatives(self, s: dict[str, Any]) -> dict[str, np.ndarray]:
        """Label -> (n, 2) imprints of each angle-locked catalog effect."""
        regime, t = s["regime"], self.times(s)
        return self.imprints(s).of_harmonics(regime, lambda fx: self.sim(regime, t, fx),
                                             self.harmonic_effects, self.harmonic_size)

    def scale_marginal(self, s: dict[str, Any]) -> None:
        """Scale a marginal record's size so that its best probe's signature is the set's
        marginal size on its own times (about linear in its size; two passes)."""
        size = s["size"]
        for _ in range(2):
            clean = self.sim(s["regime"], self.times(s), s["fx"])
            best = max(self.imprints(s).signature(s["regime"], clean).values())
            size = float(f"{size * self.marginal_sigma / best:.4g}")
            s["parts"] = tuple(s["marginal"](size))
            s["fx"], s["effects"] = combine(s["parts"])
        s["size"] = size

    def truth_entry(self, s: dict[str, Any], sig: dict) -> dict:
        """The record's entry of truth.json."""
        regime, t = s["regime"], self.times(s)
        ns = noise_or_white(s, self.white)
        entry = {
            "id": s["id"], "class": s["class"], "split": self.split, "motor": self.motor,
            "netlist": self.netlist[regime], "regime": regime,
            "sample_rate_Hz": float((t.size - 1) / (t[-1] - t[0])),
            "duration_s": self.simulator.REGIMES[regime][1],
            "csv": f"benchmarks/diagnosis/records/{s['id']}.csv",
            "probes": list(self.simulator.PROBES[regime]),
            "inputs": ["u"] if regime == "slow" else [], "free": [], "declared_error": {},
            "noise": ns, "noise_text": noise_text(ns), "seed": s["seed"]}
        if "timestamps" in s:
            entry["timestamps"] = s["timestamps"]
        entry.update({
            "samples": int(t.size), "effects": s["effects"],
            "declared_terms": list(self.declared), "signature_sigma": sig,
            "marginal": s["marginal"] is not None, "note": s["note"]})
        return entry

    def make(self, s: dict[str, Any], write: bool) -> dict:
        """One record: its truth entry, and its CSV when ``write``."""
        regime, t = s["regime"], self.times(s)
        if s["marginal"] is not None:
            self.scale_marginal(s)
        clean = self.sim(regime, t, s["fx"])
        imp = self.imprints(s)
        entry = self.truth_entry(s, imp.signature(regime, clean))
        if s["class"] == "outside":
            entry["unexplained_sigma"] = imp.unexplained(
                regime, clean, {**self.alternatives(s), **self.harmonic_alternatives(s)})
        if s["marginal"] is not None:
            e = s["effects"][0]
            same = {e["effect"], *(a["effect"] for a in e.get("also_accept", []))}
            entry["separation_sigma"] = imp.separation(regime, clean, self.alternatives(s),
                                                       same)
        if self.extra is not None:
            entry.update(self.extra(s))
        if write:
            rng = np.random.default_rng(s["seed"])
            ns = noise_or_white(s, self.white)
            cols = {p: self.simulator.add_noise(rng, t, clean[p], ns[p])
                    for p in self.simulator.PROBES[regime]}
            if regime == "slow":
                cols["u"] = clean["u"]
            RECORDS.mkdir(exist_ok=True)
            write_csv(RECORDS / f"{s['id']}.csv", t, cols)
        return entry


@dataclass(frozen=True)
class DeclaredOff(Plumbing):
    """Plumbing for records whose netlist declares some parameters wrong (fresh45 on): every
    run is at the record's TRUE values (``run``); the signatures, the marginal scaling, the
    imprints of the catalog's effects (and of the sensors of the probes given only) and of
    the freed parameters, and the CSV are those of the record's own ``probes``."""

    #: the record's clean probes at its TRUE values: run(spec, fx, times=None)
    run: Callable[..., Mapping[str, np.ndarray]] | None = None
    #: the record's clean probes at the netlist's DECLARED values: declared_run(spec)
    declared_run: Callable[[dict[str, Any]], Mapping[str, np.ndarray]] | None = None
    #: the netlist's declared parameter values [SI]
    params: Mapping[str, float] = field(default_factory=dict)
    #: the small catalog effects an imprint is compared with, at the given true values
    effects_of: Callable[[Mapping[str, float]], Sequence[tuple[str, dict]]] | None = None
    #: a freed parameter's relative step for its imprint column
    free_step: float = 0.01
    #: recordkit.places_entry's places, inertias and far side of the compliance
    places: Mapping[str, float] = field(default_factory=dict)
    inertias: Mapping[str, tuple[str, float]] = field(default_factory=dict)
    beyond: Iterable[str] = ()

    def white_of(self, s: dict[str, Any]) -> dict[str, dict[str, float]]:
        """The white sigma [probe unit] of the record's probes, in its regime."""
        return {s["regime"]: {p: self.white[s["regime"]][p] for p in s["probes"]}}

    def imprints(self, s: dict[str, Any]) -> Imprints:
        """The TRUE null run and the imprints on the record's own times and probes, once."""
        if "imprints" not in s:
            s["imprints"] = Imprints(lambda regime: self.run(s, {}), self.white_of(s))
        return s["imprints"]

    def alternatives(self, s: dict[str, Any]) -> dict[str, np.ndarray]:
        """Label -> (n, 1) imprint of each scalar catalog effect, per unit size, linearised
        at the true null (the sensor effects of the record's probes only)."""
        p = {**self.params, **s["ptrue"]}
        return self.imprints(s).of_effects(
            s["regime"], lambda fx: self.run(s, fx), self.effects_of(p), s["probes"],
            self.simulator.REGIMES[s["regime"]][1], self.sensor_steps, columns=True)

    def harmonic_alternatives(self, s: dict[str, Any]) -> dict[str, np.ndarray]:
        """Label -> (n, 2) imprints of each angle-locked catalog effect."""
        return self.imprints(s).of_harmonics(s["regime"], lambda fx: self.run(s, fx),
                                             self.harmonic_effects, self.harmonic_size)

    def freed(self, s: dict[str, Any]) -> dict[str, np.ndarray]:
        """``free:<name>`` -> (n, 1) imprint of a ``free_step`` relative step of each freed
        parameter about its true value, once."""
        if "freed" not in s:
            imp = self.imprints(s)
            s["freed"] = {
                f"free:{name}": imp.imprint(s["regime"], self.run(
                    s, {"p": {name: value * (1.0 + self.free_step)}}))[:, None]
                for name, value in s["ptrue"].items()}
        return s["freed"]

    def declared_signature(self, s: dict[str, Any]) -> dict[str, float]:
        """The declared errors' signature: the true null against the declared one, per
        probe [white sigma]."""
        dec, true = self.declared_run(s), self.imprints(s).null(s["regime"])
        return {p: float(np.linalg.norm(true[p] - dec[p]) / w)
                for p, w in self.white_of(s)[s["regime"]].items()}

    def free_separation(self, s: dict[str, Any]) -> list[dict[str, Any]]:
        """Each truth effect's own imprint (run alone) against the freed parameters' columns
        jointly, best-scaled [white sigma]."""
        imp, cols = self.imprints(s), np.column_stack(list(self.freed(s).values()))
        out = []
        for frag, e in s["parts"]:
            y = imp.imprint(s["regime"], self.run(s, frag))
            out.append({"effect": e["effect"], "target": e["target"],
                        "free": list(s["free"]), "sigma": left(y, cols),
                        "imprint_sigma": float(np.linalg.norm(y))})
        return out

    def scale_marginal(self, s: dict[str, Any]) -> None:
        """Scale a marginal record's size so that its best probe's signature (about the
        true null) is the set's marginal size: proportional passes until within 1 %."""
        size = s["size"]
        for _ in range(6):
            clean = self.run(s, s["fx"])
            best = max(self.imprints(s).signature(s["regime"], clean).values())
            if abs(best / self.marginal_sigma - 1.0) < 0.01:
                break
            size = float(f"{size * self.marginal_sigma / best:.4g}")
            s["parts"] = tuple(s["marginal"](size))
            s["fx"], s["effects"] = combine(s["parts"])
        s["size"] = size

    def truth_entry(self, s: dict[str, Any], sig: dict) -> dict:
        """The record's entry of truth.json: its probes and their noise only, the freed
        parameters and their declared and true values."""
        entry = super().truth_entry(s, sig)
        ns = {p: v for p, v in noise_or_white(s, self.white).items()
              if p in s["probes"]}
        entry.update(probes=list(s["probes"]), noise=ns,
                     noise_text=noise_text(ns), free=list(s["free"]),
                     declared_error={name: {"declared": self.params[name], "true": value}
                                     for name, value in s["ptrue"].items()},
                     declared_error_signature_sigma=self.declared_signature(s))
        return entry

    def make(self, s: dict[str, Any], write: bool) -> dict:
        """One record: its truth entry, and its CSV (the record's probes, the command in
        the slow regime) when ``write``."""
        regime, t = s["regime"], self.times(s)
        if s["marginal"] is not None:
            self.scale_marginal(s)
        clean = self.run(s, s["fx"])
        imp = self.imprints(s)
        sig = self.declared_signature(s) if s["class"] == "null" else \
            imp.signature(regime, clean)
        entry = self.truth_entry(s, sig)
        if s["class"] == "outside":
            entry["unexplained_sigma"] = imp.unexplained(
                regime, clean, {**self.alternatives(s), **self.harmonic_alternatives(s),
                                **self.freed(s)})
        if s["marginal"] is not None:
            e = s["effects"][0]
            same = {e["effect"], *(a["effect"] for a in e.get("also_accept", []))}
            # each alternative with the freed parameters beside it, as the diagnosis fits
            # them: what a freed parameter can make up between the two is no difference
            # (added after the set was run: aw10's speed gain is 6.3 sigma from its hub
            # friction alone, 0.41 sigma with R and Jm free)
            freed = np.column_stack(list(self.freed(s).values()))
            alts = {k: np.column_stack([a, freed]) for k, a in self.alternatives(s).items()}
            entry["separation_sigma"] = imp.separation(regime, clean, alts, same)
        if s["class"] in ("catalog", "two"):
            entry["free_separation_sigma"] = self.free_separation(s)
            entry.update(places_entry(
                s, t, imp, lambda _regime, tt, fx: self.run(s, fx, tt), self.places,
                self.inertias, {**self.params, **s["ptrue"]}, self.beyond))
        if write:
            rng = np.random.default_rng(s["seed"])
            ns = noise_or_white(s, self.white)
            cols = {p: self.simulator.add_noise(rng, t, clean[p], ns[p])
                    for p in s["probes"]}
            if regime == "slow":
                cols["u"] = clean["u"]
            RECORDS.mkdir(exist_ok=True)
            write_csv(RECORDS / f"{s['id']}.csv", t, cols)
        return entry


#: across a compliant element: shaft -> (the shaft an effect on it is compared with, the
#: factor its size takes there per simulator key)
Across = Mapping[str, tuple[str, Mapping[str, float]]]


def moved(frag: dict, target: str, across: Across) -> tuple[str, list[dict]] | None:
    """The other side of ``across`` from ``target``, and the columns' fx of the effect
    ``frag`` moved there at its equivalent size: one for a scalar effect, two for an
    angle-locked one (a sine and a cosine, so that the phase is fitted); None when the
    effect has no equal there."""
    other, factor = across[target]
    (kind, where), = frag.items()
    if kind not in factor:
        return None
    value = where[target]
    if kind != "cog":
        return other, [{kind: {other: value * factor[kind]}}]
    return other, [{kind: {other: [(k, math.hypot(a, b) * c, math.hypot(a, b) * d)
                                   for k, a, b in value]}} for c, d in ((1.0, 0.0), (0.0, 1.0))]


def location_entry(s: dict[str, Any], across: Across, t: np.ndarray, imp: Imprints,
                   sim: Callable[[str, np.ndarray, dict], Mapping[str, np.ndarray]]
                   ) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma``: for each truth effect on a
    shaft, the distance [white sigma] of its own clean imprint, run alone (``sim``) on the
    record's times ``t`` and regime, from the same effect at its equivalent size on the other
    side of ``across``, best-scaled; and that imprint's norm [white sigma]. Empty for other
    classes."""
    if s["class"] not in ("catalog", "two"):
        return {}
    regime, out = s["regime"], []
    for frag, e in s["parts"]:
        if e["target"] not in across or len(frag) != 1:
            continue
        there = moved(frag, e["target"], across)
        if there is None:
            continue
        other, fxs = there
        cols = np.column_stack([imp.imprint(regime, sim(regime, t, fx)) for fx in fxs])
        y = imp.imprint(regime, sim(regime, t, frag))
        out.append({"effect": e["effect"], "target": e["target"], "other": other,
                    "sigma": left(y, cols), "imprint_sigma": float(np.linalg.norm(y))})
    return {"location_sigma": out}


def left(y: np.ndarray, x: np.ndarray) -> float:
    """What least squares on the columns of ``x`` leaves of ``y`` (the residual's norm)."""
    coef, *_ = np.linalg.lstsq(x, y, rcond=None)
    return float(np.linalg.norm(y - x @ coef))


def write_csv(path: Path, t: np.ndarray, cols: Mapping[str, np.ndarray]) -> None:
    """A record: ``time`` [s] and one column per name, to 10 significant digits."""
    names = list(cols)
    data = np.column_stack([t, *(cols[n] for n in names)])
    path.parent.mkdir(exist_ok=True)
    tmp = path.with_name(f".{path.name}.tmp")
    np.savetxt(tmp, data, delimiter=",", header=",".join(["time", *names]), comments="",
               fmt="%.10g")
    os.replace(tmp, path)


def merge(entries: Iterable[dict[str, Any]]) -> None:
    """Put ``entries`` into truth.json (see the module docstring)."""
    with open(LOCK, "a+") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            data = json.loads(TRUTH.read_text()) if TRUTH.exists() else {"records": []}
            new = {e["id"]: e for e in entries}
            kept = [new.pop(e["id"], e) for e in data["records"]]
            data["records"] = kept + list(new.values())
            fd, tmp = tempfile.mkstemp(prefix=".truth-", suffix=".json", dir=HERE)
            try:
                with os.fdopen(fd, "w") as f:
                    f.write(json.dumps(data, indent=1) + "\n")
                os.chmod(tmp, 0o644)
                os.replace(tmp, TRUTH)
            except BaseException:
                if os.path.exists(tmp):
                    os.unlink(tmp)
                raise
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)


def _line(entry: Mapping[str, Any], motor: str, seconds: float) -> str:
    """A record's line of progress: its class and what the truth says of its size (the
    effects themselves stay in truth.json)."""
    sig = ", ".join(f"{k} {v:.3g}" for k, v in entry["signature_sigma"].items())
    extra = ""
    if "unexplained_sigma" in entry:
        u = entry["unexplained_sigma"]
        extra = (f"; left by the best single {u['best_single'][1]:.3g}, by all "
                 f"{u['all_scalar_effects_jointly']:.3g} of {u['imprint']:.3g}")
    if entry.get("separation_sigma"):
        extra += f"; nearest other effect {min(entry['separation_sigma'].values()):.3g} sigma"
    return (f"{entry['id']} {entry['class']:8s} {motor}-{entry['regime']:4s} | signature "
            f"{sig}{extra} ({seconds:.1f} s)")


def main(argv: list[str] | None, doc: str | None,
         record_specs: Callable[[], Iterable[dict[str, Any]]],
         make: Callable[[dict[str, Any], bool], dict[str, Any]], motor: str) -> int:
    """A generator's command line: make the records (or those of ``--only``), write their
    CSVs (not with ``--truth-only``) and merge their truth."""
    ap = argparse.ArgumentParser(description=(doc or "").splitlines()[0])
    ap.add_argument("--only", default="", help="record ids, comma-separated")
    ap.add_argument("--truth-only", action="store_true", help="do not write CSVs")
    args = ap.parse_args(argv)
    only = {x.strip() for x in args.only.split(",") if x.strip()}
    entries = []
    t_all = time.perf_counter()
    for spec in record_specs():
        if only and spec["id"] not in only:
            continue
        t0 = time.perf_counter()
        entries.append(make(spec, not args.truth_only))
        print(_line(entries[-1], motor, time.perf_counter() - t0), flush=True)
    merge(entries)
    print(f"{len(entries)} records in {time.perf_counter() - t_all:.1f} s")
    return 0


#: a torque effect's kinds that have an equal at another place of a shaft train
TORQUE_KINDS = ("coul", "offset", "visc", "stribeck", "cog")


def torque_at(kind: str, value: Any, ga: float, gb: float, other: str) -> list[dict] | None:
    """The columns' fx of a torque effect ``kind`` of size ``value`` at a place of gear
    factor ``ga`` (its speed over a reference shaft's), moved to ``other`` of factor ``gb``:
    a dry friction or an offset of ga/gb of it, a viscous friction of (ga/gb)^2, a Stribeck
    peak of ga/gb at gb/ga times its speed scale, a cogging (or unbalance) of order k ga/gb
    at ga/gb of its amplitude (two columns, a sine and a cosine, so that the phase is
    fitted); None when the order is not whole there."""
    f = ga / gb
    if kind == "visc":
        return [{kind: {other: value * f ** 2}}]
    if kind == "stribeck":
        peak, ws = value
        return [{kind: {other: (peak * f, ws / f)}}]
    if kind == "cog":
        terms = []
        for k, a, b in value:
            order = k * f
            if abs(order - round(order)) > 1e-9:
                return None
            terms.append((round(order), math.hypot(a, b) * f))
        return [{kind: {other: [(k, amp * c, amp * d) for k, amp in terms]}}
                for c, d in ((1.0, 0.0), (0.0, 1.0))]
    return [{kind: {other: value * f}}]


def places_moved(frag: dict, target: str, places: Mapping[str, float],
                 inertias: Mapping[str, tuple[str, float]], params: Mapping[str, float]
                 ) -> list[tuple[str, list[dict]]]:
    """Every other place of ``target``'s group -- ``places`` {body: gear factor} for a
    torque effect, ``inertias`` {component: (parameter, gear factor)} for an added inertia
    (dJ at factor ga is dJ (ga/gb)^2 at gb; ``params`` the declared values) -- and the
    columns' fx of the effect ``frag`` moved there at its equivalent size: (other, fxs)
    pairs, none where the effect has no equal."""
    (kind, where), = frag.items()
    out: list[tuple[str, list[dict]]] = []
    if kind == "p" and target in inertias:
        param, ga = inertias[target]
        added = float(where[param]) - params[param]
        for other, (oparam, gb) in inertias.items():
            if other != target:
                out.append((other, [{"p": {oparam: params[oparam] + added * (ga / gb) ** 2}}]))
        return out
    if kind not in TORQUE_KINDS or target not in places:
        return out
    for other, gb in places.items():
        if other != target:
            fxs = torque_at(kind, where[target], places[target], gb, other)
            if fxs is not None:
                out.append((other, fxs))
    return out


def places_entry(s: dict[str, Any], t: np.ndarray, imp: Imprints,
                 sim: Callable[[str, np.ndarray, dict], Mapping[str, np.ndarray]],
                 places: Mapping[str, float], inertias: Mapping[str, tuple[str, float]],
                 params: Mapping[str, float], beyond: Iterable[str]) -> dict[str, Any]:
    """A catalog or two-effect record's ``location_sigma`` over every pair of places
    (``places_moved``): each truth effect's own clean imprint, run alone on the record's
    times, against the same effect at its equivalent size at each other place, best-scaled
    [white sigma]; ``across`` is true for a pair one of whose places is in ``beyond`` (the
    far side of the train's compliance), false for an exact twin through a rigid gear."""
    if s["class"] not in ("catalog", "two"):
        return {}
    far, out = set(beyond), []
    for frag, e in s["parts"]:
        if (e["target"] not in places and e["target"] not in inertias) or len(frag) != 1:
            continue
        y = None
        for other, fxs in places_moved(frag, e["target"], places, inertias, params):
            if y is None:
                y = imp.imprint(s["regime"], sim(s["regime"], t, frag))
            cols = np.column_stack([imp.imprint(s["regime"], sim(s["regime"], t, fx))
                                    for fx in fxs])
            out.append({"effect": e["effect"], "target": e["target"], "other": other,
                        "across": bool(far & {e["target"], other}), "sigma": left(y, cols),
                        "imprint_sigma": float(np.linalg.norm(y))})
    return {"location_sigma": out}
