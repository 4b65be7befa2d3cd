"""Motor AF of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC motor in a quarter-turn ELECTRIC VALVE ACTUATOR on a buried DN200 butterfly valve
of a water main. The actuator's spur train and final worm stage (a rigid, lossless 600:1
gearbox) turn its output sleeve; a 1.5 m steel extension spindle (the valve sits in the ground,
the actuator in a chamber above it) twists between the sleeve and the valve's stem and disc.
The disc meets three loads: the stem's packing and bearings (a dry friction) and the water in
its bearings (a viscous friction); the elastomer liner's seat, which grips the disc's edge
near closed, a dry friction Ts exp(-(angle / ths)^2) that fades as the disc swings out of it;
and the flow's hydrodynamic torque, -Th sin(angle)^2 sin(2 angle), which pulls the disc
towards closed (nothing closed or fully open, the most, 0.65 Th, at 60 degrees).

No circuitsim import: an independent simulator (the twenty-ninth of the benchmark), written
from the physics for netlists/motor_af_fast.yaml and motor_af_slow.yaml. It is evaluated at
the record's own sample times (``t_eval``), never on a grid that is then interpolated.
Everything rests at t = 0: no current, no speed, the disc closed (angle 0) and the spindle
untwisted; the seat's and the flow's torques vanish there, so nothing creeps.

The gearbox is rigid and lossless (``gear`` G, ratio N = 600): the sleeve (the body ``hub``)
stands at th / N and turns at w / N with the rotor; a torque T on it is T / N on the rotor.
The spindle is a spring and a damper on the twist th / N - thd between the sleeve and the disc
(``spring_damper`` K).

State y = [i, w, th, wd, thd] (+ one Pade stage per delayed probe, in this order):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wd, thd    the disc's speed and angle [rad/s, rad] (0: closed, pi/2: fully open)

Equations (Jr = Jm + Jh / N^2: the rotor and the worm with the sleeve and the worm wheel):

    L di/dt   = u(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor + (X_hub - Ts_k) / N
    Jd dwd/dt = Ts_k - Td tanh(wd / 0.01) - Bd wd - Ts exp(-(thd / ths)^2) tanh(wd / 0.01)
                - Th sin(thd)^2 sin(2 thd) + X_disc
    Ts_k      = Ks (th / N - thd) + Ds (w / N - wd)            (the spindle)

Tm tanh(w / 0.01) is the brushes' and the worm's dry friction (``friction``, w_brk 0.1),
Td tanh(wd / 0.01) the stem's packing and bearings (``friction``, w_brk 0.1), Bd wd the water
in the disc's bearings (``damper``), the seat's grip and the flow's torque ``btorque`` each.

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, disc) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in the spindle K (Modelica's ElastoBacklash):
              no torque while |twist| < gap / 2, else Ks (twist -+ gap / 2) + Ds w_rel,
              the damping never pulling the sides together
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    flutter   (Tv [N m], f [Hz]): vortices shed from the open disc's edges: the disc
              receives Tv sin(thd)^2 sin(2 pi f t), nothing closed, growing as it opens
    brushes   (Vf, Vr [V]): reaction brushes angled for one direction: the contact drop is
              Vf while the current flows forward (opening), Vr while it flows back: the
              loop takes tanh(i / 1 mA) ((Vf + Vr) / 2 + (Vf - Vr) / 2 tanh(i / 1 mA))
    lip       (Tl [N m], th1 [rad], wl [rad]): a displaced lip of the seat's liner rubs the
              disc's edge around th1: the disc takes Tl exp(-((thd - th1) / wl)^2)
              tanh(wd / 0.01) against its motion
    emf_speed True: the speed column is the controller's back-EMF estimate (u - R i) / k
              (the declared R and k, no encoder): it reads w + (L / k) di/dt
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AF [SI] (motor_af_fast.yaml, motor_af_slow.yaml)
MOTOR_AF: dict[str, float] = {
    "R": 0.9, "L": 1.2e-3, "k": 0.06, "Jm": 5e-5, "bm": 1e-5, "Tm": 0.05, "N": 600.0,
    "Jh": 0.01, "Ks": 4000.0, "Ds": 1.0, "Jd": 0.03, "Bd": 1.5, "Td": 4.0,
    "Ts": 40.0, "ths": 0.12, "Th": 40.0,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_af_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.06, 24.0), (0.26, 24.0), (0.27, 10.0),
               (0.34, 10.0), (0.345, 0.0), (0.4, 0.0), (0.42, -20.0), (0.5, -20.0),
               (0.505, 0.0), (0.6, 0.0))
#: the slow regime's logged command [s, V] (motor_af_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.3, 0.0), (0.5, 24.0), (2.3, 24.0), (2.45, 8.0), (3.0, 8.0),
               (3.1, 0.0), (4.2, 0.0), (4.5, -22.0), (6.2, -22.0), (6.35, -6.0),
               (7.5, -6.0), (7.6, 0.0), (8.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.6), "slow": (250.0, 8.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "disc")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime, a quarter of the
#: mean interval in the slow one (the disc rings on the spindle at 58 Hz)
MAX_STEP = {"fast": 5e-5, "slow": 1e-3}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.array(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class ValveActuator:
    """Right-hand side of motor AF with one set of effects ``fx`` [SI]; ``ramp`` holds the
    command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.ratio = p["N"]
        self.j_rotor = p["Jm"] + p["Jh"] / self.ratio ** 2
        #: (probe, tau [s], index of its Pade state)
        self.delays: list[tuple[str, float, int]] = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.delays.append((probe, float(s["delay"]), 5 + len(self.delays)))
        self.size = 5 + len(self.delays)
        self.extras = {body: self._collect(body) for body in BODIES}
        self.ramp = (0.0, 0.0, 0.0)

    def _collect(self, body: str) -> dict[str, Any]:
        """The catalog's effects on ``body`` (empty when none)."""
        out = {}
        for key in ("visc", "coul", "offset", "stribeck", "cog"):
            value = self.fx.get(key, {}).get(body)
            if value:
                out[key] = value
        return out

    def body_torque(self, body: str, w: float, angle: float) -> float:
        """The torque [N m] the catalog's effects give ``body`` at the speed ``w`` [rad/s]
        and the angle ``angle`` [rad]."""
        ex = self.extras[body]
        if not ex:
            return 0.0
        sw = math.tanh(w / W_SWITCH)
        tq = ex.get("offset", 0.0) - ex.get("visc", 0.0) * w - ex.get("coul", 0.0) * sw
        if "stribeck" in ex:
            peak, ws = ex["stribeck"]
            tq -= peak * math.exp(-(w / ws) ** 2) * sw
        for order, a, b in ex.get("cog", ()):
            tq += a * math.sin(order * angle) + b * math.cos(order * angle)
        return tq

    def command(self, t: float) -> float:
        """The bridge's mean output [V] within the current segment."""
        t0, u0, slope = self.ramp
        return u0 + slope * (t - t0)

    def resistance(self, t: float) -> float:
        """The loop's resistance [ohm] at the time ``t`` [s]: the armature (drifting or
        warming), and a resistance in series or in the source."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        return r + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)

    def loop_voltage(self, t: float, i: float, w: float, th: float) -> float:
        """The voltage [V] the loop takes at ``t`` [s] besides the inductance's and the
        declared EMF's, at the current ``i`` [A], the rotor's speed ``w`` [rad/s] and angle
        ``th`` [rad]."""
        fx = self.fx
        v = self.resistance(t) * i
        if "Vb" in fx:
            v += fx["Vb"] * math.tanh(i / I_SWITCH)
        if "brushes" in fx:
            vf, vr = fx["brushes"]
            s = math.tanh(i / I_SWITCH)
            v += s * (0.5 * (vf + vr) + 0.5 * (vf - vr) * s)
        for order, a, b in fx.get("emf", ()):
            v += w * (a * math.sin(order * th) + b * math.cos(order * th))
        return v

    def inductance(self, i: float) -> float:
        """The differential inductance [H] at the current ``i`` [A]."""
        ell = self.p["L"]
        if "lsat" in self.fx:
            ipar, ratio = self.fx["lsat"]
            ell *= ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2)
        return ell

    def spindle(self, twist: float, wrel: float) -> float:
        """The spindle's torque [N m] on the disc at the ``twist`` [rad] and the relative
        speed ``wrel`` [rad/s] (the sleeve's minus the disc's), with a play if ``gap``."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        if "gap" not in self.fx:
            return ks * twist + ds * wrel
        half = 0.5 * self.fx["gap"]
        if abs(twist) <= half:
            return 0.0
        edge = half if twist > 0.0 else -half
        push = ks * (twist - edge) + ds * wrel
        return max(push, 0.0) if twist > 0.0 else min(push, 0.0)

    def disc_load(self, t: float, wd: float, thd: float) -> float:
        """The torque [N m] the packing, the water, the seat and the flow (and the outside
        effects on the disc) give the disc at ``t`` [s], turning at ``wd`` [rad/s], standing
        at ``thd`` [rad]."""
        p, fx = self.p, self.fx
        sw = math.tanh(wd / W_SWITCH)
        s = math.sin(thd)
        tq = (-p["Td"] * sw - p["Bd"] * wd - p["Ts"] * math.exp(-(thd / p["ths"]) ** 2) * sw
              - p["Th"] * s * s * math.sin(2.0 * thd))
        if "flutter" in fx:
            tv, f = fx["flutter"]
            tq += tv * s * s * math.sin(2.0 * math.pi * f * t)
        if "lip" in fx:
            tl, th1, wl = fx["lip"]
            tq -= tl * math.exp(-((thd - th1) / wl) ** 2) * sw
        return tq

    def __call__(self, t: float, y: np.ndarray) -> list[float]:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n = self.p, self.ratio
        i, w, th, wd, thd = (float(v) for v in y[:5])
        di = (self.command(t) - self.loop_voltage(t, i, w, th) - p["k"] * w) / self.inductance(i)
        tk = self.spindle(th / n - thd, w / n - wd)
        torque = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                  + self.body_torque("rotor", w, th)
                  + (self.body_torque("hub", w / n, th / n) - tk) / n)
        dwd = (tk + self.disc_load(t, wd, thd) + self.body_torque("disc", wd, thd)) / p["Jd"]
        seen = {"current": i, "speed": w, "load_speed": wd}
        pade = [2.0 * (seen[probe] - float(y[k])) / tau for probe, tau, k in self.delays]
        return [di, torque / self.j_rotor, w, dwd, wd, *pade]


