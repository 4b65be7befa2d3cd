"""Friction with true stick-slip: a clutch or brake whose sticking is a mode, not a creep.

The mode (stuck, slipping forward, slipping backward) is a discrete state changed by events:
it breaks away where the torque needed to stay stuck reaches the static capacity, and sticks
where the relative speed crosses zero. Stuck, the relative *acceleration* is zero and the
torque is whatever that takes (as Modelica's friction elements): with inertias on both sides
the equations stay index 1 in every mode, so the structure does not depend on the mode.
"""

from __future__ import annotations

from circuitsim.component import Branch, Event, Param, Signal, register
from circuitsim_components.drivetrain import TwoFlange


@register("stick_clutch", "stick_slip_clutch")
class StickSlipClutch(TwoFlange):
    """Clutch between two shafts (a brake when b is ``fixed``) with exact adhesion: stuck,
    w_rel' = -w_rel/t_hold (w_rel held at 0) and |tau| <= mu_s fn; slipping, tau = mu fn
    sign(w_rel). Breakaway at |tau| = mu_s fn, sticking where w_rel crosses -+w_eps.

    Parameters
    ----------
    fn : [N*m] normal-force torque capacity (friction radius times normal force), value or
        waveform
    mu : [1] kinetic friction coefficient, default 1
    mu_s : [1] static friction coefficient, default mu
    w_eps : [rad/s] speed past zero at which a slip sticks (a band, so that a breakaway
        does not stick again at once), default 1e-9
    t_hold : [s] time constant that pulls the band's w_rel back to 0 while stuck, default
        1e-4

    Ports
    -----
    a, b : rotational; tau is the torque into flange a (shaft a receives -tau, b +tau).
    Each side needs an inertia (stuck, the two accelerations are made equal).
    """

    branches = (Branch("a", "b", "R"),)
    fn = Signal("N*m", "torque capacity times friction radius")
    mu = Param("1", "kinetic friction coefficient", default=1.0, nonnegative=True)
    mu_s = Param("1", "static friction coefficient", default="mu", nonnegative=True)
    w_eps = Param("rad/s", "sticking band", default=1e-9, positive=True)
    t_hold = Param("s", "hold time constant while stuck", default=1e-4, positive=True)

    def equations(self, x):
        mode = x.discrete("mode")  # 0 stuck, +1 slipping forward, -1 backward
        stuck = 1 - mode**2
        hold = x.der(x.w_rel) + x.w_rel / self.t_hold
        return [stuck * hold + (1 - stuck) * (x.tau - mode * self.mu * self.fn)]

    def events(self, x):
        mode, stuck = x.mode, 1 - x.mode**2
        ts = self.mu_s * self.fn
        # stuck: breaks away forward when tau reaches +Ts, backward at -Ts; slipping: sticks
        # when w_rel has crossed zero by w_eps (the other guards are held at 1 meanwhile)
        forward = Event(stuck * (ts - x.tau) + (1 - stuck), ((mode, 1),))
        backward = Event(stuck * (ts + x.tau) + (1 - stuck), ((mode, -1),))
        stick = Event(mode * x.w_rel + self.w_eps * mode**2 + stuck, ((mode, 0),))
        return [forward, backward, stick]
