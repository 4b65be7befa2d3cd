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

import dataclasses
import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.optimize import lsq_linear

from circuitsim.loop.diagnose.context import (
    ModelState,
    Setup,
    angle_locked,
    compile_raw,
    simulate,
    simulate_many,
    weighted,
)
from circuitsim.solve import ahead


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
    model: Any  # the candidate's compiled model; None when not compiled yet (a sensor's)
    dim: int = 0  # length of the projected residual the share is of


def propose(setup: Setup, state: ModelState, orders: Mapping[str, list[int]],
            tried: set[str]) -> list[Proposal]:
    """The catalog's candidates not yet chosen nor rejected, each flagged when it re-tunes a
    declared term."""
    from circuitsim.loop import effects
    from circuitsim.netlist.load import build

    declared = effects.declared_orders(state.raw)
    # one of each effect on each target: the starts of a shape are one effect
    chosen = {c.candidate.kind for c in state.chosen}
    out = []
    units = state.model.meta.get("units", {})
    probes = {p: units[p] for p in setup.probes if p in units}
    t = np.asarray(setup.record.t, float)
    net = build(state.raw)
    wanted = {n: list(ks) for n, ks in orders.items()}  # the residual's, then every shaft's
    for n, ks in effects.always_orders(net).items():
        wanted.setdefault(n, []).extend(k for k in ks if k not in wanted[n])
    for c in effects.candidates(net, wanted, probes or setup.probes,
                                duration=float(t[-1] - t[0])):
        if c.key in tried or c.kind in chosen or (c.retunes and _freed(state.raw, c, setup)):
            continue
        order = c.fixed.get("order")
        same = order is not None and int(order) in declared.get(
            ("cogging" if c.effect == "unbalance" else c.effect, c.target), set())
        out.append(Proposal(c, same or c.retunes))
    return out


def _freed(raw, candidate, setup: Setup) -> bool:
    """Whether the value a re-tuning candidate scales reads a parameter the user frees
    already (EMPS's mass M): the fit moves it, and a second handle on it is degenerate."""
    from circuitsim.loop.effects import RETUNED

    entry = raw.component_entry(candidate.target)
    value = str(entry.get(RETUNED.get(str(entry.get("type")), ""), ""))
    return bool(set(re.findall(r"[A-Za-z_]\w*", value)) & set(setup.declared))


Projector = Callable[[Any], np.ndarray]


def on_waveform(candidate) -> bool:
    """Whether a candidate is screened on the waveform: a harmonic (its phase tells a torque
    from a voltage) or a sensor law (it leaves the speed, and so every angle-locked phase,
    alone); the rest, on the slow features."""
    return "order" in candidate.fixed or candidate.effect in SENSOR_LAWS


def projections(setup: Setup, model) -> tuple[Projector, Projector, bool]:
    """(slow-feature projector, waveform projector, whether a ripple is locked to a shaft's
    angle)."""
    from circuitsim.loop.fit import slow_features, smoothing_windows

    rec = setup.record
    W = smoothing_windows(rec.t, [np.asarray(rec[p]) for p in setup.probes])

    def slow(y) -> np.ndarray:
        return np.concatenate([slow_features(W, np.asarray(y[p], float)) / setup.weights[p]
                               for p in setup.probes])

    def wave(y) -> np.ndarray:
        return weighted(setup, y)

    return slow, wave, angle_locked(model)


