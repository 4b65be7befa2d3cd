"""The diagnosis's noise model (loop/diagnose/noise.py) against closed forms: the AR
prewhitening filter, and the long memory (1/f-like noise) taken out before the test."""

from __future__ import annotations

import numpy as np
import pytest

from circuitsim.loop.diagnose.noise import (
    fit_whitener,
    fractional_difference,
    memory_order,
    memory_whiteners,
)


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
