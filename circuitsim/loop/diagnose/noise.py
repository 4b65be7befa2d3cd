"""Stage: a noise model for the residual, so that test statistics mean what they say.

Measured noise is rarely white: an anti-alias filter, a speed estimate from encoder counts or
a drifting offset colour it. An output-error fit whose residual is coloured looks far more
certain than it is, and a likelihood-ratio test on it accepts effects that only fit the
noise's slow wander. Each probe's residual is therefore *prewhitened* by an autoregressive
filter (order chosen by BIC, Levinson-Durbin on the sample autocovariance) before any sum of
squares is compared.

Two models are compared with the filter estimated on the residual of the *richer* one: that
residual is the closer to pure noise, and a filter estimated on the poorer one would learn the
missing effect as "predictable noise" and hide it.

The decision never divides by an estimate of the noise floor: a few-percent error of that
estimate is as large as a marginal effect's whole signature. The likelihood ratio uses the
ratio of each probe's whitened sums of squares (a profile likelihood with a free noise
variance per probe), which needs no floor at all -- and is taken a second time where either
model's residual, otherwise noise, has a long memory (a 1/f rise an AR filter of low order
cannot follow): the memory read by conditional sum of squares and removed by a fractional
difference, both models refitted under that noise by generalised least squares (linearised
about the poorer one), so that a regressor fitting the noise's slow wander gains nothing the
poorer model's own refit does not; the share of *structure* an
effect explains is measured against the significant lines of the whitened residual's
periodogram, whose background is a median over the spectrum, not a global floor.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.fft
from scipy.ndimage import median_filter

MAX_AR_ORDER = 6
TIME_WINDOWS = 20  # windows for telling a transient from the typical residual
LINE_FALSE_ALARM = 0.01  # chance that pure noise shows one "significant" line in a spectrum


@dataclass(frozen=True)
class Whitener:
    """An AR(p) prewhitening filter e[n] = r[n] + a1 r[n-1] + ... + ap r[n-p], after a
    fractional difference (1 - B)^d when the noise has long memory (``d`` > 0)."""

    a: tuple[float, ...]  # (a1 .. ap); () is white
    sigma: float  # innovation standard deviation [probe unit]
    d: float = 0.0  # fractional order of the long memory taken out first [-]

    def apply(self, r: np.ndarray) -> np.ndarray:
        r = np.asarray(r, float)
        if self.d:
            r = fractional_difference(r, self.d)
        if not self.a:
            return r
        p = len(self.a)
        out = r[p:].copy()
        for k, ak in enumerate(self.a, start=1):
            out += ak * r[p - k:r.size - k]
        return out


def _autocovariance(r: np.ndarray, lags: int) -> np.ndarray:
    x = r - r.mean()
    n = x.size
    size = linear_size(n)
    f = scipy.fft.rfft(x, size)
    acov = scipy.fft.irfft(f * np.conj(f), size)[: lags + 1] / n
    return acov


def _quiet(r: np.ndarray) -> np.ndarray:
    """The residual without the time windows that stand out (a transient): the noise's
    colour is learnt where the residual is typical, so that a start-up error is not taken
    for slowly wandering noise."""
    m = r.size // TIME_WINDOWS
    if m < 8:
        return r
    power = np.square(r[: m * TIME_WINDOWS] - r.mean()).reshape(TIME_WINDOWS, m).sum(axis=1)
    typical = float(np.median(power))
    keep = power <= typical * (1.0 + 4.0 * math.sqrt(2.0 / m))
    return r[: m * TIME_WINDOWS].reshape(TIME_WINDOWS, m)[keep].ravel()


def fit_whitener(r: np.ndarray, max_order: int = MAX_AR_ORDER) -> Whitener:
    """The AR prewhitening filter of a residual, its order chosen by BIC (0 = white),
    estimated on its typical windows."""
    r = _quiet(np.asarray(r, float))
    n = r.size
    acov = _autocovariance(r, max_order)
    if acov[0] <= 0.0 or n < 10 * (max_order + 1):
        return Whitener((), float(math.sqrt(max(acov[0], 0.0))))
    best = (n * math.log(acov[0]), (), acov[0])
    a = np.zeros(0)
    err = acov[0]
    for p in range(1, max_order + 1):  # Levinson-Durbin recursion
        k = -(acov[p] + float(a @ acov[p - 1:0:-1])) / err if p > 1 else -acov[1] / err
        a = np.concatenate([a + k * a[::-1], [k]])
        err *= 1.0 - k * k
        if err <= 0.0:
            break
        bic = n * math.log(err) + p * math.log(n)
        if bic < best[0] - 2.0:
            best = (bic, tuple(float(v) for v in a), err)
    return Whitener(best[1], float(math.sqrt(best[2])))


def memory_order(r: np.ndarray) -> float:
    """The fractional order d of a residual's long memory (its spectrum rising as f^-2d
    towards zero frequency: 1/f noise is d = 0.5), by the log-periodogram regression of
    Geweke and Porter-Hudak on the lowest sqrt(n) frequencies, lines left out; 0 unless it
    exceeds twice its standard error pi / sqrt(24 m). An AR filter of low order cannot
    follow such a rise, and what lives at those frequencies -- a gain on a slow speed
    profile, an offset, a drift -- then looks far more certain than it is."""
    n = np.size(r)
    m = int(math.sqrt(n))
    if m < 8:
        return 0.0
    power = _low_periodogram(r, m)
    if np.any(power <= 0.0):
        return 0.0
    # lines are structure, not memory (a slow shaft's cogging orders sit among these bins)
    keep = _not_lines(power, m)
    if keep.sum() < 8:
        return 0.0
    lam = 2.0 * math.pi * np.arange(1, m + 1)[keep] / n
    z = np.log(4.0 * np.sin(lam / 2.0) ** 2)
    z = z - z.mean()
    logp = np.log(power[keep])
    d = -float(z @ (logp - logp.mean()) / (z @ z))
    return min(d, 0.49) if d > 2.0 * math.pi / math.sqrt(24.0 * keep.sum()) else 0.0


#: The lowest n^PERTURBED_BINS periodogram bins a long memory seen through white noise is
#: read on: the sqrt(n) of the log-periodogram regression hold too few where a white part
#: flattens them (a 1/f speed noise of 0.02 beside white noise of 0.015, 6 s at 200 Hz: d
#: 0.17 on its 32 lowest bins, under the regression's threshold of 0.23).
PERTURBED_BINS = 0.7
#: The likelihood ratio a long memory under white noise must reach against a flat spectrum
#: and against an AR(1) one (a short memory) on those bins: chi-square of one parameter
#: at 1e-3.
PERTURBED_LR = 10.8


def perturbed_memory_order(r: np.ndarray) -> float:
    """The fractional order d of a long memory seen through white noise: the Whittle fit of
    the spectrum w + c |2 sin(lambda/2)|^(-2d) on the lowest n^``PERTURBED_BINS``
    frequencies, lines left out (the perturbed fractional process of Hurvich and Ray, and
    Sun and Phillips); 0 unless it beats both a flat spectrum and an AR(1) one -- a short
    memory, which rises towards zero frequency too -- by ``PERTURBED_LR``. Where white noise
    lies over a 1/f noise, ``memory_order``'s regression on the lowest sqrt(n) bins sees the
    sum, whose slope there is far less than the memory's own."""
    n = np.size(r)
    m = min(n // 2 - 1, int(n ** PERTURBED_BINS))
    if m < 16:
        return 0.0
    power = _low_periodogram(r, m) / n
    keep = _not_lines(power, m)
    power = power[keep]
    if power.size < 16 or not np.all(power > 0.0):
        return 0.0
    lam = 2.0 * math.pi * np.arange(1, m + 1)[keep] / n
    g = 4.0 * np.sin(lam / 2.0) ** 2
    scale = float(np.mean(power))
    power = power / scale  # the Whittle sums on a unit level: no overflow in the exponents

    def whittle(f: np.ndarray) -> float:
        return float(np.sum(np.log(f) + power / f))

    def memory(p: np.ndarray) -> float:
        return whittle(np.exp(p[0]) + np.exp(p[1] - p[2] * np.log(g)))

    def short(p: np.ndarray) -> float:  # AR(1) of coefficient tanh(p[1])
        phi = math.tanh(p[1])
        return whittle(np.exp(p[0]) / (1.0 + phi * phi - 2.0 * phi * np.cos(lam)))

    a = math.log(float(np.median(power[power.size // 2:])))  # the white level's start
    best = min((_minimum(memory, [a, a + c, d], [(-30, 30), (-30, 30), (0.0, 0.49)])
                for d in (0.1, 0.25, 0.45) for c in (-3.0, 0.0)), key=lambda o: o.fun)
    null = min(whittle(np.ones_like(power)),
               *(_minimum(short, [0.0, z], [(-30, 30), (-5, 5)]).fun for z in (0.3, 1.5)))
    return float(best.x[2]) if 2.0 * (null - best.fun) > PERTURBED_LR else 0.0


#: The bins per block of ``rises_to_zero``, and the factor [-] by which a block's geometric
#: mean power may stand above the lowest block's. A block's mean log-periodogram has a
#: standard deviation of pi / sqrt(6 * 8) = 0.45, a difference of two 0.64; a factor 10 (2.3
#: in the log, 3.6 of those) lies beyond the largest of 2 700 noises with memory (1/f under
#: white noise, AR(1) with phi 0.95, a Gauss-Markov noise with phi 0.995 on a plateau: 300
#: seeds each at 2 001, 12 501, 25 001 and 50 001 samples; the largest 2.07, the 99th
#: percentile at most 1.43).
SHAPE_BLOCK = 8
SHAPE_RISE = 10.0


def rises_to_zero(r: np.ndarray) -> bool:
    """Whether a residual's spectrum over its lowest sqrt(n) bins is highest at the lowest
    frequencies, as a long memory's f^-2d is: no block of ``SHAPE_BLOCK`` bins stands more
    than ``SHAPE_RISE`` above the lowest block in geometric mean. Lines count here: a line
    or a resonance's band over a flat floor rises away from zero, which no memory does,
    though the log-periodogram regression, fitted over the band's fall to the floor, reads
    it as one (fresh38's ap14: a motor housing rocking on its rubber mounts, a band at
    30-40 Hz 680 times the floor's median power beside 1.4 times at 0-5 Hz, read as d 0.49;
    its lowest block stands 2.7 in the log under the band's)."""
    blocks = int(math.sqrt(np.size(r))) // SHAPE_BLOCK
    if blocks < 2:
        return True
    power = _low_periodogram(r, blocks * SHAPE_BLOCK)
    if not np.all(power > 0.0):
        return True
    means = np.log(power).reshape(blocks, SHAPE_BLOCK).mean(axis=1)
    return float(np.max(means[1:]) - means[0]) <= math.log(SHAPE_RISE)


def _low_periodogram(r: np.ndarray, m: int) -> np.ndarray:
    """|FFT|^2 of the residual less its mean at its lowest ``m`` non-zero frequencies [the
    residual's unit squared times samples]: what the memory's order and shape are read on."""
    x = np.asarray(r, float) - float(np.mean(r))
    return np.abs(np.fft.rfft(x)[1:m + 1]) ** 2


def _not_lines(power: np.ndarray, m: int) -> np.ndarray:
    """The periodogram bins of ``power`` (the lowest ``m``) that are no line: under the line
    threshold over their neighbours' median."""
    local = median_filter(power, size=9, mode="nearest") / math.log(2.0)
    return power <= line_threshold(m) * local


def _minimum(fun: Callable[[np.ndarray], float], start: list[float],
             bounds: list[tuple[float, float]]) -> Any:
    from scipy.optimize import minimize

    return minimize(fun, np.asarray(start, float), method="L-BFGS-B", bounds=bounds)


def fractional_difference(r: np.ndarray, d: float) -> np.ndarray:
    """(1 - B)^d r: the binomial weights pi_k = pi_(k-1) (k - 1 - d) / k over the whole
    record, applied as a causal convolution (by FFT)."""
    r = np.asarray(r, float)
    n = r.size
    size = linear_size(n)
    return scipy.fft.irfft(scipy.fft.rfft(r, size) * _weights(n, d, size), size)[:n]


@functools.lru_cache(maxsize=8)
def _weights(n: int, d: float, size: int) -> np.ndarray:
    """The spectrum of (1 - B)^d's first ``n`` weights, zero-padded to ``size``: one whitener
    filters hundreds of columns in a scan."""
    k = np.arange(1, n)
    w = np.concatenate([[1.0], np.cumprod((k - 1 - d) / k)])
    out = scipy.fft.rfft(w, size)
    out.flags.writeable = False
    return out


def linear_size(n: int) -> int:
    """The FFT length for a linear (not circular) convolution of two n-sample signals: the
    smallest 2-3-5-smooth length >= 2n - 1 (a power of two, as used before, was up to twice
    as long and twice as slow)."""
    return scipy.fft.next_fast_len(2 * n - 1, real=True)


def memory_whiteners(residuals: Mapping[str, np.ndarray], probes: Sequence[str]
                     ) -> dict[str, Whitener]:
    """Per probe, the long-memory whitener: the fractional difference of the residual's
    ``memory_order``, then the AR filter of what it leaves (the plain AR filter where the
    residual has no long memory, or holds more structure than ``MEMORY_STRUCTURE_MAX``)."""
    out = {}
    for p in probes:
        r = np.asarray(residuals[p], float)
        quiet = _quiet(r)  # the memory is read where the residual is typical, as the AR is
        d = memory_order(quiet) if _noise_like(quiet) else 0.0
        base = fit_whitener(fractional_difference(r, d) if d else r)
        out[p] = Whitener(base.a, base.sigma, d)
    return out


#: Share of a residual's whitened sum of squares that may be structure (lines, a transient)
#: for a low-frequency rise in it to be read as the noise's long memory: in a residual full
#: of structure the rise is that structure (a slow shaft's cogging orders crowd the lowest
#: bins of the ODrive log, smeared by its speed ripple past any line test) and taking it out
#: would hide it.
MEMORY_STRUCTURE_MAX = 0.1


def _noise_like(r: np.ndarray) -> bool:
    e = fit_whitener(r).apply(r)
    lines = significant_lines(e, 1.0)
    return max(lines.structured, transient_excess(e)) <= MEMORY_STRUCTURE_MAX * lines.total


#: The fractional orders [-] the conditional-sum-of-squares fit of a long memory tries first;
#: it then refines about the best of them by half the spacing.
CSS_ORDERS = (*(round(0.05 * k, 2) for k in range(10)), 0.49)


def own_memory_whitener(r: np.ndarray) -> Whitener:
    """The residual's ARFIMA(p, d, 0) noise by conditional sum of squares: the d of least
    innovation variance, each d's fractional difference followed by the AR filter (order
    by BIC) of what it leaves (Chung and Baillie 1993; Beran 1995). Unlike the
    log-periodogram regression of ``memory_order``, it reads a memory under white noise
    whose rise a slow regressor has partly taken away (fresh57's bi01: d 0.34 on the
    declared model's load-speed residual, and still 0.34 once a 0.02 % gain took the
    wander the regression read as none)."""
    r = np.asarray(r, float)

    def innovations(d: float) -> tuple[float, Whitener]:
        x = fractional_difference(r, d) if d else r
        w = fit_whitener(x)
        e = w.apply(x)
        return float(e @ e) / e.size, Whitener(w.a, w.sigma, d)

    tried = {d: innovations(d) for d in CSS_ORDERS}
    best = min(tried, key=lambda d: tried[d][0])
    for d in (best - 0.025, best + 0.025):
        if 0.0 < d < 0.5:
            tried[d] = innovations(d)
    return min(tried.values(), key=lambda v: v[0])[1]


def projected_sse(r: Mapping[str, np.ndarray], columns: Mapping[str, np.ndarray],
                  whiteners: Mapping[str, Whitener], probes: Sequence[str]
                  ) -> dict[str, float]:
    """Per probe, the whitened sum of squares [probe unit^2] of ``r`` less its generalised
    least-squares fit by ``columns`` (per probe, an (n, m) array of the same m regressors):
    every probe whitened by its own filter and scaled by its innovations' deviation, so
    that the fit weights each probe's samples as its noise says."""
    rows, cols, sizes = [], [], []
    for p in probes:
        w = whiteners[p]
        e = w.apply(r[p])
        scale = math.sqrt(float(e @ e) / e.size) or 1.0
        rows.append(e / scale)
        x = np.asarray(columns[p], float)
        cols.append(np.column_stack([w.apply(c) for c in x.T]) / scale if x.shape[1]
                    else np.zeros((e.size, 0)))
        sizes.append((e.size, scale))
    b, A = np.concatenate(rows), np.vstack(cols)
    if A.shape[1]:
        b = b - A @ np.linalg.lstsq(A, b, rcond=None)[0]
    out, at = {}, 0
    for p, (m, scale) in zip(probes, sizes, strict=True):
        out[p] = float(b[at:at + m] @ b[at:at + m]) * scale * scale
        at += m
    return out


def whitened_sse(residuals: Mapping[str, np.ndarray], whiteners: Mapping[str, Whitener],
                 probes: Sequence[str]) -> dict[str, float]:
    """Sum of squares of each probe's prewhitened residual [probe unit^2]."""
    out = {}
    for p in probes:
        e = whiteners[p].apply(residuals[p])
        out[p] = float(e @ e)
    return out


def whiteners_of(residuals: Mapping[str, np.ndarray], probes: Sequence[str]
                 ) -> dict[str, Whitener]:
    return {p: fit_whitener(np.asarray(residuals[p], float)) for p in probes}


def delta_bic(sse_new: Mapping[str, float], sse_old: Mapping[str, float], n: int,
              k: int, probes: Sequence[str]) -> float:
    """BIC change of adding ``k`` parameters: a Gaussian profile likelihood with its own
    noise variance per probe, on prewhitened residuals of ``n`` samples a probe."""
    ll = sum(n * math.log(max(sse_new[p], 1e-300) / max(sse_old[p], 1e-300)) for p in probes)
    return ll + k * math.log(n * len(probes))


def line_threshold(n_bins: int) -> float:
    """Power, in units of the background mean, that pure noise exceeds in any of ``n_bins``
    periodogram bins with probability LINE_FALSE_ALARM (exponential bins, Bonferroni)."""
    return math.log(max(n_bins, 1) / LINE_FALSE_ALARM)


@dataclass(frozen=True)
class Lines:
    """Significant lines of a whitened residual's periodogram."""

    freqs: np.ndarray  # [Hz] of each significant bin
    excess: np.ndarray  # its power above the background [probe unit^2, as a share of SSE]
    total: float  # sum of squares of the whitened residual
    structured: float  # sum of the excess powers (same unit as total)


def significant_lines(e: np.ndarray, dt: float) -> Lines:
    """The periodogram bins of ``e`` (white up to structure) that noise cannot explain.

    Parseval's scaling: the bins' powers sum to the sum of squares of ``e``, so ``structured``
    is directly comparable with a fit's gain in sum of squares.
    """
    e = np.asarray(e, float)
    n = e.size
    spec = np.abs(np.fft.rfft(e)) ** 2
    weight = np.full(spec.size, 2.0)
    weight[0] = 1.0
    if n % 2 == 0:
        weight[-1] = 1.0
    power = spec * weight / n  # sums to e @ e
    body = power[1:] if power.size > 2 else power
    background = float(np.median(body)) / math.log(2.0) if body.size else 0.0
    if background <= 0.0:
        return Lines(np.zeros(0), np.zeros(0), float(e @ e), 0.0)
    hit = power > line_threshold(power.size) * background
    freqs = np.fft.rfftfreq(n, dt)[hit]
    excess = power[hit] - background
    return Lines(freqs, excess, float(e @ e), float(excess.sum()))



def lines_of(e: np.ndarray, t: np.ndarray, r: np.ndarray, whitener: Whitener) -> Lines:
    """``significant_lines`` of ``e``, the residual ``r`` [probe unit] at times ``t`` [s]
    prewhitened by ``whitener``. A periodogram needs one sampling interval: where ``t`` is
    uneven (a logger's timestamps, whose varying intervals accumulate into a phase that
    wanders: 0.4 s over the ODrive's slow log, and a line at a tenth of the sampling rate
    vanishes), ``r`` is interpolated onto an even grid of as many samples over the same span,
    whitened there by its own filter (the interpolation colours the noise, which a median
    background would take for lines), and the lines' powers brought back to ``e``'s units
    by the ratio of the two innovation variances, and their total with them. On even times
    this is ``significant_lines(e, dt)`` itself."""
    from circuitsim.loop.record import even_grid

    t = np.asarray(t, float)
    grid = even_grid(t)
    if grid is t:
        return significant_lines(e, float(np.mean(np.diff(t))))
    moved = np.interp(grid, t, np.asarray(r, float))
    if whitener.d:  # the long memory the record grid's whitener takes out, taken out here
        moved = fractional_difference(moved, whitener.d)
    own = fit_whitener(moved)
    lines = significant_lines(own.apply(moved), float(grid[1] - grid[0]))
    scale = (whitener.sigma / own.sigma) ** 2 if own.sigma > 0.0 else 1.0
    # the total on the same grid and scale as the lines, so that their share is one of the
    # same spectrum (the record grid's own total held less than the even grid's lines
    # where its whitener followed a transient the even grid's did not: shares over 1)
    return Lines(lines.freqs, lines.excess * scale, lines.total * scale,
                 lines.structured * scale)


def transient_excess(e: np.ndarray) -> float:
    """Sum of squares of ``e`` (a whitened residual) that sits in time windows standing out
    above the typical window: a transient's structure, which a periodogram spreads over many
    bins none of which is significant alone. The typical window is the median one, so the
    measure needs no noise floor; a window counts when it exceeds the median by four of its
    chi-square standard deviations."""
    e = np.asarray(e, float)
    m = e.size // TIME_WINDOWS
    if m < 8:
        return 0.0
    power = np.square(e[: m * TIME_WINDOWS]).reshape(TIME_WINDOWS, m).sum(axis=1)
    typical = float(np.median(power))
    limit = typical * (1.0 + 4.0 * math.sqrt(2.0 / m))
    return float(np.sum(np.clip(power - typical, 0.0, None)[power > limit]))
