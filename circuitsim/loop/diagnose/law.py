"""Stage: does an accepted effect's *law* hold over the record's operating range?

A catalog effect is a law: a friction torque proportional to the speed, a contact voltage
that is the same at every current, a sensor that delays its reading without changing its
gain. A cause outside the catalog that a catalog law nearly fits -- an iron loss growing as
speed^1.5 taken for viscous friction, a brush contact growing as a logarithm of the current
taken for a resistance and a drop, a tachometer's lag taken for a delay -- leaves, once the
law is fitted, a residual that is the *difference between the two laws*: small beside the
effect (the two curves are close over the record's range), but systematic, and most of what
the record still holds.

The test lets the law bend: the effect's own contribution is multiplied by (1 + a1 psi1(u) +
a2 psi2(u)), the psi low-order shapes of the quantities the law reads or might read (|i|,
i^2, |w|, w^2, the angle about its mean, the time), each a new parameter with null 0, so
that the patched circuit is the accepted one exactly at a = 0. Their sensitivities come from
one batched run of that circuit (inside the dynamics: a torque that depends on the speed
feeds back through the speed). A sensor's law is tested on its reading alone: a gain's
reading bending with its size, an offset drifting, a delay's reading differing from a
first-order lag's or a second-order stage's by the reading's second and third derivatives.

As in ``stability``, the BIC change of the extra parameters and their gain in units of each
probe's whitened noise variance come out, and beside them the share of what the final model
leaves (its noise-weighted sum of squares) that the bend removes. The law is *bent* when the
gain is significant and takes a fair share of what is left: the residual is then mostly the
law's own error, the signature of a stand-in. A right law on a record that holds more (a real
machine's unnamed structure) bends by a small share of what is left, if at all.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from circuitsim.errors import CircuitsimError, SourceLoc
from circuitsim.loop.diagnose.context import (
    ModelState,
    Setup,
    compile_raw,
    simulate,
    simulate_many,
)
from circuitsim.loop.diagnose.decide import BIC_MARGIN, STRUCTURE_SHARE
from circuitsim.loop.diagnose.regress import added_with_energy
from circuitsim.loop.diagnose.residual import below_resolution

#: relative bend of the effect's contribution for the finite differences: small enough to
#: stay linear, large enough to stand clear of the integrator's error
BEND_STEP = 1e-2
#: Share of what the final model leaves (its noise-weighted sum of squares, noise included)
#: that the bend must remove, besides passing the BIC margin, for the law to be wrong: the
#: share a candidate must explain of the structure to be accepted (``decide``), so that a
#: law error is a finding by the same standard as an effect. No noise level enters. Measured
#: (2026-11-27, before the rule): 0.41-0.96 for the catalog laws standing in for an iron loss,
#: a logarithmic brush contact, a cable reel's pull and a resolver's tracking loop; at most
#: 0.19 on the real logs (EMPS's force offset; its Coulomb friction 0.013, the ODrive's
#: cogging orders 0.05); 0.000-0.003 for every right law on the synthetic records, once a
#: brush drop's transition width is fitted (``effects.brush-transition``: with it fixed at
#: 1 mA against a simulator's 5 mA, t03's viscous friction bent to take 0.36 of that misfit).
LAW_SHARE = STRUCTURE_SHARE
LAW_PREFIX = "law_bend"


@dataclass(frozen=True)
class LawTest:
    """What bending an effect's law gains, and what the final model leaves."""

    delta_bic: float  # BIC change of the bend's parameters [-]
    gain: float  # their gain [units of the probes' whitened noise variance]
    terms: tuple[str, ...]  # the shapes tried, in words
    removed: float = 0.0  # share of the final residual's sum of squares the bend removes
    bends: tuple[float, ...] = ()  # the bend's coefficients, as relative changes [-]
    imprint: float = 0.0  # what the effect changes in the probes [units of gain]
    level: tuple[float, ...] = ()  # per probe, the residual's mean square over its noise
    relative: bool = True  # the bends are relative changes of the effect (not derivatives)

    @property
    def bent(self) -> bool:
        """The law does not hold: its bend is significant and takes a fair share of what
        the final model leaves."""
        return self.delta_bic < -BIC_MARGIN and self.removed >= LAW_SHARE

    def why(self) -> str:
        """The bend, in words: each shape with the relative change of the effect where
        that shape is largest, a cosine and sine of an angle as one ripple once per turn
        (a sensor's derivatives are named only); shapes that bend it by under 5 % are left
        out when others do more."""
        return (f"its law does not hold over the record: bent by {self._shapes()}, it "
                f"explains {self.removed:.0%} of what the model leaves (ΔBIC "
                f"{self.delta_bic:.0f})")

    def _shapes(self) -> str:
        if not self.relative:
            return " and ".join(self.terms)
        parts: list[tuple[float, str]] = []
        turns: dict[str, float] = {}
        for t, b in zip(self.terms, self.bends, strict=False):
            if t.startswith(("cos(", "sin(")):
                turns[t[4:-1]] = float(np.hypot(turns.get(t[4:-1], 0.0), b))
            else:
                parts.append((abs(b), f"{t} ({b:+.0%} where it is largest)"))
        parts += [(a, f"a ripple once per turn of {u} ({a:.0%})") for u, a in turns.items()]
        big = [p for p in parts if p[0] >= 0.05] or parts
        return " and ".join(text for _, text in big)

    def as_dict(self) -> dict[str, object]:
        return {"delta_bic": self.delta_bic, "gain": self.gain, "terms": list(self.terms), "removed": self.removed, "bends": list(self.bends),
                "imprint": self.imprint, "level": list(self.level)}


