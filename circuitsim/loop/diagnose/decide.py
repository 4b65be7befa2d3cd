"""Stages: refit a screened candidate with full simulation, and decide on it.

The decision (see ``noise``): the BIC of prewhitened residuals falls by more than
``BIC_MARGIN``, and again with the noise's long memory taken out first, both models refitted
under it, where either model's residual, otherwise noise, has one; the candidate explains at least ``STRUCTURE_SHARE`` of the structure the
residual holds (its significant spectral lines), so that a slice of an effect outside the
catalog is no confident attribution -- or, for a harmonic of a shaft's angle, most of the
line at its own order and little else (a machine's cogging orders are each a minority of the
whole); and no parameter of it ends on a bound of its physical
range, nor do its parameters together leave it (a candidate's ``limit``): an effect that
only fits there is a stand-in for something else.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from circuitsim.errors import CircuitsimError
from circuitsim.loop.diagnose.context import (
    ModelState,
    Setup,
    angle_locked,
    refit,
    simulate,
    weighted,
    weighted_sse,
)
from circuitsim.loop.diagnose.describe import shaft_frequencies
from circuitsim.loop.diagnose.noise import (
    delta_bic,
    memory_whiteners,
    own_memory_whitener,
    projected_sse,
    significant_lines,
    transient_excess,
    whitened_sse,
    whiteners_of,
)
from circuitsim.loop.diagnose.residual import ORDER_TOL
from circuitsim.loop.diagnose.screen import on_waveform

BIC_MARGIN = 10.0  # "very strong" evidence on the Kass-Raftery scale
STRUCTURE_SHARE = 0.3  # share of the residual's significant structure an effect must explain
#: Where the residual's sum of squares is more than (1 + LARGE_EXCESS) times what white noise
#: at each probe's level gives (ten times: far beyond a few per cent of error in that level,
#: or what coloured noise adds), an effect must remove at least EXCESS_SHARE of the excess:
#: prewhitening learnt on a residual that is mostly a smooth transient whitens most of that
#: transient away, and a small correction of the fast part (a sensor delay on a torsional
#: resonance) can then look like most of what is left.
LARGE_EXCESS = 9.0
EXCESS_SHARE = 0.1
#: A harmonic of a shaft's angle claims one line. Where the structure is many lines (the
#: cogging orders of a slotted machine, each a minority of the whole), it passes instead when
#: it explains at least this share of the structure at its own order on a steadily turning
#: shaft, and its own line is at least this share of what it explains (it fixes that line,
#: not a slice of something else). The set of effects is judged whole at the end
#: (engine._stand_ins).
OWN_LINE_SHARE = 0.5


@dataclass
class Trial:
    """A refitted candidate set and its verdict against the model it would extend."""

    candidates: tuple[Any, ...]
    fit: Any
    delta_bic: float = math.inf
    share: float = 0.0
    at_bound: tuple[str, ...] = ()
    beyond: str = ""  # why the fitted values lie beyond a physical limit, or ""
    note: str = ""
    sse_before: float = 0.0
    sse_after: float = 0.0
    floor: float = 0.0  # the weighted sum of squares the noise alone would give
    evidence: dict[str, Any] = field(default_factory=dict)
    #: ΔBIC with the noise's long memory taken out first (-inf: none found, or not run)
    memory_bic: float = -math.inf
    own_line: float = 0.0  # a harmonic's: the structure at its own order(s) [noise units]
    gain: float = 0.0  # what it explains [noise units]

    @property
    def fixes_its_line(self) -> bool:
        """A harmonic that explains most of the line at its own order and little else."""
        return self.own_line > 0 and self.gain >= OWN_LINE_SHARE * self.own_line and \
            self.own_line >= OWN_LINE_SHARE * self.gain

    @property
    def small_of_large(self) -> bool:
        """It removes little of a residual far above the noise (see LARGE_EXCESS)."""
        excess = self.sse_before - self.floor
        return excess > LARGE_EXCESS * self.floor and \
            self.sse_before - self.sse_after < EXCESS_SHARE * excess

    @property
    def significant(self) -> bool:
        """Significant by both noise filters (the AR one and with the long memory taken
        out) and within its physical range: what a share of the structure is asked of
        beside, for acceptance (``passed``)."""
        return self.delta_bic < -BIC_MARGIN and self.memory_bic < -BIC_MARGIN and \
            not self.at_bound and not self.beyond

    @property
    def passed(self) -> bool:
        line = self.fixes_its_line
        return self.significant and (self.share >= STRUCTURE_SHARE or line) and \
            (line or not self.small_of_large)

    @property
    def masked(self) -> bool:
        """Significant by the AR filter, within its physical range, but not once the noise's
        long memory is taken out: that memory, and the share of the structure it explains,
        may be another effect's structure left in the residual."""
        return self.delta_bic < -BIC_MARGIN <= self.memory_bic and not self.at_bound and \
            not self.beyond

    @property
    def key(self) -> str:
        return " + ".join(c.key for c in self.candidates)


