"""Electromechanical coupling: back-EMF with rotor-angle harmonics and its torque."""

from __future__ import annotations

from circuitsim.component import Converter, Option, Param, RecordList, register, sp

HARMONIC = {
    "order": Param("1", "harmonic order per shaft revolution", positive=True),
    "slope": Param("V*s/rad", "amplitude per unit speed", default=0.0),
    "offset": Param("V", "amplitude at zero speed", default=0.0),
    "phase": Param("rad", "phase", default=0.0),
}


@register("emf", "BackEMF")
class BackEMF(Converter):
    """Back-EMF coupling with ripple locked to the rotor angle phi (phi' = w).

    v = k_e w + e0 + sum_h (slope_h w + offset_h) sin(order_h phi + phase_h),
    tau = -(k_t + [ripple_torque] sum_h slope_h sin(order_h phi + phase_h)) i.
    It conserves energy only when k_e = k_t, e0 = 0, offsets are 0 and ripple_torque is on.

    Parameters
    ----------
    k_t : [N*m/A] torque constant
    k_e : [V*s/rad] back-EMF constant, default k_t
    e0 : [V] constant EMF offset, default 0
    harmonics : list of {order [1], slope [V*s/rad], offset [V], phase [rad]}
    ripple_torque : bool, the harmonics also act on the torque (energy-consistent)

    Ports
    -----
    p, n : electrical; current i enters at p.
    shaft : rotational; tau is the torque into the EMF's flange (the shaft receives -tau).
    """

    k_t = Param("N*m/A", "torque constant", positive=True)
    k_e = Param("V*s/rad", "back-EMF constant", default="k_t", positive=True)
    e0 = Param("V", "constant EMF offset", default=0.0)
    harmonics = RecordList("back-EMF ripple harmonics of the rotor angle", HARMONIC)
    ripple_torque = Option("harmonics also produce torque (energy-consistent)", True)

    def equations(self, x):
        phi = x.shaft.phi
        waves = [sp.sin(h["order"] * phi + h["phase"]) for h in self.harmonics]
        ripple = sum((((h["slope"] * x.w + h["offset"]) * s)
                      for h, s in zip(self.harmonics, waves, strict=True)), sp.Integer(0))
        k_torque = self.k_t
        if self.ripple_torque:
            k_torque = k_torque + sum((h["slope"] * s for h, s in
                                       zip(self.harmonics, waves, strict=True)), sp.Integer(0))
        return [x.v - self.k_e * x.w - self.e0 - ripple, x.tau + k_torque * x.i]

    def warnings(self, values):
        out = []
        k_t, k_e = values["k_t"], values["k_e"]
        if abs(k_t - k_e) > 1e-9 * max(abs(k_t), abs(k_e)):
            out.append(f"k_t = {k_t:.6g} N*m/A differs from k_e = {k_e:.6g} V*s/rad: the "
                       f"coupling does not conserve energy (mechanical power = "
                       f"{k_t / k_e:.3g} x the electrical power converted)")
        if values["harmonics"] and not values["ripple_torque"]:
            out.append("ripple_torque is off: the EMF harmonics exchange no torque, so the "
                       "coupling does not conserve energy")
        return out
