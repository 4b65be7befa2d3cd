"""The thermal domain: heat capacity, conductance, fixed temperature, heat-flow source, and
a resistor and a winding whose resistance follows their temperature and which heat from their
own loss.

Across: temperature T [K] (absolute); through: heat flow Q [W] into a port. Write
temperatures in kelvin (20 degC = 293.15 K).
"""

from __future__ import annotations

from circuitsim.component import (
    Branch,
    Component,
    HeatPort,
    OnePort,
    Param,
    Pin,
    Signal,
    register,
)


class OneHeatPort(Component):
    """One heat port acting against the 0 K reference: T = its temperature, Q = heat flow
    into the element."""

    ports = (HeatPort("port"),)

    def bind(self, x):
        x.T = x.port.T
        x.Q = x.port.Q
        return []


@register("heat_capacitor", "thermal_mass")
class HeatCapacitor(OneHeatPort):
    """Heat capacity: C dT/dt = Q.

    Parameters
    ----------
    C : [J/K] heat capacity
    T0 : [K] initial temperature (required: starting "from rest" would mean 0 K)
    """

    branches = (Branch("port", None, "C"),)
    C = Param("J/K", "heat capacity", positive=True)
    T0 = Param("K", "initial temperature", positive=True)

    def equations(self, x):
        return [self.C * x.der(x.T) - x.Q]

    def initial(self, x):
        return {x.T: self.T0}

    def energy(self, x):
        return self.C * x.T


@register("thermal_conductor", "Gth")
class ThermalConductor(Component):
    """Heat conduction between two ports: Q = G (a.T - b.T) from a to b.

    Parameters
    ----------
    G : [W/K] thermal conductance (1 / thermal resistance)
    """

    ports = (HeatPort("a"), HeatPort("b"))
    branches = (Branch("a", "b", "R"),)
    G = Param("W/K", "thermal conductance", positive=True)

    def bind(self, x):
        x.dT = x.a.T - x.b.T
        x.Q = x.a.Q
        return [x.a.Q + x.b.Q]

    def equations(self, x):
        return [x.Q - self.G * x.dT]


@register("fixed_temperature", "ambient")
class FixedTemperature(OneHeatPort):
    """Fixed (or prescribed) temperature: T = T(t), whatever heat flows.

    Parameters
    ----------
    T : [K] value or waveform
    """

    branches = (Branch("port", None, "V"),)
    T = Signal("K", "temperature")

    def equations(self, x):
        return [x.port.T - self.T]


@register("heat_flow", "heat_source")
class HeatFlowSource(OneHeatPort):
    """Heat-flow source: the node receives P(t).

    Parameters
    ----------
    P : [W] value or waveform
    """

    branches = (Branch("port", None, "I"),)
    P = Signal("W", "heat flow delivered to the node")

    def equations(self, x):
        return [x.Q + self.P]


class _Heated(OnePort):
    """Pins p, n and a heat port h; R = R_ref (1 + alpha (h.T - T_ref)); the loss R i^2 leaves
    through h (flow into h is -R i^2)."""

    ports = (Pin("p"), Pin("n"), HeatPort("h"))
    R_ref = Param("ohm", "resistance at T_ref", positive=True)
    T_ref = Param("K", "reference temperature", default=293.15, positive=True)
    alpha = Param("1/K", "temperature coefficient (copper 3.93e-3)", default=3.93e-3)

    def bind(self, x):
        eqs = super().bind(x)
        x.T = x.h.T
        x.R = self.R_ref * (1 + self.alpha * (x.h.T - self.T_ref))
        return [*eqs, x.h.Q + x.R * x.i**2]


@register("RT", "heated_resistor")
class HeatedResistor(_Heated):
    """Resistor whose resistance follows its temperature and which heats from its own loss:
    v = R_ref (1 + alpha (T - T_ref)) i; the heat port h delivers R i^2.

    Parameters
    ----------
    R_ref : [ohm] resistance at T_ref
    T_ref : [K] reference temperature, default 293.15
    alpha : [1/K] temperature coefficient, default 3.93e-3 (copper)
    """

    branches = (Branch("p", "n", "R"), Branch("h", None, "X"))

    def equations(self, x):
        return [x.v - x.R * x.i]


@register("LT", "heated_winding")
class HeatedWinding(_Heated):
    """Winding with copper resistance that follows its temperature and heats from its own
    loss: v = L di/dt + R_ref (1 + alpha (T - T_ref)) i; the heat port h delivers R i^2.

    Parameters
    ----------
    L : [H] inductance
    R_ref : [ohm] resistance at T_ref
    T_ref : [K] reference temperature, default 293.15
    alpha : [1/K] temperature coefficient, default 3.93e-3 (copper)
    i0 : [A] initial current
    """

    branches = (Branch("p", "n", "L"), Branch("h", None, "X"))
    L = Param("H", "inductance", positive=True)
    i0 = Param("A", "initial current", default=0.0)

    def equations(self, x):
        return [x.v - self.L * x.der(x.i) - x.R * x.i]

    def initial(self, x):
        return {x.i: self.i0}

    def energy(self, x):
        return self.L * x.i**2 / 2