def refit_trial(setup: Setup, state: ModelState, candidates: Sequence[Any],
                starts: Mapping[str, float], model) -> Trial | None:
    """Refit the candidates (with everything free so far) from the screen's starts; a refit
    that ends worse than it began, or worse than the model without them, is retried with the
    new parameters alone first (the angle-locked phase of a harmonic finds its basin), then
    all together, and the better of the two ends is kept."""
    # the candidate is refitted with everything free so far: an effect accepted earlier may
    # have absorbed part of this one (a series resistance standing in for a friction too), and
    # only with its parameters free can the two share the work. The accepted model was fitted
    # to convergence with those parameters free, so what they gain here is the candidate's.
    free = [*state.free, *(n for c in candidates for n in c.free)]
    params = {**state.params, **starts}
    bounds = {**state.bounds, **{n: (lo, hi) for c in candidates
                                 for n, (_, lo, hi) in c.free.items()}}
    start_sim = simulate(setup, model, params)
    start_sse = math.inf if start_sim is None else float(np.sum(np.square(
        weighted(setup, {p: setup.record[p] - start_sim[p] for p in setup.probes}))))
    # an effect that changes the speed slides an angle-locked ripple out of phase: its
    # waveform cost has false minima, so slow features come first (as in the declared fit)
    staged = angle_locked(model) and not any(on_waveform(c) for c in candidates)
    try:
        fit = refit(setup, model, free, params, bounds, staged=staged)
    except CircuitsimError:
        fit = None
    # the model without them bounds it too: a screen's start far off (a breakaway peak's
    # size from a linearisation at rest) may end better than it began and still worse than
    # no effect at all (fresh31's ai08: ΔBIC +1391 for a stick-slip peak on the disc)
    worst = min(start_sse, weighted_sse(setup, state.fit))
    if fit is None or weighted_sse(setup, fit) > worst * (1 + 1e-9):
        new = [n for c in candidates for n in c.free]
        try:
            first = refit(setup, model, new, params, bounds, nfev=20)
            again = refit(setup, model, free, dict(first.params), bounds, nfev=20)
        except CircuitsimError as exc:
            setup.log(f"  refit of {' + '.join(c.key for c in candidates)} failed: {exc}")
            again = None
        if again is not None and (fit is None or
                                  weighted_sse(setup, again) < weighted_sse(setup, fit)):
            fit = again
        if fit is None:
            return None
    if not fit.success:
        # stopped by its budget, not converged: a trial judged there could lose to a rival
        # by what the fit had still to gain. It goes on from there on the waveform (the
        # slow stage has placed it; no phase is left to slide)
        try:
            more = refit(setup, model, free, dict(fit.params), bounds, nfev=20)
        except CircuitsimError:
            more = None
        if more is not None and weighted_sse(setup, more) < weighted_sse(setup, fit):
            fit = more
    return Trial(tuple(candidates), fit)


def judge(setup: Setup, state: ModelState, trial: Trial) -> Trial:
    """Fill in the trial's verdict: ΔBIC on prewhitened residuals (the filter estimated on
    the richer model's residual), the share of structure explained, bounds reached."""
    probes = setup.probes
    whiten = whiteners_of(trial.fit.residuals, probes)
    old = state.whitened(setup, whiten)
    new = {p: float(np.sum(np.square(whiten[p].apply(trial.fit.residuals[p]))))
           for p in probes}
    k = sum(len(c.free) for c in trial.candidates)
    trial.delta_bic = delta_bic(new, old, setup.n, k, probes)
    trial.memory_bic = -math.inf
    if trial.delta_bic < -BIC_MARGIN:
        # a noise with long memory (1/f) rises at low frequencies past what the AR filter
        # follows: the test is repeated with that memory taken out, and must pass too (a
        # gate only: candidates are still ranked by the AR test, as before)
        trial.memory_bic = _memory_bic(setup, state, trial, k)
    dt = float(np.mean(np.diff(setup.record.t)))
    orders = _own_frequencies(state, trial, dt * len(setup.record.t))
    gain, structured, own = _in_noise_units(setup, whiten, old, new, state.fit.residuals,
                                            orders)
    trial.share = gain / structured if structured > 0 else (1.0 if gain > 0 else 0.0)
    trial.gain, trial.own_line = gain, own
    trial.at_bound = _at_bound(trial)
    trial.beyond = "; ".join(filter(None, (c.limit(trial.fit.params) for c in trial.candidates
                                           if c.limit is not None)))
    trial.sse_before, trial.sse_after = weighted_sse(setup, state.fit), \
        weighted_sse(setup, trial.fit)
    trial.floor = float(setup.n * len(probes))  # residuals are in units of each probe's noise
    trial.note = _note(trial)
    return trial


