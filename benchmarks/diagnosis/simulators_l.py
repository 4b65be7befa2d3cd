"""Motor L of the diagnosis benchmark: a hand-written scipy model of a 12 V, 50 W class
permanent-magnet brushed DC motor driving the spindle of a bench micro-lathe through a
2.5:1 poly-V belt (a 20 mm pulley on the motor, a 50 mm pulley on the spindle).

No circuitsim import: an independent simulator (the ninth of the benchmark), written from
the physics for netlists/motor_l_motor.yaml, motor_l.yaml and motor_l_slow.yaml. It is
evaluated at arbitrary, unevenly spaced sample times (a data logger's): the ODE is solved
with ``t_eval`` at the very times, never on a uniform grid that is interpolated.

Base state (3 numbers) z = [i, w, th]:

    i    armature current [A]
    w    rotor speed [rad/s], th rotor angle [rad]; the spindle (node ``spindle``) turns
         rigidly with it through the belt at w / N, angle th / N

Equations (positive rotation turns the work towards the tool):

    L(i) di/dt = v - R(t) i - e,                      e = k w (+ an EMF harmonic)
    Jr dw/dt   = k i - bm w + X_rotor + (X_spindle - bs ws - Ts tanh(ws / 0.01)) / N

with Jr = Jm + Js / N^2, ws = w / N, and X_node the torques an effect adds on a node.

Effects (``fx`` keys, SI, all off by default) -- the catalog's laws, as its patches write them:

    Rs        [ohm]   an internal resistance of the supply
    Rser      [ohm]   a resistance in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   R(t) = R (1 + alpha t)
    warmup    (rise, tau [s]): R(t) = R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): L(i) = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf_h     (order, a, b): e gains w (a sin(order th) + b cos(order th)), voltage only
    cog       {node: [(order, a, b), ...]}: the node (rotor or spindle) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {node: c}: a Coulomb friction c tanh(speed / 0.01) against the node's motion
    visc      {node: b}: an extra viscous friction on the node
    offset    {node: F}: a constant torque F the node receives
    stribeck  {node: (s, ws)}: a breakaway peak s exp(-(speed / ws)^2) tanh(speed / 0.01)
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g y + o, y
              the probe through the first-order Pade stage of a delay tau (reads 2 s - x,
              tau/2 ds/dt = x - s, s(0) = 0)
    (a declared value off: pass motor parameters ``p`` with another value)

and outside the catalog:

    bar       (a, kappa, phase): a raised commutator bar: each of the two brushes lifts as
              the bar passes under it, twice per turn, and the armature's resistance rises
              by a R over a narrow arc: R (1 + a exp(kappa (cos(2 (th - phase)) - 1)))
    timing    (delta, w0 [rad/s]): the brushes are advanced for forward running: the
              armature reaction weakens the field forward and strengthens it backward,
              k becomes k (1 - delta tanh(w / w0)) in the EMF and in the torque alike
    cut       (T [N m], t1 [s], t2 [s], tr [s]): the tool is fed into the work between t1
              and t2: the spindle receives -T g(t) tanh(ws / 1 rad/s), g(t) =
              (tanh((t - t1) / tr) - tanh((t - t2) / tr)) / 2
    creep     c [N m s/rad]: the poly-V belt creeps: it carries T_b = c (w / N - ws) from
              the motor's pulley to the spindle, which becomes a body of its own (two more
              states: ws, the spindle's angle); the declared belt is rigid
    counts    True: the logger computes the motor's speed from the encoder's counts over
              its own sample intervals: speed(t_k) = (th(t_k) - th(t_k-1)) / (t_k - t_k-1)
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_l_profile.csv"

#: declared values of motor L [SI] (motor_l_motor.yaml)
MOTOR_L: dict[str, float] = {
    "R": 0.7, "L": 0.55e-3, "k": 0.032, "Jm": 3e-5, "bm": 3e-6, "N": 2.5,
    "Js": 4e-4, "bs": 2e-4, "Ts": 0.04,
}
#: [rad/s] circuitsim's friction (w_brk 0.1) and the catalog's friction switch as tanh(w/0.01)
W_SIGN = 0.01
#: [A] the catalog's brush drop switches sign as tanh(i / 1 mA)
I_SIGN = 1e-3
#: [rad/s] the cutting force's sign switches as tanh(ws / 1 rad/s)
W_CUT = 1.0
#: the fast regime's command [s, V] (motor_l.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.005, 0.0), (0.035, 12.0), (0.16, 12.0), (0.162, 6.0),
               (0.24, 6.0), (0.244, -7.0), (0.36, -7.0), (0.362, 0.0), (0.42, 0.0),
               (0.44, 10.0), (0.5, 10.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.5), "slow": (300.0, 8.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
NODES = ("rotor", "spindle")
RTOL, ATOL = 1e-10, 1e-12


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    if regime == "fast":
        return np.asarray(FAST_POINTS, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s] (for checks only: the records
    are sampled unevenly, see ``recordkit.jittered_times`` and ``logger_times``)."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- sample times

def logger_times(rng: np.random.Generator, fs: float, duration: float, drops: int,
                 lo: float = 0.6, hi: float = 2.6, step: float = 1e-6
                 ) -> tuple[np.ndarray, np.ndarray]:
    """A slow logger's times [s] and the times of the samples it dropped [s]: intervals of
    lo..hi times the mean 1/fs (lo + (hi - lo) Beta(1, b), b chosen for a mean of one),
    from 0 to at most ``duration``, rounded to ``step``; then ``drops`` interior samples
    removed (none adjacent to another)."""
    d0 = 1.0 / fs
    b = (hi - lo) / (1.0 - lo) - 1.0
    gaps = d0 * (lo + (hi - lo) * rng.beta(1.0, b, int(2 * duration * fs)))
    t = np.concatenate([[0.0], np.cumsum(gaps)])
    t = np.round(t[t <= duration] / step) * step
    pick = np.sort(rng.choice(np.arange(2, t.size - 2, 3), drops, replace=False))
    keep = np.ones(t.size, dtype=bool)
    keep[pick] = False
    return t[keep], t[pick]


class MotorL:
    """Right-hand side of motor L with one set of effects; the states the effects need are
    appended after the three base ones (or five, with a creeping belt)."""

    def __init__(self, bp: np.ndarray, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.t_cmd, self.u_cmd = bp[:, 0].copy(), bp[:, 1].copy()
        self.fx, self.p = fx, p
        self.rigid = "creep" not in fx
        self.n = 3 if self.rigid else 5
        self.idx: dict[str, int] = {}
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.idx["delay:" + probe] = self.n
                self.n += 1
        self.j_rotor = p["Jm"] + (p["Js"] / p["N"] ** 2 if self.rigid else 0.0)
        self.extra = {node: (fx.get("offset", {}).get(node, 0.0),
                             fx.get("visc", {}).get(node, 0.0),
                             fx.get("coul", {}).get(node, 0.0),
                             list(fx.get("cog", {}).get(node, ())),
                             fx.get("stribeck", {}).get(node))
                      for node in NODES}

    def x0(self) -> np.ndarray:
        """Rest [SI]."""
        return np.zeros(self.n)

    def u(self, t: float) -> float:
        """The command [V] at ``t`` [s]."""
        return float(np.interp(t, self.t_cmd, self.u_cmd))

    def added(self, node: str, w: float, angle: float) -> float:
        """The torque [N m] the catalog's effects add on a node at speed ``w`` [rad/s]."""
        off, visc, coul, harm, strib = self.extra[node]
        tq = off - visc * w
        if coul or strib is not None:
            sgn = math.tanh(w / W_SIGN)
            tq -= coul * sgn
            if strib is not None:
                tq -= strib[0] * math.exp(-(w / strib[1]) ** 2) * sgn
        for order, a, b in harm:
            tq += a * math.sin(order * angle) + b * math.cos(order * angle)
        return tq

    def spindle(self, t: float, ws: float, ths: float) -> float:
        """What the spindle receives [N m] besides the belt: its declared bearing losses,
        the effects on it and the tool's cut."""
        p = self.p
        tq = -p["bs"] * ws - p["Ts"] * math.tanh(ws / W_SIGN) + self.added("spindle", ws, ths)
        if "cut" in self.fx:
            tc, t1, t2, tr = self.fx["cut"]
            g = 0.5 * (math.tanh((t - t1) / tr) - math.tanh((t - t2) / tr))
            tq -= tc * g * math.tanh(ws / W_CUT)
        return tq

    def resistance(self, t: float, th: float) -> float:
        """The armature's resistance [ohm] at ``t`` [s], rotor angle ``th`` [rad]."""
        r0 = self.p["R"]
        r = r0 * (1.0 + self.fx.get("alpha", 0.0) * t)
        if "warmup" in self.fx:
            rise, tau = self.fx["warmup"]
            r += r0 * rise * (1.0 - math.exp(-t / tau))
        if "bar" in self.fx:
            a, kappa, ph = self.fx["bar"]
            r += r0 * a * math.exp(kappa * (math.cos(2.0 * (th - ph)) - 1.0))
        return r + self.fx.get("Rser", 0.0)

    def inductance(self, i: float) -> float:
        """The armature's differential inductance [H] at current ``i`` [A]."""
        if "lsat" not in self.fx:
            return self.p["L"]
        ipar, ratio = self.fx["lsat"]
        return self.p["L"] * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))

    def constant(self, w: float) -> float:
        """The motor constant [N m/A = V s/rad] at rotor speed ``w`` [rad/s]."""
        if "timing" in self.fx:
            delta, w0 = self.fx["timing"]
            return self.p["k"] * (1.0 - delta * math.tanh(w / w0))
        return self.p["k"]

    def __call__(self, t: float, z: np.ndarray) -> np.ndarray:
        p, fx = self.p, self.fx
        i, w, th = z[:3]
        n = p["N"]
        dz = np.zeros_like(z)
        k = self.constant(w)
        v = self.u(t) - fx.get("Rs", 0.0) * i - fx.get("Vb", 0.0) * math.tanh(i / I_SIGN)
        e = k * w
        if "emf_h" in fx:
            order, a, b = fx["emf_h"]
            e += w * (a * math.sin(order * th) + b * math.cos(order * th))
        dz[0] = (v - self.resistance(t, th) * i - e) / self.inductance(i)
        t_rotor = k * i - p["bm"] * w + self.added("rotor", w, th)
        if self.rigid:
            t_rotor += self.spindle(t, w / n, th / n) / n
        else:
            ws, ths = z[3], z[4]
            belt = fx["creep"] * (w / n - ws)
            t_rotor -= belt / n
            dz[3] = (belt + self.spindle(t, ws, ths)) / p["Js"]
            dz[4] = ws
        dz[1] = t_rotor / self.j_rotor
        dz[2] = w
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                j = self.idx["delay:" + probe]
                dz[j] = (self.quantity(probe, z) - z[j]) / (0.5 * s["delay"])
        return dz

    def quantity(self, probe: str, z: np.ndarray) -> Any:
        """The physical quantity a probe measures, from a state (or an array of states)."""
        if probe == "load_speed":
            return z[1] / self.p["N"] if self.rigid else z[3]
        return {"current": z[0], "speed": z[1]}[probe]


