"""Diode: the Shockley law with series resistance, or a piecewise-linear (ideal-ish) model."""

from __future__ import annotations

from circuitsim.component import Branch, OnePort, Option, Param, register, sp
from circuitsim_components.switches import toggle

#: Above this many thermal voltages the exponential is continued by its tangent (as SPICE
#: limits the junction voltage): exp(40) ~ 2e17 times Is is far past any real current, and
#: a Newton iterate there must not overflow.
EXP_LIMIT = 40


def _limexp(u):
    return sp.Piecewise((sp.exp(u), u < EXP_LIMIT),
                        (sp.exp(EXP_LIMIT) * (1 + u - EXP_LIMIT), True))


@register("D", "diode")
class Diode(OnePort):
    """Diode from anode p to cathode n: Shockley with series resistance, piecewise linear, or
    piecewise linear switched by events (ideal). ``model: shockley``: i = Is (exp(vd/(N Vt)) - 1),
    v = vd + Rs i. ``model: pwl``: i = (v - Vf)/Ron + Vf Goff above Vf, Goff v below it.
    ``model: ideal``: the same two lines, the branch a discrete state switched by events
    (on above Vf + Vh, off below Vf - Vh).

    Parameters
    ----------
    Is : [A] saturation current, default 1e-14
    N : [1] emission coefficient, default 1
    Vt : [V] thermal voltage kT/q, default 25.852 mV (300 K)
    Rs : [ohm] series resistance, default 0
    Vf : [V] knee voltage of the pwl model, default 0.7
    Ron : [ohm] forward resistance of the pwl model, default 10 mohm
    Goff : [S] reverse conductance of the pwl model, default 1e-9
    Vh : [V] hysteresis of the ideal model around Vf, default 1 uV (positive: at a switching
        the new mode must hold, or it would switch straight back)
    """

    branches = (Branch("p", "n", "X"),)
    Is = Param("A", "saturation current", default=1e-14, positive=True)
    N = Param("1", "emission coefficient", default=1.0, positive=True)
    Vt = Param("V", "thermal voltage", default=0.025852, positive=True)
    Rs = Param("ohm", "series resistance", default=0.0, nonnegative=True)
    Vf = Param("V", "knee voltage (pwl)", default=0.7, nonnegative=True)
    Ron = Param("ohm", "forward resistance (pwl)", default=0.01, positive=True)
    Goff = Param("S", "reverse conductance (pwl)", default=1e-9, nonnegative=True)
    Vh = Param("V", "hysteresis around Vf (ideal)", default=1e-6, positive=True)
    model = Option("shockley, pwl (piecewise linear) or ideal (pwl switched by events)",
                   "shockley", ("shockley", "pwl", "ideal"))

    def equations(self, x):
        if self.model == "ideal":
            on = x.discrete("on")
            return [x.i - self.Goff * x.v - on * (x.v - self.Vf) * (1 / self.Ron - self.Goff)]
        if self.model == "pwl":
            on = (x.v - self.Vf) / self.Ron + self.Vf * self.Goff
            return [x.i - sp.Piecewise((on, x.v > self.Vf), (self.Goff * x.v, True))]
        vd = x.var("vd")
        return [x.i - self.Is * (_limexp(vd / (self.N * self.Vt)) - 1),
                x.v - vd - self.Rs * x.i]

    def events(self, x):
        if self.model != "ideal":
            return []
        return [toggle(x.on, self.Vf + self.Vh - x.v, x.v - self.Vf + self.Vh)]
