"""Motor R of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC motor driving a sectional GARAGE-DOOR OPENER: a rigid 60:1 worm gear turns the
chain sprocket, and a roller chain (compliant) pulls the trolley and the door (60 kg, its
weight mostly carried by torsion springs, the rest a small declared imbalance).

No circuitsim import: an independent simulator (the fifteenth of the benchmark), written
from the physics for netlists/motor_r_motor.yaml, motor_r.yaml and motor_r_slow.yaml. It is
evaluated at the record's own sample times (``t_eval``), never on a grid that is then
interpolated.

State z = [i, w, th, x, wd, thd] (+ the current sensor's delay stage, + the eddy-current
branch's current, + the current shunt's temperature rise):

    i        armature current [A]
    w, th    rotor speed [rad/s] and angle [rad]; the sprocket turns at w / N (N = 60)
    x        the chain's stretch, as a twist of the sprocket th / N - thd [rad]
    wd, thd  the door's (trolley's) speed and travel as rad of the sprocket [rad/s], [rad];
             the door moves r wd (r = 0.03 m, the sprocket's pitch radius)

Equations (J1 = Jm + Jw / N^2, the rotor and the worm wheel with the sprocket seen by the
rotor; a torque T on the sprocket is T / N on the rotor, the gear being lossless):

    L di/dt  = v(t) - R i - k w - (loop extras)
    J1 dw/dt = k i - bm w + X_rotor + (X_sprocket - Tc) / N
    Jd dwd/dt = Tc - bd wd - Tf tanh(wd / 0.01) - Tg + X_door
    Tc       = c x + d (w / N - wd)                  (the chain ``K``)

Jd is the door's, the trolley's and the chain's mass reflected to the sprocket (m r^2); bd
the rollers' viscous loss, Tf tanh(wd / 0.01) the rollers' and the track's dry friction
(``friction``, w_brk 0.1), Tg the counterbalance's residual: the door is 0.8 N m too heavy
at the sprocket (``btorque``, -Tg: opening is wd > 0).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): L(i) = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {shaft: [(order, a, b), ...]}: the shaft (rotor, sprocket, door) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {shaft: c}: c tanh(speed / 0.01) against the shaft's motion [N m]
    visc      {shaft: b}: an extra viscous friction [N m s/rad]
    offset    {shaft: T}: a constant torque [N m] on the shaft
    stribeck  {shaft: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g y + o; a
              delay (the current's only) is the first-order Pade stage
              (1 - s tau/2)/(1 + s tau/2), from rest
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    ice       (kb [N m/rad], db [N m s/rad], Tb [N m]): the door's bottom seal is frozen to
              the floor: until the bond breaks the door is held at its start by
              kb thd + db wd; the bond breaks for good when that torque reaches Tb
    shunt     (Rsh [ohm], Rth [K/W], Cth [J/K], a [1/K]): the current is read across a
              copper PCB trace that its own loss heats: Cth dT/dt = i^2 Rsh - T / Rth, the
              reading i (1 + a T), T(0) = 0
    eddy      (L2 [H], Re [ohm]): eddy currents in the motor's solid yoke: the armature's
              inductance is L - L2 in series with L2 || Re (the same L at low frequency,
              L - L2 for fast changes)
    clip      Umax [V]: the bridge's duty tops out: the armature gets clamp(u, -Umax, Umax)
    splice    (Tb [N m], th0 [rad], wb [rad]): a misaligned splice of the opener's rail at
              th0 of the door's travel: the trolley drags over it with
              Tb exp(-((thd - th0) / wb)^2) tanh(wd / 0.01) against its motion
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
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_r_profile.csv"

#: declared values of motor R [SI] (motor_r_motor.yaml)
MOTOR_R: dict[str, float] = {
    "R": 0.6, "L": 1.2e-3, "k": 0.045, "Jm": 8e-5, "bm": 2e-5, "N": 60.0, "Jw": 2e-3,
    "c": 270.0, "d": 0.5, "Jd": 0.06, "bd": 0.4, "Tf": 2.0, "Tg": 0.8,
}
#: [rad/s] the friction's and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_r.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.005, 0.0), (0.065, 20.0), (0.18, 20.0), (0.181, 14.0),
               (0.25, 14.0), (0.251, 22.0), (0.31, 22.0), (0.34, 0.0), (0.38, 0.0),
               (0.43, -16.0), (0.5, -16.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.5), "slow": (250.0, 16.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
SHAFTS = ("rotor", "sprocket", "door")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime (the command's corners are restarts)
H_MAX = {"fast": 5e-5, "slow": 1e-3}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    if regime == "fast":
        return np.asarray(FAST_POINTS, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


def level_crossings(bp: np.ndarray, level: float) -> list[float]:
    """The instants [s] the piecewise-linear command ``bp`` crosses +-``level`` [V] (where a
    clamp of the command has a kink)."""
    out = []
    for (t0, u0), (t1, u1) in itertools.pairwise(bp):
        for lev in (level, -level):
            if (u0 - lev) * (u1 - lev) < 0.0:
                out.append(float(t0 + (lev - u0) * (t1 - t0) / (u1 - u0)))
    return out


# ---------------------------------------------------------------------- the model

class Opener:
    """Right-hand side of motor R with one set of effects ``fx`` [SI]. Extra states after
    the six base ones, in this order when present: the current sensor's delay stage, the
    eddy branch's current, the shunt's temperature rise."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.delay = fx.get("sensor", {}).get("current", {}).get("delay")
        n = 6
        self.i_delay = self.i_eddy = self.i_shunt = None
        if self.delay is not None:
            self.i_delay, n = n, n + 1
        if "eddy" in fx:
            self.i_eddy, n = n, n + 1
        if "shunt" in fx:
            self.i_shunt, n = n, n + 1
        self.n = n
        self.seg = (0.0, 0.0, 0.0)
        self.j1 = p["Jm"] + p["Jw"] / p["N"] ** 2
        #: the ice bond holds the door (until it breaks)
        self.bonded = "ice" in fx
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

    def drive(self, t: float) -> float:
        """The bridge's output [V]: the command, clamped at the top of the duty's range."""
        u = self.command(t)
        if "clip" in self.fx:
            top = self.fx["clip"]
            u = min(max(u, -top), top)
        return u

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
        """The differential inductance [H] at the current ``i`` [A] (less the eddy branch's
        L2, with one)."""
        ell = self.p["L"]
        if "eddy" in self.fx:
            return ell - self.fx["eddy"][0]
        if "lsat" not in self.fx:
            return ell
        ipar, ratio = self.fx["lsat"]
        return ell * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))

    def loop_voltage(self, t: float, z: np.ndarray) -> float:
        """The voltage [V] across the inductance: the drive's output less the loop's drops,
        the EMF and the eddy branch's voltage."""
        i, w, th = z[0], z[1], z[2]
        fx = self.fx
        v = self.drive(t) - self.resistance(t) * i - self.p["k"] * w
        if "Vb" in fx:
            v -= fx["Vb"] * math.tanh(i / I_SIGN)
        for order, a, b in fx.get("emf", ()):
            v -= w * (a * math.sin(order * th) + b * math.cos(order * th))
        if self.i_eddy is not None:
            v -= fx["eddy"][1] * (i - z[self.i_eddy])
        return v

    def door_load(self, wd: float, thd: float) -> float:
        """The declared losses and imbalance of the door and the outside drags [N m]
        (against it)."""
        p, fx = self.p, self.fx
        load = p["bd"] * wd + p["Tf"] * math.tanh(wd / W_SIGN) + p["Tg"]
        if "splice" in fx:
            tb, th0, wb = fx["splice"]
            load += tb * math.exp(-((thd - th0) / wb) ** 2) * math.tanh(wd / W_SIGN)
        if self.bonded:
            kb, db, _ = fx["ice"]
            load += kb * thd + db * wd
        return load

    def bond(self, t: float, z: np.ndarray) -> float:
        """What the ice bond still holds [N m]: its strength less the torque on it."""
        kb, db, tb = self.fx["ice"]
        return tb - abs(kb * z[5] + db * z[4])

    def __call__(self, t: float, z: np.ndarray) -> np.ndarray:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p, fx = self.p, self.fx
        i, w, th, x, wd, thd = z[:6]
        n = p["N"]
        dz = np.empty_like(z)
        dz[0] = self.loop_voltage(t, z) / self.inductance(i)
        tc = p["c"] * x + p["d"] * (w / n - wd)
        spr = self.torque("sprocket", w / n, th / n) - tc
        dz[1] = (p["k"] * i - p["bm"] * w + self.torque("rotor", w, th) + spr / n) / self.j1
        dz[2] = w
        dz[3] = w / n - wd
        dz[4] = (tc - self.door_load(wd, thd) + self.torque("door", wd, thd)) / p["Jd"]
        dz[5] = wd
        if self.i_delay is not None:
            dz[self.i_delay] = (i - z[self.i_delay]) / (0.5 * self.delay)
        if self.i_eddy is not None:
            l2, re = fx["eddy"]
            dz[self.i_eddy] = re * (i - z[self.i_eddy]) / l2
        if self.i_shunt is not None:
            rsh, rth, cth, _ = fx["shunt"]
            dz[self.i_shunt] = (i * i * rsh - z[self.i_shunt] / rth) / cth
        return dz


