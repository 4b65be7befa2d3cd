"""Motor S of the diagnosis benchmark: a hand-written scipy model of a 12 V permanent-magnet
brushed DC motor driving a motorised CAMERA SLIDER: a rigid 12:1 planetary gearhead turns a
40-tooth GT2 pulley (pitch radius r = 12.7 mm), and a glass-fibre timing belt (compliant)
pulls the carriage with an 8 kg cinema camera up a rail tilted 20 degrees.

No circuitsim import: an independent simulator (the sixteenth of the benchmark), written
from the physics for netlists/motor_s_motor.yaml, motor_s.yaml and motor_s_slow.yaml. It is
evaluated at the record's own sample times (``t_eval``), never on a grid that is then
interpolated; a probe read through a transport delay or a window is evaluated at the
shifted times too (from rest before the record starts).

State z = [i, w, th, x, wc, thc] (+ the battery's polarisation voltage, + the current
filter's two states):

    i        armature current [A]
    w, th    rotor speed [rad/s] and angle [rad]; the pulley turns at w / N (N = 12)
    x        the belt's stretch, as a twist of the pulley th / N - thc [rad]
    wc, thc  the carriage's speed and travel as rad of the pulley [rad/s], [rad]; the
             carriage moves r wc up the rail

Equations (J1 = Jm + Jg / N^2, the rotor and the gearhead's output with the pulley seen by
the rotor; a torque T on the pulley is T / N on the rotor, the gear being lossless):

    L di/dt  = v(t) - R i - k w - (loop extras)
    J1 dw/dt = k i - bm w + X_rotor + (X_pulley - Tb) / N
    Jc dwc/dt = Tb - bc wc - Tf tanh(wc / 0.01) - Tg + X_carriage
    Tb       = c x + d (w / N - wc)                  (the belt ``K``)

Jc is the carriage's and the camera's 8 kg reflected to the pulley (m r^2); bc the linear
bearings' viscous loss, Tf tanh(wc / 0.01) their dry friction (``friction``, w_brk 0.1), Tg
the camera's weight down the 20 degree incline at the pulley (``btorque``, -Tg: up the rail
is wc > 0).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): L(i) = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {shaft: [(order, a, b), ...]}: the shaft (rotor, pulley, carriage) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {shaft: c}: c tanh(speed / 0.01) against the shaft's motion [N m]
    visc      {shaft: b}: an extra viscous friction [N m s/rad]
    offset    {shaft: T}: a constant torque [N m] on the shaft
    stribeck  {shaft: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play in the belt (Modelica's ElastoBacklash): no torque while
              |x| < gap / 2, else c (x -+ gap / 2) + d (w / N - wc), never pulling
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads
              g y(t - tau) + o, a pure transport delay (y at rest before the record)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    aa        (fc [Hz], zeta): the current is read through a second-order low-pass
              (anti-alias) filter 1 / (s^2 / wn^2 + 2 zeta s / wn + 1), wn = 2 pi fc
    eta       [1]: the gearhead's efficiency: the pulley receives eta N tau_a while the
              motor drives it (tau_a w >= 0; tau_a the torque the rotor puts into the gear)
              and N tau_a / eta while it is driven back
    batt      (E0 [V], R0 [ohm], R1 [ohm], C1 [F]): the bridge's duty u / E0 switches a
              battery of EMF E0, resistance R0 and a polarisation R1 || C1: the armature
              gets (u / E0) (E0 - R0 (u / E0) i - v1), C1 dv1/dt = (u / E0) i - v1 / R1
    bumper    (th0 [rad], kb [N m/rad], db [N m s/rad^2]): a rubber end stop at th0 of the
              carriage's travel: -max(0, (thc - th0) (kb + db wc)) while thc > th0
    mavg      T [s]: the speed is estimated from the encoder's angle over a window:
              (th(t) - th(t - T)) / T
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp
from simulators_r import add_noise, ar1, gauss_markov, pink  # noqa: F401  (noise, not physics)

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_s_profile.csv"

#: declared values of motor S [SI] (motor_s_motor.yaml)
MOTOR_S: dict[str, float] = {
    "R": 0.5, "L": 4e-4, "k": 0.03, "Jm": 3e-5, "bm": 1e-5, "N": 12.0, "Jg": 4e-5,
    "c": 20.0, "d": 0.005, "Jc": 1.29e-3, "bc": 1.6e-3, "Tf": 0.08, "Tg": 0.34,
}
#: [rad/s] the friction's and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_s.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.005, 0.0), (0.045, 10.0), (0.15, 10.0), (0.151, 6.0),
               (0.22, 6.0), (0.221, 12.0), (0.28, 12.0), (0.30, 0.0), (0.33, 0.0),
               (0.37, -9.0), (0.48, -9.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.48), "slow": (200.0, 12.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
SHAFTS = ("rotor", "pulley", "carriage")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime (the command's corners are restarts)
H_MAX = {"fast": 4e-5, "slow": 1e-3}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    if regime == "fast":
        return np.asarray(FAST_POINTS, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class Slider:
    """Right-hand side of motor S with one set of effects ``fx`` [SI]. Extra states after
    the six base ones, in this order when present: the battery's polarisation voltage, the
    current filter's output and its rate."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        n = 6
        self.i_batt = self.i_aa = None
        if "batt" in fx:
            self.i_batt, n = n, n + 1
        if "aa" in fx:
            self.i_aa, n = n, n + 2
        self.n = n
        self.seg = (0.0, 0.0, 0.0)
        self.j1 = p["Jm"] + p["Jg"] / p["N"] ** 2
        self.shaft = {s: self._shaft_terms(s) for s in SHAFTS}

    def _shaft_terms(self, s: str) -> tuple | None:
        """(viscous, Coulomb, offset, harmonics, Stribeck) the effects put on shaft ``s``,
        or None when they put nothing there."""
        fx = self.fx
        terms = (fx.get("visc", {}).get(s, 0.0), fx.get("coul", {}).get(s, 0.0),
                 fx.get("offset", {}).get(s, 0.0), tuple(fx.get("cog", {}).get(s, ())),
                 fx.get("stribeck", {}).get(s))
        return terms if any(t for t in terms if t is not None) else None

    def command(self, t: float) -> float:
        """The logged command u [V] in the current linear segment."""
        t0, u0, slope = self.seg
        return u0 + slope * (t - t0)

    def torque(self, s: str, w: float, ang: float) -> float:
        """The torque [N m] the catalog's effects put on shaft ``s`` at ``w`` [rad/s] and
        ``ang`` [rad]."""
        terms = self.shaft[s]
        if terms is None:
            return 0.0
        visc, coul, off, harm, strib = terms
        out = off - visc * w
        if coul or strib is not None:
            sg = math.tanh(w / W_SIGN)
            out -= coul * sg
            if strib is not None:
                out -= strib[0] * math.exp(-(w / strib[1]) ** 2) * sg
        for order, a, b in harm:
            out += a * math.sin(order * ang) + b * math.cos(order * ang)
        return out

    def resistance(self, t: float) -> float:
        """The loop's resistance [ohm]: the armature's (drifting), the extras'."""
        p, fx = self.p, self.fx
        r = p["R"]
        if "alpha" in fx:
            r *= 1.0 + fx["alpha"] * t
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        return r + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)

    def inductance(self, i: float) -> float:
        """The differential inductance [H] at the current ``i`` [A]."""
        ell = self.p["L"]
        if "lsat" not in self.fx:
            return ell
        ipar, ratio = self.fx["lsat"]
        return ell * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))

    def drive(self, t: float, z: np.ndarray) -> float:
        """The bridge's output [V]: the command, or its duty times a sagging battery."""
        u = self.command(t)
        if self.i_batt is None:
            return u
        e0, r0, _, _ = self.fx["batt"]
        duty = u / e0
        return duty * (e0 - r0 * duty * z[0] - z[self.i_batt])

    def loop_voltage(self, t: float, z: np.ndarray) -> float:
        """The voltage [V] across the inductance: the drive's output less the loop's drops
        and the EMF."""
        i, w, th = z[0], z[1], z[2]
        fx = self.fx
        v = self.drive(t, z) - self.resistance(t) * i - self.p["k"] * w
        if "Vb" in fx:
            v -= fx["Vb"] * math.tanh(i / I_SIGN)
        for order, a, b in fx.get("emf", ()):
            v -= w * (a * math.sin(order * th) + b * math.cos(order * th))
        return v

    def belt(self, x: float, wrel: float) -> float:
        """The belt's torque [N m] at the stretch ``x`` [rad] and the stretch's rate
        ``wrel`` [rad/s]: a spring-damper, or with a play ElastoBacklash's law."""
        p = self.p
        gap = self.fx.get("gap")
        if gap is None:
            return p["c"] * x + p["d"] * wrel
        h = 0.5 * gap
        if x > h:
            return max(p["c"] * (x - h) + p["d"] * wrel, 0.0)
        if x < -h:
            return min(p["c"] * (x + h) + p["d"] * wrel, 0.0)
        return 0.0

    def carriage_load(self, wc: float, thc: float) -> float:
        """The declared losses and weight of the carriage and the end stop [N m] (against
        it)."""
        p, fx = self.p, self.fx
        load = p["bc"] * wc + p["Tf"] * math.tanh(wc / W_SIGN) + p["Tg"]
        if "bumper" in fx:
            th0, kb, db = fx["bumper"]
            if thc > th0:
                load += max(0.0, (thc - th0) * (kb + db * wc))
        return load

    def rotor_accel(self, drive: float, pulley: float, w: float) -> float:
        """dw/dt [rad/s^2] at the rotor's speed ``w`` [rad/s] given the torques on the rotor
        ``drive`` and on the pulley ``pulley`` [N m]: through a lossless gear, or one of
        efficiency eta whose loss depends on which way the power flows."""
        p = self.p
        n = p["N"]
        if "eta" not in self.fx:
            return (drive + pulley / n) / self.j1
        jm, jg, eta = p["Jm"], p["Jg"], self.fx["eta"]
        # the torque the rotor puts into the gear, tau_a = num / (Jg + g N^2 Jm), has num's
        # sign whichever g: the motor drives (g = eta) when it has the speed's sign
        num = drive * jg - n * pulley * jm
        g = eta if num * w >= 0.0 else 1.0 / eta
        return (drive - num / (jg + g * n * n * jm)) / jm

    def __call__(self, t: float, z: np.ndarray) -> np.ndarray:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p, fx = self.p, self.fx
        i, w, th, x, wc, thc = z[:6]
        n = p["N"]
        dz = np.empty_like(z)
        dz[0] = self.loop_voltage(t, z) / self.inductance(i)
        tb = self.belt(x, w / n - wc)
        dz[1] = self.rotor_accel(p["k"] * i - p["bm"] * w + self.torque("rotor", w, th),
                                 self.torque("pulley", w / n, th / n) - tb, w)
        dz[2] = w
        dz[3] = w / n - wc
        dz[4] = (tb - self.carriage_load(wc, thc) + self.torque("carriage", wc, thc)) / p["Jc"]
        dz[5] = wc
        if self.i_batt is not None:
            e0, _, r1, c1 = fx["batt"]
            dz[self.i_batt] = (self.command(t) / e0 * i - z[self.i_batt] / r1) / c1
        if self.i_aa is not None:
            wn = 2.0 * math.pi * fx["aa"][0]
            y, dy = z[self.i_aa], z[self.i_aa + 1]
            dz[self.i_aa] = dy
            dz[self.i_aa + 1] = wn * wn * (i - y) - 2.0 * fx["aa"][1] * wn * dy
        return dz


