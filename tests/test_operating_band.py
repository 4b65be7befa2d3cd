"""loop/diagnose/operating.py: the band of a probe's magnitude that holds a residual's
excess power, against residuals built with a known band."""

from __future__ import annotations

import numpy as np
import pytest

from circuitsim.loop.diagnose.operating import (
    BAND_COVER,
    BAND_SHARE,
    band_text,
    operating_band,
)


def _record(seed: int, n: int = 10000):
    """A speed that runs up, holds, reverses and stops [rad/s], and white noise of unit
    variance as a residual."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, 1.0, n)
    speed = np.interp(t, [0.0, 0.3, 0.5, 0.7, 0.9, 1.0], [0.0, 150.0, 150.0, -60.0, 0.0, 0.0])
    return speed, rng.normal(size=n)


@pytest.mark.parametrize("seed", range(5))
def test_a_residual_that_lives_below_a_speed_is_banded_there(seed):
    """A pick-up that reads nothing below 20 rad/s leaves a residual of the speed itself
    there (and only while the shaft turns): at least BAND_SHARE of the excess in a band that
    ends at 20 rad/s, within the bins' resolution (a twentieth of the samples), on every
    seed; the driver the record's own probe where two band alike."""
    speed, noise = _record(seed)
    low = (np.abs(speed) < 20.0) & (np.abs(speed) > 0.0)
    r = noise + np.where(low, speed, 0.0)
    band = operating_band({"speed": speed, "load_speed": speed / 3.0}, r, 1.0, "speed")
    assert band is not None and band["signal"] == "|speed|"
    assert band["share"] >= BAND_SHARE and band["cover"] <= BAND_COVER
    # the excess is the speed squared: the band's top at 20 rad/s, its bottom where the
    # slowest quarter of the excess begins (6.9-20.7 rad/s on seed 3)
    assert 0.0 <= band["low"] < 10.0 and 15.0 < band["high"] < 30.0, band
    assert "of its excess where |speed| is" in band_text(band)
    other = operating_band({"speed": speed, "load_speed": speed / 3.0}, r, 1.0, "load_speed")
    assert other["signal"] == "|load_speed|" and other["high"] == pytest.approx(
        band["high"] / 3.0)


@pytest.mark.parametrize("seed", range(5))
def test_a_residual_at_every_speed_or_noise_alone_has_no_band(seed):
    """A ripple of one amplitude through the whole record, and white noise alone (its
    excess a chance one), give no band: the excess is spread over the range."""
    speed, noise = _record(seed)
    t = np.linspace(0.0, 1.0, speed.size)
    ripple = noise + 2.0 * np.sin(2 * np.pi * 37.0 * t)
    assert operating_band({"speed": speed}, ripple, 1.0) is None
    assert operating_band({"speed": speed}, noise, 1.0) is None
    assert band_text(None) == ""
