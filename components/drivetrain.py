"""Mechanics between bodies: springs, dampers and gears between two flanges; speed and
position sources.

Flanges a and b; tau (or f) is the flow into each flange of the element, so with a twist
phi_rel = a.phi - b.phi a spring takes tau = c phi_rel from shaft a and gives it to shaft b.
"""

from __future__ import annotations

from circuitsim.component import (
    Branch,
    Component,
    Flange,
    OneFlange,
    OneTFlange,
    Param,
    Signal,
    TFlange,
    register,
    sp,
)


class TwoFlange(Component):
    """Rotational flanges a, b: w_rel = a.w - b.w, phi_rel = a.phi - b.phi, tau = torque
    into flange a (flange b takes -tau)."""

    ports = (Flange("a"), Flange("b"))

    def bind(self, x):
        x.w_rel = x.a.w - x.b.w
        x.tau = x.a.tau
        return [x.a.tau + x.b.tau]


class TwoTFlange(Component):
    """Translational flanges a, b: v_rel = a.v - b.v, f = force into flange a."""

    ports = (TFlange("a"), TFlange("b"))

    def bind(self, x):
        x.v_rel = x.a.v - x.b.v
        x.f = x.a.f
        return [x.a.f + x.b.f]


@register("spring", "rotational_spring")
class Spring(TwoFlange):
    """Torsional spring between two shafts: tau = c (phi_rel - phi_rel0).

    Parameters
    ----------
    c : [N*m/rad] stiffness
    phi_rel0 : [rad] unstretched twist, default 0
    """

    branches = (Branch("a", "b", "L"),)
    c = Param("N*m/rad", "torsional stiffness", positive=True)
    phi_rel0 = Param("rad", "unstretched twist", default=0.0)

    def equations(self, x):
        x.phi_rel = x.a.phi - x.b.phi
        return [x.tau - self.c * (x.phi_rel - self.phi_rel0)]

    def energy(self, x):
        return self.c * (x.a.phi - x.b.phi - self.phi_rel0) ** 2 / 2


@register("shaft_damper", "rotational_damper")
class ShaftDamper(TwoFlange):
    """Viscous damper between two shafts: tau = d w_rel.

    Parameters
    ----------
    d : [N*m*s/rad] damping coefficient
    """

    branches = (Branch("a", "b", "R"),)
    d = Param("N*m*s/rad", "damping coefficient", nonnegative=True)

    def equations(self, x):
        return [x.tau - self.d * x.w_rel]


@register("spring_damper")
class SpringDamper(TwoFlange):
    """Spring and damper in parallel between two shafts (a flexible coupling):
    tau = c (phi_rel - phi_rel0) + d w_rel.

    Parameters
    ----------
    c : [N*m/rad] stiffness
    d : [N*m*s/rad] damping coefficient
    phi_rel0 : [rad] unstretched twist, default 0
    """

    branches = (Branch("a", "b", "L"),)
    c = Param("N*m/rad", "torsional stiffness", positive=True)
    d = Param("N*m*s/rad", "damping coefficient", nonnegative=True)
    phi_rel0 = Param("rad", "unstretched twist", default=0.0)

    def equations(self, x):
        x.phi_rel = x.a.phi - x.b.phi
        return [x.tau - self.c * (x.phi_rel - self.phi_rel0) - self.d * x.w_rel]

    def energy(self, x):
        return self.c * (x.a.phi - x.b.phi - self.phi_rel0) ** 2 / 2


@register("gear", "ideal_gear")
class IdealGear(Component):
    """Ideal gear: a.w = ratio b.w; power passes with efficiency eta (tau_b = -eta ratio tau_a
    while a drives, -ratio tau_a / eta while b drives; lossless at eta = 1).

    Parameters
    ----------
    ratio : [1] speed ratio a.w / b.w (a reduction gear has ratio > 1)
    eta : [1] efficiency, 0 < eta <= 1, default 1
    """

    ports = (Flange("a"), Flange("b"))
    branches = (Branch("a", "b", "X"),)
    ratio = Param("1", "speed ratio a.w / b.w, negative when the direction reverses",
                  nonzero=True)
    eta = Param("1", "efficiency", default=1.0, positive=True, maximum=1.0)

    def equations(self, x):
        x.tau = x.a.tau
        driving = x.a.tau * x.a.w >= 0  # power flows from shaft a into the gear
        tau_b = sp.Piecewise((-self.eta * self.ratio * x.a.tau, driving),
                             (-self.ratio * x.a.tau / self.eta, True))
        return [x.a.w - self.ratio * x.b.w, x.b.tau - tau_b]


@register("speed", "speed_source")
class SpeedSource(OneFlange):
    """Speed source: the shaft turns at W(t) against the fixed reference, whatever the torque.

    Parameters
    ----------
    W : [rad/s] value or waveform
    """

    branches = (Branch("shaft", None, "V"),)
    W = Signal("rad/s", "imposed speed")

    def equations(self, x):
        return [x.w - self.W]


@register("angle", "angle_source")
class AngleSource(OneFlange):
    """Position source: the shaft angle follows Phi(t) (from phi = 0 at t = 0 for a
    consistent start).

    Parameters
    ----------
    Phi : [rad] value or waveform
    """

    branches = (Branch("shaft", None, "V"),)
    Phi = Signal("rad", "imposed angle")

    def equations(self, x):
        return [x.shaft.phi - self.Phi]


