"""Motor AG of the diagnosis benchmark: a hand-written scipy model of a 12 V permanent-magnet
brushed DC motor in a car's ELECTRIC PARKING BRAKE (a motor-on-caliper actuator on a rear
floating caliper), on an end-of-line test bench. The motor drives a toothed belt (3:1) and a
two-stage planetary gearbox (a rigid, lossless 100:1 reduction in all); the gearbox's output
carrier turns the caliper's spindle through a splined coupling with an elastomer ring (the
actuator's decoupling element: a torsional compliance). The spindle (1.5 mm lead, a
self-locking trapezoidal thread) drives a nut that pushes the brake piston: first across the
pads' air gap (the piston seal's rollback a weak spring), then into the pads and the disc,
whose clamp rises steeply and progressively (the pads' compressibility, the caliper's
stretch); the thread's friction grows with the clamp and holds it when the motor stops.

No circuitsim import: an independent simulator (the thirtieth of the benchmark), written from
the physics for netlists/motor_ag_fast.yaml and motor_ag_slow.yaml. It is evaluated at the
record's own sample times (``t_eval``), never on a grid that is then interpolated. Everything
rests at t = 0: no current, no speed, the nut retracted (spindle angle 0) and the coupling
untwisted; the clamp's law vanishes there, so nothing creeps.

The gearbox is rigid and lossless (``gear`` G, ratio N = 100): the carrier (the body ``hub``)
stands at th / N and turns at w / N with the rotor; a torque T on it is T / N on the rotor.
The coupling is a spring and a damper on the twist th / N - ths between the carrier and the
spindle (``spring_damper`` K).

State y = [i, w, th, ws, ths] (+ the pads' set z with creep, + one Pade stage per delayed
probe, in this order):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    ws, ths    the spindle's speed and angle [rad/s, rad] (0: the nut retracted; the pads
               touch the disc at ths = thg)

Equations (Jr = Jm + Jh / N^2: the rotor and the belt's pulleys with the planetary carrier):

    L di/dt   = u(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor + (X_hub - Tk) / N
    Js dws/dt = Tk - Bs ws - Tcl(ths) - (Tf + mu Tcl(ths)) tanh(ws / 0.01) + X_spindle
    Tk        = Ks (th / N - ths) + Ds (w / N - ws)                    (the coupling)
    Tcl(a)    = Tc (exp((a - thg) / thc) - exp(-thg / thc))            (the clamp)

Tm tanh(w / 0.01) is the brushes' and the bearings' dry friction (``friction``, w_brk 0.1),
Bs ws the spindle's grease and the piston seal's drag (``damper``), Tcl the clamp's torque on
the spindle (the ideal screw's F lead / 2 pi: ``btorque`` Clamp; zero at rest, 0.09 N m of
the seal's rollback when the pads touch, then growing e-fold every thc), the thread's friction
Tf + mu Tcl against the spindle's motion (``btorque`` Nut; mu > 1: self-locking).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, spindle) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in the coupling K (Modelica's ElastoBacklash):
              no torque while |twist| < gap / 2, else Ks (twist -+ gap / 2) + Ds w_rel,
              the damping never pulling the sides together
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    creep     Dc [N m s/rad]: hot pads creep under the clamp: the clamp's law is Tcl(ths - z),
              the pads' set z [rad, in the spindle's angle] flowing at dz/dt = Tcl(ths - z) / Dc
              (a state, from 0), and staying when the clamp is released
    diode     (nVt [V], Is [A]): the bridge's reverse-polarity FET left off, its body diode
              in the feed: the loop takes tanh(u / 0.05 V) nVt ln(1 + (sqrt(i^2 + 1 mA^2)
              - 1 mA) / Is) (the diode's forward drop whenever the bridge drives, none while
              its low sides short the motor at u = 0)
    dtv       (d [rad], f [Hz]): a dynamic apply on a turning disc whose thickness varies
              once a turn: the pads' gap is thg + d sin(2 pi f t) (d in the spindle's angle)
              in the clamp's law and the thread's friction
    knock     dg [rad]: the piston knocked back into its bore (a hard cornering test, the
              disc's runout): the nut meets it later, the pads' gap is thg + dg (in the
              spindle's angle) in the clamp's law and the thread's friction
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AG [SI] (motor_ag_fast.yaml, motor_ag_slow.yaml)
MOTOR_AG: dict[str, float] = {
    "R": 0.35, "L": 2e-4, "k": 0.012, "Jm": 6e-6, "bm": 2e-6, "Tm": 0.006, "N": 100.0,
    "Jh": 2e-4, "Ks": 60.0, "Ds": 0.02, "Js": 2e-4, "Bs": 0.05, "Tf": 0.2, "mu": 1.5,
    "Tc": 0.1, "thg": 0.8, "thc": 0.35,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: [V] the diode's gate on the command, tanh(u / 0.05 V)
U_SWITCH = 0.05
#: the fast regime's command [s, V] (motor_ag_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.005, 0.0), (0.015, 12.0), (0.265, 12.0), (0.267, 0.0),
               (0.3, 0.0), (0.31, -12.0), (0.52, -12.0), (0.522, 0.0), (0.6, 0.0))
#: the slow regime's logged command [s, V] (motor_ag_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.2, 0.0), (0.21, 12.0), (0.47, 12.0), (0.475, 0.0),
               (2.0, 0.0), (2.005, 12.0), (2.04, 12.0), (2.045, 0.0), (3.6, 0.0),
               (3.61, -12.0), (3.835, -12.0), (3.84, 0.0), (4.3, 0.0), (4.31, 9.0),
               (4.7, 9.0), (4.705, 0.0), (6.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.6), "slow": (200.0, 6.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "spindle")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime, a fifth of the
#: mean interval in the slow one
MAX_STEP = {"fast": 4e-5, "slow": 1e-3}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.array(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class ParkingBrake:
    """Right-hand side of motor AG with one set of effects ``fx`` [SI]; ``ramp`` holds the
    command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.ratio = p["N"]
        self.j_rotor = p["Jm"] + p["Jh"] / self.ratio ** 2
        #: the outside effects' own states: name -> index (the pads' set)
        self.extra: dict[str, int] = {}
        if fx.get("creep"):
            self.extra["creep"] = 5
        #: (probe, tau [s], index of its Pade state)
        self.delays: list[tuple[str, float, int]] = []
        first = 5 + len(self.extra)
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.delays.append((probe, float(s["delay"]), first + len(self.delays)))
        self.size = first + len(self.delays)
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
        if "diode" in fx:
            nvt, i_s = fx["diode"]
            drop = nvt * math.log1p((math.hypot(i, I_SWITCH) - I_SWITCH) / i_s)
            v += math.tanh(self.command(t) / U_SWITCH) * drop
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

    def coupling(self, twist: float, wrel: float) -> float:
        """The coupling's torque [N m] on the spindle at the ``twist`` [rad] and the relative
        speed ``wrel`` [rad/s] (the carrier's minus the spindle's), with a play if ``gap``."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        if "gap" not in self.fx:
            return ks * twist + ds * wrel
        half = 0.5 * self.fx["gap"]
        if abs(twist) <= half:
            return 0.0
        edge = half if twist > 0.0 else -half
        push = ks * (twist - edge) + ds * wrel
        return max(push, 0.0) if twist > 0.0 else min(push, 0.0)

    def clamp(self, t: float, ths: float, z: float) -> float:
        """The clamp's torque [N m] on the spindle (resisting the apply when positive) at
        ``t`` [s], the spindle's angle ``ths`` [rad] and the pads' set ``z`` [rad]."""
        p = self.p
        gap = p["thg"] + self.fx.get("knock", 0.0)
        if "dtv" in self.fx:
            d, f = self.fx["dtv"]
            gap += d * math.sin(2.0 * math.pi * f * t)
        return p["Tc"] * (math.exp((ths - z - gap) / p["thc"]) - math.exp(-gap / p["thc"]))

    def spindle_load(self, ws: float, tcl: float) -> float:
        """The torque [N m] the grease, the clamp ``tcl`` [N m] and the thread give the
        spindle turning at ``ws`` [rad/s]."""
        p = self.p
        return -p["Bs"] * ws - tcl - (p["Tf"] + p["mu"] * tcl) * math.tanh(ws / W_SWITCH)

    def __call__(self, t: float, y: np.ndarray) -> list[float]:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n, fx = self.p, self.ratio, self.fx
        i, w, th, ws, ths = (float(v) for v in y[:5])
        z = float(y[self.extra["creep"]]) if "creep" in self.extra else 0.0
        di = (self.command(t) - self.loop_voltage(t, i, w, th) - p["k"] * w) \
            / self.inductance(i)
        tk = self.coupling(th / n - ths, w / n - ws)
        torque = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                  + self.body_torque("rotor", w, th)
                  + (self.body_torque("hub", w / n, th / n) - tk) / n)
        tcl = self.clamp(t, ths, z)
        dws = (tk + self.spindle_load(ws, tcl) + self.body_torque("spindle", ws, ths)) / p["Js"]
        own = [tcl / fx["creep"]] if "creep" in self.extra else []
        seen = {"current": i, "speed": w, "load_speed": ws}
        pade = [2.0 * (seen[probe] - float(y[k])) / tau for probe, tau, k in self.delays]
        return [di, torque / self.j_rotor, w, dws, ws, *own, *pade]


# ---------------------------------------------------------------------- integration

def _piece(model: ParkingBrake, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AG, {a:g}-{b:g} s: {why}")


def integrate(model: ParkingBrake, t: np.ndarray, bp: np.ndarray, max_step: float
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
    """Noise-free probes of motor AG at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the spindle, from the bench's encoder on its back end), plus the
    command ``u`` [V]. ``states``: add the angles [rad], the clamp's torque [N m] and the
    coupling's torque [N m]."""
    fx = dict(fx or {})
    p = {**MOTOR_AG, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = ParkingBrake(fx, p)
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
        z = y[model.extra["creep"]] if "creep" in model.extra else np.zeros(t.size)
        twist = y[2] / p["N"] - y[4]
        clamp = [model.clamp(a, b, c) for a, b, c in zip(t, y[4], z, strict=True)]
        out.update(rotor_angle=y[2], spindle_angle=y[4], spindle_speed=y[3],
                   clamp_torque=np.array(clamp),
                   coupling_torque=p["Ks"] * twist + p["Ds"] * (y[1] / p["N"] - y[3]))
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
