"""Linear passive electrical elements: resistor, inductor, capacitor, ground."""

from __future__ import annotations

import functools

from circuitsim.component import Branch, Component, OnePort, Param, Pin, register, sp


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


#: Newton steps for the knee of Lsat_nom: 6 reach 5e-9 relative for r in [1e-4, 1 - 1e-9].
KNEE_STEPS = 6


def knee_u(r: float) -> float:
    """The u > 0 with atan(u) = r u, for 0 < r < 1 (a float, or a numpy array).

    Newton from the upper bound u0 = pi/2 sqrt(1/r^2 - 1) (atan(u)/u <= (1 + 4u^2/pi^2)^-1/2)
    descends monotonically on the concave atan(u) - r u."""
    import numpy as np

    u = np.pi / 2 * np.sqrt(1 / (r * r) - 1)
    for _ in range(KNEE_STEPS):
        u = u - (np.arctan(u) - r * u) / (1 / (1 + u * u) - r)
    return u


def _knee_text(r: str, atan: str, sqrt: str) -> str:
    """``knee_u`` as one expression of generated code (walrus steps share the iterate)."""
    steps = [f"(_kr := ({r}))", f"(_ku := 1.5707963267948966*{sqrt}(1/(_kr*_kr) - 1))"]
    steps += [f"(_ku := _ku - ({atan}(_ku) - _kr*_ku)/(1/(1 + _ku*_ku) - _kr))"] * KNEE_STEPS
    return f"({', '.join(steps)})[-1]"


@functools.cache
def _knee_function() -> type:
    """The sympy function KneeU, defined at its first use: defining a sympy Function imports
    sympy, which a run served from the model cache never needs."""

    class KneeU(sp.Function):
        """u(r) with atan(u) = r u: a parameter function, computed numerically in the generated
        code (a symbolic Newton iteration would grow threefold per step)."""

        nargs = 1

        def fdiff(self, argindex=1):
            r = self.args[0]
            return self / (1 / (1 + self**2) - r)  # implicit derivative of atan(u) - r u = 0

        def _eval_evalf(self, prec):
            r = self.args[0]
            if r.is_number:
                return sp.Float(float(knee_u(float(r))), prec)
            return None

        def _pythoncode(self, printer, **kw):
            r = printer._print(self.args[0])
            if getattr(printer, "calls", False):  # the kernels: numba types no walrus chain
                return f"knee_u({r}, {KNEE_STEPS})"
            return _knee_text(r, "math.atan", "math.sqrt")

        def _numpycode(self, printer, **kw):
            return _knee_text(printer._print(self.args[0]), "numpy.arctan", "numpy.sqrt")

    return KneeU


def knee_current(Lzer, Linf, Lnom, Inom):
    """Ipar of the atan saturation law from a nominal (secant) inductance Lnom = psi/i at
    Inom, as Modelica's SaturatingInductor takes it: with u = Inom/Ipar and
    r = (Lnom - Linf)/(Lzer - Linf), atan(u) = r u."""
    return Inom / _knee_function()((Lnom - Linf) / (Lzer - Linf))


@register("Lsat_nom", "saturating_inductor_nominal")
class SaturatingInductorNominal(OnePort):
    """Saturating inductor given as Modelica's SaturatingInductor is: the same atan law as
    ``Lsat``, with its knee found from the nominal inductance Lnom = psi/i at current Inom.

    Parameters
    ----------
    Lzer : [H] inductance at zero current
    Lnom : [H] nominal (secant) inductance psi/i at Inom, Linf < Lnom < Lzer
    Inom : [A] nominal current
    Linf : [H] inductance deep in saturation
    R : [ohm] series (winding) resistance
    i0 : [A] initial current
    """

    branches = (Branch("p", "n", "L"),)
    Lzer = Param("H", "inductance at zero current", positive=True)
    Lnom = Param("H", "nominal inductance psi/i at Inom", positive=True)
    Inom = Param("A", "nominal current", positive=True)
    Linf = Param("H", "saturated inductance", positive=True)
    R = Param("ohm", "series resistance", default=0.0, nonnegative=True)
    i0 = Param("A", "initial current", default=0.0)

    def _ipar(self):
        return knee_current(self.Lzer, self.Linf, self.Lnom, self.Inom)

    def equations(self, x):
        ipar = self._ipar()
        l_diff = self.Linf + (self.Lzer - self.Linf) / (1 + (x.i / ipar) ** 2)
        return [x.v - l_diff * x.der(x.i) - self.R * x.i]

    def initial(self, x):
        return {x.i: self.i0}

    def energy(self, x):
        ipar = self._ipar()
        return self.Linf * x.i**2 / 2 + (self.Lzer - self.Linf) * ipar**2 * \
            sp.log(1 + (x.i / ipar) ** 2) / 2

    def warnings(self, values):
        if not values["Linf"] < values["Lnom"] < values["Lzer"]:
            return [(f"Lnom = {values['Lnom']:.6g} H must lie between Linf = "
                     f"{values['Linf']:.6g} H and Lzer = {values['Lzer']:.6g} H: no knee "
                     f"current gives it")]
        return []
