"""Spectral post-processing of simulated waveforms.

Accurate estimation of one sinusoidal component (frequency, peak amplitude, phase) of a
sampled waveform whose record does *not* hold an integer number of periods, as is normal
for simulator output with adaptive time steps.

The estimator in :func:`harmonic` works in three stages:

1. a coarse estimate from a Hann-windowed, zero-padded FFT of the record after linear
   resampling onto a uniform grid and removal of mean and linear trend;
2. log-parabolic interpolation of the spectral peak;
3. a variable-projection least-squares fit on the *original* samples of
   ``offset + trend·(t - t_mid) + a·sin(2πf(t - t_mid)) + b·cos(2πf(t - t_mid))``
   (optionally plus the 2nd and 3rd harmonic), in which the linear coefficients are
   eliminated by linear least squares and only ``f`` is searched with a bounded scalar
   minimiser.

Stage 3 uses the raw samples because linear interpolation onto a uniform grid attenuates
a sine by a factor that depends on the number of samples per period; the FFT estimate
only has to land within a fraction of a bin for the least-squares stage to converge.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["Harmonic", "Ripple", "dominant_ripple", "harmonic", "resample_uniform",
           "ripple_summary", "spectrum"]

_MIN_SAMPLES = 8
_MIN_PERIODS = 2.0
# Zero padding makes the padded-bin spacing small enough that the log-parabolic
# interpolation bias of the Hann main lobe is far below one native bin.
_PAD_FACTOR = 4
# The least-squares cost is unimodal only within about one native bin of the true
# frequency; 1.5 bins leaves room for the coarse estimate's error without reaching the
# neighbouring local minima.
_SEARCH_HALF_WIDTH_BINS = 1.5
# Absolute tolerance of the frequency search in native bins; much finer than the 1e-6
# relative accuracy target even for records of only a few periods.
_SEARCH_XATOL_BINS = 1e-10
# Harmonic columns too close to Nyquist are nearly collinear with their aliases.
_HARMONIC_NYQUIST_MARGIN = 0.9
# Relative rms level (w.r.t. the largest |x|) below which a detrended record is treated as
# having no ripple at all: a few hundred ulps, i.e. round-off, not signal.
_NO_RIPPLE_REL_RMS = 1e3 * np.finfo(float).eps


_COSINE_WINDOWS = {
    "hann": (0.5, 0.5),
    "boxcar": (1.0,),
    "blackmanharris": (0.35875, 0.48829, 0.14128, 0.01168),
}


def _window(name: str, n: int) -> np.ndarray:
    """Periodic (FFT) window. The common cosine sums are written out because importing
    scipy.signal costs 0.3 s of start-up for every CLI call."""
    if name in _COSINE_WINDOWS:
        phase = 2 * np.pi * np.arange(n) / n
        return sum((-1) ** j * a * np.cos(j * phase)
                   for j, a in enumerate(_COSINE_WINDOWS[name])) * np.ones(n)
    import scipy.signal

    return scipy.signal.get_window(name, n, fftbins=True)


@dataclass(frozen=True)
class Harmonic:
    """One sinusoidal component fitted to a waveform.

    The fitted model is::

        x(t) ≈ offset + trend * (t - t_mid) + amplitude * sin(2π * frequency * t + phase)

    where ``t_mid = (t[0] + t[-1]) / 2`` is the midpoint of the analysed record.

    Phase convention: ``phase`` is referred to **absolute time t = 0** (not to the start
    of the record) and uses a **sine** reference, wrapped to ``[-π, π]``. A waveform
    ``A·cos(2πft)`` therefore has ``phase = +π/2`` and ``-A·sin(2πft)`` has
    ``phase = ±π``; ``amplitude`` is never negative. Because the reference is absolute,
    the phase of a record far from t = 0 is sensitive to frequency error
    (``dφ = 2π·t·df``); compare phases of several signals only at the same fitted
    frequency.

    Attributes
    ----------
    frequency : float
        Frequency of the component [Hz]; 0.0 when no component was found.
    amplitude : float
        Peak amplitude of the component [same unit as x]; never negative.
    phase : float
        Phase of the sine at absolute time t = 0 [rad], in ``[-π, π]``.
    offset : float
        Mean level of the fitted model at the record midpoint ``t_mid`` [same unit as x].
    rms_residual : float
        Root-mean-square of ``x - model`` over the original samples [same unit as x];
        includes any modelled extra harmonics, so it measures what the model misses.
    trend : float
        Slope of the fitted linear trend [unit of x per s].
    """

    frequency: float
    amplitude: float
    phase: float
    offset: float
    rms_residual: float
    trend: float = 0.0


def _as_record(t: object, x: object, min_samples: int) -> tuple[np.ndarray, np.ndarray]:
    """Validate a sampled record and return it as float arrays.

    Parameters
    ----------
    t : array_like
        Sample times [s]; must be finite and strictly increasing.
    x : array_like
        Sample values [any unit]; must be finite and the same length as `t`.
    min_samples : int
        Minimum acceptable number of samples [-].

    Returns
    -------
    t, x : numpy.ndarray
        1-D float64 copies of the inputs.

    Raises
    ------
    ValueError
        If the record is too short, not 1-D, mismatched, non-finite or not increasing.
    """
    t_arr = np.asarray(t, dtype=float)
    x_arr = np.asarray(x, dtype=float)
    if t_arr.ndim != 1 or x_arr.ndim != 1:
        raise ValueError(f"t and x must be 1-D, got shapes {t_arr.shape} and {x_arr.shape}")
    if t_arr.shape != x_arr.shape:
        raise ValueError(f"t and x must have the same length, got {t_arr.size} and {x_arr.size}")
    if t_arr.size < min_samples:
        raise ValueError(f"need at least {min_samples} samples, got {t_arr.size}")
    if not np.all(np.isfinite(t_arr)):
        raise ValueError("t contains NaN or inf")
    if not np.all(np.isfinite(x_arr)):
        raise ValueError("x contains NaN or inf")
    if np.any(np.diff(t_arr) <= 0.0):
        raise ValueError("t must be strictly increasing")
    return t_arr, x_arr


def resample_uniform(
    t: np.ndarray, x: np.ndarray, n: int | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Linearly interpolate a possibly non-uniformly sampled record onto a uniform grid.

    Parameters
    ----------
    t : array_like
        Sample times [s], finite and strictly increasing (spacing may vary).
    x : array_like
        Sample values [any unit], same length as `t`.
    n : int, optional
        Number of points of the uniform grid [-]; defaults to ``len(t)``. Must be >= 2.

    Returns
    -------
    tu : numpy.ndarray
        Uniform grid spanning ``[t[0], t[-1]]`` inclusive [s].
    xu : numpy.ndarray
        `x` linearly interpolated at `tu` [same unit as x].

    Raises
    ------
    ValueError
        If `t` is not strictly increasing, the inputs are non-finite or mismatched, or
        `n` < 2.
    """
    t_arr, x_arr = _as_record(t, x, 2)
    n_out = t_arr.size if n is None else int(n)
    if n_out < 2:
        raise ValueError(f"n must be at least 2, got {n}")
    tu = np.linspace(t_arr[0], t_arr[-1], n_out)
    return tu, np.interp(tu, t_arr, x_arr)


