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
from circuitsim.loop.diagnose.noise import (
    MEMORY_STRUCTURE_MAX,
    Whitener,
    fit_whitener,
    fractional_difference,
    lines_of,
    memory_whiteners,
    perturbed_memory_order,
    rises_to_zero,
    significant_lines,
    transient_excess,
    whiteners_of,
)
from circuitsim.loop.diagnose.operating import band_text, drivers_of, operating_band
from circuitsim.loop.diagnose.residual import (
    ORDER_TOL,
    RESOLUTION,
    below_resolution,
    ljung_box,
    on_travelled_angle,
)

WINDOWS = 10  # time windows for "when in the record"
MIN_SHARE = 0.02  # structure below this share of a probe's whitened residual is not reported
#: Windows over which the residual's excess power is ranked against the operating point, and
#: the rank correlation it must reach to be reported as following it (of 20 windows, a
#: chance correlation this high has odds of about 1e-5 per signal).
FOLLOW_WINDOWS = 20
FOLLOW_RHO = 0.8
#: A structure has no dominant line when its strongest holds less than the first share and
#: its three strongest less than the second: it is then described by the band its significant
#: bins span (a resonance's skirt, a transient's spectrum), not by bins that name nothing.
SPREAD_TOP = 0.25
SPREAD_TOP3 = 0.5
#: A probe whose residual is otherwise noise (structure at most ``MEMORY_STRUCTURE_MAX`` of
#: it) but not white is its sensor's own coloured noise unless another probe's residual
#: follows it: coherence at some frequency with a chance probability under this (Bonferroni
#: over the bins and the other probes), from Welch's estimate over this many segments. A
#: speed sensor's 1/f noise is seen by no other probe (the null records' largest coherence
#: 0.2-0.4); a load the model lacks moves current and speeds together (fresh13's v12, a
#: conveyor's parcel pitch: 0.99 between all three, its prewhitened share under 1 %).
FOLLOW_P = 1e-3
COHERENCE_SEGMENTS = 8
#: [BIC] A sensor's own noise is independent of the circuit's state: a residual that the
#: model's own signals (each probe's simulated value and its rate of change) fit, through
#: the probe's noise filters, by a BIC fall beyond this (the acceptance's margin,
#: decide.BIC_MARGIN) is structure whatever its spectrum. fresh20's j10, a leakage path
#: across the motor's terminals (the current reads v/150 ohm more, v = k w + R i + L di/dt):
#: -949 and -394 through the two filters (the worse counts), while the 27 probes the
#: benchmark's other records excuse as their own coloured noise (1/f speed noise in nulls
#: and beside found effects) give +21 to +51; the coherence test could not see j10's, as no
#: other probe's residual moves with it.
FOLLOW_MODEL_BIC = 10.0
#: A probe excused as its sensor's own coloured noise whose excess over its white noise is
#: mostly one sinusoid -- this share of it or more -- has that line named in the note: mains
#: hum or a PWM beat on a sensor's lead is no effect of the circuit, but a person wants to
#: know it is there. A 1/f or AR(1) noise spreads its excess over many bins (its strongest
#: holds about a tenth of it), so the share cannot come from a coloured noise alone.
NOISE_LINE_SHARE = 0.5
#: The band of a spread structure: the frequencies where its cumulative excess reaches these
#: fractions (its middle half: a resonance's skirt reaches far, its middle half does not).
SPREAD_BAND = (0.25, 0.75)


