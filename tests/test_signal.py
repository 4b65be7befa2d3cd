"""Tests for circuitsim.signal on closed-form synthetic waveforms."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from circuitsim.signal import Harmonic, dominant_ripple, harmonic, resample_uniform, spectrum

F0 = 50.0  # [Hz]
AMP = 1.3  # [V] peak
PHASE = 0.7  # [rad] at t = 0
OFFSET = 2.0  # [V] at the record midpoint
TREND = 0.3  # [V/s]
T_START = 0.123  # [s]; deliberately not 0 so the absolute phase reference is exercised
SAMPLES_PER_PERIOD = 20


def _times(periods: float, *, jitter: float = 0.0, seed: int = 0) -> np.ndarray:
    """Sample times [s] covering `periods` periods of F0; jitter in units of dt (< 0.5)."""
    n = round(periods * SAMPLES_PER_PERIOD)
    dt = periods / F0 / (n - 1)
    t = T_START + dt * np.arange(n)
    if jitter:
        rng = np.random.default_rng(seed)
        # End points stay fixed so the record length (and hence periods) is exact.
        t[1:-1] += rng.uniform(-jitter, jitter, n - 2) * dt
    return t


def _wave(t: np.ndarray) -> np.ndarray:
    """Offset + trend + sine, using the model definition of Harmonic."""
    t_mid = 0.5 * (t[0] + t[-1])
    return OFFSET + TREND * (t - t_mid) + AMP * np.sin(2 * np.pi * F0 * t + PHASE)


def _phase_error(a: float, b: float) -> float:
    """Wrapped phase difference [rad]."""
    return abs(math.remainder(a - b, 2 * math.pi))


# --- resample_uniform -----------------------------------------------------------------


def test_resample_uniform_linear_is_exact_on_nonuniform_input():
    t = np.cumsum(np.random.default_rng(3).uniform(0.5, 1.5, 50))
    x = 4.0 - 2.5 * t
    tu, xu = resample_uniform(t, x)
    assert tu.size == t.size
    assert tu[0] == t[0] and tu[-1] == t[-1]
    np.testing.assert_allclose(np.diff(tu), (t[-1] - t[0]) / (t.size - 1), rtol=1e-12)
    np.testing.assert_allclose(xu, 4.0 - 2.5 * tu, rtol=0, atol=1e-12)
    tu2, xu2 = resample_uniform(t, x, n=7)
    assert tu2.size == xu2.size == 7


def test_resample_uniform_rejects_bad_input():
    with pytest.raises(ValueError, match="strictly increasing"):
        resample_uniform([0.0, 1.0, 1.0, 2.0], [0, 1, 2, 3])
    with pytest.raises(ValueError, match="at least 2"):
        resample_uniform([0.0, 1.0], [0.0, 1.0], n=1)


# --- harmonic: clean signals ----------------------------------------------------------


@pytest.mark.parametrize("periods", [20.37, 100.61, 299.3])
@pytest.mark.parametrize("jitter", [0.0, 0.3], ids=["uniform", "jittered"])
def test_clean_sine_with_offset_and_trend(periods, jitter):
    t = _times(periods, jitter=jitter)
    h = harmonic(t, _wave(t))
    # Measured: all errors <= 1e-12 relative, phase <= 1e-10 rad.
    assert abs(h.amplitude / AMP - 1) < 1e-6
    assert abs(h.frequency / F0 - 1) < 1e-6
    assert _phase_error(h.phase, PHASE) < 1e-6
    assert abs(h.offset - OFFSET) < 1e-6 * AMP
    assert abs(h.trend - TREND) < 1e-6 * AMP * F0
    assert h.rms_residual < 1e-9 * AMP


def test_clean_sine_without_harmonic_columns():
    t = _times(100.61, jitter=0.3)
    h = harmonic(t, _wave(t), harmonics_in_model=False)
    assert abs(h.amplitude / AMP - 1) < 1e-6
    assert abs(h.frequency / F0 - 1) < 1e-6


def test_fixed_frequency_fit():
    t = _times(57.3)
    h = harmonic(t, _wave(t), frequency=F0, fit_frequency=False)
    assert h.frequency == F0
    assert abs(h.amplitude / AMP - 1) < 1e-9
    assert _phase_error(h.phase, PHASE) < 1e-9


def test_frequency_seed_is_refined():
    periods = 57.3
    t = _times(periods)
    # Seed half a bin (1/T) off; the least-squares search must recover the truth.
    seed = F0 + 0.5 * F0 / periods
    h = harmonic(t, _wave(t), frequency=seed)
    assert abs(h.frequency / F0 - 1) < 1e-6
    assert abs(h.amplitude / AMP - 1) < 1e-6


# --- harmonic: phase convention -------------------------------------------------------


@pytest.mark.parametrize(
    ("wave", "expected_phase"),
    [
        (lambda t: AMP * np.sin(2 * np.pi * F0 * t), 0.0),
        (lambda t: AMP * np.cos(2 * np.pi * F0 * t), math.pi / 2),
        (lambda t: -AMP * np.sin(2 * np.pi * F0 * t), math.pi),
        (lambda t: AMP * np.sin(2 * np.pi * F0 * t - 2.0), -2.0),
    ],
    ids=["sin", "cos", "minus-sin", "lagging"],
)
def test_phase_is_sine_phase_at_absolute_time_zero(wave, expected_phase):
    # Record starts 0.8 s after t = 0 (40 periods), so a start-of-record reference
    # would give the same phase only by accident; 0.8137 s makes it non-integer.
    t = 0.8137 + np.linspace(0.0, 33.7 / F0, 700)
    h = harmonic(t, wave(t))
    assert h.amplitude > 0
    assert _phase_error(h.phase, expected_phase) < 1e-6
    model = (
        h.offset
        + h.trend * (t - 0.5 * (t[0] + t[-1]))
        + h.amplitude * np.sin(2 * np.pi * h.frequency * t + h.phase)
    )
    np.testing.assert_allclose(model, wave(t), rtol=0, atol=1e-9 * AMP)


def test_harmonic_is_frozen():
    h = Harmonic(1.0, 2.0, 0.0, 0.0, 0.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        h.amplitude = 3.0  # type: ignore[misc]


# --- harmonic: noise ------------------------------------------------------------------


@pytest.mark.parametrize("jitter", [0.0, 0.3], ids=["uniform", "jittered"])
def test_noisy_sine_within_statistical_bounds(jitter):
    sigma = 0.01 * AMP
    t = _times(100.37, jitter=jitter, seed=11)
    n = t.size
    duration = t[-1] - t[0]
    x = _wave(t) + sigma * np.random.default_rng(12345).standard_normal(n)
    h = harmonic(t, x)
    # Least-squares amplitude std is sigma*sqrt(2/N): allow 5 standard deviations.
    assert abs(h.amplitude - AMP) < 5 * sigma / math.sqrt(n / 2)
    # Cramér-Rao std of the frequency of a real sine in white noise:
    # sqrt(24)*sigma / (2*pi*A*sqrt(N)*T); allow 5 of those.
    f_std = math.sqrt(24) * sigma / (2 * math.pi * AMP * math.sqrt(n) * duration)
    assert abs(h.frequency - F0) < 5 * f_std
    # Residual rms estimates sigma (8 fitted parameters); its relative std is 1/sqrt(2N).
    dof_corrected = h.rms_residual * math.sqrt(n / (n - 8))
    assert abs(dof_corrected / sigma - 1) < 5 / math.sqrt(2 * n)


# --- harmonic: two tones --------------------------------------------------------------


@pytest.mark.parametrize("periods", [20.37, 100.61, 299.3])
def test_second_harmonic_does_not_bias_fundamental(periods):
    t = _times(periods, jitter=0.3)
    x = _wave(t) + 0.1 * AMP * np.sin(2 * np.pi * 2 * F0 * t + 0.4)
    h = harmonic(t, x)
    # The brief's target was 1e-5 at 100 periods; with 2f in the model (default) the
    # error is at round-off level (measured <= 1e-13), so 1e-6 is asserted.
    assert abs(h.amplitude / AMP - 1) < 1e-6
    assert abs(h.frequency / F0 - 1) < 1e-6
    assert _phase_error(h.phase, PHASE) < 1e-6


def test_unmodelled_second_harmonic_leaks_which_is_why_it_is_modelled_by_default():
    # Documents the measurement behind harmonics_in_model=True: sines at distinct
    # frequencies are only near-orthogonal over a non-integer number of periods.
    t = _times(100.61)
    x = _wave(t) + 0.1 * AMP * np.sin(2 * np.pi * 2 * F0 * t + 0.4)
    h = harmonic(t, x, harmonics_in_model=False)
    assert abs(h.amplitude / AMP - 1) > 1e-5  # measured 2.4e-4


def _leakage_bound(other_amp: float, f_a: float, f_b: float, duration: float) -> float:
    """Upper estimate of the amplitude error caused by an unmodelled tone [same unit].

    Each of the fitted sine/cosine coefficients at f_a picks up at most
    B·(1/(π|Δf|T) + 1/(πΣf·T)) from a tone of amplitude B at f_b; the amplitude error is
    at most sqrt(2) times that.
    """
    per_coef = 1 / (math.pi * abs(f_a - f_b) * duration) + 1 / (math.pi * (f_a + f_b) * duration)
    return math.sqrt(2) * other_amp * per_coef


def test_two_unrelated_tones_global_and_near_selection():
    t = _times(100.37, jitter=0.3)
    duration = t[-1] - t[0]
    f_weak, amp_weak = 68.5, 0.1 * AMP
    x = _wave(t) + amp_weak * np.sin(2 * np.pi * f_weak * t + 0.2)

    strong = harmonic(t, x)
    assert abs(strong.frequency - F0) < 0.1 / duration  # the global peak, within 0.1 bin
    assert abs(strong.amplitude - AMP) < _leakage_bound(amp_weak, F0, f_weak, duration)

    weak = harmonic(t, x, near=f_weak * 1.02)
    assert abs(weak.frequency - f_weak) < 0.1 / duration
    assert abs(weak.amplitude - amp_weak) < _leakage_bound(AMP, f_weak, F0, duration)


# --- dominant_ripple ------------------------------------------------------------------


def test_dominant_ripple_finds_largest_component():
    # 12 V rail, 50 mV ripple at 100 kHz plus 10 mV at 300 kHz, 1 ms record (100.4 periods).
    t = np.linspace(0.0, 1.004e-3, 4000)
    x = 12.0 + 0.05 * np.sin(2 * np.pi * 1e5 * t + 1.0) + 0.01 * np.sin(2 * np.pi * 3e5 * t)
    h = dominant_ripple(t, x)
    assert abs(h.frequency / 1e5 - 1) < 1e-6
    assert abs(h.amplitude / 0.05 - 1) < 1e-6
    assert abs(h.offset - 12.0) < 1e-9


@pytest.mark.parametrize("wave", [lambda t: np.full_like(t, 3.3), lambda t: 1.0 + 2.0 * t])
def test_dominant_ripple_of_constant_or_ramp_is_zero(wave):
    t = np.linspace(0.0, 1.0, 100)
    h = dominant_ripple(t, wave(t))
    assert h.amplitude == 0.0
    assert h.frequency == 0.0
    assert h.offset == pytest.approx(wave(np.array([0.5]))[0], abs=1e-12)


def test_dominant_ripple_rejects_short_record():
    with pytest.raises(ValueError, match="at least 8"):
        dominant_ripple(np.arange(5.0), np.zeros(5))


# --- spectrum -------------------------------------------------------------------------


@pytest.mark.parametrize("window", ["hann", "boxcar", "blackmanharris"])
def test_spectrum_on_bin_peak_equals_amplitude(window):
    n = 1024
    t = np.linspace(0.0, 1.0, n)
    dt = t[1] - t[0]
    f_bin = 37 / (n * dt)  # exactly on bin 37 of the n-point grid
    x = 0.5 + AMP * np.sin(2 * np.pi * f_bin * t + 0.3)
    freq, amp = spectrum(t, x, window=window)
    k = int(np.argmax(amp[1:])) + 1
    assert k == 37
    assert freq[k] == pytest.approx(f_bin, rel=1e-12)
    assert amp[k] == pytest.approx(AMP, rel=1e-9)
    assert amp[0] == pytest.approx(0.5, abs=1e-3 * AMP)


def test_spectrum_off_bin_within_hann_scalloping():
    t = _times(100.5, jitter=0.3)  # half-bin offset: worst case scalloping
    _, amp = spectrum(t, _wave(t) - OFFSET)
    # Hann scalloping loss at half a bin is 1.42 dB (factor 0.849).
    assert 0.84 * AMP < amp[2:].max() <= AMP


# --- errors ---------------------------------------------------------------------------


def test_errors():
    t = _times(30.2)
    x = _wave(t)
    nyquist = 0.5 * (t.size - 1) / (t[-1] - t[0])
    with pytest.raises(ValueError, match="at least 8"):
        harmonic(t[:7], x[:7])
    t_bad = t.copy()
    t_bad[10] = t_bad[9]
    with pytest.raises(ValueError, match="strictly increasing"):
        harmonic(t_bad, x)
    with pytest.raises(ValueError, match="strictly increasing"):
        harmonic(t[::-1], x)
    x_nan = x.copy()
    x_nan[3] = np.nan
    with pytest.raises(ValueError, match="NaN"):
        harmonic(t, x_nan)
    t_nan = t.copy()
    t_nan[3] = np.nan
    with pytest.raises(ValueError, match="NaN"):
        harmonic(t_nan, x)
    with pytest.raises(ValueError, match="Nyquist"):
        harmonic(t, x, frequency=1.01 * nyquist)
    with pytest.raises(ValueError, match="Nyquist"):
        harmonic(t, x, near=1.01 * nyquist)
    with pytest.raises(ValueError, match="periods"):
        harmonic(t, x, frequency=1.9 / (t[-1] - t[0]))
    with pytest.raises(ValueError, match="periods"):
        harmonic(t, x, near=1.9 / (t[-1] - t[0]))
    with pytest.raises(ValueError, match="positive"):
        harmonic(t, x, frequency=-F0)
    with pytest.raises(ValueError, match="at most one"):
        harmonic(t, x, frequency=F0, near=F0)
    with pytest.raises(ValueError, match="same length"):
        harmonic(t, x[:-1])