def spectrum(t: np.ndarray, x: np.ndarray, window: str = "hann") -> tuple[np.ndarray, np.ndarray]:
    """One-sided amplitude spectrum of a (possibly non-uniformly sampled) record.

    The record is first resampled onto a uniform grid with ``len(t)`` points
    (:func:`resample_uniform`). The spectrum is scaled by the coherent gain of the window
    so that a sinusoid of peak amplitude ``A`` centred on a bin shows a peak of ``A``
    (off-bin it shows the window's scalloping loss, at most ≈ 15 % for Hann). The mean is
    not removed: the DC bin holds the (windowed) mean of `x`.

    Parameters
    ----------
    t : array_like
        Sample times [s], finite and strictly increasing.
    x : array_like
        Sample values [any unit].
    window : str or tuple, optional
        Any window specification accepted by :func:`scipy.signal.get_window`
        (default ``"hann"``; ``"boxcar"`` for no window).

    Returns
    -------
    freq : numpy.ndarray
        Bin frequencies from 0 to Nyquist of the uniform grid [Hz].
    amplitude : numpy.ndarray
        Peak amplitude per bin [same unit as x].

    Raises
    ------
    ValueError
        If the record is invalid (see :func:`resample_uniform`).
    """
    t_arr, x_arr = _as_record(t, x, 2)
    tu, xu = resample_uniform(t_arr, x_arr)
    n = tu.size
    dt = (tu[-1] - tu[0]) / (n - 1)
    # Periodic (fftbins) window: the DFT of a periodic window has exact zeros at the
    # neighbouring bins, which is the intended spectral-analysis behaviour.
    w = _window(window, n)
    # numpy's FFT (pocketfft, as scipy.fft, to the bit on these real transforms): importing
    # scipy.fft costs 0.05-0.1 s of every CLI run
    amp = np.abs(np.fft.rfft(xu * w)) / np.sum(w)
    # Fold negative frequencies onto positive ones; DC and (for even n) Nyquist have
    # no mirror image.
    amp[1:] *= 2.0
    if n % 2 == 0:
        amp[-1] /= 2.0
    return np.fft.rfftfreq(n, dt), amp