def _scale_of(kind: str, u: np.ndarray) -> tuple[float, float]:
    """(centre, scale) of a driver's shape over the record [its unit]."""
    u = np.asarray(u, float)
    if kind == "centred":
        lo, hi = float(np.min(u)), float(np.max(u))
        return 0.5 * (lo + hi), max(0.5 * (hi - lo), 1e-300)
    return 0.0, max(float(np.max(np.abs(u))), 1e-300)


def _shape(kind: str, u: str, c: str, s: str) -> str:
    if kind == "abs":
        return f"abs({u})/{s}"
    if kind == "square":
        return f"({u}/{s})^2"
    if kind in ("cos", "sin"):  # of an angle, once per turn: no scale
        return f"{kind}({u})"
    return f"({u} - {c})/{s}"


def _values(sim, expr: str, t: np.ndarray) -> np.ndarray | None:
    """A driver's values in a simulation (``t`` is time itself)."""
    if expr == "t":
        return np.asarray(t, float)
    try:
        return np.asarray(sim[expr], float)
    except (KeyError, ValueError):
        return None


def _names(law) -> list[tuple[str, str, str]]:
    """(bend, centre, scale) parameter names of each of the law's shapes."""
    return [tuple(f"{LAW_PREFIX}_{x}{j}" for x in "acs") for j in range(len(law.terms))]


def bent_raw(raw, law, names: Sequence[tuple[str, str, str]] | None = None):
    """``raw`` with the law's bend patched in: the effect's contribution ``law.value`` times
    the shapes, each times its new parameter (null 0), applied where the effect acts (None
    for a sensor's law, bent on its reading alone)."""
    from circuitsim.loop.effects import _add, _insert_series

    if law.place[0] == "probe":
        return None
    names = names or _names(law)
    out = raw.copy()
    loc = SourceLoc(raw.path or "<patch>")
    parts = []
    for (a, c, s), (u, kind) in zip(names, law.terms, strict=True):
        for name, v in ((a, "0.0"), (c, "0.0"), (s, "1.0")):  # set at run time
            out.params[name] = (v, loc)
        parts.append(f"{a}*{_shape(kind, u, c, s)}")
    expr = f"({law.value})*({' + '.join(parts)})"
    where, target = law.place
    name = f"LB_{target.replace('.', '_')}"
    if where == "series":
        _insert_series(out, target, name, expr)
    elif where == "torque":
        _add(out, {"name": name, "type": "btorque", "shaft": target, "expr": expr})
    else:
        _add(out, {"name": name, "type": "bforce", "flange": target, "expr": expr})
    return out


def _bend_columns(setup: Setup, state: ModelState, candidate, own_steps
                  ) -> tuple[list[dict], list[dict], list[str]] | None:
    """(the effect's own sensitivities, the bend's, the shapes in words) from one batched
    run of the bent circuit; None when a driver is not in the simulation or a run fails."""
    law = candidate.law
    sim, t = state.fit.sim, setup.record.t
    names, scales = _names(law), {}
    for (_, c, s), (u, kind) in zip(names, law.terms, strict=True):
        values = _values(sim, u, t)
        if values is None:
            return None
        scales[c], scales[s] = _scale_of(kind, values)
    raw = bent_raw(state.raw, law, names)
    try:
        model = compile_raw(raw)
    except CircuitsimError as exc:
        setup.log(f"  law test of {candidate.key}: the bent circuit does not compile ({exc})")
        return None
    base = {**state.params, **scales, **{a: 0.0 for a, _, _ in names}}
    points = [base] + [{**base, n: base[n] + h} for n, h in own_steps] + \
        [{**base, a: BEND_STEP} for a, _, _ in names]
    runs = simulate_many(setup, model, points)
    if any(r is None for r in runs):
        return None
    b, *moved = runs
    steps = [h for _, h in own_steps] + [BEND_STEP] * len(names)
    cols = [{p: (np.asarray(r[p], float) - np.asarray(b[p], float)) / h for p in setup.probes}
            for r, h in zip(moved, steps, strict=True)]
    words = [{"abs": f"|{u}|", "square": f"{u}^2", "cos": f"cos({u})", "sin": f"sin({u})"
              }.get(kind, f"{u} about its mean") for u, kind in law.terms]
    return cols[:len(own_steps)], cols[len(own_steps):], words


