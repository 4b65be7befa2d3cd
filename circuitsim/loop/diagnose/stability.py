"""Stage: are an accepted effect's parameters constants of the record?

A physical effect has the same parameters all through a record: a friction coefficient does
not change between the run-up and the reversal. A catalog effect that stands in for a cause
outside the catalog fits that cause only on average -- a warm-up of the winding taking the
place of an armature reaction, whose size follows the current, not the clock -- and its best
values then differ from one part of the record to the next.

The test is the held-out-segment check of system identification (a Chow test), linearised
about the final fit: the residual is regressed on the effect's sensitivities, once as they
are and once with their own copy in each of ``SEGMENTS`` equal pieces of the record, on
residuals prewhitened as the decisions are (``noise``). Two numbers come out: the BIC change
of the extra parameters, and the gain in units of each probe's whitened noise variance. The
effect is *unstable* when the gain is significant and at least ``STABLE_SHARE`` of what the
effect itself explains: its parameters then vary by as much as a fair part of the effect.
A small variation on a large effect (a real machine's cogging amplitude, a slightly
misshapen brush drop) is what any model of measured data shows and is no verdict.

The same holds across frequency: a physical effect's parameters are the same at every
frequency in the record. A catalog effect standing in for a dynamic cause outside it -- a
sensor delay for a sensor's first-order lag, a source resistance and two sensor delays for an
LC input filter -- fits that cause's frequency response at one frequency only, and fitted on
each part of the record's spectrum its values differ. The second split gives the sensitivities
their own copy in each of ``BANDS`` frequency bands (cosine-transform bands, each holding an
equal share of the effect's own sensitivity energy, so that every copy has as much to fit), and
is judged by the same rule.

And over the operating range: a physical effect's law holds at every current, speed and
angle the record visits. ``law`` lets the law bend there and judges the bend by the share of
what the final model leaves that it removes; its verdict travels with this one (``bent``).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from scipy import fft

from circuitsim.loop.diagnose.context import ModelState, Setup, compile_raw, simulate_many
from circuitsim.loop.diagnose.decide import BIC_MARGIN
from circuitsim.loop.diagnose.law import LawTest, bend_of, law_test
from circuitsim.loop.diagnose.regress import added_test

SEGMENTS = 4  # equal pieces of the record, each with its own copy of the parameters
BANDS = 4  # frequency bands, each with an equal share of the effect's sensitivity energy
#: Share of the effect's own gain that letting its parameters differ between the pieces must
#: reach, besides passing the BIC margin, for the effect to be a stand-in (see the module
#: docstring). Measured on the benchmark and the real logs: 0.1-1.4 % for effects of the
#: right law (the ODrive's and the PMSM's cogging orders included), 81 % for the warm-up
#: standing in for an armature reaction.
STABLE_SHARE = 0.25
MIN_SEGMENT = 20  # samples a piece needs for its own copy of the parameters to mean anything
RELATIVE_STEP = 1e-3  # forward-difference step of a parameter, relative to its value


@dataclass(frozen=True)
class Stability:
    """What letting an effect's parameters differ between pieces of the record gains."""

    delta_bic: float  # BIC change of the per-piece copies [-]
    gain: float  # their gain [units of the probes' whitened noise variance]
    own: float  # what the effect itself explains [same units]
    band_delta_bic: float = 0.0  # BIC change of the per-band copies [-]
    band_gain: float = 0.0  # their gain [same units as gain]
    law: LawTest | None = None  # bending its law over the operating range (``law``)

    @property
    def over_time(self) -> bool:
        """The parameters differ between the quarters of the record."""
        return self.delta_bic < -BIC_MARGIN and self.gain >= STABLE_SHARE * self.own

    @property
    def over_frequency(self) -> bool:
        """The parameters differ between the bands of the record's spectrum."""
        return (self.band_delta_bic < -BIC_MARGIN
                and self.band_gain >= STABLE_SHARE * self.own)

    @property
    def bent(self) -> bool:
        """Its law does not hold over the record's operating range (``law``)."""
        return self.law is not None and self.law.bent

    @property
    def unstable(self) -> bool:
        return self.over_time or self.over_frequency or self.bent

    def as_dict(self) -> dict[str, object]:
        return {"delta_bic": self.delta_bic, "gain": self.gain, "own_gain": self.own,
                "band_delta_bic": self.band_delta_bic, "band_gain": self.band_gain,
                **({"law": self.law.as_dict()} if self.law is not None else {})}

    def why(self) -> str:
        """The split(s) that found the parameters unstable, in words."""
        out = []
        if self.over_time:
            out.append(f"fitted on each quarter of the record on its own, it explains "
                       f"{self.gain / self.own:.0%} as much again as with one set of values, "
                       f"ΔBIC {self.delta_bic:.0f}")
        if self.over_frequency:
            out.append(f"fitted on each quarter of its frequency content on its own, it "
                       f"explains {self.band_gain / self.own:.0%} as much again, ΔBIC "
                       f"{self.band_delta_bic:.0f}")
        if self.bent:
            out.append(self.law.why())
        return "; ".join(out)


