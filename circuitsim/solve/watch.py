"""A run that cannot finish, found by its pace: simulated time gained per residual evaluation
(and the words for a solve that fails on a parameter beyond any physical value).

A parameter far from its physical value can make a run's solution change ever faster: a 1 TV
supply spins a motor without bound, its back-EMF ripple's frequency rises with the speed, and
IDA, which must follow it, takes ever smaller steps. Every step succeeds, so IDA's own limits
(steps per output time) never trip, and the run would take days. SPICE would grind the same
way; we stop it and say why instead.

The watch counts the Python route's residual evaluations and, every ``WINDOW`` of them, how far
the simulated time has moved (the pace): at that pace, reaching the stop time needs a projected
number of further evaluations. A run is stopped when that projection exceeds ``LIMIT`` (about
40 minutes at the Python route's 25 us an evaluation) at ``STRIKES`` judgements in a row AND
its pace kept falling over them, by ``SLOWING`` at least: a run that runs away slows down as it
goes. A long run at a steady pace (a PWM drive simulated for minutes) is never stopped, however
long it is, nor is a start-up transient that is slow for a while. The decision depends on
counts and simulated times only, never on the clock, so a run is stopped, or not, the same way
on every machine. A run on the compiled kernels (``solve/direct.py``: a sweep's, a fit's
single runs) is watched by the same rule on IDA's own count of evaluations, read between
groups of output times (``advance``), so ``run`` and ``sweep`` stop the same run. The stacked
batches of fits and diagnoses are not watched: their runs are the fit's own, bounded by IDA's
steps per output time. ``CIRCUITSIM_RUNAWAY=off`` turns the watch off for a run meant to be
that long.
"""

from __future__ import annotations

import itertools
import os
from collections.abc import Callable, Sequence

import numpy as np

from circuitsim.errors import SolverError, spoken

#: [evaluations] the pace is measured over this many residual evaluations
WINDOW = 100_000
#: [evaluations] a run projected to need more than this many more evaluations may be stopped
LIMIT = 1e8
#: judgements in a row over the limit, the pace falling at each, before the run is stopped
STRIKES = 3
#: the pace at the last of them is at most this fraction of the first's
SLOWING = 0.9


#: [SI] a state, rate or parameter beyond this is no physical value: IDA's and Newton's norms
#: square it and overflow
HUGE = 1e100


def huge_parameters(model, p: Sequence[float]) -> str:
    """The words for a failed solve's parameters beyond any physical value, if it has any
    (``p`` in the order of the model's parameters)."""
    huge = [f"{name} = {v:.3g}" for name, v in zip(model.meta["params"], p, strict=True)
            if not abs(v) < HUGE]
    if not huge:
        return ""
    return (f". The parameter values {', '.join(huge)} are beyond any physical value: they "
            f"overflow the solver's arithmetic; check the netlist's parameters and --set")


class Runaway(SolverError):
    """The run's pace projects it far beyond any reasonable number of evaluations."""


def watch_of(residual: Callable) -> Watch | None:
    """The watch a System's residual carries, for the compiled route to report to."""
    return residual if isinstance(residual, Watch) else None


def watched(residual: Callable, stop: float, names: Sequence[str], rtol: float,
            atol: float) -> Callable:
    """``residual`` itself when the watch is off, else ``residual`` watched (``Watch``)."""
    if os.environ.get("CIRCUITSIM_RUNAWAY", "").strip().lower() in ("0", "off", "no"):
        return residual
    return Watch(residual, stop, names, rtol, atol)


class Watch:
    """The residual function, passed through, counting its calls and judging the pace."""

    def __init__(self, residual: Callable, stop: float, names: Sequence[str], rtol: float,
                 atol: float):
        self.residual, self.stop, self.names = residual, stop, tuple(names)
        self.rtol, self.atol = rtol, atol
        self.count = 0
        self.mark: float | None = None  # [s] the simulated time at the last judgement
        self.mark_count = 0  # the evaluations counted at the last judgement
        self.paces: list[float] = []  # [s] gained per window, the last ones over the limit

    def __call__(self, t, y, yp, res, p):
        # the model's residual's own signature: scikit-sundae reads it, and refuses *args
        self.count += 1
        if self.count % WINDOW == 0:
            self.judge(float(t), y, yp)
        return self.residual(t, y, yp, res, p)

    def advance(self, evals: int, t: float, y, yp) -> None:
        """The compiled route's account: ``evals`` more evaluations brought the run to t.
        Judged once whenever the count passes a multiple of WINDOW (the caller reads IDA's
        count about once a window)."""
        before, self.count = self.count, self.count + int(evals)
        if self.count // WINDOW > before // WINDOW:
            self.judge(float(t), y, yp)

    def judge(self, t: float, y, yp) -> None:
        """Raise ``Runaway`` when the pace has projected more than LIMIT further evaluations
        at STRIKES judgements in a row, falling at each and by SLOWING over them."""
        if self.mark is None:
            self.mark, self.mark_count = t, self.count
            return
        # [s] per WINDOW evaluations: the Python route judges every WINDOW exactly, the
        # compiled route after about as many
        span = max(self.count - self.mark_count, 1)
        gained = (t - self.mark) * WINDOW / span
        self.mark, self.mark_count = t, self.count
        projected = np.inf if gained <= 0 else max(self.stop - t, 0.0) / gained * WINDOW
        if projected <= LIMIT:
            self.paces = []
            return
        self.paces = [*self.paces, gained][-STRIKES:]
        p = self.paces
        if (len(p) == STRIKES and all(b <= a for a, b in itertools.pairwise(p))
                and p[-1] <= SLOWING * p[0]):
            raise Runaway(self.message(t, gained, projected, y, yp))

    def message(self, t: float, gained: float, projected: float, y, yp) -> str:
        with np.errstate(all="ignore"):
            rate = np.abs(np.asarray(yp)) / (self.rtol * np.abs(np.asarray(y)) + self.atol)
        k = int(np.nanargmax(rate)) if np.isfinite(rate).any() else 0
        name = spoken(self.names[k]) if k < len(self.names) else "?"
        return (f"at t = {t:.6g} s the run gains {gained:.3g} s of simulated time per "
                f"{WINDOW} residual evaluations and slows down: reaching the stop time "
                f"{self.stop:g} s at that pace needs about {projected:.2g} more, and the pace "
                f"keeps falling, so it was stopped. Its solution changes ever faster; fastest-"
                f"changing variable: {name} = {float(np.asarray(y)[k]):.4g}. A parameter far "
                f"from its physical value does this (check the netlist's parameters and "
                f"--set), or a missing limit (a motor that accelerates without bound). A run "
                f"meant to be this long: set CIRCUITSIM_RUNAWAY=off")
