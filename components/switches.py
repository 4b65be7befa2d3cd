"""Switches as conductances that change with a control: by time (a waveform, whose edges are
integrator breakpoints) or by a voltage (SPICE S).

``model: smooth`` (default) moves the conductance continuously, on a log scale, from 1/Roff
to 1/Ron: over the signal's own edge for the time switch, over a window ``dV`` around the
threshold for the voltage switch (without events a jump of an algebraic unknown stops IDA).
``model: ideal`` holds the switch state as a discrete state that changes at a root of its
control found by the integrator (an event), and restarts from consistent values there.
"""

from __future__ import annotations

from circuitsim.component import (
    Branch,
    Event,
    OnePort,
    Option,
    Param,
    Pin,
    Signal,
    register,
    sp,
)

#: Hysteresis of a comparison with no hysteresis of its own (a time signal against 1/2, a
#: carrier against a reference), in the units compared: after a switching the new guard must
#: start positive, or the event iteration would switch straight back. 1e-9 of a unit signal
#: moves an edge by 1e-9 of its ramp.
BAND = 1e-9


def toggle(on, guard_off, guard_on, *also) -> Event:
    """Event of a two-state switch: while off (on = 0) it holds as long as ``guard_off`` > 0,
    while on as long as ``guard_on`` > 0; at the root it toggles (and sets ``also``)."""
    return Event((1 - on) * guard_off + on * guard_on, ((on, 1 - on), *also))


def ideal_conductance(on, ron, goff):
    """Goff when open (on = 0), 1/Ron when closed (on = 1); never zero in either state, so
    the structure of the equations does not depend on the mode."""
    return goff + on * (1 / ron - goff)


def _conductance(s, ron, roff):
    """1/Roff at s <= 0, 1/Ron at s >= 1, geometric in between."""
    frac = sp.Piecewise((0, s < 0), (1, s > 1), (s, True))
    return sp.exp(-sp.log(roff) + frac * (sp.log(roff) - sp.log(ron)))


@register("tswitch", "time_switch")
class TimeSwitch(OnePort):
    """Switch driven by a signal of time: closed (Ron) at ``closed`` = 1, open (Roff) at 0
    (``ideal``: switches by an event where the signal crosses 1/2), e.g.
    ``closed: {pulse: {v2: 1, delay: 1 ms, width: 2 ms, period: 10 ms}}``.

    Parameters
    ----------
    closed : [1] 0 (open) or 1 (closed), value or waveform
    Ron : [ohm] closed resistance, default 1 mohm
    Roff : [ohm] open resistance, default 1 Gohm
    model : smooth (default: a log-scale ramp over the signal's edge) or ideal
    """

    branches = (Branch("p", "n", "R"),)
    closed = Signal("1", "1 when closed, 0 when open")
    Ron = Param("ohm", "closed resistance", default=1e-3, positive=True)
    Roff = Param("ohm", "open resistance", default=1e9, positive=True)
    model = Option("smooth (log-scale ramp over the edge) or ideal (switches at closed = 1/2 "
                   "by an event)", "smooth", ("smooth", "ideal"))

    def equations(self, x):
        if self.model == "ideal":
            on = x.discrete("on")
            return [x.i - ideal_conductance(on, self.Ron, 1 / self.Roff) * x.v]
        return [x.i - _conductance(self.closed, self.Ron, self.Roff) * x.v]

    def events(self, x):
        if self.model != "ideal":
            return []
        half = sp.Rational(1, 2)
        return [toggle(x.on, half + BAND - self.closed, self.closed - half + BAND)]


@register("S", "vswitch")
class VoltageSwitch(OnePort):
    """Voltage-controlled switch (SPICE S): closed (Ron) above the threshold Vt, open (Roff)
    below; ``smooth`` over a window dV, or ``ideal`` by events with hysteresis Vh (closed
    above Vt + Vh, open below Vt - Vh, as SPICE's VT, VH). The control pins draw no current.

    Parameters
    ----------
    Vt : [V] threshold, default 0
    dV : [V] width of the transition around Vt (smooth), default 1 mV
    Vh : [V] hysteresis (ideal, as SPICE VH): closes above Vt + Vh, opens below Vt - Vh;
        positive, default 1 uV
    Ron : [ohm] closed resistance, default 1 mohm
    Roff : [ohm] open resistance, default 1 Gohm
    model : smooth (default) or ideal (an event at each threshold crossing)
    """

    ports = (Pin("p"), Pin("n"), Pin("cp"), Pin("cn"))
    branches = (Branch("p", "n", "R"),)
    Vt = Param("V", "threshold", default=0.0)
    dV = Param("V", "transition width", default=1e-3, positive=True)
    Vh = Param("V", "hysteresis (ideal)", default=1e-6, positive=True)
    Ron = Param("ohm", "closed resistance", default=1e-3, positive=True)
    Roff = Param("ohm", "open resistance", default=1e9, positive=True)
    model = Option("smooth (log-scale ramp over dV) or ideal (events with hysteresis Vh)",
                   "smooth", ("smooth", "ideal"))

    def equations(self, x):
        x.vc = x.cp.v - x.cn.v
        if self.model == "ideal":
            on = x.discrete("on")
            g = ideal_conductance(on, self.Ron, 1 / self.Roff)
            return [x.i - g * x.v, x.cp.i, x.cn.i]
        s = (x.vc - self.Vt) / self.dV + sp.Rational(1, 2)
        return [x.i - _conductance(s, self.Ron, self.Roff) * x.v, x.cp.i, x.cn.i]

    def events(self, x):
        if self.model != "ideal":
            return []
        return [toggle(x.on, self.Vt + self.Vh - x.vc, x.vc - self.Vt + self.Vh)]