def remaining(setup: Setup, state: ModelState, stand_in: bool = False) -> dict[str, Any]:
    """The structure left in the final model's residual, per probe, in plain terms.

    ``stand_in``: a catalog effect fitted part of this residual significantly (its ΔBIC on
    the prewhitened residual, under the same noise model) and was then rejected as a stand-in
    for a cause outside the catalog. The residual is then no probe's own coloured noise, and
    ``_own_noise`` does not excuse it: that test, a coherence between probes, only asks
    whether a slow wander could be the sensor's, which the stand-in's fit has answered."""
    whiten = whiteners_of(state.fit.residuals, setup.probes)
    shafts = shaft_frequencies(state)
    probes, resolved = {}, []
    for p in setup.probes:
        r = np.asarray(state.fit.residuals[p], float)
        if below_resolution(r, setup.record[p]):  # a shape this small is no evidence
            resolved.append(p)
            continue
        e = whiten[p].apply(r)
        lines = lines_of(e, setup.record.t, r, whiten[p])
        # each share on its own grid: the lines' on the even one an uneven record is read on
        share = max(lines.structured / lines.total if lines.total > 0 else 0.0,
                    transient_excess(e) / max(float(e @ e), 1e-300))
        _, pval = ljung_box(e)
        sigma = setup.weights.get(p, 0.0)
        entry = {"structured_share": share, "white_after_prewhitening": pval > 1e-3,
                 "rms_over_noise": (math.sqrt(float(np.mean(np.square(r)))) / sigma
                                    if sigma > 0 else math.inf),
                 "noise_ar_order": len(whiten[p].a),
                 "lines": _lines(lines, shafts, _Locking(setup.record.t, r, state)),
                 "timing": _timing(setup.record.t, r, sigma),
                 "follows": _follows(setup, state, r, sigma),
                 "band": operating_band(drivers_of(state.fit.sim, setup.probes), r, sigma, p)}
        spread = _spread(lines, entry["lines"])
        if spread is not None:
            entry["spread"] = spread
        if share >= MIN_SHARE or pval <= 1e-3:
            probes[p] = entry
    coloured = {} if stand_in else _own_noise(setup, state, probes)
    for p in coloured:
        del probes[p]
    structure = bool(probes)
    return {"structure": structure, "probes": probes, "note": _note(probes, resolved, coloured),
            "below_resolution": resolved, **({"coloured": coloured} if coloured else {})}


def _own_noise(setup: Setup, state: ModelState, probes: dict[str, Any]) -> dict[str, Any]:
    """Of the reported ``probes``, those whose residual is otherwise noise -- its lines and
    transients under ``MIN_SHARE``, as prewhitened or once a long memory is taken out
    (``_long_memory``): reported for not being white -- and which no other probe's residual
    follows (``FOLLOW_P``): their sensor's own coloured noise, each with the chance
    probability of its strongest coherence. A sensor's noise is independent of the circuit's
    state, so neither may the model's own signals fit the residual (``_follows_model``) nor
    may its excess power rise with the operating point (``_follows``, a signal of the
    circuit's). On a record of one probe no other probe can follow it, and these are the
    only tests: a speed sensor's 1/f noise alone was "something I cannot name" on four null
    records read by their speed alone (h06, n04, k02, j02), where their current and speed
    together were clean; fresh22's l14 (a wave's orbital flow through a propeller, the
    speed log alone) was excused until its power's rise with the speed (0.97) was read."""
    t = np.asarray(setup.record.t, float)
    res = {p: np.asarray(state.fit.residuals[p], float) for p in setup.probes}
    out = {}
    for p, e in probes.items():
        if e["structured_share"] > MEMORY_STRUCTURE_MAX or not (
                e["structured_share"] < MIN_SHARE or _long_memory(t, res[p])):
            continue
        follow = _follows_model(setup, state, res, p)
        if follow is not None:
            e["follows_model"] = follow
            continue
        if any(f["signal"] != "time" for f in e["follows"]):
            continue  # its size rises with the circuit's state (time: a sensor may drift)
        others = [q for q in setup.probes if q != p]
        chance = min((_coherence_chance(t, res[p], res[q]) for q in others), default=1.0) * \
            max(len(others), 1)
        if chance > FOLLOW_P:
            out[p] = {"coherence_chance": min(chance, 1.0),
                      "white_after_prewhitening": e["white_after_prewhitening"],
                      "rms_over_noise": e.get("rms_over_noise"),
                      **_noise_line(t, res[p], setup.weights.get(p, 0.0))}
    return out


def _noise_line(t: np.ndarray, r: np.ndarray, sigma: float) -> dict[str, Any]:
    """``{"line": {frequency [Hz], amplitude [probe's unit], share [-]}}`` when one sinusoid
    holds at least ``NOISE_LINE_SHARE`` of the residual's mean square above its white noise
    ``sigma`` and turns at least three times over the record; else empty."""
    from circuitsim.signal import dominant_ripple

    excess = float(np.mean(np.square(r))) - sigma * sigma
    if excess <= 0.0:
        return {}
    try:
        h = dominant_ripple(t, r)
    except ValueError:
        return {}
    share = 0.5 * h.amplitude ** 2 / excess
    if h.frequency * float(t[-1] - t[0]) < 3.0 or share < NOISE_LINE_SHARE:
        return {}
    return {"line": {"frequency": float(h.frequency), "amplitude": float(h.amplitude),
                     "share": min(share, 1.0)}}


