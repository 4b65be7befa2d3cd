"""Switches as conductances that change with a control: by time (a waveform, whose edges are
integrator breakpoints, so the switching instants are exact) or by a voltage (SPICE S).

Without events a jump of an algebraic unknown stops IDA (a hard threshold failed with "mxstep
steps taken" at the switching instant), so the conductance moves continuously, on a log
scale, from 1/Roff to 1/Ron: over the signal's own edge for the time switch, over a window
``dV`` around the threshold for the voltage switch."""

from __future__ import annotations

from circuitsim.component import Branch, OnePort, Param, Pin, Signal, register, sp


def _conductance(s, ron, roff):
    """1/Roff at s <= 0, 1/Ron at s >= 1, geometric in between."""
    frac = sp.Piecewise((0, s < 0), (1, s > 1), (s, True))
    return sp.exp(-sp.log(roff) + frac * (sp.log(roff) - sp.log(ron)))


@register("tswitch", "time_switch")
class TimeSwitch(OnePort):
    """Switch driven by a signal of time: closed (Ron) at ``closed`` = 1, open (Roff) at 0,
    e.g. ``closed: {pulse: {v2: 1, delay: 1 ms, width: 2 ms, period: 10 ms}}``.

    Parameters
    ----------
    closed : [1] 0 (open) or 1 (closed), value or waveform
    Ron : [ohm] closed resistance, default 1 mohm
    Roff : [ohm] open resistance, default 1 Gohm
    """

    branches = (Branch("p", "n", "R"),)
    closed = Signal("1", "1 when closed, 0 when open")
    Ron = Param("ohm", "closed resistance", default=1e-3, positive=True)
    Roff = Param("ohm", "open resistance", default=1e9, positive=True)

    def equations(self, x):
        return [x.i - _conductance(self.closed, self.Ron, self.Roff) * x.v]


@register("S", "vswitch")
class VoltageSwitch(OnePort):
    """Voltage-controlled switch (SPICE S): closed (Ron) above Vt + dV/2, open (Roff) below
    Vt - dV/2; the control pins draw no current.

    Parameters
    ----------
    Vt : [V] threshold, default 0
    dV : [V] width of the transition around Vt, default 1 mV
    Ron : [ohm] closed resistance, default 1 mohm
    Roff : [ohm] open resistance, default 1 Gohm
    """

    ports = (Pin("p"), Pin("n"), Pin("cp"), Pin("cn"))
    branches = (Branch("p", "n", "R"),)
    Vt = Param("V", "threshold", default=0.0)
    dV = Param("V", "transition width", default=1e-3, positive=True)
    Ron = Param("ohm", "closed resistance", default=1e-3, positive=True)
    Roff = Param("ohm", "open resistance", default=1e9, positive=True)

    def equations(self, x):
        x.vc = x.cp.v - x.cn.v
        s = (x.vc - self.Vt) / self.dV + sp.Rational(1, 2)
        return [x.i - _conductance(s, self.Ron, self.Roff) * x.v, x.cp.i, x.cn.i]
