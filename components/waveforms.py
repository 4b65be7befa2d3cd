"""Source waveforms: small functions of time with numeric parameters.

A source element takes one of these as its Signal parameter (as Modelica separates a
VoltageSource from its signal block). ``@`` as a unit means "the unit of the signal".
"""

from __future__ import annotations

import math
from typing import ClassVar

from circuitsim.component import Lookup, Param, Pmod, Waveform, register_waveform, sp


def _ramp(u):
    """0 below 0, u in [0, 1), 1 above: a clamped linear ramp."""
    return sp.Piecewise((0, u < 0), (u, u < 1), (1, True))


@register_waveform("dc")
class Dc(Waveform):
    """Constant: value."""

    params: ClassVar[dict[str, Param]] = {"value": Param("@", "value")}
    scalar_key = "value"

    def expr(self, t, p, data=None):
        return p["value"]


@register_waveform("step")
class Step(Waveform):
    """v0 before t0, ramping linearly to v1 over ``rise``."""

    params: ClassVar[dict[str, Param]] = {"v0": Param("@", "initial value", default=0.0), "v1": Param("@", "final value"),
              "t0": Param("s", "step time", default=0.0, nonnegative=True),
              "rise": Param("s", "rise time", default=1e-9, positive=True)}

    def expr(self, t, p, data=None):
        return p["v0"] + (p["v1"] - p["v0"]) * _ramp((t - p["t0"]) / p["rise"])

    def breakpoints(self, p, t_stop):
        return [p["t0"], p["t0"] + p["rise"]]


#: Steps per period of a smooth periodic source that bound IDA's largest step. A diode fed by a
#: sine stops conducting for most of each period; with nothing changing in the circuit IDA grows
#: its step past the period and skips whole conduction windows (v_C(10 s) 6.65 V instead of
#: 8.263 V in netlists/breadth/diode_charge.yaml). Period/2 still fails there, period/4 is right
#: in some runs and 0.2 V off in others (benchmarks/bench_step_bound.py); period/20 is right
#: with a margin, at 20 steps per period (1.2x the time on a smooth RC).
STEPS_PER_PERIOD = 20


@register_waveform("sine")
class Sine(Waveform):
    """SPICE SIN: offset + amplitude * exp(-damping (t - delay)) * sin(2 pi freq (t - delay)
    + phase) after ``delay``, offset + amplitude * sin(phase) before it. (SPICE writes the
    phase in degrees: give it as ``30 deg``.)"""

    params: ClassVar[dict[str, Param]] = {
        "offset": Param("@", "offset", default=0.0), "amplitude": Param("@", "amplitude"),
        "freq": Param("Hz", "frequency", positive=True),
        "phase": Param("rad", "phase at t = delay", default=0.0),
        "delay": Param("s", "delay before the sine starts", default=0.0, nonnegative=True),
        "damping": Param("1/s", "exponential damping factor (SPICE THETA)", default=0.0)}

    def expr(self, t, p, data=None):
        u = t - p["delay"]
        wave = sp.exp(-p["damping"] * u) * sp.sin(2 * sp.pi * p["freq"] * u + p["phase"])
        before = sp.sin(p["phase"])
        return p["offset"] + p["amplitude"] * sp.Piecewise((before, u < 0), (wave, True))

    def breakpoints(self, p, t_stop):
        return [p["delay"]] if p["delay"] > 0 else []

    def period(self, p):
        return 1.0 / p["freq"]

    def max_step(self, p):
        return 1.0 / (STEPS_PER_PERIOD * p["freq"])


@register_waveform("exp")
class Exp(Waveform):
    """SPICE EXP: v1 until ``delay1``, then rising towards v2 with time constant ``tau1``;
    from ``delay2`` on falling back towards v1 with ``tau2``."""

    params: ClassVar[dict[str, Param]] = {
        "v1": Param("@", "initial value", default=0.0), "v2": Param("@", "pulsed value"),
        "delay1": Param("s", "rise delay", default=0.0, nonnegative=True),
        "tau1": Param("s", "rise time constant", positive=True),
        "delay2": Param("s", "fall delay", positive=True),
        "tau2": Param("s", "fall time constant", positive=True)}

    def expr(self, t, p, data=None):
        dv = p["v2"] - p["v1"]
        rise = dv * (1 - sp.exp(-(t - p["delay1"]) / p["tau1"]))
        fall = -dv * (1 - sp.exp(-(t - p["delay2"]) / p["tau2"]))
        return p["v1"] + sp.Piecewise((0, t < p["delay1"]), (rise, t < p["delay2"]),
                                      (rise + fall, True))

    def breakpoints(self, p, t_stop):
        return [p["delay1"], p["delay2"]]


@register_waveform("pulse")
class Pulse(Waveform):
    """SPICE PULSE: v1, then after ``delay`` a trapezoid to v2 repeating every ``period``."""

    params: ClassVar[dict[str, Param]] = {"v1": Param("@", "low value", default=0.0), "v2": Param("@", "high value"),
              "delay": Param("s", "delay", default=0.0, nonnegative=True),
              "rise": Param("s", "rise time", default=1e-9, positive=True),
              "fall": Param("s", "fall time", default=1e-9, positive=True),
              "width": Param("s", "pulse width", positive=True),
              "period": Param("s", "period", positive=True)}

    def expr(self, t, p, data=None):
        tau = Pmod(t - p["delay"], p["period"])
        r, w, f = p["rise"], p["width"], p["fall"]
        shape = sp.Piecewise((tau / r, tau < r), (1, tau < r + w), (1 - (tau - r - w) / f,
                             tau < r + w + f), (0, True))
        return p["v1"] + (p["v2"] - p["v1"]) * sp.Piecewise((0, t < p["delay"]), (shape, True))

    def breakpoints(self, p, t_stop):
        out, k = [], 0
        while True:
            start = p["delay"] + k * p["period"]
            if start > t_stop:
                return out
            out += [start, start + p["rise"], start + p["rise"] + p["width"],
                    start + p["rise"] + p["width"] + p["fall"]]
            k += 1

    def period(self, p):
        return p["period"]


