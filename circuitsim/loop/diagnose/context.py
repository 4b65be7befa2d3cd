"""The plain objects the diagnosis stages pass to each other, and the simulations they share.

``Setup`` is what does not change during a diagnosis (the record, the probes, their noise
weights, the declared free parameters); ``ModelState`` is the model as it stands (raw
netlist, compiled model, free parameters, fit, and what has been accepted so far).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from circuitsim.errors import CircuitsimError
from circuitsim.loop.diagnose.noise import (
    Whitener,
    memory_whiteners,
    whitened_sse,
    whiteners_of,
)

MAX_EFFECTS = 4  # new causes a diagnosis names at most


@dataclass(frozen=True)
class Setup:
    """What a diagnosis holds fixed.

    weights : each probe's noise standard deviation [probe unit]: the fit's residuals are
        divided by it, so a probe counts by its signal-to-noise ratio, not its spread.
    """

    record: Any
    probes: tuple[str, ...]
    weights: Mapping[str, float]
    declared: tuple[str, ...]
    rtol: float
    max_effects: int
    say: Any = field(default=None, compare=False, repr=False)

    @property
    def n(self) -> int:
        """Samples per probe."""
        return int(self.record.t.size)

    def log(self, message: str) -> None:
        if self.say is not None:
            self.say(message)


@dataclass(frozen=True)
class Choice:
    """An accepted catalog candidate; ``correction``: it re-tunes a term the netlist already
    declares (the same harmonic order on the same component), not a new cause."""

    candidate: Any
    correction: bool = False


@dataclass
class ModelState:
    """The model as it stands: the netlist with the accepted patches, fitted."""

    raw: Any
    model: Any
    free: list[str]
    params: dict[str, float]
    fit: Any
    bounds: dict[str, tuple[float, float]]
    chosen: list[Choice] = field(default_factory=list)
    base_raw: Any = None  # the declared netlist, before any patch
    _memory: Any = field(default=None, repr=False, compare=False)
    _columns: Any = field(default=None, repr=False, compare=False)

    def whitened(self, setup: Setup, whiteners: Mapping[str, Whitener] | None = None
                 ) -> dict[str, float]:
        """Per-probe sums of squares of the prewhitened residual (own filters by default)."""
        w = whiteners or whiteners_of(self.fit.residuals, setup.probes)
        return whitened_sse(self.fit.residuals, w, setup.probes)

    def memory(self, setup: Setup) -> dict[str, Whitener]:
        """The residual's long-memory whiteners (``noise.memory_whiteners``), kept while the
        fit is this one: every trial judged against this state reads them."""
        if self._memory is None or self._memory[0] is not self.fit:
            self._memory = (self.fit, memory_whiteners(self.fit.residuals, setup.probes))
        return self._memory[1]

    def columns(self, setup: Setup) -> dict[str, np.ndarray] | None:
        """Per probe, the model's change [probe unit] for a step of each free parameter of
        one standard error (a thousandth of its value where that is unknown): the
        linearised model about this fit, for refitting it under another noise model. None
        when a step fails to simulate."""
        if self._columns is None or self._columns[0] is not self.fit:
            self._columns = (self.fit, self._stepped(setup))
        return self._columns[1]

    def _stepped(self, setup: Setup) -> dict[str, np.ndarray] | None:
        stderr = getattr(self.fit, "stderr", {}) or {}
        steps = {}
        for name in self.free:
            value, h = float(self.params[name]), float(stderr.get(name, math.nan))
            steps[name] = h if math.isfinite(h) and h > 0 else 1e-3 * (abs(value) or 1.0)
        if not steps:  # nothing freed: the poorer model has no columns, and nothing to run
            return {p: np.zeros((np.size(self.fit.residuals[p]), 0)) for p in setup.probes}
        runs = simulate_many(setup, self.model, [{**self.params, n: self.params[n] + h}
                                                 for n, h in steps.items()])
        if any(r is None for r in runs):
            return None
        base = {p: np.asarray(setup.record[p], float) - np.asarray(self.fit.residuals[p])
                for p in setup.probes}
        return {p: np.column_stack([np.asarray(r[p], float) - base[p] for r in runs])
                for p in setup.probes}


def compile_raw(raw):
    """Compile a (patched) raw netlist; the cache makes a repeated topology cheap (and the
    worker compiling ahead may have filled it: ``solve/ahead.py``)."""
    from circuitsim.compiler.model import compile as compile_model
    from circuitsim.netlist.load import build
    from circuitsim.solve import ahead

    ahead.claim(raw)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return compile_model(build(raw))


def simulate(setup: Setup, model, params: Mapping[str, float], rtol: float | None = None):
    """The model's transient on the record's grid, or None when it fails."""
    rec = setup.record
    try:
        res = model.simulate(stop=float(rec.t[-1]), params=dict(params), t_eval=rec.t,
                             rtol=rtol or setup.rtol, atol=model.netlist.analysis.atol)
    except (CircuitsimError, ArithmeticError, ValueError):
        return None  # a patch pushed to a bad value fails like a failed run
    if not res.success or res.t.size != rec.t.size:
        return None
    return res


def simulate_many(setup: Setup, model, params_list: Sequence[Mapping[str, float]],
                  rtol: float | None = None, nearby: bool = True) -> list[Any]:
    """Several parameter sets of one model in one batched integration; None for a member
    that fails. ``nearby``: small steps from one point (see ``simulate_batch``)."""
    from circuitsim.solve.batch import simulate_batch

    rec = setup.record
    try:
        runs = simulate_batch(model, [dict(q) for q in params_list], stop=float(rec.t[-1]),
                              t_eval=rec.t, rtol=rtol or setup.rtol,
                              atol=model.netlist.analysis.atol, nearby=nearby)
    except (CircuitsimError, ArithmeticError, ValueError):
        return [simulate(setup, model, q, rtol) for q in params_list]
    return [r if r.success and r.t.size == rec.t.size else None for r in runs]


def weighted(setup: Setup, series: Mapping[str, Any]) -> np.ndarray:
    """Probe series divided by each probe's noise, concatenated."""
    return np.concatenate([np.asarray(series[p], float) / setup.weights[p]
                           for p in setup.probes])