# ---------------------------------------------------------------------- integration

def _solve(model: Slider, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
           h_max: float) -> np.ndarray:
    """solve_ivp from ``a`` to ``b`` [s]: LSODA, then Radau if it fails."""
    msg = ""
    for method in ("LSODA", "Radau"):
        sol = solve_ivp(model, (a, b), z0, method=method, t_eval=t_out, rtol=RTOL,
                        atol=ATOL, max_step=h_max)
        if sol.success and np.isfinite(sol.y).all():
            return sol.y
        msg = sol.message
    raise RuntimeError(f"motor S, {a:g}-{b:g} s: {msg}")


def integrate(model: Slider, t: np.ndarray, bp: np.ndarray, h_max: float) -> np.ndarray:
    """The states at the increasing times ``t`` [s], from rest at 0, restarted at every
    corner of the command ``bp`` [s, V]. Returns (n_states, t.size)."""
    cuts = [0.0, *sorted(float(c) for c in set(bp[:, 0]) if 0.0 < c < t[-1]), float(t[-1])]
    z0 = np.zeros(model.n)
    y = np.empty((model.n, t.size))
    for j in range(len(cuts) - 1):
        a, b = cuts[j], cuts[j + 1]
        ua, ub = np.interp([a, b], bp[:, 0], bp[:, 1])
        model.seg = (a, float(ua), float((ub - ua) / (b - a)))
        last = j == len(cuts) - 2
        sel = (t >= a) & (t <= b) if last else (t >= a) & (t < b)
        t_out = t[sel] if last else np.append(t[sel], b)
        ys = _solve(model, a, b, z0, t_out, h_max)
        y[:, sel] = ys[:, :int(sel.sum())]
        z0 = ys[:, -1].copy()
    return y