def _fft_peak_frequency(t: np.ndarray, x: np.ndarray, near: float | None, rel_band: float) -> float:
    """Coarse frequency of the largest spectral peak (Hann FFT + log-parabolic interpolation).

    Parameters
    ----------
    t : numpy.ndarray
        Validated sample times [s].
    x : numpy.ndarray
        Validated sample values [any unit].
    near : float or None
        Search centre [Hz]; ``None`` searches all bins at or above ``2/T``.
    rel_band : float
        Relative half-width of the search band around `near` [-].

    Returns
    -------
    float
        Estimated peak frequency [Hz].

    Raises
    ------
    ValueError
        If the searched part of the spectrum is identically zero.
    """
    n = t.size
    duration = t[-1] - t[0]
    _, xu = resample_uniform(t, x)
    # Mean and trend leak through the window's sidelobes into low bins and can hide
    # a weak ripple, so they are removed before windowing.
    k = np.arange(n)
    xu = xu - np.polyval(np.polyfit(k, xu, 1), k)
    nfft = _PAD_FACTOR * (1 << (n - 1).bit_length())
    w = _window("hann", n)
    mag = np.abs(np.fft.rfft(xu * w, nfft))
    freqs = np.fft.rfftfreq(nfft, duration / (n - 1))

    if near is None:
        candidates = np.flatnonzero(freqs >= _MIN_PERIODS / duration)
    else:
        candidates = np.flatnonzero(np.abs(freqs - near) <= rel_band * near)
        if candidates.size == 0:
            # Band narrower than the padded bin spacing: the nearest bin is the band.
            candidates = np.array([int(np.argmin(np.abs(freqs - near)))])
    if candidates.size == 0:
        raise ValueError("record too short to hold 2 periods of any resolvable frequency")
    k = int(candidates[np.argmax(mag[candidates])])
    if mag[k] <= 0.0:
        raise ValueError("signal has no non-DC spectral component")

    delta = 0.0
    if 0 < k < mag.size - 1 and mag[k - 1] > 0.0 and mag[k + 1] > 0.0:
        # The Hann main lobe is close to a Gaussian, whose logarithm is exactly a
        # parabola, so interpolating log|X| is far less biased than interpolating |X|.
        lm, l0, lp = np.log(mag[k - 1 : k + 2])
        curvature = lm - 2.0 * l0 + lp
        if curvature < 0.0:
            delta = float(np.clip(0.5 * (lm - lp) / curvature, -0.5, 0.5))
    return float((k + delta) * freqs[1])


def _design_matrix(tc: np.ndarray, half: float, frequency: float, orders: int) -> np.ndarray:
    """Columns of the linear model at a fixed frequency.

    Parameters
    ----------
    tc : numpy.ndarray
        Sample times relative to the record midpoint [s].
    half : float
        Half the record duration [s]; scales the trend column to O(1).
    frequency : float
        Fundamental frequency of the model [Hz].
    orders : int
        Highest harmonic order included (1 = fundamental only) [-].

    Returns
    -------
    numpy.ndarray
        Matrix with columns 1, tc/half, then sin and cos for each order.
    """
    cols = [np.ones_like(tc), tc / half]
    for order in range(1, orders + 1):
        # Centred time keeps the sine/cosine columns nearly orthogonal to the offset
        # and trend columns and avoids cancellation in the phase argument.
        arg = (2.0 * np.pi * order * frequency) * tc
        cols.extend((np.sin(arg), np.cos(arg)))
    return np.column_stack(cols)


