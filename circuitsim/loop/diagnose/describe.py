"""Stage: describe what remains in the residual when no candidate explains it.

Never a catalog label: the probe it lives in, whether its lines are locked to a shaft's angle
(orders) or to time (Hz), whether it is transient or steady, its main lines with their share
of the structure, when in the record it is strongest, and what it grows with (a probe's
magnitude or its rate of change, or time) -- what a person needs to name it.
"""

from __future__ import annotations

import itertools
import math
from typing import Any

import numpy as np

from circuitsim.loop.diagnose.context import ModelState, Setup
from circuitsim.loop.diagnose.noise import significant_lines, transient_excess, whiteners_of
from circuitsim.loop.diagnose.residual import ORDER_TOL, ljung_box

WINDOWS = 10  # time windows for "when in the record"
MIN_SHARE = 0.02  # structure below this share of a probe's whitened residual is not reported
#: Windows over which the residual's excess power is ranked against the operating point, and
#: the rank correlation it must reach to be reported as following it (of 20 windows, a
#: chance correlation this high has odds of about 1e-5 per signal).
FOLLOW_WINDOWS = 20
FOLLOW_RHO = 0.8


def remaining(setup: Setup, state: ModelState) -> dict[str, Any]:
    """The structure left in the final model's residual, per probe, in plain terms."""
    whiten = whiteners_of(state.fit.residuals, setup.probes)
    dt = float(np.mean(np.diff(setup.record.t)))
    shafts = shaft_frequencies(state)
    probes = {}
    for p in setup.probes:
        r = np.asarray(state.fit.residuals[p], float)
        e = whiten[p].apply(r)
        lines = significant_lines(e, dt)
        structured = max(lines.structured, transient_excess(e))
        share = structured / lines.total if lines.total > 0 else 0.0
        _, pval = ljung_box(e)
        entry = {"structured_share": share, "white_after_prewhitening": pval > 1e-3,
                 "noise_ar_order": len(whiten[p].a), "lines": _lines(lines, shafts),
                 "timing": _timing(setup.record.t, r),
                 "follows": _follows(setup, state, r, setup.weights.get(p, 0.0))}
        if share >= MIN_SHARE or pval <= 1e-3:
            probes[p] = entry
    structure = bool(probes)
    return {"structure": structure, "probes": probes, "note": _note(probes)}


