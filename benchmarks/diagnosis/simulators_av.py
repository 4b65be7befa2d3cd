"""Motor AV of the diagnosis benchmark: a hand-written scipy model of a 20 V permanent-magnet
brushed DC motor (a cordless tool's 2-pole, 9-slot can motor) driving the DRUM of a cordless
DRUM DRAIN CLEANER (a drain auger for sinks and floor drains: a 240 mm drum holding 7.5 m of
8 mm spring-wound cable) on the workshop's service bench, with 3 m of the cable paid out
through the bench's clear test pipe (a 40 mm pipe with two bends, water standing in it) to
the cutter head. The motor's 12-tooth pinion drives a 36-tooth gear, whose shaft's 5:1
planetary stage turns the drum (a 15:1 reduction, `gear` G, declared rigid and lossless); the
body ``hub`` is the drum with the coiled cable inside it. The paid-out cable is a long
torsion spring, a `spring_damper` K between the drum and the body ``head`` (the cutter head
with the paid-out cable's own inertia lumped at it). The head turns at the drum's speed on
average (1:1), its angle its own. Forward is head.w > 0 (the cable's coils tightening, the
working direction); backing the head out of a snag turns it backwards (head.w < 0).

No circuitsim import, and no other set's simulator: an independent simulator, written from the
physics for netlists/motor_av_fast.yaml and motor_av_slow.yaml. It is evaluated at the record's
own sample times (``t_eval``), never on a grid that is then interpolated. Everything rests at
t = 0: no current, no speed, the drum and the head at 0 and the cable untwisted.

The gear train is rigid (``gear`` G, ratio N = 15): the drum stands at th / N and turns at
w / N with the rotor; a torque T on it is T / N on the rotor. The cable is a spring and a
damper on the twist th / N - thl between the drum and the head (``spring_damper`` K), its
torque on the head

    Tk = Ks (th / N - thl) + Ds (w / N - wl).

The drum's axle bushes and the cable's rubbing in the drum's outlet guide give the drum a dry
friction (``friction`` Fh, Th tanh(wh / 0.01), w_brk 0.1). The head meets the test pipe: the
cable's dry rubbing through the bends (``friction`` Fl, Tl tanh(wl / 0.01), w_brk 0.1) and the
standing water's viscous drag (``damper`` Bl).

State y = [i, w, th, wl, thl] (+ one Pade stage per delayed probe):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wl, thl    the head's speed and angle [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the armature with its pinion, and the drum):

    L di/dt   = v(t) - R i - kx w - (the loop's extras)
    Jr dw/dt  = kx i - bm w - Tm tanh(w / 0.01) + X_rotor
                + (X_hub - Th tanh((w / N) / 0.01) - Tk) / N
    Jl dwl/dt = Tk - Tl tanh(wl / 0.01) - Bl wl + X_head

v(t) the bench supply's output u(t), kx = k (or k times the outside ``float``'s factor), Tm
tanh(w / 0.01) the brushes' and the motor's bearings' dry friction (``friction`` Fr, w_brk
0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, head) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in K (no torque while |twist| < gap / 2,
              else Ks (twist -+ gap / 2) + Ds w_rel, the damping never pulling the sides
              together)
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: parameters changed (the record's true values of the declared
              ones the user frees, an inertia's or the inductance's correction)

and outside the catalog:

    tachrev   (a [1], w0 [rad/s]): the speed probe, a DC tachogenerator with its brushes off
              the neutral, reads w (1 + a tanh(w / w0)): its constant a higher one way than
              declared and a lower the other (its reversal error)
    partway   f [1]: the load_speed probe reads the cable a fraction f of the way from the
              drum to the head: (1 - f) w / N + f wl (the twist shared along the cable)
    float     (a [1], I1 [A], dI [A]): the armature floats axially: the helical pinion's
              thrust, once the current's torque beats the wave washer's preload (about I1),
              pushes it out of the magnets by its end play: kx = k (1 - a s), s = (1 +
              tanh((i - I1) / dI)) / 2, in the EMF and in the torque alike
    helix     (r [1], e [rad]): the spring-wound cable is stiff while its coils tighten and
              r times as stiff while they open: Tk = Ks ((1 + r) / 2 x + (1 - r) / 2
              (sqrt(x^2 + e^2) - e)) + Ds v, x = th / N - thl, v = w / N - wl
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AV [SI] (motor_av_fast.yaml, motor_av_slow.yaml): what the
#: diagnosis starts from; a record's true values differ in the parameters it frees
MOTOR_AV: dict[str, float] = {
    "R": 0.42, "L": 3.2e-4, "k": 0.028, "Jm": 3.2e-5, "bm": 6e-6, "Tm": 0.012,
    "N": 15.0, "Jh": 0.024, "Th": 0.35, "Ks": 0.32, "Ds": 0.0065, "Jl": 8e-4,
    "Tl": 0.22, "Bl": 2.5e-3,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_av_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.02, 0.0), (0.14, 18.0), (0.26, 18.0), (0.29, 7.0),
               (0.36, 7.0), (0.44, -13.0), (0.52, -13.0), (0.54, 0.0), (0.56, 0.0))
#: the slow regime's logged command [s, V] (motor_av_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.4, 0.0), (1.1, 8.0), (2.5, 8.0), (3.0, 18.0), (4.9, 18.0),
               (5.3, 0.0), (5.7, 0.0), (6.2, -12.0), (7.9, -12.0), (8.3, 0.0), (9.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (32e3, 0.56), "slow": (400.0, 9.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "head")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime, a quarter of the
#: mean interval in the slow one
MAX_STEP = {"fast": 1.0 / 32e3, "slow": 6.25e-4}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.array(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class DrainDrive:
    """Right-hand side of motor AV with one set of effects ``fx`` and parameters ``p`` [SI];
    ``ramp`` holds the command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.fx, self.p = fx, p
        self.n = p["N"]
        self.j_rotor = p["Jm"] + p["Jh"] / self.n ** 2
        size = 5
        #: (probe, tau [s], index of its Pade state)
        self.delays: list[tuple[str, float, int]] = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.delays.append((probe, float(s["delay"]), size))
                size += 1
        self.size = size
        self.torques = {body: self._torques(body) for body in BODIES}
        self.ramp = (0.0, 0.0, 0.0)

    def _torques(self, body: str) -> dict[str, Any]:
        """The catalog's torque effects on ``body`` (empty when none)."""
        found = {}
        for key in ("visc", "coul", "offset", "stribeck", "cog"):
            value = self.fx.get(key, {}).get(body)
            if value:
                found[key] = value
        return found

    def torque_on(self, body: str, w: float, angle: float) -> float:
        """The torque [N m] the catalog's effects give ``body`` at its speed ``w`` [rad/s]
        and angle ``angle`` [rad]."""
        eff = self.torques[body]
        if not eff:
            return 0.0
        sw = math.tanh(w / W_SWITCH)
        tq = eff.get("offset", 0.0) - eff.get("visc", 0.0) * w - eff.get("coul", 0.0) * sw
        if "stribeck" in eff:
            peak, ws = eff["stribeck"]
            tq -= peak * math.exp(-(w / ws) ** 2) * sw
        for order, a, b in eff.get("cog", ()):
            tq += a * math.sin(order * angle) + b * math.cos(order * angle)
        return tq

    def command(self, t: float) -> float:
        """The supply's output [V]: the command, linear within its segment."""
        t0, u0, slope = self.ramp
        return u0 + slope * (t - t0)

    def constant(self, i: float) -> float:
        """The motor constant [V s/rad = N m/A] at the current ``i`` [A] (``float``)."""
        k = self.p["k"]
        if "float" in self.fx:
            a, i1, di = self.fx["float"]
            k *= 1.0 - a * 0.5 * (1.0 + math.tanh((i - i1) / di))
        return k

    def loop_drop(self, t: float, i: float, th: float, w: float) -> float:
        """The voltage [V] the loop takes besides the inductance's and the EMF's."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        v = (r + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)) * i
        if "Vb" in fx:
            v += fx["Vb"] * math.tanh(i / I_SWITCH)
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

    def cable(self, twist: float, wrel: float) -> float:
        """The cable's torque [N m] on the head at the ``twist`` [rad] and the relative
        speed ``wrel`` [rad/s] (the drum's minus the head's), with a play if ``gap``, one
        way softer if ``helix``."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        if "helix" in self.fx:
            r, e = self.fx["helix"]
            return ks * (0.5 * (1.0 + r) * twist
                         + 0.5 * (1.0 - r) * (math.sqrt(twist * twist + e * e) - e)) \
                + ds * wrel
        if "gap" not in self.fx:
            return ks * twist + ds * wrel
        half = 0.5 * self.fx["gap"]
        if abs(twist) <= half:
            return 0.0
        edge = half if twist > 0.0 else -half
        push = ks * (twist - edge) + ds * wrel
        return max(push, 0.0) if twist > 0.0 else min(push, 0.0)

    def __call__(self, t: float, y: np.ndarray) -> list[float]:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n = self.p, self.n
        i, w, th, wl, thl = (float(v) for v in y[:5])
        k = self.constant(i)
        di = (self.command(t) - self.loop_drop(t, i, th, w) - k * w) / self.inductance(i)
        tk = self.cable(th / n - thl, w / n - wl)
        on_hub = self.torque_on("hub", w / n, th / n) - p["Th"] * math.tanh(
            (w / n) / W_SWITCH)
        torque = (k * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                  + self.torque_on("rotor", w, th) + (on_hub - tk) / n)
        on_head = (tk - p["Tl"] * math.tanh(wl / W_SWITCH) - p["Bl"] * wl
                   + self.torque_on("head", wl, thl))
        seen = self.readings(i, w, wl)
        pade = [2.0 * (seen[probe] - float(y[j])) / tau for probe, tau, j in self.delays]
        return [di, torque / self.j_rotor, w, on_head / p["Jl"], wl, *pade]

    def readings(self, i: Any, w: Any, wl: Any) -> dict[str, Any]:
        """What each probe's sensor sees [A, rad/s] before its catalog effects: the current,
        the rotor's speed and the head's (or the outside effects' readings of them)."""
        seen = {"current": i, "speed": w, "load_speed": wl}
        if "tachrev" in self.fx:
            a, w0 = self.fx["tachrev"]
            seen["speed"] = w * (1.0 + a * np.tanh(w / w0))
        if "partway" in self.fx:
            f = self.fx["partway"]
            seen["load_speed"] = (1.0 - f) * w / self.n + f * wl
        return seen


