"""Rotational and translational mechanics: inertia/mass, dampers, friction, cogging, supports.

Every one-flange element acts between its flange and the fixed reference; tau (or f) is the
flow into the element's flange, so the shaft receives -tau.
"""

from __future__ import annotations

from circuitsim.component import Branch, OneFlange, OneTFlange, Param, RecordList, register, sp


def _stribeck(w, f_brk, f_c, w_brk, b):
    """Smooth friction (ModelingToolkitStandardLibrary / Simscape form).

    Stribeck bump of height f_brk - f_c peaking at w_st = sqrt(2) w_brk, Coulomb part
    f_c tanh(w / w_coul) with w_coul = w_brk / 10, viscous b w. Smooth, so the Jacobian is
    continuous at w = 0.
    """
    w_st = w_brk * sp.sqrt(2)
    scale = sp.sqrt(2 * sp.E) * (f_brk - f_c)
    return scale * sp.exp(-((w / w_st) ** 2)) * w / w_st + f_c * sp.tanh(w / (w_brk / 10)) + b * w


@register("inertia")
class Inertia(OneFlange):
    """Rotor inertia: J dw/dt = tau.

    Parameters
    ----------
    J : [kg*m^2] moment of inertia
    w0 : [rad/s] initial speed
    phi0 : [rad] initial angle
    """

    branches = (Branch("shaft", None, "C"),)
    J = Param("kg*m^2", "moment of inertia", positive=True)
    w0 = Param("rad/s", "initial speed", default=0.0)
    phi0 = Param("rad", "initial angle", default=0.0)

    def equations(self, x):
        return [self.J * x.der(x.w) - x.tau]

    def initial(self, x):
        return {x.w: self.w0, x.shaft.phi: self.phi0}

    def energy(self, x):
        return self.J * x.w**2 / 2


@register("damper")
class Damper(OneFlange):
    """Viscous friction: tau = b w.

    Parameters
    ----------
    b : [N*m*s/rad] viscous coefficient
    """

    branches = (Branch("shaft", None, "R"),)
    b = Param("N*m*s/rad", "viscous coefficient", nonnegative=True)

    def equations(self, x):
        return [x.tau - self.b * x.w]


@register("friction")
class Friction(OneFlange):
    """Breakaway + Coulomb + viscous friction, smooth: tau = stribeck(w) (see _stribeck).

    Parameters
    ----------
    tau_brk : [N*m] breakaway torque (>= tau_c)
    tau_c : [N*m] Coulomb torque
    w_brk : [rad/s] breakaway velocity (smaller is sharper and stiffer)
    b : [N*m*s/rad] viscous coefficient
    """

    branches = (Branch("shaft", None, "R"),)
    tau_brk = Param("N*m", "breakaway torque", default="tau_c", nonnegative=True)
    tau_c = Param("N*m", "Coulomb torque", nonnegative=True)
    w_brk = Param("rad/s", "breakaway velocity", default=0.1, positive=True)
    b = Param("N*m*s/rad", "viscous coefficient", default=0.0, nonnegative=True)

    def equations(self, x):
        return [x.tau - _stribeck(x.w, self.tau_brk, self.tau_c, self.w_brk, self.b)]


COGGING = {
    "order": Param("1", "periods per shaft revolution", positive=True),
    "amplitude": Param("N*m", "torque amplitude"),
    "phase": Param("rad", "phase", default=0.0),
}


@register("cogging")
class Cogging(OneFlange):
    """Detent torque of the rotor angle: the shaft receives sum_h T_h sin(order_h phi + phase_h).

    Parameters
    ----------
    harmonics : list of {order [1], amplitude [N*m], phase [rad]} (order 1 is unbalance)
    """

    harmonics = RecordList("cogging harmonics of the rotor angle", COGGING)

    def equations(self, x):
        phi = x.shaft.phi
        torque = sum((h["amplitude"] * sp.sin(h["order"] * phi + h["phase"])
                      for h in self.harmonics), sp.Integer(0))
        return [x.tau + torque]


@register("fixed")
class Fixed(OneFlange):
    """Holds a shaft still: w = 0."""

    branches = (Branch("shaft", None, "V"),)

    def equations(self, x):
        return [x.w]


@register("mass")
class Mass(OneTFlange):
    """Sliding mass: m dv/dt = f.

    Parameters
    ----------
    m : [kg] mass
    v0 : [m/s] initial speed
    x0 : [m] initial position
    """

    branches = (Branch("flange", None, "C"),)
    m = Param("kg", "mass", positive=True)
    v0 = Param("m/s", "initial speed", default=0.0)
    x0 = Param("m", "initial position", default=0.0)

    def equations(self, x):
        return [self.m * x.der(x.v) - x.f]

    def initial(self, x):
        return {x.v: self.v0, x.flange.x: self.x0}

    def energy(self, x):
        return self.m * x.v**2 / 2


@register("tdamper")
class TDamper(OneTFlange):
    """Translational viscous friction: f = d v.

    Parameters
    ----------
    d : [N*s/m] viscous coefficient
    """

    branches = (Branch("flange", None, "R"),)
    d = Param("N*s/m", "viscous coefficient", nonnegative=True)

    def equations(self, x):
        return [x.f - self.d * x.v]


@register("tfriction")
class TFriction(OneTFlange):
    """Translational breakaway + Coulomb + viscous friction (smooth, as ``friction``).

    Parameters
    ----------
    f_brk : [N] breakaway force
    f_c : [N] Coulomb force
    v_brk : [m/s] breakaway velocity
    d : [N*s/m] viscous coefficient
    """

    branches = (Branch("flange", None, "R"),)
    f_brk = Param("N", "breakaway force", default="f_c", nonnegative=True)
    f_c = Param("N", "Coulomb force", nonnegative=True)
    v_brk = Param("m/s", "breakaway velocity", default=1e-3, positive=True)
    d = Param("N*s/m", "viscous coefficient", default=0.0, nonnegative=True)

    def equations(self, x):
        return [x.f - _stribeck(x.v, self.f_brk, self.f_c, self.v_brk, self.d)]
