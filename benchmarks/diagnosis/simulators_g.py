"""Motor G of the diagnosis benchmark: a hand-written scipy model of a 24 V, 150 W class
permanent-magnet brushed DC hoist motor. The rotor drives a winch drum through a flexible jaw
coupling (a torsional spring and damper) and a rigid 10:1 gearbox; a hanging load pulls the
drum backwards with a constant gravity torque, declared in the netlist.

No circuitsim import: an independent simulator (the fifth of the benchmark), written from the
physics for netlists/motor_g_motor.yaml, motor_g.yaml and motor_g_slow.yaml.

Base state (6 numbers) z = [i, w_r, a_r, q, w_h, a_d], then the states effects add:

    i    armature current [A]
    w_r  rotor speed [rad/s],      a_r  rotor angle [rad]
    q    twist of the coupling, rotor angle minus pinion angle [rad]
    w_h  pinion (gearbox input) speed [rad/s]; the drum turns at w_d = w_h / N
    a_d  drum angle [rad]

Equations (lifting is positive rotation):

    dpsi/di di/dt = v_arm - R(t) i - e,          e = k w_r (+ an EMF harmonic)
    Jm dw_r/dt    = k i - bm w_r - T_K + (rotor-side extras)
    dq/dt         = w_r - w_h,                    T_K = c q + d (w_r - w_h)
    Jp dw_h/dt    = T_K + T_drum / N,             Jp = Jh + Jd / N^2
    T_drum        = -Tg - bd w_d + (drum-side extras)

Effects (``fx`` keys, SI, all off by default) -- the catalog's:

    Rs        [ohm]   an internal resistance of the supply
    Rser      [ohm]   a resistance in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   R(t) = R (1 + alpha t)
    warmup    (rise, tau [s]): R(t) = R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf_h     (order, a, b): e gains w_r (a sin(order a_r) + b cos(order a_r))
    cog       {node: [(order, a, b), ...]}: the node (rotor or drum) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {node: Fc}: Coulomb friction Fc tanh(w / 0.01) against the node's motion
    visc      {node: b}: extra viscous friction on the node
    offset    {node: F}: a constant torque F the node receives
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads
              g y + o, y the probe seen through the first-order Pade stage of a delay tau
              (2 s - x with tau/2 ds/dt = x - s, s(0) = 0); gain is the factor
    (an inertia off: pass motor parameters ``p`` with another Jd)

and outside the catalog:

    hall_sat  Is [A]: the Hall current sensor's core saturates: it reads Is tanh(i / Is)
    rdc       (fn [Hz], zeta): the speed probe is a resolver-to-digital converter's velocity,
              the integrator of a type-II tracking loop: th_hat' = v_hat + 2 zeta wn err,
              v_hat' = wn^2 err, err = a_r - th_hat (a second-order low-pass of the speed)
    bus       (Vs [V], Rs [ohm], C [F], Vclamp [V], Rbr [ohm]): the bridge is fed from a
              capacitor bank C charged through a diode and Rs from the supply Vs; a brake
              chopper bleeds (Vbus - Vclamp)/Rbr above Vclamp. The command is a duty
              d = u / Vs: the armature sees d Vbus, the bank gives d i. Regeneration (u i < 0)
              pumps the bus above Vs
    reel      (m [kg], r0 [m], delta [m/turn], J0 [kg m^2]): the rope winds on itself (a cable
              reel): the radius is r0 + delta a_d / 2 pi; the load's pull m g r, and its
              inertia m r^2 on the drum (plus the drum's own J0), follow it, with the
              Lagrangian term m r r' w_d^2
    logbrush  (V1 [V], I1 [A]): a brush contact voltage V1 ln(1 + |i| / I1) sign(i), growing
              with the current like a carbon brush's film, not the catalog's constant drop
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_g_profile.csv"

#: declared values of motor G [SI] (motor_g_motor.yaml)
MOTOR_G: dict[str, float] = {
    "R": 0.35, "L": 0.4e-3, "k": 0.06, "Jm": 8e-5, "bm": 1e-5, "c": 20.0, "d": 6e-3,
    "Jh": 2e-5, "N": 10.0, "Jd": 0.012, "bd": 4e-3, "Tg": 2.943,
}
G0 = 9.81  # [m/s^2]
#: [rad/s] circuitsim's friction (w_brk 0.1) switches sign as tanh(w / 0.01)
W_SIGN = 0.01
#: [A] the catalog's brush drop switches sign as tanh(i / 1 mA)
I_SIGN = 1e-3
#: the fast regime's command [s, V] (motor_g.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.002, 0.0), (0.022, 24.0), (0.15, 24.0), (0.152, 12.0),
               (0.24, 12.0), (0.27, -6.0), (0.34, -6.0), (0.342, 2.0), (0.45, 2.0))
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.45), "slow": (1e3, 5.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
RTOL, ATOL = 1e-10, 1e-12


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t, u]: the command, linear between points, held after the last."""
    if regime == "fast":
        return np.asarray(FAST_POINTS, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


class _Model:
    """Motor G's right-hand side for one set of effects. Extra states are appended after the
    six base ones as the effects ask for them."""

    I, WR, AR, Q, WH, AD = range(6)

    def __init__(self, bp: np.ndarray, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.tb, self.ub = bp[:, 0].copy(), bp[:, 1].copy()
        self.fx, self.p = fx, p
        self.n = 6
        self.slots: dict[str, int] = {}
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.slots["delay:" + probe] = self._slot(1)
        if "rdc" in fx:
            self.slots["rdc"] = self._slot(2)
        if "bus" in fx:
            self.slots["bus"] = self._slot(1)
        self.cog = {n: list(v) for n, v in fx.get("cog", {}).items()}
        self.coul = dict(fx.get("coul", {}))
        self.visc = dict(fx.get("visc", {}))
        self.offs = dict(fx.get("offset", {}))

    def _slot(self, size: int) -> int:
        first = self.n
        self.n += size
        return first

    def x0(self) -> np.ndarray:
        z = np.zeros(self.n)
        if "bus" in self.fx:
            z[self.slots["bus"]] = self.fx["bus"][0]  # the bank starts charged to Vs
        return z

    def command(self, t: float) -> float:
        return float(np.interp(t, self.tb, self.ub))

    def node_torque(self, node: str, w: float, angle: float) -> float:
        """The extras a node (rotor or drum) receives, positive along lifting."""
        tq = self.offs.get(node, 0.0) - self.visc.get(node, 0.0) * w \
            - self.coul.get(node, 0.0) * math.tanh(w / W_SIGN)
        for order, a, b in self.cog.get(node, ()):
            tq += a * math.sin(order * angle) + b * math.cos(order * angle)
        return tq

    def resistance(self, t: float) -> float:
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        return r + fx.get("Rser", 0.0)

    def inductance(self, i: float) -> float:
        if "lsat" not in self.fx:
            return self.p["L"]
        ipar, ratio = self.fx["lsat"]
        return self.p["L"] * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))

    def __call__(self, t: float, z: np.ndarray) -> np.ndarray:
        p, fx = self.p, self.fx
        i, wr, ar, q, wh, ad = z[:6]
        n_gear = p["N"]
        wd = wh / n_gear
        dz = np.zeros_like(z)
        u = self.command(t)

        # --- the armature loop
        if "bus" in fx:
            vs, rs_bus, cb, vcl, rbr = fx["bus"]
            k_b = self.slots["bus"]
            vbus = z[k_b]
            duty = u / vs
            x = vs - vbus
            i_in = 0.5 * (x + math.sqrt(x * x + 1e-6)) / rs_bus  # the diode, smooth
            y = vbus - vcl
            i_br = 0.5 * (y + math.sqrt(y * y + 1e-6)) / rbr  # the brake chopper
            dz[k_b] = (i_in - i_br - duty * i) / cb
            v = duty * vbus
        else:
            v = u
        v -= fx.get("Rs", 0.0) * i
        v -= fx.get("Vb", 0.0) * math.tanh(i / I_SIGN)
        if "logbrush" in fx:
            v1, i1 = fx["logbrush"]
            v -= math.copysign(v1 * math.log1p(abs(i) / i1), i)
        emf = p["k"] * wr
        if "emf_h" in fx:
            order, a, b = fx["emf_h"]
            emf += wr * (a * math.sin(order * ar) + b * math.cos(order * ar))
        dz[0] = (v - self.resistance(t) * i - emf) / self.inductance(i)

        # --- rotor, coupling, pinion and drum
        t_k = p["c"] * q + p["d"] * (wr - wh)
        dz[1] = (p["k"] * i - p["bm"] * wr - t_k + self.node_torque("rotor", wr, ar)) / p["Jm"]
        dz[2] = wr
        dz[3] = wr - wh
        if "reel" in fx:
            m, r0, delta, j0 = fx["reel"]
            drdth = delta / (2.0 * math.pi)
            r = r0 + drdth * ad
            jd = j0 + m * r * r
            t_drum = -m * G0 * r - m * r * drdth * wd * wd
        else:
            jd = p["Jd"]
            t_drum = -p["Tg"]
        t_drum += -p["bd"] * wd + self.node_torque("drum", wd, ad)
        dz[4] = (t_k + t_drum / n_gear) / (p["Jh"] + jd / n_gear**2)
        dz[5] = wd

        # --- sensor states
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                k_s = self.slots["delay:" + probe]
                dz[k_s] = (self.raw_probe(probe, z) - z[k_s]) / (0.5 * s["delay"])
        if "rdc" in fx:
            fn, zeta = fx["rdc"]
            wn = 2.0 * math.pi * fn
            k_r = self.slots["rdc"]
            err = ar - z[k_r]
            dz[k_r] = z[k_r + 1] + 2.0 * zeta * wn * err
            dz[k_r + 1] = wn * wn * err
        return dz

    def raw_probe(self, probe: str, z: np.ndarray) -> Any:
        """The probe's physical quantity (before any sensor law) from a state (or states)."""
        if probe == "current":
            return z[0]
        if probe == "speed":
            return z[1]
        return z[4] / self.p["N"]


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None) -> dict[str, np.ndarray]:
    """Noise-free probes of motor G on ``t`` (default: the record grid), from rest, plus the
    command ``u``: current, speed (and load_speed in the slow regime)."""
    fx = dict(fx or {})
    p = dict(MOTOR_G if p is None else p)
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = _Model(bp, fx, p)
    # the command has kinks at its breakpoints: integrate between them, restarting there
    cuts = [float(t[0])] + [float(b) for b in bp[:, 0] if t[0] < b < t[-1]] + [float(t[-1])]
    z0 = model.x0()
    states = np.empty((model.n, t.size))
    h_max = 1.0 / REGIMES[regime][0]
    for k in range(len(cuts) - 1):
        a, b = cuts[k], cuts[k + 1]
        final = k == len(cuts) - 2
        mask = (t >= a) & (t <= b) if final else (t >= a) & (t < b)
        t_out = np.append(t[mask], b) if not final else t[mask]
        sol = None
        for method in ("LSODA", "Radau"):
            sol = solve_ivp(model, (a, b), z0, method=method, t_eval=t_out, rtol=RTOL,
                            atol=ATOL, max_step=h_max)
            if sol.success and np.isfinite(sol.y).all():
                break
        if sol is None or not (sol.success and np.isfinite(sol.y).all()):
            raise RuntimeError(f"motor G, {regime}, {a:g}-{b:g} s: "
                               f"{sol.message if sol else 'no solution'}")
        states[:, mask] = sol.y[:, :mask.sum()]
        z0 = sol.y[:, -1].copy()

    out: dict[str, np.ndarray] = {}
    for probe in PROBES[regime]:
        y = model.raw_probe(probe, states)
        s = fx.get("sensor", {}).get(probe, {})
        if s.get("delay"):
            y = 2.0 * states[model.slots["delay:" + probe]] - y
        out[probe] = np.asarray(y, dtype=float)
    if "hall_sat" in fx:
        out["current"] = fx["hall_sat"] * np.tanh(out["current"] / fx["hall_sat"])
    if "rdc" in fx:
        out["speed"] = states[model.slots["rdc"] + 1].copy()
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    return out


