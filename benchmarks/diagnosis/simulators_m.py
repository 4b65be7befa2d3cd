"""Motor M of the diagnosis benchmark: a hand-written scipy model of a 48 V, 500 W class
permanent-magnet brushed DC motor (2 poles, 7 slots, 7 commutator bars) driving the
impeller of a centrifugal blower directly, through a short elastomer jaw coupling.

No circuitsim import: an independent simulator, written from the physics for
netlists/motor_m_motor.yaml, motor_m.yaml and motor_m_slow.yaml. It is evaluated at the
record's own sample times (even or a data logger's uneven ones): the ODE is solved with
``t_eval`` at the very times, never on a uniform grid that is interpolated.

Base state (5 numbers) z = [i, w, th, wf, thf]:

    i    armature current [A]
    w    rotor speed [rad/s], th rotor angle [rad]
    wf   impeller (node ``fan``) speed [rad/s], thf its angle [rad]

Equations:

    L(i) di/dt = v - R(t) i - e,     e = k w + kh w sin(14 th + ph)   (+ an EMF harmonic)
    Jm dw/dt   = (k + kh sin(14 th + ph)) i - bm w - Tc tanh(w / 0.01) - Tk + X_rotor
    Jf dwf/dt  = Tk - bf wf - Tf tanh(wf / 0.01) - cf wf |wf| + X_fan
    Tk         = c (th - thf) + d (w - wf)          (the jaw coupling)

with X_node the torques an effect adds on a node. The order-14 ripple is declared (the
netlist's ``harmonics`` with ``ripple_torque``): it acts on the EMF and the torque alike.

Effects (``fx`` keys, SI, all off by default) -- the catalog's laws, as its patches write them:

    Rs        [ohm]   an internal resistance of the supply
    Rser      [ohm]   a resistance in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   R(t) = R (1 + alpha t)
    warmup    (rise, tau [s]): R(t) = R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): L(i) = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf_h     (order, a, b): e gains w (a sin(order th) + b cos(order th)), voltage only
    cog       {node: [(order, a, b), ...]}: the node (rotor or fan) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {node: c}: a Coulomb friction c tanh(speed / 0.01) against the node's motion
    visc      {node: b}: an extra viscous friction on the node
    offset    {node: F}: a constant torque F the node receives
    stribeck  {node: (s, ws)}: a breakaway peak s exp(-(speed / ws)^2) tanh(speed / 0.01)
    sensor    {probe: {"gain": g, "offset": o}}: the probe reads g y + o
    (a declared value off: pass motor parameters ``p`` with another value)

and outside the catalog:

    ntc       (R25 [ohm], B [K], Cth [J/K], Rth [K/W]): an NTC inrush limiter in the supply
              lead, R_ntc = R25 exp(B (1/(T0 + dT) - 1/T0)), T0 = 298.15 K, heated by its
              own loss: Cth d(dT)/dt = i^2 R_ntc - dT / Rth, cold (dT = 0) at t = 0
    chopper   (Roff [ohm], i0 [A]): a one-quadrant chopper (a switch and a freewheeling
              diode) that cannot carry a negative current: Roff (1 - tanh(i / i0)) / 2 i
              more in the armature loop, the diode's blocking as a large resistance
    rub       (T [N m], kappa, phase [rad]): the impeller rubs the inlet cone over a narrow
              arc once per turn: the fan receives
              -T exp(kappa (cos(thf - phase) - 1)) tanh(wf / 0.01)
    damper    (drop, t1 [s], tr [s]): a duct damper closes: the fan's load coefficient
              becomes cf (1 - drop g(t)), g(t) = (1 + tanh((t - t1) / tr)) / 2
    encoder   (e, phase [rad]): the motor's encoder disk is mounted off-centre: the speed
              reads w (1 + e cos(th + phase))
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_m_profile.csv"

#: declared values of motor M [SI] (motor_m_motor.yaml); ``nh``: the declared ripple's order
MOTOR_M: dict[str, float] = {
    "R": 0.45, "L": 0.9e-3, "k": 0.075, "kh": 3e-4, "ph": 0.5, "nh": 14.0,
    "Jm": 1.2e-4, "bm": 1e-5, "Tc": 0.015, "c": 120.0, "d": 0.05,
    "Jf": 6e-4, "bf": 2e-5, "Tf": 0.01, "cf": 3e-6,
}
#: [rad/s] circuitsim's friction (w_brk 0.1) and the catalog's friction switch as tanh(w/0.01)
W_SIGN = 0.01
#: [A] the catalog's brush drop switches sign as tanh(i / 1 mA)
I_SIGN = 1e-3
#: [K] the NTC's reference temperature (25 degC)
T0 = 298.15
#: the fast regime's command [s, V] (motor_m.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.005, 0.0), (0.125, 36.0), (0.22, 36.0), (0.223, 48.0),
               (0.33, 48.0), (0.332, 24.0), (0.43, 24.0), (0.46, 40.0), (0.5, 40.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.5), "slow": (250.0, 8.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
NODES = ("rotor", "fan")
RTOL, ATOL = 1e-10, 1e-12


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    if regime == "fast":
        return np.asarray(FAST_POINTS, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- sample times

def logger_times(rng: np.random.Generator, fs: float, duration: float, drops: int,
                 lo: float = 0.5, hi: float = 2.0, step: float = 1e-6
                 ) -> tuple[np.ndarray, np.ndarray]:
    """A slow logger's times [s] and those of the samples it dropped [s]: intervals of
    lo..hi [1] times the mean 1/fs [Hz] (lo + (hi - lo) Beta(2, b), b chosen for a mean of
    one), from 0 to at most ``duration`` [s], rounded to ``step`` [s]; then ``drops``
    interior samples removed (none adjacent to another)."""
    d0 = 1.0 / fs
    b = 2.0 * ((hi - lo) / (1.0 - lo) - 1.0)
    gaps = d0 * (lo + (hi - lo) * rng.beta(2.0, b, int(2 * duration * fs)))
    t = np.concatenate([[0.0], np.cumsum(gaps)])
    t = np.round(t[t <= duration] / step) * step
    pick = np.sort(rng.choice(np.arange(2, t.size - 2, 3), drops, replace=False))
    keep = np.ones(t.size, dtype=bool)
    keep[pick] = False
    return t[keep], t[pick]


# ---------------------------------------------------------------------- the model

class MotorM:
    """Right-hand side of motor M with one set of effects; an NTC's temperature rise [K] is
    appended after the five base states when ``fx`` has one."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.n = 6 if "ntc" in fx else 5
        self.seg = (0.0, 0.0, 0.0)
        self.extra = {node: (fx.get("offset", {}).get(node, 0.0),
                             fx.get("visc", {}).get(node, 0.0),
                             fx.get("coul", {}).get(node, 0.0),
                             list(fx.get("cog", {}).get(node, ())),
                             fx.get("stribeck", {}).get(node))
                      for node in NODES}

    def x0(self) -> np.ndarray:
        """Rest, cold [SI]."""
        return np.zeros(self.n)

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

    def fan_load(self, t: float, wf: float, thf: float) -> float:
        """The impeller's declared losses and load plus an outside rub or damper [N m]."""
        p, fx = self.p, self.fx
        cf = p["cf"]
        if "damper" in fx:
            drop, t1, tr = fx["damper"]
            cf *= 1.0 - drop * 0.5 * (1.0 + math.tanh((t - t1) / tr))
        tq = p["bf"] * wf + p["Tf"] * math.tanh(wf / W_SIGN) + cf * wf * abs(wf)
        if "rub" in fx:
            tr_, kappa, ph = fx["rub"]
            tq += tr_ * math.exp(kappa * (math.cos(thf - ph) - 1.0)) * math.tanh(wf / W_SIGN)
        return tq

    def loop_drop(self, t: float, i: float, th: float, z: np.ndarray) -> float:
        """Every voltage [V] the armature loop takes besides the EMF at current ``i`` [A]."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        r += fx.get("Rser", 0.0) + fx.get("Rs", 0.0)
        if "ntc" in fx:
            r += self.ntc(z[5])
        if "chopper" in fx:
            roff, i0 = fx["chopper"]
            r += 0.5 * roff * (1.0 - math.tanh(i / i0))
        return r * i + fx.get("Vb", 0.0) * math.tanh(i / I_SIGN)

    def ntc(self, dtemp: float) -> float:
        """The NTC's resistance [ohm] at a temperature rise ``dtemp`` [K]."""
        r25, b, _, _ = self.fx["ntc"]
        return r25 * math.exp(b * (1.0 / (T0 + dtemp) - 1.0 / T0))

    def inductance(self, i: float) -> float:
        """The armature's differential inductance [H] at current ``i`` [A]."""
        if "lsat" not in self.fx:
            return self.p["L"]
        ipar, ratio = self.fx["lsat"]
        return self.p["L"] * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))

    def __call__(self, t: float, z: np.ndarray) -> np.ndarray:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p, fx = self.p, self.fx
        i, w, th, wf, thf = z[:5]
        dz = np.zeros_like(z)
        ripple = p["kh"] * math.sin(p["nh"] * th + p["ph"])
        e = (p["k"] + ripple) * w
        if "emf_h" in fx:
            order, a, b = fx["emf_h"]
            e += w * (a * math.sin(order * th) + b * math.cos(order * th))
        ta, ua, slope = self.seg
        u = ua + slope * (t - ta)
        dz[0] = (u - self.loop_drop(t, i, th, z) - e) / self.inductance(i)
        tk = p["c"] * (th - thf) + p["d"] * (w - wf)
        dz[1] = ((p["k"] + ripple) * i - p["bm"] * w - p["Tc"] * math.tanh(w / W_SIGN) - tk
                 + self.added("rotor", w, th)) / p["Jm"]
        dz[2] = w
        dz[3] = (tk - self.fan_load(t, wf, thf) + self.added("fan", wf, thf)) / p["Jf"]
        dz[4] = wf
        if "ntc" in fx:
            _, _, cth, rth = fx["ntc"]
            dz[5] = (i * i * self.ntc(z[5]) - z[5] / rth) / cth
        return dz