def screen(setup: Setup, state: ModelState, proposal: Proposal,
           project: Projector | tuple[Projector, ...], noise: float,
           margin: float = 10.0) -> Screen | None:
    """Score test of one candidate (see the module docstring); None when it cannot run or
    acts on nothing measured (its sensitivity stays within the solver's own noise).
    ``project``: a projection, or alternatives in order of preference -- a grid's runs are
    seen through each, and the first whose promise pays ``margin`` is kept (as in
    ``screen_many``); the others use the first."""
    cand = proposal.candidate
    views = _alternatives(project)
    project = views[0]
    base = {**state.params, **{k: v[0] for k, v in cand.free.items()}}
    if cand.effect in SENSOR_LAWS:  # no run: its model is compiled if it is refitted
        return _sensor(setup, state, proposal, base, project)
    model = compile_raw(cand.apply(state.raw))
    if cand.grid:
        return _grid(setup, proposal, model, base, views, _undone(state, cand), margin)
    # the base and one step of each parameter in one batched run (one step sequence for all:
    # the differences carry no integration noise of their own)
    steps = {n: cand.steps.get(n, 1e-3) for n in sized(cand)}
    runs = simulate_many(setup, model, [base, *({**base, n: base[n] + h}
                                                 for n, h in steps.items())])
    if runs[0] is None:
        return None
    s = _from_runs(setup, proposal, model, runs[0], dict(zip(steps, runs[1:], strict=True)),
                   project, noise, base)
    return None if s is None else dataclasses.replace(s, model=model)


def screen_many(setup: Setup, state: ModelState, proposals: list[Proposal],
                projector: Callable[[Proposal], Projector | tuple[Projector, ...]],
                noise: Callable[[Projector], float], margin: float = 10.0) -> list[Screen]:
    """Every proposal's score test, the linearisable ones from one batched run of a model
    carrying all their patches at once.

    At their null values the patches are inert, so the joint model's base run is the current
    model's and the step of one candidate's parameter is that candidate's own sensitivity:
    one compile and one integration of 1 + (their free parameters) members replace one of
    each per candidate. ``projector`` may give alternative projections in order of
    preference (slow features, then the waveform): each is scored from the same runs, and the
    first whose promise pays ``margin`` (the BIC margin) is kept. A candidate whose step
    leaves the linear range is re-stepped alone in the joint model; when the joint model
    cannot be built or run, each is screened alone.
    """
    joint = [p for p in proposals if p.candidate.effect not in SENSOR_LAWS
             and (not p.candidate.grid or p.candidate.slope)]
    rest = [p for p in proposals if p not in joint or p.candidate.grid]
    # compiled ahead where a second core can, while this process compiles the joint model:
    # the grid-screened topologies, needed next (not the candidates' own: which of them the
    # refits need is known after the screen, and a guess would compete with this process)
    ahead.expect([p.candidate.apply(state.raw) for p in rest if p.candidate.grid],
                 replace=True)
    runs, model, members = _joint_runs(setup, state, joint) if len(joint) > 1 else (None,) * 3
    if runs is None:
        rest, joint = proposals, []
    out: list[Screen | None] = []
    accepted = _accepted_steps(state)
    for prop in rest:
        setup.log(f"screening {prop.candidate.key}")
        fns = _alternatives(projector(prop))
        if prop.candidate.effect in SENSOR_LAWS and runs is not None:
            base = {**state.params, **{k: v[0] for k, v in prop.candidate.free.items()}}
            out.append(_sensor(setup, state, prop, base, fns[0],
                               _columns(runs, members, accepted, fns[0])))
        else:
            out.append(screen(setup, state, prop, fns, noise(fns[0]), margin))
    for prop in joint:
        setup.log(f"screening {prop.candidate.key}")
        mine = {n: runs[members[n]] for n in sized(prop.candidate)}
        # one projection, or alternatives in order of preference, seen from the same runs
        views = [_from_runs(setup, prop, model, runs[0], mine, fn, noise(fn),
                            _null_params(state, joint), _columns(runs, members, accepted, fn))
                 for fn in _alternatives(projector(prop))]
        out.append(_preferred([v for v in views if v is not None], margin))
    return _better_of_two(out)


def _better_of_two(screens: list[Screen | None]) -> list[Screen]:
    """The screens that ran, one per proposal, in order: of a candidate screened both on
    its grid and by its slope (``Candidate.slope``), the one that explains the larger
    share."""
    best: dict[int, Screen] = {}
    for s in screens:
        if s is not None and (id(s.proposal) not in best or
                              s.share > best[id(s.proposal)].share):
            best[id(s.proposal)] = s  # a dict keeps the first place of a key
    return list(best.values())


