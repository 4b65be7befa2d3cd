"""Motor Q of the diagnosis benchmark: a hand-written scipy model of a 60 V, 1.5 kW class
permanent-magnet brushed DC TRACTION motor driving the rear axle of a small electric
utility cart (350 kg laden) through a rigid 12:1 reduction (helical stage and differential)
and the compliant half-shafts and tyres, on a level factory floor.

No circuitsim import: an independent simulator (the fourteenth of the benchmark), written
from the physics for netlists/motor_q_motor.yaml, motor_q.yaml and motor_q_slow.yaml. It is
evaluated at the record's own sample times (``t_eval``), never on a grid that is then
interpolated.

State z = [i, w, th, x, wv, thv] (+ the current sensor's delay stage, + the battery's
polarisation voltage, + the cart body's speed behind slipping tyres, + a sloshing payload's
twist and speed):

    i        armature current [A]
    w, th    rotor speed [rad/s] and angle [rad]; the axle's hub turns at w / N (N = 12)
    x        the half-shafts' twist th / N - thv [rad]
    wv, thv  the drive wheels' speed [rad/s] and angle [rad]; the cart moves r wv (r 0.2 m)

Equations (J1 = Jm + Jh / N^2, the rotor and the hub seen by the rotor; a torque T on the
hub is T / N on the rotor, power being conserved):

    L(i) di/dt = v(t) - R i - k w - (loop extras)
    J1 dw/dt   = k i - bm w + X_rotor + (X_hub - Tq) / N
    Jv dwv/dt  = Tq - bv wv - Tf tanh(wv / 0.01) - ca wv |wv| + X_wheel
    Tq         = c x + d (w / N - wv)                    (the half-shafts ``K``)

Jv is the cart's mass reflected to the wheels (m r^2) with the wheels' own inertia; bv the
wheel bearings' and the tyres' viscous loss, Tf tanh(wv / 0.01) the tyres' rolling
resistance (``friction``, w_brk 0.1), ca wv |wv| the air drag.

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): L(i) = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {node: [(order, a, b), ...]}: the node (rotor, hub, wheel) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {node: c}: c tanh(speed / 0.01) against the node's motion [N m]
    visc      {node: b}: an extra viscous friction [N m s/rad]
    offset    {node: T}: a constant torque [N m] on the node
    stribeck  {node: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g y + o; a
              delay is the first-order Pade stage (1 - s tau/2)/(1 + s tau/2), from rest
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    polar     (Rp [ohm], Cp [F]): the traction battery's polarisation (diffusion) voltage:
              the source gives u - vp, Cp dvp/dt = i - vp / Rp, vp(0) = 0 (a Thevenin
              battery's RC branch)
    traction  (Jw [kg m^2], Tmax [N m], ks [N m s/rad]): the tyres slip on a dusty floor:
              the wheel shaft keeps only the wheels' inertia Jw (with all the declared
              losses), the cart body (Jv - Jw, speed wb) is pushed by the tyres' traction
              Tmax tanh(ks (wv - wb) / Tmax), from rest
    deadband  db [V]: the throttle's dead zone: the armature gets u - clamp(u, -db, db)
    slosh     (Js [kg m^2], cs [N m/rad], ds [N m s/rad]): part of the payload is liquid
              (Js of the declared Jv, reflected to the wheels) and sloshes: Jv keeps
              Jv - Js, the liquid is an inertia Js on a spring cs and damper ds to the
              wheels (the tank's first sloshing mode)
    grade     (Tg [N m], th0 [rad], dth [rad]): the floor rises onto a ramp after th0 of the
              wheels' travel: the wheels take -Tg (1 + tanh((thv - th0) / dth)) / 2
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
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_q_profile.csv"

#: declared values of motor Q [SI] (motor_q_motor.yaml)
MOTOR_Q: dict[str, float] = {
    "R": 0.25, "L": 0.8e-3, "k": 0.17, "Jm": 2.5e-3, "bm": 1.5e-4, "N": 12.0, "Jh": 0.03,
    "c": 1500.0, "d": 3.0, "Jv": 14.4, "bv": 0.3, "Tf": 10.0, "ca": 4.3e-3,
}
#: [rad/s] the friction's and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_q.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.005, 0.0), (0.065, 12.0), (0.14, 12.0), (0.24, 30.0),
               (0.3, 30.0), (0.302, 24.0), (0.36, 24.0), (0.39, 8.0), (0.42, 0.0),
               (0.45, 0.0), (0.47, -6.0), (0.5, -6.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.5), "slow": (400.0, 20.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
SHAFTS = ("rotor", "hub", "wheel")
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


def deadband_corners(bp: np.ndarray, db: float) -> list[float]:
    """The instants [s] the piecewise-linear command ``bp`` crosses +-``db`` [V] (the dead
    zone's corners, where the armature voltage has a kink)."""
    out = []
    for (t0, u0), (t1, u1) in itertools.pairwise(bp):
        for lev in (db, -db):
            if (u0 - lev) * (u1 - lev) < 0.0:
                out.append(float(t0 + (lev - u0) * (t1 - t0) / (u1 - u0)))
    return out


# ---------------------------------------------------------------------- the model

class Cart:
    """Right-hand side of motor Q with one set of effects ``fx`` [SI]. Extra states after
    the six base ones, in this order when present: the current sensor's delay stage, the
    battery's polarisation voltage, the cart body's speed, the liquid's twist and speed."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.delay = fx.get("sensor", {}).get("current", {}).get("delay")
        n = 6
        self.i_delay = self.i_polar = self.i_body = self.i_slosh = None
        if self.delay is not None:
            self.i_delay, n = n, n + 1
        if "polar" in fx:
            self.i_polar, n = n, n + 1
        if "traction" in fx:
            self.i_body, n = n, n + 1
        if "slosh" in fx:
            self.i_slosh, n = n, n + 2
        self.n = n
        self.seg = (0.0, 0.0, 0.0)
        self.j1 = p["Jm"] + p["Jh"] / p["N"] ** 2
        jv = p["Jv"]
        if "traction" in fx:
            jv = fx["traction"][0]
        elif "slosh" in fx:
            jv = p["Jv"] - fx["slosh"][0]
        self.jv = jv
        self.shaft = {s: self._shaft_terms(s) for s in SHAFTS}

    def _shaft_terms(self, s: str) -> tuple | None:
        """(viscous, Coulomb, offset, harmonics, Stribeck) the effects put on shaft ``s``,
        or None when they put nothing there."""
        fx = self.fx
        terms = (fx.get("visc", {}).get(s, 0.0), fx.get("coul", {}).get(s, 0.0),
                 fx.get("offset", {}).get(s, 0.0), tuple(fx.get("cog", {}).get(s, ())),
                 fx.get("stribeck", {}).get(s))
        return terms if any(terms) else None

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

    def drive(self, t: float) -> float:
        """The drive's output voltage [V]: the command, past the throttle's dead zone."""
        u = self.command(t)
        if "deadband" in self.fx:
            db = self.fx["deadband"]
            u -= min(max(u, -db), db)
        return u

    def loop_voltage(self, t: float, z: np.ndarray) -> float:
        """The voltage [V] across L: the drive's output less the loop's drops and the EMF."""
        i, w, th = z[0], z[1], z[2]
        fx = self.fx
        v = self.drive(t) - self.resistance(t) * i - self.p["k"] * w
        if self.i_polar is not None:
            v -= z[self.i_polar]
        if "Vb" in fx:
            v -= fx["Vb"] * math.tanh(i / I_SIGN)
        for order, a, b in fx.get("emf", ()):
            v -= w * (a * math.sin(order * th) + b * math.cos(order * th))
        return v

    def wheel_load(self, wv: float, thv: float) -> float:
        """The declared losses of the wheels and the outside grade [N m] (against them)."""
        p, fx = self.p, self.fx
        load = p["bv"] * wv + p["Tf"] * math.tanh(wv / W_SIGN) + p["ca"] * wv * abs(wv)
        if "grade" in fx:
            tg, th0, dth = fx["grade"]
            load += 0.5 * tg * (1.0 + math.tanh((thv - th0) / dth))
        return load

    def __call__(self, t: float, z: np.ndarray) -> np.ndarray:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p, fx = self.p, self.fx
        i, w, th, x, wv, thv = z[:6]
        n = p["N"]
        dz = np.empty_like(z)
        dz[0] = self.loop_voltage(t, z) / self.inductance(i)
        tq = p["c"] * x + p["d"] * (w / n - wv)
        hub = self.torque("hub", w / n, th / n) - tq
        dz[1] = (p["k"] * i - p["bm"] * w + self.torque("rotor", w, th) + hub / n) / self.j1
        dz[2] = w
        dz[3] = w / n - wv
        wheel = tq - self.wheel_load(wv, thv) + self.torque("wheel", wv, thv)
        if self.i_body is not None:
            _, tmax, ks = fx["traction"]
            wb = z[self.i_body]
            push = tmax * math.tanh(ks * (wv - wb) / tmax)
            wheel -= push
            dz[self.i_body] = push / (p["Jv"] - fx["traction"][0])
        if self.i_slosh is not None:
            js, cs, ds = fx["slosh"]
            xs, ws = z[self.i_slosh], z[self.i_slosh + 1]
            ts = cs * xs + ds * (wv - ws)
            wheel -= ts
            dz[self.i_slosh] = wv - ws
            dz[self.i_slosh + 1] = ts / js
        dz[4] = wheel / self.jv
        dz[5] = wv
        if self.i_delay is not None:
            dz[self.i_delay] = (i - z[self.i_delay]) / (0.5 * self.delay)
        if self.i_polar is not None:
            rp, cp = fx["polar"]
            dz[self.i_polar] = (i - z[self.i_polar] / rp) / cp
        return dz


# ---------------------------------------------------------------------- integration

def _solve(model: Cart, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
           h_max: float) -> Any:
    """solve_ivp from ``a`` to ``b`` [s]: LSODA, then Radau if it fails."""
    msg = ""
    for method in ("LSODA", "Radau"):
        sol = solve_ivp(model, (a, b), z0, method=method, t_eval=t_out, rtol=RTOL,
                        atol=ATOL, max_step=h_max)
        if sol.success and np.isfinite(sol.y).all():
            return sol
        msg = sol.message
    raise RuntimeError(f"motor Q, {a:g}-{b:g} s: {msg}")


def integrate(model: Cart, t: np.ndarray, bp: np.ndarray, h_max: float) -> np.ndarray:
    """The states at the times ``t`` [s], from rest at t[0], restarted at every corner of
    the command ``bp`` [s, V] (and of the dead zone, with one). Returns (n_states, t.size)."""
    corners = [float(c) for c in bp[:, 0]]
    if "deadband" in model.fx:
        corners += deadband_corners(bp, model.fx["deadband"])
    cuts = [float(t[0]), *sorted(c for c in set(corners) if t[0] < c < t[-1]), float(t[-1])]
    z0 = np.zeros(model.n)
    y = np.empty((model.n, t.size))
    for j in range(len(cuts) - 1):
        a, b = cuts[j], cuts[j + 1]
        ua, ub = np.interp([a, b], bp[:, 0], bp[:, 1])
        model.seg = (a, float(ua), float((ub - ua) / (b - a)))
        last = j == len(cuts) - 2
        sel = (t >= a) & (t <= b) if last else (t >= a) & (t < b)
        t_out = t[sel] if last else np.append(t[sel], b)
        sol = _solve(model, a, b, z0, t_out, h_max)
        y[:, sel] = sol.y[:, :int(sel.sum())]
        z0 = sol.y[:, -1].copy()
    return y


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor Q at the times ``t`` [s] (default: the nominal grid), from
    rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the drive wheels' speed sensor), plus the command ``u`` [V].
    ``states``: add the angles [rad] and the half-shafts' twist [rad]."""
    fx = dict(fx or {})
    p = {**MOTOR_Q, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = Cart(fx, p)
    y = integrate(model, t, bp, H_MAX[regime])
    full = {"current": y[0], "speed": y[1], "load_speed": y[4]}
    if model.i_delay is not None:
        full["current"] = 2.0 * y[model.i_delay] - full["current"]
    out = {probe: full[probe].copy() for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out.update(rotor_angle=y[2], twist=y[3], wheel_angle=y[5])
    return out


# ---------------------------------------------------------------------- noise

def gauss_markov(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float
                 ) -> np.ndarray:
    """A stationary first-order Gauss-Markov process [probe unit] of standard deviation
    ``sigma`` and correlation time ``tau`` [s], exact at the times ``t`` [s] however uneven:
    x_k = r_k x_(k-1) + sigma sqrt(1 - r_k^2) e_k, r_k = exp(-(t_k - t_(k-1)) / tau)."""
    r = np.exp(-np.diff(np.asarray(t, dtype=float)) / tau)
    e = rng.standard_normal(len(t))
    x = np.empty(len(t))
    x[0] = sigma * e[0]
    kick = sigma * np.sqrt(1.0 - r * r) * e[1:]
    for k in range(1, len(t)):
        x[k] = r[k - 1] * x[k - 1] + kick[k - 1]
    return x


def ar1(rng: np.random.Generator, t: np.ndarray, sigma: float, phi: float) -> np.ndarray:
    """AR(1) noise [probe unit]: correlation ``phi`` over the mean interval, a Gauss-Markov
    process of correlation time -mean(dt) / ln(phi) [s]."""
    return gauss_markov(rng, t, sigma, -float(np.mean(np.diff(t))) / math.log(phi))


def pink(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise [probe unit] of standard deviation ``sigma`` at the times ``t`` [s]: equal
    variance Gauss-Markov processes whose correlation times are spaced by factors of two
    from the record's length down to the mean interval (their summed Lorentzians make a 1/f
    spectrum between the two), mean removed and scaled."""
    span, dt = float(t[-1] - t[0]), float(np.mean(np.diff(t)))
    taus = span * 0.5 ** np.arange(int(math.log2(span / dt)) + 1)
    x = np.sum([gauss_markov(rng, t, 1.0, tau) for tau in taus], axis=0)
    x -= x.mean()
    return sigma * x / x.std()


def add_noise(rng: np.random.Generator, t: np.ndarray, y: np.ndarray,
              spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` at the times ``t`` [s] with ``white`` sigma, ``ar1`` [sigma, phi] and ``pink``
    sigma noise added [probe unit], then read by an ADC of step ``quant`` [probe unit]."""
    out = np.array(y, dtype=float)
    if spec.get("white"):
        out += rng.normal(0.0, spec["white"], out.size)
    if spec.get("ar1"):
        out += ar1(rng, t, *spec["ar1"])
    if spec.get("pink"):
        out += pink(rng, t, spec["pink"])
    step = spec.get("quant")
    return np.round(out / step) * step if step else out