def integrate(model: MotorM, t: np.ndarray, bp: np.ndarray, h_max: float) -> np.ndarray:
    """The states at the times ``t`` [s] (from rest at t[0]), restarting at every corner of
    the command ``bp`` [s, V]; LSODA (stiff/non-stiff switching), Radau as a fallback;
    steps of at most ``h_max`` [s]. Returns (n_states, t.size)."""
    cuts = [float(t[0])] + [float(b) for b in bp[:, 0] if t[0] < b < t[-1]] + [float(t[-1])]
    z0 = model.x0()
    y = np.empty((model.n, t.size))
    for j in range(len(cuts) - 1):
        a, b = cuts[j], cuts[j + 1]
        ua, ub = np.interp([a, b], bp[:, 0], bp[:, 1])
        model.seg = (a, float(ua), float((ub - ua) / (b - a)))
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
            raise RuntimeError(f"motor M, {a:g}-{b:g} s: {sol.message if sol else 'none'}")
        y[:, sel] = sol.y[:, :sel.sum()]
        z0 = sol.y[:, -1].copy()
    return y


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor M at the times ``t`` [s] (default: the nominal grid), from
    rest, plus the command ``u`` [V]: current [A], speed [rad/s] (and load_speed [rad/s] in
    the slow regime). ``states``: add the rotor's angle [rad] and the fan's speed and angle."""
    fx = dict(fx or {})
    p = dict(MOTOR_M if p is None else p)
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = MotorM(fx, p)
    y = integrate(model, t, bp, 1.0 / REGIMES[regime][0])
    full = {"current": y[0].copy(), "speed": y[1].copy(), "load_speed": y[3].copy()}
    if "encoder" in fx:
        ecc, ph = fx["encoder"]
        full["speed"] = y[1] * (1.0 + ecc * np.cos(y[2] + ph))
    out = {probe: full[probe] for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out["rotor_angle"], out["fan_speed"], out["fan_angle"] = y[2], y[3], y[4]
    return out


# ---------------------------------------------------------------------- noise

def ar1(rng: np.random.Generator, t: np.ndarray, sigma: float, phi: float) -> np.ndarray:
    """A stationary Gauss-Markov noise of standard deviation ``sigma`` [probe unit] at the
    times ``t`` [s]: its correlation over the mean interval is ``phi`` [1], over an interval
    dt it is phi^(dt / mean interval)."""
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
    """1/f noise of standard deviation ``sigma`` [probe unit] at the times ``t`` [s]: white
    noise shaped by f^-1/2 on an even grid four times as fine as the mean interval, read at
    ``t`` (the noise, not the motor, is interpolated), mean removed."""
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