def _preferred(views: list[Screen], margin: float) -> Screen | None:
    """The first view whose promise pays the margin; when none does, the most promising."""
    return next((v for v in views if promise(v) > margin),
                max(views, key=promise, default=None))


def _alternatives(project: Projector | tuple[Projector, ...]) -> tuple[Projector, ...]:
    return project if isinstance(project, tuple) else (project,)


def promise(s: Screen) -> float:
    """The BIC fall a screened gain promises (white noise, in its own space)."""
    dim = max(s.dim, 2)
    return -dim * math.log(max(1.0 - s.share, 1e-300)) - \
        len(s.proposal.candidate.free) * math.log(dim)


def sized(candidate) -> list[str]:
    """The free parameters the score test linearises: all but the shape's (a shape moves
    nothing while the size is at its null)."""
    return [n for n in candidate.free if n not in candidate.shape]


def _accepted_steps(state: ModelState) -> dict[str, float]:
    """The parameters a candidate's score test re-tunes beside it, with their screening
    steps: the effects' accepted so far, and the declared parameters the user frees (a step
    of ``DECLARED_STEP`` of their value). The refit frees them all; a screen that held the
    declared ones fixed credited a current sensor's 3.5 % gain with 0.40 of a residual that
    its refit, the load torque, the stiffness and an inertia free beside it, explained in
    full (fresh54's bf10: ranked seventh, never refitted, two wrong effects taken)."""
    steps = {n: c.candidate.steps.get(n, 1e-3) for c in state.chosen
             for n in c.candidate.free if n in state.free}
    for n in state.free:
        if n not in steps:
            v = abs(float(state.params[n]))
            steps[n] = DECLARED_STEP * v if v > 0.0 else DECLARED_STEP
    return steps


#: relative step of a declared free parameter's sensitivity in the score test (absolute
#: for a parameter declared 0)
DECLARED_STEP = 1e-3


def _columns(runs: list, members: Mapping[str, int], steps: Mapping[str, float],
             project: Projector) -> np.ndarray | None:
    """Sensitivities of the accepted effects' parameters (None when any run failed)."""
    cols = []
    for n, h in steps.items():
        y = runs[members[n]] if n in members else None
        if y is None:
            return None
        cols.append((project(y) - project(runs[0])) / h)
    return np.column_stack(cols) if cols else None


def _null_params(state: ModelState, proposals: list[Proposal]) -> dict[str, float]:
    return {**state.params, **{k: v[0] for p in proposals
                               for k, v in p.candidate.free.items()}}


def _joint_raw(state: ModelState, proposals: list[Proposal]):
    """The current netlist with every proposal's patch applied (at their null values)."""
    raw = state.raw
    for p in proposals:
        raw = p.candidate.apply(raw)
    return raw


def _joint_runs(setup: Setup, state: ModelState, proposals: list[Proposal]
                ) -> tuple[list | None, Any, dict[str, int]]:
    """The joint model's base run and one step of each free parameter, batched: (runs, model,
    index of each parameter's run), or Nones when it cannot be built or its base fails."""
    from circuitsim.errors import CircuitsimError

    try:
        model = compile_raw(_joint_raw(state, proposals))
    except (CircuitsimError, KeyError, ValueError):
        return None, None, {}
    base = _null_params(state, proposals)
    fast = _fast(setup, state, proposals)
    sets, members = [base], {}
    steps = {n: h for p in proposals if p not in fast for n in sized(p.candidate)
             for h in [p.candidate.steps.get(n, 1e-3)]}
    for n, h in {**steps, **_accepted_steps(state)}.items():
        members[n] = len(sets)
        sets.append({**base, n: base[n] + h})
    runs = simulate_many(setup, model, sets)
    if runs[0] is None:
        return None, None, {}
    if fast:
        runs += _fast_runs(setup, model, base, fast, runs[0], members, len(runs))
    return runs, model, members


