"""Motor AK of the diagnosis benchmark: a hand-written scipy model of a 90 V permanent-magnet
brushed DC motor (a 1/2 hp, 2-pole ceramic-magnet motor on a phase-controlled SCR supply) in a
POTTER'S WHEEL (a studio throwing wheel with a 14-inch cast-aluminium wheel head and a lump of
clay on it). The motor, standing upright under the wheel's tray, drives the wheel's vertical
shaft through a poly-V belt, a 38 mm motor pulley to a 304 mm shaft pulley (an 8:1 reduction,
its ratio rigid: `gear` G, lossless); the body ``hub`` is the shaft's pulley with the lower
shaft. The belt's stretch and the long shaft's twist are a compliance (`spring_damper` K)
between the pulley and the body ``wheel``, the wheel head with its clay (and the plaster bat
on it). Turning anticlockwise seen from above (the potter's usual direction) is wheel.w > 0.

No circuitsim import: an independent simulator (the thirty-fourth of the benchmark), written
from the physics for netlists/motor_ak_fast.yaml and motor_ak_slow.yaml. It is evaluated at
the record's own sample times (``t_eval``), never on a grid that is then interpolated.
Everything rests at t = 0: no current, no speed, the wheel head at 0 and the belt unstrained.

The belt's ratio is rigid (``gear`` G, ratio N = 8): the pulley stands at th / N and turns at
w / N with the rotor; a torque T on it is T / N on the rotor. The belt and the shaft are a
spring and a damper on the twist th / N - thw between the pulley and the wheel head
(``spring_damper`` K), their torque on the wheel head

    Tk = Ks (th / N - thw) + Ds (w / N - ww).

The wheel head meets three declared loads: its bearings' grease and the slurry on the head (a
viscous drag Bw ww, ``damper``); the potter's steadying hands on the clay (a dry friction
Tw tanh(ww / 0.01), ``friction``, w_brk 0.1); and the slurry film between the hands and the
spinning clay, which shears before the hands drag: a soft dry drag Cs tanh(ww / ws),
ws = 3 rad/s (``btorque`` Slurry).

State y = [i, w, th, ww, thw] (+ one Pade stage per delayed probe):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    ww, thw    the wheel head's speed and angle [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the rotor with its pulley, and the shaft's pulley):

    L di/dt   = u(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor + (X_hub - Tk) / N
    Jw dww/dt = Tk - Bw ww - Tw tanh(ww / 0.01) - Cs tanh(ww / ws) + X_wheel

Tm tanh(w / 0.01) is the brushes' and the bearings' dry friction (``friction``, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, wheel) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in the belt K (Modelica's ElastoBacklash): no
              torque while |twist| < gap / 2, else Ks (twist -+ gap / 2) + Ds w_rel, the
              damping never pulling the sides together
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    rub       (F [N m], a [rad], d [rad]): the splash pan, seated askew, touches the wheel
              head's rim at one point of its turn (at the head's angle a): the wheel head
              receives -F exp((cos(thw - a) - 1) / d^2) tanh(ww / 0.01), a dry drag once a
              turn, about d wide
    hands     (F [N m], t1 [s], t2 [s], dt [s]): the potter leans in to centre the clay
              between the times t1 and t2 (edges dt): the wheel head receives
              -F s((t - t1) / dt) s((t2 - t) / dt) tanh(ww / 0.01), s(x) = 1 / (1 + exp(-x))
    ripple    (m, f [Hz]): the SCR bridge's unfiltered output: the motor sees
              u(t) (1 + m cos(2 pi f t)) instead of its mean u(t) (the loop takes
              -m u(t) cos(2 pi f t) more)
    flat      (Rf [ohm], a [rad], d [rad]): a flat spot burnt into the commutator (the wheel
              stalled under a heavy lump while centring): once a turn of the rotor, at its
              angle a, the brushes ride over it and their contact resistance rises, the loop
              taking Rf exp((cos(th - a) - 1) / d^2) i
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AK [SI] (motor_ak_fast.yaml, motor_ak_slow.yaml)
MOTOR_AK: dict[str, float] = {
    "R": 2.4, "L": 0.012, "k": 0.45, "Jm": 1.2e-3, "bm": 2e-4, "Tm": 0.05, "N": 8.0,
    "Jh": 0.02, "Ks": 600.0, "Ds": 1.5, "Jw": 0.09, "Bw": 0.05, "Tw": 1.5, "Cs": 2.0,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: [rad/s] the slurry film's speed scale, tanh(ww / ws)
W_SLURRY = 3.0
#: the fast regime's command [s, V] (motor_ak_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.02, 0.0), (0.1, 90.0), (0.24, 90.0), (0.3, 0.0),
               (0.33, 0.0), (0.39, -60.0), (0.45, -60.0), (0.48, 0.0), (0.5, 0.0))
#: the slow regime's logged command [s, V] (motor_ak_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.2, 0.0), (0.7, 60.0), (1.8, 60.0), (2.0, 90.0), (2.8, 90.0),
               (3.1, 30.0), (3.5, 30.0), (3.6, 0.0), (3.9, 0.0), (4.2, -45.0),
               (4.8, -45.0), (4.9, 0.0), (5.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.5), "slow": (500.0, 5.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "wheel")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime, a fifth of the
#: mean interval in the slow one
MAX_STEP = {"fast": 4e-5, "slow": 4e-4}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.array(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


def logistic(x: float) -> float:
    """1 / (1 + exp(-x)), without overflow."""
    if x >= 0.0:
        return 1.0 / (1.0 + math.exp(-x))
    e = math.exp(x)
    return e / (1.0 + e)


# ---------------------------------------------------------------------- the model

class WheelDrive:
    """Right-hand side of motor AK with one set of effects ``fx`` [SI]; ``ramp`` holds the
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
        """The controller's mean output [V] within the current segment."""
        t0, u0, slope = self.ramp
        return u0 + slope * (t - t0)

    def resistance(self, t: float, th: float) -> float:
        """The loop's resistance [ohm] at the time ``t`` [s] and the rotor's angle ``th``
        [rad]: the armature (drifting or warming), a resistance in series or in the source,
        and the brushes on a flat of the commutator."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        if "flat" in fx:
            rf, a, d = fx["flat"]
            r += rf * math.exp((math.cos(th - a) - 1.0) / d ** 2)
        return r + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)

    def loop_voltage(self, t: float, i: float, w: float, th: float) -> float:
        """The voltage [V] the loop takes at ``t`` [s] besides the inductance's and the
        declared EMF's, at the current ``i`` [A], the rotor's speed ``w`` [rad/s] and angle
        ``th`` [rad]."""
        fx = self.fx
        v = self.resistance(t, th) * i
        if "Vb" in fx:
            v += fx["Vb"] * math.tanh(i / I_SWITCH)
        for order, a, b in fx.get("emf", ()):
            v += w * (a * math.sin(order * th) + b * math.cos(order * th))
        if "ripple" in fx:
            m, f = fx["ripple"]
            v -= m * self.command(t) * math.cos(2.0 * math.pi * f * t)
        return v

    def inductance(self, i: float) -> float:
        """The differential inductance [H] at the current ``i`` [A]."""
        ell = self.p["L"]
        if "lsat" in self.fx:
            ipar, ratio = self.fx["lsat"]
            ell *= ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2)
        return ell

    def belt(self, twist: float, wrel: float) -> float:
        """The belt's torque [N m] on the wheel head at the ``twist`` [rad] and the relative
        speed ``wrel`` [rad/s] (the pulley's minus the head's), with a play if ``gap``."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        if "gap" not in self.fx:
            return ks * twist + ds * wrel
        half = 0.5 * self.fx["gap"]
        if abs(twist) <= half:
            return 0.0
        edge = half if twist > 0.0 else -half
        push = ks * (twist - edge) + ds * wrel
        return max(push, 0.0) if twist > 0.0 else min(push, 0.0)

    def wheel_load(self, t: float, ww: float, thw: float) -> float:
        """The torque [N m] the outside effects' laws give the wheel head at the time ``t``
        [s], its speed ``ww`` [rad/s] and angle ``thw`` [rad] (0 when none)."""
        fx, tq = self.fx, 0.0
        if "rub" in fx:
            f, a, d = fx["rub"]
            tq -= f * math.exp((math.cos(thw - a) - 1.0) / d ** 2) * math.tanh(ww / W_SWITCH)
        if "hands" in fx:
            f, t1, t2, dt = fx["hands"]
            tq -= f * logistic((t - t1) / dt) * logistic((t2 - t) / dt) \
                * math.tanh(ww / W_SWITCH)
        return tq

    def __call__(self, t: float, y: np.ndarray) -> list[float]:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n = self.p, self.ratio
        i, w, th, ww, thw = (float(v) for v in y[:5])
        di = (self.command(t) - self.loop_voltage(t, i, w, th) - p["k"] * w) \
            / self.inductance(i)
        tk = self.belt(th / n - thw, w / n - ww)
        torque = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                  + self.body_torque("rotor", w, th)
                  + (self.body_torque("hub", w / n, th / n) - tk) / n)
        dww = (tk - p["Bw"] * ww - p["Tw"] * math.tanh(ww / W_SWITCH)
               - p["Cs"] * math.tanh(ww / W_SLURRY)
               + self.body_torque("wheel", ww, thw) + self.wheel_load(t, ww, thw)) / p["Jw"]
        seen = {"current": i, "speed": w, "load_speed": ww}
        pade = [2.0 * (seen[probe] - float(y[k])) / tau for probe, tau, k in self.delays]
        return [di, torque / self.j_rotor, w, dww, ww, *pade]