def shaft_frequencies(state: ModelState) -> dict[str, tuple[float, bool]]:
    """Per shaft: its mean rotation frequency [rev/s] and whether it is steady enough for
    a line to be read as an order."""
    out = {}
    sim = state.fit.sim
    for n in state.model.shafts:
        try:
            w = np.asarray(sim[f"{n}.w"], float)
        except KeyError:
            continue
        tail = w[w.size // 2:]
        out[n] = (float(np.mean(tail)) / (2 * math.pi),
                  bool(np.std(tail) < 0.02 * max(abs(float(np.mean(tail))), 1e-300)))
    return out


def _lines(lines, shafts) -> list[dict[str, Any]]:
    order = np.argsort(lines.excess)[::-1]
    out: list[dict[str, Any]] = []
    for k in order[:40]:
        f = float(lines.freqs[k])
        if any(abs(f - q["frequency"]) <= 1.5 * _resolution(lines) for q in out):
            continue
        label = {"frequency": f, "share": float(lines.excess[k] / lines.structured)}
        for n, (fs, steady) in shafts.items():
            if fs > 0 and steady and f > 0:
                ratio = f / fs
                kk = round(ratio * 2) / 2  # half orders too (a belt, a 2-pole slip)
                if kk >= 0.5 and abs(ratio - kk) < ORDER_TOL * kk:
                    label["order"] = {"shaft": n, "order": kk}
        out.append(label)
        if len(out) == 5:
            break
    return out


def _resolution(lines) -> float:
    return float(np.min(np.diff(np.sort(lines.freqs)))) if lines.freqs.size > 1 else 0.0


def _timing(t: np.ndarray, r: np.ndarray) -> dict[str, Any]:
    """Where in the record the residual is large: steady when spread evenly."""
    edges = np.linspace(0, r.size, WINDOWS + 1).astype(int)
    rms = np.array([math.sqrt(float(np.mean(np.square(r[a:b])))) if b > a else 0.0
                    for a, b in itertools.pairwise(edges)])
    med = float(np.median(rms))
    strong = [i for i, v in enumerate(rms) if v > 2 * med]
    kind = "transient" if strong and max(rms) > 3 * med else "steady"
    return {"kind": kind, "rms_by_window": rms.tolist(),
            "strongest": [[float(t[edges[i]]), float(t[min(edges[i + 1], t.size - 1)])]
                          for i in strong[:3]]}


def _follows(setup: Setup, state: ModelState, r: np.ndarray, sigma: float
             ) -> list[dict[str, Any]]:
    """What the residual's excess power over the noise (``sigma`` [probe unit]) rises with
    across the record: a probe's simulated magnitude, its rate of change, or time -- the
    signals whose rank correlation over ``FOLLOW_WINDOWS`` windows reaches ``FOLLOW_RHO``, the
    strongest first (at most two). A field weakening with current, a loss growing with
    speed, a lag seen at every step: each leaves its mark where its driver is large."""
    from scipy.stats import spearmanr

    edges = np.linspace(0, r.size, FOLLOW_WINDOWS + 1).astype(int)
    if np.min(np.diff(edges)) < 3:
        return []
    t = np.asarray(setup.record.t, float)

    def per_window(x: np.ndarray) -> np.ndarray:
        return np.array([float(np.mean(x[a:b])) for a, b in itertools.pairwise(edges)])

    # the power above the noise level: ranks of raw power would follow a noise whose level
    # scales with a probe as readily as structure
    power = np.clip(per_window(np.square(r)) - sigma ** 2, 0.0, None)
    drivers = {"time": t}
    for q in setup.probes:
        try:
            x = np.asarray(state.fit.sim[q], float)
        except KeyError:
            continue
        drivers[f"|{q}|"] = np.abs(x)
        drivers[f"|d{q}/dt|"] = np.abs(np.gradient(x, t))
    found = []
    for name, x in drivers.items():
        level = per_window(x)
        if np.ptp(level) <= 1e-12 * max(float(np.max(np.abs(level))), 1e-300):
            continue  # a signal constant over the record cannot rank anything
        rho = float(spearmanr(level, power).statistic)
        if math.isfinite(rho) and rho >= FOLLOW_RHO:
            found.append({"signal": name, "rank_correlation": rho})
    # the strongest two: a field weakening shows at high current, and so at every step
    return sorted(found, key=lambda f: -f["rank_correlation"])[:2]


def _follow_text(entry: dict[str, Any]) -> str:
    follows = entry.get("follows") or []
    signals = [f"{f['signal']} ({f['rank_correlation']:.2f})" for f in follows
               if f["signal"] != "time"]
    verb = "are" if len(signals) > 1 else "is"
    parts = [f"largest where {' and '.join(signals)} {verb} large"] if signals else []
    timed = [f"grows through the record ({f['rank_correlation']:.2f})" for f in follows
             if f["signal"] == "time"]
    # the strongest first, as _follows orders them
    parts = timed + parts if follows and follows[0]["signal"] == "time" else parts + timed
    return ("; " + ", ".join(parts) + " (rank correlation over the record)") if parts else ""


def _note(probes: dict[str, Any]) -> str:
    if not probes:
        return "nothing significant remains: the residual is noise"
    parts = []
    for p, e in probes.items():
        lines = ", ".join(
            (f"order {ln['order']['order']:g} of {ln['order']['shaft']}" if "order" in ln
             else f"{ln['frequency']:.4g} Hz (time-locked)") + f" ({ln['share']:.0%})"
            for ln in e["lines"][:3])
        when = e["timing"]
        span = "; strongest " + ", ".join(f"{a:.3g}-{b:.3g} s" for a, b in when["strongest"]) \
            if when["strongest"] else ""
        parts.append(f"{p}: {e['structured_share']:.0%} of its residual is structure, "
                     f"{when['kind']}{span}" + _follow_text(e) +
                     (f"; lines at {lines}" if lines else "") +
                     ("" if e["white_after_prewhitening"] else "; not white"))
    return "something remains that no catalog effect explains -- " + " | ".join(parts)
