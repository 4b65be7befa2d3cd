"""The run plot draws a long series through ``report.plots.envelope``: per pixel column its
first, lowest, highest and last point, so no peak is lost; the CSV keeps every point."""

from __future__ import annotations

import numpy as np

from circuitsim.report.plots import envelope


def test_envelope_keeps_every_columns_extremes_and_ends():
    rng = np.random.default_rng(3)
    n, columns = 200_003, 700
    t = np.linspace(0.0, 1.0, n)
    y = np.cumsum(rng.standard_normal(n)) + 50 * (rng.random(n) < 1e-4)  # walk plus spikes
    te, ye = envelope(t, y, columns)
    assert te.size < 5 * columns
    assert np.all(np.diff(te) > 0)  # a subset, in time order
    idx = np.searchsorted(t, te)
    assert np.array_equal(t[idx], te) and np.array_equal(y[idx], ye)
    per = n // columns
    for start in range(0, n, per):  # every block's extremes and ends are drawn
        block = slice(start, min(start + per, n))
        kept = ye[(te >= t[block][0]) & (te <= t[block][-1])]
        assert kept.max() == y[block].max() and kept.min() == y[block].min()
    assert te[0] == t[0] and te[-1] == t[-1]


def test_short_series_are_drawn_whole():
    t = np.linspace(0.0, 0.3, 6001)
    y = np.sin(2 * np.pi * 826 * t)
    te, ye = envelope(t, y, 660)  # the base model's run plot: 9 points a column
    assert te is t and ye is y
