"""The diagnosis's noise model (loop/diagnose/noise.py) against closed forms: the AR
prewhitening filter, and the long memory (1/f-like noise) taken out before the test."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from circuitsim.loop.diagnose import decide
from circuitsim.loop.diagnose.noise import (
    Whitener,
    delta_bic,
    fit_whitener,
    fractional_difference,
    lines_of,
    memory_order,
    memory_whiteners,
    own_memory_whitener,
    perturbed_memory_order,
    projected_sse,
    rises_to_zero,
    significant_lines,
    whitened_sse,
    whiteners_of,
)

from conftest import white_over_pink


def test_fractional_difference_of_order_one_is_the_first_difference_and_inverts():
    r = np.random.default_rng(0).normal(size=500)
    assert np.allclose(fractional_difference(r, 1.0), np.diff(r, prepend=0.0), atol=1e-12)
    # (1 - B)^-d (1 - B)^d is the identity (the weights run over the whole record)
    back = fractional_difference(fractional_difference(r, 0.4), -0.4)
    assert np.allclose(back, r, atol=1e-9)


@pytest.mark.parametrize("d", [0.2, 0.4])
def test_memory_order_recovers_a_long_memory_and_ignores_short_ones(d):
    rng = np.random.default_rng(1)
    n = 20000
    # fractionally integrated white noise has long memory of order d exactly
    assert memory_order(fractional_difference(rng.normal(size=n), -d)) == pytest.approx(
        d, abs=0.12)  # about twice the estimate's standard error, pi / sqrt(24 sqrt(n))
    assert memory_order(rng.normal(size=n)) == 0.0
    ar = np.zeros(n)
    e = rng.normal(size=n)
    for k in range(1, n):  # AR(1), phi 0.5: short memory, flat at low frequencies
        ar[k] = 0.5 * ar[k - 1] + e[k]
    assert memory_order(ar) == 0.0


def test_the_memory_whitener_leaves_a_long_memory_noise_white():
    """The AR(<= 6) filter alone leaves a 1/f-like noise's low end far above its level (the
    lowest 50 bins' mean over the median bin: 1.44 for white noise, 5.7-8.6 here over four
    seeds); with the long memory taken out first it is within 1.5x of white (1.9-2.5: the
    log-periodogram estimate of d runs a little low, 0.37-0.43 for 0.45)."""
    rng = np.random.default_rng(2)
    r = fractional_difference(rng.normal(size=20000), -0.45)

    def low_to_mid(e):  # power of the lowest 50 bins against the median bin
        p = np.abs(np.fft.rfft(e - e.mean())) ** 2
        return float(np.mean(p[1:51]) / np.median(p[1:]))

    plain = fit_whitener(r).apply(r)
    memory = memory_whiteners({"x": r}, ["x"])["x"]
    assert memory.d > 0.3
    assert low_to_mid(plain) > 4.0
    assert low_to_mid(memory.apply(r)) < min(3.0, 0.5 * low_to_mid(plain))


def test_a_residual_full_of_structure_is_not_given_a_long_memory():
    """Where a residual is mostly structure, a low-frequency rise in it is taken for that
    structure (a slow shaft's cogging orders), not for the noise's memory: the whitener
    keeps d = 0 there, and takes the memory out of the same noise without the lines."""
    rng = np.random.default_rng(4)
    n = 20000
    t = np.arange(n)
    noise = fractional_difference(rng.normal(size=n), -0.45)
    lines = sum(2.0 * np.sin(2 * np.pi * f * t + f) for f in (0.021, 0.037, 0.052, 0.11))
    assert memory_whiteners({"x": noise}, ["x"])["x"].d > 0.3
    assert memory_whiteners({"x": noise + lines}, ["x"])["x"].d == 0.0


@pytest.mark.parametrize("seeds", [8, pytest.param(20, marks=pytest.mark.slow)])
def test_a_long_memory_is_read_through_white_noise_where_the_lowest_bins_miss_it(seeds):
    """perturbed_memory_order on 20 seeds of a 1/f noise under white noise (the first 8 in
    the fast set: each seed costs about 2 s): d between 0.3 and
    0.49 on every one (a 1/f noise is d = 0.5, capped at 0.49), where the log-periodogram
    regression on the lowest sqrt(n) bins of the typical windows (``memory_whiteners``)
    gives 0 on some (seeds 7 and 14 of these 20); white noise,
    white noise with a 0.5 Hz line of a tenth of its power, and AR(1) noises (a short
    memory, rising towards zero frequency too: phi 0.5 and 0.95) give 0."""
    t = np.arange(1200) / 200.0
    missed = 0
    for seed in range(seeds):
        x, white = white_over_pink(seed)
        assert 0.3 < perturbed_memory_order(x) <= 0.49, seed
        missed += memory_whiteners({"x": x}, ["x"])["x"].d == 0.0
        line = 0.015 * np.sqrt(0.2) * np.sin(2 * np.pi * 0.5 * t + seed)
        assert perturbed_memory_order(white) == 0.0, seed
        assert perturbed_memory_order(white + line) == 0.0, seed
        e = np.random.default_rng(100 + seed).normal(size=t.size)
        for phi in (0.5, 0.95):
            ar = np.zeros(t.size)
            for k in range(1, t.size):
                ar[k] = phi * ar[k - 1] + e[k]
            assert perturbed_memory_order(ar) == 0.0, (seed, phi)
    assert missed >= 1


def _rings(seed: int, amp: float, n: int = 12501, fs: float = 25e3) -> np.ndarray:
    """White noise of unit variance plus a 34 Hz ringing (damping ratio 0.09) of peak
    ``amp`` after each of four steps, of random sign: a housing's speed rocking on its
    mounts as a record's current sees it (fresh38's ap14), a band over a flat floor."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / fs
    wd = 2 * np.pi * 34.0 * np.sqrt(1 - 0.09 ** 2)
    x = rng.normal(size=n)
    for t0 in (0.05, 0.2, 0.3, 0.4):
        tau = np.clip(t - t0, 0.0, None)
        x += np.where(t >= t0, amp * np.exp(-0.09 * 2 * np.pi * 34.0 * tau) *
                      np.cos(wd * tau) * rng.choice([-1.0, 1.0]), 0.0)
    return x


