"""What the sources ask of the integrator: a largest step, and an output fine enough.

SPICE bounds its step by the sources (TMAX, breakpoints); so does circuitsim. A smooth
periodic source (a sine) bounds IDA's step to a fraction of its period: a circuit that is
quiet for most of a period (a reverse-biased diode) would otherwise let the step grow past
the next period and skip what happens there, and report success. Corners are breakpoints
(integrate.py). A source too fast to follow over the run is refused; one faster than the
output step is integrated correctly but warned about, since the samples alias it.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping

import numpy as np

from circuitsim.errors import CircuitWarning, ParameterError

#: More periods than this in one run cannot be followed step by step (each needs tens of
#: steps or four restarts); the user is told to average the source or shorten the run.
MAX_PERIODS = 5e6


def _sources(model, values: Mapping[str, float]):
    """(component, waveform kind, waveform, numeric fields) of every waveform with a hook."""
    from circuitsim.component import WAVEFORMS
    from circuitsim_components import waveforms  # noqa: F401 - registry

    for kind, fields in model.meta["breaks"]:
        p = {f: values[name] for f, name in fields}
        # parameter names are COMPONENT.SIGNAL.FIELD (a component in a subcircuit is X1.V1)
        owner = fields[0][1].rsplit(".", 2)[0] if fields else "?"
        yield owner, kind, WAVEFORMS[kind](), p


def bound_step(model, values: Mapping[str, float], stop: float, t_eval: np.ndarray,
               max_step: float) -> float:
    """The largest step [s] for IDA: ``max_step`` (0: none) tightened by every periodic
    source. Raises ParameterError for a source that repeats more than MAX_PERIODS times in
    [0, stop]; warns (CircuitWarning) when the output step under-samples a source."""
    out_step = float(np.max(np.diff(t_eval))) if t_eval.size > 1 else stop
    bound = max_step if max_step and max_step > 0 else 0.0
    for owner, kind, wave, p in _sources(model, values):
        period = wave.period(p)
        if not period > 0:
            continue
        if stop / period > MAX_PERIODS:
            loc = _loc(model, owner)
            raise ParameterError(
                f"the {kind} source repeats every {period:.3g} s: {stop / period:.3g} periods "
                f"in {stop:g} s, more than an integrator can follow ({MAX_PERIODS:.0e}); "
                f"shorten the run, lower the frequency, or replace the source by its average",
                loc, owner)
        if out_step > period / 2:
            warnings.warn(
                f"{owner}: the output step {out_step:.3g} s is longer than half the {kind} "
                f"source's period {period:.3g} s, so the output aliases it (the integration "
                f"itself follows the source); use step <= {period / 10:.3g} s to see it",
                CircuitWarning, stacklevel=4)
        limit = wave.max_step(p)
        if limit > 0:
            bound = limit if bound == 0.0 else min(bound, limit)
    return bound


def check_period(model, values: Mapping[str, float], period: float) -> None:
    """Refuse a shooting period [s] that is not a whole number of every periodic source's
    periods: the map over it is not the drive's, and Newton finds its fixed point all the
    same (an RC fed a 1 kHz sine, shot over 0.7 ms, gave a 'steady' mean of 1.30 V for 1 V).
    Raises ParameterError naming the source and the period that would fit."""
    for owner, kind, wave, p in _sources(model, values):
        own = wave.period(p)
        if not own > 0:
            continue
        ratio = period / own
        if ratio >= 0.5 and abs(ratio - round(ratio)) <= 1e-6 * ratio:
            continue
        raise ParameterError(
            f"the shooting period {period:.6g} s is not a whole number of the {kind} source's "
            f"period {own:.6g} s ({ratio:.6g} of them): give --period {own:.6g} (or a multiple "
            f"of it that every source shares)", _loc(model, owner), owner)


def _loc(model, owner: str):
    try:
        return model.netlist.component(owner).loc
    except KeyError:
        return None
