"""A long record brought to the resolution its content needs, before a fit or a diagnosis.

A record sampled far faster than anything in it changes (a 1 MHz logger on a motor whose
fastest time constant is a millisecond) costs every simulation of a fit an output point per
sample -- the integrator then spends 40x longer handing back output than integrating, and the
residuals, Jacobians and spectra of the fit and the diagnosis grow with it -- while the
samples beyond the content carry nothing but noise. :func:`reduce_record` therefore

1. finds, per probe, the highest frequency at which the record holds more than white noise:
   the periodogram in quarter-octave bands against the noise floor (the lowest band median),
   a band counting when its mean stands five standard errors above the floor, and any single
   bin counting above the same 1 % false-alarm line level the diagnosis uses;
2. chooses the largest decimation factor q whose anti-alias filter stays flat (to 2e-7) up to
   twice that frequency, and never fewer than ``WORK_ROWS`` rows;
3. filters every column with a zero-phase FIR that keeps white noise white (``_filter``) and
   keeps every q-th sample at its own time.

The filter removes only noise, so the estimates and their standard errors are those of the
whole record (the information of a band-limited signal in white noise does not depend on the
sampling rate once it exceeds the band), while the noise of the working record is its own:
1/sqrt(q) of the original's, and still white. Every statistic downstream (weights, whiteners,
BIC, standard errors) is computed on the working record, never with the original's noise
level.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from circuitsim.loop.record import Record, even_grid

WORK_ROWS = 50_000  # a record is reduced to no fewer rows (spectra and windows need them)
MARGIN = 2.0  # the filter's flat band reaches this factor beyond the highest content
PASS = 0.6  # flat (2e-7) passband edge of the filter, as a fraction of the working Nyquist
ROLL_OFF = 0.3  # the filter's transition band: (1 -+ ROLL_OFF) x the working Nyquist
BANDS_PER_OCTAVE = 4
BAND_Z = 5.0  # standard errors above the floor at which a band holds content
LINE_FALSE_ALARM = 0.01  # as the diagnosis's line test (diagnose.noise)
FLOOR_BINS = 1024  # bins a band needs to serve as the noise floor
JITTER = 1e-3  # relative spread of the sample spacing beyond which the grid is resampled


@dataclass(frozen=True)
class Reduction:
    """What :func:`reduce_record` did to a record.

    rows, working_rows : samples before and after.
    factor : the decimation factor q (1: the record is used as it is).
    rate : the record's mean sample rate [Hz].
    content : highest frequency with significant content over the probes [Hz] (NaN: not
        measured).
    reason : why, in words.
    resampled : the time grid was not uniform and was interpolated onto one first.
    """

    rows: int
    working_rows: int
    factor: int
    rate: float
    content: float
    reason: str
    resampled: bool = False

    @property
    def reduced(self) -> bool:
        return self.factor > 1

    @property
    def passband(self) -> float:
        """Edge of the filter's flat band [Hz] (the record's Nyquist frequency if not reduced)."""
        return PASS * self.rate / (2 * self.factor) if self.reduced else self.rate / 2

    def note(self) -> str:
        """One line for the report."""
        if not self.reduced:
            return f"record: {self.rows} rows, all used ({self.reason})"
        grid = ", resampled onto a uniform grid first" if self.resampled else ""
        return (f"record: {self.rows} rows reduced to {self.working_rows} for fitting (one "
                f"row in {self.factor}, after an anti-alias filter flat to "
                f"{self.passband:.4g} Hz{grid}): {self.reason}")

    def as_dict(self) -> dict:
        return {"rows": self.rows, "working_rows": self.working_rows, "factor": self.factor,
                "rate_hz": self.rate,
                "content_hz": self.content if math.isfinite(self.content) else None,
                "passband_hz": self.passband, "resampled": self.resampled,
                "note": self.note()}


def reduce_record(record: Record, probes: Sequence[str] | None = None, *,
                  work_rows: int = WORK_ROWS,
                  progress: Callable[[str], None] | None = None) -> tuple[Record, Reduction]:
    """The record at the resolution its content needs (see the module docstring).

    Parameters
    ----------
    record : the measured record.
    probes : the columns whose content decides the resolution (default: every column).
    work_rows : fewest rows of the working record; a record of fewer than twice as many is
        returned as it is.
    progress : called with a line of text.

    Returns
    -------
    (Record, Reduction)
        The working record (the same object when nothing is reduced; its times are the
        original sample times kept) and what was done.
    """
    t = np.asarray(record.t, float)
    n = t.size
    rate = (n - 1) / float(t[-1] - t[0]) if n > 1 and t[-1] > t[0] else float("nan")
    if n < 2 * work_rows:
        return record, Reduction(n, n, 1, rate, float("nan"),
                                 f"fewer than {2 * work_rows} rows")
    if progress is not None:
        progress(f"record: {n} rows; finding its content")
    # a probe the record lacks is the caller's to report; the content of what is there decides
    names = [p for p in (probes or ()) if p in record.columns] or list(record.names)
    # on the samples as they are: interpolation would colour the noise and pass for content
    content = max(_content(np.asarray(record[p], float), rate) for p in names)
    q = min(int(PASS * rate / (2 * MARGIN * content)), n // work_rows)
    nyquist = rate / 2
    if q < 2:
        return record, Reduction(n, n, 1, rate, content,
                                 f"its content reaches {content:.4g} Hz of the {nyquist:.4g} "
                                 f"Hz it can hold: not oversampled")
    if progress is not None:
        progress(f"record: filtering, then keeping one row in {q} of {n}")
    grid = even_grid(t, JITTER)
    resampled = grid is not t
    out = {k: _decimate(np.interp(grid, t, v) if resampled else np.asarray(v, float), q)
           for k, v in record.columns.items()}
    t_work = grid[::q]
    reason = (f"its content ends near {content:.4g} Hz, {nyquist / content:.0f}x below its "
              f"Nyquist frequency ({nyquist:.4g} Hz); the rest is noise")
    return (Record(np.ascontiguousarray(t_work), out, record.path),
            Reduction(n, t_work.size, q, rate, content, reason, resampled))


def _content(x: np.ndarray, rate: float) -> float:
    """Highest frequency [Hz] at which ``x`` holds more than white noise (see the module
    docstring); the record's Nyquist frequency when no noise floor can be found."""
    n = x.size
    # a cubic through the ends' values and slopes makes the periodic extension smooth, so
    # neither the jump nor the kink between the ends leaks into every bin as "content"
    power = np.abs(np.fft.rfft(x - _end_cubic(x)))[1:] ** 2
    m = power.size
    edges = np.unique(np.geomspace(1, m + 1, int(BANDS_PER_OCTAVE * math.log2(m + 1)) + 2)
                      .astype(int)) - 1
    bands = [(int(a), int(b)) for a, b in itertools.pairwise(edges)]
    medians = [(float(np.median(power[a:b])), b - a) for a, b in bands if b - a >= FLOOR_BINS]
    if not medians:
        return rate / 2
    floor_median, floor_bins = min(medians)
    floor = floor_median / math.log(2.0)  # an exponential's median is ln 2 of its mean
    if floor <= 0.0:
        return rate / 2
    top = 0
    for a, b in bands:
        size = b - a
        limit = floor * (1.0 + BAND_Z * math.sqrt(1.0 / size + 2.1 / floor_bins))
        if float(np.mean(power[a:b])) > limit:
            top = max(top, b)
    lines = np.flatnonzero(power > floor * math.log(m / LINE_FALSE_ALARM))
    if lines.size:
        top = max(top, int(lines[-1]) + 1)
    return max(top, 1) * rate / n