# ---------------------------------------------------------------------- integration

def _piece(model: WheelDrive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AK, {a:g}-{b:g} s: {why}")


def integrate(model: WheelDrive, t: np.ndarray, bp: np.ndarray, max_step: float
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
    """Noise-free probes of motor AK at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A], speed [rad/s] (the motor's tachometer), and in the slow regime
    load_speed [rad/s] (the wheel head, from an optical sensor reading marks under its rim),
    plus the command ``u`` [V]. ``states``: add the angles [rad] and the belt's torque
    [N m]."""
    fx = dict(fx or {})
    p = {**MOTOR_AK, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = WheelDrive(fx, p)
    y = integrate(model, t, bp, MAX_STEP[regime])
    u = np.interp(t, bp[:, 0], bp[:, 1])
    true = {"current": y[0], "speed": y[1], "load_speed": y[3]}
    for probe, _, k in model.delays:
        true[probe] = 2.0 * y[k] - true[probe]
    out = {probe: np.array(true[probe]) for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = u
    if states:
        twist = y[2] / p["N"] - y[4]
        out.update(rotor_angle=y[2], wheel_angle=y[4], wheel_speed=y[3],
                   belt_torque=p["Ks"] * twist + p["Ds"] * (y[1] / p["N"] - y[3]))
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