def _linear_fit(
    tc: np.ndarray, half: float, x: np.ndarray, frequency: float, orders: int
) -> tuple[np.ndarray, float]:
    """Linear least-squares fit of the model at a fixed frequency.

    Parameters
    ----------
    tc : numpy.ndarray
        Sample times relative to the record midpoint [s].
    half : float
        Half the record duration [s].
    x : numpy.ndarray
        Sample values [any unit].
    frequency : float
        Fundamental frequency [Hz].
    orders : int
        Highest harmonic order included [-].

    Returns
    -------
    coef : numpy.ndarray
        Model coefficients in the column order of :func:`_design_matrix`.
    rss : float
        Residual sum of squares [unit of x squared].
    """
    design = _design_matrix(tc, half, frequency, orders)
    coef, *_ = np.linalg.lstsq(design, x, rcond=None)
    # Recomputing the residual explicitly keeps the cost accurate to round-off of x
    # itself, which the frequency search needs near a near-zero minimum.
    resid = x - design @ coef
    return coef, float(resid @ resid)


def bounded_minimum(func: Callable[[float], float], lo: float, hi: float, *,
                    xatol: float = 1e-5, maxiter: int = 500) -> float:
    """The x in [lo, hi] minimising ``func``: Brent's bounded search (golden sections and
    parabolic steps; Forsythe, Malcolm & Moler 1977, ``fmin``), step for step as scipy's
    ``minimize_scalar(method="bounded")`` takes it, so results agree to the bit; written
    here because importing scipy.optimize costs 0.1-0.2 s of every CLI run."""
    golden = 0.5 * (3.0 - math.sqrt(5.0))
    sqrt_eps = math.sqrt(2.2e-16)
    a, b = lo, hi
    v = w = x = a + golden * (b - a)  # third best, second best, best point so far
    fv = fw = fx = func(x)
    d = e = 0.0  # this step and the one before the last
    calls = 1
    xm = 0.5 * (a + b)
    tol1 = sqrt_eps * abs(x) + xatol / 3.0
    while abs(x - xm) > 2.0 * tol1 - 0.5 * (b - a):
        parabolic = False
        if abs(e) > tol1:  # try a parabola through x, w, v
            r = (x - w) * (fx - fv)
            q = (x - v) * (fx - fw)
            p = (x - v) * q - (x - w) * r
            q = 2.0 * (q - r)
            if q > 0.0:
                p = -p
            q = abs(q)
            r, e = e, d
            if abs(p) < abs(0.5 * q * r) and q * (a - x) < p < q * (b - x):
                parabolic = True
                d = (p + 0.0) / q
                u = x + d
                if (u - a) < 2.0 * tol1 or (b - u) < 2.0 * tol1:
                    d = tol1 * (1.0 if xm >= x else -1.0)
        if not parabolic:
            e = (a - x) if x >= xm else (b - x)
            d = golden * e
        u = x + (1.0 if d >= 0 else -1.0) * max(abs(d), tol1)
        fu = func(u)
        calls += 1
        if fu <= fx:
            a, b = (x, b) if u >= x else (a, x)
            v, fv, w, fw, x, fx = w, fw, x, fx, u, fu
        else:
            a, b = (u, b) if u < x else (a, u)
            if fu <= fw or w == x:
                v, fv, w, fw = w, fw, u, fu
            elif fu <= fv or v == x or v == w:
                v, fv = u, fu
        xm = 0.5 * (a + b)
        tol1 = sqrt_eps * abs(x) + xatol / 3.0
        if calls >= maxiter:
            break
    return x


def _check_frequency(name: str, value: float, duration: float, nyquist: float) -> float:
    """Validate a user-supplied frequency [Hz] against the record; return it as float."""
    value = float(value)
    if not math.isfinite(value) or value <= 0.0:
        raise ValueError(f"{name} must be a positive finite frequency, got {value}")
    if value > nyquist:
        raise ValueError(
            f"{name}={value:g} Hz is above the Nyquist frequency {nyquist:g} Hz "
            "(mean sample rate / 2)"
        )
    if value * duration < _MIN_PERIODS:
        raise ValueError(
            f"{name}={value:g} Hz gives only {value * duration:.3g} periods in the "
            f"{duration:g} s record; at least {_MIN_PERIODS:g} are required"
        )
    return value