def _memory_bic(setup: Setup, state: ModelState, trial: Trial, k: int) -> float:
    """ΔBIC with the noise's long memory taken out, where either model's residual has one
    (-inf where neither has). Such a probe is whitened by the long-memory noise read on the
    richer model's residual by conditional sum of squares (``noise.own_memory_whitener``),
    the others by their AR filter; both models are then refitted under that noise, linearised
    about the poorer one (its free parameters' steps, and the richer model's change from
    it), by generalised least squares. A fit that weighs a 1/f noise's slow wander as
    heavily as the rest pulls the declared parameters after it, and a candidate that takes
    the wander then "explains" the other probes too (fresh57's bi01: a 0.02 % load-speed
    gain, ΔBIC -73 by the AR filter; its true 1/f spectrum gives the gain 2.2 sigma)."""
    probes = setup.probes
    res, before = trial.fit.residuals, state.fit.residuals
    memory = memory_whiteners(res, probes)
    was = state.memory(setup)
    long = [p for p in probes if memory[p].d or was[p].d]
    if not long:
        return -math.inf
    whiten = {p: own_memory_whitener(res[p]) if p in long else memory[p] for p in probes}
    steps = state.columns(setup)
    if steps is None:
        return delta_bic(whitened_sse(res, whiten, probes), state.whitened(setup, whiten),
                         setup.n, k, probes)
    moved = {p: np.column_stack([steps[p], np.asarray(before[p]) - np.asarray(res[p])])
             for p in probes}
    return delta_bic(projected_sse(before, moved, whiten, probes),
                     projected_sse(before, steps, whiten, probes), setup.n, k, probes)


def explained_and_left(setup: Setup, before: ModelState, after: ModelState,
                       whole: ModelState | None = None) -> tuple[float, float]:
    """What the model ``after`` explains of ``before``'s misfit, and the structure it leaves
    (steady lines or a transient, whichever holds more), both in units of each probe's
    whitened noise variance and measured as ``judge`` measures a trial.

    ``whole``: a model with ``after``'s effects and more, which is then the yardstick: the
    misfit is what ``whole`` explains plus what it leaves, both through the filters learnt
    on its residual, and ``after`` leaves all of it that it does not explain. Effects taken
    out of a model leave their structure in its residual, where filters learnt on that
    residual take a slow part of it for the noise's colour (fresh14's w13: a battery's
    droop, fitted in part by two sensor gains taken out as unstable, left the speeds' sag
    to an AR(6) filter, and a third gain seemed to explain most of what remained)."""
    if whole is None:
        whiten, old, new = _whitened_both(setup, before, after)
        gain, left, _ = _in_noise_units(setup, whiten, old, new, after.fit.residuals)
        return gain, left
    whiten, old, full = _whitened_both(setup, before, whole)
    gain, left, _ = _in_noise_units(setup, whiten, old, full, whole.fit.residuals)
    part = after.whitened(setup, whiten)
    own = sum((old[p] - part[p]) * np.asarray(whole.fit.residuals[p]).size / max(full[p], 1e-300)
              for p in setup.probes)
    return own, max(gain + left - own, 0.0)  # a survivor may fit more than the whole did


def _whitened_both(setup: Setup, before: ModelState, after: ModelState
                   ) -> tuple[Mapping[str, Any], dict[str, float], dict[str, float]]:
    """The whitening filters learnt on ``after``'s residual (as ``judge`` learns them) and
    both models' per-probe whitened sums of squares through them."""
    whiten = whiteners_of(after.fit.residuals, setup.probes)
    return whiten, before.whitened(setup, whiten), after.whitened(setup, whiten)


def probe_rises(setup: Setup, before: ModelState, after: ModelState) -> dict[str, float]:
    """Per probe, how much worse ``after`` fits it than ``before``: the rise of its whitened
    sum of squares in units of its whitened noise variance (negative: it fits better), the
    filter learnt on ``after``'s residual as ``judge`` learns it."""
    _, old, new = _whitened_both(setup, before, after)
    out = {}
    for p in setup.probes:
        var = max(new[p] / max(np.asarray(after.fit.residuals[p]).size, 1), 1e-300)
        out[p] = (new[p] - old[p]) / var
    return out


