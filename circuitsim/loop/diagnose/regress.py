"""Linearised tests: does a set of extra regressors explain a residual beyond a base set?

The stand-in tests (``stability``, ``law``) regress the final residual on an effect's
sensitivities and on extra columns (their copies per piece of the record, per band, or the
bends of its law) and compare, on prewhitened residuals, what the extra columns gain.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from circuitsim.loop.diagnose.noise import Whitener, delta_bic, whiteners_of


def added_test(residuals: Mapping[str, np.ndarray],
               columns: Sequence[Mapping[str, np.ndarray]],
               split: Sequence[Mapping[str, np.ndarray]], weights: Mapping[str, float],
               probes: Sequence[str]) -> tuple[float, float]:
    """(ΔBIC, gain [units of each probe's whitened noise variance]) of the regressors
    ``split`` added to ``columns`` (each, per probe, a change of the model's output [probe
    unit]) against ``residuals`` (measured - model). The prewhitening filter is learnt on the
    richer regression's residual, as every decision's is (``noise``)."""
    n = len(np.asarray(residuals[probes[0]]))
    whole = list(columns)
    if not split:
        return 0.0, 0.0
    raw = _stack(residuals, probes, weights)
    x, _ = unit_columns(np.column_stack([_stack(c, probes, weights) for c in whole + split]))
    beta, *_ = np.linalg.lstsq(x, raw, rcond=None)
    left = raw - x @ beta
    whiten = whiteners_of({p: left[k * n:(k + 1) * n] for k, p in enumerate(probes)}, probes)

    def stack(series: Mapping[str, np.ndarray]) -> np.ndarray:
        return _stack(series, probes, weights, whiten)

    r = stack(residuals)
    sizes = [whiten[p].apply(np.zeros(n)).size for p in probes]
    old = _probe_sse(r, np.column_stack([stack(c) for c in whole]), probes, sizes)
    new = _probe_sse(r, np.column_stack([stack(c) for c in whole + split]), probes, sizes)
    gain = sum((old[p] - new[p]) / max(new[p] / m, 1e-300) for p, m in zip(probes, sizes,
                                                                           strict=True))
    return delta_bic(new, old, n, len(split), probes), max(gain, 0.0)


def unit_columns(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(``x`` with each column scaled to unit norm, the norms): a least squares on columns
    whose scales differ by many orders (a reading's third derivative beside its gain) then
    loses no digits; an all-zero column keeps norm 1."""
    norms = np.linalg.norm(x, axis=0)
    norms = np.where(norms > 0.0, norms, 1.0)
    return x / norms, norms


def _stack(series: Mapping[str, np.ndarray], probes: Sequence[str],
           weights: Mapping[str, float], whiten: Mapping[str, Whitener] | None = None
           ) -> np.ndarray:
    """The probes' series, each prewhitened (when ``whiten``) and over its noise level."""
    return np.concatenate([(whiten[p].apply(np.asarray(series[p], float)) if whiten else
                            np.asarray(series[p], float)) / weights[p] for p in probes])


def _probe_sse(r: np.ndarray, x: np.ndarray, probes: Sequence[str], sizes: Sequence[int]
               ) -> dict[str, float]:
    """Each probe's sum of squares of ``r`` less its least-squares fit on ``x``."""
    scaled, _ = unit_columns(x)
    beta, *_ = np.linalg.lstsq(scaled, r, rcond=None)
    e = r - scaled @ beta
    out, i = {}, 0
    for p, m in zip(probes, sizes, strict=True):
        out[p] = float(e[i:i + m] @ e[i:i + m])
        i += m
    return out
