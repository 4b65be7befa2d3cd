"""Stage: does an accepted effect leave its misfit where it acts?

An effect that is the cause, fitted, leaves noise where it acts: what it adds to the model is
then what the data hold there. One that stands in for a cause outside the catalog matches
that cause only where their shapes agree, and leaves the rest of it in the residual exactly
where it acts -- a fixed sensor delay in place of a speed averaged over a logger's uneven
intervals leaves its misfit at the accelerations, where a delay acts; a viscous drag in
place of shorted turns leaves the turns' speed-dependent ripple where the drag is largest.
This is the residual-against-regressor check of regression diagnostics, read the way
``describe`` reads a residual's rise with the operating point: the residual's power above
its noise, per window of the record, ranked against the power of the effect's own
sensitivity there.

It is asked only of a probe whose final residual still holds structure (``describe``): on a
record the model explains down to its noise there is no misfit to place. A right effect
beside a larger cause outside the catalog that happens to act in the same windows is lost
with this test; the named-share rule (``engine._stand_ins``) already keeps such an effect
out when the cause outside is the larger.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from circuitsim.loop.diagnose.context import ModelState, Setup
from circuitsim.loop.diagnose.describe import FOLLOW_RHO, FOLLOW_WINDOWS
from circuitsim.loop.diagnose.stability import sensitivities


@dataclass(frozen=True)
class Where:
    """How closely a probe's remaining misfit follows where an effect acts."""

    probe: str
    rank_correlation: float  # Spearman's, over FOLLOW_WINDOWS windows [-]

    @property
    def flagged(self) -> bool:
        return self.rank_correlation >= FOLLOW_RHO

    def as_dict(self) -> dict[str, object]:
        return {"probe": self.probe, "rank_correlation": self.rank_correlation,
                "windows": FOLLOW_WINDOWS}

    def why(self) -> str:
        return (f"the structure left in {self.probe} is largest where the effect itself "
                f"acts (rank correlation {self.rank_correlation:.2f} over {FOLLOW_WINDOWS} "
                f"windows of the record), where a cause it described would leave noise")


def _per_window(x: np.ndarray, edges: np.ndarray) -> np.ndarray:
    return np.array([float(np.mean(x[a:b])) for a, b in itertools.pairwise(edges)])


def follows_columns(residual: np.ndarray, sigma: float,
                    columns: Sequence[Mapping[str, np.ndarray]], probe: str
                    ) -> float | None:
    """Spearman's rank correlation, over ``FOLLOW_WINDOWS`` windows, of ``residual``'s power
    above the noise ``sigma`` [probe unit] with the power of ``columns`` (the effect's
    sensitivities in ``probe``, each scaled to unit energy so that every parameter counts);
    None when either is the same in every window (nothing to rank)."""
    from scipy.stats import spearmanr

    r = np.asarray(residual, float)
    edges = np.linspace(0, r.size, FOLLOW_WINDOWS + 1).astype(int)
    if np.min(np.diff(edges)) < 3:
        return None
    # above the noise level: raw power would rank a noise whose level scales with a probe
    power = np.clip(_per_window(np.square(r), edges) - sigma ** 2, 0.0, None)
    acts = np.zeros(FOLLOW_WINDOWS)
    for c in columns:
        e = np.square(np.asarray(c[probe], float))
        total = float(np.sum(e))
        if total > 0.0 and np.isfinite(total):
            acts += _per_window(e, edges) / total
    if np.ptp(power) == 0.0 or np.ptp(acts) <= 1e-12 * float(np.max(acts, initial=0.0)):
        return None
    rho = float(spearmanr(acts, power).statistic)
    return rho if np.isfinite(rho) else None


def where_it_acts(setup: Setup, state: ModelState, candidate, probes: Sequence[str]
                  ) -> Where | None:
    """The probe of ``probes`` (those still holding structure) whose remaining misfit most
    closely follows where ``candidate`` acts in the fitted ``state``; None when a run fails
    or the effect acts alike everywhere."""
    if not candidate.free or not probes:
        return None
    columns = sensitivities(setup, state, candidate)
    if columns is None:
        return None
    best = None
    for p in probes:
        rho = follows_columns(state.fit.residuals[p], setup.weights.get(p, 0.0), columns, p)
        if rho is not None and (best is None or rho > best.rank_correlation):
            best = Where(p, rho)
    return best