@register("tspring", "translational_spring")
class TSpring(TwoTFlange):
    """Linear spring between two flanges: f = c (x_rel - s0), x_rel = a.x - b.x.

    Parameters
    ----------
    c : [N/m] stiffness
    s0 : [m] unstretched offset, default 0
    """

    branches = (Branch("a", "b", "L"),)
    c = Param("N/m", "stiffness", positive=True)
    s0 = Param("m", "unstretched offset", default=0.0)

    def equations(self, x):
        x.x_rel = x.a.x - x.b.x
        return [x.f - self.c * (x.x_rel - self.s0)]

    def energy(self, x):
        return self.c * (x.a.x - x.b.x - self.s0) ** 2 / 2


@register("tspring_damper")
class TSpringDamper(TwoTFlange):
    """Spring and damper in parallel between two flanges: f = c (x_rel - s0) + d v_rel.

    Parameters
    ----------
    c : [N/m] stiffness
    d : [N*s/m] damping coefficient
    s0 : [m] unstretched offset, default 0
    """

    branches = (Branch("a", "b", "L"),)
    c = Param("N/m", "stiffness", positive=True)
    d = Param("N*s/m", "damping coefficient", nonnegative=True)
    s0 = Param("m", "unstretched offset", default=0.0)

    def equations(self, x):
        x.x_rel = x.a.x - x.b.x
        return [x.f - self.c * (x.x_rel - self.s0) - self.d * x.v_rel]

    def energy(self, x):
        return self.c * (x.a.x - x.b.x - self.s0) ** 2 / 2


@register("tspeed", "velocity_source")
class VelocitySource(OneTFlange):
    """Velocity source: the flange moves at V(t) against the fixed reference.

    Parameters
    ----------
    V : [m/s] value or waveform
    """

    branches = (Branch("flange", None, "V"),)
    V = Signal("m/s", "imposed velocity")

    def equations(self, x):
        return [x.v - self.V]


@register("tposition", "position_source")
class PositionSource(OneTFlange):
    """Position source: the flange position follows X(t) (from x = 0 at t = 0 for a
    consistent start).

    Parameters
    ----------
    X : [m] value or waveform
    """

    branches = (Branch("flange", None, "V"),)
    X = Signal("m", "imposed position")

    def equations(self, x):
        return [x.flange.x - self.X]


@register("clutch", "brake_clutch")
class Clutch(TwoFlange):
    """Friction clutch between two shafts (a brake when b is ``fixed``), regularised Coulomb
    friction: tau = mu fn(t) tanh(w_rel / w_slip). It slips while |w_rel| >> w_slip and
    (nearly) sticks below it: sticking is a creep of w_rel ~ w_slip tau / (mu fn), not
    exact adhesion (for that, ``stick_clutch``).

    Parameters
    ----------
    fn : [N*m] normal-force torque capacity (friction radius times normal force), value or
        waveform (0 releases the clutch)
    mu : [1] friction coefficient, default 1
    w_slip : [rad/s] regularisation speed, default 1e-3
    """

    branches = (Branch("a", "b", "R"),)
    fn = Signal("N*m", "torque capacity times friction radius")
    mu = Param("1", "friction coefficient", default=1.0, nonnegative=True)
    w_slip = Param("rad/s", "regularisation speed", default=1e-3, positive=True)

    def equations(self, x):
        return [x.tau - self.mu * self.fn * sp.tanh(x.w_rel / self.w_slip)]


@register("backlash", "elasto_backlash")
class Backlash(TwoFlange):
    """Spring-damper with a gap (Modelica's ElastoBacklash): no torque while |phi_rel -
    phi_rel0| < gap/2, tau = c (phi_rel - phi_rel0 -+ gap/2) + d w_rel in contact (the
    damping never pulls the sides together). A gap of at most GAP_EPS is the plain
    spring-damper, as in Modelica: with no play there are no sides to part.

    Parameters
    ----------
    gap : [rad] total play
    c : [N*m/rad] contact stiffness
    d : [N*m*s/rad] contact damping, default 0
    phi_rel0 : [rad] the twist at the middle of the play (a prestressed coupling's
        unstretched twist), default 0
    """

    GAP_EPS = 1e-10  # [rad] Modelica's bEps
    branches = (Branch("a", "b", "L"),)
    gap = Param("rad", "total play", nonnegative=True)
    c = Param("N*m/rad", "contact stiffness", positive=True)
    d = Param("N*m*s/rad", "contact damping", default=0.0, nonnegative=True)
    phi_rel0 = Param("rad", "twist at the middle of the play", default=0.0)

    def equations(self, x):
        x.phi_rel = x.a.phi - x.b.phi
        h, twist = self.gap / 2, x.phi_rel - self.phi_rel0
        push = sp.Piecewise((self.c * (twist - h) + self.d * x.w_rel, twist > h),
                            (self.c * (twist + h) + self.d * x.w_rel, twist < -h),
                            (0, True))
        # in contact the damper may slow the approach but never glue the sides; a relation
        # of parameters alone is evaluated as written (no event)
        tau = sp.Piecewise((self.c * twist + self.d * x.w_rel, self.gap <= self.GAP_EPS),
                           (sp.Max(push, 0), twist > h), (sp.Min(push, 0), True))
        return [x.tau - tau]