def split_test(residuals: Mapping[str, np.ndarray], columns: Sequence[Mapping[str, np.ndarray]],
               weights: Mapping[str, float], probes: Sequence[str],
               segments: int = SEGMENTS) -> tuple[float, float]:
    """(ΔBIC, gain [noise units]) of giving each sensitivity in ``columns`` (per probe, the
    change of the model's output per unit parameter [probe unit]) its own copy in each of
    ``segments`` equal pieces of the record, against the residual ``residuals`` (measured -
    model [probe unit]) regressed on the columns as they are. The prewhitening filter is
    learnt on the richer model's residual, as every decision's is (``noise``)."""
    n = len(np.asarray(residuals[probes[0]]))
    piece = np.minimum(np.arange(n) * segments // n, segments - 1)
    split = [{p: np.where(piece == s, c[p], 0.0) for p in probes}
             for c in columns for s in range(1, segments)]
    return added_test(residuals, columns, split, weights, probes)


def band_test(residuals: Mapping[str, np.ndarray], columns: Sequence[Mapping[str, np.ndarray]],
              weights: Mapping[str, float], probes: Sequence[str], bands: int = BANDS
              ) -> tuple[float, float]:
    """(ΔBIC, gain [noise units]) of giving each sensitivity its own copy in each of
    ``bands`` frequency bands, as ``split_test`` does with pieces of the record. The bands
    are of the cosine transform (no leakage from a record's unequal ends), cut where the
    columns' energy over the probes' noise reaches each equal share; a bin holding more than
    a share leaves fewer, wider bands."""
    n = len(np.asarray(residuals[probes[0]]))
    spectra = [{p: fft.dct(np.asarray(c[p], float), norm="ortho") for p in probes}
               for c in columns]
    energy = sum(np.square(s[p] / weights[p]) for s in spectra for p in probes)
    share = np.cumsum(energy) / max(float(np.sum(energy)), 1e-300)
    band = np.minimum((share * bands).astype(int), bands - 1)
    # a band is the bins whose cumulative share falls in it: the first bin past a cut opens
    # the next band, so that each holds its share and none is empty
    band = np.concatenate([[0], band[:-1]]) if n > 1 else band
    used = [b for b in range(1, bands) if np.any(band == b)]
    split = [{p: fft.idct(np.where(band == b, s[p], 0.0), norm="ortho") for p in probes}
             for s in spectra for b in used]
    return added_test(residuals, columns, split, weights, probes)


def steps_of(state: ModelState, candidate) -> list[tuple[str, float]]:
    """(parameter, forward-difference step) for each free parameter of ``candidate``."""
    out = []
    for name in candidate.free:
        v = float(state.params[name])
        # a value of 0 has no scale of its own: a tenth of the screen's linear step
        h = max(RELATIVE_STEP * abs(v), 0.1 * candidate.steps.get(name, 0.0)) or RELATIVE_STEP
        out.append((name, h if v + h <= state.bounds.get(name, (-np.inf, np.inf))[1] else -h))
    return out


def sensitivities(setup: Setup, state: ModelState, candidate
                  ) -> list[dict[str, np.ndarray]] | None:
    """Forward differences of the probes in each free parameter of ``candidate`` about the
    fitted values, from one batched run (None when a run fails)."""
    model = state.model or compile_raw(state.raw)
    pairs = steps_of(state, candidate)
    steps = [h for _, h in pairs]
    points = [dict(state.params)] + [{**state.params, n: state.params[n] + h}
                                     for n, h in pairs]
    runs = simulate_many(setup, model, points)
    if any(run is None for run in runs):
        return None
    base, *moved = runs
    return [{p: (np.asarray(run[p], float) - np.asarray(base[p], float)) / h
             for p in setup.probes} for run, h in zip(moved, steps, strict=True)]


def stability(setup: Setup, state: ModelState, candidate, own: float) -> Stability | None:
    """The stability of ``candidate``'s parameters in the fitted ``state`` (None when the
    record is too short to split or a run fails); ``own``: what the effect explains [noise
    units]."""
    if setup.n < SEGMENTS * MIN_SEGMENT or not candidate.free:
        return None
    # a circuit's law is bent in a run that gives the effect's own columns too
    bend = bend_of(setup, state, candidate, steps_of(state, candidate))
    columns = bend.own if bend is not None and bend.own is not None else \
        sensitivities(setup, state, candidate)
    if columns is None:
        return None
    args = (state.fit.residuals, columns, setup.weights, setup.probes)
    verdict = law_test(setup, state, columns, bend) if bend is not None else None
    return Stability(*split_test(*args), own, *band_test(*args), verdict)
