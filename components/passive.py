"""Linear passive electrical elements: resistor, inductor, capacitor, ground."""

from __future__ import annotations

import sympy as sp

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


@register("Lsat", "saturating_inductor")
class SaturatingInductor(OnePort):
    """Inductor whose inductance falls with current (as Modelica's SaturatingInductor):
    psi = Linf i + (Lzer - Linf) Ipar atan(i / Ipar), v = d psi/dt + R i.

    Parameters
    ----------
    Lzer : [H] inductance at zero current
    Linf : [H] inductance deep in saturation (<= Lzer)
    Ipar : [A] knee current: the differential inductance has fallen half way at i = Ipar
    R : [ohm] series (winding) resistance
    i0 : [A] initial current
    """

    branches = (Branch("p", "n", "L"),)
    Lzer = Param("H", "inductance at zero current", positive=True)
    Linf = Param("H", "saturated inductance", positive=True)
    Ipar = Param("A", "knee current", positive=True)
    R = Param("ohm", "series resistance", default=0.0, nonnegative=True)
    i0 = Param("A", "initial current", default=0.0)

    def equations(self, x):
        l_diff = self.Linf + (self.Lzer - self.Linf) / (1 + (x.i / self.Ipar) ** 2)
        return [x.v - l_diff * x.der(x.i) - self.R * x.i]

    def initial(self, x):
        return {x.i: self.i0}

    def energy(self, x):
        # W = integral of i dpsi = Linf i^2/2 + (Lzer - Linf) Ipar^2 ln(1 + (i/Ipar)^2) / 2
        return self.Linf * x.i**2 / 2 + (self.Lzer - self.Linf) * self.Ipar**2 * \
            sp.log(1 + (x.i / self.Ipar) ** 2) / 2


@register("Rdrift", "drifting_resistor")
class DriftingResistor(OnePort):
    """Resistor warming up: v = R0 (1 + alpha t) i (linear drift in time).

    Parameters
    ----------
    R0 : [ohm] resistance at t = 0
    alpha : [1/s] relative drift rate
    """

    branches = (Branch("p", "n", "R"),)
    R0 = Param("ohm", "resistance at t = 0", positive=True)
    alpha = Param("1/s", "relative drift rate", default=0.0)

    def equations(self, x):
        return [x.v - self.R0 * (1 + self.alpha * x.t) * x.i]
