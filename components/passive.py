"""Linear passive electrical elements: resistor, inductor, capacitor, ground."""

from __future__ import annotations

from circuitsim.component import Branch, Component, OnePort, Param, Pin, register


@register("R", "resistor")
class Resistor(OnePort):
    """Ideal resistor: v = R i.

    Parameters
    ----------
    R : [ohm] resistance
    """

    branches = (Branch("p", "n", "R"),)
    R = Param("ohm", "resistance", positive=True)

    def equations(self, x):
        return [x.v - self.R * x.i]


@register("L", "inductor")
class Inductor(OnePort):
    """Inductor with optional series resistance: v = L di/dt + R i.

    Parameters
    ----------
    L : [H] inductance
    R : [ohm] series (winding) resistance, default 0
    i0 : [A] initial current, default 0
    """

    branches = (Branch("p", "n", "L"),)
    L = Param("H", "inductance", positive=True)
    R = Param("ohm", "series resistance", default=0.0, nonnegative=True)
    i0 = Param("A", "initial current", default=0.0)

    def equations(self, x):
        return [x.v - self.L * x.der(x.i) - self.R * x.i]

    def initial(self, x):
        return {x.i: self.i0}

    def energy(self, x):
        return self.L * x.i**2 / 2


@register("C", "capacitor")
class Capacitor(OnePort):
    """Ideal capacitor: i = C dv/dt.

    Parameters
    ----------
    C : [F] capacitance
    v0 : [V] initial voltage, default 0
    """

    branches = (Branch("p", "n", "C"),)
    C = Param("F", "capacitance", positive=True)
    v0 = Param("V", "initial voltage", default=0.0)

    def equations(self, x):
        return [x.i - self.C * x.der(x.v)]

    def initial(self, x):
        return {x.v: self.v0}

    def energy(self, x):
        return self.C * x.v**2 / 2


@register("ground")
class Ground(Component):
    """Ties a node to the electrical reference: p.v = 0."""

    ports = (Pin("p"),)
    branches = (Branch("p", None, "V"),)

    def equations(self, x):
        return [x.p.v]