def _follows_model(setup: Setup, state: ModelState, res: dict[str, np.ndarray], p: str
                   ) -> dict[str, Any] | None:
    """Whether probe ``p``'s residual follows the model's own signals (``FOLLOW_MODEL_BIC``):
    it and each probe's simulated value and rate of change through ``p``'s AR filter and
    its long-memory filter, the worse BIC fall of the two least-squares fits. The BIC fall
    and the two signals that weigh most, or None."""
    t = np.asarray(setup.record.t, float)
    cols: dict[str, np.ndarray] = {}
    for q in setup.probes:
        try:
            s = np.asarray(state.fit.sim[q], float)
        except KeyError:
            continue
        cols[q], cols[f"d{q}/dt"] = s, np.gradient(s, t)
    if not cols:
        return None
    worst, weights = -math.inf, np.zeros(len(cols))
    for w in (whiteners_of(res, [p])[p], memory_whiteners(res, [p])[p]):
        e = w.apply(res[p])
        x = np.column_stack([w.apply(c) for c in cols.values()])
        x = x / np.where((norm := np.linalg.norm(x, axis=0)) > 0.0, norm, 1.0)
        beta, *_ = np.linalg.lstsq(x, e, rcond=None)
        left, sse = e - x @ beta, float(e @ e)
        if sse <= 0.0:
            return None
        fall = e.size * math.log(max(float(left @ left), 1e-300) / sse) + \
            x.shape[1] * math.log(e.size)
        if fall > worst:
            worst, weights = fall, np.abs(beta)
    if worst >= -FOLLOW_MODEL_BIC:
        return None
    names = list(cols)
    return {"delta_bic": worst, "signals": [names[i] for i in np.argsort(-weights)[:2]]}


def _long_memory(t: np.ndarray, r: np.ndarray) -> bool:
    """Whether a residual ``r`` at times ``t`` [s] is noise with long memory: one the
    long-memory whitener (a fractional difference, then AR) leaves with structure under
    ``MIN_SHARE`` where the AR filter alone did not. A line -- a tachometer's ripple seen by
    its own probe alone -- outlasts a fractional difference and keeps its share.

    Where the decisions' whitener finds no memory, it is read once more through white noise
    (``perturbed_memory_order``), on the whole residual: a 1/f speed noise under white
    noise, its lowest bins flattened by the white part, left one of them as a "line" on
    fresh33's null record ak02; and the typical windows the decisions read the memory on
    leave out the 1/f noise's own widest excursions. A transient outside them keeps its
    share through the fractional difference. The decisions keep their whitener.

    A spectrum that rises away from zero frequency is no memory however the order reads
    (``rises_to_zero``): an AR filter after the fractional difference whitens a resonance's
    band too, and a housing rocking on its mounts was excused as the current sensor's own
    noise (fresh38's ap14)."""
    if not rises_to_zero(r):
        return False
    w = memory_whiteners({"r": r}, ["r"])["r"]
    if not w.d:
        d = perturbed_memory_order(r)
        if not d:
            return False
        base = fit_whitener(fractional_difference(r, d))
        w = Whitener(base.a, base.sigma, d)
    e = w.apply(r)
    lines = lines_of(e, t, r, w)
    share = max(lines.structured / lines.total if lines.total > 0 else 0.0,
                transient_excess(e) / max(float(e @ e), 1e-300))
    return share < MIN_SHARE


def _coherence_chance(t: np.ndarray, x: np.ndarray, y: np.ndarray) -> float:
    """The chance probability of the strongest magnitude-squared coherence of ``x`` and
    ``y`` at times ``t`` [s] (on an even grid when uneven) over the frequencies resolved:
    (1 - c)^(K - 1) per bin for independent noises over K segments, times the bins."""
    from scipy.signal import coherence

    from circuitsim.loop.record import even_grid

    grid = even_grid(t)
    if grid is not t:
        x, y = np.interp(grid, t, x), np.interp(grid, t, y)
    size = x.size // COHERENCE_SEGMENTS
    if size < 16:
        return 1.0
    c = coherence(x, y, nperseg=size)[1][1:]
    # Welch's half overlap gives about 2K - 1 segments, but only K independent ones
    return float(c.size * (1.0 - float(np.max(c))) ** (COHERENCE_SEGMENTS - 1))


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


