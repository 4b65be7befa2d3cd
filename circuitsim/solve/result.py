"""Simulation results: solve_ivp-like fields plus access by name to every probe and variable."""

from __future__ import annotations

import difflib
import os
from dataclasses import dataclass, field
from enum import Enum
from typing import Any

import numpy as np

from circuitsim import signal
from circuitsim.files import atomic_write


class Status(Enum):
    """Outcome of a run; the text says what to try next."""

    OK = (0, "reached the stop time")
    SOLVER_FAILED = (-1, "the integrator failed")
    INIT_FAILED = (-2, "no consistent initial values were found")
    NOT_FINITE = (-3, "a probe is not a finite number")

    @property
    def ok(self) -> bool:
        return self.value[0] == 0


@dataclass
class SimResult:
    """Transient result. ``y`` has shape (n_states, n_points) as in ``solve_ivp``.

    ``res[name]`` gives a probe, a state, or any eliminated variable (``R1.v``, ``a.v``,
    ``rotor.w``, ``M1.shaft.tau``); ``res.names`` lists them all.
    """

    t: np.ndarray
    y: np.ndarray
    yp: np.ndarray
    states: tuple[str, ...]
    status: Status
    detail: str
    nfev: int
    njev: int
    model: Any = field(repr=False)
    params: tuple[float, ...] = field(repr=False, default=())
    #: [s] the instants at which events switched something (ideal switches, held relations)
    t_events: np.ndarray = field(repr=False, default_factory=lambda: np.zeros(0))
    _obs: dict[str, np.ndarray] | None = field(default=None, repr=False)
    _index: dict[str, int] = field(default_factory=dict, repr=False)

    @property
    def success(self) -> bool:
        return self.status.ok

    @property
    def message(self) -> str:
        return f"{self.status.value[1]}: {self.detail}" if self.detail else self.status.value[1]

    @property
    def probes(self) -> tuple[str, ...]:
        return self.model.probe_names

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(dict.fromkeys((*self.model.meta["observed"], *self.states)))

    def _observed(self, name: str) -> np.ndarray | None:
        """One probe or exported quantity over the run, evaluated when first asked for
        (a large circuit exports tens of thousands; evaluating all would cost gigabytes)."""
        if self._obs is None:
            self._obs = {}
            self._index = {k: i for i, k in enumerate(self.model.meta["observed"])}
        if name not in self._obs:
            if name not in self._index:
                return None
            _, _, _, observe, _ = self.model.fns
            try:
                with np.errstate(all="ignore"):
                    (v,) = observe(self.t, self.y, self.yp, self.params,
                                   which=[self._index[name]])
            except (ArithmeticError, ValueError) as exc:
                from circuitsim.errors import NetlistError

                raise NetlistError(f"a probe or variable cannot be evaluated on this run "
                                   f"({type(exc).__name__}: {exc}); check the probe "
                                   f"expressions for division by zero",
                                   None) from None
            self._obs[name] = np.broadcast_to(np.asarray(v, float), (len(self.t),)).copy()
        return self._obs[name]

    def __contains__(self, name: object) -> bool:
        """Whether ``name`` is a probe, an observable or a state of this run (``in``
        otherwise falls back to item access by integer index)."""
        if not isinstance(name, str):
            return False
        try:
            self[name]
        except KeyError:
            return False
        return True

    def __getitem__(self, name: str) -> np.ndarray:
        got = self._observed(name)
        if got is not None:
            return got
        if name in self.states:
            return self.y[self.states.index(name)]
        close = difflib.get_close_matches(name, list(self.names), n=4, cutoff=0.5)
        hint = f"; did you mean {', '.join(close)}?" if close else ""
        raise KeyError(f"no probe or variable '{name}'{hint}")

    def window(self, fraction: float = 0.2) -> np.ndarray:
        """Mask of the last ``fraction`` of the run (the steady window)."""
        return self.t >= self.t[-1] - fraction * (self.t[-1] - self.t[0])

    def shaft_frequency(self, fraction: float = 0.2, shaft: str | None = None) -> float:
        """Mean rotation frequency [rev/s] of a shaft over the window."""
        shafts = self.model.shafts
        if shaft is None:
            if len(shafts) != 1:
                raise ValueError(f"say which shaft (one of {', '.join(shafts) or 'none'})")
            shaft = shafts[0]
        m = self.window(fraction)
        return float(np.mean(self[f"{shaft}.w"][m]) / (2 * np.pi))

    def harmonic(self, name: str, order: float | None = None, frequency: float | None = None,
                 window: float = 0.2, shaft: str | None = None) -> signal.Harmonic:
        """Frequency [Hz] and amplitude of one harmonic of a probe over the steady window.

        ``order`` counts per shaft revolution (the 8th order of a 2-pole 8-slot motor);
        ``frequency`` [Hz] is a guess refined by the fit; neither: the dominant ripple (a
        CircuitWarning when that line is a shaft-locked ripple the output grid folds down:
        ``solve/alias.py``).
        """
        m = self.window(window)
        if order is not None:  # a frequency whichever way the shaft turns
            frequency = order * abs(self.shaft_frequency(window, shaft))
        if frequency is None:
            h = signal.dominant_ripple(self.t[m], self[name][m])
            from circuitsim.solve.alias import Aliasing

            alias = Aliasing(self, window).of(h.frequency)
            if alias is not None:
                import warnings

                from circuitsim.errors import CircuitWarning

                warnings.warn(f"{name}: its dominant ripple on the output grid is "
                              f"{alias.words()}", CircuitWarning, stacklevel=2)
            return h
        return signal.harmonic(self.t[m], self[name][m], near=frequency)

    def to_dataframe(self, names: list[str] | None = None):
        """A pandas DataFrame indexed by time [s], one column per named series (default: the
        probes, else the states). Needs pandas (not a dependency of circuitsim)."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("to_dataframe needs pandas: pip install pandas") from None
        names = list(names or self.probes or self.states)
        frame = pd.DataFrame({n: self[n] for n in names},
                             index=pd.Index(self.t, name="time"))
        frame.attrs["units"] = {n: self.model.meta["units"].get(n, "") for n in names}
        return frame

    def to_csv(self, path: str | os.PathLike, names: list[str] | None = None,
               units: bool = True) -> None:
        """Write time and the named series (default: probes, else states), atomically; the
        header names each column's unit in brackets (``time [s]``, ``i [A]``; ``fit`` and
        ``diagnose`` read them back), or only the names with ``units=False``."""
        names = list(names or self.probes or self.states)
        data = np.column_stack([self.t] + [self[n] for n in names])
        header = self.csv_header(names, units)

        def write(tmp: str) -> None:
            with open(tmp, "w", encoding="utf-8") as fh:
                fh.write(",".join(header) + "\n")
                np.savetxt(fh, data, delimiter=",", fmt="%.12g")

        atomic_write(path, write, make_dirs=False)

    def csv_header(self, names: list[str], units: bool = True) -> list[str]:
        """The CSV header cells of time and ``names``: ``time [s]``, ``v_out [V]`` (a name
        without a known unit, or a dimensionless one, stays bare)."""
        if not units:
            return ["time", *names]
        known = self.model.meta["units"]
        return ["time [s]", *(f"{n} [{known[n]}]" if known.get(n) not in (None, "", "1")
                              else n for n in names)]