def integrate(model: MotorL, t: np.ndarray, bp: np.ndarray, h_max: float) -> np.ndarray:
    """The states at the times ``t`` [s] (from rest at t[0]), restarting at every corner of
    the command; LSODA, Radau as a fallback. Returns (n_states, t.size)."""
    cuts = [float(t[0])] + [float(b) for b in bp[:, 0] if t[0] < b < t[-1]] + [float(t[-1])]
    z0 = model.x0()
    y = np.empty((model.n, t.size))
    for j in range(len(cuts) - 1):
        a, b = cuts[j], cuts[j + 1]
        last = j == len(cuts) - 2
        sel = (t >= a) & (t <= b) if last else (t >= a) & (t < b)
        t_out = t[sel] if last else np.append(t[sel], b)
        sol = None
        for method in ("LSODA", "Radau"):
            sol = solve_ivp(model, (a, b), z0, method=method, t_eval=t_out, rtol=RTOL,
                            atol=ATOL, max_step=h_max)
            if sol.success and np.isfinite(sol.y).all():
                break
        if sol is None or not (sol.success and np.isfinite(sol.y).all()):
            raise RuntimeError(f"motor L, {a:g}-{b:g} s: {sol.message if sol else 'none'}")
        y[:, sel] = sol.y[:, :sel.sum()]
        z0 = sol.y[:, -1].copy()
    return y


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor L at the times ``t`` [s] (default: the nominal grid), from
    rest, plus the command ``u`` [V]: current [A], speed [rad/s] (and load_speed [rad/s] in
    the slow regime). ``states``: add the rotor's angle and the spindle's speed and angle."""
    fx = dict(fx or {})
    p = dict(MOTOR_L if p is None else p)
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = MotorL(bp, fx, p)
    y = integrate(model, t, bp, 1.0 / REGIMES[regime][0])
    out: dict[str, np.ndarray] = {}
    for probe in PROBES[regime]:
        x = np.asarray(model.quantity(probe, y), dtype=float)
        s = fx.get("sensor", {}).get(probe, {})
        if s.get("delay"):
            x = 2.0 * y[model.idx["delay:" + probe]] - x
        out[probe] = x
    if fx.get("counts"):
        out["speed"] = np.concatenate([[y[1, 0]], np.diff(y[2]) / np.diff(t)])
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out["rotor_angle"] = y[2].copy()
        out["spindle_speed"] = y[1] / p["N"] if model.rigid else y[3].copy()
        out["spindle_angle"] = y[2] / p["N"] if model.rigid else y[4].copy()
    return out


# ---------------------------------------------------------------------- noise

def ar1(rng: np.random.Generator, t: np.ndarray, sigma: float, phi: float) -> np.ndarray:
    """A stationary Gauss-Markov (Ornstein-Uhlenbeck) noise of standard deviation ``sigma``
    sampled at the times ``t`` [s]: its correlation over the mean interval is ``phi``, over
    an interval dt it is phi^(dt / mean interval)."""
    rho = phi ** (np.diff(t) / np.mean(np.diff(t)))
    e = rng.normal(0.0, 1.0, t.size)
    out = np.empty(t.size)
    acc = sigma * e[0]
    out[0] = acc
    for j in range(1, t.size):
        acc = rho[j - 1] * acc + sigma * math.sqrt(1.0 - rho[j - 1] ** 2) * e[j]
        out[j] = acc
    return out


def pink(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise at the times ``t`` [s]: white noise shaped by f^-1/2 on an even grid four
    times as fine as the mean interval, read at ``t`` (a noise, not the motor, is
    interpolated), mean removed, standard deviation ``sigma``."""
    n = 4 * t.size
    spec = np.fft.rfft(rng.normal(size=n))
    f = np.fft.rfftfreq(n)
    spec[0] = 0.0
    spec[1:] = spec[1:] / np.sqrt(f[1:])
    x = np.interp(t, np.linspace(t[0], t[-1], n), np.fft.irfft(spec, n))
    x -= np.mean(x)
    return sigma * x / np.std(x)


def add_noise(rng: np.random.Generator, t: np.ndarray, y: np.ndarray,
              spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` at the times ``t`` [s] plus ``white`` sigma, ``ar1`` [sigma, phi] and ``pink``
    sigma noise [probe unit], then rounded to the ADC step ``quant`` [probe unit]."""
    out = np.array(y, dtype=float)
    if spec.get("white"):
        out = out + rng.normal(0.0, spec["white"], out.size)
    if spec.get("ar1"):
        out = out + ar1(rng, t, *spec["ar1"])
    if spec.get("pink"):
        out = out + pink(rng, t, spec["pink"])
    if spec.get("quant"):
        out = np.round(out / spec["quant"]) * spec["quant"]
    return out
