"""Motor N of the diagnosis benchmark: a hand-written scipy model of a 24 V, 150 W class
permanent-magnet brushed DC motor (4 poles, 6 slots) driving the head drum of an inclined
belt conveyor (a parcel incline, 10 degrees) through a rigid 20:1 spur gearhead.

No circuitsim import: an independent simulator (the eleventh of the benchmark), written
from the physics for netlists/motor_n_motor.yaml, motor_n.yaml and motor_n_slow.yaml. It is
evaluated at the record's own sample times (even, or jittered, or a data logger's irregular
ones): the ODE is solved with ``t_eval`` at those very times, never on a grid that is then
interpolated.

The gearhead is rigid and lossless in the declared model, so the drum turns at w / N and
its angle is th / N: one mechanical degree of freedom, written in the rotor's frame.
State z = [i, w, th] (+ [y, dy/dt] of a current sensor's filter and the speed vp [m/s] of a
dropped parcel, both outside the catalog):

    i    armature current [A]
    w    rotor speed [rad/s], th rotor angle [rad]; drum speed wd = w / N, angle thd = th / N

Equations (J = Jm + Jd / N^2, the inertia seen by the rotor):

    L(i) di/dt = u - R(t) i - (loop extras) - k w
    J dw/dt    = k i - bm w + X_rotor + (X_drum - bd wd - Td tanh(wd / 0.01) - Tg) / N

Tg is the declared gravity torque of the parcels on the incline at the drum (a constant
``torque`` source in the netlist), Td the declared idlers' and skirts' drag (``friction``,
w_brk 0.1, i.e. Td tanh(wd / 0.01 rad/s)), X_node the torque an effect adds on a node.

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs        [ohm]   an internal resistance of the supply (in the loop)
    Rser      [ohm]   a resistance in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   R(t) = R (1 + alpha t)
    warmup    (rise, tau [s]): R(t) = R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): L(i) = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    cog       {node: [(order, a, b), ...]}: the node (rotor or drum) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {node: c}: a Coulomb friction c tanh(speed / 0.01) against the node's motion
    visc      {node: b}: an extra viscous friction on the node
    offset    {node: F}: a constant torque F the node receives
    stribeck  {node: (s, ws)}: a breakaway peak s exp(-(speed / ws)^2) tanh(speed / 0.01)
    sensor    {probe: {"gain": g, "offset": o}}: the probe reads g y + o

and outside the catalog:

    bounce    (Rb [ohm], w1 [rad/s], dw [rad/s]): the brushes bounce on the commutator at
              high speed: a contact resistance Rb (1 + tanh((|w| - w1) / dw)) / 2 more in
              the loop (|w| smoothed as sqrt(w^2 + 1))
    csensor   (fn [Hz], zeta): the current is read through a second-order low-pass
              (natural frequency fn, damping ratio zeta), from rest
    items     (dT [N m], pitch [m], r [m], kappa, phase [rad]): parcels placed at a fixed
              pitch on the incline: the drum receives -dT tanh(kappa sin(2 pi r thd / pitch
              + phase)) about the declared mean gravity torque
    brake     (Tb [N m], tr [s], ((t_release, t_apply), ...)): a spring-applied holding brake
              on the motor's rear shaft: the rotor receives -Tb g(t) tanh(w / 0.01), g = 1
              (applied) but between each release and the following application, with
              tanh edges of time constant tr
    parcel    (m [kg], mu, slope [rad], r [m], ta [s], tr [s], eps [m/s]): a parcel of mass m
              dropped onto the belt at ta (its weight coming on over tr): it slides on the
              belt, kinetic friction mu m g cos(slope) tanh((r wd - vp) / eps) pulling it
              up to the belt's speed, then rides with it; the drum receives -F r. The
              parcel's speed vp [m/s] up the incline is one more state:
              m dvp/dt = h(t) (F - m g sin(slope)), h = (1 + tanh((t - ta) / tr)) / 2
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_n_profile.csv"

#: declared values of motor N [SI] (motor_n_motor.yaml)
MOTOR_N: dict[str, float] = {
    "R": 0.5, "L": 0.8e-3, "k": 0.06, "Jm": 6e-5, "bm": 5e-6, "N": 20.0,
    "Jd": 0.07, "bd": 0.02, "Td": 0.8, "Tg": 1.7,
}
#: [rad/s] circuitsim's friction (w_brk 0.1) and the catalog's switch: tanh(w / 0.01)
W_SIGN = 0.01
#: [A] the catalog's brush drop switches sign as tanh(i / 1 mA)
I_SIGN = 1e-3
#: the fast regime's command [s, V] (motor_n.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.005, 0.0), (0.085, 24.0), (0.2, 24.0), (0.202, 12.0),
               (0.28, 12.0), (0.282, 0.0), (0.33, 0.0), (0.335, -16.0), (0.43, -16.0),
               (0.435, 20.0), (0.5, 20.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.5), "slow": (400.0, 8.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
NODES = ("rotor", "drum")
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
                 step: float = 1e-6) -> tuple[np.ndarray, np.ndarray]:
    """A logger's times [s] and the times it dropped [s]: intervals of 0.4 + 0.6 Gamma(3,
    1/3) [1] times the mean 1/fs [Hz] (mean one, at most 3), from 0 to at most ``duration``
    [s], rounded to ``step`` [s]; then ``drops`` interior samples removed, none adjacent."""
    gaps = np.minimum(0.4 + 0.6 * rng.gamma(3.0, 1.0 / 3.0, int(1.5 * duration * fs)), 3.0)
    t = np.concatenate([[0.0], np.cumsum(gaps / fs)])
    t = np.round(t[t <= duration] / step) * step
    pick = np.sort(rng.choice(np.arange(3, t.size - 3, 4), drops, replace=False))
    keep = np.ones(t.size, dtype=bool)
    keep[pick] = False
    return t[keep], t[pick]


# ---------------------------------------------------------------------- the model

class MotorN:
    """Right-hand side of motor N with one set of effects ``fx`` [SI]; a current sensor's
    filter adds two states after the three base ones, a dropped parcel one more."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.n = 3 + 2 * ("csensor" in fx) + ("parcel" in fx)
        self.seg = (0.0, 0.0, 0.0)
        self.j = p["Jm"] + p["Jd"] / p["N"] ** 2
        self.torq = {node: (fx.get("offset", {}).get(node, 0.0),
                            fx.get("visc", {}).get(node, 0.0),
                            fx.get("coul", {}).get(node, 0.0),
                            tuple(fx.get("cog", {}).get(node, ())),
                            fx.get("stribeck", {}).get(node)) for node in NODES}

    def command(self, t: float) -> float:
        """The command u [V] in the current linear segment."""
        ta, ua, slope = self.seg
        return ua + slope * (t - ta)

    def extra(self, node: str, w: float, angle: float) -> float:
        """The torque [N m] the catalog's effects add on ``node`` turning at ``w`` [rad/s]
        at ``angle`` [rad]."""
        off, visc, coul, harm, strib = self.torq[node]
        tq = off - visc * w
        if coul or strib is not None:
            sgn = math.tanh(w / W_SIGN)
            tq -= coul * sgn
            if strib is not None:
                tq -= strib[0] * math.exp(-(w / strib[1]) ** 2) * sgn
        for order, a, b in harm:
            tq += a * math.sin(order * angle) + b * math.cos(order * angle)
        return tq

    def drum(self, wd: float, thd: float) -> float:
        """Every torque the drum receives [N m]: declared losses and gravity, the effects."""
        p, fx = self.p, self.fx
        tq = -p["bd"] * wd - p["Td"] * math.tanh(wd / W_SIGN) - p["Tg"]
        if "items" in fx:
            dt, pitch, r, kappa, ph = fx["items"]
            tq -= dt * math.tanh(kappa * math.sin(2.0 * math.pi * r * thd / pitch + ph))
        return tq + self.extra("drum", wd, thd)

    def parcel(self, t: float, wd: float, vp: float) -> tuple[float, float]:
        """A dropped parcel's pull on the drum [N m] and its acceleration [m/s^2]."""
        m, mu, slope, r, ta, tr, eps = self.fx["parcel"]
        f = mu * m * 9.81 * math.cos(slope) * math.tanh((r * wd - vp) / eps)
        h = 0.5 * (1.0 + math.tanh((t - ta) / tr))
        return -h * f * r, h * (f / m - 9.81 * math.sin(slope))

    def brake(self, t: float, w: float) -> float:
        """The holding brake's torque on the rotor [N m] (outside the catalog), or 0."""
        if "brake" not in self.fx:
            return 0.0
        tb, tr, spans = self.fx["brake"]
        g = 1.0 - sum(0.5 * (math.tanh((t - a) / tr) - math.tanh((t - b) / tr))
                      for a, b in spans)
        return -tb * g * math.tanh(w / W_SIGN)

    def loop(self, t: float, i: float, w: float) -> float:
        """The armature loop's voltage [V] besides the EMF and L di/dt, at ``i`` [A]."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        r += fx.get("Rser", 0.0) + fx.get("Rs", 0.0)
        if "bounce" in fx:
            rb, w1, dw = fx["bounce"]
            r += 0.5 * rb * (1.0 + math.tanh((math.sqrt(w * w + 1.0) - w1) / dw))
        return r * i + fx.get("Vb", 0.0) * math.tanh(i / I_SIGN)

    def inductance(self, i: float) -> float:
        """The armature's differential inductance [H] at ``i`` [A]."""
        if "lsat" not in self.fx:
            return self.p["L"]
        ipar, ratio = self.fx["lsat"]
        return self.p["L"] * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))

    def __call__(self, t: float, z: np.ndarray) -> np.ndarray:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p = self.p
        i, w, th = z[0], z[1], z[2]
        dz = np.empty_like(z)
        dz[0] = (self.command(t) - self.loop(t, i, w) - p["k"] * w) / self.inductance(i)
        drum = self.drum(w / p["N"], th / p["N"])
        if "parcel" in self.fx:
            pull, dz[-1] = self.parcel(t, w / p["N"], z[-1])
            drum += pull
        tq = p["k"] * i - p["bm"] * w + self.extra("rotor", w, th) + self.brake(t, w)
        dz[1] = (tq + drum / p["N"]) / self.j
        dz[2] = w
        if "csensor" in self.fx:
            fn, zeta = self.fx["csensor"]
            wn = 2.0 * math.pi * fn
            dz[3] = z[4]
            dz[4] = wn * wn * (i - z[3]) - 2.0 * zeta * wn * z[4]
        return dz


