"""Controlled sources by their SPICE names, coupled inductors and the ideal transformer.

E (VCVS), G (VCCS) sense a voltage between the control pins cp, cn, which draw no current.
F (CCCS), H (CCVS) sense the current flowing into cp and out of cn through a zero-volt
branch (SPICE names a 0 V source instead; wire these pins where that source would be).
Output sign as SPICE: a current source's current flows from p through it to n.
"""

from __future__ import annotations

from circuitsim.component import Branch, Component, Param, Pin, register, sp


class _Controlled(Component):
    """Output pins p, n and control pins cp, cn; v = p.v - n.v, i enters at p."""

    ports = (Pin("p"), Pin("n"), Pin("cp"), Pin("cn"))

    def bind(self, x):
        x.v = x.p.v - x.n.v
        x.i = x.p.i
        return [x.p.i + x.n.i]


class _VoltageSensed(_Controlled):
    branches = (Branch("p", "n", "X"),)

    def bind(self, x):
        eqs = super().bind(x)
        x.vc = x.cp.v - x.cn.v
        return [*eqs, x.cp.i, x.cn.i]


class _CurrentSensed(_Controlled):
    branches = (Branch("p", "n", "X"), Branch("cp", "cn", "X"))

    def bind(self, x):
        eqs = super().bind(x)
        x.ic = x.cp.i
        return [*eqs, x.cp.i + x.cn.i, x.cp.v - x.cn.v]


@register("E", "vcvs")
class Vcvs(_VoltageSensed):
    """Voltage-controlled voltage source (SPICE E): v(p, n) = gain v(cp, cn).

    Parameters
    ----------
    gain : [1] voltage gain
    """

    gain = Param("V/V", "voltage gain")

    def equations(self, x):
        return [x.v - self.gain * x.vc]


@register("G", "vccs")
class Vccs(_VoltageSensed):
    """Voltage-controlled current source (SPICE G): i = gain v(cp, cn), from p through it to n.

    Parameters
    ----------
    gain : [A/V] transconductance
    """

    gain = Param("A/V", "transconductance")

    def equations(self, x):
        return [x.i - self.gain * x.vc]


@register("F", "cccs")
class Cccs(_CurrentSensed):
    """Current-controlled current source (SPICE F): i = gain i_c, i_c entering cp.

    Parameters
    ----------
    gain : [1] current gain
    """

    gain = Param("A/A", "current gain")

    def equations(self, x):
        return [x.i - self.gain * x.ic]


@register("H", "ccvs")
class Ccvs(_CurrentSensed):
    """Current-controlled voltage source (SPICE H): v(p, n) = gain i_c, i_c entering cp.

    Parameters
    ----------
    gain : [ohm] transresistance
    """

    gain = Param("ohm", "transresistance")

    def equations(self, x):
        return [x.v - self.gain * x.ic]


class _TwoWinding(Component):
    """Windings p1-n1 and p2-n2; v1, i1, v2, i2 with currents entering p1 and p2."""

    ports = (Pin("p1"), Pin("n1"), Pin("p2"), Pin("n2"))

    def bind(self, x):
        x.v1 = x.p1.v - x.n1.v
        x.v2 = x.p2.v - x.n2.v
        x.i1 = x.p1.i
        x.i2 = x.p2.i
        return [x.p1.i + x.n1.i, x.p2.i + x.n2.i]


@register("K", "coupled_inductors")
class CoupledInductors(_TwoWinding):
    """Two magnetically coupled windings (SPICE L1, L2 and K): v1 = L1 i1' + M i2' + R1 i1,
    v2 = M i1' + L2 i2' + R2 i2, M = k sqrt(L1 L2). Dots at p1 and p2.

    The stored energy L1 i1^2/2 + M i1 i2 + L2 i2^2/2 is never negative for 0 <= k <= 1; at
    k = 1 (no leakage) the two currents share one flux and only their combination is a state.

    Parameters
    ----------
    L1, L2 : [H] self inductances
    k : [1] coupling coefficient, 0..1
    R1, R2 : [ohm] winding resistances, default 0
    i10, i20 : [A] initial currents, default 0
    """

    branches = (Branch("p1", "n1", "L"), Branch("p2", "n2", "L"))
    L1 = Param("H", "inductance of winding 1", positive=True)
    L2 = Param("H", "inductance of winding 2", positive=True)
    k = Param("1", "coupling coefficient", nonnegative=True, maximum=1.0)
    R1 = Param("ohm", "resistance of winding 1", default=0.0, nonnegative=True)
    R2 = Param("ohm", "resistance of winding 2", default=0.0, nonnegative=True)
    i10 = Param("A", "initial current of winding 1", default=0.0)
    i20 = Param("A", "initial current of winding 2", default=0.0)

    def _m(self):
        return self.k * sp.sqrt(self.L1 * self.L2)

    def equations(self, x):
        m = self._m()
        d1, d2 = x.der(x.i1), x.der(x.i2)
        return [x.v1 - self.L1 * d1 - m * d2 - self.R1 * x.i1,
                x.v2 - m * d1 - self.L2 * d2 - self.R2 * x.i2]

    def initial(self, x):
        return {x.i1: self.i10, x.i2: self.i20}

    def energy(self, x):
        return self.L1 * x.i1**2 / 2 + self._m() * x.i1 * x.i2 + self.L2 * x.i2**2 / 2


@register("transformer", "ideal_transformer")
class IdealTransformer(_TwoWinding):
    """Ideal transformer, turns ratio n = N1/N2: v1 = n v2, i2 = -n i1 (no loss, no storage;
    dots at p1 and p2). Each side needs its own path to ground.

    Parameters
    ----------
    n : [1] turns ratio N1/N2
    """

    branches = (Branch("p1", "n1", "X"), Branch("p2", "n2", "X"))
    n = Param("1", "turns ratio N1/N2", positive=True)

    def equations(self, x):
        return [x.v1 - self.n * x.v2, x.i2 + self.n * x.i1]