# ---------------------------------------------------------------------- integration

def _solve(model: Opener, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
           h_max: float, events: Any = None) -> Any:
    """solve_ivp from ``a`` to ``b`` [s]: LSODA, then Radau if it fails."""
    msg = ""
    for method in ("LSODA", "Radau"):
        sol = solve_ivp(model, (a, b), z0, method=method, t_eval=t_out, rtol=RTOL,
                        atol=ATOL, max_step=h_max, events=events)
        if sol.success and np.isfinite(sol.y).all():
            return sol
        msg = sol.message
    raise RuntimeError(f"motor R, {a:g}-{b:g} s: {msg}")


def _piece(model: Opener, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
           h_max: float) -> np.ndarray:
    """The states at ``t_out`` [s] (which ends with ``b``) from ``z0`` at ``a``; while the
    ice bond holds, stopped where it breaks and continued without it."""
    if not model.bonded:
        return _solve(model, a, b, z0, t_out, h_max).y

    def breaks(t: float, z: np.ndarray) -> float:
        return model.bond(t, z)

    breaks.terminal, breaks.direction = True, -1
    sol = _solve(model, a, b, z0, t_out, h_max, [breaks])
    if sol.status == 0:
        return sol.y
    tb = float(sol.t_events[0][0])
    model.bonded = False
    rest = t_out[t_out > tb]
    after = _solve(model, tb, b, sol.y_events[0][0].copy(), rest, h_max).y
    return np.concatenate([sol.y[:, :t_out.size - rest.size], after], axis=1)


