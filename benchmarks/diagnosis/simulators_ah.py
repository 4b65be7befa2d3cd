"""Motor AH of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC motor in a SLIDING-GATE OPERATOR (a ground-mounted operator beside a 300 kg
sliding gate that runs on V-groove wheels along a level track). The motor drives a
single-start worm and an oil-bathed bronze worm wheel (a rigid 36:1 reduction, declared
lossless as a `gear`; the worm's mesh friction is declared on the wheel as a behavioural
torque), whose output shaft carries an 18-tooth module-4 pinion (pitch radius r = 36 mm).
The pinion meshes with the nylon-and-steel rack bolted along the gate's leaf; the rack's
mounting, the leaf's frame and the mesh are a compliance (`spring_damper` K) between the
wheel's shaft and the gate. The gate is reflected to the pinion through r: the body
``gate``'s angle is its travel over r (1 rad = 36 mm), its speed v / r, its inertia m r^2, a
force F on it the torque F r. Opening is gate.w > 0.

No circuitsim import: an independent simulator (the thirty-first of the benchmark), written
from the physics for netlists/motor_ah_fast.yaml and motor_ah_slow.yaml. It is evaluated at
the record's own sample times (``t_eval``), never on a grid that is then interpolated.
Everything rests at t = 0: no current, no speed, the gate at 0 and the rack unstrained; every
load vanishes there (the track is level).

The worm gear is rigid (``gear`` G, ratio N = 36): the wheel (the body ``hub``, the pinion's
shaft) stands at th / N and turns at w / N with the rotor; a torque T on it is T / N on the
rotor. The rack is a spring and a damper on the twist th / N - thg between the wheel and the
gate (``spring_damper`` K), its torque on the gate

    Tk = Ks (th / N - thg) + Ds (w / N - wg).

The worm's mesh friction (``btorque`` Worm on the wheel) opposes the wheel's motion with
Tw + mu |Tk| (|x| written sqrt(x^2 + (0.01 N m)^2), circuitsim's smooth_abs): a no-load part
Tw (the oil bath, the seals, the bearings) and a part proportional to the torque the mesh
carries. With mu = 1.2 > 1 the gate cannot drive the worm back (self-locking: the forward
efficiency 1/(1 + mu) = 0.45): when the motor stops, the wheel holds, and the gate swings on
the rack's compliance.

State y = [i, w, th, wg, thg] (+ one Pade stage per delayed probe):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wg, thg    the gate's speed and travel at the pinion [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the rotor with the worm, and the wheel with the pinion):

    L di/dt   = u(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor
                + (X_hub - Tk - (Tw + mu |Tk|) tanh((w / N) / 0.01)) / N
    Jg dwg/dt = Tk - Bg wg - Tr tanh(wg / 0.01) + X_gate

Tm tanh(w / 0.01) is the brushes' and the bearings' dry friction (``friction``, w_brk 0.1),
Bg wg the gate's guide rollers' and the air's drag (``damper``), Tr tanh(wg / 0.01) the
V-groove wheels' rolling resistance (``friction``, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, gate) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in the rack K (Modelica's ElastoBacklash): no
              torque while |twist| < gap / 2, else Ks (twist -+ gap / 2) + Ds w_rel, the
              damping never pulling the sides together; the Worm's declared law is left as
              the netlist writes it (of the linear Ks twist + Ds w_rel), as the catalog's patch
              of K leaves it
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    snow      (ks [N m/rad], th0 [rad], d [rad]): a snow drift against the post the gate opens
              towards: past th0 the leaf's end ploughs and packs it, a resistance
              ks d ln(1 + exp((thg - th0) / d)) against the opening only, weighted
              (1 + tanh(wg / 0.01)) / 2 (the packed snow stays behind when the gate closes)
    relay     Ro [ohm]: the controller's brake relay's contact burnt open: whenever the
              command is zero the motor is left across the controller's bleed resistor
              instead of the short: the loop takes Ro (1 - tanh(u / 0.5 V)^2) i
    scrape    (F [N m], th1, th2, d [rad]): the leaf sags on a worn roller and its tail drags
              on the paving between th1 and th2: F (tanh((thg - th1)/d) - tanh((thg - th2)/d))
              / 2 tanh(wg / 0.01) against the gate's motion
    joint     (e [rad], thj [rad], d [rad]): two rack segments joined with a pitch error e
              (at the pinion's radius) at thj: the mesh's twist is th / N - thg
              - e (1 + tanh((thg - thj) / d)) / 2 in Tk (the spring's part) and in the
              Worm's law
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AH [SI] (motor_ah_fast.yaml, motor_ah_slow.yaml)
MOTOR_AH: dict[str, float] = {
    "R": 0.45, "L": 9e-4, "k": 0.065, "Jm": 1.5e-4, "bm": 1e-5, "Tm": 0.02, "N": 36.0,
    "Jh": 4e-3, "Ks": 1200.0, "Ds": 6.0, "Jg": 0.3888, "Bg": 0.3, "Tr": 3.6, "Tw": 1.0,
    "mu": 1.2,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: [N m] smooth_abs's epsilon in the Worm's law
T_EPS = 0.01
#: [V] the brake relay's window on the command, 1 - tanh(u / 0.5 V)^2
U_RELAY = 0.5
#: the fast regime's command [s, V] (motor_ah_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.08, 24.0), (0.24, 24.0), (0.26, 10.0),
               (0.32, 10.0), (0.325, 0.0), (0.37, 0.0), (0.41, -24.0), (0.49, -24.0),
               (0.51, -8.0), (0.56, -8.0), (0.565, 0.0), (0.6, 0.0))
#: the slow regime's logged command [s, V] (motor_ah_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.2, 0.0), (0.4, 24.0), (2.2, 24.0), (2.3, 9.0), (2.8, 9.0),
               (2.81, 0.0), (3.4, 0.0), (3.6, -24.0), (5.0, -24.0), (5.1, -9.0),
               (5.6, -9.0), (5.61, 0.0), (6.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.6), "slow": (200.0, 6.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "gate")
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


def _step(x: float, d: float) -> float:
    """A smooth unit step (1 + tanh(x / d)) / 2."""
    return 0.5 * (1.0 + math.tanh(x / d))


# ---------------------------------------------------------------------- the model

class GateOperator:
    """Right-hand side of motor AH with one set of effects ``fx`` [SI]; ``ramp`` holds the
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
        if "relay" in fx:
            v += fx["relay"] * (1.0 - math.tanh(self.command(t) / U_RELAY) ** 2) * i
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

    def rack(self, twist: float, wrel: float) -> tuple[float, float]:
        """The rack's torque [N m] on the gate at the ``twist`` [rad] and the relative speed
        ``wrel`` [rad/s] (the wheel's minus the gate's), with a play if ``gap``; and the
        torque the Worm's law is written of (the declared linear one)."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        linear = ks * twist + ds * wrel
        if "gap" not in self.fx:
            return linear, linear
        half = 0.5 * self.fx["gap"]
        if abs(twist) <= half:
            return 0.0, linear
        edge = half if twist > 0.0 else -half
        push = ks * (twist - edge) + ds * wrel
        return (max(push, 0.0) if twist > 0.0 else min(push, 0.0)), linear

    def gate_load(self, wg: float, thg: float) -> float:
        """The torque [N m] the outside effects' laws give the gate at its speed ``wg``
        [rad/s] and travel ``thg`` [rad] (0 when none)."""
        fx, tq = self.fx, 0.0
        if "snow" in fx:
            ks, th0, d = fx["snow"]
            x = (thg - th0) / d
            soft = x + math.log1p(math.exp(-x)) if x > 0.0 else math.log1p(math.exp(x))
            tq -= ks * d * soft * _step(wg, W_SWITCH)
        if "scrape" in fx:
            f, th1, th2, d = fx["scrape"]
            tq -= f * 0.5 * (math.tanh((thg - th1) / d) - math.tanh((thg - th2) / d)) \
                * math.tanh(wg / W_SWITCH)
        return tq

    def __call__(self, t: float, y: np.ndarray) -> list[float]:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n = self.p, self.ratio
        i, w, th, wg, thg = (float(v) for v in y[:5])
        di = (self.command(t) - self.loop_voltage(t, i, w, th) - p["k"] * w) \
            / self.inductance(i)
        twist = th / n - thg
        if "joint" in self.fx:
            e, thj, d = self.fx["joint"]
            twist -= e * _step(thg - thj, d)
        tk, t_worm = self.rack(twist, w / n - wg)
        worm = (p["Tw"] + p["mu"] * math.hypot(t_worm, T_EPS)) * math.tanh(w / n / W_SWITCH)
        torque = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                  + self.body_torque("rotor", w, th)
                  + (self.body_torque("hub", w / n, th / n) - tk - worm) / n)
        dwg = (tk - p["Bg"] * wg - p["Tr"] * math.tanh(wg / W_SWITCH)
               + self.body_torque("gate", wg, thg) + self.gate_load(wg, thg)) / p["Jg"]
        seen = {"current": i, "speed": w, "load_speed": wg}
        pade = [2.0 * (seen[probe] - float(y[k])) / tau for probe, tau, k in self.delays]
        return [di, torque / self.j_rotor, w, dwg, wg, *pade]


# ---------------------------------------------------------------------- integration

def _piece(model: GateOperator, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AH, {a:g}-{b:g} s: {why}")


def integrate(model: GateOperator, t: np.ndarray, bp: np.ndarray, max_step: float
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
    """Noise-free probes of motor AH at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A], speed [rad/s] (the motor's Hall encoder), and in the slow regime
    load_speed [rad/s] (the gate, from the commissioning kit's wheel encoder rolling on the
    leaf, at the pinion's radius), plus the command ``u`` [V]. ``states``: add the angles
    [rad] and the rack's torque [N m]."""
    fx = dict(fx or {})
    p = {**MOTOR_AH, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = GateOperator(fx, p)
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
        out.update(rotor_angle=y[2], gate_angle=y[4], gate_speed=y[3],
                   rack_torque=p["Ks"] * twist + p["Ds"] * (y[1] / p["N"] - y[3]))
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