# ---------------------------------------------------------------------- integration

def _piece(model: DrainDrive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AV, {a:g}-{b:g} s: {why}")


def integrate(model: DrainDrive, t: np.ndarray, bp: np.ndarray, max_step: float
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
    """Noise-free probes of motor AV at the times ``t`` [s] (default: the nominal grid),
    from rest, with the parameters ``p`` over the declared ones (and ``fx["p"]`` over
    those): current [A] (the bench's shunt in the supply's lead), speed [rad/s] (the bench's
    DC tachogenerator on the motor's rear shaft end, rad/s at the rotor), and in the slow
    regime load_speed [rad/s] (the head, from the bench's optical tachometer reading a
    reflective band on the cutter head through the clear test pipe), plus the command ``u``
    [V]. ``states``: add the bodies' speeds [rad/s] and angles [rad], the cable's twist
    [rad] and torque [N m] and the motor constant [V s/rad]."""
    fx = dict(fx or {})
    p = {**MOTOR_AV, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = DrainDrive(fx, p)
    y = integrate(model, t, bp, MAX_STEP[regime])
    u = np.interp(t, bp[:, 0], bp[:, 1])
    true = model.readings(y[0], y[1], y[3])
    for probe, _, j in model.delays:
        true[probe] = 2.0 * y[j] - true[probe]
    out = {probe: np.array(true[probe], dtype=float) for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = u
    if states:
        twist, wrel = y[2] / p["N"] - y[4], y[1] / p["N"] - y[3]
        torque = np.array([model.cable(a, b) for a, b in zip(twist, wrel, strict=True)])
        out.update(rotor_angle=y[2], hub_angle=y[2] / p["N"], hub_speed=y[1] / p["N"],
                   head_angle=y[4], head_speed=y[3], armature_current=y[0],
                   cable_twist=twist, cable_torque=torque,
                   motor_constant=np.array([model.constant(float(i)) for i in y[0]]))
    return out


# ---------------------------------------------------------------------- noise

def gauss_markov(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float
                 ) -> np.ndarray:
    """A stationary first-order Gauss-Markov process [probe unit] of standard deviation
    ``sigma`` and correlation time ``tau`` [s], exact at the (uneven) times ``t``."""
    rho = np.exp(-np.diff(t) / tau)
    e = rng.standard_normal(t.size) * sigma
    e[1:] *= np.sqrt(1.0 - rho ** 2)
    x = np.empty(t.size)
    x[0] = e[0]
    for j in range(1, t.size):
        x[j] = rho[j - 1] * x[j - 1] + e[j]
    return x


def flicker(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise [probe unit] of standard deviation ``sigma`` at the times ``t`` [s]: white
    noise on an even grid spanning the record, its amplitude spectrum shaped by 1/sqrt(f)
    (no mean), read at ``t`` linearly."""
    n = t.size
    even = np.linspace(float(t[0]), float(t[-1]), n)
    f = np.fft.rfftfreq(n, float(even[1] - even[0]))
    spec = np.fft.rfft(rng.standard_normal(n))
    spec[0] = 0.0
    spec[1:] *= np.sqrt(f[1] / f[1:])
    x = np.interp(t, even, np.fft.irfft(spec, n))
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
        out += gauss_markov(rng, t, sigma, -float(np.mean(np.diff(t))) / math.log(phi))
    if spec.get("pink"):
        out += flicker(rng, t, spec["pink"])
    step = spec.get("quant")
    return np.round(out / step) * step if step else out