#: The relative change of the weighted SSE that ends a refit. The SSE is about the number of
#: samples (tens of thousands), so 1e-6 of it is far below the BIC margin a decision turns
#: on; iterating further only buys digits no decision reads.
FIT_TOL = 1e-6


def refit(setup: Setup, model, free: Sequence[str], params: Mapping[str, float],
          bounds: Mapping[str, tuple[float, float]], *, staged: bool = False,
          nfev: int = 12, slip: bool = False,
          progress: Callable[[str], None] | None = None):
    """Least squares of ``free`` on the record, residuals weighted by the probes' noise.
    ``setup.record`` is the working record already and is fitted as it is (a long one the
    user keeps whole, ``--full-record``, stays whole);
    ``slip``: refuse a record the model matches only after a unit's factor or a sign;
    ``progress``: called with a line after each of the fit's simulations."""
    from circuitsim.loop.fit import fit_record

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        b = {k: v for k, v in bounds.items() if k in free}
        return fit_record(model, setup.record, list(free), params=dict(params),
                          bounds=b or None, probes=list(setup.probes), rtol=setup.rtol,
                          staged=staged, max_nfev=nfev,
                          weights=dict(setup.weights), tol=FIT_TOL, refuse_slip=slip,
                          progress=progress, reduce=False)


def weighted_sse(setup: Setup, fit) -> float:
    e = weighted(setup, fit.residuals)
    return float(e @ e)


def angle_locked(model) -> bool:
    """Whether the model's laws read a shaft angle (a declared ripple, cogging): then a change
    of speed slides that ripple out of phase, and speed effects are compared on slow features
    rather than on the waveform. A shaft whose angle only integrates its speed holds no such
    phase, and neither does a coupling that reads only the twist between two shafts (a
    spring): the waveform, with every sample, is then the sharper view."""
    meta = model.meta
    angles = [s for s, d in meta.get("integrals", {}).items() if d == "rotational"]
    states, pattern = meta.get("states"), meta.get("fy_pattern")
    if not angles or states is None or pattern is None:
        return bool(angles)  # no pattern to tell by: assume the ripple is there
    cols = {states.index(a) for a in angles if a in states}
    # an angle's own row (phi' = w) has no entry in dF/dphi: any entry is a law of the angle
    if not any(int(c) in cols for c in pattern[1]):
        return False
    return not _twist_only(model, sorted(cols))


def _twist_only(model, cols: Sequence[int]) -> bool:
    """Whether the residual is unchanged when every shaft turns by the same angle, at a few
    arbitrary states: its laws then read differences of angles only. A ripple reads the
    angle itself and changes; a gear (the shafts turn by different angles) counts as a
    ripple here, the cautious side."""
    residual = model.fns[0]
    p = model.param_vector()
    n = len(model.meta["states"])
    rng = np.random.default_rng(0)
    for _ in range(3):
        y, yp = rng.uniform(0.1, 1.0, n), rng.uniform(-1.0, 1.0, n)
        shifted = y.copy()
        shifted[list(cols)] += 0.7318  # no simple fraction of a turn: no order repeats
        r0, r1 = np.zeros(n), np.zeros(n)
        try:
            with np.errstate(all="ignore"):
                residual(0.0, y, yp, r0, p)
                residual(0.0, shifted, yp, r1, p)
        except (ArithmeticError, ValueError):  # a law undefined at this arbitrary state
            return False
        scale = np.abs(r0) + 1.0
        if not (np.all(np.isfinite(r0)) and np.all(np.abs(r1 - r0) <= 1e-9 * scale)):
            return False
    return True