#: A harmonic whose ripple at its shaft's top speed is faster than this share of the
#: sampling rate is stepped in a batch of its own: members share one step sequence, and a
#: ripple of order 482 (a spectral line read as an order) held all 63 members of a blower's
#: screen to its steps (9 s against 3 s a round).
FAST_RIPPLE = 0.1


def _fast(setup: Setup, state: ModelState, proposals: list[Proposal]) -> list[Proposal]:
    """The proposals whose ripple at top speed exceeds ``FAST_RIPPLE`` of the sampling rate
    (none when the record or the fitted run lacks what it takes to tell)."""
    from circuitsim.loop.effects import converters
    from circuitsim.netlist.load import build

    t = np.asarray(setup.record.t, float)
    if t.size < 2:
        return []
    rate = (t.size - 1) / float(t[-1] - t[0])
    shaft_of = dict(converters(build(state.raw)))
    out = []
    for p in proposals:
        order = p.candidate.fixed.get("order")
        if order is None:  # not a harmonic: no ripple of its own
            continue
        shaft = shaft_of.get(p.candidate.target, p.candidate.target)
        try:
            top = float(np.max(np.abs(np.asarray(state.fit.sim[f"{shaft}.w"], float))))
        except KeyError:
            continue
        if order * top / (2 * math.pi) > FAST_RIPPLE * rate:
            out.append(p)
    return out


def _fast_runs(setup: Setup, model, base: Mapping[str, float], fast: list[Proposal],
               point, members: dict[str, int], first: int) -> list:
    """The fast proposals' steps in a batch of their own with the base, each moved onto the
    main batch's base run ``point`` by its difference from this batch's (``batch.moved``): a
    sensitivity stays a difference on one step sequence. ``members`` gets their indices,
    from ``first`` on."""
    from circuitsim.solve.batch import moved

    names = [n for p in fast for n in sized(p.candidate)]
    runs = simulate_many(setup, model, [base, *({**base, n: base[n] + p.candidate.steps.get(
        n, 1e-3)} for p in fast for n in sized(p.candidate))])
    for j, n in enumerate(names):
        members[n] = first + j
    if runs[0] is None:  # each is then stepped alone where it is screened
        return [None] * len(names)
    return [None if r is None else moved(point, runs[0], r) for r in runs[1:]]


def _from_runs(setup: Setup, proposal: Proposal, model, y0, stepped: Mapping[str, Any],
               project: Projector, noise: float, base: Mapping[str, float],
               retune: np.ndarray | None = None) -> Screen | None:
    """The score test from a base run and one stepped run per free parameter. ``retune``:
    sensitivities of the effects accepted before, which may move with the candidate; its
    gain is then what it adds to them (their own projection is the model's optimum, ~0)."""
    cand = proposal.candidate
    e0 = project(setup.record) - project(y0)
    norm0 = float(e0 @ e0)
    if norm0 <= 0.0:
        return None
    cols = []
    for name, y in stepped.items():
        h = cand.steps.get(name, 1e-3)
        col = _first_column(y, y0, h, project, noise, e0)
        if col is None:  # out of the linear range or below the noise: adapt the step alone
            col = _sensitivity(setup, model, base, name, h, y0, project, noise, e0)
        if col is None:
            return None
        cols.append(col)
    S = np.column_stack(cols)
    k = S.shape[1]
    if retune is not None:
        S = np.column_stack([S, retune])
    coef = _bounded_lstsq(S, e0, [cand.free[n] for n in stepped], [base[n] for n in stepped])
    gain = norm0 - float(np.sum((e0 - S @ coef) ** 2))
    if retune is not None:
        alone, *_ = np.linalg.lstsq(retune, e0, rcond=None)
        gain -= float(e0 @ (retune @ alone))
    start = {n: _inside(cand.free[n], base[n] + float(c))
             for n, c in zip(stepped, coef[:k], strict=True)}
    start.update({n: cand.free[n][0] for n in cand.shape})
    return Screen(proposal, gain / norm0, start, None, e0.size)