def _in_noise_units(setup: Setup, whiten, old: Mapping[str, float], new: Mapping[str, float],
                    residuals, orders: list[tuple[float, float]] = ()
                    ) -> tuple[float, float, float]:
    """Summed over the probes, each in units of its whitened noise variance (the richer
    model's whitened sum ``new`` per sample): the gain ``old - new``, the structure
    ``residuals`` hold (steady lines or a transient, whichever holds more) and, of it, the
    lines inside the ``orders`` windows (``_own_frequencies``)."""
    dt = float(np.mean(np.diff(setup.record.t)))
    gain = structured = own = 0.0
    for p in setup.probes:
        e = whiten[p].apply(residuals[p])
        var = max(new[p] / max(e.size, 1), 1e-300)  # the probe's whitened noise variance
        lines = significant_lines(e, dt)
        gain += (old[p] - new[p]) / var
        structured += max(lines.structured, transient_excess(e)) / var
        own += _line_excess(lines, orders) / var
    return gain, structured, own


def _own_frequencies(state: ModelState, trial: Trial, duration: float
                     ) -> list[tuple[float, float]]:
    """(frequency [Hz], tolerance [Hz]) of each harmonic candidate's order on its own shaft
    (its target, when that is a shaft; else every shaft) where it turns steadily in the model
    as it stands; none unless every candidate is a harmonic. The tolerance is the order's
    spread (ORDER_TOL) or the record's resolution, whichever is wider: on a record of few
    turns it spans neighbouring orders (the ODrive log holds 1.1 turns)."""
    if not trial.candidates or any("order" not in c.fixed for c in trial.candidates):
        return []
    shafts = shaft_frequencies(state)
    out = []
    for c in trial.candidates:
        own = {c.target: shafts[c.target]} if c.target in shafts else shafts
        k = c.fixed["order"]
        out += [(abs(k * fs), max(ORDER_TOL * abs(k * fs), 1.5 / duration))
                for fs, steady in own.values() if steady and fs != 0.0]
    return out


def _line_excess(lines, windows: list[tuple[float, float]]) -> float:
    """The excess power of the significant lines inside any of ``windows`` (each counted
    once) [as lines.excess]."""
    if not windows or lines.freqs.size == 0:
        return 0.0
    inside = np.any([np.abs(lines.freqs - f) <= tol for f, tol in windows], axis=0)
    return float(np.sum(lines.excess[inside]))


def _at_bound(trial: Trial) -> tuple[str, ...]:
    """Parameters that end on a bound other than their null value (the physical range's
    edge): the effect fits only by being pushed against it."""
    out = []
    for c in trial.candidates:
        for n, (null, lo, hi) in c.free.items():
            v = trial.fit.params[n]
            at_lo = abs(v - lo) <= 1e-6 * max(abs(lo), 1e-12)
            at_hi = abs(v - hi) <= 1e-6 * max(abs(hi), 1e-12)
            if (at_lo and lo != null) or (at_hi and hi != null):
                out.append(n)
    return tuple(out)


def _note(trial: Trial) -> str:
    if trial.at_bound:
        return f"fits only with {', '.join(trial.at_bound)} at the edge of its physical range"
    if trial.beyond:
        return f"fits only beyond its physical range: {trial.beyond}"
    if trial.delta_bic >= -BIC_MARGIN:
        return f"not significant (ΔBIC {trial.delta_bic:.1f} on prewhitened residuals)"
    if trial.memory_bic >= -BIC_MARGIN:
        return (f"not significant once the noise's long memory is taken out (ΔBIC "
                f"{trial.memory_bic:.1f}; {trial.delta_bic:.1f} with the AR filter alone)")
    if trial.fixes_its_line and (trial.small_of_large or trial.share < STRUCTURE_SHARE):
        return (f"ΔBIC {trial.delta_bic:.1f}, explains {trial.gain / trial.own_line:.0%} of "
                f"the line at its order ({trial.share:.0%} of all the structure)")
    if trial.small_of_large:
        return (f"significant (ΔBIC {trial.delta_bic:.1f}) but removes only "
                f"{(trial.sse_before - trial.sse_after) / (trial.sse_before - trial.floor):.0%}"
                f" of a residual far above the noise")
    if trial.share < STRUCTURE_SHARE:
        return (f"significant (ΔBIC {trial.delta_bic:.1f}) but explains only "
                f"{trial.share:.0%} of the structure the residual holds")
    return f"ΔBIC {trial.delta_bic:.1f}, explains {trial.share:.0%} of the structure"