# ---------------------------------------------------------------------- noise

def ar1(rng: np.random.Generator, n: int, sigma: float, phi: float) -> np.ndarray:
    """A stationary AR(1) sequence of marginal standard deviation ``sigma``."""
    out = np.empty(n)
    out[0] = rng.normal(0.0, sigma)
    e = rng.normal(0.0, sigma * math.sqrt(1.0 - phi * phi), n)
    for j in range(1, n):
        out[j] = phi * out[j - 1] + e[j]
    return out


def pink(rng: np.random.Generator, n: int, sigma: float) -> np.ndarray:
    """1/f noise: white noise whose spectrum is shaped by f^-1/2 (mean removed), std sigma."""
    spec = np.fft.rfft(rng.normal(size=n))
    f = np.fft.rfftfreq(n)
    spec[0] = 0.0
    spec[1:] /= np.sqrt(f[1:])
    x = np.fft.irfft(spec, n)
    return sigma * x / np.std(x)


def add_noise(rng: np.random.Generator, y: np.ndarray, spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` plus ``white`` sigma, ``ar1`` [sigma, phi] and ``pink`` sigma noise, then rounded
    to the ADC step ``quant``."""
    out = np.array(y, dtype=float)
    if spec.get("white"):
        out += rng.normal(0.0, spec["white"], out.size)
    if spec.get("ar1"):
        out += ar1(rng, out.size, *spec["ar1"])
    if spec.get("pink"):
        out += pink(rng, out.size, spec["pink"])
    if spec.get("quant"):
        out = np.round(out / spec["quant"]) * spec["quant"]
    return out
