"""Brushless (BLDC / PMSM) machine parts and drives, after Kapun et al. 2008.

A three-phase motor is assembled in the netlist from parts: per phase an inductor with its
series resistance and a ``phase_emf`` in series, the three in wye with a floating neutral, all
on one rotor shaft with ``inertia``, ``damper``, ``friction`` and ``cogging`` (cogging from the
rotor self-inductance harmonics, and the 1-per-turn unbalance as a cogging order 1). Drives:
``foc_drive`` imposes the phase currents of a field-oriented current loop, ``pwm_leg`` is one
half-bridge of a voltage inverter with a smooth switch.

Kapun's notation: the mutual inductance of phase i with a fictitious rotor winding carrying
i_r = 1 A is L_ir(theta) = sum_k [a_k cos(k x_i) + b_k sin(k x_i)] with the electrical angle
x_i = p theta - shift_i, so the back-EMF constant is K_i = i_r dL_ir/dtheta [V*s/rad].
"""

from __future__ import annotations

from circuitsim.component import (
    Branch,
    Component,
    Converter,
    Expression,
    Flange,
    OnePort,
    Param,
    Pin,
    Pmod,
    RecordList,
    Signal,
    register,
    sp,
)

FOURIER = {
    "order": Param("1", "harmonic order k of the electrical angle", positive=True, integer=True),
    "a": Param("H", "cosine coefficient L_rak of L_ir (Kapun: L_irak)", default=0.0),
    "b": Param("H", "sine coefficient L_rbk of L_ir (Kapun: L_irbk)", default=0.0),
}


def emf_constant(phi, p, shift, i_r, harmonics):
    """i_r dL_ir/dtheta [V*s/rad] of L_ir = sum_k a_k cos(k x) + b_k sin(k x), x = p phi - shift."""
    x = p * phi - shift
    return i_r * sum((h["order"] * p * (-h["a"] * sp.sin(h["order"] * x)
                                        + h["b"] * sp.cos(h["order"] * x))
                      for h in harmonics), sp.Integer(0))


@register("phase_emf")
class PhaseEMF(Converter):
    """Back-EMF of one phase, Fourier series in the electrical angle: v = K(phi) w, tau = -K i.

    K(phi) = i_r dL_ir/dphi with L_ir = sum_k [a_k cos(k(p phi - shift)) + b_k sin(...)]. The
    same K gives the voltage and the torque, so the coupling conserves energy (v i = -tau w).

    Parameters
    ----------
    p : [1] pole pairs (electrical angle = p * shaft angle)
    shift : [rad] electrical phase displacement of this phase (0, 2 pi/3, 4 pi/3)
    i_r : [A] fictitious rotor current (Kapun: 1 A)
    harmonics : list of {order [1], a [H], b [H]}

    Ports
    -----
    p, n : electrical; current i enters at p.
    shaft : rotational; tau is the torque into the EMF's flange (the shaft receives K i).
    """

    pp = Param("1", "pole pairs", positive=True, integer=True)
    shift = Param("rad", "electrical phase displacement", default=0.0)
    i_r = Param("A", "fictitious rotor current", default=1.0, positive=True)
    harmonics = RecordList("Fourier coefficients of L_ir in the electrical angle", FOURIER)

    def equations(self, x):
        k = emf_constant(x.shaft.phi, self.pp, self.shift, self.i_r, self.harmonics)
        x.K = k
        return [x.v - k * x.w, x.tau + k * x.i]


@register("foc_drive")
class FocDrive(Component):
    """Ideal field-oriented current drive: phase currents along the fundamental back-EMF.

    i_j = I_q (-a_1 sin x_j + b_1 cos x_j) / |L_1|, x_j = p phi - (j-1) 2 pi/3, with
    I_q = 2 T_ref / (3 p i_r |L_1|), so the fundamental mutual torque is T_ref. Currents
    i_a, i_b leave pins a, b; pin c is held at the potential of n (a three-wire drive has two
    independent currents; the third returns through c).

    Parameters
    ----------
    T_ref : [N*m] torque reference (value or waveform)
    pp : [1] pole pairs
    a1, b1 : [H] fundamental coefficients of L_1r (Kapun: L_1ra1, L_1rb1)
    i_r : [A] fictitious rotor current

    Ports
    -----
    a, b, c : electrical, to the phase terminals; n : electrical reference of the drive.
    shaft : rotational, angle sensor only (no torque).
    """

    ports = (Pin("a"), Pin("b"), Pin("c"), Pin("n"), Flange("shaft"))
    branches = (Branch("a", "n", "I"), Branch("b", "n", "I"), Branch("c", "n", "V"),
                Branch("shaft", None, "X"))
    T_ref = Signal("N*m", "torque reference")
    pp = Param("1", "pole pairs", positive=True, integer=True)
    a1 = Param("H", "fundamental cosine coefficient of L_1r")
    b1 = Param("H", "fundamental sine coefficient of L_1r", default=0.0)
    i_r = Param("A", "fictitious rotor current", default=1.0, positive=True)

    def equations(self, x):
        mag = sp.sqrt(self.a1**2 + self.b1**2)
        i_q = 2 * self.T_ref / (3 * self.pp * self.i_r * mag)
        refs = []
        for j in range(2):
            xj = self.pp * x.shaft.phi - j * 2 * sp.pi / 3
            refs.append(i_q * (-self.a1 * sp.sin(xj) + self.b1 * sp.cos(xj)) / mag)
        x.i_q = i_q
        return [x.a.i + refs[0], x.b.i + refs[1], x.c.v - x.n.v,
                x.a.i + x.b.i + x.c.i + x.n.i, x.shaft.tau]


@register("pwm_leg")
class PwmLeg(OnePort):
    """Inverter half-bridge, smooth switch: v = s (V_dc+ - n.v), s = (1 + tanh((m - c)/eps))/2.

    The leg connects its output p to the DC rail ``dc`` (s = 1) or to n (s = 0); c(t) is a
    triangle carrier in [-1, 1] at f_sw, m the modulating signal (sinusoidal PWM:
    m = M sin(p rotor.phi - shift + delta)). Lossless: the rail current is s times the output
    current, so v_p i_p + v_dc i_dc + v_n i_n = 0.

    Parameters
    ----------
    m : [1] modulating signal in [-1, 1] (expression of t, parameters, circuit quantities)
    f_sw : [Hz] carrier (switching) frequency
    eps : [1] switch smoothing width in carrier units (smaller is sharper and stiffer)

    Ports
    -----
    p : electrical, the leg output; n : electrical, DC minus rail; dc : electrical, DC plus rail.
    """

    ports = (Pin("p"), Pin("n"), Pin("dc"))
    branches = (Branch("p", "n", "X"), Branch("dc", "n", "X"))
    m = Expression("1", "modulating signal")
    f_sw = Param("Hz", "switching frequency", positive=True)
    eps = Param("1", "switch smoothing width", default=0.02, positive=True)

    def bind(self, x):
        x.v = x.p.v - x.n.v
        x.i = x.p.i
        return []

    def equations(self, x):
        frac = Pmod(x.t * self.f_sw, sp.Integer(1))
        carrier = sp.Piecewise((4 * frac - 1, frac < sp.Rational(1, 2)), (3 - 4 * frac, True))
        s = (1 + sp.tanh((self.m - carrier) / self.eps)) / 2
        x.s = s
        return [x.v - s * (x.dc.v - x.n.v), x.dc.i + s * x.p.i,
                x.p.i + x.dc.i + x.n.i]