def harmonic(
    t: np.ndarray,
    x: np.ndarray,
    frequency: float | None = None,
    *,
    near: float | None = None,
    rel_band: float = 0.05,
    fit_frequency: bool = True,
    harmonics_in_model: bool = True,
) -> Harmonic:
    """Fit one sinusoidal component, offset and linear trend of a sampled waveform, accurate
    for a non-integer number of periods and non-uniform sampling (:class:`Harmonic`: model and
    phase convention; module docstring: the three stages).

    Parameters
    ----------
    t, x : array_like
        Sample times [s] (finite, strictly increasing, any spacing) and values [any unit].
    frequency : float, optional
        Known (approximate) frequency [Hz]: it seeds a search within ±1.5 bins (1 bin = 1/T,
        T the record duration), or with ``fit_frequency=False`` is used as it is. Use `near`
        when it is only roughly known.
    near, rel_band : float, optional
        Search the largest spectral peak within ``near·(1 ± rel_band)`` [Hz] (default band
        0.05) instead of the global peak. Mutually exclusive with `frequency`.
    fit_frequency : bool, optional
        Refine the frequency by least squares (default); if False, `frequency` if given, else
        the interpolated FFT peak.
    harmonics_in_model : bool, optional
        Also fit the 2nd and 3rd harmonics (below 0.9·Nyquist), so that a waveform's own
        harmonics do not bias the fundamental: without them a 10 % second harmonic biases a
        100-period fit's amplitude by 4e-5 to 4e-4 (sidelobe leakage, ~1/(π·Δf·T)); with them
        the error is at round-off. Other tones leak in the same way.

    Returns a :class:`Harmonic`. Raises ValueError for fewer than 8 samples, non-increasing
    or non-finite `t`, non-finite `x`, both `frequency` and `near`, a requested frequency not
    positive, above Nyquist (half the mean sample rate) or giving fewer than 2 periods, or no
    non-DC spectral content.
    """
    t_arr, x_arr = _as_record(t, x, _MIN_SAMPLES)
    duration = float(t_arr[-1] - t_arr[0])
    nyquist = 0.5 * (t_arr.size - 1) / duration
    f_start = _start_frequency(t_arr, x_arr, frequency, near, rel_band, duration, nyquist)
    t_mid = 0.5 * (t_arr[0] + t_arr[-1])
    half = 0.5 * duration
    tc = t_arr - t_mid
    orders = 1
    if harmonics_in_model:
        # Fixed once from the starting frequency so the cost stays continuous in f.
        for order in (2, 3):
            if order * f_start < _HARMONIC_NYQUIST_MARGIN * nyquist:
                orders = order
    f_fit = f_start
    coef, rss = _linear_fit(tc, half, x_arr, f_fit, orders)
    if fit_frequency:
        f_fit, coef, rss = _refine_frequency(tc, half, x_arr, f_start, orders, duration,
                                             nyquist, (f_fit, coef, rss))
    return _as_harmonic(f_fit, coef, rss, t_mid, half, t_arr.size)


def _start_frequency(t_arr: np.ndarray, x_arr: np.ndarray, frequency: float | None,
                     near: float | None, rel_band: float, duration: float,
                     nyquist: float) -> float:
    """Stage 1 of :func:`harmonic`: the given frequency [Hz], or the FFT peak (near ``near``)."""
    if frequency is not None and near is not None:
        raise ValueError("give at most one of `frequency` and `near`")
    if not (math.isfinite(rel_band) and rel_band > 0.0):
        raise ValueError(f"rel_band must be positive and finite, got {rel_band}")
    if frequency is not None:
        return _check_frequency("frequency", frequency, duration, nyquist)
    if near is not None:
        near = _check_frequency("near", near, duration, nyquist)
    return _fft_peak_frequency(t_arr, x_arr, near, rel_band)