def _shifts(fx: Mapping[str, Any]) -> list[float]:
    """The time shifts [s] a probe is read at besides its own time: a sensor's transport
    delay, an estimate's window."""
    out = [float(s["delay"]) for s in fx.get("sensor", {}).values() if s.get("delay")]
    if "mavg" in fx:
        out.append(float(fx["mavg"]))
    return out


def _at(y: np.ndarray, where: np.ndarray, idx: np.ndarray) -> np.ndarray:
    """A state's values at the union's indices ``idx``, at rest (0) where the shifted time
    ``where`` [s] precedes the record."""
    return np.where(where >= 0.0, y[idx], 0.0)


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor S at the times ``t`` [s] (default: the nominal grid), from
    rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the carriage's linear encoder, as rad/s of the pulley), plus the
    command ``u`` [V]. ``states``: add the angles [rad] and the belt's stretch [rad]."""
    fx = dict(fx or {})
    p = {**MOTOR_S, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = Slider(fx, p)
    # the times a shifted reading needs, run in one pass with the record's own
    # (rounded to 1 ps, so that a shifted time that is a sample time is that very time)
    every = np.concatenate([t, *(np.round(t - s, 12) for s in _shifts(fx))])
    union, inv = np.unique(every[every >= 0.0], return_inverse=True)
    y = integrate(model, union, bp, H_MAX[regime])
    pos = np.full(every.size, -1)
    pos[every >= 0.0] = inv
    pos = pos.reshape(-1, t.size)
    full = {"current": y[0], "speed": y[1], "load_speed": y[4]}
    if model.i_aa is not None:
        full["current"] = y[model.i_aa]
    out = {probe: full[probe][pos[0]].copy() for probe in PROBES[regime]}
    k = 1
    for probe, s in fx.get("sensor", {}).items():
        if s.get("delay"):
            out[probe] = _at(full[probe], t - s["delay"], pos[k])
            k += 1
    if "mavg" in fx:
        win = float(fx["mavg"])
        out["speed"] = (y[2][pos[0]] - _at(y[2], t - win, pos[k])) / win
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out.update(rotor_angle=y[2][pos[0]], stretch=y[3][pos[0]],
                   carriage_angle=y[5][pos[0]])
    return out