def test_a_band_over_a_flat_floor_is_no_memory_noises_with_memory_rise_to_zero():
    """rises_to_zero: true on every seed of noises whose spectra rise towards zero
    frequency -- 1/f under white noise, AR(1) with phi 0.95, a Gauss-Markov noise (phi
    0.995) on its plateau -- at 2 001 and 25 001 samples; false on at least 18 of 20 seeds of
    a 34 Hz ringing over white noise, which the log-periodogram regression reads as a long
    memory on every one (d 0.26-0.44) and which describe._long_memory would otherwise
    excuse as the sensor's own noise."""
    from scipy.signal import lfilter

    from circuitsim.loop.diagnose import describe

    for n in (2001, 25001):
        for seed in range(20):
            rng = np.random.default_rng(seed)
            spectrum = np.fft.rfft(rng.normal(size=n))
            spectrum[0] = 0.0
            spectrum[1:] /= np.sqrt(np.arange(1, spectrum.size))
            pink = np.fft.irfft(spectrum, n)
            assert rises_to_zero(0.3 * pink / pink.std() + 0.4 * rng.normal(size=n)), seed
            assert rises_to_zero(lfilter([1.0], [1.0, -0.95], rng.normal(size=n)) +
                                 0.5 * rng.normal(size=n)), seed
            assert rises_to_zero(0.1 * lfilter([1.0], [1.0, -0.995], rng.normal(size=n)) +
                                 rng.normal(size=n)), seed
    t = np.arange(12501) / 25e3
    refused = 0
    for seed in range(20):
        x = _rings(seed, 2.0)
        assert memory_order(x) > 0.2, seed
        refused += not rises_to_zero(x)
        assert describe._long_memory(t, x) == rises_to_zero(x), seed
    assert refused >= 18


# ------------------------------------------------------------ lines on uneven times

N_LOG = 3000  # samples of a logger's record


def _logger_times(seed: int) -> np.ndarray:
    """A logger's timestamps [s]: intervals between 0.6 and 2.6 times their mean, 1.25 ms."""
    steps = np.random.default_rng(seed).uniform(0.6, 2.6, N_LOG - 1) * 1.25e-3 / 1.6
    return np.concatenate([[0.0], np.cumsum(steps)])


def _ou(t: np.ndarray, tau: float, seed: int) -> np.ndarray:
    """An Ornstein-Uhlenbeck noise of unit variance and correlation time ``tau`` [s], at the
    times ``t`` exactly: coloured in time, whatever the spacing of the samples."""
    rng = np.random.default_rng(seed)
    x = np.empty(t.size)
    x[0] = rng.normal()
    for k in range(1, t.size):
        a = np.exp(-(t[k] - t[k - 1]) / tau)
        x[k] = a * x[k - 1] + np.sqrt(1.0 - a * a) * rng.normal()
    return x