def _probe_columns(setup: Setup, state: ModelState, candidate
                   ) -> tuple[list[dict], list[str]] | None:
    """The shapes a sensor's reading may have beyond its law, on the fitted reading itself
    (a sensor feeds nothing back): a gain bending with the reading's size, an offset drifting
    with time, a delayed reading's second and third derivatives (a lag or a second-order
    stage differ from a delay there)."""
    probe = candidate.law.place[1]
    if probe not in setup.probes:
        return None
    y = np.asarray(state.fit.sim[probe], float)
    t = np.asarray(setup.record.t, float)
    zero = np.zeros_like(y)
    size = max(float(np.max(np.abs(y))), 1e-300)
    kind = candidate.law.value
    if kind == "gain":
        shapes = {"the reading's |size|": y * np.abs(y) / size, "its cube": y ** 3 / size ** 2}
    elif kind == "offset":
        shapes = {"time": (t - t.mean()) / max(np.ptp(t), 1e-300),
                  "the reading's |size|": np.abs(y) / size}
    else:
        d2 = np.gradient(np.gradient(y, t), t)
        shapes = {"the reading's 2nd derivative": d2,
                  "its 3rd derivative": np.gradient(d2, t)}
    cols = [{p: (v if p == probe else zero) for p in setup.probes} for v in shapes.values()]
    return cols, list(shapes)


def law_test(setup: Setup, state: ModelState, candidate, own_columns: list[dict] | None,
             own_steps: Sequence[tuple[str, float]]) -> LawTest | None:
    """Bend ``candidate``'s law in the fitted ``state`` (see the module docstring); None
    when it has no law to bend or a run fails. ``own_columns``: its own sensitivities (for a
    sensor, whose bend needs no run), ``own_steps``: (parameter, step) to compute them with
    the bent circuit otherwise."""
    law = getattr(candidate, "law", None)
    if law is None or all(below_resolution(state.fit.residuals[p], setup.record[p])
                          for p in setup.probes):
        return None  # nothing left for a law to bend against (a noise-free record)
    if law.place[0] == "probe":
        got = _probe_columns(setup, state, candidate)
        if got is None or own_columns is None:
            return None
        bend, words = got
        own = own_columns
    else:
        got3 = _bend_columns(setup, state, candidate, own_steps)
        if got3 is None:
            return None
        own, bend, words = got3
    imprint = _imprint(setup, state, candidate)
    if imprint is None:
        return None
    dbic, gain, energy = added_with_energy(state.fit.residuals, own, bend, setup.weights,
                                           setup.probes, imprint)
    removed, bends = _removed(setup, state.fit.residuals, own, bend)
    level = tuple(float(np.mean(np.square(np.asarray(state.fit.residuals[p], float)
                                          / setup.weights[p]))) for p in setup.probes)
    return LawTest(dbic, gain, tuple(words), removed, bends, energy, level,
                   law.value != "delay")


def _imprint(setup: Setup, state: ModelState, candidate) -> dict[str, np.ndarray] | None:
    """What the effect changes in each probe [probe unit]: the fitted model less the same
    model with the effect's size at its null (its shape parameters, inert there, kept)."""
    null = {n: start for n, (start, _, _) in candidate.free.items() if n not in candidate.shape}
    sim = simulate(setup, state.model or compile_raw(state.raw), {**state.params, **null})
    if sim is None:
        return None
    return {p: np.asarray(state.fit.sim[p], float) - np.asarray(sim[p], float)
            for p in setup.probes}


def _removed(setup: Setup, residuals, own: list[dict], bend: list[dict]
             ) -> tuple[float, tuple[float, ...]]:
    """(share of the residual's noise-weighted sum of squares, after the effect's own
    columns, that the bend's columns remove; their coefficients). No noise level enters:
    a residual that is mostly noise gives a share near zero whatever its level."""
    probes, w = setup.probes, setup.weights
    r = np.concatenate([np.asarray(residuals[p], float) / w[p] for p in probes])

    def design(cols):
        return np.column_stack([np.concatenate([np.asarray(c[p], float) / w[p]
                                                for p in probes]) for c in cols])

    def sse(x):
        beta, *_ = np.linalg.lstsq(x, r, rcond=None)
        e = r - x @ beta
        return float(e @ e), beta

    before, _ = sse(design(own))
    after, beta = sse(design([*own, *bend]))
    share = (before - after) / before if before > 0 else 0.0
    return share, tuple(float(b) for b in beta[len(own):])
