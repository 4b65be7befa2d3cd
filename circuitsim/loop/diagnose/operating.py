"""Where in its operating range a probe's unexplained residual lives: the band of a probe's
simulated magnitude that holds most of the residual's excess power over its noise.

A cause outside the catalog often acts in one part of the range only: a speed pick-up that
reads nothing below some speed, a dead zone or a stiction about zero, a field that weakens
at high current, an inrush that a relay's resistance limits. Time windows (``describe``'s
timing and its rank correlations) mix the parts of the range a record passes through; the
samples sorted by a probe's own magnitude separate them. For the report's words only: no
decision reads it.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

#: the equal-count bins the samples are sorted into by a driver's magnitude, the largest
#: share of the samples a band may cover, and the least share of the excess it must hold
BAND_BINS = 20
BAND_COVER = 0.25
BAND_SHARE = 0.75
#: a band's excess must stand this many of the noise's own standard deviations above zero
#: (a sum of m squared white samples of variance s^2 has standard deviation s^2 sqrt(2 m))
BAND_SIGMAS = 6.0


def operating_band(drivers: Mapping[str, np.ndarray], r: np.ndarray, sigma: float,
                   own: str | None = None) -> dict[str, Any] | None:
    """The narrowest band of one driver's magnitude (``drivers``: a probe's simulated
    values [probe unit] per sample) that holds at least ``BAND_SHARE`` of the residual
    ``r``'s excess power over its white noise ``sigma`` [probe unit] while covering at most
    ``BAND_COVER`` of the samples, its excess ``BAND_SIGMAS`` beyond the noise's spread;
    among drivers, the narrowest band, then the largest share, then the residual's ``own``
    probe (a load's speed read through a rigid gear bands as the motor's does). None when
    no driver has one (an excess spread over the whole range: a cogging, a ripple at every
    speed)."""
    found = [b for name, x in drivers.items()
             if (b := _band(name, np.abs(np.asarray(x, float)), np.asarray(r, float), sigma))]
    if not found:
        return None
    return min(found, key=lambda b: (round(b["cover"], 9), -round(b["share"], 9),
                                     b["signal"] != f"|{own}|"))


def _band(name: str, level: np.ndarray, r: np.ndarray, sigma: float) -> dict[str, Any] | None:
    """``operating_band`` for one driver's magnitude ``level`` per sample."""
    n = r.size
    if level.size != n or n < 4 * BAND_BINS or not sigma > 0.0:
        return None
    order = np.argsort(level, kind="stable")
    edges = np.linspace(0, n, BAND_BINS + 1).astype(int)
    excess = np.array([float(np.sum(np.square(r[order[a:b]]))) - (b - a) * sigma ** 2
                       for a, b in itertools.pairwise(edges)])
    # a bin at its noise may fall below zero by chance: it adds nothing to the total
    total = float(np.sum(np.clip(excess, 0.0, None)))
    if total <= 0.0:
        return None
    for width in range(1, int(BAND_COVER * BAND_BINS) + 1):
        runs = [(i, i + width, float(np.sum(excess[i:i + width])) / total)
                for i in range(BAND_BINS - width + 1)]
        i, j, share = max(runs, key=lambda run: run[2])
        m = int(edges[j] - edges[i])
        if share >= BAND_SHARE and share * total > BAND_SIGMAS * sigma ** 2 * math.sqrt(2 * m):
            return {"signal": f"|{name}|", "low": float(level[order[edges[i]]]),
                    "high": float(level[order[edges[j] - 1]]), "share": min(share, 1.0),
                    "cover": m / n}
    return None


def band_text(band: Mapping[str, Any] | None, lead: str = "; ") -> str:
    """The band in words after ``lead``, or '' without one."""
    if not band:
        return ""
    return (f"{lead}{band['share']:.0%} of its excess where {band['signal']} is "
            f"{band['low']:.3g}-{band['high']:.3g} ({band['cover']:.0%} of the samples)")


def drivers_of(sim: Mapping[str, Any], probes: Sequence[str]) -> dict[str, np.ndarray]:
    """Each probe's simulated values that ``sim`` holds [probe unit]."""
    out = {}
    for q in probes:
        try:
            out[q] = np.asarray(sim[q], float)
        except KeyError:
            continue
    return out