def _end_cubic(x: np.ndarray, k: int = 64) -> np.ndarray:
    """The cubic (Hermite) with the value and slope of least-squares lines through the first
    and the last ``k`` samples of ``x`` at its two ends."""
    n = x.size
    k = min(k, n // 8)
    s = np.arange(k, dtype=float)
    s0, v0 = np.polyfit(s, x[:k], 1)
    s1, c1 = np.polyfit(s, x[-k:], 1)
    v1 = c1 + s1 * (k - 1)
    u = np.linspace(0.0, 1.0, n)
    span = n - 1
    return ((2 * u**3 - 3 * u**2 + 1) * v0 + (u**3 - 2 * u**2 + u) * span * s0 +
            (-2 * u**3 + 3 * u**2) * v1 + (u**3 - u**2) * span * s1)


def _decimate(x: np.ndarray, q: int) -> np.ndarray:
    """Every q-th sample of ``x`` after the zero-phase anti-alias filter of ``_filter``;
    sample j is at the time of x[j q]."""
    from scipy.signal import resample_poly

    h = _filter(q)
    pad = -(-(h.size // 2 + q) // q) * q  # a multiple of q keeps output j on input j q
    head = _extend(x[: pad + 1][::-1], pad, 8 * q)[::-1]
    tail = _extend(x[-pad - 1:], pad, 8 * q)
    y = resample_poly(np.concatenate([head, x, tail]), 1, q, window=h, padtype="constant")
    start = pad // q
    return np.ascontiguousarray(y[start:start + -(-x.size // q)])


def _filter(q: int) -> np.ndarray:
    """FIR taps (60 q + 1, Kaiser-windowed) whose squared response is a raised cosine about
    the working Nyquist frequency N = 1/q (of the input's), from 0.7 N to 1.3 N.

    The power such a filter takes from just below N it lets through from just above, and
    the decimation folds the one onto the other: white noise comes out white (Ljung-Box
    whiteness p-values uniform over 30 seeds, the third-difference noise estimate of the
    diagnosis within 2 %), where a plain low-pass with its edge below N leaves a dip under
    the Nyquist frequency that the diagnosis reads as coloured noise. Flat to 2e-7 up to
    PASS = 0.6 N; 118 dB down beyond 1.4 N."""
    from scipy.signal import firwin2

    lo, hi = (1.0 - ROLL_OFF) / q, (1.0 + ROLL_OFF) / q
    freq = np.concatenate([[0.0], np.linspace(lo, hi, 201), [1.0]])
    u = np.clip((freq - lo) / (hi - lo), 0.0, 1.0)
    gain = np.sqrt(0.5 * (1.0 + np.cos(np.pi * u)))
    taps = 60 * q + 1
    # a fine design grid: the transition band is a few hundredths of the input's band
    grid = 1 + 2 ** (math.ceil(math.log2(taps)) + 4)
    return firwin2(taps, freq, gain, window=("kaiser", 8.0), nfreqs=grid)


def _extend(end: np.ndarray, pad: int, fit: int) -> np.ndarray:
    """``pad`` samples continuing ``end`` (its last pad + 1 samples, in time order) beyond its
    last one: the point reflection about the end value of a quadratic fitted to the last
    ``fit`` samples, so that value and slope continue and no single noisy sample is the
    pivot. The fit is short (a few working samples), so a curved start-up transient does not
    bend it."""
    fit = min(fit, end.size)
    s = np.arange(fit, dtype=float)
    pivot = float(np.polyval(np.polyfit(s, end[-fit:], 2), fit - 1))
    # x[N-1+j] ~ 2 pivot - x[N-1-j]: an odd continuation about the fitted end value
    return 2.0 * pivot - end[-2::-1]
