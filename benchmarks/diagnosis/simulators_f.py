"""Motor F of the diagnosis benchmark: a hand-written scipy model of a 48 V, 200 W class
permanent-magnet brushed DC motor with brush friction, driving a fan through a rigid 5:1
gearbox. The fan's load torque is quadratic in its speed and declared in the netlist.

No circuitsim import: an independent simulator (the fourth of the benchmark; it mirrors
netlists/motor_f_motor.yaml, motor_f.yaml and motor_f_slow.yaml).

State x = [i, w, theta, extra...]: armature current [A], rotor speed [rad/s], rotor angle
[rad], then the states an effect adds (an input filter's current and capacitor voltage, a
tachometer's lag). The gearbox is rigid: the fan turns at w_f = w / N. Written at the rotor:

    L di/dt   = v_arm(t, x) - R i - k w
    J dw/dt   = k i - bm w - Tc tanh(w / 0.01) - Q(t, w_f) / N,     J = Jm + Jf / N^2
    Q         = bf w_f + cf w_f |w_f|   (+ the fan side's extra torques)

v_arm is the drive's command u(t) (linear between breakpoints) minus whatever an effect puts
in the loop. Effects (``fx`` keys, SI, all off by default):

  catalog
    Rser     [ohm]  resistance in series with the armature (a connector)
    Rs       [ohm]  internal resistance of the supply
    Vb       [V]    brush drop Vb tanh(i / 1 mA)
    alpha    [1/s]  Ra(t) = R (1 + alpha t)
    Fc_fan   [N*m]  Coulomb friction on the fan shaft, Fc tanh(w_f / 0.01)
    Fc_rotor [N*m]  Coulomb friction on the rotor, Fc tanh(w / 0.01)
    b_fan    [N*m*s/rad]  extra viscous friction on the fan shaft
    b_rotor  [N*m*s/rad]  extra viscous friction on the rotor
    T_rotor  [N*m]  a constant torque delivered to the rotor (the catalog's force-offset)
    stribeck (s [N*m], ws [rad/s]): a breakaway peak on the rotor over its brush friction,
             s exp(-(w/ws)^2) tanh(w / 0.01) more against the motion
    warmup   (rise [1], tau [s]): Ra(t) = R (1 + rise (1 - exp(-t/tau)))
    lsat     (Ipar [A], ratio [1]): dpsi/di = L (ratio + (1 - ratio)/(1 + (i/Ipar)^2))
    sensor   {probe: {"gain": g, "offset": o}}: the probe reads g x + o (gain is the factor)
    (an inertia off: pass motor parameters ``p`` with another Jf)
  outside the catalog
    deadtime (Vdt [V], i0 [A], Vdc [V]): the bridge's dead time takes
             Vdt tanh(i / i0) (1 - (u / Vdc)^2) off the armature voltage: opposite to the
             current, largest at 50 % duty (u = 0), nothing at full duty
    fan_exp  (n [1], w_ref [rad/s]): the fan's torque is cf w_ref^(2 - n) |w_f|^n sign(w_f)
             instead of the declared cf w_f |w_f| (equal at w_f = w_ref)
    lc_in    (Lf [H], Rf [ohm], Cf [F]): an LC filter between the supply and the bridge:
             Lf diL/dt = u - Rf iL - vC, Cf dvC/dt = iL - i; the armature sees vC
    bearing_warm (F1 [N*m], tau [s]): the fan bearing's Coulomb friction grows as it warms,
             F1 (1 - exp(-t / tau)) tanh(w_f / 0.01)
    tacho    (tau [s], a3 [1]): the speed probe is a tachometer read through a first-order
             lag y' = (w - y) / tau, with a ripple of 3 per revolution: reads y (1 + a3 sin 3 theta)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_f_profile.csv"

#: declared values of motor F [SI]
MOTOR_F: dict[str, float] = {
    "R": 0.8, "L": 1.2e-3, "k": 0.15, "Jm": 1.5e-4, "bm": 2e-5, "Tc": 0.02, "N": 5.0,
    "Jf": 5e-3, "bf": 1e-3, "cf": 1e-3,
}
#: [rad/s] circuitsim's friction with w_brk 0.1 rad/s changes sign as tanh(w / 0.01)
W_COUL = 0.01
#: [A] the catalog's brush drop smooths sign(i) as tanh(i / 1 mA)
I_BRUSH = 1e-3
#: the fast regime's command [s, V] (motor_f.yaml's pwl)
PWL_FAST: tuple[tuple[float, float], ...] = (
    (0.0, 0.0), (0.002, 0.0), (0.007, 24.0), (0.08, 24.0), (0.083, 48.0), (0.17, 48.0),
    (0.172, 18.0), (0.23, 18.0), (0.29, -36.0), (0.35, -36.0), (0.352, 0.0), (0.4, 0.0))
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.4), "slow": (1e3, 5.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
RTOL, ATOL = 1e-10, 1e-12


def command(regime: str) -> np.ndarray:
    """The command's breakpoints, (n, 2): [t [s], u [V]], linear between, held at the ends."""
    if regime == "fast":
        return np.array(PWL_FAST, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    fs, dur = REGIMES[regime]
    return np.arange(round(dur * fs) + 1) / fs


class _Plant:
    """The right-hand side of motor F with effects ``fx`` and parameters ``p``."""

    def __init__(self, pts: np.ndarray, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.pts, self.fx, self.p = pts, fx, p
        self.J = p["Jm"] + p["Jf"] / p["N"] ** 2
        self.n_extra = 0
        self.i_lc = self.i_tach = -1
        if "lc_in" in fx:
            self.i_lc = 3 + self.n_extra
            self.n_extra += 2
        if "tacho" in fx:
            self.i_tach = 3 + self.n_extra
            self.n_extra += 1

    def u(self, t: float) -> float:
        return float(np.interp(t, self.pts[:, 0], self.pts[:, 1]))

    def fan_torque(self, t: float, wf: float) -> float:
        """Q [N*m]: what the fan shaft takes, against positive rotation."""
        p, fx = self.p, self.fx
        if "fan_exp" in fx:
            n, wref = fx["fan_exp"]
            quad = p["cf"] * wref ** (2.0 - n) * abs(wf) ** n * math.copysign(1.0, wf)
        else:
            quad = p["cf"] * wf * abs(wf)
        q = p["bf"] * wf + quad
        q += fx.get("b_fan", 0.0) * wf
        q += fx.get("Fc_fan", 0.0) * math.tanh(wf / W_COUL)
        if "bearing_warm" in fx:
            f1, tau = fx["bearing_warm"]
            q += f1 * (1.0 - math.exp(-t / tau)) * math.tanh(wf / W_COUL)
        return q

    def rhs(self, t: float, x: np.ndarray) -> np.ndarray:
        p, fx = self.p, self.fx
        i, w = x[0], x[1]
        u = self.u(t)
        dx = np.zeros_like(x)
        # the voltage at the bridge
        if self.i_lc >= 0:
            lf, rf, cf = fx["lc_in"]
            il, vc = x[self.i_lc], x[self.i_lc + 1]
            dx[self.i_lc] = (u - rf * il - vc) / lf
            dx[self.i_lc + 1] = (il - i) / cf
            v = vc
        else:
            v = u
        v -= fx.get("Rs", 0.0) * i
        if "deadtime" in fx:
            vdt, i0, vdc = fx["deadtime"]
            v -= vdt * math.tanh(i / i0) * (1.0 - (u / vdc) ** 2)
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t) + fx.get("Rser", 0.0)
        if "warmup" in fx:
            rise, tw = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tw))
        ldiff = p["L"]
        if "lsat" in fx:
            ipar, ratio = fx["lsat"]
            ldiff = p["L"] * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))
        v -= fx.get("Vb", 0.0) * math.tanh(i / I_BRUSH)
        dx[0] = (v - r * i - p["k"] * w) / ldiff
        tm = p["k"] * i - (p["bm"] + fx.get("b_rotor", 0.0)) * w \
            - (p["Tc"] + fx.get("Fc_rotor", 0.0)) * math.tanh(w / W_COUL) \
            - self.fan_torque(t, w / p["N"]) / p["N"] + fx.get("T_rotor", 0.0)
        if "stribeck" in fx:
            s_, ws = fx["stribeck"]
            tm -= s_ * math.exp(-(w / ws) ** 2) * math.tanh(w / W_COUL)
        dx[1] = tm / self.J
        dx[2] = w
        if self.i_tach >= 0:
            dx[self.i_tach] = (w - x[self.i_tach]) / fx["tacho"][0]
        return dx


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None) -> dict[str, np.ndarray]:
    """Noise-free probes on ``t`` (default: the record grid): current, speed (and load_speed
    in the slow regime), plus the command ``u``."""
    fx = dict(fx or {})
    p = dict(MOTOR_F if p is None else p)
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    pts = command(regime)
    plant = _Plant(pts, fx, p)
    x0 = np.zeros(3 + plant.n_extra)
    # integrate piece by piece between the command's breakpoints (kinks in u)
    edges = sorted({float(t[0]), float(t[-1]),
                    *[float(b) for b in pts[:, 0] if t[0] < b < t[-1]]})
    fs = REGIMES[regime][0]
    hmax = 2.0 / fs
    xs = np.empty((t.size, x0.size))
    for a, b in itertools.pairwise(edges):
        last = b == edges[-1]
        sel = (t >= a) & ((t <= b) if last else (t < b))
        te = t[sel]
        # the state at b is the next piece's start: evaluate there too
        te_ext = te if last else np.append(te, b)
        sol = None
        for method in ("LSODA", "Radau"):
            sol = solve_ivp(plant.rhs, (a, b), x0, method=method, t_eval=te_ext, rtol=RTOL,
                            atol=ATOL, max_step=hmax)
            if sol.success and np.all(np.isfinite(sol.y)):
                break
        if not (sol.success and np.all(np.isfinite(sol.y))):
            raise RuntimeError(f"motor F {regime} {a:g}-{b:g} s: {sol.message}")
        xs[sel] = sol.y[:, :te.size].T
        x0 = sol.y[:, -1]
    i, w, th = xs[:, 0], xs[:, 1], xs[:, 2]
    speed = w
    if plant.i_tach >= 0:
        speed = xs[:, plant.i_tach] * (1.0 + fx["tacho"][1] * np.sin(3.0 * th))
    out = {"current": i, "speed": speed}
    if regime == "slow":
        out["load_speed"] = w / p["N"]
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, pts[:, 0], pts[:, 1])
    return out


# ---------------------------------------------------------------------- noise

def ar1(rng: np.random.Generator, n: int, sigma: float, phi: float) -> np.ndarray:
    """Stationary AR(1) of standard deviation ``sigma``, via scipy's lfilter."""
    from scipy.signal import lfilter
    e = rng.normal(0.0, sigma * math.sqrt(1.0 - phi * phi), n)
    zi = np.array([phi * rng.normal(0.0, sigma)])
    return lfilter([1.0], [1.0, -phi], e, zi=zi)[0]


def pink(rng: np.random.Generator, n: int, sigma: float) -> np.ndarray:
    """1/f noise: white shaped by f^-1/2 in the frequency domain (no DC), std ``sigma``."""
    spec = np.fft.rfft(rng.normal(size=n))
    f = np.fft.rfftfreq(n)
    spec[0] = 0.0
    spec[1:] /= np.sqrt(f[1:])
    x = np.fft.irfft(spec, n)
    return sigma * x / np.std(x)


def add_noise(rng: np.random.Generator, y: np.ndarray, spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` plus ``white`` sigma, ``ar1`` [sigma, phi], ``pink`` sigma, then rounded to the
    ADC step ``quant``."""
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
