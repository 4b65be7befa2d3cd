"""Stages: propose candidates from the catalog, and screen them by a linearised fit gain.

A score test projects the residual on each candidate's sensitivity at its null value (one
short simulation per free parameter, plus the base run); its least-squares coefficients are
the candidate's start values, complete for every free parameter. Effects a linearisation
cannot see at their null value (saturation) are screened on a small grid instead.

Screening compares phase-insensitive slow features (windowed means and ripple RMS, as the
fit's first stage) for effects that change the speed: a ripple locked to the rotor angle
slides out of phase as soon as the speed changes, and a linearisation of the raw waveform then
points anywhere. Harmonic candidates leave the speed alone to first order and are screened on
the waveform, where the phase tells a torque (cogging) from a voltage (EMF harmonic).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from circuitsim.loop.diagnose.context import (
    ModelState,
    Setup,
    compile_raw,
    simulate,
    simulate_many,
    weighted,
)


@dataclass(frozen=True)
class Proposal:
    """A catalog candidate for this round; ``correction`` when it only re-tunes a term the
    netlist declares (the same order on the same component)."""

    candidate: Any
    correction: bool


@dataclass(frozen=True)
class Screen:
    """A candidate's linearised gain: the share of the projected residual it explains, and
    start values for every one of its free parameters [SI]."""

    proposal: Proposal
    share: float
    start: Mapping[str, float]
    model: Any
    dim: int = 0  # length of the projected residual the share is of


def propose(setup: Setup, state: ModelState, orders: Mapping[str, list[int]],
            tried: set[str]) -> list[Proposal]:
    """The catalog's candidates not yet chosen nor rejected, each flagged when it re-tunes a
    declared term."""
    from circuitsim.loop import effects
    from circuitsim.netlist.load import build

    declared = effects.declared_orders(state.raw)
    chosen = {c.candidate.key for c in state.chosen}
    out = []
    for c in effects.candidates(build(state.raw), orders, setup.probes):
        if c.key in tried or c.key in chosen:
            continue
        order = c.fixed.get("order")
        same = order is not None and int(order) in declared.get(
            ("cogging" if c.effect == "unbalance" else c.effect, c.target), set())
        out.append(Proposal(c, same))
    return out


Projector = Callable[[Any], np.ndarray]


def projections(setup: Setup, model) -> tuple[Projector, Projector, bool]:
    """(slow-feature projector, waveform projector, whether a shaft turns)."""
    from circuitsim.loop.fit import slow_features, smoothing_windows

    rec = setup.record
    W = smoothing_windows(rec.t, [np.asarray(rec[p]) for p in setup.probes])

    def slow(y) -> np.ndarray:
        return np.concatenate([slow_features(W, np.asarray(y[p], float)) / setup.weights[p]
                               for p in setup.probes])

    def wave(y) -> np.ndarray:
        return weighted(setup, y)

    rotating = "rotational" in model.meta.get("integrals", {}).values()
    return slow, wave, rotating


def screen(setup: Setup, state: ModelState, proposal: Proposal, project: Projector,
           noise: float) -> Screen | None:
    """Score test of one candidate (see the module docstring); None when it cannot run or
    acts on nothing measured (its sensitivity stays within the solver's own noise)."""
    cand = proposal.candidate
    model = compile_raw(cand.apply(state.raw))
    base = {**state.params, **{k: v[0] for k, v in cand.free.items()}}
    if cand.effect in SENSOR_LAWS:
        return _sensor(setup, state, proposal, model, base, project)
    if cand.grid:
        y0 = simulate(setup, model, base)
        if y0 is None:
            return None
        e0 = project(setup.record) - project(y0)
        norm0 = float(e0 @ e0)
        return _grid(setup, proposal, model, base, y0, e0, project, norm0) \
            if norm0 > 0.0 else None
    # the base and one step of each parameter in one batched run (one step sequence for all:
    # the differences carry no integration noise of their own)
    steps = {n: cand.steps.get(n, 1e-3) for n in cand.free}
    runs = simulate_many(setup, model, [base, *({**base, n: base[n] + h}
                                                 for n, h in steps.items())])
    y0 = runs[0]
    if y0 is None:
        return None
    e0 = project(setup.record) - project(y0)
    norm0 = float(e0 @ e0)
    if norm0 <= 0.0:
        return None
    cols = []
    for (name, h), y in zip(steps.items(), runs[1:], strict=True):
        col = _first_column(y, y0, h, project, noise)
        if col is None:  # out of the linear range or below the noise: adapt the step alone
            col = _sensitivity(setup, model, base, name, h, y0, project, noise)
        if col is None:
            return None
        cols.append(col)
    S = np.column_stack(cols)
    coef, *_ = np.linalg.lstsq(S, e0, rcond=None)
    gain = float(e0 @ (S @ coef))
    start = {n: _inside(cand.free[n], base[n] + float(c))
             for n, c in zip(cand.free, coef, strict=True)}
    return Screen(proposal, gain / norm0, start, model, e0.size)


def _inside(spec: tuple[float, float, float], value: float) -> float:
    _, lo, hi = spec
    return min(max(value, lo), hi)


def _first_column(y, y0, h: float, project: Projector, noise: float) -> np.ndarray | None:
    """The batched first difference, when its size is in the linear range above the noise."""
    if y is None:
        return None
    col = (project(y) - project(y0)) / h
    size = float(np.linalg.norm(col * h))
    if max(1e-7 * math.sqrt(col.size), 10 * noise) <= size <= 0.3 * math.sqrt(col.size):
        return col
    return None


def _sensitivity(setup: Setup, model, base: Mapping[str, float], name: str, h: float, y0,
                 project: Projector, noise: float) -> np.ndarray | None:
    """d(projection)/d(parameter) by a step sized to stay above the solver's noise and
    below the non-linear range."""
    size = 0.0
    for _ in range(3):
        y = simulate(setup, model, {**base, name: base[name] + h})
        if y is None:
            return None
        col = (project(y) - project(y0)) / h
        size = float(np.linalg.norm(col * h))
        if size < max(1e-7 * math.sqrt(col.size), 10 * noise):
            h *= 100  # invisible above the solver's noise: a bigger step
        elif size > 0.3 * math.sqrt(col.size):
            h /= 30  # far from linear: a smaller one
        else:
            return col
    return col if size >= 10 * noise else None


def _grid(setup: Setup, proposal: Proposal, model, base: Mapping[str, float], y0,
          e0: np.ndarray, project: Projector, norm0: float) -> Screen | None:
    """Effects invisible to a linearisation at null: a few values of the first parameter,
    scaled by the target's current where it has one; the others keep their start values."""
    cand = proposal.candidate
    first = next(iter(cand.free))
    key = f"{cand.target}.i"
    scale = max(float(np.max(np.abs(y0[key]))), 1e-9) if key in y0.names else 1.0
    best: Screen | None = None
    for g in cand.grid:
        trial = {**base, first: _inside(cand.free[first], g * scale)}
        y = simulate(setup, model, trial)
        if y is None:
            continue
        e = e0 - (project(y) - project(y0))
        share = (norm0 - float(e @ e)) / norm0
        if best is None or share > best.share:
            best = Screen(proposal, share, {n: trial[n] for n in cand.free}, model, e0.size)
    return best


# a sensor law's sensitivity to its parameter at null, from the probe's own series x
SENSOR_LAWS = {"sensor-gain": lambda x: x, "sensor-offset": np.ones_like}


def _sensor(setup: Setup, state: ModelState, proposal: Proposal, model, base,
            project: Projector) -> Screen | None:
    """Sensor effects act on one probe only, through a known law: their sensitivity needs
    no simulation."""
    cand = proposal.candidate
    sim = state.fit.sim
    y0 = {p: np.asarray(sim[p], float) for p in setup.probes}
    if cand.target not in y0:
        return None
    bumped = dict(y0)
    bumped[cand.target] = y0[cand.target] + SENSOR_LAWS[cand.effect](y0[cand.target])
    col = project(bumped) - project(y0)
    e0 = project(setup.record) - project(y0)
    norm0 = float(e0 @ e0)
    den = float(col @ col)
    if norm0 <= 0.0 or den <= 0.0:
        return None
    coef = float(col @ e0) / den
    (name,) = cand.free
    start = {name: _inside(cand.free[name], base[name] + coef)}
    return Screen(proposal, coef * coef * den / norm0, start, model, e0.size)
