"""Whether a ripple read from the output grid is an alias of a shaft-locked one.

A run's outputs are samples at the analysis step; the solver itself follows every ripple, but
a ripple locked to a shaft's angle at order k has the frequency k w / 2 pi, which a fast shaft
(or a high order) puts above the output grid's Nyquist frequency. Its samples then show it at
|k w / 2 pi - m fs|, a line that is not in the circuit: the Kim & Kim motor at 200 V turns at
10 809 rad/s, its 8th-order ripple is at 13.76 kHz, and a 50 us grid shows it at 6.24 kHz.

The orders a shaft's angle carries are read from the compiled model itself: the residual at
the run's final state, the angle set to ``SAMPLES`` points of a turn, other states held; the
orders of its Fourier series are the angle's laws (an EMF harmonic, a cogging, a behavioural
law of the angle), whatever component wrote them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: angles per turn the residual is sampled at: orders up to SAMPLES/2 - 1 are read exactly
SAMPLES = 256
#: an order counts when its line in the residual is this fraction of the angle's largest
ORDER_FLOOR = 1e-9


@dataclass(frozen=True)
class Alias:
    """A line on the output grid that is a shaft-locked ripple folded down: the ripple of
    ``order`` on ``shaft`` at ``true`` [Hz] shows at ``seen`` [Hz] on a grid whose Nyquist
    frequency is ``nyquist`` [Hz]."""

    shaft: str
    order: int
    true: float
    seen: float
    nyquist: float

    def words(self) -> str:
        step = 0.5 / self.true
        return (f"an alias: the order-{self.order} ripple of {self.shaft} at {self.true:.6g} Hz "
                f"lies above the output grid's Nyquist frequency ({self.nyquist:.6g} Hz), and "
                f"its samples show it at {self.seen:.6g} Hz; an output step below "
                f"{step:.3g} s (run --step, or the netlist's analysis: step) resolves it")


def angle_orders(model, y: np.ndarray, yp: np.ndarray, p: tuple, t: float = 0.0
                 ) -> dict[str, list[int]]:
    """The orders of each shaft angle's laws at the state ``y``, ``yp`` (shaft angle name ->
    orders, each in [1, SAMPLES/2)), read from the residual's Fourier series over a turn."""
    integrals = model.meta.get("integrals", {})
    names = list(model.state_names)
    residual = model.fns[0]
    out: dict[str, list[int]] = {}
    for name, domain in integrals.items():
        if domain != "rotational" or name not in names:
            continue
        a = names.index(name)
        rows = np.empty((SAMPLES, len(names)))
        ys = np.array(y, dtype=float)
        try:
            with np.errstate(all="ignore"):
                for j in range(SAMPLES):
                    ys[a] = 2 * np.pi * j / SAMPLES
                    residual(t, ys, yp, rows[j], p)
        except (ArithmeticError, ValueError):  # a law undefined at some angle: no reading
            continue
        if not np.all(np.isfinite(rows)):  # a law that overflows somewhere: no reading
            continue
        lines = np.abs(np.fft.rfft(rows, axis=0))[1: SAMPLES // 2]
        size = lines.max(axis=1)
        if size.size and size.max() > 0:
            out[name] = [int(k) + 1 for k in np.flatnonzero(size > ORDER_FLOOR * size.max())]
    return out


class Aliasing:
    """The shaft-locked ripples of ``res``'s output over its last ``window`` (a fraction)
    that its grid folds down: ``of(frequency)`` says which one a line is, if any."""

    def __init__(self, res, window: float):
        self.res, self.mask = res, res.window(window)
        t = res.t[self.mask]
        self.span = float(t[-1] - t[0]) if t.size >= 3 else 0.0
        self.fs = (t.size - 1) / self.span if self.span > 0 else 0.0
        self._orders: dict[str, list[int]] | None = None

    def orders(self) -> dict[str, list[int]]:
        if self._orders is None:
            r = self.res
            self._orders = angle_orders(r.model, r.y[:, -1], r.yp[:, -1], r.params,
                                        float(r.t[-1]))
        return self._orders

    def of(self, frequency: float) -> Alias | None:
        """The ripple the line at ``frequency`` [Hz] is an alias of; None when none."""
        if not (frequency > 0 and self.fs > 0):
            return None
        tolerance = 2.0 / self.span + 1e-6 * frequency
        for angle, ks in self.orders().items():
            f1 = abs(float(np.mean(self.res.yp[self.res.states.index(angle), self.mask])))
            for k in ks:
                true = k * f1 / (2 * np.pi)
                seen = abs(true - round(true / self.fs) * self.fs)
                if true > 0.5 * self.fs and abs(seen - frequency) <= tolerance:
                    return Alias(angle.rsplit(".", 1)[0], k, true, seen, 0.5 * self.fs)
        return None