@register_waveform("pwm")
class Pwm(Pulse):
    """Pulse-width modulation: low/high at ``freq`` with ``duty`` in [0, 1]."""

    params: ClassVar[dict[str, Param]] = {"low": Param("@", "low value", default=0.0), "high": Param("@", "high value"),
              "freq": Param("Hz", "switching frequency", positive=True),
              "duty": Param("1", "duty cycle", nonnegative=True),
              "rise": Param("s", "edge time", default=1e-7, positive=True)}

    @staticmethod
    def _as_pulse(p):
        period = 1 / p["freq"]
        return {"v1": p["low"], "v2": p["high"], "delay": 0 * period, "rise": p["rise"],
                "fall": p["rise"], "width": p["duty"] * period, "period": period}

    def expr(self, t, p, data=None):
        return super().expr(t, self._as_pulse(p))

    def breakpoints(self, p, t_stop):
        return super().breakpoints(self._as_pulse(p), t_stop)

    def period(self, p):
        return 1.0 / p["freq"]


@register_waveform("table")
class Table(Waveform):
    """A column of a CSV file, linearly interpolated in time (held at the ends).

    Netlist: ``{table: {file: data.csv, column: v_in, time: time, scale: 1}}``.
    """

    params: ClassVar[dict[str, Param]] = {"scale": Param("1", "factor applied to the column", default=1.0)}

    def expr(self, t, p, data=None):
        return p["scale"] * Lookup(sp.Integer(data.index), t)


@register_waveform("pwl")
class Pwl(Waveform):
    """Piecewise linear through [t_k, v_k] points, held constant outside them.

    Netlist: ``{pwl: [[0, 0], [1 ms, 12 V]]}``, or from two columns of a CSV file:
    ``{pwl: {file: points.csv, column: v, time: time}}`` (every point is a breakpoint; for
    long measured records use ``table``).
    """

    params: ClassVar[dict[str, Param]] = {}

    def expr(self, t, p, data=None):
        n = len(p) // 2
        ts = [p[f"t{k}"] for k in range(n)]
        vs = [p[f"v{k}"] for k in range(n)]
        pieces = [(vs[0], t < ts[0])]
        for k in range(n - 1):
            slope = (vs[k + 1] - vs[k]) / (ts[k + 1] - ts[k])
            pieces.append((vs[k] + slope * (t - ts[k]), t < ts[k + 1]))
        pieces.append((vs[-1], True))
        return sp.Piecewise(*pieces)

    def breakpoints(self, p, t_stop):
        return [v for k, v in p.items() if k.startswith("t")]


def _carrier_times(p, t_stop, per_period: int) -> list[float]:
    """Times in [0, t_stop] where a carrier of ``per_period`` equal pieces has a corner."""
    f, shift = p["freq"], p["phase"] / (2 * math.pi)
    k = math.ceil(per_period * shift)  # first corner at or after t = 0
    out = []
    while True:
        t = (k / per_period - shift) / f
        if t > t_stop:
            return out
        if t >= 0:
            out.append(t)
        k += 1


CARRIER = {"freq": Param("Hz", "carrier frequency", positive=True),
           "phase": Param("rad", "phase shift (2 pi = one period; 120 deg for a third)",
                          default=0.0),
           "low": Param("@", "lowest value", default=-1.0),
           "high": Param("@", "highest value", default=1.0),
           "invert": Param("1", "1: mirrored (high where it would be low)", default=0.0,
                           nonnegative=True, integer=True, maximum=1)}


def _scaled(unit, p):
    """A unit carrier in [-1, 1] scaled to [low, high], mirrored when ``invert`` is 1."""
    u = unit * (1 - 2 * p["invert"])
    return p["low"] + (p["high"] - p["low"]) * (u + 1) / 2


@register_waveform("triangle")
class Triangle(Waveform):
    """PWM carrier: low at the start of each period, high at its middle (as ``pwm_leg``'s),
    shifted by ``phase``. Its corners are breakpoints, so each half-period crosses a slowly
    varying reference once and an event finds the crossing."""

    params: ClassVar[dict[str, Param]] = CARRIER

    def expr(self, t, p, data=None):
        frac = Pmod(p["freq"] * t + p["phase"] / (2 * sp.pi), sp.Integer(1))
        unit = sp.Piecewise((4 * frac - 1, frac < sp.Rational(1, 2)), (3 - 4 * frac, True))
        return _scaled(unit, p)

    def breakpoints(self, p, t_stop):
        return _carrier_times(p, t_stop, 2)

    def period(self, p):
        return 1.0 / p["freq"]


@register_waveform("sawtooth")
class Sawtooth(Waveform):
    """PWM carrier rising from low to high over each period and falling back at once
    (falling ramps with ``invert: 1``), shifted by ``phase``; the fall is a breakpoint."""

    params: ClassVar[dict[str, Param]] = CARRIER

    def expr(self, t, p, data=None):
        frac = Pmod(p["freq"] * t + p["phase"] / (2 * sp.pi), sp.Integer(1))
        return _scaled(2 * frac - 1, p)

    def breakpoints(self, p, t_stop):
        return _carrier_times(p, t_stop, 1)

    def period(self, p):
        return 1.0 / p["freq"]