def integrate(model: Opener, t: np.ndarray, bp: np.ndarray, h_max: float) -> np.ndarray:
    """The states at the times ``t`` [s], from rest at t[0], restarted at every corner of
    the command ``bp`` [s, V] (and of its clamp, with one). Returns (n_states, t.size)."""
    corners = [float(c) for c in bp[:, 0]]
    if "clip" in model.fx:
        corners += level_crossings(bp, model.fx["clip"])
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
        ys = _piece(model, a, b, z0, t_out, h_max)
        y[:, sel] = ys[:, :int(sel.sum())]
        z0 = ys[:, -1].copy()
    return y


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor R at the times ``t`` [s] (default: the nominal grid), from
    rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the door's speed, as rad/s of the sprocket), plus the command ``u``
    [V]. ``states``: add the angles [rad] and the chain's stretch [rad]."""
    fx = dict(fx or {})
    p = {**MOTOR_R, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = Opener(fx, p)
    y = integrate(model, t, bp, H_MAX[regime])
    full = {"current": y[0], "speed": y[1], "load_speed": y[4]}
    if model.i_delay is not None:
        full["current"] = 2.0 * y[model.i_delay] - full["current"]
    if model.i_shunt is not None:
        full["current"] = full["current"] * (1.0 + fx["shunt"][3] * y[model.i_shunt])
    out = {probe: full[probe].copy() for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out.update(rotor_angle=y[2], stretch=y[3], door_angle=y[5])
        if model.i_shunt is not None:
            out["shunt_rise"] = y[model.i_shunt]
    return out


# ---------------------------------------------------------------------- noise

def gauss_markov(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float
                 ) -> np.ndarray:
    """A stationary first-order Gauss-Markov process [probe unit] of standard deviation
    ``sigma`` and correlation time ``tau`` [s], exact at the times ``t`` [s] however uneven."""
    r = np.exp(-np.diff(np.asarray(t, dtype=float)) / tau)
    e = rng.standard_normal(len(t))
    x = np.empty(len(t))
    x[0] = sigma * e[0]
    kick = sigma * np.sqrt(1.0 - r * r) * e[1:]
    for k in range(1, len(t)):
        x[k] = r[k - 1] * x[k - 1] + kick[k - 1]
    return x


def ar1(rng: np.random.Generator, t: np.ndarray, sigma: float, phi: float) -> np.ndarray:
    """AR(1) noise [probe unit]: correlation ``phi`` over the mean interval."""
    return gauss_markov(rng, t, sigma, -float(np.mean(np.diff(t))) / math.log(phi))


def pink(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise [probe unit] of standard deviation ``sigma``: equal-variance Gauss-Markov
    processes whose correlation times are an octave apart, from the record's length down to
    the mean interval, mean removed and scaled."""
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
