"""Motor Z of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC motor in a SWIMMING-POOL ROBOT CLEANER's track drive: the sealed motor drives the
drive sprocket through a rigid 30:1 spur gearhead; the sprocket pulls a rubber track (the
track's lugs on the sprocket's teeth, the rubber's stretch a compliance) that carries the
robot, its entrained water and its scrubbing brush over the pool floor.

No circuitsim import: an independent simulator (the twenty-third of the benchmark), written
from the physics for netlists/motor_z_fast.yaml and motor_z_slow.yaml. It is evaluated at the
record's own sample times (``t_eval``), never on a grid that is then interpolated. Everything
rests at t = 0 (no current, no speed, the track unstretched).

The gearhead is rigid and lossless: the sprocket stands at ths = th / N and turns at
ws = w / N with the rotor; a torque T on the sprocket is T / N on the rotor. The robot is
reflected to the sprocket as an angle thb [rad] (its travel over the pitch radius 32 mm) and
a speed wb [rad/s]; the track couples the two as a spring and damper on the twist
ths - thb (``spring_damper``).

State z = [i, w, th, wb, thb] (+ the fuse's temperature rise, + one Pade stage per delayed
probe):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wb, thb    the robot's speed and travel, reflected to the sprocket [rad/s, rad]

Equations (J1 = Jm + Js / N^2: the rotor with its pinion and, through the gearhead, its
output gear and the sprocket):

    L di/dt  = v(t) - R i - k w - (the loop's extras)
    J1 dw/dt = k i - bm w - Tb tanh(w / 0.01) + X_rotor + S / N
    S        = -Bs ws - Tk + X_spr                          (on the sprocket)
    Jb dwb/dt = Tk - Bb wb - Tr tanh(wb / 0.01) - cq wb |wb| + X_robot
    Tk       = Kt (ths - thb) + Dt (ws - wb)                (the track; a play if ``gap``)

Tb tanh(w / 0.01) is the brushes' and the shaft seal's dry friction (``friction``, w_brk 0.1),
Bs ws the gearhead's oil churning at its output, Bb wb the scrubbing brush's and the water's
linear drag, Tr tanh(wb / 0.01) the track's rolling and the brush's dry scrubbing on the tiles
(``friction``) and cq wb |wb| the water's form drag (``btorque``).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, spr, robot) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in the track (Modelica's ElastoBacklash):
              no torque while |twist| < gap / 2, else Kt (twist -+ gap / 2) + Dt (ws - wb),
              never pulling the sides together
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    fuse      (R0 [ohm], a [1/K], C [J/K], G [W/K]): a resettable (PTC) fuse in the supply
              lead: R0 (1 + a dT) in the loop, its temperature rise dT [K] heated by its loss:
              C ddT/dt = R0 (1 + a dT) i^2 - G dT (from 0)
    tooth     (A [N m], kappa [1], th0 [rad]): a chipped tooth on the gearhead's output gear
              binding once per output turn: the sprocket takes
              -A exp(kappa (cos(ths - th0) - 1)) tanh(ws / 0.01)
    arc       ka [ohm s/rad]: the commutation's reactance drop, a voltage
              ka sqrt(w^2 + 1) i against the current (a resistance growing with the speed)
    cable     (cb [N m s/rad^2], x0 [rad]): the floating power cable dragged through the
              water, its drag growing with the length paid out: the robot takes
              -cb sqrt(thb^2 + x0^2) wb
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor Z [SI] (motor_z_fast.yaml, motor_z_slow.yaml)
MOTOR_Z: dict[str, float] = {
    "R": 0.9, "L": 6e-4, "k": 0.045, "Jm": 3e-5, "bm": 1.5e-5, "Tb": 6e-3, "N": 30.0,
    "Js": 4e-4, "Bs": 5e-3, "Kt": 40.0, "Dt": 0.08, "Jb": 0.0102, "Bb": 0.01, "Tr": 0.5,
    "cq": 5e-4,
}
#: [rad/s] the frictions' and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_z_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.03, 14.0), (0.15, 14.0), (0.152, 8.0),
               (0.22, 8.0), (0.25, -12.0), (0.32, -12.0), (0.322, 0.0), (0.36, 0.0),
               (0.362, 6.0), (0.4, 6.0))
#: the slow regime's logged command [s, V] (motor_z_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.2, 0.0), (0.4, 16.0), (1.4, 16.0), (1.5, 10.0), (2.2, 10.0),
               (2.4, 0.0), (2.6, 0.0), (2.8, -16.0), (3.6, -16.0), (3.7, -8.0), (4.2, -8.0),
               (4.3, 12.0), (5.0, 12.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.4), "slow": (1000.0, 5.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "spr", "robot")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime (L/R is
#: 0.67 ms), a fifth of the mean interval in the slow one
H_MAX = {"fast": 4e-5, "slow": 2e-4}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.asarray(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class TrackDrive:
    """Right-hand side of motor Z with one set of effects ``fx`` [SI]."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.n = p["N"]
        self.j1 = p["Jm"] + p["Js"] / self.n ** 2
        n_states = 5
        #: index of the fuse's temperature state, or None
        self.k_fuse: int | None = None
        if "fuse" in fx:
            self.k_fuse = n_states
            n_states += 1
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
        """The driver's mean output [V] as commanded, linear within the segment."""
        t0, u0, slope = self.seg
        return u0 + slope * (t - t0)

    def loop_resistance(self, t: float, w: float, dtf: float) -> float:
        """The loop's resistance [ohm] at the time ``t`` [s], the rotor's speed ``w``
        [rad/s] and the fuse's temperature rise ``dtf`` [K]: the armature's (drifting) and
        the extras'."""
        p, fx = self.p, self.fx
        r = p["R"]
        if "alpha" in fx:
            r += p["R"] * fx["alpha"] * t
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        if "arc" in fx:
            r += fx["arc"] * math.sqrt(w * w + 1.0)
        if "fuse" in fx:
            r += self.fuse_resistance(dtf)
        return r + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)

    def fuse_resistance(self, dtf: float) -> float:
        """The fuse's resistance [ohm] at its temperature rise ``dtf`` [K]."""
        r0, a, _, _ = self.fx["fuse"]
        return r0 * (1.0 + a * dtf)

    def inductance(self, i: float) -> float:
        """The differential inductance [H] at the current ``i`` [A]."""
        ell = self.p["L"]
        if "lsat" in self.fx:
            ipar, ratio = self.fx["lsat"]
            ell *= ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2)
        return ell

    def track_torque(self, twist: float, wrel: float) -> float:
        """The track's pull [N m] from the sprocket on the robot at the ``twist`` [rad] and
        the relative speed ``wrel`` [rad/s] (sprocket minus robot)."""
        p = self.p
        gap = self.fx.get("gap")
        if gap is None:
            return p["Kt"] * twist + p["Dt"] * wrel
        h = 0.5 * gap
        if twist > h:
            return max(p["Kt"] * (twist - h) + p["Dt"] * wrel, 0.0)
        if twist < -h:
            return min(p["Kt"] * (twist + h) + p["Dt"] * wrel, 0.0)
        return 0.0

    def sprocket_torque(self, ws: float, ths: float) -> float:
        """Everything the sprocket receives [N m] but the gear's and the track's torque."""
        out = -self.p["Bs"] * ws + self.extra_torque("spr", ws, ths)
        if "tooth" in self.fx:
            amp, kappa, th0 = self.fx["tooth"]
            out -= amp * math.exp(kappa * (math.cos(ths - th0) - 1.0)) * math.tanh(ws / W_SIGN)
        return out

    def robot_torque(self, wb: float, thb: float) -> float:
        """Everything the robot receives [N m] but the track's pull."""
        p, fx = self.p, self.fx
        out = (-p["Bb"] * wb - p["Tr"] * math.tanh(wb / W_SIGN) - p["cq"] * wb * abs(wb)
               + self.extra_torque("robot", wb, thb))
        if "cable" in fx:
            cb, x0 = fx["cable"]
            out -= cb * math.sqrt(thb * thb + x0 * x0) * wb
        return out

    def __call__(self, t: float, z: np.ndarray) -> list[float]:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p, fx, n = self.p, self.fx, self.n
        i, w, th, wb, thb = (float(v) for v in z[:5])
        dtf = float(z[self.k_fuse]) if self.k_fuse is not None else 0.0
        # the loop
        v = self.command(t) - self.loop_resistance(t, w, dtf) * i - p["k"] * w
        if "Vb" in fx:
            v -= fx["Vb"] * math.tanh(i / I_SIGN)
        for order, a, b in fx.get("emf", ()):
            v -= w * (a * math.sin(order * th) + b * math.cos(order * th))
        di = v / self.inductance(i)
        # the rotor with the sprocket through the rigid gearhead; the track; the robot
        ws, ths = w / n, th / n
        tk = self.track_torque(ths - thb, ws - wb)
        tau = (p["k"] * i - p["bm"] * w - p["Tb"] * math.tanh(w / W_SIGN)
               + self.extra_torque("rotor", w, th)
               + (self.sprocket_torque(ws, ths) - tk) / n)
        dwb = (tk + self.robot_torque(wb, thb)) / p["Jb"]
        out = [di, tau / self.j1, w, dwb, wb]
        if self.k_fuse is not None:
            _, _, cap, g = fx["fuse"]
            out.append((self.fuse_resistance(dtf) * i * i - g * dtf) / cap)
        values = {"current": i, "speed": w, "load_speed": wb}
        out += [2.0 * (values[probe] - float(z[k])) / tau_d for probe, tau_d, k in self.pade]
        return out


# ---------------------------------------------------------------------- integration

def _solve(model: TrackDrive, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor Z, {a:g}-{b:g} s: {msg}")


def integrate(model: TrackDrive, t: np.ndarray, bp: np.ndarray, h_max: float
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
    """Noise-free probes of motor Z at the times ``t`` [s] (default: the nominal grid), from
    rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the robot's ground speed over the sprocket's pitch radius, from its
    optical floor sensor), plus the command ``u`` [V]. ``states``: add the angles [rad]."""
    fx = dict(fx or {})
    p = {**MOTOR_Z, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = TrackDrive(fx, p)
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
        out.update(rotor_angle=y[2], sprocket_angle=y[2] / p["N"], robot_angle=y[4])
        if model.k_fuse is not None:
            out["fuse_rise"] = y[model.k_fuse]
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