def test_lines_of_even_times_are_the_periodogram_of_the_whitened_residual():
    t = np.arange(N_LOG) * 1e-3
    r = 0.3 * np.sin(2 * np.pi * 60.0 * t) + np.random.default_rng(3).normal(size=N_LOG)
    w = fit_whitener(r)
    e = w.apply(r)
    got, ref = lines_of(e, t, r, w), significant_lines(e, 1e-3)
    assert np.array_equal(got.freqs, ref.freqs) and got.structured == ref.structured


def test_a_line_on_a_loggers_uneven_times_is_found_where_the_raw_periodogram_loses_it():
    """A 60 Hz line holding 4.3 % of the residual, sampled at 800 Hz on average with
    intervals from 0.6 to 2.6 times the mean (8 records). Read as if even, its phase wanders
    with the accumulated timing error: at most a quarter of its power stands out (none in 5
    of the 8). On the even grid it is found at 60 Hz with 40-125 % of the power the same line
    and noise give on even times (measured 0.55-1.03): the interpolation lowers a line's
    amplitude (by cos(pi f dt) on average over an interval) and weighs the samples of long
    intervals more, which raises the noise at low frequencies."""
    for seed in range(8):
        t = _logger_times(4 + seed)
        noise = np.random.default_rng(5 + seed).normal(size=N_LOG)
        shares = []
        for times in (t, np.linspace(0.0, t[-1], N_LOG)):
            r = 0.3 * np.sin(2 * np.pi * 60.0 * times + 0.3) + noise
            w = fit_whitener(r)
            e = w.apply(r)
            lines = lines_of(e, times, r, w)
            assert lines.freqs.size and np.all(np.abs(lines.freqs - 60.0) < 1.0), lines.freqs
            shares.append(lines.structured / lines.total)
            if times is t:
                raw = significant_lines(e, float(np.mean(np.diff(t))))
                shares.append(raw.structured / raw.total)
        uneven, raw, even = shares
        assert 0.4 < uneven / even < 1.25 and raw < 0.25 * even, (seed, shares)


@pytest.mark.parametrize("tau", [0.0, 5e-3])
def test_noise_alone_on_a_loggers_uneven_times_holds_no_line(tau):
    """White noise, and a noise coloured in time (Ornstein-Uhlenbeck, 5 ms) sampled at the
    uneven times: the interpolation colours both, the even grid's own whitening follows
    that, and no line is found (6 seeds each)."""
    for seed in range(6):
        t = _logger_times(10 + seed)
        r = _ou(t, tau, seed) if tau else np.random.default_rng(seed).normal(size=N_LOG)
        w = fit_whitener(r)
        assert lines_of(w.apply(r), t, r, w).freqs.size == 0, seed


@pytest.mark.parametrize("d", [0.0, 0.25, 0.45])
def test_the_conditional_sum_of_squares_reads_a_long_memory_white_noise_has_none(d):
    """own_memory_whitener on fractionally integrated white noise of order d (20 000
    samples; the estimate's standard error sqrt(6 / (pi^2 n)) is 0.006): within 0.05 of d;
    an AR(1) noise (phi 0.5, short memory) gets at most 0.1, its AR filter taking the rest."""
    rng = np.random.default_rng(11)
    x = rng.normal(size=20000)
    w = own_memory_whitener(fractional_difference(x, -d) if d else x)
    assert w.d == pytest.approx(d, abs=0.05)
    ar = np.zeros(x.size)
    for k in range(1, x.size):
        ar[k] = 0.5 * ar[k - 1] + x[k]
    assert own_memory_whitener(ar).d <= 0.1


def test_projected_sse_is_generalised_least_squares_with_each_probe_its_own_filter():
    """projected_sse against the explicit transform: each probe's AR(1) filter as a matrix
    (its first row dropped, as ``Whitener.apply`` does), rows scaled by the deviation of the
    whitened residual, the stacked columns fitted by least squares."""
    rng = np.random.default_rng(5)
    n, probes = 300, ["a", "b"]
    filters = {"a": Whitener((-0.6,), 1.0), "b": Whitener((0.3,), 1.0, 0.0)}
    r = {p: rng.normal(size=n) for p in probes}
    cols = {p: rng.normal(size=(n, 2)) for p in probes}
    rows, blocks = [], []
    for p in probes:
        L = np.eye(n)[1:] + filters[p].a[0] * np.eye(n)[:-1]  # e[k] = r[k] + a1 r[k-1]
        scale = np.sqrt(np.mean((L @ r[p]) ** 2))
        rows.append(L @ r[p] / scale)
        blocks.append(L @ cols[p] / scale)
    b, A = np.concatenate(rows), np.vstack(blocks)
    e = b - A @ np.linalg.lstsq(A, b, rcond=None)[0]
    out = projected_sse(r, cols, filters, probes)
    for j, p in enumerate(probes):
        scale = np.sqrt(np.mean((np.eye(n)[1:] @ r[p] + filters[p].a[0] *
                                 np.eye(n)[:-1] @ r[p]) ** 2))
        part = e[j * (n - 1):(j + 1) * (n - 1)]
        assert out[p] == pytest.approx(float(part @ part) * scale ** 2, rel=1e-10)


