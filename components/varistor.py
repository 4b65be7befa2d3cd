"""Metal-oxide varistor: the paper's linear equivalent and a power-law clamp."""

from __future__ import annotations

from circuitsim.component import Branch, OnePort, Param, register, sp


@register("varistor_rc")
class VaristorRC(OnePort):
    """Varistor below its rated voltage (Kim & Kim): R in series with C.

    v = R i + v_C, i = C dv_C/dt.

    Parameters
    ----------
    R : [ohm] leakage resistance (500 Mohm for S08K20)
    C : [F] capacitance
    """

    branches = (Branch("p", "n", "X"),)
    R = Param("ohm", "series (leakage) resistance", positive=True)
    C = Param("F", "capacitance", positive=True)

    def equations(self, x):
        vc = x.var("vc")
        return [x.v - self.R * x.i - vc, x.i - self.C * x.der(vc)]

    def energy(self, x):
        return self.C * x.vc**2 / 2


@register("varistor")
class Varistor(OnePort):
    """Power-law clamp in parallel with its capacitance.

    i = C dv/dt + I_ref * sinh-like clamp: i_clamp = I_ref * sign(v) * |v / V_ref|^alpha.
    Written as I_ref * v/V_ref * (v^2/V_ref^2 + eps)^((alpha-1)/2) so it stays smooth at 0.

    Parameters
    ----------
    V_ref : [V] varistor voltage at the reference current (e.g. 33 V for S08K20)
    I_ref : [A] reference current (1 mA in datasheets)
    alpha : [1] nonlinearity exponent (20-40 for metal oxide)
    C : [F] capacitance
    """

    branches = (Branch("p", "n", "C"),)
    V_ref = Param("V", "varistor voltage at I_ref", positive=True)
    I_ref = Param("A", "reference current", default=1e-3, positive=True)
    alpha = Param("1", "nonlinearity exponent", default=30.0, positive=True)
    C = Param("F", "capacitance", positive=True)

    def equations(self, x):
        u = x.v / self.V_ref
        clamp = self.I_ref * u * (u**2 + sp.Float(1e-12)) ** ((self.alpha - 1) / 2)
        return [x.i - self.C * x.der(x.v) - clamp]

    def energy(self, x):
        return self.C * x.v**2 / 2