def _lines(lines, shafts, locking: _Locking) -> list[dict[str, Any]]:
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
        if "order" not in label and f > 0:
            unsteady = [n for n, (_, steady) in shafts.items() if not steady]
            locked = locking.order_of(f, unsteady) if unsteady else "time"
            if isinstance(locked, dict):
                label["order"] = locked
            else:
                label["locking"] = locked
        same = next((q for q in out if "order" in q and "order" in label and
                     (q["order"]["shaft"], q["order"]["order"]) ==
                     (label["order"]["shaft"], label["order"]["order"])), None)
        if same is not None:  # an order swept through several bins is one line
            same["share"] += label["share"]
            continue
        out.append(label)
        if len(out) == 5:
            break
    return out


class _Locking:
    """Whether a line found in the time spectrum is locked to a shaft's angle when that shaft
    does not turn steadily (it speeds up, reverses, stops): a harmonic of the angle then
    sweeps through frequencies. Of the orders the line could be at one of the speeds the shaft
    holds, one names it when (a) its sine and cosine of the angle explain more of the residual
    than the line's own fixed-frequency sine and cosine (equal numbers of regressors: no
    penalty needed), and (b) the residual, resampled on the angle the shaft travels (order
    tracking; a reversal keeps the order), has a significant line there holding at least
    ``SHARE`` of its structure, at an order of 1 or more. A line the fixed sine
    explains better is locked to time; one that passes (a) alone cannot be told (slow structure
    that follows the speed profile correlates with any low order)."""

    QUANTILES = (0.1, 0.25, 0.5, 0.75, 0.9, 1.0)  # speeds of the turning shaft tried
    SHARE = 0.25  # of the order-tracked structure the line at the order must hold

    def __init__(self, t: np.ndarray, r: np.ndarray, state: ModelState):
        self.t, self.r, self.sim = t, r - np.mean(r), state.fit.sim
        self._tracked: dict[str, Any] = {}

    def _explained(self, phase: np.ndarray) -> float:
        x = np.column_stack([np.sin(phase), np.cos(phase)])
        coef, *_ = np.linalg.lstsq(x, self.r, rcond=None)
        return float(np.sum(np.square(x @ coef)))

    def _order_lines(self, n: str, w: np.ndarray):
        """Significant lines of the residual resampled on shaft ``n``'s travelled angle
        [orders: cycles per turn] (None when it travels under two turns)."""
        if n not in self._tracked:
            tracked, out = on_travelled_angle(self.t, w, self.r), None
            if tracked is not None:
                grid, x = tracked
                x = x - np.polyval(np.polyfit(grid, x, 1), grid)
                out = significant_lines(fit_whitener(x).apply(x),
                                        (grid[1] - grid[0]) / (2 * math.pi))
            self._tracked[n] = out
        return self._tracked[n]

    def order_of(self, f: float, shafts: list[str]) -> dict[str, Any] | str:
        """{"shaft", "order", "locking": "angle"} when the line at ``f`` [Hz] is locked to
        the angle of one of ``shafts``; "time" when it is locked to time; "" when the two
        cannot be told apart."""
        fixed = self._explained(2 * math.pi * f * self.t)
        best, compared, angle_won = None, False, False
        for n in shafts:
            try:
                phi = np.asarray(self.sim[f"{n}.phi"], float)
                w = np.abs(np.asarray(self.sim[f"{n}.w"], float))
            except KeyError:
                continue
            turning = w[w > 0.1 * max(float(np.max(w)), 1e-300)]
            if turning.size == 0 or np.ptp(phi) < 4 * math.pi:  # two turns at least
                continue
            freqs = np.quantile(turning, self.QUANTILES) / (2 * math.pi)
            for kk in sorted({round(2 * f / fs) / 2 for fs in freqs if fs > 0}):
                if kk < 1:  # slow structure that follows the profile fills the lowest
                    continue
                gain = self._explained(kk * phi)
                compared = True
                if gain <= fixed:
                    continue
                angle_won = True  # an order explains more: time-locked is ruled out
                lines = self._order_lines(n, w)
                if lines is None or lines.structured <= 0:
                    continue
                near = np.abs(lines.freqs - kk) <= max(ORDER_TOL * kk, 1.5 * _resolution(lines))
                if float(np.sum(lines.excess[near])) >= self.SHARE * lines.structured and \
                        (best is None or gain > best[0]):
                    best = (gain, {"shaft": n, "order": kk, "locking": "angle"})
        if best is not None:
            return best[1]
        return "time" if compared and not angle_won else ""