def _slow_profile_under_pink(seed: int, amp: float) -> tuple:
    """fresh57's bi01 as a linear model: a slow speed profile (16 s at 125 Hz) on probe "a"
    under white noise of unit deviation and a 1/f noise of 0.5; probe "b" white; one declared
    parameter acting on both (its column the profile's slope), fitted by least squares
    weighing every sample alike, as the diagnosis's refit does; the candidate is ``amp``
    times the profile on "a" alone, refitted beside the declared parameter. The (setup,
    poorer state, trial) that ``decide._memory_bic`` reads, and the AR filter's ΔBIC."""
    n = 2001
    t = np.arange(n) / 125.0
    y = np.interp(t, [0, 1, 1.5, 4.5, 5.5, 8.5, 9.2, 10.5, 13.5, 14.2, 16],
                  [0, 0, 3, 3, 9.5, 9.5, 0, -6, -6, 0, 0])
    rng = np.random.default_rng(seed)
    spectrum = np.fft.rfft(rng.normal(size=n))
    spectrum[0] = 0.0
    spectrum[1:] /= np.sqrt(np.arange(1, spectrum.size))
    pink = np.fft.irfft(spectrum, n)
    data = np.concatenate([rng.normal(size=n) + 0.5 * pink / pink.std() + amp * y,
                           rng.normal(size=n)])
    slope = np.gradient(y, t)
    declared = {"a": slope[:, None], "b": 0.3 * slope[:, None]}
    J0 = np.vstack([declared["a"], declared["b"]])
    X = np.column_stack([J0, np.concatenate([y, np.zeros(n)])])
    r0 = data - J0 @ np.linalg.lstsq(J0, data, rcond=None)[0]
    r1 = r0 - X @ np.linalg.lstsq(X, r0, rcond=None)[0]
    probes = ["a", "b"]
    before, after = {"a": r0[:n], "b": r0[n:]}, {"a": r1[:n], "b": r1[n:]}
    setup = SimpleNamespace(probes=probes, n=n)
    state = SimpleNamespace(fit=SimpleNamespace(residuals=before),
                            memory=lambda s: memory_whiteners(before, probes),
                            columns=lambda s: declared,
                            whitened=lambda s, w: whitened_sse(before, w, probes))
    trial = SimpleNamespace(fit=SimpleNamespace(residuals=after))
    w = whiteners_of(after, probes)
    ar = delta_bic(whitened_sse(after, w, probes), whitened_sse(before, w, probes), n, 1, probes)
    return setup, state, trial, ar


def test_a_slow_regressor_fitting_a_pink_wander_is_no_effect_a_real_one_is():
    """The long-memory test (``decide._memory_bic``) on 200 seeds of the linear bi01 above.
    With no effect, the AR filter alone accepts the profile on 35 (ΔBIC < -10: a spurious
    regression on the wander); the long-memory test, which refits the declared parameter
    under the noise read by conditional sum of squares, on 4 (the gate it replaced, a
    log-periodogram order on the richer residual and no refit, on 7). With the profile at
    0.1 of the noise (24 sigma over the record) it accepts 183 (the old gate 138)."""
    def accepted(amp: float) -> tuple[int, int]:
        ar = new = 0
        for seed in range(200):
            setup, state, trial, d_ar = _slow_profile_under_pink(seed, amp)
            ar += d_ar < -decide.BIC_MARGIN
            new += d_ar < -decide.BIC_MARGIN and \
                decide._memory_bic(setup, state, trial, 1) < -decide.BIC_MARGIN
        return ar, new

    ar, new = accepted(0.0)
    assert ar >= 20 and new <= 10  # binomial sd about 2 at 4 in 200
    assert accepted(0.1)[1] >= 170