def _bounded_lstsq(S: np.ndarray, e0: np.ndarray, specs: list[tuple[float, float, float]],
                   base: list[float]) -> np.ndarray:
    """The least-squares coefficients of ``S``'s columns on ``e0``, the first ``len(specs)``
    kept within their parameters' physical bounds (``specs``: (null, low, high) [SI], about
    ``base``); any further columns (the accepted effects' re-tuning) are free. A screen's
    gain is what the candidate can explain where it can be: a resistance whose slope points
    below zero explains nothing, however well its negative value would (fresh53's be05: a
    brush drop, a dry friction and two series resistances, each screened at 0.9 of the slow
    features by a negative size, were refitted in place of the round's best and found
    nothing)."""
    coef, *_ = np.linalg.lstsq(S, e0, rcond=None)
    lo = np.full(S.shape[1], -np.inf)
    hi = np.full(S.shape[1], np.inf)
    for j, ((_, a, b), x) in enumerate(zip(specs, base, strict=True)):
        lo[j], hi[j] = a - x, b - x
    if np.all((coef >= lo) & (coef <= hi)):
        return coef
    return lsq_linear(S, e0, bounds=(lo, hi), method="bvls").x


def _inside(spec: tuple[float, float, float], value: float) -> float:
    _, lo, hi = spec
    return min(max(value, lo), hi)


def _linear_limit(col: np.ndarray, e0: np.ndarray) -> float:
    """The largest change a step may make and still count as a slope: 0.3 noise units RMS,
    or the residual's own size when that is larger (the slope over the range the fit will
    move through is what the score test needs, a secant there included)."""
    return max(0.3 * math.sqrt(col.size), float(np.linalg.norm(e0)))


def _first_column(y, y0, h: float, project: Projector, noise: float, e0: np.ndarray
                  ) -> np.ndarray | None:
    """The batched first difference, when its size is in the linear range above the noise."""
    if y is None:
        return None
    col = (project(y) - project(y0)) / h
    size = float(np.linalg.norm(col * h))
    if max(1e-7 * math.sqrt(col.size), 10 * noise) <= size <= _linear_limit(col, e0):
        return col
    return None


def _sensitivity(setup: Setup, model, base: Mapping[str, float], name: str, h: float, y0,
                 project: Projector, noise: float, e0: np.ndarray) -> np.ndarray | None:
    """d(projection)/d(parameter) by a step sized to stay above the solver's noise and
    below the non-linear range."""
    size = 0.0
    for _ in range(3):
        y = simulate(setup, model, {**base, name: base[name] + h})
        if y is None:
            return None
        col = (project(y) - project(y0)) / h
        size = float(np.linalg.norm(col * h))
        if size == 0.0:
            return None  # acts on nothing measured (a resistor in series with no current)
        if size < max(1e-7 * math.sqrt(col.size), 10 * noise):
            h *= 100  # invisible above the solver's noise: a bigger step
        elif size > _linear_limit(col, e0):
            h /= 30  # far from linear: a smaller one
        else:
            return col
    return col if size >= 10 * noise else None