def _spread(lines, named: list[dict[str, Any]]) -> dict[str, Any] | None:
    """The band [Hz] a structure without a dominant line spans, or None when one dominates.

    ``named`` are the probe's reported lines (``_lines``: a swept order already merged into
    one). A line at 2 Hz holding 13 % of a 0.5 s record's transient is the spectrum's lowest
    bin, and an input filter's resonance spreads over dozens of bins near 800 Hz: naming three
    of their bins as lines misleads, the band they span and its peak do not. A structure
    whose strongest line is a shaft order keeps its lines."""
    ranked = sorted(named, key=lambda ln: -ln["share"])
    shares = [ln["share"] for ln in ranked]
    # a line locked to a shaft's angle is a line whatever its share (a machine's cogging
    # orders are each a minority of the whole: the ODrive's strongest holds 26 %)
    if lines.freqs.size < 4 or not shares or "order" in ranked[0] \
            or shares[0] >= SPREAD_TOP or sum(shares[:3]) >= SPREAD_TOP3:
        return None
    order = np.argsort(lines.freqs)
    f, x = lines.freqs[order], lines.excess[order]
    cum = np.cumsum(x) / float(np.sum(x))
    lo, hi = (float(f[min(int(np.searchsorted(cum, q)), f.size - 1)]) for q in SPREAD_BAND)
    peak = int(np.argmax(x))
    return {"low": lo, "high": hi, "peak": float(f[peak]), "bins": int(f.size),
            "top_share": float(shares[0])}


def lines_text(e: dict[str, Any]) -> str:
    """The probe's main lines in words, or the band of a structure with none dominant."""
    sp = e.get("spread")
    if sp is not None:
        return (f"no dominant line: {sp['bins']} significant bins, half of their excess at "
                f"{sp['low']:.4g}-{sp['high']:.4g} Hz, peak {sp['peak']:.4g} Hz "
                f"(the strongest line {sp['top_share']:.0%})")
    lines = ", ".join(
        (f"order {ln['order']['order']:g} of {ln['order']['shaft']}" +
         (" (angle-locked while it changes speed)" if ln["order"].get("locking") else "")
         if "order" in ln
         else f"{ln['frequency']:.4g} Hz" + (" (time-locked)" if ln.get("locking", "time")
                                              else "")) + f" ({ln['share']:.0%})"
        for ln in e["lines"][:3])
    return f"lines at {lines}" if lines else ""


def _resolution(lines) -> float:
    return float(np.min(np.diff(np.sort(lines.freqs)))) if lines.freqs.size > 1 else 0.0


def _timing(t: np.ndarray, r: np.ndarray, sigma: float) -> dict[str, Any]:
    """Where in the record the residual ``r`` [probe unit] is large: transient when some
    windows' rms is over twice the median window's and one's over three times (an event
    and what follows it), or when a few windows hold a bump over a record otherwise at its
    noise level ``sigma`` [probe unit] that the rms hides (``_bump``); else steady."""
    edges = np.linspace(0, r.size, WINDOWS + 1).astype(int)
    rms = np.array([math.sqrt(float(np.mean(np.square(r[a:b])))) if b > a else 0.0
                    for a, b in itertools.pairwise(edges)])
    med = float(np.median(rms))
    strong = [i for i, v in enumerate(rms) if v > 2 * med]
    if strong and max(rms) > 3 * med:
        kind = "transient"
    else:  # a steady structure still names a window whose rms is twice the median's
        bump = _bump(rms**2, sigma**2, int(np.min(np.diff(edges))))
        kind = "transient" if bump else "steady"
        strong = bump or strong
    span = [[float(t[edges[i]]), float(t[min(edges[i + 1], t.size - 1)])]
            for i in range(WINDOWS)]
    onset = _onset(rms**2, sigma**2, int(np.min(np.diff(edges))))
    return {"kind": kind, "rms_by_window": rms.tolist(),
            "strongest": [span[i] for i in strong[:3]],
            **({"onset": span[onset]} if onset is not None else {})}


