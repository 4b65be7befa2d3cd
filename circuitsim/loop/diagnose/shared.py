"""Independent refits of one diagnosis step on this machine's cores (``solve/fork.py``).

A round refits each screened candidate on its own, and a revision refits each combination of
effects on its own: none reads another's result. They are shared with forked copies of this
process, which compute the same numbers as this process would one after another. Each refit's
log lines are kept and said here in the refits' order once all have run; a fit comes back
without its compiled model (which does not pickle) and is given the model it ran on again.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from typing import Any

from circuitsim.loop.diagnose.context import Setup
from circuitsim.solve.fork import fork_map, in_copy


def refits(setup: Setup, work: Callable[[Setup, int], Any], models: Sequence[Any]
           ) -> list[Any]:
    """``work(setup, i)`` for each index i of ``models``: a fit (``fit_record``'s result) or
    None. ``models[i]``: the compiled model refit i runs on, compiled before (a copy
    compiles nothing: what it compiled would be lost to this process)."""
    def one(i: int) -> tuple[Any, list[str]]:
        lines: list[str] = []
        fit = work(dataclasses.replace(setup, say=lines.append), i)
        return (_bare(fit) if in_copy() else fit), lines

    out = []
    for (fit, lines), model in zip(fork_map(one, range(len(models))), models, strict=True):
        for line in lines:
            setup.log(line)
        out.append(_bound(fit, model))
    return out


def _bare(fit: Any) -> Any:
    """The fit with its run's model left out, to be pickled."""
    if fit is None or getattr(fit, "sim", None) is None:
        return fit
    return dataclasses.replace(fit, sim=dataclasses.replace(fit.sim, model=None))


def _bound(fit: Any, model: Any) -> Any:
    """The fit with its run's model given back."""
    if fit is None or getattr(fit, "sim", None) is None or fit.sim.model is not None:
        return fit
    return dataclasses.replace(fit, sim=dataclasses.replace(fit.sim, model=model))
