"""Motor AI of the diagnosis benchmark: a hand-written scipy model of a 12 V permanent-magnet
brushed DC motor in a motorised GARDEN HOSE REEL (a wall-mounted reel that winds in, and pays
out, 15 m of 1/2-inch hose). The motor drives a rigid, lossless 25:1 spur gearhead (`gear`
G), whose output shaft carries a 12-tooth chain sprocket (the body ``hub``); a 3/8-inch roller
chain (a compliance, `spring_damper` K: its stretch and the reel sprocket's rubber cush
dampers) turns the reel's own 12-tooth sprocket (1:1). The body ``reel`` is the drum (winding
radius about 0.12 m) with the hose on it. Winding in is reel.w > 0.

No circuitsim import: an independent simulator (the thirty-second of the benchmark), written
from the physics for netlists/motor_ai_fast.yaml and motor_ai_slow.yaml. It is evaluated at
the record's own sample times (``t_eval``), never on a grid that is then interpolated.
Everything rests at t = 0: no current, no speed, the reel at 0 and the chain unstrained.

The gearhead is rigid (``gear`` G, ratio N = 25): the hub stands at th / N and turns at w / N
with the rotor; a torque T on it is T / N on the rotor. The chain is a spring and a damper on
the twist th / N - thl between the hub and the reel (``spring_damper`` K), its torque on the
reel

    Tk = Ks (th / N - thl) + Ds (w / N - wl).

The reel meets three declared loads: the swivel's water seal (a viscous drag Bl wl,
``damper``); the hose dragging over the lawn and through the guide's rollers (a dry friction
Th tanh(wl / 0.01), ``friction``, w_brk 0.1); and the hose's whipping and the drum's air
(a quadratic drag Cq wl |wl|, |x| written sqrt(x^2 + (0.01 rad/s)^2), circuitsim's
smooth_abs, ``btorque`` Whip).

State y = [i, w, th, wl, thl] (+ one Pade stage per delayed probe):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wl, thl    the reel's speed and angle [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the rotor with the gearhead's input, and the hub):

    L di/dt   = u(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor + (X_hub - Tk) / N
    Jl dwl/dt = Tk - Bl wl - Th tanh(wl / 0.01) - Cq wl |wl| + X_reel

Tm tanh(w / 0.01) is the brushes' and the bearings' dry friction (``friction``, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, reel) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in the chain K (Modelica's ElastoBacklash): no
              torque while |twist| < gap / 2, else Ks (twist -+ gap / 2) + Ds w_rel, the
              damping never pulling the sides together
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    lawn      c [N m/rad]: the hose's drag over the lawn falls as the hose comes off it: the
              length lying out shrinks by the drum's radius per radian wound, so the reel
              receives + c thl tanh(wl / 0.01) (the declared Th is the drag with all of the
              hose out; paying out lays it back)
    levelwind (F [N m], P [rad], th0 [rad], m): the level-wind guide's diamond screw
              reverses at each end of its traverse, and its follower drags through the
              crossover: -F cos(pi (thl - th0) / P)^(2 m) tanh(wl / 0.01), a pulse every P
              of the reel's angle (each reversal), centred at th0 + j P
    ilim      (Ilim [A], G [ohm], d [A]): the controller's current limit folds its output
              back by G d (softplus((i - Ilim) / d) - softplus((-i - Ilim) / d)) [V]
              (softplus(x) = ln(1 + exp(x))), taken in the loop
    nozzle    (Ke [N m/rad], the [rad], d [rad]): the hose's end fitting jams against the
              guide's rollers past the reel's angle the: the reel receives
              -Ke d softplus((thl - the) / d)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AI [SI] (motor_ai_fast.yaml, motor_ai_slow.yaml)
MOTOR_AI: dict[str, float] = {
    "R": 0.32, "L": 4.5e-4, "k": 0.032, "Jm": 6e-5, "bm": 5e-6, "Tm": 0.012, "N": 25.0,
    "Jh": 8e-4, "Ks": 150.0, "Ds": 0.5, "Jl": 0.065, "Bl": 0.05, "Th": 2.0, "Cq": 0.004,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: [rad/s] smooth_abs's epsilon in the Whip's law
W_EPS = 0.01
#: the fast regime's command [s, V] (motor_ai_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.06, 12.0), (0.28, 12.0), (0.285, 0.0),
               (0.33, 0.0), (0.38, -12.0), (0.52, -12.0), (0.53, -5.0), (0.56, -5.0),
               (0.565, 0.0), (0.6, 0.0))
#: the slow regime's logged command [s, V] (motor_ai_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.2, 0.0), (0.5, 12.0), (2.6, 12.0), (2.7, 6.0), (3.0, 6.0),
               (3.01, 0.0), (3.5, 0.0), (3.8, -12.0), (5.2, -12.0), (5.3, -6.0),
               (5.6, -6.0), (5.61, 0.0), (6.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.6), "slow": (200.0, 6.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "reel")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime, a fifth of the
#: mean interval in the slow one
MAX_STEP = {"fast": 5e-5, "slow": 1e-3}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.array(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


def softplus(x: float) -> float:
    """ln(1 + exp(x)), without overflow."""
    return x + math.log1p(math.exp(-x)) if x > 0.0 else math.log1p(math.exp(x))


# ---------------------------------------------------------------------- the model

class HoseReel:
    """Right-hand side of motor AI with one set of effects ``fx`` [SI]; ``ramp`` holds the
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
        if "ilim" in fx:
            ilim, g, d = fx["ilim"]
            v += g * d * (softplus((i - ilim) / d) - softplus((-i - ilim) / d))
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

    def chain(self, twist: float, wrel: float) -> float:
        """The chain's torque [N m] on the reel at the ``twist`` [rad] and the relative speed
        ``wrel`` [rad/s] (the hub's minus the reel's), with a play if ``gap``."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        if "gap" not in self.fx:
            return ks * twist + ds * wrel
        half = 0.5 * self.fx["gap"]
        if abs(twist) <= half:
            return 0.0
        edge = half if twist > 0.0 else -half
        push = ks * (twist - edge) + ds * wrel
        return max(push, 0.0) if twist > 0.0 else min(push, 0.0)

    def reel_load(self, wl: float, thl: float) -> float:
        """The torque [N m] the outside effects' laws give the reel at its speed ``wl``
        [rad/s] and angle ``thl`` [rad] (0 when none)."""
        fx, tq = self.fx, 0.0
        if "lawn" in fx:
            tq += fx["lawn"] * thl * math.tanh(wl / W_SWITCH)
        if "levelwind" in fx:
            f, period, th0, m = fx["levelwind"]
            tq -= f * math.cos(math.pi * (thl - th0) / period) ** (2 * m) \
                * math.tanh(wl / W_SWITCH)
        if "nozzle" in fx:
            ke, the, d = fx["nozzle"]
            tq -= ke * d * softplus((thl - the) / d)
        return tq

    def __call__(self, t: float, y: np.ndarray) -> list[float]:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n = self.p, self.ratio
        i, w, th, wl, thl = (float(v) for v in y[:5])
        di = (self.command(t) - self.loop_voltage(t, i, w, th) - p["k"] * w) \
            / self.inductance(i)
        tk = self.chain(th / n - thl, w / n - wl)
        torque = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                  + self.body_torque("rotor", w, th)
                  + (self.body_torque("hub", w / n, th / n) - tk) / n)
        dwl = (tk - p["Bl"] * wl - p["Th"] * math.tanh(wl / W_SWITCH)
               - p["Cq"] * wl * math.hypot(wl, W_EPS)
               + self.body_torque("reel", wl, thl) + self.reel_load(wl, thl)) / p["Jl"]
        seen = {"current": i, "speed": w, "load_speed": wl}
        pade = [2.0 * (seen[probe] - float(y[k])) / tau for probe, tau, k in self.delays]
        return [di, torque / self.j_rotor, w, dwl, wl, *pade]


# ---------------------------------------------------------------------- integration

def _piece(model: HoseReel, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AI, {a:g}-{b:g} s: {why}")


def integrate(model: HoseReel, t: np.ndarray, bp: np.ndarray, max_step: float
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
    """Noise-free probes of motor AI at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the reel, from a magnet-and-Hall tachometer on its sprocket),
    plus the command ``u`` [V]. ``states``: add the angles [rad] and the
    chain's torque [N m]."""
    fx = dict(fx or {})
    p = {**MOTOR_AI, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = HoseReel(fx, p)
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
        out.update(rotor_angle=y[2], reel_angle=y[4], reel_speed=y[3],
                   chain_torque=p["Ks"] * twist + p["Ds"] * (y[1] / p["N"] - y[3]))
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