def _onset(power: np.ndarray, noise: float, m: int) -> int | None:
    """The window in which a structure starts that then lasts to the end of the record, from
    each window's mean square ``power`` [unit^2] of ``m`` samples or more: every window
    before it within four chi-square standard deviations of the white ``noise`` level
    [unit^2], every one from it on beyond them (a load that lands on a conveyor at 2 s and
    stays, which the windows' rms, raised over most of the record, calls steady). None for
    a structure over the whole record, one that ends, or noise alone."""
    if noise <= 0.0:
        return None
    above = power > noise * (1.0 + 4.0 * math.sqrt(2.0 / max(m, 1)))
    k = int(np.argmax(above)) if above.any() else power.size
    return k if 0 < k < power.size and bool(above[k:].all()) else None


def _bump(power: np.ndarray, noise: float, m: int) -> list[int]:
    """The windows of a bump that the rms hides (a rub's pulses as a fan runs up: 3.4 times
    the noise power in one window, an rms 1.8 times the others'), from each window's mean
    square ``power`` [unit^2] of ``m`` samples or more: the quietest three (their mean) must
    be at the white ``noise`` level [unit^2] (twice it at most: a steady structure fills
    them too, and a cogging everywhere is no bump); then the at most three windows that hold
    three quarters of the power above them, each beyond four of its chi-square standard
    deviations, the first at least twice it. None when the excess spreads wider (a ripple
    whose amplitude grows in proportion to the time: 69 % in the last three of ten windows)
    or stays within the noise's own spread."""
    floor = float(np.mean(np.sort(power)[:3]))
    if not 0.0 < floor <= 2.0 * noise:
        return []
    excess = np.clip(power - floor, 0.0, None)
    top = [int(i) for i in np.argsort(-excess, kind="stable")[:3]
           if power[i] > floor * (1.0 + 4.0 * math.sqrt(2.0 / max(m, 1)))]
    if not top or excess[top[0]] < floor or excess[top].sum() < 0.75 * excess.sum():
        return []
    return top


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
    if np.ptp(power) == 0.0:  # no window above the noise: nothing rises with anything
        return []
    drivers = {"time": t}
    for q, x in drivers_of(state.fit.sim, setup.probes).items():
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


def _model_text(entry: dict[str, Any]) -> str:
    follow = entry.get("follows_model")
    if not follow:
        return ""
    return (f"; follows the model's own {' and '.join(follow['signals'])} (ΔBIC "
            f"{follow['delta_bic']:.0f} through its noise filters): no sensor noise does")


def _note(probes: dict[str, Any], resolved: list[str] | None = None,
          coloured: dict[str, Any] | None = None) -> str:
    hum = "".join(f"; {p}'s excess is mostly one line, {c['line']['frequency']:.4g} Hz "
                  f"({c['line']['share']:.0%}): an interference at a fixed frequency (mains "
                  f"hum, a PWM beat) reads so" for p, c in (coloured or {}).items()
                  if "line" in c)
    own = (f" ({', '.join(coloured)}: otherwise noise, not white beyond its noise model, "
           f"and neither another probe nor the model's own signals follow it: not counted "
           f"as structure{hum})") if coloured else ""
    if not probes:
        if resolved:
            return (f"nothing significant remains: the model matches {', '.join(resolved)} to "
                    f"within {RESOLUTION:g} of the spread, finer than any record resolves"
                    + own)
        return "nothing significant remains: the residual is noise" + own
    parts = []
    for p, e in probes.items():
        lines = lines_text(e)
        when = e["timing"]
        span = "; strongest " + ", ".join(f"{a:.3g}-{b:.3g} s" for a, b in when["strongest"]) \
            if when["strongest"] else ""
        if "onset" in when:
            a, b = when["onset"]
            span += f"; starts in {a:.3g}-{b:.3g} s and lasts to the end (at its noise before)"
        level = e.get("rms_over_noise", math.nan)
        rms = f"rms {level:.3g} times its white noise, " if math.isfinite(level) else ""
        parts.append(f"{p}: {rms}"
                     f"{e['structured_share']:.0%} of the prewhitened residual structure, "
                     f"{when['kind']}{span}" + _follow_text(e) + band_text(e.get("band")) +
                     _model_text(e) +
                     (f"; {lines}" if lines else "") +
                     ("" if e["white_after_prewhitening"] else "; not white"))
    return "something remains that no catalog effect explains -- " + " | ".join(parts) + own
