"""Motor X of the diagnosis benchmark: a hand-written scipy model of a 12 V permanent-magnet
brushed DC motor in a car's POWER-WINDOW REGULATOR: the motor's worm drives a plastic worm
wheel (73:1) that carries the cable drum; a steel cable, run over the regulator's pulleys to
the glass carrier, lifts and lowers the pane in its glass-run seals against its weight.

No circuitsim import: an independent simulator (the twenty-first of the benchmark), written
from the physics for netlists/motor_x_fast.yaml and motor_x_slow.yaml. It is evaluated at the
record's own sample times (``t_eval``), never on a grid that is then interpolated. Everything
rests at t = 0 (the pane held by its seals, the cable slack-free and unstretched).

The pane is reflected to the drum through the drum's radius r = 0.02 m: the ``pane`` body's
angle thg = x / r [rad] is its height x above the start over r, its speed wg = v / r, its
inertia Jg = m r^2, and a force F on it is the torque F r. The worm gear is rigid (the drum
turns at w / N with the rotor) and, as declared, lossless; the cable is a compliance (a
spring and a damper between the drum and the pane). Up is wg > 0.

State z = [i, w, th, wg, thg] (+ extras, in this order when present: the seal's freshness
``u`` for ``dwell``; one Pade stage per delayed probe):

    i         armature current [A]
    w, th     rotor speed [rad/s] and angle [rad]; the drum turns at w / N, stands at th / N
    wg, thg   the pane's speed and height in the reflected units [rad/s, rad] (v / r, x / r)

Equations (Jm the rotor with the worm, Jd the worm wheel with the drum):

    L di/dt = v(t) - R i - k w - (the loop's extras)
    torque the rotor gives the worm   T_in = k i - bm w - Tb tanh(w / 0.01) + X_rotor - Jm dw/dt
    torque the drum asks of the wheel T_out = Jd dw/dt / N + Tk - X_drum
    lossless gear                     T_in = T_out / N
    Jg dwg/dt = Tk - Tg - Ts tanh(wg / 0.01) - Bg wg + X_pane
    Tk = c (th / N - thg) + d (w / N - wg)        (the cable ``K``)

so that (Jm + Jd / N^2) dw/dt = k i - bm w - Tb tanh(w/0.01) + X_rotor - (Tk - X_drum) / N.
Tb tanh(w / 0.01) is the brushes' and bearings' dry friction on the rotor (``friction``,
w_brk 0.1), Tg the pane's weight m g r (``btorque``, a constant), Ts tanh(wg / 0.01) the
glass-run seals' dry friction and Bg wg their viscous drag (``friction``, ``damper``).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th)),
              voltage only
    cog       {body: [(order, a, b), ...]}: the body (rotor, drum, pane) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play in the cable (Modelica's ElastoBacklash): no torque while
              |x| < gap / 2, else c (x -+ gap / 2) + d x', never pulling the sides together
              (x = th / N - thg)
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    worm      (eta_f, eta_b, P0 [W]): the worm mesh's friction: the wheel receives
              eta_f N T_in while the worm drives it (power flowing from the rotor, T_in w > 0),
              the worm N T_in = eta_b T_out while the pane's weight drives the wheel back;
              the two laws blended over a transmitted power of P0 (s = (1 + tanh(P / P0)) / 2)
    header    (dT [N m], th1 [rad], wth [rad]): the upper frame's seal, which the pane's top
              edge enters near the top of its travel, adds a dry friction
              dT (1 + tanh((thg - th1) / wth)) / 2 tanh(wg / 0.01) against the pane
    ripple    (U [V], a1 [V], f [Hz], a2 [V], psi2 [rad]): the alternator's ripple on the
              car's supply reaches the motor through the bridge's duty u / U: the motor sees
              u (1 + (a1 sin(2 pi f t) + a2 sin(4 pi f t + psi2)) / U)
    dwell     (dT [N m], tau [s], D [rad]): the seals' rubber creeps into the glass while the
              pane stands (rate-and-state aging): a freshness u (0 aged, 1 sliding) with
              du/dt = -u / tau + (1 - u) |wg| / D from u(0) = 0 adds the dry friction
              dT (1 - u) tanh(wg / 0.01) against the pane
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor X [SI] (motor_x_fast.yaml, motor_x_slow.yaml)
MOTOR_X: dict[str, float] = {
    "R": 0.7, "L": 5.5e-4, "k": 0.02, "Jm": 1.2e-5, "bm": 6e-6, "Tb": 0.02, "N": 73.0,
    "Jd": 2e-5, "c": 10.0, "d": 0.02, "Jg": 1.8e-3, "Bg": 0.04, "Ts": 0.7, "Tg": 0.883,
}
#: [rad/s] the frictions' and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_x_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.05, 12.0), (0.22, 12.0), (0.23, 7.0),
               (0.3, 7.0), (0.32, 0.0), (0.36, 0.0), (0.38, -12.0), (0.5, -12.0),
               (0.505, -4.0), (0.56, -4.0), (0.575, 0.0), (0.6, 0.0))
#: the slow regime's logged command [s, V] (motor_x_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.3, 0.0), (0.4, 12.0), (3.0, 12.0), (3.1, 6.0), (3.6, 6.0),
               (3.7, 0.0), (4.6, 0.0), (4.7, -12.0), (6.3, -12.0), (6.4, -3.0),
               (7.0, -3.0), (7.1, 0.0), (8.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.6), "slow": (500.0, 8.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "drum", "pane")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime (L/R is 0.79 ms,
#: the pane's mode on the cable 12 Hz, the alternator's ripple 1.3 kHz), a tenth of the mean
#: interval in the slow one (a 10th-order term of the rotor's angle has a period of 1.1 ms
#: at the top speed: the error control resolves it)
H_MAX = {"fast": 5e-5, "slow": 2e-4}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.asarray(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class WindowLift:
    """Right-hand side of motor X with one set of effects ``fx`` [SI]."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.n = p["N"]
        self.j_lossless = p["Jm"] + p["Jd"] / self.n ** 2
        n_states = 5
        self.k_dwell = None
        if "dwell" in fx:
            self.k_dwell, n_states = n_states, n_states + 1
        #: (probe, tau [s], index of its Pade state)
        self.pade: list[tuple[str, float, int]] = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.pade.append((probe, float(s["delay"]), n_states))
                n_states += 1
        self.n_states = n_states
        self.terms = {b: self._terms_of(b) for b in BODIES}
        self.seg = (0.0, 0.0, 0.0)

    def _terms_of(self, body: str) -> tuple | None:
        """What the catalog's effects put on ``body``: (viscous, Coulomb, offset,
        harmonics, Stribeck), or None when nothing."""
        fx = self.fx
        t = (fx.get("visc", {}).get(body, 0.0), fx.get("coul", {}).get(body, 0.0),
             fx.get("offset", {}).get(body, 0.0), tuple(fx.get("cog", {}).get(body, ())),
             fx.get("stribeck", {}).get(body))
        return t if (t[0] or t[1] or t[2] or t[3] or t[4] is not None) else None

    def extra_torque(self, body: str, w: float, angle: float) -> float:
        """The torque [N m] the catalog's effects give ``body`` at its speed ``w`` [rad/s]
        and angle ``angle`` [rad]."""
        t = self.terms[body]
        if t is None:
            return 0.0
        visc, coul, off, harm, strib = t
        out = off - visc * w
        if coul or strib is not None:
            sw = math.tanh(w / W_SIGN)
            out -= coul * sw
            if strib is not None:
                out -= strib[0] * math.exp(-((w / strib[1]) ** 2)) * sw
        for order, a, b in harm:
            out += a * math.sin(order * angle) + b * math.cos(order * angle)
        return out

    def command(self, t: float) -> float:
        """The bridge's mean output [V] as commanded, linear within the segment."""
        t0, u0, slope = self.seg
        return u0 + slope * (t - t0)

    def motor_voltage(self, t: float) -> float:
        """The voltage [V] the bridge puts on the motor: the command, times the supply's
        ripple over its nominal level when the alternator's ripple is on."""
        u = self.command(t)
        if "ripple" in self.fx:
            big_u, a1, f, a2, psi2 = self.fx["ripple"]
            ph = 2.0 * math.pi * f * t
            u *= 1.0 + (a1 * math.sin(ph) + a2 * math.sin(2.0 * ph + psi2)) / big_u
        return u

    def loop_resistance(self, t: float) -> float:
        """The loop's resistance [ohm]: the armature's (drifting) and the extras'."""
        p, fx = self.p, self.fx
        r = p["R"]
        if "alpha" in fx:
            r += p["R"] * fx["alpha"] * t
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        return r + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)

    def inductance(self, i: float) -> float:
        """The differential inductance [H] at the current ``i`` [A]."""
        ell = self.p["L"]
        if "lsat" in self.fx:
            ipar, ratio = self.fx["lsat"]
            ell *= ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2)
        return ell

    def cable(self, x: float, xdot: float) -> float:
        """The cable's torque [N m] from the drum into the pane at the twist ``x`` [rad]
        (th / N - thg) and its rate ``xdot`` [rad/s]."""
        p = self.p
        gap = self.fx.get("gap")
        if gap is None:
            return p["c"] * x + p["d"] * xdot
        h = 0.5 * gap
        if x > h:
            return max(p["c"] * (x - h) + p["d"] * xdot, 0.0)
        if x < -h:
            return min(p["c"] * (x + h) + p["d"] * xdot, 0.0)
        return 0.0

    def rotor_accel(self, tau_r: float, q: float, w: float) -> float:
        """dw/dt [rad/s^2] from the rotor's own torque ``tau_r`` [N m] (the motor's less its
        frictions) and the drum's demand ``q`` [N m] (the cable's pull less the drum's own
        extra torques), through the lossless gear, or the worm's mesh friction (``worm``)."""
        p, n = self.p, self.n
        if "worm" not in self.fx:
            return (tau_r - q / n) / self.j_lossless
        eta_f, eta_b, p0 = self.fx["worm"]
        # T_out + cj g(T_out) = y with g(T) = T / (eta N) forward, eta_b T / N back: g keeps
        # the sign of T, so T_out has the sign of y, and the direction is that of y w
        cj = p["Jd"] / (n * p["Jm"])
        y = cj * tau_r + q
        s = 0.5 * (1.0 + math.tanh(y * w / n / p0))
        gain = (s / eta_f + (1.0 - s) * eta_b) / n
        t_out = y / (1.0 + cj * gain)
        return (tau_r - gain * t_out) / p["Jm"]

    def __call__(self, t: float, z: np.ndarray) -> list[float]:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p, fx, n = self.p, self.fx, self.n
        i, w, th, wg, thg = (float(v) for v in z[:5])
        # the loop
        v = self.motor_voltage(t) - self.loop_resistance(t) * i - p["k"] * w
        if "Vb" in fx:
            v -= fx["Vb"] * math.tanh(i / I_SIGN)
        for order, a, b in fx.get("emf", ()):
            v -= w * (a * math.sin(order * th) + b * math.cos(order * th))
        di = v / self.inductance(i)
        # the cable and the drum's demand on the gear
        tk = self.cable(th / n - thg, w / n - wg)
        q = tk - self.extra_torque("drum", w / n, th / n)
        tau_r = (p["k"] * i - p["bm"] * w - p["Tb"] * math.tanh(w / W_SIGN)
                 + self.extra_torque("rotor", w, th))
        dw = self.rotor_accel(tau_r, q, w)
        # the pane
        sg = math.tanh(wg / W_SIGN)
        pane = tk - p["Tg"] - p["Ts"] * sg - p["Bg"] * wg + self.extra_torque("pane", wg, thg)
        if "header" in fx:
            dt_h, th1, wth = fx["header"]
            pane -= dt_h * 0.5 * (1.0 + math.tanh((thg - th1) / wth)) * sg
        extra = []
        if self.k_dwell is not None:
            dt_d, tau_d, dist = fx["dwell"]
            u = float(z[self.k_dwell])
            pane -= dt_d * (1.0 - u) * sg
            extra.append(-u / tau_d + (1.0 - u) * abs(wg) / dist)
        values = {"current": i, "speed": w, "load_speed": wg}
        for probe, tau, k in self.pade:
            extra.append(2.0 * (values[probe] - float(z[k])) / tau)
        return [di, dw, w, pane / p["Jg"], wg, *extra]