def _grid(setup: Setup, proposal: Proposal, model, base: Mapping[str, float],
          views: tuple[Projector, ...], undo: Mapping[str, float], margin: float
          ) -> Screen | None:
    """Effects invisible to a linearisation at null: a few values of the first parameter,
    scaled by the target's current where it has one; the others keep their start values.
    Each of ``views`` scores the same runs; the first whose promise pays ``margin`` is kept
    (a saturation acts in the current's transients, which slow features average away).
    ``undo``: the parameters of an accepted correction the candidate generalises, with their
    null values; at each value they move along the secant towards null by least squares."""
    cand = proposal.candidate
    first = next(iter(cand.free))
    y0 = simulate(setup, model, base)
    if y0 is None:
        return None
    key = f"{cand.target}.i"
    scale = max(float(np.max(np.abs(y0[key]))), 1e-9) if key in y0.names else 1.0
    trials = [{**base, first: _inside(cand.free[first], g * scale)} for g in cand.grid]
    # far-apart values: each member keeps its own error bound (not ``nearby``)
    runs = simulate_many(setup, model, [*trials, *({**t, **undo} for t in trials if undo)],
                         nearby=False)
    backs = runs[len(trials):] or [None] * len(trials)
    out = []
    for project in views:
        e0 = project(setup.record) - project(y0)
        norm0 = float(e0 @ e0)
        if norm0 <= 0.0:
            continue
        best: Screen | None = None
        for trial, y, back in zip(trials, runs[:len(trials)], backs, strict=True):
            if y is None:
                continue
            e = e0 - (project(y) - project(y0))
            trial, e = _moved_back(trial, e, undo, None if back is None else
                                   project(back) - project(y))
            share = (norm0 - float(e @ e)) / norm0
            if best is None or share > best.share:
                start = {n: trial[n] for n in cand.free} | {n: trial[n] for n in undo}
                best = Screen(proposal, share, start, model, e0.size)
        if best is not None:
            out.append(best)
    return _preferred(out, margin)


def _moved_back(trial: dict[str, float], e: np.ndarray, undo: Mapping[str, float],
                d: np.ndarray | None) -> tuple[dict[str, float], np.ndarray]:
    """The trial moved a fraction ``a`` of the way from its corrected values to ``undo``'s
    (``d``: the projected change all the way), ``a`` in [0, 2] fitting the residual ``e``
    best, and the residual left."""
    if d is None or not undo or float(d @ d) <= 1e-12 * max(float(e @ e), 1e-300):
        return trial, e
    a = min(max(float(e @ d) / float(d @ d), 0.0), 2.0)
    return ({**trial, **{n: trial[n] + a * (v - trial[n]) for n, v in undo.items()}},
            e - a * d)


def _undone(state: ModelState, cand) -> dict[str, float]:
    """The free parameters of the accepted corrections ``cand`` generalises (the same
    target's), with their null values."""
    return {n: spec[0] for c in state.chosen
            if c.correction and cand.generalises == c.candidate.effect
            and c.candidate.target == cand.target
            for n, spec in c.candidate.free.items() if n in state.params}


# a sensor law's sensitivity to its parameter at null, from the probe's own series x on
# the record's times t (a delay's is the series' slope, negated)
SENSOR_LAWS = {"sensor-gain": lambda x, t: x, "sensor-offset": lambda x, t: np.ones_like(x),
               "sensor-delay": lambda x, t: -np.gradient(x, t)}


def _sensor(setup: Setup, state: ModelState, proposal: Proposal, base,
            project: Projector, retune: np.ndarray | None = None) -> Screen | None:
    """Sensor effects act on one probe only, through a known law: their sensitivity needs
    no simulation. ``retune``: the sensitivities re-tuned beside it (``_from_runs``)."""
    cand = proposal.candidate
    sim = state.fit.sim
    y0 = {p: np.asarray(sim[p], float) for p in setup.probes}
    if cand.target not in y0:
        return None
    bumped = dict(y0)
    bumped[cand.target] = y0[cand.target] + SENSOR_LAWS[cand.effect](
        y0[cand.target], np.asarray(setup.record.t, float))
    col = project(bumped) - project(y0)
    e0 = project(setup.record) - project(y0)
    norm0 = float(e0 @ e0)
    den = float(col @ col)
    if norm0 <= 0.0 or den <= 0.0:
        return None
    (name,) = cand.free
    S = col[:, None] if retune is None else np.column_stack([col, retune])
    coef = _bounded_lstsq(S, e0, [cand.free[name]], [base[name]])
    gain = norm0 - float(np.sum((e0 - S @ coef) ** 2))
    if retune is not None:
        alone, *_ = np.linalg.lstsq(retune, e0, rcond=None)
        gain -= float(e0 @ (retune @ alone))
    start = {name: _inside(cand.free[name], base[name] + float(coef[0]))}
    return Screen(proposal, gain / norm0, start, None, e0.size)
