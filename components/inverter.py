"""Ideal PWM half-bridge: two switches with anti-parallel diodes, switched by events.

The comparator of a reference m with a carrier (``triangle`` or ``sawtooth``, phase-shifted
or inverted) is a discrete state changed at the crossings, which the integrator's root
finding locates; a dead time delays each turn-on, and meanwhile the leg's current flows
through the diodes. H-bridges and three-phase inverters are two or three legs on one DC link
(``netlists/inverters/``). The smooth ``pwm_leg`` (bldc.py) is its tanh-edged counterpart.
"""

from __future__ import annotations

from circuitsim.component import (
    Branch,
    Component,
    Event,
    Expression,
    Option,
    Param,
    Pin,
    Signal,
    register,
)
from circuitsim_components.switches import BAND, ideal_conductance, toggle


def _diode(on, va, vf, rd, goff):
    """Current [A] of an ideal diode with anode-cathode voltage va: its pwl branches."""
    return goff * va + on * (va - vf) * (1 / rd - goff)


@register("half_bridge", "pwm_half_bridge")
class HalfBridge(Component):
    """Ideal PWM inverter leg: output p to the rail dc while m > carrier (upper switch), to n
    otherwise (lower switch); each turn-on waits the dead time td; diodes across both.

    Switches: 1/Ron closed, 1/Roff open. Diodes (anode at the lower potential side: p to dc
    and n to p): i = (va - Vf)/Rd above Vf, switched with hysteresis Vh. Each transition is an
    event at the exact crossing (comparator, with a 1e-9 band) or the exact end of the dead
    time.

    Parameters
    ----------
    m : [1] reference (expression of t, parameters, circuit quantities), in carrier units
    carrier : [1] carrier waveform, e.g. ``{triangle: {freq: 20 kHz, phase: 0}}``
    td : [s] dead time, default 0
    Ron : [ohm] switch on resistance, default 1 mohm
    Roff : [ohm] switch off resistance, default 1 Gohm
    Vf : [V] diode knee voltage, default 0.7 V
    Rd : [ohm] diode forward resistance, default 1 mohm
    Vh : [V] diode hysteresis, default 1 uV
    invert : reference inverted (upper switch on while m < carrier), default false

    Ports
    -----
    p : electrical, the leg output; dc : DC plus rail; n : DC minus rail.
    """

    ports = (Pin("p"), Pin("n"), Pin("dc"))
    branches = (Branch("p", "n", "X"), Branch("dc", "n", "X"))
    m = Expression("1", "reference")
    carrier = Signal("1", "carrier waveform")
    td = Param("s", "dead time", default=0.0, nonnegative=True)
    Ron = Param("ohm", "switch on resistance", default=1e-3, positive=True)
    Roff = Param("ohm", "switch off resistance", default=1e9, positive=True)
    Vf = Param("V", "diode knee voltage", default=0.7, nonnegative=True)
    Rd = Param("ohm", "diode forward resistance", default=1e-3, positive=True)
    Vh = Param("V", "diode hysteresis", default=1e-6, positive=True)
    invert = Option("upper switch on while m < carrier", False)

    def bind(self, x):
        x.v = x.p.v - x.n.v
        x.i = x.p.i
        return []

    def equations(self, x):
        cmd, ready = x.discrete("cmd"), x.discrete("ready")
        x.discrete("t_edge")
        du, dl = x.discrete("d_hi"), x.discrete("d_lo")
        goff = 1 / self.Roff
        x.gate_hi = cmd * ready
        x.gate_lo = (1 - cmd) * ready
        v_hi = x.dc.v - x.p.v  # across the upper switch
        i_hi = (ideal_conductance(x.gate_hi, self.Ron, goff) * v_hi
                - _diode(du, -v_hi, self.Vf, self.Rd, goff))  # from dc into p
        i_lo = (ideal_conductance(x.gate_lo, self.Ron, goff) * x.v
                - _diode(dl, -x.v, self.Vf, self.Rd, goff))  # from p into n
        return [x.dc.i - i_hi, x.n.i + i_lo, x.p.i + x.dc.i + x.n.i]

    def events(self, x):
        m, c = (-self.m, -self.carrier) if self.invert else (self.m, self.carrier)
        # the comparator: on at m = c + BAND, off at m = c - BAND; each edge starts a dead time
        cmd = toggle(x.cmd, c + BAND - m, m - c + BAND, (x.t_edge, x.t), (x.ready, 0))
        dead = Event((1 - x.ready) * (x.t_edge + self.td - x.t) + x.ready, ((x.ready, 1),))
        vf, vh = self.Vf, self.Vh
        hi = toggle(x.d_hi, vf + vh - (x.p.v - x.dc.v), x.p.v - x.dc.v - vf + vh)
        lo = toggle(x.d_lo, vf + vh - (x.n.v - x.p.v), x.n.v - x.p.v - vf + vh)
        return [cmd, dead, hi, lo]