# ---------------------------------------------------------------------- integration

def _solve(model: WindowLift, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
           h_max: float) -> np.ndarray:
    """solve_ivp from ``a`` to ``b`` [s] at the times ``t_out`` [s]: LSODA, then Radau if
    it fails."""
    msg = ""
    for method in ("LSODA", "Radau"):
        sol = solve_ivp(model, (a, b), z0, method=method, t_eval=t_out, rtol=RTOL,
                        atol=ATOL, max_step=h_max)
        if sol.success and np.isfinite(sol.y).all() and sol.y.shape[1] == t_out.size:
            return sol.y
        msg = sol.message
    raise RuntimeError(f"motor X, {a:g}-{b:g} s: {msg}")


def integrate(model: WindowLift, t: np.ndarray, bp: np.ndarray, h_max: float) -> np.ndarray:
    """The states at the increasing times ``t`` [s], from rest at 0, restarted at every
    corner of the command ``bp`` [s, V]. Returns (n_states, t.size)."""
    stop = float(t[-1])
    cuts = [0.0, *sorted({float(c) for c in bp[:, 0] if 0.0 < c < stop}), stop]
    z0 = np.zeros(model.n_states)
    y = np.empty((model.n_states, t.size))
    for j in range(len(cuts) - 1):
        a, b = cuts[j], cuts[j + 1]
        ua, ub = (float(x) for x in np.interp([a, b], bp[:, 0], bp[:, 1]))
        model.seg = (a, ua, (ub - ua) / (b - a))
        last = j == len(cuts) - 2
        sel = (t >= a) & (t <= b) if last else (t >= a) & (t < b)
        t_out = t[sel] if last else np.append(t[sel], b)
        ys = _solve(model, a, b, z0, t_out, h_max)
        y[:, sel] = ys[:, :int(sel.sum())]
        z0 = ys[:, -1].copy()
    return y


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor X at the times ``t`` [s] (default: the nominal grid), from
    rest: current [A], speed [rad/s] (the motor's Hall sensor, at the rotor), and in the slow
    regime load_speed [rad/s] (the test rig's draw-wire encoder on the pane, as v / r), plus
    the command ``u`` [V]. ``states``: add the angles [rad] (and the seal's freshness)."""
    fx = dict(fx or {})
    p = {**MOTOR_X, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = WindowLift(fx, p)
    y = integrate(model, t, bp, H_MAX[regime])
    full = {"current": y[0], "speed": y[1], "load_speed": y[3]}
    for probe, _, k in model.pade:
        full[probe] = 2.0 * y[k] - full[probe]
    out = {probe: full[probe].copy() for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out.update(rotor_angle=y[2], pane_speed=y[3], pane_angle=y[4],
                   twist=y[2] / p["N"] - y[4])
        if model.k_dwell is not None:
            out["freshness"] = y[model.k_dwell]
    return out


# ---------------------------------------------------------------------- noise

def ou_noise(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float) -> np.ndarray:
    """An Ornstein-Uhlenbeck (Gauss-Markov) process [probe unit], stationary with standard
    deviation ``sigma`` and correlation time ``tau`` [s], exact at any times ``t`` [s]."""
    decay = np.exp(-np.diff(t) / tau)
    kick = sigma * np.sqrt(1.0 - decay ** 2) * rng.standard_normal(t.size - 1)
    x = np.empty(t.size)
    x[0] = sigma * rng.standard_normal()
    for n in range(1, t.size):
        x[n] = decay[n - 1] * x[n - 1] + kick[n - 1]
    return x


def pink_noise(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise [probe unit] of standard deviation ``sigma`` at the times ``t`` [s]: white
    noise on an even grid over the record, its spectrum's amplitude shaped by 1/sqrt(f)
    (no mean), read at ``t`` by linear interpolation, then scaled."""
    n = t.size
    tg = np.linspace(float(t[0]), float(t[-1]), n)
    spec = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, float(tg[1] - tg[0]))
    spec[0] = 0.0
    spec[1:] *= np.sqrt(f[1] / f[1:])
    x = np.interp(t, tg, np.fft.irfft(spec, n))
    x -= x.mean()
    return sigma * x / x.std()


def add_noise(rng: np.random.Generator, t: np.ndarray, y: np.ndarray,
              spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` at the times ``t`` [s] with ``white`` sigma, ``ar1`` [sigma, phi] (a
    Gauss-Markov process correlated by phi over the mean interval) and ``pink`` (1/f) sigma
    noise added [probe unit], then read by an ADC of step ``quant`` [probe unit]."""
    out = np.array(y, dtype=float)
    if spec.get("white"):
        out += rng.normal(0.0, spec["white"], out.size)
    if spec.get("ar1"):
        sig, phi = spec["ar1"]
        out += ou_noise(rng, t, sig, -float(np.mean(np.diff(t))) / math.log(phi))
    if spec.get("pink"):
        out += pink_noise(rng, t, spec["pink"])
    step = spec.get("quant")
    return np.round(out / step) * step if step else out