# ---------------------------------------------------------------------- integration

def _piece(model: ValveActuator, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
           max_step: float) -> np.ndarray:
    """The states at ``t_out`` [s] from ``y0`` at ``a`` to ``b`` [s]: LSODA, Radau if LSODA
    fails."""
    why = ""
    for method in ("LSODA", "Radau"):
        sol = solve_ivp(model, (a, b), y0, method=method, t_eval=t_out, rtol=RTOL,
                        atol=ATOL, max_step=max_step)
        if sol.success and sol.y.shape[1] == t_out.size and np.isfinite(sol.y).all():
            return sol.y
        why = sol.message
    raise RuntimeError(f"motor AF, {a:g}-{b:g} s: {why}")


def integrate(model: ValveActuator, t: np.ndarray, bp: np.ndarray, max_step: float
              ) -> np.ndarray:
    """The states (n_states, t.size) at the increasing times ``t`` [s], from rest at 0, the
    integration restarted at every corner of the command ``bp`` [s, V]."""
    end = float(t[-1])
    corners = sorted({0.0, end, *(float(c) for c in bp[:, 0] if 0.0 < c < end)})
    out = np.empty((model.size, t.size))
    y0 = np.zeros(model.size)
    for a, b in itertools.pairwise(corners):
        ua, ub = np.interp([a, b], bp[:, 0], bp[:, 1])
        model.ramp = (a, float(ua), float(ub - ua) / (b - a))
        inside = (t >= a) & ((t <= b) if b == end else (t < b))
        t_out = t[inside] if b == end else np.append(t[inside], b)
        ys = _piece(model, a, b, y0, t_out, max_step)
        out[:, inside] = ys[:, :int(inside.sum())]
        y0 = ys[:, -1].copy()
    return out


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor AF at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the valve's stem, from an encoder on its top flange), plus the
    command ``u`` [V]. ``states``: add the angles [rad] and the spindle's torque [N m]."""
    fx = dict(fx or {})
    p = {**MOTOR_AF, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = ValveActuator(fx, p)
    y = integrate(model, t, bp, MAX_STEP[regime])
    u = np.interp(t, bp[:, 0], bp[:, 1])
    true = {"current": y[0], "speed": y[1], "load_speed": y[3]}
    for probe, _, k in model.delays:
        true[probe] = 2.0 * y[k] - true[probe]
    if fx.get("emf_speed"):
        true["speed"] = (u - p["R"] * y[0]) / p["k"]
    out = {probe: np.array(true[probe]) for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = u
    if states:
        twist = y[2] / p["N"] - y[4]
        out.update(rotor_angle=y[2], disc_angle=y[4], disc_speed=y[3],
                   spindle_torque=p["Ks"] * twist + p["Ds"] * (y[1] / p["N"] - y[3]))
    return out


# ---------------------------------------------------------------------- noise

def ar1(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float) -> np.ndarray:
    """A stationary first-order Gauss-Markov process [probe unit], standard deviation
    ``sigma``, correlation time ``tau`` [s], sampled exactly at the (uneven) times ``t``."""
    rho = np.exp(-np.diff(t) / tau)
    kick = rng.standard_normal(t.size) * sigma
    kick[1:] *= np.sqrt(1.0 - rho ** 2)
    x = np.empty(t.size)
    x[0] = kick[0]
    for j, r in enumerate(rho, start=1):
        x[j] = r * x[j - 1] + kick[j]
    return x


def pink(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise [probe unit] of standard deviation ``sigma`` at the times ``t`` [s]: white
    noise on an even grid over the record, its amplitude spectrum divided by sqrt(f) (no
    mean), read at ``t`` linearly."""
    n = t.size
    even = np.linspace(float(t[0]), float(t[-1]), n)
    f = np.fft.rfftfreq(n, float(even[1] - even[0]))
    spectrum = np.fft.rfft(rng.standard_normal(n))
    spectrum[0] = 0.0
    spectrum[1:] *= np.sqrt(f[1] / f[1:])
    x = np.interp(t, even, np.fft.irfft(spectrum, n))
    x -= x.mean()
    return x * (sigma / x.std())


def add_noise(rng: np.random.Generator, t: np.ndarray, y: np.ndarray,
              spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` at the times ``t`` [s] with ``white`` sigma, ``ar1`` [sigma, phi] (a
    Gauss-Markov process correlated by phi over the mean interval) and ``pink`` (1/f) sigma
    noise added [probe unit], then read by an ADC of step ``quant`` [probe unit]."""
    out = np.array(y, dtype=float)
    if spec.get("white"):
        out += rng.normal(0.0, spec["white"], out.size)
    if spec.get("ar1"):
        sigma, phi = spec["ar1"]
        out += ar1(rng, t, sigma, -float(np.mean(np.diff(t))) / math.log(phi))
    if spec.get("pink"):
        out += pink(rng, t, spec["pink"])
    step = spec.get("quant")
    return np.round(out / step) * step if step else out
