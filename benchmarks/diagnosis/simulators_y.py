"""Motor Y of the diagnosis benchmark: a hand-written scipy model of a 12 V permanent-magnet
brushed DC motor in a car's ELECTRONIC THROTTLE BODY: the motor's pinion drives the throttle
shaft through a two-stage spur gear (20:1, an intermediate gear and the shaft's sector gear);
the shaft carries the butterfly plate and a torsion return spring wound against the housing,
preloaded so that it closes the plate towards the limp-home position and beyond.

No circuitsim import: an independent simulator (the twenty-second of the benchmark), written
from the physics for netlists/motor_y_fast.yaml and motor_y_slow.yaml. It is evaluated at the
record's own sample times (``t_eval``), never on a grid that is then interpolated. Everything
rests at t = 0 (no current, the plate at the limp-home position, angle 0); the bridge's
command starts at the limp-home holding voltage, so the start is a 0.5 ms current transient.

The gear is rigid and lossless: the plate stands at thp = th / N and turns at wp = w / N with
the rotor, and a torque T on the plate is T / N on the rotor. Opening is thp > 0; the closed
stop lies 0.14 rad below limp-home and full open 1.45 rad above it (neither is reached).

State z = [i, w, th] (+ one Pade stage per delayed probe):

    i        armature current [A]
    w, th    rotor speed [rad/s] and angle [rad]

Equations (Jm the rotor with its pinion, Jp the plate, shaft, sector gear and the position
sensor's magnet; J = Jm + Jp / N^2):

    L di/dt = v(t) - R i - k w - (the loop's extras)
    J dw/dt = k i - bm w - Tb tanh(w / 0.01) + X_rotor + P / N
    P       = -Bp wp - Tp tanh(wp / 0.01) - c thp - T0 + X_plate     (on the plate)

Tb tanh(w / 0.01) is the brushes' and the motor bearings' dry friction (``friction``, w_brk
0.1), Bp wp and Tp tanh(wp / 0.01) the shaft's bushings' grease drag and its seal's dry
friction, c thp the return spring's rate (``spring`` to ``fixed``) and T0 its preload at
limp-home (``btorque``, a constant: the closest form a netlist states).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th)),
              voltage only
    cog       {body: [(order, a, b), ...]}: the body (rotor, plate) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog (all on the plate):

    limp      (T1 [N m], c2 [N m/rad], thl [rad], wl [rad]): the limp-home (default)
              spring, whose lever meets the plate at thl, just below limp-home, and pushes it
              open below there: the plate receives
              (T1 - c2 (thp - thl)) (1 - tanh((thp - thl) / wl)) / 2
    coil      mu [1]: the return spring's coils rub on each other and on their guide: a dry
              friction mu (T0 + c thp) tanh(wp / 0.01) against the plate, in proportion to
              the spring's wind-up torque
    pulse     (A [N m/rad], phc [rad], f [Hz], psi [rad]): the intake manifold's pressure
              pulsation at the engine's firing frequency acting on the plate's off-centre
              shaft: the plate receives A (thp + phc) sin(2 pi f t + psi)
    coke      (dT [N m], thc [rad], wc [rad]): a ring of carbon deposit in the bore around
              the idle position: a dry friction dT exp(-((thp - thc) / wc)^2) tanh(wp / 0.01)
              against the plate
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor Y [SI] (motor_y_fast.yaml, motor_y_slow.yaml)
MOTOR_Y: dict[str, float] = {
    "R": 1.8, "L": 9e-4, "k": 0.016, "Jm": 2.5e-6, "bm": 2e-6, "Tb": 2e-3, "N": 20.0,
    "Jp": 2.5e-5, "Bp": 2e-3, "Tp": 0.02, "c": 0.5, "T0": 0.12,
}
#: [rad/s] the frictions' and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_y_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.675), (0.02, 0.675), (0.022, 3.5), (0.12, 3.5), (0.122, 2.0),
               (0.19, 2.0), (0.192, -4.0), (0.205, -4.0), (0.207, 1.2), (0.27, 1.2),
               (0.30, 4.0), (0.34, 4.0), (0.342, 0.9), (0.4, 0.9))
#: the slow regime's logged command [s, V] (motor_y_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.675), (0.3, 0.675), (0.5, 2.2), (1.2, 2.2), (1.6, 3.8), (2.2, 3.8),
               (2.21, -3.0), (2.24, -3.0), (2.25, 0.2), (3.2, 0.2), (3.3, 1.6),
               (3.9, 1.6), (4.0, 3.0), (4.6, 3.0), (5.2, 1.0), (5.5, 1.0), (5.51, -2.0),
               (5.53, -2.0), (5.54, 0.2), (6.0, 0.2))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.4), "slow": (500.0, 6.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "plate")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime (L/R is 0.5 ms,
#: the intake pulsation 40 Hz), a tenth of the mean interval in the slow one
H_MAX = {"fast": 5e-5, "slow": 2e-4}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.asarray(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class ThrottleBody:
    """Right-hand side of motor Y with one set of effects ``fx`` [SI]."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.n = p["N"]
        self.j = p["Jm"] + p["Jp"] / self.n ** 2
        n_states = 3
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

    def plate_torque(self, t: float, wp: float, thp: float) -> float:
        """Everything the plate receives [N m] at its speed ``wp`` [rad/s] and angle
        ``thp`` [rad] but the gear's torque."""
        p, fx = self.p, self.fx
        sp = math.tanh(wp / W_SIGN)
        out = (-p["Bp"] * wp - p["Tp"] * sp - p["c"] * thp - p["T0"]
               + self.extra_torque("plate", wp, thp))
        if "limp" in fx:
            t1, c2, thl, wl = fx["limp"]
            out += (t1 - c2 * (thp - thl)) * 0.5 * (1.0 - math.tanh((thp - thl) / wl))
        if "coil" in fx:
            out -= fx["coil"] * (p["T0"] + p["c"] * thp) * sp
        if "pulse" in fx:
            amp, phc, f, psi = fx["pulse"]
            out += amp * (thp + phc) * math.sin(2.0 * math.pi * f * t + psi)
        if "coke" in fx:
            dt, thc, wc = fx["coke"]
            out -= dt * math.exp(-(((thp - thc) / wc) ** 2)) * sp
        return out

    def __call__(self, t: float, z: np.ndarray) -> list[float]:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p, fx, n = self.p, self.fx, self.n
        i, w, th = (float(v) for v in z[:3])
        # the loop
        v = self.command(t) - self.loop_resistance(t) * i - p["k"] * w
        if "Vb" in fx:
            v -= fx["Vb"] * math.tanh(i / I_SIGN)
        for order, a, b in fx.get("emf", ()):
            v -= w * (a * math.sin(order * th) + b * math.cos(order * th))
        di = v / self.inductance(i)
        # the rotor and, through the rigid gear, the plate
        tau = (p["k"] * i - p["bm"] * w - p["Tb"] * math.tanh(w / W_SIGN)
               + self.extra_torque("rotor", w, th)
               + self.plate_torque(t, w / n, th / n) / n)
        values = {"current": i, "speed": w, "load_speed": w / n}
        extra = [2.0 * (values[probe] - float(z[k])) / tau_d for probe, tau_d, k in self.pade]
        return [di, tau / self.j, w, *extra]


# ---------------------------------------------------------------------- integration

def _solve(model: ThrottleBody, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor Y, {a:g}-{b:g} s: {msg}")


def integrate(model: ThrottleBody, t: np.ndarray, bp: np.ndarray, h_max: float
              ) -> np.ndarray:
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
    """Noise-free probes of motor Y at the times ``t`` [s] (default: the nominal grid), from
    rest: current [A], speed [rad/s] (the bench's encoder on the motor's rotor), and in the
    slow regime load_speed [rad/s] (the plate's speed, from the throttle position sensor),
    plus the command ``u`` [V]. ``states``: add the angles [rad]."""
    fx = dict(fx or {})
    p = {**MOTOR_Y, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = ThrottleBody(fx, p)
    y = integrate(model, t, bp, H_MAX[regime])
    full = {"current": y[0], "speed": y[1], "load_speed": y[1] / p["N"]}
    for probe, _, k in model.pade:
        full[probe] = 2.0 * y[k] - full[probe]
    out = {probe: full[probe].copy() for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out.update(rotor_angle=y[2], plate_angle=y[2] / p["N"])
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