def _refine_frequency(tc: np.ndarray, half: float, x_arr: np.ndarray, f_start: float,
                      orders: int, duration: float, nyquist: float,
                      start: tuple[float, np.ndarray, float]
                      ) -> tuple[float, np.ndarray, float]:
    """Stage 3 of :func:`harmonic`: the least-squares frequency within ±1.5 bins of
    ``f_start`` [Hz]; returns (frequency, coefficients, rss), never worse than ``start``."""
    bin_width = 1.0 / duration
    # Search in bins relative to the start so the optimiser's relative tolerance
    # acts on the small offset, not on the (large) absolute frequency.
    lo = max(-_SEARCH_HALF_WIDTH_BINS, (0.5 * bin_width - f_start) / bin_width)
    hi = min(_SEARCH_HALF_WIDTH_BINS, (nyquist - f_start) / bin_width)
    if not hi > lo:
        return start
    u_best = bounded_minimum(
        lambda u: _linear_fit(tc, half, x_arr, f_start + u * bin_width, orders)[1],
        lo, hi, xatol=_SEARCH_XATOL_BINS, maxiter=500)
    f_try = f_start + u_best * bin_width
    coef_try, rss_try = _linear_fit(tc, half, x_arr, f_try, orders)
    # Bounded Brent can in principle settle in a side minimum; never return a
    # fit worse than the starting frequency.
    if rss_try <= start[2]:
        return f_try, coef_try, rss_try
    return start


def _as_harmonic(f_fit: float, coef: np.ndarray, rss: float, t_mid: float, half: float,
                 n: int) -> Harmonic:
    a_sin, b_cos = float(coef[2]), float(coef[3])
    amplitude = math.hypot(a_sin, b_cos)
    phase_mid = math.atan2(b_cos, a_sin)
    # Shift the phase reference from t_mid to t = 0; reducing f·t_mid to a fraction of
    # a cycle first keeps the subtraction accurate for records far from t = 0.
    cycles = f_fit * t_mid
    phase = math.remainder(phase_mid - 2.0 * math.pi * (cycles - round(cycles)), 2.0 * math.pi)
    return Harmonic(
        frequency=float(f_fit),
        amplitude=amplitude,
        phase=phase,
        offset=float(coef[0]),
        rms_residual=math.sqrt(rss / n),
        trend=float(coef[1]) / half,
    )


def dominant_ripple(t: np.ndarray, x: np.ndarray) -> Harmonic:
    """Largest non-DC sinusoidal component of a waveform (e.g. converter output ripple).

    Equivalent to ``harmonic(t, x)``, except that a record that is constant or purely
    linear (rms deviation from a fitted line below ~2e-13 of max |x|, i.e. round-off)
    returns a :class:`Harmonic` with ``frequency = 0.0`` and ``amplitude = 0.0`` instead
    of raising.

    Parameters
    ----------
    t : array_like
        Sample times [s], finite and strictly increasing.
    x : array_like
        Sample values [any unit], finite.

    Returns
    -------
    Harmonic
        The dominant component; see :func:`harmonic`.

    Raises
    ------
    ValueError
        For an invalid record (see :func:`harmonic`).
    """
    t_arr, x_arr = _as_record(t, x, _MIN_SAMPLES)
    half = 0.5 * float(t_arr[-1] - t_arr[0])
    tc = t_arr - 0.5 * (t_arr[0] + t_arr[-1])
    line = np.column_stack((np.ones_like(tc), tc / half))
    coef, *_ = np.linalg.lstsq(line, x_arr, rcond=None)
    resid = x_arr - line @ coef
    rms = math.sqrt(float(resid @ resid) / t_arr.size)
    if rms <= _NO_RIPPLE_REL_RMS * float(np.max(np.abs(x_arr))):
        return Harmonic(
            frequency=0.0,
            amplitude=0.0,
            phase=0.0,
            offset=float(coef[0]),
            rms_residual=rms,
            trend=float(coef[1]) / half,
        )
    return harmonic(t_arr, x_arr)


# A ripple is reported only above these: Fisher's g-test false-alarm probability of the
# largest periodogram line, the periods the window must hold (two per half, so that the two
# halves can be compared), and the relative change of mean and rms between the halves that a
# periodic steady state may show (round-off and the solver's tolerance, not a transient).
_LINE_P_VALUE = 1e-3
_STEADY_MIN_PERIODS = 4
_STEADY_REL_CHANGE = 0.05


