"""Independent sources: voltage, current, torque and force, each driven by a waveform."""

from __future__ import annotations

from circuitsim.component import (
    Branch,
    Expression,
    OneFlange,
    OnePort,
    OneTFlange,
    Signal,
    register,
)


@register("V", "vsource")
class VoltageSource(OnePort):
    """Ideal voltage source: v = V(t). Its current i flows into p (negative when delivering).

    Parameters
    ----------
    V : [V] value or waveform (dc, step, sine, pulse, pwm, pwl, table)
    """

    branches = (Branch("p", "n", "V"),)
    V = Signal("V", "source voltage")

    def equations(self, x):
        return [x.v - self.V]


@register("I", "isource")
class CurrentSource(OnePort):
    """Ideal current source: i = I(t), flowing from p through the source to n.

    Parameters
    ----------
    I : [A] value or waveform
    """

    branches = (Branch("p", "n", "I"),)
    I = Signal("A", "source current")

    def equations(self, x):
        return [x.i - self.I]


@register("torque")
class TorqueSource(OneFlange):
    """Torque source: the shaft receives T(t) against the fixed reference.

    Positive T accelerates positive rotation; the flow into the source's flange is -T.

    Parameters
    ----------
    T : [N*m] value or waveform (a load torque is a negative T)
    """

    branches = (Branch("shaft", None, "I"),)
    T = Signal("N*m", "torque delivered to the shaft")

    def equations(self, x):
        return [x.tau + self.T]


@register("force")
class ForceSource(OneTFlange):
    """Force source: the flange receives F(t) against the fixed reference.

    Parameters
    ----------
    F : [N] value or waveform
    """

    branches = (Branch("flange", None, "I"),)
    F = Signal("N", "force delivered to the flange")

    def equations(self, x):
        return [x.f + self.F]


@register("BV", "bvoltage")
class BehaviouralVoltage(OnePort):
    """Behavioural voltage source (SPICE B-source): v = expr(t, parameters, circuit quantities).

    Parameters
    ----------
    expr : [V] e.g. ``Kp*(ref.v - out.v)``
    """

    branches = (Branch("p", "n", "X"),)
    expr = Expression("V", "source voltage")

    def equations(self, x):
        return [x.v - self.expr]


@register("BI", "bcurrent")
class BehaviouralCurrent(OnePort):
    """Behavioural current source: i = expr, flowing from p through the source to n.

    Parameters
    ----------
    expr : [A] e.g. ``g*(a.v - b.v)``
    """

    branches = (Branch("p", "n", "X"),)
    expr = Expression("A", "source current")

    def equations(self, x):
        return [x.i - self.expr]


@register("btorque")
class BehaviouralTorque(OneFlange):
    """Behavioural torque: the shaft receives T = expr (e.g. a controller's output).

    Parameters
    ----------
    expr : [N*m]
    """

    branches = (Branch("shaft", None, "X"),)
    expr = Expression("N*m", "torque delivered to the shaft")

    def equations(self, x):
        return [x.tau + self.expr]


@register("bforce")
class BehaviouralForce(OneTFlange):
    """Behavioural force: the flange receives F = expr (e.g. a PD position loop).

    Parameters
    ----------
    expr : [N] e.g. ``Kp*(ref.v - cart.x) - Kd*cart.v``
    """

    branches = (Branch("flange", None, "X"),)
    expr = Expression("N", "force delivered to the flange")

    def equations(self, x):
        return [x.f + self.expr]