def integrate(model: MotorN, t: np.ndarray, bp: np.ndarray, h_max: float) -> np.ndarray:
    """The states at the times ``t`` [s], from rest at t[0], restarted at every corner of
    the command ``bp`` [s, V]; LSODA, Radau if it fails; steps of at most ``h_max`` [s].
    Returns (n_states, t.size)."""
    cuts = [float(t[0]), *(float(b) for b in bp[:, 0] if t[0] < b < t[-1]), float(t[-1])]
    z0 = np.zeros(model.n)
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
            raise RuntimeError(f"motor N, {a:g}-{b:g} s: {sol.message if sol else 'none'}")
        y[:, sel] = sol.y[:, :int(sel.sum())]
        z0 = sol.y[:, -1].copy()
    return y


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor N at the times ``t`` [s] (default: the nominal grid), from
    rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the drum's), plus the command ``u`` [V]. ``states``: add the rotor's
    angle [rad] and the drum's angle [rad]."""
    fx = dict(fx or {})
    p = dict(MOTOR_N if p is None else p)
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    y = integrate(MotorN(fx, p), t, bp, 1.0 / REGIMES[regime][0])
    u = np.interp(t, bp[:, 0], bp[:, 1])
    full = {"current": y[3].copy() if "csensor" in fx else y[0].copy(),
            "speed": y[1].copy(), "load_speed": y[1] / p["N"]}
    out = {probe: full[probe] for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = u
    if states:
        out["rotor_angle"], out["drum_angle"] = y[2], y[2] / p["N"]
    return out


# ---------------------------------------------------------------------- noise

def gauss_markov(rng: np.random.Generator, t: np.ndarray, sigma: float, phi: float
                 ) -> np.ndarray:
    """Stationary first-order Gauss-Markov noise of standard deviation ``sigma`` [probe
    unit] at the times ``t`` [s]; correlation ``phi`` [1] over the mean interval, phi^(dt /
    mean) over an interval dt (an AR(1) noise on an even grid)."""
    rho = phi ** (np.diff(t) / np.mean(np.diff(t)))
    e = rng.standard_normal(t.size)
    out = np.empty(t.size)
    out[0] = sigma * e[0]
    scale = sigma * np.sqrt(1.0 - rho ** 2)
    for j in range(1, t.size):
        out[j] = rho[j - 1] * out[j - 1] + scale[j - 1] * e[j]
    return out


def flicker(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise of standard deviation ``sigma`` [probe unit] at the times ``t`` [s]: white
    noise shaped by f^-1/2 on an even grid eight times as fine as the mean interval, read at
    ``t`` (the noise is interpolated, never the motor), mean removed."""
    n = 8 * t.size
    spec = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n)
    spec[0] = 0.0
    spec[1:] /= np.sqrt(f[1:])
    x = np.interp(t, np.linspace(t[0], t[-1], n), np.fft.irfft(spec, n))
    x -= x.mean()
    return sigma * x / x.std()


def add_noise(rng: np.random.Generator, t: np.ndarray, y: np.ndarray,
              spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` at the times ``t`` [s] plus ``white`` sigma, ``ar1`` [sigma, phi] and ``pink``
    sigma noise [probe unit], then rounded to the ADC step ``quant`` [probe unit]."""
    out = np.array(y, dtype=float)
    if spec.get("white"):
        out += rng.normal(0.0, spec["white"], out.size)
    if spec.get("ar1"):
        out += gauss_markov(rng, t, *spec["ar1"])
    if spec.get("pink"):
        out += flicker(rng, t, spec["pink"])
    if spec.get("quant"):
        out = np.round(out / spec["quant"]) * spec["quant"]
    return out