@dataclass(frozen=True)
class Ripple:
    """What the steady window of a waveform holds.

    ``state`` is 'periodic' (a periodic steady state with a significant spectral line: the
    ripple is ``frequency`` [Hz] and ``amplitude`` [unit of x, peak]), 'settling' (the window
    still changes: a transient; a significant line, e.g. a decaying ring, is given for
    information) or 'none' (no significant spectral line: flat or noise). ``mean`` is the mean
    of the window (of the fitted steady state when periodic) [unit of x]; ``p_value`` is the
    false-alarm
    probability of the line (Fisher's g-test; 1.0 when there is none).
    """

    state: str
    mean: float
    frequency: float = 0.0
    amplitude: float = 0.0
    p_value: float = 1.0

    @property
    def label(self) -> str:
        return {"periodic": "periodic", "settling": "settling",
                "none": "no periodic ripple"}[self.state]


def fisher_g_test(power: np.ndarray) -> tuple[int, float]:
    """Index of the largest periodogram ordinate and the probability that white noise gives a
    line that large (Fisher 1929: p = sum_k (-1)^(k-1) C(m,k) (1 - k g)^(m-1), g = max/sum;
    the first term, m (1 - g)^(m-1), bounds it and is exact where it matters, p < 0.1)."""
    m = power.size
    total = float(np.sum(power))
    k = int(np.argmax(power))
    if m < 2 or total <= 0.0:
        return k, 1.0
    g = float(power[k]) / total
    return k, min(1.0, m * math.exp((m - 1) * math.log1p(-min(g, 1.0 - 1e-16))))


def ripple_summary(t: np.ndarray, x: np.ndarray) -> Ripple:
    """Classify the window ``t`` [s], ``x`` as a periodic steady state, settling, or without a
    periodic ripple; see :class:`Ripple`.

    The line is the largest ordinate of the periodogram of the mean-free uniform resample,
    kept when Fisher's g-test gives a false-alarm probability below 1e-3 and it holds at least
    four periods; the window is steady when, over a whole number of periods, its two halves
    agree in mean and rms to 5 % of the rms.
    """
    t_arr, x_arr = _as_record(t, x, _MIN_SAMPLES)
    mean = float(np.mean(x_arr))
    scale = float(np.max(np.abs(x_arr)))
    tu, xu = resample_uniform(t_arr, x_arr)
    dev = xu - np.mean(xu)
    if float(np.std(dev)) <= _NO_RIPPLE_REL_RMS * max(scale, np.finfo(float).tiny):
        return Ripple("none", mean)
    power = np.abs(np.fft.rfft(dev))[1:] ** 2
    k, p = fisher_g_test(power)
    duration = float(tu[-1] - tu[0])
    line = (k + 1) / duration  # bin k+1 (the DC bin was dropped)
    h = None
    if p <= _LINE_P_VALUE and line * duration >= _MIN_PERIODS:
        try:
            h = harmonic(t_arr, x_arr, near=line)
        except ValueError:
            h = None
    if h is None or h.frequency * duration < _STEADY_MIN_PERIODS:
        # no line, or too few periods to compare two halves: a transient shows as a drift of
        # the mean well beyond the noise (a quarter of the rms)
        drift = _drifts(tu, xu, duration, mean_only=0.25)
        state = "settling" if drift else "none"
        if h is None:
            return Ripple(state, mean, p_value=p)
        return Ripple(state, mean, float(h.frequency), float(h.amplitude), p)
    periods = int(h.frequency * duration) // 2 * 2
    span = periods / h.frequency
    keep = tu >= tu[-1] - span
    state = "settling" if _drifts(tu[keep], xu[keep], span) else "periodic"
    # periodic: the fit's offset is the mean of the steady state, free of the partial period
    # and of the sampling grid (a sample mean over whole periods is off by up to a sample's
    # share of the ripple)
    level = float(h.offset) if state == "periodic" else mean
    return Ripple(state, level, float(h.frequency), float(h.amplitude), p)


def _drifts(t: np.ndarray, x: np.ndarray, span: float, mean_only: float | None = None) -> bool:
    """True when the two halves of ``x`` differ in mean or rms by more than 5 % of its rms
    (``mean_only``: in mean only, by more than that fraction of the rms)."""
    first = t < t[0] + 0.5 * span
    a, b = x[first], x[~first]
    if a.size < 2 or b.size < 2:
        return False
    rms = float(np.std(x))
    shift = abs(float(np.mean(a)) - float(np.mean(b)))
    if mean_only is not None:
        return shift > mean_only * rms
    return (shift > _STEADY_REL_CHANGE * rms or
            abs(float(np.std(a)) - float(np.std(b))) > _STEADY_REL_CHANGE * rms)
